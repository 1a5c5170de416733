//! Claim: bad optimisation input — population below 2, a truncation threshold outside (0, 1],
//! an empty catalogue, an unknown rod, constraints no design meets, an unknown objective — exits
//! with code 2 and a message naming the key, the value and the valid range, and creates no
//! output directory; an output directory holding an earlier run is never written into without
//! --resume, and a missing, corrupt or mismatched checkpoint on --resume is refused with code 2
//! and leaves every earlier file byte for byte as it was. A negative --seed or --threads is refused
//! naming the flag.

use crate::common;

use std::path::Path;

const BASE: &str = "[design]\npositions = 3\ncatalogue_mm = [20, 80]\n[run]\nduration_s = 1e-4\ntime_step_s = 2e-7\n[ga]\npopulation = 4\ngenerations = 2\n";

fn fails(dir: &Path, args: &[&str], expected: &[&str]) {
    let out = common::run_in(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
    for e in expected {
        assert!(stderr.contains(e), "{args:?}: expected `{e}` in: {stderr}");
    }
}

fn bad_config(name: &str, config: &str, expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "c.toml", config);
    fails(
        dir.path(),
        &["optimize", "c.toml", "--out", "out"],
        expected,
    );
    assert!(
        !dir.path().join("out").exists(),
        "{name}: output dir created"
    );
}

#[test]
fn invalid_ga_settings_name_field_and_range() {
    let with = |k: &str| BASE.replace("population = 4", k);
    bad_config(
        "pop",
        &with("population = 1"),
        &["ga.population", "1", "at least 2"],
    );
    bad_config(
        "T0",
        &with("population = 4\ntruncation = 0.0"),
        &["ga.truncation", "(0, 1]"],
    );
    bad_config(
        "T>1",
        &with("population = 4\ntruncation = 1.5"),
        &["ga.truncation", "1.5", "(0, 1]"],
    );
    bad_config(
        "objective",
        &with("population = 4\nobjective = \"force\""),
        &["ga.objective", "force", "transmitted-force"],
    );
}

#[test]
fn bad_catalogue_and_infeasible_constraints() {
    bad_config(
        "empty",
        &BASE.replace("catalogue_mm = [20, 80]", "catalogue_mm = []"),
        &["design.catalogue_mm", "at least one element"],
    );
    bad_config(
        "unknown rod",
        &BASE.replace("catalogue_mm = [20, 80]", "catalogue_mm = [20, 25]"),
        &["design.catalogue_mm[1]", "25", "20, 30, 40"],
    );
    bad_config(
        "too light",
        &BASE.replace(
            "[run]",
            "[design.constraints]\nmax_total_mass_g = 1.0\n[run]",
        ),
        // In the config's own unit and key (it was reported as max_total_mass_kg = 0.001).
        &[
            "design.constraints.max_total_mass_g = 1:",
            "weighs 2.598 g",
            "lightest design",
        ],
    );
    bad_config(
        "nan mass",
        &BASE.replace(
            "[run]",
            "[design.constraints]\nmax_total_mass_g = nan\n[run]",
        ),
        // As written, in grams: not the core's max_total_mass_kg.
        &["design.constraints.max_total_mass_g = NaN", "finite"],
    );
    bad_config(
        "counts",
        &BASE.replace(
            "[run]",
            "[design.constraints]\nmax_count = [{ rod_mm = 20, count = 1 }, { rod_mm = 80, count = 1 }]\n[run]",
        ),
        &["design.constraints", "room for 2 elements but 3 positions"],
    );
    bad_config(
        "fixed vs count",
        &BASE.replace(
            "[run]",
            "[design.constraints]\nfixed = [{ layer = 1, rod_mm = 80 }]\nmax_count = [{ rod_mm = 80, count = 0 }]\n[run]",
        ),
        &["design.constraints", "80mm", "at most 0"],
    );
    bad_config(
        "layer",
        &BASE.replace(
            "[run]",
            "[design.constraints]\nfixed = [{ layer = 4, rod_mm = 80 }]\n[run]",
        ),
        &["design.constraints.fixed[0].layer", "4", "1..=3"],
    );
}

fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn earlier_results_are_never_overwritten() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    common::write(d, "c.toml", BASE);
    let ok = common::run_in(d, &["optimize", "c.toml", "--out", "out", "--quiet"]);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let before = snapshot(&d.join("out"));

    // Without --resume: refused.
    fails(
        d,
        &["optimize", "c.toml", "--out", "out"],
        &["--out", "--resume"],
    );
    // A different seed on --resume: mismatched checkpoint.
    fails(
        d,
        &[
            "optimize", "c.toml", "--out", "out", "--resume", "--seed", "9",
        ],
        &["--resume", "different problem", "seed"],
    );
    // A changed config on --resume.
    common::write(
        d,
        "c2.toml",
        &BASE.replace("positions = 3", "positions = 2"),
    );
    fails(
        d,
        &["optimize", "c2.toml", "--out", "out", "--resume"],
        &["different problem", "[design]"],
    );
    assert_eq!(snapshot(&d.join("out")), before, "files changed");

    // A corrupt checkpoint.
    std::fs::write(d.join("out/checkpoint.json"), "{ \"format\": 3").unwrap();
    let corrupt = snapshot(&d.join("out"));
    fails(
        d,
        &["optimize", "c.toml", "--out", "out", "--resume"],
        &["checkpoint.json", "corrupt"],
    );
    assert_eq!(snapshot(&d.join("out")), corrupt, "files changed");

    // --resume where there is nothing to resume; a non-empty directory of something else.
    std::fs::create_dir(d.join("other")).unwrap();
    fails(
        d,
        &["optimize", "c.toml", "--out", "other", "--resume"],
        &["nothing to resume"],
    );
    std::fs::write(d.join("other/notes.txt"), "mine").unwrap();
    fails(d, &["optimize", "c.toml", "--out", "other"], &["not empty"]);
    assert_eq!(
        std::fs::read_to_string(d.join("other/notes.txt")).unwrap(),
        "mine"
    );
}

/// A negative count is refused naming its flag and value (clap's "use '-- -1'" tip, which fails
/// too, was the answer before).
#[test]
fn negative_counts_name_their_flag() {
    for (args, flag) in [
        (
            &["optimize", "any.toml", "--seed", "-1", "--out", "o"][..],
            "--seed",
        ),
        (
            &["optimize", "any.toml", "--threads", "-2", "--out", "o"],
            "--threads",
        ),
        (&["report", "--out", "r", "--seed", "-1"], "--seed"),
        (&["report", "--out", "r", "--threads", "-2"], "--threads"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let out = common::run_in(dir.path(), args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(flag) && stderr.contains("'-"),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("tip:"), "{args:?}: {stderr}");
        assert!(
            common::leftovers(dir.path()).is_empty(),
            "{args:?}: left files"
        );
    }
}
