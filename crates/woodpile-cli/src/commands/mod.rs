//! One module per subcommand: its clap arguments and its `run` function.
//!
//! To add a subcommand: a module here with `Args` (`#[derive(clap::Args)]`) and
//! `pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError>`, then one variant of `Command`
//! and one match arm in `main.rs`.

pub mod cells;
pub mod optimize;
pub mod plot;
pub mod report;
pub mod scenarios;
pub mod simulate;
pub mod transmission;

/// Options shared by every subcommand.
#[derive(Debug, Clone, Copy, Default)]
pub struct Context {
    /// Print nothing but errors.
    pub quiet: bool,
}
