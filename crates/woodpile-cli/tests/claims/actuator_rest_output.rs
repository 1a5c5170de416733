//! Claim: a displacement drive's actuator at rest, u* (downward; every tip's overlap is
//! δ = u* + u(t) − w, docs/physics.md §14 and §16), is written to `summary.json` as
//! `actuator_rest_m` — in a lattice's `lab` section, at the top level of a chain's — and it is
//! the static state's: checked against the contacts' Hertz overlaps recomputed from the run
//! directory alone (`run.json`'s β, the static forces in `summary.json`). Without a displacement
//! actuator the key is absent.
//!
//! (1) Lattice: one 80 mm quartz rod on two supports at x = ±20 mm, pressed by the actuator at
//! the same two points with F_p = 2 N. By symmetry each tip and each support carries F_p/2, and
//! at each point two opposite forces meet on the same section, so no force bends the rod: it
//! only translates, by the support's overlap. Hence u* = (F_t/β_t)^{2/3} + (F_s/β_s)^{2/3} at
//! either point, the tip's and the support's overlaps in series, with the forces read from
//! `lab.contact_static_forces_n` and β from `run.json`. Tolerance 1e-10 of u*: the static solve
//! stops at |∇Π| ≤ 1e-12 |f|, so a static force is off by at most ~1e-12 F_p, an overlap by
//! (2/3) of that relatively; the rest is margin for the JSON round trip (1 ulp) and rounding.
//! The tips' forces are checked to be F_p/2 each (1e-10 of F_p, the same residual).
//!
//! (2) Chain: three rods under the default tip (the paper's steel cap), with gravity, preloaded
//! with F_p = 1 N and 4 N. The elements are rigid point masses in series on the wall, so the top
//! element rests at x₁ = Σ_{c=1..N} (F_c/β_c)^{2/3} (every contact's static overlap from the
//! file's forces and β; gravity makes the forces differ), and u* − x₁ is the tip's own overlap
//! (F_p/β₀)^{2/3}: positive, and scaling as F_p^{2/3} between the two runs — the Hertz exponent
//! of the tip, whose β run.json does not list. Tolerance 1e-9 of the ratio: the static state of a
//! chain is closed form (rounding ~1e-16), but u* − x₁ cancels a sum about N + 1 times larger,
//! and every value went through JSON once.
//!
//! (3) The same lattice under a force drive (no actuator, a `lab` section all the same) and the
//! chain under an impact: `actuator_rest_m` absent.

use crate::common;
use std::path::PathBuf;

