//! Claim: a command that would not end, or would fill the disk, is refused before it starts,
//! with the estimate and the override named; each refusal returns at once (well under the
//! 10 s allowed here, against days of work refused).
//!
//! - `duration_s = 1e6` at the default 0.1 µs step is 1e13 steps (> 1e9): exit 2, --allow-long.
//! - 0.1 ns sampling for 2 ms is 2e7 samples × 32 columns ≈ 19 GB: exit 2, --allow-large.
//! - `--threads 100000` (more than 4 per core): exit 2 naming --threads, for optimize and report.

use crate::common;
use std::time::{Duration, Instant};

fn refused(args: &[&str], scenario: &str, needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", scenario);
    let started = Instant::now();
    let out = common::run_in(dir.path(), args);
    assert!(
        started.elapsed() < Duration::from_secs(10),
        "refused at once"
    );
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    for n in needles {
        assert!(stderr.contains(n), "expected `{n}` in: {stderr}");
    }
    assert!(!dir.path().join("o").exists());
}

#[test]
fn endless_run_is_refused() {
    refused(
        &["simulate", "s.toml", "--out", "o"],
        "[chain]\nrods_mm = [20, 20]\n[run]\nduration_s = 1e6\nsample_interval_s = 1.0\n",
        &["1.000e13 steps", "--allow-long"],
    );
}

#[test]
fn huge_output_is_refused() {
    refused(
        &["simulate", "s.toml", "--out", "o"],
        "[chain]\nrods_mm = [20, 20, 20, 20, 20]\n[run]\nsample_interval_s = 1e-10\n",
        &["GB", "--allow-large", "run.sample_interval_s"],
    );
}

#[test]
fn absurd_thread_count_is_refused() {
    refused(
        &[
            "optimize",
            "--scenario",
            "paper-impact",
            "--out",
            "o",
            "--threads",
            "100000",
        ],
        "",
        &["--threads", "100000", "--allow-many-threads"],
    );
    refused(
        &["report", "--out", "o", "--threads", "100000"],
        "",
        &["--threads", "100000"],
    );
}

/// `positions = 100000` (100 × 100,000 elements per generation) and `population = 100000000`
/// (2e9) once hung for minutes without a word; both are refused at once against the limit of
/// 1e6 elements per generation, naming both keys, the product and the override.
#[test]
fn endless_generation_is_refused() {
    refused(
        &["optimize", "s.toml", "--out", "o"],
        "[design]\npositions = 100000\n",
        &[
            "ga.population × design.positions",
            "100 × 100000 = 10000000",
            "--allow-large",
        ],
    );
    refused(
        &["optimize", "s.toml", "--out", "o"],
        "[ga]\npopulation = 100000000\n",
        &["100000000 × 20 = 2000000000", "--allow-large"],
    );
}
