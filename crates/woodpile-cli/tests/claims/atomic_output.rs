//! Claim: outputs are written atomically and never clobber foreign data. A second run into the
//! same directory replaces the previous run (recognised by its run.json) completely; an empty
//! directory is used; a non-empty directory without run.json is refused with exit 2 and left
//! untouched; an unwritable location exits 2 naming the path; no staging directory survives.

use crate::common;

#[test]
fn previous_run_is_replaced() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", common::SHORT);
    let first = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out", "-q"]);
    assert!(first.status.success());
    common::write(&dir.path().join("out"), "stale.txt", "from before");
    common::write(
        dir.path(),
        "t.toml",
        "[chain]\nrods_mm = [20, 20]\n[run]\nduration_s = 1e-4\n",
    );
    let second = common::run_in(dir.path(), &["simulate", "t.toml", "--out", "out", "-q"]);
    assert!(
        second.status.success(),
        "{}",
        String::from_utf8_lossy(&second.stderr)
    );
    let s = common::json(&dir.path().join("out/summary.json"));
    assert_eq!(s["n_elements"], 2);
    assert!(
        !dir.path().join("out/stale.txt").exists(),
        "old run removed whole"
    );
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
    let out = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "thesis"]);
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
