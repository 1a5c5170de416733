//! Claim: `woodpile simulate` with no argument is the project's default job: docs/physics.md §9's
//! optimised 20-rod chain, resonant, under the paper's impact (10 mm glass sphere from 0.20 m,
//! 2 ms, RK4 at 0.1 µs), written to ./runs/paper-impact-optimized/; the conserved energy drifts by
//! less than 1e-6 relative (the library's RK4 tolerance at this step).

use crate::common;

#[test]
fn no_argument_runs_the_optimised_chain_under_impact() {
    let dir = tempfile::tempdir().unwrap();
    let out = common::run_in(dir.path(), &["simulate"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let d = dir.path().join("runs/paper-impact-optimized");
    let s = common::json(&d.join("summary.json"));
    let labels: Vec<String> = s["chain_labels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap().trim_end_matches("mm").to_string())
        .collect();
    assert_eq!(
        labels.join(" "),
        "50 80 80 80 60 70 80 80 40 30 40 40 40 30 50 40 20 20 30 50"
    );
    assert_eq!(s["excitation"], "impact");
    assert_eq!(s["n_samples"], 2001);
    assert!(s["energy"]["max_relative_error"].as_f64().unwrap() < 1e-6);
    let r = common::json(&d.join("run.json"));
    assert_eq!(r["scenario"]["chain"]["model"], "resonant");
    assert_eq!(r["scenario"]["excitation"]["drop_height_m"], 0.2);
}
