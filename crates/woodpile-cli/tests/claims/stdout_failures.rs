//! Claim: a command whose standard output cannot be written does not panic. A reader that closed
//! the pipe (`woodpile scenario … | head -c 10`) ends the command quietly with exit code 141 (as
//! SIGPIPE would), and a full disk (`> /dev/full`) is refused with exit code 2 and a message that
//! names standard output and the reason. Checked on `scenario`, `scenarios` and `cells`, whose
//! whole work is printing.

use crate::common;
use std::process::Stdio;

const COMMANDS: [&[&str]; 3] = [
    &["scenario", "paper-impact-80mm"],
    &["scenarios"],
    &["cells"],
];

#[test]
fn a_closed_pipe_ends_quietly_with_141() {
    for args in COMMANDS {
        // The read end is closed before the command starts, so every write finds it gone.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = common::woodpile()
            .args(args)
            .stdout(Stdio::from(writer))
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(141), "{args:?}: {stderr}");
        assert!(stderr.is_empty(), "{args:?}: {stderr}");
    }
}

#[test]
fn a_full_disk_is_an_error_that_names_standard_output() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return; // not a Linux machine: nothing to check
    };
    for args in COMMANDS {
        let out = common::woodpile()
            .args(args)
            .stdout(Stdio::from(full.try_clone().unwrap()))
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.starts_with("error: ") && stderr.contains("standard output"),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}
