//! Scenarios (`woodpile.scenario`): built-in scenarios, completion, the TOML ↔ JSON bridge for
//! Python dictionaries, and woodpile-io's table of scenario keys (defaults, alternatives).

use crate::errors::{py_err, Failure, Kind};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyString};
use std::path::PathBuf;
use woodpile_io::lattice::LatticeScenario;
use woodpile_io::scenario::{builtin, builtin_names, keys, resolve, KeyDefault, Scenario};

/// One key of the scenario file, as Python's `ScenarioKey` takes it (its fields in order):
/// name, type, unit, default, the rule of a derived default, choices, alternatives (the keys
/// setting it removes), what is valid, doc.
type KeyRow = (
    &'static str,
    &'static str,
    &'static str,
    Option<Py<PyAny>>,
    Option<String>,
    Vec<&'static str>,
    Vec<&'static str>,
    &'static str,
    &'static str,
);

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
    if woodpile_io::lattice::is_lattice(text) {
        let (scenario, _) = crate::lattice::parse_and_resolve(text)?;
        return crate::lattice::complete_toml(&scenario);
    }
    let scenario = Scenario::parse(text).map_err(py_err)?;
    resolve(&scenario, &base_dir).map_err(py_err)?;
    Ok(scenario.to_toml())
}

/// The scenario as JSON text (the TOML file's structure), for Python dictionaries.
#[pyfunction]
fn toml_to_json(text: &str) -> PyResult<String> {
    let json = if woodpile_io::lattice::is_lattice(text) {
        let scenario = LatticeScenario::parse(text, "scenario").map_err(py_err)?;
        serde_json::to_string(&scenario)
    } else {
        serde_json::to_string(&Scenario::parse(text).map_err(py_err)?)
    };
    json.map_err(|e| Failure::new(Kind::Scenario, format!("scenario: {e}")).into())
}

/// A scenario (a chain's, or a lattice's when the tree has a `lattice` table) from JSON text
/// (as [`toml_to_json`] writes it) as complete TOML. A value of the
/// wrong type or an unknown key is refused naming its dotted key (`chain.rods_mm[2]`) and the
/// value, not a place in the JSON text.
#[pyfunction]
fn json_to_toml(json: &str) -> PyResult<String> {
    let not_json =
        |e: serde_json::Error| PyErr::from(Failure::new(Kind::Scenario, format!("scenario: {e}")));
    let tree: serde_json::Value = serde_json::from_str(json).map_err(not_json)?;
    if tree.get("lattice").is_some() {
        let scenario: LatticeScenario = from_tree(&tree)?;
        return crate::lattice::complete_toml(&scenario);
    }
    let scenario: Scenario = from_tree(&tree)?;
    Ok(scenario.to_toml())
}

/// A scenario deserialised from a JSON tree; a value of the wrong type or an unknown key is
/// refused naming its dotted key and the value.
fn from_tree<T: serde::de::DeserializeOwned>(tree: &serde_json::Value) -> PyResult<T> {
    serde_path_to_error::deserialize(tree).map_err(|e| {
        let value = json_pointer(e.path())
            .and_then(|p| tree.pointer(&p))
            .map_or_else(|| "(as given)".to_string(), |v| v.to_string());
        let field = e.path().to_string();
        let reason = e.into_inner().to_string();
        PyErr::from(if field == "." {
            Failure::new(Kind::Scenario, format!("scenario: {reason}"))
        } else {
            Failure::invalid(field, value, reason)
        })
    })
}

/// The JSON pointer (`/chain/rods_mm/2`) of a deserialisation path, when every segment is a
/// key or an index.
fn json_pointer(path: &serde_path_to_error::Path) -> Option<String> {
    use serde_path_to_error::Segment;
    path.iter()
        .map(|segment| match segment {
            Segment::Map { key } => Some(format!("/{}", key.replace('~', "~0").replace('/', "~1"))),
            Segment::Seq { index } => Some(format!("/{index}")),
            _ => None,
        })
        .collect()
}

/// Every key of the scenario file (woodpile-io's table), in the order of the file; defaults
/// come from `woodpile::defaults` through it.
#[pyfunction]
fn scenario_keys(py: Python<'_>) -> Vec<KeyRow> {
    key_rows(py, keys())
}

/// Every key of a lattice scenario (woodpile-io's `lattice::lattice_keys()`), in the order of
/// the file.
#[pyfunction]
fn lattice_keys(py: Python<'_>) -> Vec<KeyRow> {
    key_rows(py, woodpile_io::lattice::lattice_keys())
}

fn key_rows(py: Python<'_>, keys: &'static [woodpile_io::scenario::Key]) -> Vec<KeyRow> {
    keys.iter()
        .map(|k| {
            let (default, derived) = match &k.default {
                KeyDefault::Float(x) => (Some(PyFloat::new(py, *x).into_any().unbind()), None),
                KeyDefault::Bool(b) => (
                    Some(PyBool::new(py, *b).to_owned().into_any().unbind()),
                    None,
                ),
                KeyDefault::Name(n) => (Some(PyString::new(py, n).into_any().unbind()), None),
                KeyDefault::Derived(rule) => (None, Some(rule.clone())),
                KeyDefault::None => (None, None),
            };
            let (choices, alternatives) = (k.choices.to_vec(), k.alternatives.to_vec());
            (
                k.name,
                k.ty.name(),
                k.unit,
                default,
                derived,
                choices,
                alternatives,
                k.valid,
                k.doc,
            )
        })
        .collect()
}

/// Adds this module's functions to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(builtin_scenarios, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_toml, m)?)?;
    m.add_function(wrap_pyfunction!(complete_toml, m)?)?;
    m.add_function(wrap_pyfunction!(toml_to_json, m)?)?;
    m.add_function(wrap_pyfunction!(json_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(scenario_keys, m)?)?;
    m.add_function(wrap_pyfunction!(lattice_keys, m)?)?;
    Ok(())
}
