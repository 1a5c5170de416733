//! # woodpile-cli
//!
//! The `woodpile` command line: argument parsing, progress, Ctrl-C, terminal text, and the
//! report. File formats, scenarios and their checks live in [`woodpile_io`], figures in
//! [`woodpile_plot`], the physics in [`woodpile`].
//!
//! [`commands`] holds one module per subcommand, in the order a user works:
//! - [`commands::scenarios`]: `woodpile scenarios` lists the built-in scenarios, `woodpile
//!   scenario NAME` prints one as a complete TOML file to start from;
//! - [`commands::cells`]: the unit-cell catalogue (paper Table 1), or a rod's cell from beam
//!   theory;
//! - [`commands::simulate`]: one run of a scenario into its run directory;
//! - [`commands::transmission`]: a preloaded chain's transmission spectrum;
//! - [`commands::optimize`]: the breeder GA, checkpointed and resumable;
//! - [`commands::fit`]: calibration of a scenario's parameters to measured signals;
//! - [`commands::plot`]: the figures of a run or optimisation directory;
//! - [`commands::report`]: everything the paper's figures need, as report.md and report.html,
//!   one module per section.
//!
//! Around them: [`progress`] (a bar with an ETA on a terminal, a line per stage otherwise),
//! [`interrupt`] (one Ctrl-C handler) and [`CliError`] (every failure: woodpile-io's error;
//! [`exit`] gives its exit code, 2 = bad input, 1 = failed run, 130 = interrupted, and its
//! message in this command line's flags).

pub mod commands;
pub mod exit;
pub mod interrupt;
pub mod out;
pub mod progress;

pub use woodpile_io::Error as CliError;
