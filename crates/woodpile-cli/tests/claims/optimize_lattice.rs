//! Claim: `woodpile optimize` of a lattice study (a config with a `[lattice]` table), struck,
//! under a blast, or damped under gravity, writes the front as `pareto.csv` and lattice scenarios that `woodpile simulate`
//! re-runs to the row's transmitted peak force (the summary's value, bit for bit), and
//! `--resume` of the finished run continues from its checkpoint to the same front; bad design
//! input and a chain-only flag exit 2 naming the key or flag and create no output directory.

use crate::common;

const STUDY: &str = r#"[lattice]
layers = [
  { rods = 3, pitch_mm = 16.0, length_mm = 60.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 3 },
]
rod = { fe_elements = 2 }
[run]
duration_s = 1e-4
peak_tolerance = 1e-4
[design]
length_mm = [50.0, 60.0, 70.0]
pitch_mm = { from_mm = 12.0, to_mm = 16.0, step_mm = 4.0 }
[ga]
population = 6
generations = 3
seed = 5
"#;

#[test]
fn a_lattice_study_writes_a_front_that_reruns_and_resumes() {
    front_reruns_and_resumes(STUDY);
    let blast = STUDY.replace(
        "[run]",
        "[excitation]\nkind = \"blast\"\npeak_force_n = 50.0\nduration_s = 5e-5\n[run]",
    );
    front_reruns_and_resumes(&blast);
    let damped = STUDY.replace(
        "[run]",
        "[damping]\nmodal_ratio = 0.02\n[preload]\ngravity_m_s2 = 9.81\n[run]",
    );
    front_reruns_and_resumes(&damped);
}

fn front_reruns_and_resumes(study: &str) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", study);
    let out = common::run_in(dir.path(), &["optimize", "s.toml", "--out", "o", "--quiet"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.path().join("o/pareto.csv")).unwrap();
    let first: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    let force: f64 = first[0].parse().unwrap();
    let sim = common::run_in(
        dir.path(),
        &["simulate", "o/pareto/001.toml", "--out", "r", "--quiet"],
    );
    assert!(
        sim.status.success(),
        "{}",
        String::from_utf8_lossy(&sim.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("r/summary.json")).unwrap())
            .unwrap();
    assert_eq!(
        summary["transmitted_peak_force_n"]
            .as_f64()
            .unwrap()
            .to_bits(),
        force.to_bits()
    );
    let again = common::run_in(
        dir.path(),
        &["optimize", "s.toml", "--out", "o", "--resume", "--quiet"],
    );
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("o/pareto.csv")).unwrap(),
        csv
    );
}

#[test]
fn bad_lattice_study_input_exits_2_naming_the_key() {
    for (config, flag, expected) in [
        (
            STUDY.replace("step_mm = 4.0", "step_mm = -1.0"),
            None,
            "design.pitch_mm.step_mm",
        ),
        (
            STUDY.replace("[50.0, 60.0, 70.0]", "[50.0, 0.0]"),
            None,
            "design.length_mm[1]",
        ),
        (
            STUDY.replace("seed = 5", "objectives = [\"stack-height\"]"),
            None,
            "ga.objectives[0]",
        ),
        (
            STUDY.to_string(),
            Some("--paper-settings"),
            "--paper-settings",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        common::write(dir.path(), "s.toml", &config);
        let mut args = vec!["optimize", "s.toml", "--out", "o"];
        args.extend(flag);
        let out = common::run_in(dir.path(), &args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{expected}: {stderr}");
        assert!(
            stderr.contains(expected),
            "expected `{expected}` in: {stderr}"
        );
        assert!(
            !dir.path().join("o").exists(),
            "{expected}: output dir created"
        );
    }
}
