//! Python bindings of woodpile: the extension module `woodpile._core`, a thin layer over the
//! scenario format and run directories of `woodpile-io` and the physics core. The Python package
//! (`python/woodpile`) builds its API on these functions; every scenario crosses the boundary as
//! TOML text, so Python and the command line read the same files with the same checks.
//!
//! The GIL is released while Rust simulates; [`evaluate`] runs many scenarios on rayon's pool.

use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use woodpile::analysis::{BandStructure, EffectiveMassCurve};
use woodpile::{simulate as run_simulation, RunSummary, Trajectory};
use woodpile_io::rundir::{read_run_info, read_trajectory, write_run, RunRecord, SummaryJson};
use woodpile_io::scenario::{builtin, builtin_names, resolve, Resolved, Scenario};

pyo3::create_exception!(
    _core,
    WoodpileError,
    PyValueError,
    "A bad input: `args` = (message, field, value, reason); field, value and reason are None when the error is not about one key."
);

/// A `woodpile-io` error as a Python exception: bad input → `WoodpileError` (with the key, the
/// value and what would be valid), files → `OSError`, a failed run → `RuntimeError`.
fn py_err(e: woodpile_io::Error) -> PyErr {
    use woodpile_io::Error as E;
    let message = e.to_string();
    let (field, value, reason) = match &e {
        E::Invalid {
            field,
            value,
            reason,
        } => (
            Some(field.clone()),
            Some(value.clone()),
            Some(reason.clone()),
        ),
        E::Field {
            field,
            source:
                woodpile::Error::InvalidParameter {
                    field: inner,
                    value,
                    reason,
                },
        } => (
            Some(format!("{field}.{inner}")),
            Some(value.clone()),
            Some(reason.clone()),
        ),
        E::Model(woodpile::Error::InvalidParameter {
            field,
            value,
            reason,
        }) => (
            Some(field.clone()),
            Some(value.clone()),
            Some(reason.clone()),
        ),
        E::Read { .. } | E::Output { .. } | E::OutputNotEmpty { .. } => {
            return PyOSError::new_err(message)
        }
        _ if e.exit_code() == 1 => return PyRuntimeError::new_err(message),
        _ => (None, None, None),
    };
    WoodpileError::new_err((message, field, value, reason))
}

/// Two NumPy vectors of the same length.
type ArrayPair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

fn core_err(e: woodpile::Error) -> PyErr {
    py_err(woodpile_io::Error::from(e))
}

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
    serde_json::to_string(&scenario).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// A scenario from JSON text (as [`toml_to_json`] writes it) as complete TOML.
#[pyfunction]
fn json_to_toml(json: &str) -> PyResult<String> {
    let scenario: Scenario = serde_json::from_str(json).map_err(|e| {
        WoodpileError::new_err((
            format!("scenario: {e}"),
            None::<String>,
            None::<String>,
            None::<String>,
        ))
    })?;
    Ok(scenario.to_toml())
}

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
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))
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
            let staging = woodpile_io::atomic::Staging::prepare(&dir, overwrite).map_err(|e| {
                match e {
                    // The command line's flags by their Python names.
                    woodpile_io::Error::Invalid { value, reason, .. } => {
                        py_err(woodpile_io::Error::Invalid {
                            field: "directory".into(),
                            value,
                            reason: reason
                                .replace("--overwrite", "overwrite=True")
                                .replace("--out", "directory"),
                        })
                    }
                    other => py_err(other),
                }
            })?;
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

/// Resolves and runs a scenario (TOML text; relative files against `base_dir`), GIL released.
#[pyfunction]
fn simulate(py: Python<'_>, text: &str, base_dir: PathBuf, name: String) -> PyResult<Run> {
    let scenario = Scenario::parse(text).map_err(py_err)?;
    let resolved = resolve(&scenario, &base_dir).map_err(py_err)?;
    py.detach(|| {
        let mut trajectory = Trajectory::default();
        let summary = run_simulation(
            &resolved.chain,
            &resolved.excitation,
            &resolved.settings,
            &mut trajectory,
        )
        .map_err(core_err)?;
        Ok(Run {
            name,
            scenario,
            resolved,
            summary,
            trajectory,
        })
    })
}

