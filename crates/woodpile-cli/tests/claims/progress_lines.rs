//! Claim: off a terminal (stderr a pipe, as in a batch job's log) `woodpile optimize` and
//! `woodpile report` show their progress as plain lines `LABEL [DONE/TOTAL] T s[, ETA E s]: STAGE`
//! on stderr, with DONE never decreasing and never above TOTAL, no terminal control characters,
//! and nothing of it on stdout. The ETA is the mean time per finished step times the steps left.
//! (`report`'s lines are checked in report_quick, on its cached rerun.)
//!
//! Tolerance: the ETA check allows for the one-decimal rounding of the printed elapsed time
//! (±0.05 s × steps left / steps done) and the ETA's rounding to whole seconds (±0.5 s).

use crate::common;
use std::time::Duration;
use woodpile_cli::progress::line;

/// Checks every line of `stderr` that starts with `label [`: the format, the counts and the ETA.
pub fn check_lines(stderr: &str, label: &str, total: u64) {
    assert!(
        !stderr.contains('\u{1b}'),
        "control characters in {stderr:?}"
    );
    let prefix = format!("{label} [");
    let mut last = 0;
    let mut n = 0;
    for l in stderr.lines().filter(|l| l.starts_with(&prefix)) {
        n += 1;
        let rest = &l[prefix.len()..];
        let (counts, rest) = rest.split_once("] ").expect("`] ` after the counts");
        let (done, len) = counts.split_once('/').expect("DONE/TOTAL");
        let (done, len): (u64, u64) = (done.parse().unwrap(), len.parse().unwrap());
        assert_eq!(len, total, "{l}");
        assert!(done >= last && done <= total, "{l} after {last}");
        last = done;
        let (times, stage) = rest.split_once(": ").expect("`: ` before the stage");
        assert!(!stage.is_empty(), "{l}");
        let elapsed: f64 = times
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .expect("elapsed seconds");
        if let Some(eta) = times.split(", ETA ").nth(1) {
            let eta: f64 = eta.trim_end_matches(" s").parse().expect("ETA seconds");
            let left = (total - done) as f64 / done as f64;
            assert!(
                (eta - elapsed * left).abs() <= 0.05 * left + 0.5,
                "{l}: ETA {eta} s, expected {} s",
                elapsed * left
            );
        }
    }
    assert!(n > 0, "no `{label} [` progress line in:\n{stderr}");
}

#[test]
fn eta_is_the_mean_time_per_step_times_the_steps_left() {
    let l = line(
        "report",
        3,
        15,
        Duration::from_secs(12),
        "blast cases",
        None,
    );
    assert_eq!(l, "report [3/15] 12.0 s, ETA 48 s: blast cases");
    // No estimate before the first step is done, nor after the last.
    let l = line(
        "report",
        0,
        15,
        Duration::from_secs(2),
        "start",
        Some("detail"),
    );
    assert_eq!(l, "report [0/15] 2.0 s: start (detail)");
    let l = line("report", 15, 15, Duration::from_secs(60), "", Some("done"));
    assert_eq!(l, "report [15/15] 60.0 s: done");
}

#[test]
fn optimize_prints_progress_lines_off_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    common::write(
        d,
        "c.toml",
        "[design]\npositions = 3\ncatalogue_mm = [20, 80]\n[run]\nduration_s = 2e-4\ntime_step_s = 2e-7\n[ga]\npopulation = 4\ngenerations = 3\nseed = 1\n",
    );
    let o = common::run_in(d, &["optimize", "c.toml", "--out", "opt"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stderr = String::from_utf8_lossy(&o.stderr);
    check_lines(&stderr, "optimize", 3);
    assert!(
        stderr.contains("generation 0: best "),
        "the initial population is shown: {stderr}"
    );
    assert!(!String::from_utf8_lossy(&o.stdout).contains("optimize ["));
}
