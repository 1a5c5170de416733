//! The typed error of woodpile-io, in the words of the files and the scenario, never of a front
//! end: no exit codes and no option names. Each variant carries the numbers; [`Error::kind`]
//! sorts it, [`Error::field`], [`Error::value`] and [`Error::reason`] take it apart. Where the
//! user would set an option of the front end (overwrite, resume, an override of a limit), the
//! variant says which ([`Error::OutputExists`], [`Error::OverLimit`], …) and the front end words
//! its own option: the command line says `--overwrite`, Python `overwrite=True`.

use std::path::PathBuf;

/// Everything that can go wrong while reading, checking, running or writing.
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
    /// A name that is not a built-in scenario (or built-in problem).
    #[error("unknown scenario `{name}` (valid: {valid})")]
    UnknownScenario {
        /// The name as given.
        name: String,
        /// The built-in names, comma separated.
        valid: String,
    },
    /// The output directory holds an earlier run and replacing it was not asked for. With the
    /// overwrite option only the run's own files are replaced (other files and `plots/` stay).
    #[error("output directory {} holds an earlier run: its run files are replaced (your other files and plots/ are kept) only when overwriting is asked for; or choose another output directory", path.display())]
    OutputExists {
        /// The directory.
        path: PathBuf,
    },
    /// The output directory holds an earlier optimisation run (its checkpoint) and continuing it
    /// was not asked for: the resume option continues it (same config and seed).
    #[error("output directory {} holds an earlier optimisation run: resume it (same config and seed), or choose another output directory", path.display())]
    CheckpointExists {
        /// The directory.
        path: PathBuf,
    },
    /// The output directory exists, is not empty and holds no earlier output of this kind.
    #[error("output directory {} exists and is not empty and holds no earlier run (no {marker}): refusing to write into it; choose another output directory", path.display())]
    OutputNotEmpty {
        /// The directory.
        path: PathBuf,
        /// The file that marks an earlier run (`run.json`, `checkpoint.json`).
        marker: &'static str,
    },
    /// The output directory holds the file that marks a study's directory (`summary.json`):
    /// an earlier study, or a file of the user's. A study neither overwrites nor resumes, so it
    /// never writes into it (and nothing in it is removed).
    #[error("output directory {} holds a {marker} (an earlier study's, or a file of yours): a study writes only into a new or empty directory, and changes nothing in this one; choose another output directory", path.display())]
    StudyExists {
        /// The directory.
        path: PathBuf,
        /// The file found (`summary.json`).
        marker: &'static str,
    },
    /// A lattice scenario (a `[lattice]` table) given where only a chain is read.
    #[error("{source_name} is a lattice scenario (its [lattice] table), and this reads chains only (a [chain] table)")]
    ChainsOnly {
        /// The file (or "scenario" for text).
        source_name: String,
    },
    /// The output location cannot be written.
    #[error("cannot write output {}: {source}", path.display())]
    Output {
        /// The path that failed.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Resuming was asked for, but the directory holds no checkpoint.
    #[error("{} holds no {file}: nothing to resume; start a new run instead", path.display())]
    NothingToResume {
        /// The output directory.
        path: PathBuf,
        /// The checkpoint's file name.
        file: &'static str,
    },
    /// A checkpoint that cannot be resumed by this invocation (another version, modified, or a
    /// different problem).
    #[error("cannot resume from {}: {reason}", path.display())]
    ResumeRefused {
        /// The checkpoint.
        path: PathBuf,
        /// Why, and what would resume it.
        reason: String,
    },
    /// The command was interrupted (Ctrl-C or SIGTERM) after saving what lets it continue.
    #[error("interrupted: {saved}")]
    Interrupted {
        /// What was saved and how to continue.
        saved: String,
    },
    /// A run whose energy balance does not close to the stated accuracy: its numbers would not
    /// mean what they say. The allow-inaccurate option keeps the results anyway.
    #[error("inaccurate run: the energy balance is off by {relative_error:.2e} of {reference}, above the limit {limit:.0e}; use a smaller run.peak_tolerance (or run.time_step_s under rk4, rtol/atol under dopri5), or allow an inaccurate run to keep the results anyway")]
    Inaccurate {
        /// Largest relative energy error over the samples.
        relative_error: f64,
        /// What it is relative to.
        reference: &'static str,
        /// The limit it exceeds.
        limit: f64,
    },
    /// A run or command beyond an up-front limit (module `limits`); the option named by
    /// `limit` overrides it.
    #[error("invalid {field} = {value}: {reason}")]
    OverLimit {
        /// Which limit, hence which override.
        limit: Limit,
        /// The key or option as the user wrote it.
        field: String,
        /// The value, or the estimate it leads to.
        value: String,
        /// What the limit is and how to stay within it.
        reason: String,
    },
    /// The worker threads could not be started.
    #[error("cannot start {threads} worker threads: {reason}")]
    ThreadPool {
        /// Threads asked for.
        threads: usize,
        /// Why.
        reason: String,
    },
    /// A design of an optimisation could not be simulated.
    #[error("while evaluating design [{design}]: {source}")]
    Evaluation {
        /// The design, as its element labels.
        design: String,
        /// The library's error.
        source: woodpile::Error,
    },
    /// An error of the library: invalid parameters or a numerical failure of the run.
    #[error(transparent)]
    Model(#[from] woodpile::Error),
}

/// An up-front limit (module `limits`), each with its own override.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Limit {
    /// More worker threads than `limits::THREADS_PER_CORE` per core.
    Threads,
    /// More integration steps than `limits::MAX_STEPS`.
    Steps,
    /// A run directory larger than `limits::MAX_OUTPUT_BYTES`.
    OutputSize,
    /// A design study's generation above `limits::MAX_GENERATION_ELEMENTS` elements.
    Generation,
    /// A study's runs (samples of a scenario, a sensitivity design) above
    /// `limits::MAX_GENERATION_ELEMENTS` elements in all, or a fit's model runs above
    /// `limits::MAX_FIT_RUNS`.
    Study,
}

