//! Errors on their way to Python. Every error becomes an instance of one of the exception
//! classes of `woodpile.errors` (a `WoodpileError` subclass per [`Kind`]) with `field`, `value`
//! and `reason` set, so that Python code reads attributes instead of parsing messages.
//!
//! [`classify`] is the one place where `woodpile_io::Error` is mapped to a kind; messages that
//! would name the command line's flags are phrased here in Python's terms (`overwrite=True`,
//! a `directory` argument).

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyModule;
use woodpile_io::Error as IoError;

/// What went wrong, as Python sees it: one exception class of `woodpile.errors` each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A scenario, problem config, checkpoint or argument value is not valid (`ScenarioError`).
    Scenario,
    /// A file or directory could not be read or written (`FileError`).
    Io,
    /// The output directory exists and may not be written (`OverwriteError`).
    Overwrite,
    /// A run failed numerically (`RunError`).
    Run,
    /// A run's energy balance does not close to the stated accuracy (`InaccurateRunError`).
    Inaccurate,
    /// The work was interrupted (`InterruptedRunError`).
    Interrupted,
    /// A call the object's state does not allow yet, e.g. `tell()` without `ask()` (`StateError`).
    State,
}

impl Kind {
    /// The exception class of `woodpile.errors`.
    fn class_name(self) -> &'static str {
        match self {
            Kind::Scenario => "ScenarioError",
            Kind::Io => "FileError",
            Kind::Overwrite => "OverwriteError",
            Kind::Run => "RunError",
            Kind::Inaccurate => "InaccurateRunError",
            Kind::Interrupted => "InterruptedRunError",
            Kind::State => "StateError",
        }
    }
}

/// An error for Python: its kind, its message and, where it is about one value, the field, the
/// value as given and what would be valid.
#[derive(Debug, Clone)]
pub struct Failure {
    kind: Kind,
    message: String,
    field: Option<String>,
    value: Option<String>,
    reason: Option<String>,
}

impl Failure {
    /// An error that is not about one value.
    pub fn new(kind: Kind, message: impl Into<String>) -> Self {
        Failure {
            kind,
            message: message.into(),
            field: None,
            value: None,
            reason: None,
        }
    }

    /// A value that is not valid: "invalid {field} = {value}: {reason}".
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        let (field, value, reason) = (field.into(), value.to_string(), reason.into());
        Failure {
            kind: Kind::Scenario,
            message: format!("invalid {field} = {value}: {reason}"),
            field: Some(field),
            value: Some(value),
            reason: Some(reason),
        }
    }

    /// The same error with another kind.
    fn kind(self, kind: Kind) -> Self {
        Failure { kind, ..self }
    }

    /// The exception instance, built from the class of `woodpile.errors`.
    fn to_py(&self, py: Python<'_>) -> PyErr {
        let class =
            PyModule::import(py, "woodpile.errors").and_then(|m| m.getattr(self.kind.class_name()));
        let args = (
            self.message.clone(),
            self.field.clone(),
            self.value.clone(),
            self.reason.clone(),
        );
        match class.and_then(|c| c.call1(args)) {
            Ok(instance) => PyErr::from_value(instance),
            Err(e) => PyRuntimeError::new_err(format!(
                "{} (and woodpile.errors.{} could not be raised: {e})",
                self.message,
                self.kind.class_name()
            )),
        }
    }
}

impl From<Failure> for PyErr {
    fn from(f: Failure) -> PyErr {
        Python::attach(|py| f.to_py(py))
    }
}

/// A `woodpile-io` error as a Python exception (see [`classify`]).
pub fn py_err(e: IoError) -> PyErr {
    classify(e).into()
}

/// A library error as a Python exception.
pub fn core_err(e: woodpile::Error) -> PyErr {
    py_err(IoError::from(e))
}

/// A GA error as a Python exception.
pub fn ga_err(e: woodpile::optimize::OptimizeError) -> PyErr {
    py_err(woodpile_io::optimize::optimize_error(e))
}

