//! Claim: `woodpile optimize` with `ga.objectives = [...]` runs NSGA-II and writes what a designer
//! reads: `pareto.csv` with one column per objective named as in the config, then `layer_1` …
//! `layer_N` (rod lengths in mm); no row dominates another; row k is `pareto/00k.toml`, a
//! scenario `woodpile simulate` re-runs to the same transmitted force (bit for bit) and whose
//! mass is the row's total-mass; `history.csv` holds the hypervolume of every generation and
//! `summary.json` its reference point; `references.csv` holds the catalogue's homogeneous
//! chains with their objectives (the 5 × 20mm chain's total-mass is 5 times the 20 mm rod's
//! mass in Table 1, 0.423 g + 0.443 g of resonator, to rounding), and `woodpile plot` of the directory draws
//! the front, the front's designs and the hypervolume history. Bad input — an unknown objective, both `objective` and
//! `objectives`, two objectives for the breeder GA, a pressure limit for the breeder GA, a
//! height no design meets (refused before any simulation, with both heights in mm) — exits
//! with code 2 naming the key, and creates no output directory.

use crate::common;

const MO: &str = "[design]\npositions = 5\ncatalogue_mm = [20, 40, 60, 80]\n[run]\nduration_s = 4e-4\npeak_tolerance = 1e-4\n[ga]\nobjectives = [\"transmitted-force\", \"total-mass\"]\npopulation = 12\ngenerations = 4\n";

#[test]
fn nsga2_writes_a_front_that_reruns() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "mo.toml", MO);
    let out = common::run_in(dir.path(), &["optimize", "mo.toml", "--out", "o"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let o = dir.path().join("o");
    let csv = std::fs::read_to_string(o.join("pareto.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "transmitted-force,total-mass,layer_1,layer_2,layer_3,layer_4,layer_5"
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    assert!(!rows.is_empty());
    let values: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r[0].parse().unwrap(), r[1].parse().unwrap()))
        .collect();
    for (i, a) in values.iter().enumerate() {
        for b in &values[i + 1..] {
            let dominates = |x: &(f64, f64), y: &(f64, f64)| x.0 <= y.0 && x.1 <= y.1 && x != y;
            assert!(
                !dominates(a, b) && !dominates(b, a),
                "{a:?} and {b:?} on one front"
            );
        }
    }
    let summary = common::json(&o.join("summary.json"));
    assert_eq!(summary["reference_point"].as_array().unwrap().len(), 2);
    assert_eq!(summary["objectives"][1]["unit"], "kg");
    let history = std::fs::read_to_string(o.join("history.csv")).unwrap();
    assert!(history.starts_with("generation,hypervolume,"));
    assert_eq!(history.lines().count(), 1 + 5, "generations 0..=4");
    let references = std::fs::read_to_string(o.join("references.csv")).unwrap();
    let homogeneous: Vec<&str> = references
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(
        homogeneous,
        ["5 × 20mm", "5 × 40mm", "5 × 60mm", "5 × 80mm"],
        "{references}"
    );
    let mass_20: f64 = references
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .nth(2)
        .unwrap()
        .parse()
        .unwrap();
    let table1_g = 0.423 + 0.443;
    assert!(
        (mass_20 / 5.0 * 1e3 / table1_g - 1.0).abs() < 1e-12,
        "5 × 20mm weighs {mass_20} kg"
    );
    let plot = common::run_in(dir.path(), &["plot", "o"]);
    let stderr = String::from_utf8_lossy(&plot.stderr);
    assert!(
        plot.status.success(),
        "plot of an NSGA-II directory: {stderr}"
    );
    for figure in ["pareto_front", "pareto_designs", "hypervolume"] {
        for ext in ["png", "svg"] {
            let file = o.join("plots").join(format!("{figure}.{ext}"));
            assert!(
                std::fs::metadata(&file).is_ok_and(|m| m.len() > 1000),
                "{} drawn",
                file.display()
            );
        }
    }
    for (k, row) in rows.iter().enumerate() {
        let scenario = format!("o/pareto/{:03}.toml", k + 1);
        let run_dir = format!("run{k}");
        let rerun = common::run_in(dir.path(), &["simulate", &scenario, "--out", &run_dir]);
        assert!(
            rerun.status.success(),
            "{}",
            String::from_utf8_lossy(&rerun.stderr)
        );
        let figures = common::json(&dir.path().join(&run_dir).join("summary.json"));
        let force = figures["transmitted_peak_force_n"].as_f64().unwrap();
        assert_eq!(
            force.to_bits(),
            values[k].0.to_bits(),
            "row {}: {force} N vs {}",
            k + 1,
            values[k].0
        );
        let text = std::fs::read_to_string(dir.path().join(&scenario)).unwrap();
        let rods = row[2..].join(", ");
        assert!(
            text.contains(&format!("rods_mm = [{rods}]")),
            "row {} is not {scenario}",
            k + 1
        );
    }
}

#[test]
fn bad_design_studies_exit_2_naming_the_key() {
    let cases: [(&str, String, &[&str]); 5] = [
        (
            "unknown objective",
            MO.replace("\"total-mass\"]", "\"total-mass\", \"weight\"]"),
            &["ga.objectives[2]", "weight", "max-contact-pressure"],
        ),
        (
            "objective and objectives",
            MO.replace(
                "population = 12",
                "population = 12\nobjective = \"transmitted-force\"",
            ),
            &["ga.objectives", "not both"],
        ),
        (
            "breeder with two objectives",
            MO.replace(
                "population = 12",
                "population = 12\nalgorithm = \"breeder\"",
            ),
            &["ga.algorithm", "breeder", "nsga2"],
        ),
        (
            "pressure limit for the breeder",
            MO.replace(
                "[\"transmitted-force\", \"total-mass\"]",
                "[\"transmitted-force\"]",
            )
            .replace(
                "[run]",
                "[design.constraints]\nmax_contact_pressure_pa = 1e9\n[run]",
            ),
            &["design.constraints.max_contact_pressure_pa", "nsga2"],
        ),
        (
            "height no design meets, before any simulation (a 10 s run would take minutes)",
            MO.replace(
                "[run]",
                "[design.constraints]\nmax_stack_height_mm = 24.5\n[run]",
            )
            .replace(
                "duration_s = 4e-4",
                "duration_s = 10.0\nsample_interval_s = 1e-3",
            ),
            &["design.constraints.max_stack_height_mm", "24.5", "25 mm"],
        ),
    ];
    for (name, config, expected) in cases {
        let dir = tempfile::tempdir().unwrap();
        common::write(dir.path(), "c.toml", &config);
        let out = common::run_in(dir.path(), &["optimize", "c.toml", "--out", "out"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        for e in expected {
            assert!(stderr.contains(e), "{name}: expected `{e}` in: {stderr}");
        }
        assert!(
            !dir.path().join("out").exists(),
            "{name}: output dir created"
        );
    }
}