/// What kind of failure an [`Error`] is: what a front end maps to an exit code or an
/// exception class.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ErrorKind {
    /// A scenario, config or input value, or a file's content, is invalid (including a request
    /// the output directory cannot meet, such as resuming where there is nothing to resume).
    Scenario,
    /// A file cannot be read or written, or the output location cannot be used.
    Io,
    /// The output holds an earlier run and neither overwriting nor resuming it was asked for.
    Overwrite,
    /// Beyond an up-front limit (threads, steps, output size) and its override not given.
    Limit,
    /// The run failed numerically (blow-up, too many steps, a step size too small, …).
    Run,
    /// The energy balance is off: the results are kept only when inaccuracy is allowed.
    Inaccurate,
    /// Interrupted (Ctrl-C or SIGTERM) after saving what lets it continue.
    Interrupted,
}

/// Whether a library error is a numerical failure of the run (rather than a bad input).
fn is_numerical(e: &woodpile::Error) -> bool {
    matches!(
        e,
        woodpile::Error::NonFiniteState { .. }
            | woodpile::Error::RunawayOverlap { .. }
            | woodpile::Error::LoadBeyondContact { .. }
            | woodpile::Error::LoadExceedsContact { .. }
            | woodpile::Error::TooManySteps { .. }
            | woodpile::Error::StepSizeTooSmall { .. }
    )
}

/// The field, value and reason of a library error, where it has them.
fn model_parts(e: &woodpile::Error) -> (Option<&str>, Option<String>, String) {
    match e {
        woodpile::Error::InvalidParameter {
            field,
            value,
            reason,
        } => (Some(field), Some(value.clone()), reason.clone()),
        woodpile::Error::Unknown { what, name, valid } => (
            None,
            Some(name.clone()),
            format!("unknown {what} (valid: {valid})"),
        ),
        other => (None, None, other.to_string()),
    }
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

    /// What kind of failure this is.
    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::Model(e) | Error::Evaluation { source: e, .. } if is_numerical(e) => {
                ErrorKind::Run
            }
            Error::Read { .. }
            | Error::Output { .. }
            | Error::OutputNotEmpty { .. }
            | Error::StudyExists { .. } => ErrorKind::Io,
            Error::OutputExists { .. } | Error::CheckpointExists { .. } => ErrorKind::Overwrite,
            Error::OverLimit { .. } => ErrorKind::Limit,
            Error::Inaccurate { .. } => ErrorKind::Inaccurate,
            Error::Interrupted { .. }
            | Error::Model(woodpile::Error::Interrupted { .. })
            | Error::Evaluation {
                source: woodpile::Error::Interrupted { .. },
                ..
            } => ErrorKind::Interrupted,
            _ => ErrorKind::Scenario,
        }
    }

    /// The key or option the error is about, as the user wrote it (e.g. `chain.rods_mm[3]`),
    /// where there is one.
    pub fn field(&self) -> Option<&str> {
        match self {
            Error::Invalid { field, .. }
            | Error::Field { field, .. }
            | Error::OverLimit { field, .. } => Some(field),
            Error::ChainsOnly { .. } => Some("lattice"),
            Error::Model(e) | Error::Evaluation { source: e, .. } => model_parts(e).0,
            _ => None,
        }
    }

    /// The offending value as given (for a file or directory: its path), where there is one.
    pub fn value(&self) -> Option<String> {
        match self {
            Error::Invalid { value, .. } | Error::OverLimit { value, .. } => Some(value.clone()),
            Error::Field { source: e, .. }
            | Error::Model(e)
            | Error::Evaluation { source: e, .. } => model_parts(e).1,
            Error::UnknownScenario { name, .. } => Some(name.clone()),
            Error::ThreadPool { threads, .. } => Some(threads.to_string()),
            Error::Inaccurate { relative_error, .. } => Some(format!("{relative_error:.2e}")),
            Error::Read { path, .. }
            | Error::Output { path, .. }
            | Error::Table { path, .. }
            | Error::OutputExists { path }
            | Error::CheckpointExists { path }
            | Error::OutputNotEmpty { path, .. }
            | Error::StudyExists { path, .. }
            | Error::NothingToResume { path, .. }
            | Error::ResumeRefused { path, .. } => Some(path.display().to_string()),
            Error::ChainsOnly { source_name } => Some(source_name.clone()),
            Error::Parse { .. } | Error::Interrupted { .. } => None,
        }
    }

    /// What is wrong and what would be valid, without the field and value (front-end neutral).
    pub fn reason(&self) -> String {
        match self {
            Error::Invalid { reason, .. }
            | Error::OverLimit { reason, .. }
            | Error::ResumeRefused { reason, .. }
            | Error::ThreadPool { reason, .. } => reason.clone(),
            Error::Field { source: e, .. } | Error::Model(e) => model_parts(e).2,
            Error::UnknownScenario { valid, .. } => {
                format!("not a built-in scenario (valid: {valid})")
            }
            Error::ChainsOnly { .. } => {
                "a lattice scenario (its [lattice] table): this reads chains only (a [chain] table)"
                    .into()
            }
            other => other.to_string(),
        }
    }
}
