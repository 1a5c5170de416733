//! The `woodpile` command line. Each subcommand is one variant of [`Command`] and one arm in
//! [`dispatch`]; the work is done in `woodpile_cli::commands`.

use clap::{Parser, Subcommand};
use std::process::ExitCode;
use woodpile_cli::commands::{self, Context};
use woodpile_cli::{exit, out, CliError};

/// Locally resonant woodpile metamaterials under impact and blast (Kim, Yang et al. 2017).
#[derive(Debug, Parser)]
#[command(name = "woodpile", version, about)]
struct Cli {
    /// Print nothing but errors.
    #[arg(long, short, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a scenario file or a built-in scenario and write its outputs.
    Simulate(commands::simulate::Args),
    /// List the built-in scenarios.
    Scenarios(commands::scenarios::ListArgs),
    /// Print a built-in scenario as a complete TOML file to start from.
    Scenario(commands::scenarios::ShowArgs),
    /// Print the unit-cell catalogue (paper Table 1): masses, resonances, negative-mass bands.
    Cells(commands::cells::Args),
    /// Search the element arrangement that minimises an objective (breeder GA, docs/physics.md §11).
    Optimize(commands::optimize::Args),
    /// Measure the transmission spectrum of a preloaded chain and compare its gaps with the
    /// Bloch prediction (docs/physics.md §15).
    Transmission(commands::transmission::Args),
    /// Sobol' indices of the figures of merit over a scenario's `[uncertainty]` (Saltelli
    /// sampling, SALib's estimators; docs/sensitivity.md).
    Sensitivity(commands::sensitivity::Args),
    /// Calibrate a scenario's parameters to measured signals, with uncertainties (docs/fit.md).
    Fit(commands::fit::Args),
    /// Draw the figures of a `simulate` or `optimize` output directory into DIR/plots (PNG, SVG).
    Plot(commands::plot::Args),
    /// Run everything the paper's figures need; write the figures, report.md and report.html.
    Report(commands::report::Args),
}

fn dispatch(command: &Command, ctx: &Context) -> Result<(), CliError> {
    match command {
        Command::Simulate(args) => match args.samples {
            Some(k) => commands::samples::run(args, k, ctx),
            None => commands::simulate::run(args, ctx),
        },
        Command::Scenarios(args) => commands::scenarios::list(args, ctx),
        Command::Scenario(args) => commands::scenarios::show(args, ctx),
        Command::Cells(args) => commands::cells::run(args, ctx),
        Command::Optimize(args) => commands::optimize::run(args, ctx),
        Command::Transmission(args) => commands::transmission::run(args, ctx),
        Command::Fit(args) => commands::fit::run(args, ctx),
        Command::Sensitivity(args) => commands::sensitivity::run(args, ctx),
        Command::Plot(args) => commands::plot::run(args, ctx),
        Command::Report(args) => commands::report::run(args, ctx),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    woodpile_cli::interrupt::install();
    let ctx = Context { quiet: cli.quiet };
    match dispatch(&cli.command, &ctx) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if out::closed_pipe(&e) => ExitCode::from(out::EXIT_CLOSED_PIPE),
        Err(e @ woodpile_cli::CliError::Interrupted { .. }) => {
            out::eprintln(exit::message(&e));
            ExitCode::from(exit::code(&e))
        }
        Err(e) => {
            out::eprintln(format_args!("error: {}", exit::message(&e)));
            ExitCode::from(exit::code(&e))
        }
    }
}
