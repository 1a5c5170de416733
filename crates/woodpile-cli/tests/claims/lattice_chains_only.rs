//! Claim: a command that runs chains only, given a valid lattice scenario (the repository's
//! `examples/lattice.toml`), says so — `woodpile COMMAND supports chains only`, naming the
//! `[lattice]` table and the file — and exits 2 without writing, instead of a TOML parser's
//! "unknown field `lattice`" that reads as if the file were wrong. Checked for `transmission`,
//! `sensitivity`, `simulate --samples` and `fit` (whose fit file names the lattice as its model),
//! and for the built-in lattice (`--scenario lattice`), which is not an "unknown scenario".

use crate::common;
use std::path::PathBuf;

fn lattice() -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/lattice.toml");
    std::fs::read_to_string(p).expect("the example lattice")
}

fn refused(command: &str, args: &[&str], extra: &[(&str, &str)]) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "lattice.toml", &lattice());
    for (name, text) in extra {
        common::write(dir.path(), name, text);
    }
    let out = common::run_in(dir.path(), args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{command}: {stderr}");
    for n in [
        format!("woodpile {command} supports chains only"),
        "[lattice]".into(),
        "lattice".into(),
    ] {
        assert!(
            stderr.contains(&n),
            "{command}: expected `{n}` in: {stderr}"
        );
    }
    for wrong in ["unknown field", "unknown scenario"] {
        assert!(!stderr.contains(wrong), "{command}: {stderr}");
    }
    assert!(!dir.path().join("o").exists(), "{command}: output written");
}

#[test]
fn chain_only_commands_name_the_lattice_table() {
    refused(
        "transmission",
        &["transmission", "lattice.toml", "--out", "o"],
        &[],
    );
    refused(
        "sensitivity",
        &["sensitivity", "lattice.toml", "--out", "o"],
        &[],
    );
    refused(
        "simulate --samples",
        &["simulate", "lattice.toml", "--samples", "4", "--out", "o"],
        &[],
    );
    refused(
        "transmission",
        &["transmission", "--scenario", "lattice", "--out", "o"],
        &[],
    );
    let fit = "scenario = \"lattice.toml\"\n[[data]]\nfile = \"m.csv\"\nsignals = { sensor_n = \"contact_2_n\" }\n[fit]\nparameters = [{ key = \"excitation.velocity_m_s\", bounds = [1.5, 2.5] }]\n";
    refused(
        "fit",
        &["fit", "f.toml", "--out", "o"],
        &[("f.toml", fit), ("m.csv", "time_s,sensor_n\n0,0\n1e-6,1\n")],
    );
}
