//! Claim: inputs whose results would mean nothing are refused (exit 2) or warned, naming the
//! key, flag or file they are about, and no number is printed from them:
//! - a drive of amplitude 0 (every dynamic force would be rounding noise: a ratio of 6.0 was
//!   printed from 0.0000 N dynamic peaks): `excitation.amplitude`;
//! - a 1 GHz drive with the default 0.1 µs step, above the step's Nyquist frequency 5 MHz:
//!   `excitation.frequency_hz` and `run.time_step_s`;
//! - a harmonic drive whose default ramp (three periods, 3 ms at 1 kHz) is longer than the run
//!   (0.1 ms): run, with a warning naming `excitation.ramp_s`;
//! - a blast with decay b = 1e300, whose force falls within one step (Td/(1 + b) ≪ 0.1 µs):
//!   `excitation.decay`;
//! - `cells --rod 1e9` (2e8 diameters: frequencies printed as 0.00) and `--rod 0.001` (a disc):
//!   `--rod`, and not `--modes`, which was not given;
//! - `wall.cap_radius_mm = 1e300`: named, and no 300-digit radius printed (message < 400 chars);
//! - `plot` on a run directory whose `forces_n.npy` holds a NaN names that file, and one whose
//!   `run.json` was deleted is called a simulate run missing its run.json, not an optimize output;
//! - a chain of 2,000 elements prints a `chain` line of at most 300 characters (it printed 60 KB
//!   for 10,000).

use crate::common;

fn refused(args: &[&str], scenario: Option<&str>, expect: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let mut argv: Vec<&str> = args.to_vec();
    if let Some(s) = scenario {
        common::write(dir.path(), "s.toml", s);
        argv.insert(1, "s.toml");
    }
    argv.extend(["--out", "out"]);
    let o = common::run_in(dir.path(), &argv);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    for e in expect {
        assert!(err.contains(e), "{args:?}: expected `{e}` in {err}");
    }
    assert!(!dir.path().join("out").exists());
    err
}

const DRIVE: &str =
    "[chain]\nrods_mm = [20, 20]\n[excitation]\nkind = \"drive\"\nsignal = \"harmonic\"\n";

#[test]
fn drives_that_mean_nothing_are_refused() {
    refused(
        &["simulate"],
        Some(&format!("{DRIVE}amplitude = 0.0\nfrequency_hz = 1e3\n")),
        &["excitation.amplitude", "rest"],
    );
    refused(
        &["simulate"],
        Some(&format!("{DRIVE}amplitude = 1.0\nfrequency_hz = 1e9\n")),
        &["excitation.frequency_hz", "Nyquist", "run.time_step_s"],
    );
}

#[test]
fn a_ramp_longer_than_the_run_is_warned() {
    let dir = tempfile::tempdir().unwrap();
    common::write(
        dir.path(),
        "s.toml",
        &format!("{DRIVE}amplitude = 1.0\nfrequency_hz = 1e3\n[run]\nduration_s = 1e-4\n"),
    );
    let o = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out", "-q"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("warning: excitation.ramp_s"), "{err}");
}

#[test]
fn a_blast_that_decays_within_one_step_is_refused() {
    refused(
        &["simulate"],
        Some("[chain]\nrods_mm = [20, 20]\n[excitation]\nkind = \"blast\"\ndecay = 1e300\n"),
        &["excitation.decay", "run.time_step_s"],
    );
}

#[test]
fn rods_that_are_no_beam_are_refused_naming_the_rod() {
    for rod in ["1e9", "0.001"] {
        let dir = tempfile::tempdir().unwrap();
        let o = common::run_in(dir.path(), &["cells", "--rod", rod]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{rod}: {err}");
        assert!(err.contains("--rod"), "{rod}: {err}");
        assert!(!err.contains("--modes"), "{rod}: {err}");
        assert!(
            o.stdout.is_empty(),
            "{rod}: printed {}",
            String::from_utf8_lossy(&o.stdout)
        );
    }
}

#[test]
fn an_absurd_cap_radius_is_named_without_300_digits() {
    let err = refused(
        &["simulate"],
        Some("[chain]\nrods_mm = [20, 20]\n[wall]\ncap_radius_mm = 1e300\n"),
        &["wall.cap_radius_mm"],
    );
    assert!(err.len() < 400, "{} characters: {err}", err.len());
}

#[test]
fn plot_names_a_damaged_run_directory() {
    let dir = tempfile::tempdir().unwrap();
    common::write(
        dir.path(),
        "s.toml",
        "[chain]\nrods_mm = [20, 20]\n[run]\nduration_s = 5e-5\n",
    );
    let o = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "run", "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // A NaN in the last 8 bytes of forces_n.npy (the last sample of the wall contact).
    let npy = dir.path().join("run/forces_n.npy");
    let mut bytes = std::fs::read(&npy).unwrap();
    let n = bytes.len();
    bytes[n - 8..].copy_from_slice(&f64::NAN.to_le_bytes());
    std::fs::write(&npy, bytes).unwrap();
    let o = common::run_in(dir.path(), &["plot", "run", "--out", "plots"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("forces_n.npy") && err.contains("NaN"), "{err}");
    std::fs::remove_file(dir.path().join("run/run.json")).unwrap();
    let o = common::run_in(dir.path(), &["plot", "run", "--out", "plots"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("run.json") && err.contains("woodpile simulate"),
        "{err}"
    );
    assert!(!err.contains("optimize output"), "{err}");
}

#[test]
fn a_long_chain_prints_a_short_chain_line() {
    let dir = tempfile::tempdir().unwrap();
    let rods: Vec<&str> = (0..2000).map(|k| ["20", "40", "80"][k % 3]).collect();
    common::write(
        dir.path(),
        "s.toml",
        &format!(
            "[chain]\nrods_mm = [{}]\n[run]\nduration_s = 2e-7\nsample_interval_s = 2e-7\n",
            rods.join(", ")
        ),
    );
    let o = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "run"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let line = out.lines().find(|l| l.starts_with("chain")).unwrap();
    assert!(line.len() <= 300, "{} characters: {line}", line.len());
    assert!(line.contains("2000 elements"), "{line}");
}
