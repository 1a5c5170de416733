//! Design optimisation (`woodpile.optimize`): the breeder GA as ask/tell, so that Python can
//! evaluate designs anywhere (an executor, Dask).

use crate::errors::{classify, ga_err, py_err, Failure, Kind};
use pyo3::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use woodpile::optimize::{BreederGa, GaState, Ledger};
use woodpile_io::optimize::{Algorithm, Checkpoint, OptimizeConfig, Problem};

/// The problem of a config given as `kind` = "builtin" (a problem name), "toml" or "json"
/// text, with Python's keyword arguments over it (`seed` → `ga.seed`, `objectives` →
/// `ga.objectives` in place of `ga.objective`, `algorithm` → `ga.algorithm`); an NSGA-II
/// problem made accuracy-targeted exactly as `woodpile optimize` does
/// (`OptimizeConfig::accuracy_targeted`: every contact peak within 1e-5 unless the run's
/// integration is stated).
/// An error about a key set by a keyword names the keyword (`objectives[1]`, `algorithm`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn load_problem(
    kind: &str,
    text: &str,
    base_dir: &Path,
    seed: Option<u64>,
    threads: usize,
    objectives: Option<Vec<String>>,
    algorithm: Option<String>,
) -> PyResult<Problem> {
    let mut config = match kind {
        "builtin" => OptimizeConfig::builtin(text).map_err(py_err)?,
        "toml" => OptimizeConfig::parse(text, "problem").map_err(py_err)?,
        "json" => serde_json::from_str(text)
            .map_err(|e| PyErr::from(Failure::new(Kind::Scenario, format!("problem: {e}"))))?,
        other => {
            return Err(Failure::invalid("kind", other, "\"builtin\", \"toml\" or \"json\"").into())
        }
    };
    if seed.is_some() {
        config.ga.seed = seed;
    }
    let by_keyword = (objectives.is_some(), algorithm.is_some());
    if let Some(objectives) = objectives {
        config.ga.objectives = Some(objectives);
        config.ga.objective = None;
    }
    if algorithm.is_some() {
        config.ga.algorithm = algorithm;
    }
    let named = |e| {
        let mut failure = classify(e);
        if by_keyword.0 {
            failure = failure.keyword("ga.objectives", "objectives");
        }
        if by_keyword.1 {
            failure = failure.keyword("ga.algorithm", "algorithm");
        }
        PyErr::from(failure)
    };
    let problem = Problem::new(&config, base_dir, threads).map_err(named)?;
    if problem.algorithm == Algorithm::Breeder {
        // The breeder GA keeps the problem's own settings here: with early stopping the
        // ask/tell path's history differs from `BreederGa::run`'s (see docs/python.md).
        return Ok(problem);
    }
    Problem::new(&config.accuracy_targeted(), base_dir, threads).map_err(named)
}

/// Which search a problem runs, "breeder" or "nsga2" (the problem checked whole, as the
/// sessions' constructors do).
#[pyfunction]
#[pyo3(signature = (kind, text, base_dir, objectives=None, algorithm=None))]
fn study_algorithm(
    kind: &str,
    text: &str,
    base_dir: PathBuf,
    objectives: Option<Vec<String>>,
    algorithm: Option<String>,
) -> PyResult<&'static str> {
    let problem = load_problem(kind, text, &base_dir, None, 1, objectives, algorithm)?;
    Ok(match problem.algorithm {
        Algorithm::Breeder => "breeder",
        Algorithm::Nsga2 => "nsga2",
    })
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
    fn build(problem: Problem) -> PyResult<Self> {
        if problem.algorithm != Algorithm::Breeder {
            return Err(Failure::invalid(
                "ga.algorithm",
                "nsga2",
                "BreederGA runs one objective; for a Pareto front call woodpile.optimize (it returns a ParetoResult)",
            )
            .into());
        }
        // `ga.robust`: the statistic over the `[uncertainty]` samples, as in `woodpile optimize`.
        let objective: Box<dyn woodpile::Objective> = match problem.robust_objective() {
            Some(robust) => Box::new(robust),
            None => Box::new(problem.objective),
        };
        let ga =
            BreederGa::new(problem.space.clone(), objective, problem.settings).map_err(ga_err)?;
        Ok(GaSession {
            config: problem.config.clone(),
            problem,
            ga,
            state: None,
            pending: None,
        })
    }

    fn state(&self) -> PyResult<&GaState> {
        self.state.as_ref().ok_or_else(|| {
            Failure::new(Kind::State, "no generation yet: ask() and tell() first").into()
        })
    }
}

