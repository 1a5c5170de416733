//! Claim: a study or a fit whose size alone would fill memory or never end is refused before
//! anything is drawn or run, naming the number as the user wrote it, the estimate and the
//! override (`--allow-large`): `simulate --samples 1000000000`, `sensitivity --base-samples
//! 4194304` and a fit of `starts = 1000000000`. Each returns well within 10 s (against hours of
//! growing memory refused): the refusal comes before any sample's scenario is built.

use crate::common;
use std::time::{Duration, Instant};

const SCATTERED: &str = "[chain]\nrods_mm = [40, 30, 20]\n[run]\nduration_s = 2e-4\n[uncertainty]\nimpact_velocity_m_s = { uniform = [1.8, 2.2] }\n";

fn refused(files: &[(&str, &str)], args: &[&str], needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        common::write(dir.path(), name, text);
    }
    let started = Instant::now();
    let out = common::run_in(dir.path(), args);
    assert!(
        started.elapsed() < Duration::from_secs(10),
        "refused at once"
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    for n in needles {
        assert!(stderr.contains(n), "expected `{n}` in: {stderr}");
    }
    assert!(!dir.path().join("o").exists(), "{args:?}: output written");
}

#[test]
fn a_billion_samples_are_refused_naming_the_flag_and_its_override() {
    refused(
        &[("s.toml", SCATTERED)],
        &[
            "simulate",
            "s.toml",
            "--samples",
            "1000000000",
            "--out",
            "o",
        ],
        &[
            "--samples = 1000000000",
            "3000000000 elements",
            "--allow-large",
        ],
    );
}

#[test]
fn a_sensitivity_design_of_millions_of_runs_is_refused_naming_base_samples() {
    refused(
        &[("s.toml", SCATTERED)],
        &[
            "sensitivity",
            "s.toml",
            "--base-samples",
            "4194304",
            "--out",
            "o",
        ],
        &["--base-samples = 4194304", "--allow-large"],
    );
}

#[test]
fn a_fit_of_a_billion_starts_is_refused_naming_the_keys_and_the_override() {
    let model = "[chain]\nrods_mm = [80, 40]\n[run]\nduration_s = 1e-4\n";
    let csv = "time_s,sensor_n\n0,0\n1e-6,0.5\n2e-6,1.0\n3e-6,1.5\n";
    let fit = "scenario = \"model.toml\"\n[[data]]\nfile = \"m.csv\"\nsignals = { sensor_n = \"contact_2_n\" }\n[fit]\nparameters = [{ key = \"excitation.velocity_m_s\", bounds = [1.5, 2.5] }]\nstarts = 1000000000\n";
    refused(
        &[("model.toml", model), ("m.csv", csv), ("f.toml", fit)],
        &["fit", "f.toml", "--out", "o"],
        &[
            "fit.starts × fit.max_evaluations",
            "1000000000 × 200",
            "--allow-large",
        ],
    );
}
