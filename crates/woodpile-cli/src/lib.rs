//! # woodpile-cli
//!
//! The library behind the `woodpile` command line: scenario files, built-in scenarios, run
//! outputs and the subcommands. The physics lives in the [`woodpile`] crate.
//!
//! - [`scenario`]: the TOML scenario format ([`scenario::Scenario`]), its defaults, the built-in
//!   scenarios and [`scenario::resolve`] into a [`woodpile::Chain`], [`woodpile::Excitation`] and
//!   [`woodpile::RunSettings`].
//! - [`table`]: blast force tables from CSV.
//! - [`output`]: `summary.json`, `run.json`, CSV and `.npy` files, written atomically.
//! - [`commands`]: one module per subcommand.
//! - [`CliError`]: every failure, with [`CliError::exit_code`] (2 = bad input, 1 = failed run).

pub mod commands;
pub mod error;
pub mod optimize_cmd;
pub mod output;
pub mod plot_cmd;
pub mod report_cmd;
pub mod scenario;
pub mod table;

pub use error::CliError;
