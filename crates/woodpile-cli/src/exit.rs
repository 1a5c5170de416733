//! The command line's words for [`CliError`]: its exit code and its message, naming this
//! command line's flags where woodpile-io's error says which option would help.

use crate::CliError;
use woodpile_io::error::{ErrorKind, Limit};

/// The process exit code: 2 for bad input (arguments, scenario, files, output location, a limit
/// without its override), 1 for a failed or inaccurate run, 130 for an interrupted command.
pub fn code(e: &CliError) -> u8 {
    match e.kind() {
        ErrorKind::Interrupted => 130,
        ErrorKind::Run | ErrorKind::Inaccurate => 1,
        ErrorKind::Scenario | ErrorKind::Io | ErrorKind::Overwrite | ErrorKind::Limit => 2,
        _ => 1,
    }
}

/// The flag that overrides `limit`.
fn override_flag(limit: Limit) -> &'static str {
    match limit {
        Limit::Threads => "--allow-many-threads",
        Limit::Steps => "--allow-long",
        Limit::OutputSize | Limit::Generation | Limit::Study => "--allow-large",
        _ => "the matching --allow-* flag",
    }
}

/// The message to print (after `error: `), with the options woodpile-io leaves unnamed spelt as
/// this command line's flags.
pub fn message(e: &CliError) -> String {
    match e {
        CliError::OutputExists { path } => format!(
            "invalid --out = {}: holds an earlier run: pass --overwrite to replace its run files (your other files and plots/ are kept), or choose another --out",
            path.display()
        ),
        CliError::CheckpointExists { path } => format!(
            "invalid --out = {}: holds an earlier optimisation run: add --resume to continue it (same config and seed), or choose another --out",
            path.display()
        ),
        CliError::OutputNotEmpty { path, marker } => format!(
            "invalid --out = {}: exists and is not empty and holds no earlier run (no {marker}): refusing to write into it; choose another --out",
            path.display()
        ),
        CliError::StudyExists { path, marker } => format!(
            "invalid --out = {}: holds a {marker} (an earlier study's, or a file of yours): a study writes only into a new or empty directory and changes nothing in this one; choose another --out",
            path.display()
        ),
        CliError::NothingToResume { path, file } => format!(
            "invalid --resume = {}: holds no {file}: nothing to resume; drop --resume to start a new run",
            path.display()
        ),
        CliError::ResumeRefused { path, reason } => {
            format!("invalid --resume = {}: {reason}", path.display())
        }
        CliError::ThreadPool { threads, reason } => format!("invalid --threads = {threads}: {reason}"),
        CliError::OverLimit { limit, .. } => {
            format!("{e}; pass {} to go ahead anyway", override_flag(*limit))
        }
        CliError::Inaccurate {
            relative_error,
            reference,
            limit,
        } => format!(
            "inaccurate run: the energy balance is off by {relative_error:.2e} of {reference}, above the limit {limit:.0e}; use a smaller run.peak_tolerance (or run.time_step_s under rk4, rtol/atol under dopri5), or pass --allow-inaccurate to keep the results anyway"
        ),
        other => other.to_string(),
    }
}