/// Runs many scenarios in parallel on `threads` threads (default: one per core), GIL released;
/// one JSON `RunSummary` (or "error: …" with the message) per scenario, in order. Scenarios
/// that only need figures of merit (`run.sample_interval_s` = `run.duration_s`) advance together
/// in SIMD lanes (`woodpile::lanes`), with the same results as one by one.
#[pyfunction]
#[pyo3(signature = (texts, base_dir, threads=None))]
fn evaluate(
    py: Python<'_>,
    texts: Vec<String>,
    base_dir: PathBuf,
    threads: Option<usize>,
) -> PyResult<Vec<String>> {
    py.detach(|| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.unwrap_or(0))
            .build()
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(pool.install(|| {
            let resolved: Vec<Result<Resolved, woodpile_io::Error>> = texts
                .par_iter()
                .map(|t| Scenario::parse(t).and_then(|s| resolve(&s, &base_dir)))
                .collect();
            // One call: the lanes of every thread share one queue of runs.
            let jobs: Vec<woodpile::Job<'_>> = resolved
                .iter()
                .filter_map(|r| r.as_ref().ok())
                .map(|r| woodpile::Job {
                    chain: &r.chain,
                    excitation: &r.excitation,
                    settings: &r.settings,
                })
                .collect();
            let mut runs =
                woodpile::simulate_many(&jobs, woodpile::LaneWidth::detect()).into_iter();
            resolved
                .iter()
                .map(|r| match r {
                    Err(e) => format!("error: {e}"),
                    Ok(_) => match runs.next().expect("one result per job") {
                        Ok(summary) => serde_json::to_string(&summary).unwrap_or_else(|e| {
                            format!("error: cannot serialise the summary: {e}")
                        }),
                        Err(e) => format!("error: {}", woodpile_io::Error::from(e)),
                    },
                })
                .collect()
        }))
    })
}

/// Reads a run directory written by `woodpile simulate` (or `Run.save`).
#[pyfunction]
fn load_run(py: Python<'_>, dir: PathBuf) -> PyResult<(String, String, String)> {
    py.detach(|| {
        let info = read_run_info(&dir).map_err(py_err)?;
        // Checks the arrays as well (shapes, finite values).
        read_trajectory(&dir, info.labels.len()).map_err(py_err)?;
        let summary = std::fs::read_to_string(dir.join("summary.json"))
            .map_err(|e| PyOSError::new_err(format!("{}: {e}", dir.display())))?;
        let run_json = std::fs::read_to_string(dir.join("run.json"))
            .map_err(|e| PyOSError::new_err(format!("{}: {e}", dir.display())))?;
        Ok((info.name, summary, run_json))
    })
}

/// The paper's Table 1 cell of a rod length, or a rod's cell from beam theory: (primary mass
/// [kg], resonator masses [kg], resonator stiffnesses [N/m]).
#[pyfunction]
#[pyo3(signature = (length_mm, diameter_mm=None, material=None, modes=None))]
fn cell(
    length_mm: f64,
    diameter_mm: Option<f64>,
    material: Option<String>,
    modes: Option<usize>,
) -> PyResult<(f64, Vec<f64>, Vec<f64>)> {
    let table1 = length_mm.fract() == 0.0
        && diameter_mm.is_none()
        && material.is_none()
        && modes.is_none()
        && woodpile::TABLE1_LENGTHS_MM.contains(&(length_mm as u32));
    let cell = if table1 {
        woodpile::UnitCell::table1(length_mm as u32).map_err(core_err)?
    } else {
        let request = woodpile_io::cells::RodRequest {
            length_mm,
            diameter_mm: diameter_mm.unwrap_or(woodpile::defaults::ROD_DIAMETER_MM),
            inner_diameter_mm: None,
            material: material.unwrap_or_else(|| woodpile::defaults::ELEMENT_MATERIAL.into()),
            modes,
            reduction: woodpile_io::scenario::ReductionSpec::PoleZero,
        };
        let d = woodpile_io::cells::derive(&request, &|k: &str| k.to_string()).map_err(py_err)?;
        return Ok((
            d.primary_mass_g * 1e-3,
            d.resonators.iter().map(|r| r.mass_g * 1e-3).collect(),
            d.resonators
                .iter()
                .map(|r| r.stiffness_kn_per_mm * 1e6)
                .collect(),
        ));
    };
    Ok((
        cell.primary_mass_kg,
        cell.resonators.iter().map(|r| r.mass_kg).collect(),
        cell.resonators
            .iter()
            .map(|r| r.stiffness_n_per_m)
            .collect(),
    ))
}

