//! Claim: woodpile-io's errors speak the language of the files, not of a front end. Each failure
//! below, produced through the public API as a front end would, (1) names no command-line flag
//! (no `--` in its message: the command line and Python word their own options), (2) has the
//! kind a front end maps to an exit code or exception class, and (3) gives the field as the user
//! wrote it, the value, and a reason that says what is valid. No tolerance: these are strings.

use std::path::Path;
use woodpile_io::error::{ErrorKind, Limit};
use woodpile_io::limits::{check_threads, RunSize, MAX_STEPS};
use woodpile_io::optimize::{prepare_output, OptimizeConfig, CHECKPOINT_FILE};
use woodpile_io::scenario::{resolve, Scenario};
use woodpile_io::{atomic, Error};

/// The checks every error below must pass; returns it for the specific ones.
fn neutral(e: Error, kind: ErrorKind) -> Error {
    let text = e.to_string();
    assert!(!text.contains("--"), "names a flag: {text}");
    assert!(!e.reason().contains("--"), "names a flag: {}", e.reason());
    assert_eq!(e.kind(), kind, "{text}");
    e
}

fn scenario_error(text: &str) -> Error {
    let s = Scenario::parse(text).expect("parses");
    resolve(&s, Path::new(".")).expect_err("invalid")
}

#[test]
fn an_invalid_value_names_its_key_value_and_valid_range() {
    let e = neutral(
        scenario_error("[chain]\nrods_mm = [20, 30, 40, 45]\n"),
        ErrorKind::Scenario,
    );
    assert_eq!(e.field(), Some("chain.rods_mm[3]"));
    assert_eq!(e.value().as_deref(), Some("45"));
    assert!(e.reason().contains("20, 30, 40"), "{}", e.reason());
    // A name not in its catalogue: the key, the name, and the valid names.
    let e = neutral(
        scenario_error("[chain]\nrods_mm = [20]\n[wall]\nmaterial = \"unobtainium\"\n"),
        ErrorKind::Scenario,
    );
    assert_eq!(e.field(), Some("wall.material"));
    assert_eq!(e.value().as_deref(), Some("unobtainium"));
    assert!(e.reason().contains("stainless-steel"), "{}", e.reason());
}

#[test]
fn an_earlier_run_is_an_overwrite_refusal_that_names_no_flag() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join(atomic::RUN_MARKER), "{}").unwrap();
    let e = neutral(
        atomic::Staging::prepare(dir.path(), false).unwrap_err(),
        ErrorKind::Overwrite,
    );
    assert!(matches!(e, Error::OutputExists { .. }), "{e:?}");
    assert_eq!(e.value(), Some(dir.path().display().to_string()));
    assert!(atomic::Staging::prepare(dir.path(), true).is_ok());
}

#[test]
fn a_foreign_directory_is_refused_as_an_output_problem() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("thesis.tex"), "x").unwrap();
    let e = neutral(
        atomic::Staging::prepare(dir.path(), true).unwrap_err(),
        ErrorKind::Io,
    );
    assert!(e.to_string().contains(atomic::RUN_MARKER), "{e}");
}

#[test]
fn limits_say_which_override_would_lift_them() {
    let threads = neutral(
        check_threads("threads", usize::MAX / 2, false).unwrap_err(),
        ErrorKind::Limit,
    );
    assert!(matches!(
        threads,
        Error::OverLimit {
            limit: Limit::Threads,
            ..
        }
    ));
    assert_eq!(threads.field(), Some("threads"));
    let size = RunSize {
        steps: Some(10 * MAX_STEPS),
        samples: 1,
        output_bytes: 1e15,
    };
    let steps = neutral(size.check(false, true, true).unwrap_err(), ErrorKind::Limit);
    assert!(matches!(
        steps,
        Error::OverLimit {
            limit: Limit::Steps,
            ..
        }
    ));
    let bytes = neutral(size.check(true, false, true).unwrap_err(), ErrorKind::Limit);
    assert!(matches!(
        bytes,
        Error::OverLimit {
            limit: Limit::OutputSize,
            ..
        }
    ));
    assert!(size.check(true, true, true).is_ok());
}

#[test]
fn an_optimisation_output_says_what_it_holds() {
    let config = OptimizeConfig::builtin("paper-impact").unwrap();
    let dir = tempfile::tempdir().unwrap();
    let e = neutral(
        prepare_output(dir.path(), true, &config).unwrap_err(),
        ErrorKind::Scenario,
    );
    assert!(matches!(e, Error::NothingToResume { .. }), "{e:?}");
    std::fs::write(dir.path().join(CHECKPOINT_FILE), "{}").unwrap();
    let e = neutral(
        prepare_output(dir.path(), false, &config).unwrap_err(),
        ErrorKind::Overwrite,
    );
    assert!(matches!(e, Error::CheckpointExists { .. }), "{e:?}");
    let e = neutral(
        prepare_output(dir.path(), true, &config).unwrap_err(),
        ErrorKind::Scenario,
    );
    assert!(e.to_string().contains("corrupt"), "{e}");
}

#[test]
fn an_unfinished_study_says_to_resume_it_without_naming_a_flag() {
    let dir = tempfile::tempdir().unwrap();
    let e = neutral(
        woodpile_io::pareto::read_pareto_output(dir.path()).unwrap_err(),
        ErrorKind::Io,
    );
    assert!(e.to_string().contains("resume the study"), "{e}");
}
