//! Runs (`woodpile.run`): one simulation, its samples as NumPy arrays, its run directory
//! written and read back.

use crate::errors::{core_err, py_err, Failure, Kind};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use std::path::PathBuf;
use woodpile::{simulate as run_simulation, RunSummary, Trajectory};
use woodpile_io::rundir::{read_run_info, read_trajectory, write_run, RunRecord, SummaryJson};
use woodpile_io::scenario::{resolve, Resolved, Scenario};

/// One run: what was run, its figures of merit and its samples.
#[pyclass(module = "woodpile._core", frozen)]
struct Run {
    name: String,
    scenario: Scenario,
    resolved: Resolved,
    summary: RunSummary,
    trajectory: Trajectory,
}

impl Run {
    fn record(&self) -> RunRecord<'_> {
        RunRecord {
            name: &self.name,
            file: None,
            scenario: &self.scenario,
            resolved: &self.resolved,
            summary: &self.summary,
            trajectory: &self.trajectory,
        }
    }

    fn matrix<'py>(
        &self,
        py: Python<'py>,
        data: &[f64],
        columns: usize,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows = data.len().checked_div(columns).unwrap_or(0);
        PyArray1::from_slice(py, data).reshape([rows, columns])
    }
}

#[pymethods]
impl Run {
    /// `summary.json` of this run, as JSON text.
    fn summary_json(&self) -> PyResult<String> {
        serde_json::to_string(&SummaryJson::new(&self.record()))
            .map_err(|e| Failure::new(Kind::Run, format!("summary.json: {e}")).into())
    }

    /// The scenario as complete TOML.
    fn scenario_toml(&self) -> String {
        self.scenario.to_toml()
    }

    /// Scenario name.
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// Sample times [s], shape (S,).
    #[getter]
    fn time_s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.trajectory.times_s)
    }

    /// Contact forces [N], shape (S, N + 1).
    #[getter]
    fn forces_n<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = &self.trajectory;
        self.matrix(py, &t.contact_forces_n, t.n_contacts())
    }

    /// Layer energies [J], shape (S, N + 1).
    #[getter]
    fn energy_j<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = &self.trajectory;
        self.matrix(py, &t.layer_energies_j, t.n_contacts())
    }

    /// Primary-mass displacements [m], shape (S, N).
    #[getter]
    fn displacements_m<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = &self.trajectory;
        self.matrix(py, &t.displacements_m, t.n_elements)
    }

    /// Primary-mass velocities [m/s], shape (S, N).
    #[getter]
    fn velocities_m_s<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = &self.trajectory;
        self.matrix(py, &t.velocities_m_s, t.n_elements)
    }

    /// The wall's share of the last contact's energy [J], shape (S,).
    #[getter]
    fn wall_energy_j<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.trajectory.wall_energy_j)
    }

    /// Work of the external forces [J], shape (S,).
    #[getter]
    fn input_work_j<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.trajectory.input_work_j)
    }

    /// Energy dissipated [J], shape (S,).
    #[getter]
    fn dissipated_j<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.trajectory.dissipated_j)
    }

    /// Writes the run directory `dir` exactly as `woodpile simulate --out dir` does (staged, then
    /// moved into place; an earlier run there is replaced only with `overwrite`).
    fn save(&self, py: Python<'_>, dir: PathBuf, overwrite: bool) -> PyResult<String> {
        py.detach(|| {
            let staging = woodpile_io::atomic::Staging::prepare(&dir, overwrite).map_err(py_err)?;
            write_run(staging.path(), &self.record()).map_err(py_err)?;
            let done = staging
                .commit(
                    woodpile_io::rundir::RUN_FILES,
                    woodpile_io::atomic::RUN_MARKER,
                )
                .map_err(py_err)?;
            Ok(done.display().to_string())
        })
    }
}

/// Resolves and runs a scenario (TOML text; relative files against `base_dir`), GIL released,
/// Ctrl-C honoured. As `woodpile simulate`, a run whose energy balance is off by more than
/// `defaults::ENERGY_ERROR_FAIL` is refused unless `allow_inaccurate`. The command line's up-front limits apply (more than `limits::MAX_STEPS`
/// steps unless `allow_long`; samples beyond `limits::MAX_OUTPUT_BYTES` unless `allow_large`:
/// the trajectory is held in memory).
#[pyfunction]
#[pyo3(signature = (text, base_dir, name, allow_long=false, allow_large=false, allow_inaccurate=false))]
fn simulate(
    py: Python<'_>,
    text: &str,
    base_dir: PathBuf,
    name: String,
    allow_long: bool,
    allow_large: bool,
    allow_inaccurate: bool,
) -> PyResult<Run> {
    let scenario = Scenario::parse(text).map_err(py_err)?;
    let resolved = resolve(&scenario, &base_dir).map_err(py_err)?;
    woodpile_io::limits::RunSize::estimate(&resolved.settings, resolved.chain.len())
        .check(allow_long, allow_large, true)
        .map_err(py_err)?;
    crate::interrupt::detach_interruptibly(py, || {
        let mut trajectory = Trajectory::default();
        let summary = run_simulation(
            &resolved.chain,
            &resolved.excitation,
            &resolved.settings,
            &mut trajectory,
        )
        .map_err(core_err)?;
        woodpile_io::limits::check_accuracy(&summary.energy, allow_inaccurate).map_err(py_err)?;
        Ok(Run {
            name,
            scenario,
            resolved,
            summary,
            trajectory,
        })
    })
}

/// Reads a run directory written by `woodpile simulate` (or `Run.save`): (scenario name,
/// `summary.json` text, `run.json` text), after checking its arrays (shapes, finite values).
#[pyfunction]
fn load_run(py: Python<'_>, dir: PathBuf) -> PyResult<(String, String, String)> {
    py.detach(|| {
        let info = read_run_info(&dir).map_err(py_err)?;
        read_trajectory(&dir, info.labels.len()).map_err(py_err)?;
        let read = |file: &str| {
            let path = dir.join(file);
            std::fs::read_to_string(&path)
                .map_err(|source| py_err(woodpile_io::Error::Read { path, source }))
        };
        Ok((info.name, read("summary.json")?, read("run.json")?))
    })
}

/// Adds this module's class and functions to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Run>()?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(load_run, m)?)?;
    Ok(())
}
