//! Errors on their way to Python. Every error becomes an instance of one of the exception
//! classes of `woodpile.errors` (a `WoodpileError` subclass per [`Kind`]) with `field`, `value`
//! and `reason` set, so that Python code reads attributes instead of parsing messages.
//!
//! [`classify`] is the one place where a `woodpile_io::Error` is mapped: its class from
//! `kind()`, its attributes from `field()`, `value()` and `reason()`, and where the error asks
//! for a front end's option or names an argument, Python's words (`overwrite=True`, the
//! `directory` argument).

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
    /// Beyond an up-front limit of the run (steps, output size, threads) (`LimitError`).
    Limit,
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
            Kind::Limit => "LimitError",
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

    /// The same error naming `keyword` where its field is the config key `key` (or an element
    /// of it, `key[k]`): a key the caller set through a keyword argument.
    pub fn keyword(mut self, key: &str, keyword: &str) -> Self {
        let Some(field) = self.field.clone() else {
            return self;
        };
        let Some(rest) = field.strip_prefix(key) else {
            return self;
        };
        if !(rest.is_empty() || rest.starts_with('[')) {
            return self;
        }
        let renamed = format!("{keyword}{rest}");
        self.message = self.message.replacen(&field, &renamed, 1);
        self.field = Some(renamed);
        self
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

/// Why a directory holding an earlier run is not replaced, in Python's terms.
const EARLIER_RUN: &str = "holds an earlier run: pass overwrite=True to replace its run files \
    (other files and folders in it are kept), or choose another directory";

/// The keyword argument that overrides `limit`.
fn override_argument(limit: woodpile_io::error::Limit) -> &'static str {
    use woodpile_io::error::Limit;
    match limit {
        Limit::Threads => "fewer threads",
        Limit::Steps => "allow_long=True",
        Limit::OutputSize | Limit::Study => "allow_large=True",
        Limit::Generation => "ga.allow_large = true in the config",
        _ => "the matching allow_* argument",
    }
}

/// The one mapping of `woodpile_io::Error` to Python: the class from its kind, its field, value
/// and reason as woodpile-io gives them, and Python's words where the error asks for an option
/// of the front end (`overwrite=True`) or names an argument (`directory`, `checkpoint`,
/// `threads`).
pub fn classify(e: IoError) -> Failure {
    use woodpile_io::error::ErrorKind as K;
    let kind = match e.kind() {
        K::Io => Kind::Io,
        K::Overwrite => Kind::Overwrite,
        K::Limit => Kind::Limit,
        K::Run => Kind::Run,
        K::Inaccurate => Kind::Inaccurate,
        K::Interrupted => Kind::Interrupted,
        _ => Kind::Scenario,
    };
    let failure = Failure {
        kind,
        message: e.to_string(),
        field: e.field().map(String::from),
        value: e.value(),
        reason: Some(e.reason()),
    };
    let directory = |reason: String| Failure {
        message: format!(
            "output directory {} {reason}",
            failure.value.as_deref().unwrap_or("")
        ),
        field: Some("directory".into()),
        reason: Some(reason),
        kind: Kind::Overwrite,
        ..failure.clone()
    };
    match e {
        IoError::OutputExists { .. } => directory(EARLIER_RUN.into()),
        // Not an earlier run, so overwrite=True would not help; the directory is left untouched.
        IoError::OutputNotEmpty { marker, .. } => directory(format!(
            "is not empty and holds no earlier run (no {marker}): refusing to write into it; \
             choose another directory"
        )),
        IoError::ResumeRefused { .. } => Failure {
            field: Some("checkpoint".into()),
            ..failure
        },
        // The override as this front end spells it.
        IoError::OverLimit { limit, .. } => Failure {
            message: format!(
                "{}; pass {} to go ahead anyway",
                failure.message,
                override_argument(limit)
            ),
            ..failure
        },
        IoError::ThreadPool { .. } => Failure {
            field: Some("threads".into()),
            ..failure
        },
        // A run directory that cannot be read: the argument of `load_run`.
        IoError::Invalid {
            field,
            value,
            reason,
        } if field == "RUN_DIR" => Failure::invalid("directory", value, reason),
        _ => failure,
    }
}
