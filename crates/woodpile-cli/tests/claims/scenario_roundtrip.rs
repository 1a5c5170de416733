//! Claim: a scenario round-trips. `Scenario::to_toml` (what `woodpile scenario NAME` prints) writes
//! every key explicitly; parsing it back gives the same completed scenario, the same resolved chain,
//! excitation and run settings, and `woodpile simulate FILE` gives exactly the same figures of merit
//! as `woodpile simulate --scenario NAME` (same model, same arithmetic: compared with `==`, only
//! the wall-clock time differs).

use crate::common;

use std::path::Path;
use woodpile_io::scenario::{builtin, builtin_names, resolve, Scenario};

const GENERAL: &str = r#"
description = "general form"
[chain]
model = "rigid"
crossing_angle_deg = 75.0
elements = [
    { rod_mm = 40 },
    { rod_mm = 80, model = "resonant" },
    { kind = "rod", diameter_mm = 6.0, length_mm = 45.0, material = "borosilicate-glass", cell = { primary_mass_g = 0.5, resonators = [{ mass_g = 0.7, stiffness_kn_per_mm = 5.0 }] } },
    { rod_mm = 20 },
    { kind = "rod", length_mm = 30.0, diameter_mm = 6.0, inner_diameter_mm = 4.0, material = "steel", cell = { modes = 2, reduction = "modal-mass" } },
    { kind = "rod", length_mm = 50.0, model = "resonant" },
    { kind = "sphere", diameter_mm = 8.0, material = { name = "pmma", youngs_modulus_pa = 3.1e9, poisson_ratio = 0.35, density_kg_m3 = 1180.0 } },
]
contact_beta = [{ contact = 2, beta = 2.5e9 }]
[excitation]
kind = "blast"
peak_force_n = 150.0
duration_s = 1.5e-4
decay = 0.5
[wall]
kind = "flat"
material = "brass"
[run]
duration_s = 3e-4
integrator = "dopri5"
rtol = 1e-8
sample_interval_s = 2e-6
"#;

fn roundtrip(s: &Scenario) {
    let text = s.to_toml();
    let back = Scenario::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(back.complete(), s.complete(), "{text}");
    assert_eq!(
        back.complete().complete(),
        back.complete(),
        "complete() is idempotent"
    );
    let a = resolve(s, Path::new(".")).expect("resolves");
    let b = resolve(&back, Path::new(".")).expect("printed form resolves");
    assert_eq!(a, b);
}

#[test]
fn every_builtin_round_trips() {
    for name in builtin_names() {
        roundtrip(&builtin(&name).unwrap());
    }
}

#[test]
fn general_form_round_trips() {
    let s = Scenario::parse(GENERAL).unwrap();
    roundtrip(&s);
    let text = s.to_toml();
    for key in [
        "kind = \"sphere\"",
        "pmma",
        "contact_beta",
        "rtol",
        "atol",
        "cap_radius_mm",
    ] {
        if key == "cap_radius_mm" {
            assert!(
                !text.contains("\ncap_radius_mm"),
                "flat wall has no cap radius"
            );
        } else {
            assert!(text.contains(key), "missing {key} in\n{text}");
        }
    }
}

fn summary_without_wall_time(path: &Path) -> serde_json::Value {
    let mut v = common::json(path);
    v.as_object_mut().unwrap().remove("wall_time_s");
    v.as_object_mut().unwrap().remove("scenario");
    v
}

#[test]
fn printed_scenario_runs_identically() {
    let dir = tempfile::tempdir().unwrap();
    let name = "paper-impact-optimized";
    let printed = common::run_in(dir.path(), &["scenario", name]);
    assert!(printed.status.success());
    common::write(
        dir.path(),
        "s.toml",
        &String::from_utf8(printed.stdout).unwrap(),
    );
    let a = common::run_in(
        dir.path(),
        &["simulate", "--scenario", name, "--out", "a", "-q"],
    );
    assert!(a.status.success(), "{}", String::from_utf8_lossy(&a.stderr));
    let b = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "b", "-q"]);
    assert!(b.status.success(), "{}", String::from_utf8_lossy(&b.stderr));
    assert_eq!(
        summary_without_wall_time(&dir.path().join("a/summary.json")),
        summary_without_wall_time(&dir.path().join("b/summary.json"))
    );
    let (ra, rb) = (
        common::json(&dir.path().join("a/run.json")),
        common::json(&dir.path().join("b/run.json")),
    );
    assert_eq!(ra["scenario"], rb["scenario"]);
    assert_eq!(
        ra["contact_betas_n_per_m1_5"],
        rb["contact_betas_n_per_m1_5"]
    );
}