fn unit_cell(
    primary_kg: f64,
    masses_kg: &[f64],
    stiffnesses: &[f64],
) -> PyResult<woodpile::UnitCell> {
    let resonators = masses_kg
        .iter()
        .zip(stiffnesses)
        .map(|(&mass_kg, &stiffness_n_per_m)| woodpile::Resonator {
            mass_kg,
            stiffness_n_per_m,
        })
        .collect();
    woodpile::UnitCell::new(primary_kg, resonators).map_err(core_err)
}

/// M_eff(2πf)/M_total of a cell at `frequencies_hz` (real and imaginary parts; the resonators
/// damped at `ratio`).
#[pyfunction]
fn effective_mass<'py>(
    py: Python<'py>,
    primary_kg: f64,
    masses_kg: Vec<f64>,
    stiffnesses: Vec<f64>,
    frequencies_hz: Vec<f64>,
    ratio: f64,
) -> PyResult<ArrayPair<'py>> {
    let cell = unit_cell(primary_kg, &masses_kg, &stiffnesses)?;
    let c = EffectiveMassCurve::damped(&cell, &frequencies_hz, ratio).map_err(core_err)?;
    Ok((
        PyArray1::from_vec(py, c.normalised_mass),
        PyArray1::from_vec(py, c.normalised_loss),
    ))
}

/// Pass bands and gaps [Hz] of a homogeneous chain of a cell with contact coefficient β under a
/// static force F_p: (pass bands, gaps), each a list of (lower, upper); an open gap's upper edge
/// is infinite.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn band_gaps(
    primary_kg: f64,
    masses_kg: Vec<f64>,
    stiffnesses: Vec<f64>,
    beta: f64,
    precompression_n: f64,
) -> PyResult<(Vec<(f64, f64)>, Vec<(f64, f64)>)> {
    let cell = unit_cell(primary_kg, &masses_kg, &stiffnesses)?;
    let b = BandStructure::homogeneous(&cell, beta, precompression_n).map_err(core_err)?;
    Ok((b.pass_bands_hz, b.gaps_hz))
}

/// One-sided spectrum of a uniformly sampled signal: (frequencies [Hz], values). `scaling`:
/// "fourier" (|F̂(f)| in unit·s, independent of the record length for a transient) or
/// "amplitude" (the sine amplitude, for steady signals).
#[pyfunction]
#[pyo3(signature = (signal, sample_interval_s, scaling = "fourier"))]
fn spectrum<'py>(
    py: Python<'py>,
    signal: Vec<f64>,
    sample_interval_s: f64,
    scaling: &str,
) -> PyResult<ArrayPair<'py>> {
    let scaling = match scaling {
        "fourier" => woodpile::analysis::Scaling::FourierMagnitude,
        "amplitude" => woodpile::analysis::Scaling::Amplitude,
        other => {
            return Err(py_err(woodpile_io::Error::invalid(
                "scaling",
                other,
                "\"fourier\" (Fourier-transform magnitude, for transients) or \"amplitude\" (sine amplitude, for steady signals)",
            )))
        }
    };
    let settings = woodpile::analysis::SpectrumSettings {
        scaling,
        ..Default::default()
    };
    let s = woodpile::Spectrum::of(&signal, sample_interval_s, &settings).map_err(core_err)?;
    Ok((
        PyArray1::from_vec(py, s.frequencies_hz),
        PyArray1::from_vec(py, s.amplitudes),
    ))
}

// ---------------------------------------------------------------------------------------------
// The breeder GA as ask/tell, so that Python can evaluate designs anywhere (an executor, Dask).

use std::collections::HashMap;
use woodpile::optimize::{BreederGa, GaState, Ledger};
use woodpile_io::optimize::{optimize_error, Checkpoint, OptimizeConfig, Problem};

