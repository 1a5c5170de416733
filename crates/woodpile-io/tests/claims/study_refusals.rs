//! Claim: the refusals of studies and fits are typed errors in the words of the files, naming
//! no flag (each front end words its own): a lattice scenario where a chain is read is
//! `ChainsOnly` about the key `lattice`; a study's directory holding a `summary.json` (a user's
//! or an earlier study's) is `StudyExists`, an output problem that advises removing nothing; a
//! study or a fit beyond its size is the `Study` limit naming the number as the caller spells it;
//! fewer than 8 base samples are refused saying why. No tolerance: these are strings and kinds.

use woodpile_io::error::{ErrorKind, Limit};
use woodpile_io::scenario::Scenario;
use woodpile_io::{atomic, Error};

fn neutral(e: &Error) {
    let text = e.to_string();
    assert!(!text.contains("--"), "names a flag: {text}");
}

#[test]
fn a_lattice_where_a_chain_is_read_names_the_lattice_table() {
    let text = "[lattice]\nlayers = [{ rods = 3, pitch_mm = 20.0, length_mm = 80.0 }]\n";
    let e = Scenario::parse(text).unwrap_err();
    neutral(&e);
    assert!(matches!(e, Error::ChainsOnly { .. }), "{e:?}");
    assert_eq!(e.kind(), ErrorKind::Scenario);
    assert_eq!(e.field(), Some("lattice"));
    assert!(e.to_string().contains("[lattice]"), "{e}");
    // A chain scenario with a typo is still the parser's error, with its line.
    let e = Scenario::parse("[chain]\nrodz_mm = [20]\n").unwrap_err();
    assert!(matches!(e, Error::Parse { .. }), "{e:?}");
}

#[test]
fn a_studys_directory_holding_a_summary_is_refused_without_advice_to_delete() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("summary.json"), "{\"mine\": 1}").unwrap();
    let e = atomic::Staging::prepare_study(dir.path(), "summary.json").unwrap_err();
    neutral(&e);
    assert!(matches!(e, Error::StudyExists { .. }), "{e:?}");
    assert_eq!(e.kind(), ErrorKind::Io);
    assert!(!e.to_string().contains("remove"), "{e}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("summary.json")).unwrap(),
        "{\"mine\": 1}"
    );
}

#[test]
fn sizes_beyond_the_study_limit_name_the_callers_field() {
    let e = woodpile_io::limits::check_fit(1_000_000_000, 200, false).unwrap_err();
    neutral(&e);
    assert!(
        matches!(
            e,
            Error::OverLimit {
                limit: Limit::Study,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(woodpile_io::limits::check_fit(8, 200, false).is_ok());
    assert!(woodpile_io::limits::check_fit(1_000_000_000, 200, true).is_ok());
    let s = Scenario::parse("[chain]\nrods_mm = [40, 30, 20]\n").unwrap();
    let e = woodpile_io::uncertainty::check_size(&s, 1_000_000_000, "samples", false).unwrap_err();
    assert_eq!(e.field(), Some("samples"));
    assert!(
        matches!(
            e,
            Error::OverLimit {
                limit: Limit::Study,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(woodpile_io::uncertainty::check_size(&s, 64, "samples", false).is_ok());
}

#[test]
fn fewer_than_eight_base_samples_are_refused_saying_why() {
    for n in [0, 1, 2, 4] {
        let reason = woodpile_io::sensitivity::base_samples_refusal(n).expect("refused");
        assert!(reason.contains("at least 8"), "{n}: {reason}");
        assert!(reason.contains("bootstrap"), "{n}: {reason}");
    }
    assert!(woodpile_io::sensitivity::base_samples_refusal(8).is_none());
    assert!(woodpile_io::sensitivity::base_samples_refusal(12).is_some());
}
