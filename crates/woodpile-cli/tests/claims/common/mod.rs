//! Helpers shared by the command-line tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `woodpile` binary under test.
pub fn woodpile() -> Command {
    Command::new(env!("CARGO_BIN_EXE_woodpile"))
}

/// Runs `woodpile` with these arguments in `cwd`.
pub fn run_in(cwd: &Path, args: &[&str]) -> Output {
    woodpile()
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("the woodpile binary runs")
}

/// Writes `text` to `dir/name` and returns the path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write test file");
    p
}

/// A short, valid scenario (5 rods, 0.2 ms) for runs in tests.
pub const SHORT: &str = "[chain]\nrods_mm = [80, 40, 20, 30, 50]\n[run]\nduration_s = 2e-4\n";

/// Names in `dir` that look like staging directories of an unfinished run.
pub fn leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.contains(".partial-") || n.contains(".old-"))
                .collect()
        })
        .unwrap_or_default()
}

/// Reads a JSON file.
pub fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("read json")).expect("valid json")
}

/// `woodpile simulate NAME --out out --quiet` in `dir`, which must succeed.
pub fn simulate_ok(dir: &Path, name: &str) {
    let out = run_in(dir, &["simulate", name, "--out", "out", "--quiet"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `woodpile simulate` of `scenario` must exit 2 with an error holding every `expected` text
/// and leave no output directory (`name` labels the case).
pub fn refused_scenario(name: &str, scenario: &str, expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "s.toml", scenario);
    let out = run_in(dir.path(), &["simulate", "s.toml", "--out", "out"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
    assert!(stderr.starts_with("error: "), "{name}: {stderr}");
    for e in expected {
        assert!(stderr.contains(e), "{name}: expected `{e}` in: {stderr}");
    }
    assert!(!dir.path().join("out").exists(), "{name}: output dir left");
}
