//! Lattices (`woodpile.lattice`, docs/physics.md §16): a `[lattice]` scenario run once, its
//! per-contact forces as NumPy arrays, its contacts in output order, and its run directory
//! written exactly as `woodpile simulate` writes it.

use crate::errors::{core_err, py_err, Failure, Kind};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use std::path::PathBuf;
use woodpile::ode::LatticeOde;
use woodpile::simulate::{simulate_lattice as run_lattice, LatticeRun as CoreRun};
use woodpile_io::lattice::{
    contacts_json, read_lattice_run, write_lattice_run, LatticeScenario, LatticeSummaryJson,
    ResolvedLattice, LATTICE_RUN_FILES,
};

/// One contact as Python's contacts table takes it: layer_above, rod_above, layer_below,
/// rod_below, x_mm, y_mm.
type ContactRow = (usize, usize, usize, usize, f64, f64);

/// Parses and checks a lattice scenario: the scenario and its resolution.
pub fn parse_and_resolve(text: &str) -> PyResult<(LatticeScenario, ResolvedLattice)> {
    let scenario = LatticeScenario::parse(text, "scenario").map_err(py_err)?;
    let resolved = scenario.resolve().map_err(py_err)?;
    Ok((scenario, resolved))
}

/// The complete lattice scenario (every default written out) as TOML.
pub fn complete_toml(scenario: &LatticeScenario) -> PyResult<String> {
    toml::to_string(&scenario.complete())
        .map_err(|e| Failure::new(Kind::Scenario, format!("scenario: {e}")).into())
}

/// One lattice run: what was run, its per-contact peaks and its samples.
#[pyclass(module = "woodpile._core", frozen)]
struct LatticeRun {
    name: String,
    scenario: LatticeScenario,
    resolved: ResolvedLattice,
    betas: Vec<f64>,
    run: CoreRun,
}

#[pymethods]
impl LatticeRun {
    /// `summary.json` of this run, as JSON text.
    fn summary_json(&self) -> PyResult<String> {
        serde_json::to_string(&LatticeSummaryJson::of(
            &self.name,
            &self.resolved.excitation,
            &self.run,
        ))
        .map_err(|e| Failure::new(Kind::Run, format!("summary.json: {e}")).into())
    }

    /// The scenario as complete TOML.
    fn scenario_toml(&self) -> PyResult<String> {
        complete_toml(&self.scenario)
    }

    /// Scenario name.
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// The contacts in output order (striker, crossings, supports).
    #[getter]
    fn contacts(&self) -> Vec<ContactRow> {
        contacts_json(&self.resolved)
            .into_iter()
            .map(|c| {
                (
                    c.layer_above,
                    c.rod_above,
                    c.layer_below,
                    c.rod_below,
                    c.x_mm,
                    c.y_mm,
                )
            })
            .collect()
    }

    /// β of every contact in output order [N/m^1.5].
    #[getter]
    fn contact_betas(&self) -> Vec<f64> {
        self.betas.clone()
    }

    /// Indices of the supports' contacts, in output order.
    #[getter]
    fn supports(&self) -> Vec<usize> {
        self.run.supports.clone()
    }

    /// Rods per layer, top to bottom.
    #[getter]
    fn rods_per_layer(&self) -> Vec<usize> {
        let l = &self.resolved.lattice;
        (1..=l.layers)
            .map(|k| l.rods.iter().filter(|r| r.layer == k).count())
            .collect()
    }

    /// Total mass of the rods [kg].
    #[getter]
    fn lattice_mass_kg(&self) -> f64 {
        self.resolved.lattice.mass_kg()
    }

    /// Integrator steps taken.
    #[getter]
    fn steps(&self) -> u64 {
        self.run.stats.steps
    }

    /// A displacement drive's actuator at rest: its static position u* [m] (downward; None
    /// without a displacement actuator).
    #[getter]
    fn actuator_rest_m(&self) -> Option<f64> {
        self.run.actuator_rest_m
    }

