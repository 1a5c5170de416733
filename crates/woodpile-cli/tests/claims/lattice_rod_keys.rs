//! Claim: a lattice scenario's per-rod keys work from the command line (docs/physics.md §16). A
//! staggered, graded layer (`offsets_mm`, `lengths_mm`) runs (exit 0) and its `run.json` lists
//! the crossings the geometry gives: the shortened rod loses the two beyond its ends, and every
//! crossing lies at its rods' axes (x of the lower rod, y of the upper, whatever their offsets).
//! Bad per-rod keys exit 2 naming the dotted key as written (`lattice.layers[1].lengths_mm[1]`),
//! the value and what is valid, and leave no output directory: a wrong count, a length that is
//! not > 0, a rod moved off every rod of the adjacent layer, more distinct rods than the limit.
//! `rod = { modes = 4 }` runs the same lattice on analytic modes (exit 0; the completed scenario
//! keeps `modes` and no `fe_elements`; the energy kept to 1e-4 at the default peak tolerance);
//! `fe_elements` and `modes` together, `modes = 0`, and more modes than lie below the rods'
//! shear cutoff exit 2 naming `lattice.rod.modes`.

use crate::common;

const LATTICE: &str = r#"
[lattice]
layers = [
  { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 3, lengths_mm = [80.0, 30.0, 80.0], offsets_mm = [-15.0, 0.0, 15.0] },
]
rod = { fe_elements = 2 }
[excitation]
kind = "impact"
at_mm = [0.0, 0.0]
[run]
duration_s = 1e-4
"#;

#[test]
fn staggered_graded_layer_runs_with_its_crossings() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "lat.toml", LATTICE);
    common::simulate_ok(dir.path(), "lat.toml");
    let run = common::json(&dir.path().join("out/run.json"));
    let contacts = run["contacts"].as_array().unwrap();
    let crossings: Vec<_> = contacts
        .iter()
        .filter(|c| c["layer_above"] == 1 && c["layer_below"] == 2)
        .collect();
    // Lower rods along y at x = −20, 0, 20 mm; the middle one 30 mm long reaches y = ±15 mm
    // only, so it meets the top rod at y = 0 and not those at y = ±20 mm: 9 − 2 crossings.
    assert_eq!(crossings.len(), 7);
    for c in crossings {
        let (upper, lower) = (
            c["rod_above"].as_f64().unwrap(),
            c["rod_below"].as_f64().unwrap(),
        );
        assert!(lower != 2.0 || upper == 2.0, "{c}");
        assert!(
            (c["x_mm"].as_f64().unwrap() - (lower - 2.0) * 20.0).abs() < 1e-9,
            "{c}"
        );
        assert!(
            (c["y_mm"].as_f64().unwrap() - (upper - 2.0) * 20.0).abs() < 1e-9,
            "{c}"
        );
    }
    // The supports sit under the bottom rods' centres, which the offsets moved along y.
    let supports: Vec<_> = contacts.iter().filter(|c| c["layer_below"] == 3).collect();
    for (s, offset) in supports.iter().zip([-15.0, 0.0, 15.0]) {
        assert!((s["y_mm"].as_f64().unwrap() - offset).abs() < 1e-9, "{s}");
    }
    // The completed scenario keeps the per-rod keys of the layer that gave them only.
    let layers = run["scenario"]["lattice"]["layers"].as_array().unwrap();
    assert!(layers[0].get("lengths_mm").is_none());
    assert_eq!(layers[1]["offsets_mm"][2], 15.0);
}

#[test]
fn analytic_modes_rod_runs() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = LATTICE.replace("rod = { fe_elements = 2 }", "rod = { modes = 4 }");
    common::write(dir.path(), "lat.toml", &scenario);
    common::simulate_ok(dir.path(), "lat.toml");
    let run = common::json(&dir.path().join("out/run.json"));
    assert_eq!(run["scenario"]["lattice"]["rod"]["modes"], 4);
    assert!(run["scenario"]["lattice"]["rod"]
        .get("fe_elements")
        .is_none());
    let summary = common::json(&dir.path().join("out/summary.json"));
    assert!(summary["energy"]["max_relative_error"].as_f64().unwrap() < 1e-4);
}

#[test]
fn bad_per_rod_keys_exit_2_naming_the_key() {
    common::refused_scenario(
        "both rod models",
        &LATTICE.replace(
            "rod = { fe_elements = 2 }",
            "rod = { fe_elements = 2, modes = 3 }",
        ),
        &["lattice.rod.modes", "alternatives"],
    );
    common::refused_scenario(
        "no bending mode",
        &LATTICE.replace("rod = { fe_elements = 2 }", "rod = { modes = 0 }"),
        &["lattice.rod.modes", "at least 1"],
    );
    common::refused_scenario(
        "above the shear cutoff",
        &LATTICE.replace("rod = { fe_elements = 2 }", "rod = { modes = 500 }"),
        &["lattice.rod.modes", "500", "shear cutoff"],
    );
    common::refused_scenario(
        "count",
        &LATTICE.replace(
            "lengths_mm = [80.0, 30.0, 80.0]",
            "lengths_mm = [80.0, 30.0]",
        ),
        &[
            "lattice.layers[1].lengths_mm",
            "2 entries",
            "one entry per rod of the layer: 3",
        ],
    );
    common::refused_scenario(
        "length",
        &LATTICE.replace(
            "lengths_mm = [80.0, 30.0, 80.0]",
            "lengths_mm = [80.0, 0.0, 80.0]",
        ),
        &["lattice.layers[1].lengths_mm[1]", "> 0"],
    );
    common::refused_scenario(
        "rod moved off",
        &LATTICE.replace(
            "offsets_mm = [-15.0, 0.0, 15.0]",
            "offsets_mm = [-15.0, 0.0, 150.0]",
        ),
        &[
            "lattice.layers[1].offsets_mm[2]",
            "150",
            "rod 3 of this layer crosses no rod",
        ],
    );
    let lengths: Vec<String> = (0..101)
        .map(|i| format!("{}", 60.0 + 0.1 * i as f64))
        .collect();
    common::refused_scenario(
        "distinct rods",
        &LATTICE
            .replace(
                "{ rods = 3, pitch_mm = 20.0",
                "{ rods = 101, pitch_mm = 20.0",
            )
            .replace(
                "length_mm = 80.0,",
                &format!("lengths_mm = [{}],", lengths.join(", ")),
            ),
        &[
            "lattice.layers[0].lengths_mm[100]",
            "70",
            "more than 100 distinct rods",
        ],
    );
}
