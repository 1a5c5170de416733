//! Claim: Ctrl-C (SIGINT) stops `woodpile optimize` cleanly (exit 130) at its last complete
//! generation (a generation under way is abandoned), with its checkpoint written and a message
//! saying how to resume; `--resume` then ends exactly
//! where an uninterrupted run ends (same population, history, cache and counters), with 1 or
//! 2 threads.
//!
//! Tolerance: none (bit-identical JSON numbers), except the wall-clock column.

use crate::common;

use std::path::Path;
use std::time::{Duration, Instant};

const CONFIG: &str = "[design]\npositions = 8\n[run]\nduration_s = 1e-3\n[ga]\npopulation = 16\ngenerations = 40\nstall_generations = 0\nseed = 5\npaper_settings = true\n";

/// The checkpoint without its wall-clock times (and so without the checksum over them).
fn without_elapsed(mut v: serde_json::Value) -> serde_json::Value {
    v.as_object_mut().unwrap().remove("elapsed_s");
    v.as_object_mut().unwrap().remove("checksum");
    for h in v["history"].as_array_mut().unwrap() {
        h.as_object_mut().unwrap().remove("elapsed_s");
    }
    v
}

#[test]
fn interrupted_and_resumed_run_equals_uninterrupted_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    common::write(d, "c.toml", CONFIG);
    let full = common::run_in(
        d,
        &[
            "optimize",
            "c.toml",
            "--out",
            "full",
            "--quiet",
            "--threads",
            "2",
        ],
    );
    assert!(
        full.status.success(),
        "{}",
        String::from_utf8_lossy(&full.stderr)
    );

    let child = common::woodpile()
        .current_dir(d)
        .args([
            "optimize",
            "c.toml",
            "--out",
            "part",
            "--quiet",
            "--threads",
            "1",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let checkpoint = d.join("part/checkpoint.json");
    let started = Instant::now();
    while !checkpoint.exists() {
        assert!(started.elapsed() < Duration::from_secs(60), "no checkpoint");
        std::thread::sleep(Duration::from_millis(2));
    }
    let killed = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(130),
        "an interrupted optimize exits 130: {stderr}"
    );
    let part = common::json(&checkpoint);
    let stopped_at = part["generation"].as_u64().unwrap();
    assert!(stopped_at < 40, "the run ended before the signal");
    assert!(stderr.contains("--resume"), "{stderr}");
    assert_eq!(
        common::json(&d.join("part/summary.json"))["status"],
        "interrupted"
    );

    let resumed = common::run_in(
        d,
        &[
            "optimize",
            "c.toml",
            "--out",
            "part",
            "--quiet",
            "--resume",
            "--threads",
            "2",
        ],
    );
    assert!(
        resumed.status.success(),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    let a = without_elapsed(common::json(&d.join("full/checkpoint.json")));
    let b = without_elapsed(common::json(&checkpoint));
    assert_eq!(a, b, "resumed from generation {stopped_at}");
    let read = |p: &Path| std::fs::read_to_string(p).unwrap();
    assert_eq!(
        read(&d.join("full/population.csv")),
        read(&d.join("part/population.csv"))
    );
    assert_eq!(
        read(&d.join("full/best.toml")),
        read(&d.join("part/best.toml"))
    );
}