/// Whether a library error is a numerical failure of the run rather than a bad input.
fn is_numerical(e: &woodpile::Error) -> bool {
    use woodpile::Error as E;
    matches!(
        e,
        E::NonFiniteState { .. }
            | E::RunawayOverlap { .. }
            | E::LoadBeyondContact { .. }
            | E::TooManySteps { .. }
            | E::StepSizeTooSmall { .. }
    )
}

/// Why a directory holding an earlier run is not replaced, in Python's terms.
const EARLIER_RUN: &str = "holds an earlier run: pass overwrite=True to replace its run files \
    (other files and folders in it are kept), or choose another directory";

/// Why any other non-empty directory is refused.
const NOT_A_RUN: &str = "is not empty and holds no earlier run (no run.json): refusing to write \
    into it; choose another directory";

/// The one mapping of `woodpile_io::Error` to Python: its kind, its field, value and reason,
/// and a message in Python's terms (keyword arguments, not the command line's flags).
pub fn classify(e: IoError) -> Failure {
    use woodpile::Error as M;
    use Kind::*;
    let message = e.to_string();
    let with = |kind, field: Option<String>, value: Option<String>, reason: Option<String>| {
        let message = message.clone();
        Failure {
            kind,
            message,
            field,
            value,
            reason,
        }
    };
    match e {
        // The command line's output, resume and thread flags and its run-directory argument, by
        // their Python names (today's woodpile-io names the command line's).
        IoError::Invalid { field, value, .. } if field == "--out" => {
            Failure::invalid("directory", value, EARLIER_RUN).kind(Overwrite)
        }
        IoError::Invalid { field, value, reason } if field == "--resume" => {
            Failure::invalid("checkpoint", value, reason)
        }
        IoError::Invalid { field, value, reason } if field == "--threads" => {
            Failure::invalid("threads", value, reason)
        }
        IoError::Invalid { field, value, reason } if field == "RUN_DIR" => {
            Failure::invalid("directory", value, reason)
        }
        IoError::Invalid { field, value, reason }
        | IoError::Model(M::InvalidParameter { field, value, reason }) => {
            Failure::invalid(field, value, reason)
        }
        IoError::Field { field, source: M::InvalidParameter { field: inner, value, reason } } => {
            Failure::invalid(format!("{field}.{inner}"), value, reason)
        }
        IoError::Field { field, source } => {
            with(Scenario, Some(field), None, Some(source.to_string()))
        }
        IoError::Model(M::Unknown { what, name, valid }) => {
            with(Scenario, None, Some(name), Some(format!("not a known {what}; valid: {valid}")))
        }
        IoError::Model(M::WaveNotArrived { duration_s, .. }) => with(
            Scenario,
            Some("run.duration_s".into()),
            Some(format!("{duration_s:e}")),
            Some("too short for the wave to reach the wall; increase it".into()),
        ),
        IoError::Model(m) | IoError::Evaluation { source: m, .. } if is_numerical(&m) => {
            Failure::new(Run, message)
        }
        IoError::UnknownScenario { name, valid } => Failure {
            message: format!(
                "unknown scenario `{name}` (valid: {valid}); woodpile.builtin_scenarios() lists them"
            ),
            ..with(Scenario, Some("name".into()), Some(name), Some(format!("valid: {valid}")))
        },
        IoError::OutputNotEmpty { path } => {
            Failure::invalid("directory", path.display(), NOT_A_RUN).kind(Overwrite)
        }
        IoError::Read { path, source } | IoError::Output { path, source } => {
            with(Io, None, Some(path.display().to_string()), Some(source.to_string()))
        }
        IoError::Table { path, line, message: what } => {
            with(Scenario, None, Some(format!("{}, line {line}", path.display())), Some(what))
        }
        IoError::Inaccurate { relative_error, reference, limit } => Failure::new(
            Inaccurate,
            format!(
                "inaccurate run: the energy balance is off by {relative_error:.2e} of \
                 {reference}, above the limit {limit:.0e}; use a smaller run.time_step_s (rk4) \
                 or a tighter rtol/atol (dopri5)"
            ),
        ),
        IoError::Interrupted { saved } => with(Interrupted, None, None, Some(saved)),
        // Parse errors (line and column in the message), other library errors about the input.
        _ => Failure::new(Scenario, message),
    }
}
