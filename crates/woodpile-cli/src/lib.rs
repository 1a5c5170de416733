//! # woodpile-cli
//!
//! The `woodpile` command line: argument parsing, progress, Ctrl-C, terminal text and the
//! rendering of the report. File formats, scenarios and checks live in [`woodpile_io`]; the
//! physics lives in [`woodpile`].
//!
//! - [`commands`]: one module per subcommand.
//! - [`progress`]: a bar with an ETA on a terminal, a line per stage otherwise.
//! - [`CliError`]: every failure (woodpile-io's error); [`exit`] gives its exit code (2 = bad
//!   input, 1 = failed run, 130 = interrupted) and its message in this command line's flags.

pub mod commands;
pub mod exit;
pub mod interrupt;
pub mod optimize_cmd;
pub mod plot_cmd;
pub mod progress;
pub mod report;

pub use woodpile_io::Error as CliError;
