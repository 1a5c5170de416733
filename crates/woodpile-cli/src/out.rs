//! Standard output and error that never panic (`print!` and `eprintln!` do when they cannot be
//! written): a write that
//! fails is [`CliError::Output`] on `standard output`, so a full disk ends with exit code 2 and the
//! reason, and a reader that closed the pipe (`| head`) ends the command quietly with exit code
//! 141, as a process stopped by SIGPIPE does ([`closed_pipe`]).

use crate::CliError;
use std::fmt::Display;
use std::io::{self, Write};
use std::path::PathBuf;

/// Writes `text` to standard output and flushes it.
pub fn print(text: impl Display) -> Result<(), CliError> {
    let mut out = io::stdout().lock();
    write!(out, "{text}")
        .and_then(|()| out.flush())
        .map_err(|source| CliError::Output {
            path: PathBuf::from("standard output"),
            source,
        })
}

/// Writes `text` and a newline to standard output.
pub fn println(text: impl Display) -> Result<(), CliError> {
    print(format_args!("{text}\n"))
}

/// Whether `e` is a write to standard output whose reader has gone (a closed pipe): the command
/// then ends without a message.
pub fn closed_pipe(e: &CliError) -> bool {
    matches!(e, CliError::Output { path, source }
        if source.kind() == io::ErrorKind::BrokenPipe && path.as_os_str() == "standard output")
}

/// Writes `text` and a newline to standard error (warnings, notes, the final error). A failure
/// there is ignored: there is nowhere left to report it, and it must not panic.
pub fn eprintln(text: impl Display) {
    let _ = writeln!(io::stderr().lock(), "{text}");
}

/// The exit code of a command whose output pipe was closed: 128 + SIGPIPE.
pub const EXIT_CLOSED_PIPE: u8 = 141;