    /// Sample times [s], shape (S,).
    #[getter]
    fn time_s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.times_s)
    }

    /// Contact forces [N], shape (S, C), columns in output order.
    #[getter]
    fn forces_n<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = &self.run;
        PyArray1::from_slice(py, &r.contact_forces_n).reshape([r.times_s.len(), r.contacts])
    }

    /// Total energy [J], shape (S,).
    #[getter]
    fn total_energy_j<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.energy_j)
    }

    /// Each body's energy [J], shape (S, bodies): the striker or a displacement actuator first,
    /// if any, then the rods (`energy_j.npy`).
    #[getter]
    fn body_energies_j<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = &self.run;
        PyArray1::from_slice(py, &r.body_energies_j).reshape([r.times_s.len(), r.bodies])
    }

    /// The supports' halves of their contacts' potential [J], shape (S,).
    #[getter]
    fn support_energy_j<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.support_energy_j)
    }

    /// Work W of the external forces [J], shape (S,) (zeros without lab physics).
    #[getter]
    fn input_work_j<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let r = &self.run;
        match r.work_j.is_empty() {
            true => PyArray1::from_vec(py, vec![0.0; r.times_s.len()]),
            false => PyArray1::from_slice(py, &r.work_j),
        }
    }

    /// Energy D dissipated [J], shape (S,) (zeros without lab physics).
    #[getter]
    fn dissipated_j<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let r = &self.run;
        match r.dissipated_j.is_empty() {
            true => PyArray1::from_vec(py, vec![0.0; r.times_s.len()]),
            false => PyArray1::from_slice(py, &r.dissipated_j),
        }
    }

    /// Each contact's Hertz potential [J], shape (S, C), columns in output order
    /// (`contact_energy_j.npy`).
    #[getter]
    fn contact_energy_j<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = &self.run;
        PyArray1::from_slice(py, &r.contact_energies_j).reshape([r.times_s.len(), r.contacts])
    }

    /// Each contact's energy dissipated since the start [J], shape (S, C), columns in output
    /// order (`contact_dissipated_j.npy`); None without lab physics.
    #[getter]
    fn contact_dissipated_j<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        let r = &self.run;
        if r.work_j.is_empty() {
            return Ok(None);
        }
        PyArray1::from_slice(py, &r.contact_dissipated_samples_j)
            .reshape([r.times_s.len(), r.contacts])
            .map(Some)
    }

    /// Writes the run directory `dir` exactly as `woodpile simulate --out dir` does (staged, then
    /// moved into place; an earlier run there is replaced only with `overwrite`).
    fn save(&self, py: Python<'_>, dir: PathBuf, overwrite: bool) -> PyResult<String> {
        py.detach(|| {
            let staging = woodpile_io::atomic::Staging::prepare(&dir, overwrite).map_err(py_err)?;
            write_lattice_run(
                staging.path(),
                &self.name,
                &self.scenario,
                &self.resolved,
                &self.betas,
                &self.run,
            )
            .map_err(py_err)?;
            let done = staging
                .commit(LATTICE_RUN_FILES, woodpile_io::atomic::RUN_MARKER)
                .map_err(py_err)?;
            Ok(done.display().to_string())
        })
    }
}

/// Resolves and runs a lattice scenario (TOML text), GIL released, Ctrl-C honoured. The
/// command line's up-front limits apply, and as `woodpile simulate` a run whose energy balance
/// is off by more than `defaults::ENERGY_ERROR_FAIL` is refused unless `allow_inaccurate`.
#[pyfunction]
#[pyo3(signature = (text, name, allow_long=false, allow_large=false, allow_inaccurate=false))]
fn simulate_lattice(
    py: Python<'_>,
    text: &str,
    name: String,
    allow_long: bool,
    allow_large: bool,
    allow_inaccurate: bool,
) -> PyResult<LatticeRun> {
    let (scenario, resolved) = parse_and_resolve(text)?;
    woodpile_io::lattice::run_size(&resolved)
        .check(allow_long, allow_large, true)
        .map_err(py_err)?;
    crate::interrupt::detach_interruptibly(py, || {
        let mut ode = LatticeOde::build(&resolved.lattice, &resolved.excitation, &resolved.lab)
            .map_err(core_err)?;
        let run = run_lattice(&mut ode, &resolved.settings).map_err(core_err)?;
        woodpile_io::limits::check_accuracy(&run.energy, allow_inaccurate).map_err(py_err)?;
        let betas = ode.contact_betas().to_vec();
        Ok(LatticeRun {
            name,
            scenario,
            resolved,
            betas,
            run,
        })
    })
}

/// Reads a lattice run directory (`woodpile simulate` or `LatticeRun.save`): (scenario name,
/// `summary.json` text, `run.json` text), after checking its arrays' shapes.
#[pyfunction]
fn load_lattice_run(py: Python<'_>, dir: PathBuf) -> PyResult<(String, String, String)> {
    py.detach(|| {
        let read = read_lattice_run(&dir).map_err(py_err)?;
        let text = |file: &str| {
            let path = dir.join(file);
            std::fs::read_to_string(&path)
                .map_err(|source| py_err(woodpile_io::Error::Read { path, source }))
        };
        Ok((
            read.run.scenario_name.clone(),
            text("summary.json")?,
            text("run.json")?,
        ))
    })
}

/// Whether a scenario text describes a lattice (has a top-level `lattice` table).
#[pyfunction]
fn is_lattice(text: &str) -> bool {
    woodpile_io::lattice::is_lattice(text)
}

/// Whether a directory holds a lattice run.
#[pyfunction]
fn is_lattice_run(dir: PathBuf) -> bool {
    woodpile_io::lattice::is_lattice_run(&dir)
}

/// Adds this module's class and functions to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<LatticeRun>()?;
    m.add_function(wrap_pyfunction!(simulate_lattice, m)?)?;
    m.add_function(wrap_pyfunction!(load_lattice_run, m)?)?;
    m.add_function(wrap_pyfunction!(is_lattice_run, m)?)?;
    m.add_function(wrap_pyfunction!(is_lattice, m)?)?;
    Ok(())
}