fn ga_err(e: woodpile::optimize::OptimizeError) -> PyErr {
    py_err(optimize_error(e))
}

/// One optimisation: the problem of a config and the GA's state between generations.
#[pyclass(module = "woodpile._core")]
struct GaSession {
    config: OptimizeConfig,
    problem: Problem,
    ga: BreederGa,
    state: Option<GaState>,
    /// The designs of the last `ask` (all children, duplicates and cached ones included).
    pending: Option<Vec<Vec<u8>>>,
}

impl GaSession {
    fn build(config: OptimizeConfig, base_dir: &Path, threads: usize) -> PyResult<Self> {
        let problem = Problem::new(&config, base_dir, threads).map_err(py_err)?;
        let ga = BreederGa::new(
            problem.space.clone(),
            Box::new(problem.objective),
            problem.settings,
        )
        .map_err(ga_err)?;
        Ok(GaSession {
            config: problem.config.clone(),
            problem,
            ga,
            state: None,
            pending: None,
        })
    }

    fn state(&self) -> PyResult<&GaState> {
        self.state
            .as_ref()
            .ok_or_else(|| PyRuntimeError::new_err("no generation yet: ask() and tell() first"))
    }
}

#[pymethods]
impl GaSession {
    /// A session for a config given as `kind` = "builtin" (a problem name), "toml" or "json"
    /// text; `seed` overrides `ga.seed`; `threads` for local evaluation (0 = one per core).
    #[new]
    #[pyo3(signature = (kind, text, base_dir, seed=None, threads=0))]
    fn new(
        kind: &str,
        text: &str,
        base_dir: PathBuf,
        seed: Option<u64>,
        threads: usize,
    ) -> PyResult<Self> {
        let mut config = match kind {
            "builtin" => OptimizeConfig::builtin(text).map_err(py_err)?,
            "toml" => OptimizeConfig::parse(text, "problem").map_err(py_err)?,
            "json" => serde_json::from_str(text).map_err(|e| {
                WoodpileError::new_err((
                    format!("problem: {e}"),
                    None::<String>,
                    None::<String>,
                    None::<String>,
                ))
            })?,
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown config kind {other}"
                )))
            }
        };
        if seed.is_some() {
            config.ga.seed = seed;
        }
        Self::build(config, &base_dir, threads)
    }

    /// The completed config as JSON (what a worker needs to evaluate designs).
    fn config_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.config).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// Ask: the designs of the next generation to simulate first (with the cache, the
    /// distinct ones it holds no value for, in order of first appearance; catalogue indices,
    /// top to bottom).
    fn ask(&mut self) -> Vec<Vec<u8>> {
        let designs = match &self.state {
            None => self.ga.initial_designs(),
            Some(s) => self.ga.offspring(s),
        };
        let fresh = Ledger::default();
        let ledger = self.state.as_ref().map_or(&fresh, |s| &s.ledger);
        let new = self
            .ga
            .new_designs(&designs, ledger)
            .into_iter()
            .cloned()
            .collect();
        self.pending = Some(designs);
        new
    }

    /// Tell: the values `evaluate` gives the designs `ask` returned; completes the generation
    /// (with screening, first simulating here, GIL released, the designs whose rank needs a
    /// value at the run's settings).
    fn tell(
        &mut self,
        py: Python<'_>,
        designs: Vec<Vec<u8>>,
        objectives: Vec<f64>,
        elapsed_s: f64,
    ) -> PyResult<()> {
        let pending = self
            .pending
            .take()
            .ok_or_else(|| PyRuntimeError::new_err("tell() without a pending ask()"))?;
        let refuse = |pending, message: String, session: &mut Self| {
            session.pending = Some(pending);
            Err(PyValueError::new_err(message))
        };
        if designs.len() != objectives.len() {
            let message = format!(
                "{} designs but {} objectives",
                designs.len(),
                objectives.len()
            );
            return refuse(pending, message, self);
        }
        if let Some((g, _)) = designs.iter().zip(&objectives).find(|(_, v)| v.is_nan()) {
            return refuse(pending, format!("objective of design {g:?} is NaN"), self);
        }
        let mut ledger = self
            .state
            .as_ref()
            .map(|s| s.ledger.clone())
            .unwrap_or_default();
        let told: std::collections::HashSet<&Vec<u8>> = designs.iter().collect();
        let known = |g: &Vec<u8>| {
            told.contains(g) || ledger.cache.contains_key(g) || ledger.screened.contains_key(g)
        };
        if let Some(missing) = pending.iter().find(|g| !known(g)) {
            let message = format!("design {missing:?} of the last ask() was not told");
            return refuse(pending, message, self);
        }
        self.ga
            .record_new(pending.len(), &designs, &objectives, &mut ledger);
        let carried = self
            .state
            .as_ref()
            .map(|s| self.ga.elites(s).to_vec())
            .unwrap_or_default();
        let ga = &self.ga;
        let settled = py.detach(|| ga.settle(&carried, &pending, &mut ledger));
        let individuals = match settled {
            Ok(individuals) => individuals,
            Err(e) => {
                self.pending = Some(pending);
                return Err(ga_err(e));
            }
        };
        match self.state.as_mut() {
            None => self.state = Some(self.ga.start(individuals, ledger, elapsed_s)),
            Some(state) => self.ga.advance(state, individuals, ledger, elapsed_s),
        }
        Ok(())
    }

    /// First values of designs, simulated here in parallel (GIL released): screened with
    /// `ga.screen_peak_tolerance`, at the run's settings otherwise.
    fn evaluate(&self, py: Python<'_>, designs: Vec<Vec<u8>>) -> PyResult<Vec<f64>> {
        py.detach(|| self.ga.evaluate_new(&designs).map_err(ga_err))
    }

    /// Why the GA stops now ("generation-limit" or "stalled"), or None to go on.
    fn stop_reason(&self) -> Option<&'static str> {
        let state = self.state.as_ref()?;
        self.ga.stop_reason(state).map(|r| match r {
            woodpile::optimize::StopReason::GenerationLimit => "generation-limit",
            woodpile::optimize::StopReason::Stalled => "stalled",
            _ => "stopped",
        })
    }

    /// Generations completed (None before the first tell).
    fn generation(&self) -> Option<usize> {
        self.state.as_ref().map(|s| s.generation)
    }

    /// (best design, its objective, its element labels).
    fn best(&self) -> PyResult<(Vec<u8>, f64, Vec<String>)> {
        let b = self.state()?.best();
        Ok((
            b.genome.clone(),
            b.objective,
            self.problem.space.labels(&b.genome),
        ))
    }

    /// The history: (generation, best, mean, worst, evaluations, screenings, cache_hits,
    /// elapsed_s) rows.
    #[allow(clippy::type_complexity)]
    fn history(&self) -> PyResult<Vec<(usize, f64, f64, f64, u64, u64, u64, f64)>> {
        Ok(self
            .state()?
            .history
            .iter()
            .map(|h| {
                (
                    h.generation,
                    h.best,
                    h.mean,
                    h.worst,
                    h.evaluations,
                    h.screenings,
                    h.cache_hits,
                    h.elapsed_s,
                )
            })
            .collect())
    }

    /// The scenario of a design, as complete TOML.
    fn scenario_toml(&self, design: Vec<u8>) -> String {
        self.problem.scenario(&design, None).to_toml()
    }

    /// The state as the command line's checkpoint JSON (None before the first tell).
    fn state_json(&self) -> PyResult<Option<String>> {
        self.state
            .as_ref()
            .map(|s| serde_json::to_string(&Checkpoint::new(&self.config, s)))
            .transpose()
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// Continues from a checkpoint JSON (as `state_json` or `woodpile optimize` wrote it) of
    /// the same problem; its checksum and problem are checked.
    fn restore(&mut self, json: &str) -> PyResult<()> {
        let cp: Checkpoint = serde_json::from_str(json)
            .map_err(|e| PyValueError::new_err(format!("checkpoint: {e}")))?;
        if cp.checksum != cp.content_checksum() {
            return Err(PyValueError::new_err(
                "checkpoint: checksum mismatch (edited or damaged)",
            ));
        }
        if !cp.config.same_problem(&self.config) {
            return Err(PyValueError::new_err(
                "checkpoint: saved for a different problem",
            ));
        }
        let state = cp.into_state();
        self.ga.check_state(&state).map_err(ga_err)?;
        self.state = Some(state);
        self.pending = None;
        Ok(())
    }

    /// Runs the whole GA here, exactly as `woodpile optimize` does (BreederGa::run), GIL
    /// released: the reference the ask/tell loop must reproduce.
    fn run_to_end(&mut self, py: Python<'_>) -> PyResult<()> {
        let stop = std::sync::atomic::AtomicBool::new(false);
        let outcome = py
            .detach(|| {
                self.ga.run(self.state.take(), &stop, &mut |_| {
                    std::ops::ControlFlow::Continue(())
                })
            })
            .map_err(ga_err)?;
        self.state = Some(outcome.state);
        Ok(())
    }
}

