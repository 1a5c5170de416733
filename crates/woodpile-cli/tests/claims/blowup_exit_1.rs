//! Claim: a run that blows up numerically (here RK4 with a step 200× too large on rigid rods, so
//! the striker overruns rod 1) stops with exit code 1 and a message naming the time, the contact
//! and the fix, and leaves no output directory behind. Bad input is exit 2; a failed run is
//! exit 1. (With resonant rods such a step is refused before the run, as bad input, because it
//! is beyond RK4's stability limit on a resonator: exit 2 naming run.time_step_s.)

use crate::common;

#[test]
fn numerical_blowup_exits_1_without_output() {
    let dir = tempfile::tempdir().unwrap();
    common::write(
        dir.path(),
        "s.toml",
        "[chain]\nrods_mm = [20, 20]\nmodel = \"rigid\"\n[run]\ntime_step_s = 2e-5\n",
    );
    common::write(
        dir.path(),
        "r.toml",
        "[chain]\nrods_mm = [20, 20]\n[run]\ntime_step_s = 1e-5\n",
    );
    let refused = common::run_in(dir.path(), &["simulate", "r.toml", "--out", "out"]);
    let err = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{err}");
    assert!(
        err.contains("run.time_step_s") && err.contains("resonator"),
        "{err}"
    );
    let out = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    for e in ["t = ", "contact", "reduce run.time_step_s"] {
        assert!(stderr.contains(e), "expected `{e}` in {stderr}");
    }
    assert!(!dir.path().join("out").exists());
    assert!(common::leftovers(dir.path()).is_empty());
}

/// An impossible load is told apart from a step that is too large, from the physics: a 1e300 N
/// and a 1e9 N blast would compress contact 1 statically by (F/β)^{2/3} = 5e193 m and 0.55 m, a
/// drop from 1e300 m stores enough energy to compress the striker's contact by 2e115 m, all
/// beyond 10 % of a 2.5 mm radius: exit 1, "the load exceeds" naming the scenario key, "a smaller
/// time step will not help", and no number that is not finite ("inf"/"NaN" never printed).
#[test]
fn an_impossible_load_is_not_blamed_on_the_step() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("blast", "peak_force_n = 1e300", "excitation.peak_force_n"),
        ("blast", "peak_force_n = 1e9", "excitation.peak_force_n"),
        ("impact", "drop_height_m = 1e300", "drop_height_m"),
    ];
    for (kind, line, key) in cases {
        common::write(
            dir.path(),
            "s.toml",
            &format!("[chain]\nrods_mm = [20, 20, 20]\n[excitation]\nkind = \"{kind}\"\n{line}\n[run]\nduration_s = 1e-4\n"),
        );
        let out = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{line}: {stderr}");
        for e in ["the load exceeds", key, "a smaller time step will not help"] {
            assert!(stderr.contains(e), "{line}: expected `{e}` in {stderr}");
        }
        assert!(
            !stderr.contains("reduce run.time_step_s"),
            "{line}: {stderr}"
        );
        for bad in ["inf", "NaN"] {
            assert!(!stderr.contains(bad), "{line}: `{bad}` in {stderr}");
        }
        assert!(!dir.path().join("out").exists());
    }
}
