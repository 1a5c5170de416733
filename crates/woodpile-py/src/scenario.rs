//! Scenarios (`woodpile.scenario`): built-in scenarios, completion and the TOML ↔ JSON bridge
//! for Python dictionaries, and which keys exclude each other.

use crate::errors::{py_err, Failure, Kind};
use pyo3::prelude::*;
use std::path::PathBuf;
use woodpile_io::scenario::{builtin, builtin_names, resolve, Scenario};

/// Keys that exclude each other: setting the first removes the others. The scenario format's
/// rule (`Scenario::complete` fills in one of each pair); it moves to woodpile-io's table of
/// scenario keys when that exists.
const EXCLUSIVE: &[(&str, &[&str])] = &[
    ("excitation.velocity_m_s", &["excitation.drop_height_m"]),
    ("excitation.drop_height_m", &["excitation.velocity_m_s"]),
    ("chain.rods_mm", &["chain.elements"]),
    ("chain.elements", &["chain.rods_mm"]),
    // A stated peak accuracy replaces the integrator settings, and the other way round.
    (
        "run.peak_tolerance",
        &["run.integrator", "run.time_step_s", "run.rtol", "run.atol"],
    ),
    ("run.integrator", &["run.peak_tolerance"]),
    ("run.time_step_s", &["run.peak_tolerance"]),
    ("run.rtol", &["run.peak_tolerance"]),
    ("run.atol", &["run.peak_tolerance"]),
];

/// Names of the built-in scenarios.
#[pyfunction]
fn builtin_scenarios() -> Vec<String> {
    builtin_names()
}

/// A built-in scenario as complete TOML (every default written out).
#[pyfunction]
fn builtin_toml(name: &str) -> PyResult<String> {
    let scenario = builtin(name).ok_or_else(|| {
        py_err(woodpile_io::Error::UnknownScenario {
            name: name.to_string(),
            valid: builtin_names().join(", "),
        })
    })?;
    Ok(scenario.to_toml())
}

/// Parses a scenario, checks that it resolves (relative files against `base_dir`) and returns
/// it as complete TOML.
#[pyfunction]
fn complete_toml(text: &str, base_dir: PathBuf) -> PyResult<String> {
    let scenario = Scenario::parse(text).map_err(py_err)?;
    resolve(&scenario, &base_dir).map_err(py_err)?;
    Ok(scenario.to_toml())
}

/// The scenario as JSON text (the TOML file's structure), for Python dictionaries.
#[pyfunction]
fn toml_to_json(text: &str) -> PyResult<String> {
    let scenario = Scenario::parse(text).map_err(py_err)?;
    serde_json::to_string(&scenario)
        .map_err(|e| Failure::new(Kind::Scenario, format!("scenario: {e}")).into())
}

/// A scenario from JSON text (as [`toml_to_json`] writes it) as complete TOML.
#[pyfunction]
fn json_to_toml(json: &str) -> PyResult<String> {
    let scenario: Scenario = serde_json::from_str(json)
        .map_err(|e| PyErr::from(Failure::new(Kind::Scenario, format!("scenario: {e}"))))?;
    Ok(scenario.to_toml())
}

/// The dotted keys that setting `key` removes (empty for a key without alternatives).
#[pyfunction]
fn excluded_by(key: &str) -> Vec<&'static str> {
    EXCLUSIVE
        .iter()
        .find(|(k, _)| *k == key)
        .map_or_else(Vec::new, |(_, others)| others.to_vec())
}

/// Adds this module's functions to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(builtin_scenarios, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_toml, m)?)?;
    m.add_function(wrap_pyfunction!(complete_toml, m)?)?;
    m.add_function(wrap_pyfunction!(toml_to_json, m)?)?;
    m.add_function(wrap_pyfunction!(json_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(excluded_by, m)?)?;
    Ok(())
}