/// Objective values of designs of a problem (config JSON), for a worker process; sessions are
/// kept per config so a worker builds each problem once.
#[pyfunction]
fn evaluate_designs(
    py: Python<'_>,
    config_json: &str,
    base_dir: PathBuf,
    designs: Vec<Vec<u8>>,
    threads: usize,
) -> PyResult<Vec<f64>> {
    use std::sync::{Mutex, OnceLock};
    static SESSIONS: OnceLock<Mutex<HashMap<String, std::sync::Arc<GaSession>>>> = OnceLock::new();
    let sessions = SESSIONS.get_or_init(|| Mutex::new(HashMap::new()));
    let key = format!("{}\u{0}{}\u{0}{threads}", base_dir.display(), config_json);
    let session = {
        let mut map = sessions
            .lock()
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        match map.get(&key) {
            Some(s) => s.clone(),
            None => {
                let s = std::sync::Arc::new(GaSession::new(
                    "json",
                    config_json,
                    base_dir.clone(),
                    None,
                    threads,
                )?);
                map.insert(key, s.clone());
                s
            }
        }
    };
    session.evaluate(py, designs)
}

/// The transmission spectrum of a scenario's preloaded chain (docs/physics.md §15), GIL
/// released: ((frequencies [Hz], T), T [dB], `transmission.json` as JSON text).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn transmission<'py>(
    py: Python<'py>,
    text: &str,
    base_dir: PathBuf,
    name: &str,
    start_hz: f64,
    end_hz: f64,
    resolution_hz: f64,
    relative_amplitude: f64,
    threshold_db: f64,
) -> PyResult<(ArrayPair<'py>, Bound<'py, PyArray1<f64>>, String)> {
    let scenario = Scenario::parse(text).map_err(py_err)?;
    let resolved = resolve(&scenario, &base_dir).map_err(py_err)?;
    let settings = woodpile::analysis::TransmissionSettings {
        start_hz,
        end_hz,
        resolution_hz,
        relative_amplitude,
        method: resolved.settings.method,
        ..woodpile::analysis::TransmissionSettings::standard()
    };
    let (t, record) = py.detach(|| {
        let t = woodpile::analysis::transmission(&resolved.chain, &settings).map_err(core_err)?;
        let record =
            woodpile_io::transmission::TransmissionJson::new(name, &t, &settings, threshold_db);
        Ok::<_, PyErr>((t, record))
    })?;
    let json =
        serde_json::to_string(&record).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok((
        (
            PyArray1::from_vec(py, t.frequencies_hz),
            PyArray1::from_vec(py, t.transmission),
        ),
        PyArray1::from_vec(py, t.transmission_db),
        json,
    ))
}

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("WoodpileError", m.py().get_type::<WoodpileError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Run>()?;
    m.add_class::<GaSession>()?;
    m.add_function(wrap_pyfunction!(evaluate_designs, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_scenarios, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_toml, m)?)?;
    m.add_function(wrap_pyfunction!(complete_toml, m)?)?;
    m.add_function(wrap_pyfunction!(toml_to_json, m)?)?;
    m.add_function(wrap_pyfunction!(json_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(load_run, m)?)?;
    m.add_function(wrap_pyfunction!(cell, m)?)?;
    m.add_function(wrap_pyfunction!(effective_mass, m)?)?;
    m.add_function(wrap_pyfunction!(band_gaps, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(transmission, m)?)?;
    Ok(())
}
