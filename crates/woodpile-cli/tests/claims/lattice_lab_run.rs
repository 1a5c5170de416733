//! Claim: `woodpile simulate` runs a damped, loaded lattice (docs/physics.md §16) into the
//! lattice run-directory format: a blast on every top-layer crossing of a 3 × 2-rod lattice
//! under gravity with restitution contacts lists its 6 load points first in `run.json`'s
//! `contacts` (layer 0, numbered 1..6, each on the top rod under it), then the crossings and
//! supports; each load point's peak is F0/6 (to 1e-9: the Friedlander profile peaks at
//! t = 0, which counts); `energy.csv` has `total_j`, `work_j`, `dissipated_j`, and E + D − E(0) − W
//! at its last row is below 1e-6 of the largest W (the run's own audit, in `summary.json`);
//! `summary.json` holds per-contact dissipated energies (the supports' positive) and
//! the static forces, whose supports carry the rods' weight within 1e-9. Bad lab input — a
//! blast point on no top rod, an unknown `points`, `at_mm` with a blast, a negative modal
//! ratio, resonator damping, Hunt–Crossley without an impact speed under a
//! blast, rest without a static load, `points` with an impact, `modal_ratio` in a chain — exits
//! with code 2 naming the dotted key as written, the value and what is valid.

use crate::common;

const BLAST: &str = r#"
[lattice]
layers = [
  { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 2 },
]
rod = { fe_elements = 2 }
[excitation]
kind = "blast"
peak_force_n = 60.0
duration_s = 1e-4
[damping]
contact = "restitution"
restitution = 0.8
modal_ratio = 0.01
[preload]
gravity_m_s2 = 9.81
[run]
duration_s = 3e-4
"#;

#[test]
fn damped_blast_run_writes_the_lattice_format() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "lat.toml", BLAST);
    common::simulate_ok(dir.path(), "lat.toml");
    let run = common::json(&dir.path().join("out/run.json"));
    let contacts = run["contacts"].as_array().unwrap();
    // 6 load points + 3 × 2 crossings + 2 supports.
    assert_eq!(contacts.len(), 14);
    for (k, c) in contacts[..6].iter().enumerate() {
        assert_eq!(c["layer_above"], 0);
        assert_eq!(c["rod_above"].as_u64().unwrap(), k as u64 + 1);
        assert_eq!(c["layer_below"], 1);
        // The load point is the crossing below it.
        assert_eq!(c["x_mm"], contacts[6 + k]["x_mm"]);
        assert_eq!(c["y_mm"], contacts[6 + k]["y_mm"]);
    }
    let summary = common::json(&dir.path().join("out/summary.json"));
    let peaks = summary["contact_peak_forces_n"].as_array().unwrap();
    for p in &peaks[..6] {
        assert!((p.as_f64().unwrap() - 10.0).abs() < 1e-9, "{p}");
    }
    let error = summary["energy"]["max_relative_error"].as_f64().unwrap();
    assert!(error < 1e-6, "{error}");
    let dissipated: Vec<f64> = summary["contact_dissipated_j"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(dissipated.len(), 14);
    assert!(dissipated[12] > 0.0 && dissipated[13] > 0.0);
    let statics: Vec<f64> = summary["static_contact_forces_n"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let weight = run["lattice_mass_kg"].as_f64().unwrap() * 9.81;
    assert!((statics[12] + statics[13] - weight).abs() < 1e-9 * weight);
    let energy = std::fs::read_to_string(dir.path().join("out/energy.csv")).unwrap();
    let mut lines = energy.lines();
    assert_eq!(lines.next(), Some("time_s,total_j,work_j,dissipated_j"));
    let first: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let last: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let balance = (last[1] + last[3] - first[1] - last[2]).abs() / last[2];
    assert!(last[3] > 0.01 * last[2], "something was dissipated");
    assert!(balance < 1e-6, "{balance}");
}

#[test]
fn bad_lab_input_exits_2_naming_the_key() {
    let blast = |old: &str, new: &str| BLAST.replace(old, new);
    common::refused_scenario(
        "point off the top layer",
        &blast(
            "kind = \"blast\"",
            "kind = \"blast\"\npoints_mm = [[0.0, 0.0], [0.0, 30.0]]",
        ),
        &[
            "excitation.points_mm[1]",
            "[0, 30]",
            "no rod of the top layer",
        ],
    );
    common::refused_scenario(
        "unknown points",
        &blast(
            "kind = \"blast\"",
            "kind = \"blast\"\npoints = \"everywhere\"",
        ),
        &["excitation.points", "\"everywhere\"", "top-crossings"],
    );
    common::refused_scenario(
        "at_mm with a blast",
        &blast("kind = \"blast\"", "kind = \"blast\"\nat_mm = [0.0, 0.0]"),
        &["excitation.at_mm", "striker's impact point", "points_mm"],
    );
    common::refused_scenario(
        "negative modal ratio",
        &blast("modal_ratio = 0.01", "modal_ratio = -0.01"),
        &["damping.modal_ratio", "-0.01", ">= 0"],
    );
    common::refused_scenario(
        "resonator damping",
        &blast("modal_ratio = 0.01", "resonator_ratio = 0.05"),
        &["damping.resonator_ratio", "0.05", "damping.modal_ratio"],
    );
    common::refused_scenario(
        "hunt-crossley without v_in",
        &blast("contact = \"restitution\"", "contact = \"hunt-crossley\""),
        &["damping.impact_speed_m_s", "v_in"],
    );
    common::refused_scenario(
        "rest without a load",
        &blast(
            "kind = \"blast\"\npeak_force_n = 60.0\nduration_s = 1e-4",
            "kind = \"rest\"",
        )
        .replace("gravity_m_s2 = 9.81", ""),
        &["excitation.kind", "\"rest\"", "[preload]"],
    );
    common::refused_scenario(
        "points with an impact",
        &blast(
            "kind = \"blast\"\npeak_force_n = 60.0\nduration_s = 1e-4",
            "kind = \"impact\"\npoints = \"top-crossings\"",
        ),
        &["excitation.points", "at_mm"],
    );
    common::refused_scenario(
        "modal ratio in a chain",
        "[chain]\nrods_mm = [40, 40]\n[damping]\nmodal_ratio = 0.01\n",
        &["damping.modal_ratio", "0.01", "resonator_ratio"],
    );
}
