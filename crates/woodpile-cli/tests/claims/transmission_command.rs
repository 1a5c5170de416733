//! Claim: `woodpile transmission` writes a complete directory (spectrum as CSV and `.npy` of the
//! same length, the figure, `transmission.json` with the predicted gaps and each predicted edge
//! against the nearest measured one) for a homogeneous preloaded chain, and its first measured gap
//! edge lies within 5 % of the Bloch prediction (ten 40 mm rods with the wall given the rods' β, a
//! 20 ms record: fewer cells and coarser bins than the core's 2 % claim, so a wider bound); a chain
//! without a preload is refused with exit 2 naming `preload.force_n`; a chain without damping is
//! measured with stated added damping, its edges against the finite chain's linear prediction.

use crate::common;

const SCENARIO: &str = "[chain]\nrods_mm = [40, 40, 40, 40, 40, 40, 40, 40, 40, 40]\ncontact_beta = [{ contact = 10, beta = BETA }]\n[preload]\nforce_n = 10.0\n[damping]\non_site_time_s = 0.005\n[run]\ntime_step_s = 5e-7\n";

#[test]
fn writes_the_spectrum_and_compares_the_edges() {
    let dir = tempfile::tempdir().unwrap();
    // β between two crossed 40 mm fused-quartz rods, from a first run's run.json.
    common::write(
        dir.path(),
        "probe.toml",
        "[chain]\nrods_mm = [40, 40]\n[run]\nduration_s = 1e-5\n",
    );
    let o = common::run_in(
        dir.path(),
        &["simulate", "probe.toml", "--out", "probe", "-q"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let beta = common::json(&dir.path().join("probe/run.json"))["contact_betas_n_per_m1_5"]
        ["inner"][0]
        .as_f64()
        .unwrap();
    common::write(
        dir.path(),
        "tx.toml",
        &SCENARIO.replace("BETA", &format!("{beta:e}")),
    );
    let args = [
        "transmission",
        "tx.toml",
        "--out",
        "tx",
        "--end-hz",
        "20000",
        "--resolution-hz",
        "50",
        "-q",
    ];
    let o = common::run_in(dir.path(), &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let d = dir.path().join("tx");
    for f in [
        "transmission.csv",
        "frequency_hz.npy",
        "transmission_db.npy",
        "transmission.png",
        "transmission.svg",
    ] {
        assert!(d.join(f).is_file(), "{f}");
    }
    let rows = std::fs::read_to_string(d.join("transmission.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    let j = common::json(&d.join("transmission.json"));
    assert_eq!(j["preload_n"].as_f64(), Some(10.0));
    let gaps = j["predicted_gaps"]
        .as_array()
        .expect("a homogeneous chain has a prediction");
    assert!(!gaps.is_empty());
    let edge = &j["edges"][0];
    let err = edge["relative_error"]
        .as_f64()
        .expect("a measured stop band");
    assert!(err.abs() < 0.05, "first edge off by {err}: {edge}");
    // 100 Hz to 20 kHz in 50 Hz bins.
    assert!((398..=400).contains(&rows), "{rows} rows");
    // Again into the same directory only with --overwrite (it was refused even with it, as a
    // directory holding no run.json).
    let o = common::run_in(dir.path(), &args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("--overwrite"), "{err}");
    let again: Vec<&str> = args.iter().copied().chain(["--overwrite"]).collect();
    let o = common::run_in(dir.path(), &again);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn a_chain_without_preload_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "free.toml", "[chain]\nrods_mm = [40, 40]\n");
    let o = common::run_in(dir.path(), &["transmission", "free.toml", "--out", "tx"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("preload.force_n"), "{err}");
    assert!(!dir.path().join("tx").exists(), "nothing written");
}

/// A threshold at or above 0 dB would count pass bands as gaps: refused naming the flag (it was
/// silently accepted).
#[test]
fn a_threshold_that_is_no_attenuation_is_refused() {
    for level in ["10", "0"] {
        let dir = tempfile::tempdir().unwrap();
        let out = common::run_in(dir.path(), &["transmission", "--threshold-db", level]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{level}: {stderr}");
        assert!(stderr.contains("--threshold-db"), "{level}: {stderr}");
        assert!(common::leftovers(dir.path()).is_empty());
    }
}

/// A chain without damping is measured with on-site damping τ = 20 ms added (stated on the
/// terminal and in `transmission.json` as `added_damping_time_s`), and its edge table compares
/// like with like: the first measured edge of ten lossless 40 mm rods (on the default sensor,
/// 10 Hz bins) lies within 1 % of the finite chain's linear prediction cut at the same level on
/// the same bins (measured +0.39 %; ten cells make a shallow gap, so the bound is the 1 % target,
/// not the 0.3 % of 40 cells). Giving `--damping-time-s` for a chain that has its own damping is
/// refused naming the flag.
#[test]
fn a_lossless_chain_gets_stated_damping_and_a_like_with_like_edge_table() {
    let dir = tempfile::tempdir().unwrap();
    common::write(
        dir.path(),
        "lossless.toml",
        "[chain]\nrods_mm = [40, 40, 40, 40, 40, 40, 40, 40, 40, 40]\n[preload]\nforce_n = 10.0\n[run]\ntime_step_s = 5e-7\n",
    );
    let o = common::run_in(
        dir.path(),
        &["transmission", "lossless.toml", "--out", "tx"],
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("on-site τ = 0.02 s added"), "{stdout}");
    let j = common::json(&dir.path().join("tx/transmission.json"));
    assert_eq!(j["added_damping_time_s"].as_f64(), Some(0.02), "{j}");
    let first = &j["edge_table"][0];
    let linear = first["linear_hz"].as_f64().expect("a linear edge");
    assert!((9.5e3..10e3).contains(&linear), "{first}");
    let err = first["error_vs_linear"].as_f64().expect("a measured edge");
    assert!(err.abs() < 0.01, "measured against linear: {first}");
    assert!(dir.path().join("tx/linear_transmission_db.npy").is_file());

    common::write(
        dir.path(),
        "damped.toml",
        "[chain]\nrods_mm = [40, 40]\n[preload]\nforce_n = 10.0\n[damping]\non_site_time_s = 0.005\n",
    );
    let o = common::run_in(
        dir.path(),
        &[
            "transmission",
            "damped.toml",
            "--out",
            "tx2",
            "--damping-time-s",
            "0.01",
        ],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("--damping-time-s"), "{err}");
}
