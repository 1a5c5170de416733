//! `woodpile scenarios` (list the built-ins) and `woodpile scenario NAME` (print one as TOML).

use super::Context;
use crate::CliError;
use woodpile_io::scenario::{self, builtin, builtin_names};

/// Arguments of `woodpile scenarios`.
#[derive(Debug, Clone, clap::Args)]
pub struct ListArgs {}

/// Arguments of `woodpile scenario`.
#[derive(Debug, Clone, clap::Args)]
pub struct ShowArgs {
    /// Built-in scenario name (see `woodpile scenarios`).
    pub name: String,
}

/// Lists the built-in scenarios with a one-line description each.
pub fn list(_args: &ListArgs, _ctx: &Context) -> Result<(), CliError> {
    let all = scenario::builtins();
    let width = all.iter().map(|b| b.name.len()).max().unwrap_or(0);
    for b in all {
        let default = if b.name == scenario::DEFAULT_SCENARIO {
            " [default]"
        } else {
            ""
        };
        crate::out::println(format_args!(
            "{:<width$}  {}{default}",
            b.name,
            b.scenario.description.as_deref().unwrap_or("")
        ))?;
    }
    for &(name, text) in woodpile_io::lattice::BUILTIN_LATTICES {
        let description = woodpile_io::lattice::LatticeScenario::parse(text, name)?
            .description
            .unwrap_or_default();
        crate::out::println(format_args!("{name:<width$}  {description}"))?;
    }
    Ok(())
}

/// A built-in scenario by name, or the error listing the valid names.
pub fn lookup(name: &str) -> Result<scenario::Scenario, CliError> {
    builtin(name).ok_or_else(|| CliError::UnknownScenario {
        name: name.to_string(),
        valid: builtin_names()
            .into_iter()
            .chain(
                woodpile_io::lattice::BUILTIN_LATTICES
                    .iter()
                    .map(|(n, _)| n.to_string()),
            )
            .collect::<Vec<_>>()
            .join(", "),
    })
}

/// Prints a built-in scenario as complete, commented TOML.
pub fn show(args: &ShowArgs, _ctx: &Context) -> Result<(), CliError> {
    let text = match woodpile_io::lattice::builtin_lattice(&args.name) {
        Some(lattice) => lattice.to_string(),
        None => lookup(&args.name)?.to_toml(),
    };
    crate::out::print(format_args!(
        "# Run it with `woodpile simulate THIS_FILE.toml --out DIR`.\n{text}"
    ))?;
    Ok(())
}