const LATTICE: &str = r#"
[lattice]
layers = [{ rods = 1, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" }]
rod = { fe_elements = 4 }
[wall]
supports = [{ x_mm = -20.0, y_mm = 0.0 }, { x_mm = 20.0, y_mm = 0.0 }]
[excitation]
kind = "drive"
drive = "displacement"
signal = "harmonic"
amplitude = 1e-7
frequency_hz = 1e4
points_mm = [[-20.0, 0.0], [20.0, 0.0]]
tip = { kind = "cap", material = "steel", cap_radius_mm = 5.0 }
[preload]
force_n = 2.0
[run]
duration_s = 2e-5
"#;

const CHAIN: &str = r#"
[chain]
rods_mm = [80, 40, 20]
[excitation]
kind = "drive"
drive = "displacement"
signal = "harmonic"
amplitude = 1e-7
frequency_hz = 5e3
[preload]
force_n = PRELOAD
gravity_m_s2 = 9.81
[run]
duration_s = 2e-5
"#;

fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Runs `scenario` in a fresh directory: the directory (kept while it lives) and the run's.
fn run_dir(scenario: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", scenario);
    common::simulate_ok(dir.path(), "s.toml");
    let out = dir.path().join("out");
    (dir, out)
}

/// Runs `scenario` in a fresh directory: (run.json, summary.json).
fn simulate(scenario: &str) -> (serde_json::Value, serde_json::Value) {
    let (_dir, out) = run_dir(scenario);
    (
        common::json(&out.join("run.json")),
        common::json(&out.join("summary.json")),
    )
}

/// The static overlap (F/β)^{2/3} of a Hertz contact \[m\].
fn overlap_m(force_n: f64, beta: f64) -> f64 {
    (force_n / beta).powf(2.0 / 3.0)
}

#[test]
fn a_lattice_actuator_rests_on_its_tips_and_supports_in_series() {
    let (_dir, out) = run_dir(LATTICE);
    let run = common::json(&out.join("run.json"));
    let summary = common::json(&out.join("summary.json"));
    let u = summary["actuator_rest_m"]
        .as_f64()
        .expect("actuator_rest_m");
    // Read back through woodpile-io's typed reader as well.
    let typed = woodpile_io::lattice::read_lattice_summary(&out, 4).unwrap();
    assert_eq!(typed.actuator_rest_m, Some(u));

    let contacts = run["contacts"].as_array().unwrap();
    let betas = numbers(&run["contact_betas_n_per_m1_5"]);
    let statics = numbers(&summary["static_contact_forces_n"]);
    assert_eq!(contacts.len(), 4, "two tips, two supports: {contacts:?}");
    let fp = 2.0;
    for tip in 0..2 {
        assert_eq!(contacts[tip]["layer_above"], 0);
        assert!(
            (statics[tip] - fp / 2.0).abs() <= 1e-10 * fp,
            "tip {tip} carries {} N",
            statics[tip]
        );
        // The support at the same point.
        let support = (2..4)
            .find(|&c| contacts[c]["x_mm"] == contacts[tip]["x_mm"])
            .expect("a support under the tip");
        assert_eq!(contacts[support]["layer_below"], 2);
        let series =
            overlap_m(statics[tip], betas[tip]) + overlap_m(statics[support], betas[support]);
        let error = (u - series).abs() / series;
        eprintln!(
            "tip at x = {} mm: u* = {u:.15e} m, tip + support overlaps {series:.15e} m: {error:.2e}",
            contacts[tip]["x_mm"]
        );
        assert!(
            error <= 1e-10,
            "u* = {u} m, the overlaps in series {series} m"
        );
    }

    let (_, forced) = simulate(
        &LATTICE
            .replace("drive = \"displacement\"", "drive = \"force\"")
            .replace(
                "tip = { kind = \"cap\", material = \"steel\", cap_radius_mm = 5.0 }\n",
                "",
            ),
    );
    assert!(
        forced["static_contact_forces_n"].is_array(),
        "a force drive's preload has a static state"
    );
    assert!(
        forced.get("actuator_rest_m").is_none(),
        "a force drive has no actuator: {forced}"
    );
}

/// A chain run under `preload_n`: u* − x₁, both from its run directory.
fn chain_tip_overlap(preload_n: f64) -> f64 {
    let (run, summary) = simulate(&CHAIN.replace("PRELOAD", &format!("{preload_n:?}")));
    let u = summary["actuator_rest_m"]
        .as_f64()
        .expect("actuator_rest_m");
    let statics = numbers(&summary["static_contact_forces_n"]);
    let betas = &run["contact_betas_n_per_m1_5"];
    let mut beta = numbers(&betas["inner"]);
    beta.push(betas["wall"].as_f64().unwrap());
    assert_eq!(statics.len(), beta.len() + 1, "contacts 0..=N");
    assert!(
        (statics[0] - preload_n).abs() <= 1e-12 * preload_n,
        "the tip carries {} N",
        statics[0]
    );
    let top_m: f64 = statics[1..]
        .iter()
        .zip(&beta)
        .map(|(&f, &b)| overlap_m(f, b))
        .sum();
    u - top_m
}

#[test]
fn a_chain_actuator_rests_a_hertz_overlap_above_its_top_element() {
    let (low, high) = (1.0, 4.0);
    let tip_low = chain_tip_overlap(low);
    let tip_high = chain_tip_overlap(high);
    let ratio = tip_high / tip_low;
    let hertz = (high / low).powf(2.0 / 3.0);
    eprintln!(
        "tip overlaps u* − x₁: {tip_low:.6e} m at {low} N, {tip_high:.6e} m at {high} N; ratio \
         {ratio:.15} against (F₂/F₁)^(2/3) = {hertz:.15}: {:.2e}",
        (ratio - hertz).abs() / hertz
    );
    assert!(
        tip_low > 0.0,
        "the tip above the top element by {tip_low} m"
    );
    assert!(
        (ratio - hertz).abs() <= 1e-9 * hertz,
        "the tip's overlap scales by {ratio}, Hertz by {hertz}"
    );

    let (_, impact) = simulate(
        "[chain]\nrods_mm = [80, 40, 20]\n[preload]\nforce_n = 1.0\n[run]\nduration_s = 2e-5\n",
    );
    assert!(
        impact.get("actuator_rest_m").is_none(),
        "an impact has no actuator: {impact}"
    );
}