#[pymethods]
impl GaSession {
    /// A session for a config given as `kind` = "builtin" (a problem name), "toml" or "json"
    /// text; `seed` overrides `ga.seed`; `threads` for local evaluation (0 = one per core).
    #[new]
    #[pyo3(signature = (kind, text, base_dir, seed=None, threads=0, objectives=None, algorithm=None))]
    fn new(
        kind: &str,
        text: &str,
        base_dir: PathBuf,
        seed: Option<u64>,
        threads: usize,
        objectives: Option<Vec<String>>,
        algorithm: Option<String>,
    ) -> PyResult<Self> {
        Self::build(load_problem(
            kind, text, &base_dir, seed, threads, objectives, algorithm,
        )?)
    }

    /// The completed config as JSON (what a worker needs to evaluate designs).
    fn config_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.config)
            .map_err(|e| Failure::new(Kind::Run, format!("problem: {e}")).into())
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
        let pending = self.pending.take().ok_or_else(|| {
            PyErr::from(Failure::new(Kind::State, "tell() without a pending ask()"))
        })?;
        let refuse = |pending, failure: Failure, session: &mut Self| {
            session.pending = Some(pending);
            Err(failure.into())
        };
        if designs.len() != objectives.len() {
            let reason = format!("one per design: {} designs were told", designs.len());
            let failure =
                Failure::invalid("objectives", format!("{} values", objectives.len()), reason);
            return refuse(pending, failure, self);
        }
        if let Some((g, _)) = designs.iter().zip(&objectives).find(|(_, v)| v.is_nan()) {
            let failure =
                Failure::invalid("objectives", "NaN", format!("a number for design {g:?}"));
            return refuse(pending, failure, self);
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
            let failure = Failure::invalid(
                "designs",
                format!("{} designs", designs.len()),
                format!("every design of the last ask(); {missing:?} is missing"),
            );
            return refuse(pending, failure, self);
        }
        self.ga
            .record_new(pending.len(), &designs, &objectives, &mut ledger);
        let carried = self
            .state
            .as_ref()
            .map(|s| self.ga.elites(s).to_vec())
            .unwrap_or_default();
        let ga = &self.ga;
        let settled = crate::interrupt::detach_interruptibly(py, || {
            ga.settle(&carried, &pending, &mut ledger).map_err(ga_err)
        });
        let individuals = match settled {
            Ok(individuals) => individuals,
            Err(e) => {
                self.pending = Some(pending);
                return Err(e);
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
        crate::interrupt::detach_interruptibly(py, || {
            self.ga.evaluate_new(&designs).map_err(ga_err)
        })
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

    /// The history, one row per generation: the fields of `woodpile::optimize::GenerationStats`
    /// in their order (Python's `GenerationStats` names them).
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
            .map_err(|e| Failure::new(Kind::Run, format!("checkpoint: {e}")).into())
    }

    /// Continues from a checkpoint JSON (as `state_json` or `woodpile optimize` wrote it) of
    /// the same problem; its checksum and problem are checked.
    fn restore(&mut self, json: &str) -> PyResult<()> {
        let bad =
            |value: &str, reason: &str| PyErr::from(Failure::invalid("checkpoint", value, reason));
        let cp: Checkpoint = serde_json::from_str(json)
            .map_err(|e| bad("(as given)", &format!("not a checkpoint: {e}")))?;
        if cp.checksum != cp.content_checksum() {
            let reason = "its checksum does not match its content (edited or damaged)";
            return Err(bad(&format!("checksum {}", cp.checksum), reason));
        }
        if !cp.config.same_problem(&self.config) {
            return Err(bad(
                "(as given)",
                "a checkpoint of this problem; it was saved for another",
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
        let (outcome, raised) = crate::interrupt::detach_polling(py, || {
            self.ga.run(self.state.take(), &stop, &mut |_| {
                std::ops::ControlFlow::Continue(())
            })
        });
        // Interrupted: the state of the last complete generation is kept, then the exception.
        match (outcome, raised) {
            (Ok(outcome), raised) => {
                self.state = Some(outcome.state);
                raised.map_or(Ok(()), Err)
            }
            (Err(_), Some(raised)) => Err(raised),
            (Err(e), None) => Err(ga_err(e)),
        }
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
            .map_err(|e| PyErr::from(Failure::new(Kind::Run, format!("session cache: {e}"))))?;
        match map.get(&key) {
            Some(s) => s.clone(),
            None => {
                let s = std::sync::Arc::new(GaSession::new(
                    "json",
                    config_json,
                    base_dir.clone(),
                    None,
                    threads,
                    None,
                    None,
                )?);
                map.insert(key, s.clone());
                s
            }
        }
    };
    session.evaluate(py, designs)
}

/// Adds this module's class and functions to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<GaSession>()?;
    m.add_function(wrap_pyfunction!(evaluate_designs, m)?)?;
    m.add_function(wrap_pyfunction!(study_algorithm, m)?)?;
    Ok(())
}
