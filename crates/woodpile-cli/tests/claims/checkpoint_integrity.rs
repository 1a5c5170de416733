//! Claim: a checkpoint is trusted only when it is exactly what woodpile wrote for this problem.
//!
//! - `checkpoint.json` records the tool version and a checksum of its content.
//! - A hand-edited objective (0.001 N) is refused on --resume (exit 2) naming the checksum.
//! - A checkpoint of another version (its checksum recomputed, so only the version differs) is
//!   refused naming both versions.
//! - A config that differs only in its description resumes (exit 0) and ends with the same best
//!   objective as the uninterrupted run; one that differs in the problem is refused.
//! - Duplicate catalogue entries and duplicate contact_beta entries are input errors (exit 2)
//!   naming both indices.

use crate::common;
use woodpile_io::optimize::Checkpoint;

const CONFIG: &str = "[design]\npositions = 3\ncatalogue_mm = [20, 50, 80]\n[run]\nduration_s = 3e-4\ntime_step_s = 2e-7\n[ga]\npopulation = 6\ngenerations = 3\nseed = 4\n";

fn finished_run(d: &std::path::Path) {
    common::write(d, "c.toml", CONFIG);
    let out = common::run_in(d, &["optimize", "c.toml", "--out", "opt", "-q"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn resume(d: &std::path::Path, config: &str) -> std::process::Output {
    common::run_in(d, &["optimize", config, "--out", "opt", "--resume", "-q"])
}

#[test]
fn checkpoint_records_version_and_checksum() {
    let dir = tempfile::tempdir().unwrap();
    finished_run(dir.path());
    let cp = common::json(&dir.path().join("opt/checkpoint.json"));
    assert_eq!(cp["tool_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(cp["checksum"].as_str().unwrap().len(), 16);
    let ok = resume(dir.path(), "c.toml");
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
}

#[test]
fn tampered_objective_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    finished_run(dir.path());
    let path = dir.path().join("opt/checkpoint.json");
    let mut cp = common::json(&path);
    cp["population"][0]["objective"] = serde_json::json!(0.001);
    std::fs::write(&path, serde_json::to_string(&cp).unwrap()).unwrap();
    let out = resume(dir.path(), "c.toml");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("checksum") && stderr.contains("modified"),
        "{stderr}"
    );
}

#[test]
fn foreign_version_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    finished_run(dir.path());
    let path = dir.path().join("opt/checkpoint.json");
    let mut cp: Checkpoint =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    cp.tool_version = "0.0.1".into();
    cp.checksum = cp.content_checksum();
    std::fs::write(&path, serde_json::to_string(&cp).unwrap()).unwrap();
    let out = resume(dir.path(), "c.toml");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("0.0.1") && stderr.contains(env!("CARGO_PKG_VERSION")),
        "{stderr}"
    );
}

#[test]
fn description_does_not_change_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    finished_run(d);
    let best = common::json(&d.join("opt/summary.json"))["best_objective"].as_f64();
    common::write(
        d,
        "described.toml",
        &format!("description = \"my notes\"\n{CONFIG}"),
    );
    let out = resume(d, "described.toml");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        common::json(&d.join("opt/summary.json"))["best_objective"].as_f64(),
        best
    );
    common::write(d, "other.toml", &CONFIG.replace("seed = 4", "seed = 5"));
    let other = resume(d, "other.toml");
    assert_eq!(other.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&other.stderr).contains("different problem"));
}

#[test]
fn duplicate_entries_are_input_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    common::write(
        d,
        "dup.toml",
        &CONFIG.replace("[20, 50, 80]", "[20, 50, 20]"),
    );
    let out = common::run_in(d, &["optimize", "dup.toml", "--out", "o"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("design.catalogue_mm[2]") && stderr.contains("design.catalogue_mm[0]"),
        "{stderr}"
    );
    common::write(
        d,
        "s.toml",
        "[chain]\nrods_mm = [20, 20, 20]\ncontact_beta = [{ contact = 1, beta = 1e9 }, { contact = 1, beta = 2e9 }]\n",
    );
    let out = common::run_in(d, &["simulate", "s.toml", "--out", "o"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("chain.contact_beta[1]") && stderr.contains("chain.contact_beta[0]"),
        "{stderr}"
    );
}
