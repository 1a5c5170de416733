//! Claim: the built-in lattice `lattice` (docs/physics.md §16: the 3 × 3-rod, 4-layer quartz
//! woodpile struck at (13, 0) mm) is listed by `woodpile scenarios`, printed by `woodpile scenario
//! lattice` as a lattice scenario file that runs as the built-in does, and run by name:
//! `woodpile simulate --scenario lattice` writes a lattice run directory with the striker's contact, the
//! 3 × 9 crossings and the 3 supports (31 contacts), and a lossless energy balance within the
//! peak tolerance's 1e-4 (measured: docs/physics.md §16's mesh table).

use crate::common;

#[test]
fn builtin_lattice_is_listed_printed_and_run_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let list = common::run_in(dir.path(), &["scenarios"]);
    assert!(list.status.success());
    let text = String::from_utf8_lossy(&list.stdout);
    assert!(
        text.lines()
            .any(|l| l.starts_with("lattice ") && l.contains("4-layer")),
        "{text}"
    );
    let shown = common::run_in(dir.path(), &["scenario", "lattice"]);
    assert!(shown.status.success());
    let toml = String::from_utf8_lossy(&shown.stdout).to_string();
    assert!(woodpile_io::lattice::is_lattice(&toml), "{toml}");
    common::write(dir.path(), "lat.toml", &toml);
    for source in [
        &["--scenario", "lattice", "--out", "by-name"][..],
        &["lat.toml", "--out", "from-file"],
    ] {
        let args: Vec<&str> = ["simulate", "--quiet"]
            .iter()
            .chain(source)
            .copied()
            .collect();
        let run = common::run_in(dir.path(), &args);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
    }
    let run = common::json(&dir.path().join("by-name/run.json"));
    assert_eq!(run["scenario_name"], "lattice");
    assert_eq!(run["contacts"].as_array().unwrap().len(), 31);
    let by_name = common::json(&dir.path().join("by-name/summary.json"));
    let from_file = common::json(&dir.path().join("from-file/summary.json"));
    for key in ["contact_peak_forces_n", "transmitted_peak_force_n"] {
        assert_eq!(
            by_name[key], from_file[key],
            "the printed file is the built-in"
        );
    }
    assert!(by_name["energy"]["max_relative_error"].as_f64().unwrap() < 1e-4);
}
