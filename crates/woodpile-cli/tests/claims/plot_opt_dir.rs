//! Claim: `woodpile plot OPT_DIR` recognises a `woodpile optimize` output and draws the GA's
//! convergence and the best chain (rods to scale, paper Fig. 5 d, e right) into OPT_DIR/plots;
//! an unfinished run (no best.toml yet) still gets its convergence; a directory that is neither
//! a run nor an optimisation, or an optimisation without history.csv, or a corrupt history, is
//! refused with exit code 2 and a message that says what was expected. `--format svg` writes
//! the same figures as SVG only.
//! No tolerance: file existence and exit codes are exact.

use crate::common;

const CONFIG: &str = "[design]\npositions = 4\ncatalogue_mm = [20, 50, 80]\n[run]\nduration_s = 2e-4\n[ga]\npopulation = 6\ngenerations = 3\nseed = 3\n";

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn optimisation_output_gets_convergence_and_best_chain() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    common::write(d, "c.toml", CONFIG);
    let o = common::run_in(d, &["optimize", "c.toml", "--out", "opt", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = common::run_in(d, &["plot", "opt"]);
    assert!(o.status.success(), "{}", stderr(&o));
    for f in [
        "convergence.png",
        "convergence.svg",
        "best_chain.png",
        "best_chain.svg",
    ] {
        let p = d.join("opt/plots").join(f);
        assert!(p.is_file(), "{} missing", p.display());
        assert!(std::fs::metadata(&p).unwrap().len() > 1000);
    }
    // The output options apply to an optimisation's figures too: SVG only.
    let o = common::run_in(d, &["plot", "opt", "--out", "svg", "--format", "svg", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(d.join("svg/convergence.svg").is_file() && d.join("svg/best_chain.svg").is_file());
    assert!(!d.join("svg/convergence.png").exists() && !d.join("svg/best_chain.png").exists());

    // An unfinished run: history and checkpoint only.
    std::fs::create_dir(d.join("partial")).unwrap();
    for f in ["history.csv", "checkpoint.json"] {
        std::fs::copy(d.join("opt").join(f), d.join("partial").join(f)).unwrap();
    }
    let o = common::run_in(d, &["plot", "partial"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(d.join("partial/plots/convergence.png").is_file());
    assert!(!d.join("partial/plots/best_chain.png").exists());
    assert!(stderr(&o).contains("best.toml"));
}

#[test]
fn bad_directories_are_refused_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Neither kind.
    std::fs::create_dir(d.join("empty")).unwrap();
    let o = common::run_in(d, &["plot", "empty"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("woodpile optimize"), "{}", stderr(&o));
    // An optimisation marker without history.csv.
    std::fs::create_dir(d.join("nohist")).unwrap();
    common::write(&d.join("nohist"), "summary.json", "{}");
    let o = common::run_in(d, &["plot", "nohist"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("history.csv"), "{}", stderr(&o));
    // A corrupt history.
    std::fs::create_dir(d.join("bad")).unwrap();
    common::write(&d.join("bad"), "summary.json", "{}");
    common::write(
        &d.join("bad"),
        "history.csv",
        "generation,best,mean\n0,abc,1\n",
    );
    let o = common::run_in(d, &["plot", "bad"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("line 2"), "{}", stderr(&o));
    // Not a directory at all.
    let o = common::run_in(d, &["plot", "missing"]);
    assert_eq!(o.status.code(), Some(2));
}
