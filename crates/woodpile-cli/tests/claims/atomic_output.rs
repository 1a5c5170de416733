//! Claim: no command deletes a file it did not write, and outputs appear whole or not at all.
//!
//! - A run into a directory that holds an earlier run is refused (exit 2, naming --overwrite);
//!   with --overwrite only the run's own files are replaced — the user's notes and plots/ stay,
//!   and an own file the new run does not write (striker.csv after a blast) is removed.
//! - An empty directory is used; a non-empty directory that is not a run is refused even with
//!   --overwrite and left untouched; an unwritable location exits 2 naming the path.
//! - SIGINT during a run removes its staging directory and exits 130; the staging directory of
//!   a killed run (its process gone) is removed by the next run into the same place, while a
//!   user's hidden directory beside it is not.

use crate::common;

const BLAST: &str =
    "[chain]\nrods_mm = [20, 20]\n[excitation]\nkind = \"blast\"\n[run]\nduration_s = 1e-4\n";

#[test]
fn earlier_run_is_kept_without_overwrite() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", common::SHORT);
    let first = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out", "-q"]);
    assert!(first.status.success());
    let before = std::fs::read(dir.path().join("out/summary.json")).unwrap();
    let second = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out", "-q"]);
    assert_eq!(second.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&second.stderr);
    assert!(stderr.contains("--overwrite"), "{stderr}");
    assert_eq!(
        std::fs::read(dir.path().join("out/summary.json")).unwrap(),
        before
    );
    assert!(common::leftovers(dir.path()).is_empty());
}

#[test]
fn overwrite_replaces_only_run_files() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", common::SHORT);
    let first = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out", "-q"]);
    assert!(first.status.success());
    assert!(dir.path().join("out/striker.csv").is_file());
    common::write(&dir.path().join("out"), "notes.txt", "my notes");
    std::fs::create_dir(dir.path().join("out/plots")).unwrap();
    common::write(&dir.path().join("out/plots"), "fig.png", "a figure");
    common::write(dir.path(), "b.toml", BLAST);
    let second = common::run_in(
        dir.path(),
        &["simulate", "b.toml", "--out", "out", "--overwrite", "-q"],
    );
    assert!(
        second.status.success(),
        "{}",
        String::from_utf8_lossy(&second.stderr)
    );
    let s = common::json(&dir.path().join("out/summary.json"));
    assert_eq!(s["n_elements"], 2);
    assert_eq!(s["excitation"], "blast");
    let out = dir.path().join("out");
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "my notes"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("plots/fig.png")).unwrap(),
        "a figure"
    );
    assert!(!out.join("striker.csv").exists(), "stale own file removed");
    assert!(out.join("run.json").is_file());
    assert!(common::leftovers(dir.path()).is_empty());
}

#[test]
fn empty_directory_is_used() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", common::SHORT);
    std::fs::create_dir(dir.path().join("out")).unwrap();
    let out = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out", "-q"]);
    assert!(out.status.success());
    assert!(dir.path().join("out/run.json").is_file());
}

#[test]
fn foreign_directory_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", common::SHORT);
    std::fs::create_dir(dir.path().join("thesis")).unwrap();
    common::write(&dir.path().join("thesis"), "chapter1.tex", "precious");
    let out = common::run_in(
        dir.path(),
        &["simulate", "s.toml", "--out", "thesis", "--overwrite"],
    );
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("thesis") && stderr.contains("run.json"),
        "{stderr}"
    );
    let names: Vec<_> = std::fs::read_dir(dir.path().join("thesis"))
        .unwrap()
        .collect();
    assert_eq!(names.len(), 1, "left untouched");
    assert!(common::leftovers(dir.path()).is_empty());
}

#[test]
fn unwritable_location_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", common::SHORT);
    common::write(dir.path(), "afile", "not a directory");
    let out = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "afile/out"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("afile"));
}

#[test]
fn default_output_is_runs_slash_name() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "short.toml", common::SHORT);
    let out = common::run_in(dir.path(), &["simulate", "short.toml", "-q"]);
    assert!(out.status.success());
    assert!(dir.path().join("runs/short/summary.json").is_file());
    assert!(common::leftovers(&dir.path().join("runs")).is_empty());
}

#[test]
fn staging_of_a_killed_run_is_cleaned_and_nothing_else() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", common::SHORT);
    // PID 999999999 exceeds Linux's pid_max: that process cannot be alive.
    let stale = dir.path().join(".out.partial-999999999");
    std::fs::create_dir(&stale).unwrap();
    common::write(&stale, "forces.csv", "half-written");
    let mine = dir.path().join(".out.partial-notes");
    std::fs::create_dir(&mine).unwrap();
    let out = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out", "-q"]);
    assert!(out.status.success());
    assert!(!stale.exists(), "abandoned staging directory removed");
    assert!(mine.is_dir(), "a directory woodpile did not write is kept");
}

#[cfg(unix)]
#[test]
fn sigint_removes_staging_and_exits_130() {
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    // 100 rods for 0.5 s of simulated time: minutes of work, interrupted within a second.
    common::write(
        dir.path(),
        "long.toml",
        "[chain]\nrods_mm = [40, 40, 40, 40, 40, 40, 40, 40, 40, 40]\n[run]\nduration_s = 0.5\nsample_interval_s = 1e-4\n",
    );
    let child = common::woodpile()
        .current_dir(dir.path())
        .args(["simulate", "long.toml", "--out", "out", "-q"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while common::leftovers(dir.path()).is_empty() {
        assert!(
            started.elapsed() < Duration::from_secs(30),
            "no staging directory"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    std::thread::sleep(Duration::from_millis(100));
    let killed = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130));
    assert!(common::leftovers(dir.path()).is_empty(), "staging removed");
    assert!(!dir.path().join("out").exists());
}
