//! One module per subcommand: its clap arguments and its `run` function.
//!
//! To add a subcommand: a module here with `Args` (`#[derive(clap::Args)]`) and
//! `pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError>`, then one variant of `Command`
//! and one match arm in `main.rs`.

use crate::CliError;
use std::path::{Path, PathBuf};

pub mod cells;
pub mod fit;
pub mod optimize;
pub mod plot;
pub mod report;
pub mod samples;
pub mod scenarios;
pub mod sensitivity;
pub mod simulate;
pub mod transmission;

/// The worker threads of a command that runs many simulations (`optimize`, `report`).
#[derive(Debug, Clone, Copy, clap::Args)]
pub struct Workers {
    /// Worker threads for the simulations (default: one per core). Does not change results.
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "T",
        default_value_t = 0
    )]
    pub threads: usize,
    /// Allow more than 4 worker threads per core.
    #[arg(long)]
    pub allow_many_threads: bool,
}

impl Workers {
    /// The thread count, checked against the per-core limit (0: one per core).
    pub fn checked(&self) -> Result<usize, CliError> {
        woodpile_io::limits::check_threads("--threads", self.threads, self.allow_many_threads)
    }
}

/// A lattice scenario given to `command`, which runs chains only: the refusal in its words.
pub fn chains_only(command: &'static str) -> impl Fn(CliError) -> CliError {
    move |e| match e {
        CliError::ChainsOnly { source_name } => {
            let reason = format!(
                "woodpile {command} supports chains only (a [chain] table), and this scenario is a lattice (its [lattice] table); a lattice runs with woodpile simulate and woodpile optimize"
            );
            CliError::invalid("lattice", source_name, reason)
        }
        other => other,
    }
}

/// Options shared by every subcommand.
#[derive(Debug, Clone, Copy, Default)]
pub struct Context {
    /// Print nothing but errors.
    pub quiet: bool,
}

/// The name a file gives a command's outputs (its stem, or `fallback`) and the directory its
/// relative paths start from (its folder, or `.`).
pub fn name_and_base(file: &Path, fallback: &str) -> (String, PathBuf) {
    let name = file
        .file_stem()
        .map_or_else(|| fallback.into(), |s| s.to_string_lossy().into_owned());
    let base = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    (name, base)
}
