//! The command line's typed error. Each variant knows whether it is the user's input that is
//! wrong (exit code 2) or the run that failed (exit code 1).

use std::path::PathBuf;

/// Everything that can go wrong in a `woodpile` command.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The scenario text is not valid TOML or does not match the scenario format (the message
    /// carries the line and column).
    #[error("{source_name}: {message}")]
    Parse {
        /// File name (or "scenario" for text).
        source_name: String,
        /// The TOML parser's message, with line, column and the offending snippet.
        message: String,
    },
    /// A file could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A value of the scenario is not valid.
    #[error("invalid {field} = {value}: {reason}")]
    Invalid {
        /// Dotted path of the key, e.g. `chain.rods_mm[3]`.
        field: String,
        /// The value as given.
        value: String,
        /// What would be valid.
        reason: String,
    },
    /// A library error about one key of the scenario (e.g. an unknown material or rod length).
    #[error("{field}: {source}")]
    Field {
        /// Dotted path of the key.
        field: String,
        /// The library's error.
        source: woodpile::Error,
    },
    /// The blast table file is malformed.
    #[error("{}, line {line}: {message}", path.display())]
    Table {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number in the file.
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// A name that is not a built-in scenario.
    #[error("unknown scenario `{name}` (valid: {valid}); `woodpile scenarios` lists them")]
    UnknownScenario {
        /// The name as given.
        name: String,
        /// The built-in names, comma separated.
        valid: String,
    },
    /// The output directory exists and holds something other than a previous run.
    #[error("output directory {} exists and is not empty and holds no previous run (no run.json): refusing to overwrite it; choose another --out", path.display())]
    OutputNotEmpty {
        /// The directory.
        path: PathBuf,
    },
    /// The output location cannot be written.
    #[error("cannot write output {}: {source}", path.display())]
    Output {
        /// The path that failed.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The command was interrupted (Ctrl-C or SIGTERM) after saving what lets it continue.
    #[error("interrupted: {saved}")]
    Interrupted {
        /// What was saved and how to continue.
        saved: String,
    },
    /// A run whose energy balance does not close to the stated accuracy: its numbers would not
    /// mean what they say.
    #[error("inaccurate run: the energy balance is off by {relative_error:.2e} of {reference}, above the limit {limit:.0e}; use a smaller run.time_step_s (rk4) or a tighter rtol/atol (dopri5), or pass --allow-inaccurate to keep the results anyway")]
    Inaccurate {
        /// Largest relative energy error over the samples.
        relative_error: f64,
        /// What it is relative to.
        reference: &'static str,
        /// The limit it exceeds.
        limit: f64,
    },
    /// A design of an optimisation could not be simulated.
    #[error("while evaluating design [{design}]: {source}")]
    Evaluation {
        /// The design, as its element labels.
        design: String,
        /// The library's error.
        source: woodpile::Error,
    },
    /// An error of the library: invalid parameters (usage) or a numerical failure of the run.
    #[error(transparent)]
    Model(#[from] woodpile::Error),
}

impl Error {
    /// Shorthand for [`Error::Invalid`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        Error::Invalid {
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// Wraps a library error with the scenario key it is about (an error that already names its
    /// own field passes through unchanged).
    pub fn at(field: impl Into<String>) -> impl FnOnce(woodpile::Error) -> Error {
        let field = field.into();
        move |e| match e {
            woodpile::Error::InvalidParameter { .. } => Error::Model(e),
            other => Error::Field {
                field,
                source: other,
            },
        }
    }

    /// Whether the user's input (arguments, scenario, files, output location) is at fault, as
    /// opposed to a run that failed numerically.
    pub fn is_usage(&self) -> bool {
        match self {
            Error::Model(e) | Error::Evaluation { source: e, .. } => !matches!(
                e,
                woodpile::Error::NonFiniteState { .. }
                    | woodpile::Error::RunawayOverlap { .. }
                    | woodpile::Error::LoadBeyondContact { .. }
                    | woodpile::Error::TooManySteps { .. }
                    | woodpile::Error::StepSizeTooSmall { .. }
            ),
            Error::Inaccurate { .. } | Error::Interrupted { .. } => false,
            _ => true,
        }
    }

    /// The process exit code: 2 for a usage error, 1 for a failed or inaccurate run, 130 for
    /// an interrupted command.
    pub fn exit_code(&self) -> u8 {
        if matches!(self, Error::Interrupted { .. }) {
            130
        } else if self.is_usage() {
            2
        } else {
            1
        }
    }
}
