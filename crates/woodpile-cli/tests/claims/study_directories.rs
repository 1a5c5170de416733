//! Claim: the output directories of the studies are told apart and never put a user's files at
//! risk.
//!
//! - `plot` of a sensitivity study draws its bar charts; `plot` of a `--samples` study says it
//!   has no figures (and never that it "looks like a `woodpile optimize` output").
//! - `--out` a directory of the user's that happens to hold a `summary.json` is refused for
//!   `simulate --samples` and `sensitivity` without advice to remove or delete anything and
//!   without a flag `sensitivity` does not have (`--overwrite`); the user's files are untouched,
//!   byte for byte.
//! - Of two `sensitivity` runs into one new directory, one completes it and the other is refused
//!   in the same words (no `--overwrite`).
//! - `--resume` of a finished NSGA-II run whose `history.csv` was lost writes it again from the
//!   checkpoint, so the directory is whole and `plot` draws it.

use crate::common;

const SCATTERED: &str = "[chain]\nrods_mm = [40, 30, 20]\n[run]\nduration_s = 2e-4\n[uncertainty]\nimpact_velocity_m_s = { uniform = [1.8, 2.2] }\n";

fn ok(dir: &std::path::Path, args: &[&str]) -> String {
    let out = common::run_in(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{args:?}: {stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned() + &stderr
}

fn refused(dir: &std::path::Path, args: &[&str]) -> String {
    let out = common::run_in(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    stderr
}

#[test]
fn plot_tells_a_sensitivity_study_and_a_samples_study_apart() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", SCATTERED);
    ok(
        dir.path(),
        &[
            "sensitivity",
            "s.toml",
            "--base-samples",
            "8",
            "--out",
            "sens",
            "--quiet",
        ],
    );
    std::fs::remove_dir_all(dir.path().join("sens/plots")).unwrap();
    ok(dir.path(), &["plot", "sens", "--quiet"]);
    assert!(dir
        .path()
        .join("sens/plots/indices_transmitted_peak_force_n.png")
        .is_file());
    ok(
        dir.path(),
        &[
            "simulate",
            "s.toml",
            "--samples",
            "4",
            "--out",
            "k",
            "--quiet",
        ],
    );
    let stderr = refused(dir.path(), &["plot", "k"]);
    assert!(stderr.contains("samples study"), "{stderr}");
    assert!(!stderr.contains("optimize"), "{stderr}");
}

#[test]
fn a_users_summary_json_is_neither_overwritten_nor_advised_away() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", SCATTERED);
    let mine = dir.path().join("mine");
    std::fs::create_dir(&mine).unwrap();
    common::write(&mine, "summary.json", "{\"my\": \"results\"}");
    common::write(&mine, "notes.txt", "lab book");
    for args in [
        &["simulate", "s.toml", "--samples", "4", "--out", "mine"][..],
        &[
            "sensitivity",
            "s.toml",
            "--base-samples",
            "8",
            "--out",
            "mine",
        ][..],
    ] {
        let stderr = refused(dir.path(), args);
        assert!(stderr.contains("--out = mine"), "{stderr}");
        assert!(stderr.contains("choose another --out"), "{stderr}");
        for advice in ["remove", "delete", "--overwrite"] {
            assert!(
                !stderr.contains(advice),
                "{args:?} says `{advice}`: {stderr}"
            );
        }
    }
    let summary = std::fs::read_to_string(mine.join("summary.json")).unwrap();
    assert_eq!(summary, "{\"my\": \"results\"}");
    assert_eq!(std::fs::read_dir(&mine).unwrap().count(), 2);
}

#[test]
fn the_loser_of_two_concurrent_studies_is_not_told_to_overwrite() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", SCATTERED);
    let args = [
        "sensitivity",
        "s.toml",
        "--base-samples",
        "128",
        "--out",
        "same",
        "--quiet",
    ];
    let runs: Vec<_> = (0..2)
        .map(|_| {
            common::woodpile()
                .current_dir(dir.path())
                .args(args)
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    let outs: Vec<_> = runs
        .into_iter()
        .map(|c| c.wait_with_output().unwrap())
        .collect();
    let won = outs.iter().filter(|o| o.status.success()).count();
    assert!(won >= 1, "one run completes the directory");
    for o in outs.iter().filter(|o| !o.status.success()) {
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{stderr}");
        assert!(!stderr.contains("--overwrite"), "{stderr}");
    }
    assert!(dir.path().join("same/summary.json").is_file());
    assert!(common::leftovers(dir.path()).is_empty());
}

#[test]
fn resuming_a_finished_nsga2_run_restores_its_history() {
    let dir = tempfile::tempdir().unwrap();
    let config = "[design]\npositions = 4\ncatalogue_mm = [20, 40, 60]\n[run]\nduration_s = 3e-4\npeak_tolerance = 1e-4\n[ga]\nobjectives = [\"transmitted-force\", \"total-mass\"]\npopulation = 8\ngenerations = 2\n";
    common::write(dir.path(), "mo.toml", config);
    ok(
        dir.path(),
        &["optimize", "mo.toml", "--out", "o", "--quiet"],
    );
    let history = dir.path().join("o/history.csv");
    let written = std::fs::read_to_string(&history).unwrap();
    std::fs::remove_file(&history).unwrap();
    ok(
        dir.path(),
        &["optimize", "mo.toml", "--out", "o", "--resume", "--quiet"],
    );
    assert_eq!(std::fs::read_to_string(&history).unwrap(), written);
    ok(dir.path(), &["plot", "o", "--quiet"]);
}
