//! Pareto studies (`woodpile.optimize` with several objectives, `woodpile.pymoo`): NSGA-II run
//! exactly as `woodpile optimize` runs it, its front and history, and a population's objectives
//! and constraints evaluated in one call into the SIMD lanes for other optimisers.

use crate::errors::{classify, ga_err, py_err, Failure, Kind};
use crate::optimize::load_problem;
use pyo3::prelude::*;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use woodpile::optimize::{GenomeSpace, Nsga2, Nsga2State, StopReason};
use woodpile_io::lattice_study::{
    checkpoint_json, restore_checkpoint, LatticeStudy, LatticeStudyConfig,
};
use woodpile_io::optimize::{Algorithm, Problem};
use woodpile_io::pareto::{pareto_csv, ParetoCheckpoint};

/// (genome, objective values, element labels) of a design of the front.
type FrontRow = (Vec<u8>, Vec<f64>, Vec<String>);

/// One NSGA-II study: its problem and its state after the last complete generation.
#[pyclass(module = "woodpile._core")]
struct ParetoSession {
    problem: Problem,
    ga: Nsga2,
    state: Option<Nsga2State>,
    reason: Option<StopReason>,
}

impl ParetoSession {
    fn state(&self) -> PyResult<&Nsga2State> {
        self.state
            .as_ref()
            .ok_or_else(|| Failure::new(Kind::State, "no generation yet: run() first").into())
    }
}

/// Writes `json` to `path` atomically (a temporary file in the same folder renamed into place).
fn write_file(path: &Path, json: &[u8]) -> Result<(), woodpile_io::Error> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("checkpoint.json");
    woodpile_io::atomic::write_atomic(dir, name, json)
}

#[pymethods]
impl ParetoSession {
    /// A study of a config (`kind`, `text` as for `GaSession`) with the keyword arguments of
    /// `woodpile.optimize` over it; refuses a problem that is not NSGA-II's.
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
        let problem = load_problem(kind, text, &base_dir, seed, threads, objectives, algorithm)?;
        if problem.algorithm != Algorithm::Nsga2 {
            return Err(Failure::invalid(
                "algorithm",
                "breeder",
                "a Pareto study runs NSGA-II: give algorithm=\"nsga2\" or two or more objectives",
            )
            .into());
        }
        let ga = Nsga2::new(
            problem.space.clone(),
            problem.objectives.clone(),
            problem.nsga2.clone(),
        )
        .map_err(ga_err)?;
        Ok(ParetoSession {
            problem,
            ga,
            state: None,
            reason: None,
        })
    }

    /// The completed config as JSON.
    fn config_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.problem.config)
            .map_err(|e| Failure::new(Kind::Run, format!("problem: {e}")).into())
    }

    /// (name, unit) of each objective, in column order.
    fn objectives(&self) -> Vec<(String, String)> {
        self.problem
            .objectives
            .iter()
            .map(|f| (f.as_str().to_string(), f.unit().to_string()))
            .collect()
    }

    /// The seed.
    fn seed(&self) -> u64 {
        self.problem.nsga2.seed
    }

    /// Runs NSGA-II from the current state (or a fresh start) to its generation or stall
    /// limit exactly as `woodpile optimize` does (`Nsga2::run`), GIL released; with
    /// `checkpoint`, its state is written there after every generation (the command line's
    /// NSGA-II checkpoint). Ctrl-C keeps the last complete generation, then raises.
    #[pyo3(signature = (checkpoint=None))]
    fn run(&mut self, py: Python<'_>, checkpoint: Option<PathBuf>) -> PyResult<()> {
        let config = &self.problem.config;
        let initial = self.state.take();
        let (state, result) = run_nsga2(py, &self.ga, initial, checkpoint, |path, s| {
            serde_json::to_vec(&ParetoCheckpoint::new(config, s))
                .map_err(|e| woodpile_io::atomic::io_err(path)(std::io::Error::other(e)))
        });
        if let Some((state, reason)) = state {
            self.state = Some(state);
            self.reason = Some(reason);
        }
        result
    }

    /// Why the study stopped ("generation-limit", "stalled", "interrupted"...), None before.
    fn stop_reason(&self) -> Option<&'static str> {
        self.reason.map(|r| match r {
            StopReason::GenerationLimit => "generation-limit",
            StopReason::Stalled => "stalled",
            StopReason::Interrupted => "interrupted",
            _ => "stopped",
        })
    }

    /// Generations completed (None before the first).
    fn generation(&self) -> Option<usize> {
        self.state.as_ref().map(|s| s.generation)
    }

    /// The feasible non-dominated designs, in the rows of `pareto.csv`.
    fn front(&self) -> PyResult<Vec<FrontRow>> {
        Ok(self
            .state()?
            .front()
            .into_iter()
            .map(|i| {
                (
                    i.genome.clone(),
                    i.objectives.clone(),
                    self.problem.space.labels(&i.genome),
                )
            })
            .collect())
    }

    /// `pareto.csv` of the front, as `woodpile optimize` writes it.
    fn pareto_csv(&self) -> PyResult<String> {
        Ok(pareto_csv(&self.problem, &self.state()?.front()))
    }

    /// `history.csv` as `woodpile optimize` writes it.
    fn history_csv(&self) -> PyResult<String> {
        Ok(woodpile_io::pareto::history_csv(&self.state()?.history))
    }

    /// The hypervolume's reference point (one value per objective, SI units).
    fn reference_point(&self) -> PyResult<Vec<f64>> {
        Ok(self.state()?.reference_point.clone())
    }

    /// The scenario of a design, as complete TOML.
    fn scenario_toml(&self, design: Vec<u8>) -> String {
        self.problem.scenario(&design, None).to_toml()
    }

    /// The state as the command line's NSGA-II checkpoint JSON (None before the first
    /// generation).
    fn state_json(&self) -> PyResult<Option<String>> {
        self.state
            .as_ref()
            .map(|s| serde_json::to_string(&ParetoCheckpoint::new(&self.problem.config, s)))
            .transpose()
            .map_err(|e| Failure::new(Kind::Run, format!("checkpoint: {e}")).into())
    }

    /// Continues from an NSGA-II checkpoint JSON of the same problem (checksum and problem
    /// checked).
    fn restore(&mut self, json: &str) -> PyResult<()> {
        let bad =
            |value: &str, reason: &str| PyErr::from(Failure::invalid("checkpoint", value, reason));
        let cp: ParetoCheckpoint = serde_json::from_str(json)
            .map_err(|e| bad("(as given)", &format!("not an NSGA-II checkpoint: {e}")))?;
        if cp.checksum != cp.content_checksum() {
            let reason = "its checksum does not match its content (edited or damaged)";
            return Err(bad(&format!("checksum {}", cp.checksum), reason));
        }
        if !cp.config.same_problem(&self.problem.config) {
            return Err(bad(
                "(as given)",
                "a checkpoint of this problem; it was saved for another",
            ));
        }
        let state = cp.into_state();
        self.ga.check_state(&state).map_err(ga_err)?;
        self.state = Some(state);
        self.reason = None;
        Ok(())
    }

    /// (positions, catalogue entries, fixed (position, index) pairs): the integer box of the
    /// designs.
    fn bounds(&self) -> (usize, usize, Vec<(usize, usize)>) {
        let space = &self.problem.space;
        (
            space.positions,
            space.catalogue.len(),
            space.constraints.fixed.clone(),
        )
    }

    /// The config keys of the constraints `evaluate` returns, in column order.
    fn constraint_names(&self) -> Vec<String> {
        let c = &self.problem.space.constraints;
        let mut names = Vec::new();
        if c.max_total_mass_kg.is_some() {
            names.push("design.constraints.max_total_mass_g".to_string());
        }
        if c.max_stack_height_m.is_some() {
            names.push("design.constraints.max_stack_height_mm".to_string());
        }
        for (k, _) in c.max_count.iter().enumerate() {
            names.push(format!("design.constraints.max_count[{k}]"));
        }
        if c.max_contact_pressure_pa.is_some() {
            names.push("design.constraints.max_contact_pressure_pa".to_string());
        }
        names
    }

    /// The objectives and constraints (g ≤ 0 where met, in the order of `constraint_names`:
    /// relative excess of mass and height, copies beyond a cap, the relative excess of the worst
    /// contact pressure, clipped at 0 as NSGA-II's constraint domination uses it) of designs,
    /// simulated in one call into the SIMD lanes (GIL released; no cache).
    #[allow(clippy::type_complexity)]
    fn evaluate(
        &self,
        py: Python<'_>,
        designs: Vec<Vec<u8>>,
    ) -> PyResult<(Vec<Vec<f64>>, Vec<Vec<f64>>)> {
        let space = &self.problem.space;
        if let Some((k, g)) = designs.iter().enumerate().find(|(_, g)| {
            g.len() != space.positions || g.iter().any(|&x| usize::from(x) >= space.catalogue.len())
        }) {
            return Err(Failure::invalid(
                format!("designs[{k}]"),
                format!("{g:?}"),
                format!(
                    "{} catalogue indices, each 0 ≤ index < {}",
                    space.positions,
                    space.catalogue.len()
                ),
            )
            .into());
        }
        let ga = &self.ga;
        let individuals = crate::interrupt::detach_interruptibly(py, || {
            ga.evaluate_designs(&designs).map_err(ga_err)
        })?;
        let c = &space.constraints;
        let constraints = individuals
            .iter()
            .map(|ind| {
                let g = &ind.genome;
                let mut row = Vec::new();
                if let Some(max) = c.max_total_mass_kg {
                    row.push(space.mass_kg(g) / max - 1.0);
                }
                if let Some(max) = c.max_stack_height_m {
                    row.push(space.height_m(g) / max - 1.0);
                }
                for &(entry, cap) in &c.max_count {
                    let n = g.iter().filter(|&&x| usize::from(x) == entry).count();
                    row.push(n as f64 - cap as f64);
                }
                if c.max_contact_pressure_pa.is_some() {
                    row.push(ind.violation);
                }
                row
            })
            .collect();
        let objectives = individuals.into_iter().map(|i| i.objectives).collect();
        Ok((objectives, constraints))
    }
}

/// One lattice design study (a config with a `[lattice]` table): NSGA-II over rod lengths per
/// layer and the pitch, exactly as `woodpile optimize` runs it; the same methods as
/// [`ParetoSession`] for `woodpile.ParetoResult`.
#[pyclass(module = "woodpile._core")]
struct LatticeParetoSession {
    study: LatticeStudy,
    state: Option<Nsga2State>,
    reason: Option<StopReason>,
}

impl LatticeParetoSession {
    fn state(&self) -> PyResult<&Nsga2State> {
        self.state
            .as_ref()
            .ok_or_else(|| Failure::new(Kind::State, "no generation yet: run() first").into())
    }
}

#[pymethods]
impl LatticeParetoSession {
    /// A study of a lattice config (`kind` "toml" or "json" text) with `woodpile.optimize`'s
    /// keyword arguments.
    #[new]
    #[pyo3(signature = (kind, text, seed=None, threads=0, objectives=None))]
    fn new(
        kind: &str,
        text: &str,
        seed: Option<u64>,
        threads: usize,
        objectives: Option<Vec<String>>,
    ) -> PyResult<Self> {
        let mut config = if kind == "json" {
            serde_json::from_str::<LatticeStudyConfig>(text).map_err(|e| {
                PyErr::from(Failure::new(Kind::Scenario, format!("lattice study: {e}")))
            })?
        } else {
            LatticeStudyConfig::parse(text, "config").map_err(py_err)?
        };
        if let Some(seed) = seed {
            config.ga.seed = Some(seed);
        }
        if let Some(o) = objectives {
            config.ga.objectives = Some(o);
        }
        let study = config
            .resolve(threads)
            .map_err(|e| classify(e).keyword("ga.objectives", "objectives"))?;
        Ok(LatticeParetoSession {
            study,
            state: None,
            reason: None,
        })
    }

    /// The completed config as JSON.
    fn config_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.study.config)
            .map_err(|e| Failure::new(Kind::Run, format!("problem: {e}")).into())
    }

    /// (name, unit) of each objective, in column order.
    fn objectives(&self) -> Vec<(String, String)> {
        self.study
            .ga
            .designs()
            .objectives()
            .iter()
            .map(|f| (f.as_str().to_string(), f.unit().to_string()))
            .collect()
    }

    /// The seed.
    fn seed(&self) -> u64 {
        self.study.ga.settings().seed
    }

    /// Runs NSGA-II from the current state (or a fresh start), GIL released; with
    /// `checkpoint`, its state is written there after every generation (the command line's
    /// lattice checkpoint). Ctrl-C keeps the last complete generation, then raises.
    #[pyo3(signature = (checkpoint=None))]
    fn run(&mut self, py: Python<'_>, checkpoint: Option<PathBuf>) -> PyResult<()> {
        let initial = self.state.take();
        let config = &self.study.config;
        let (state, result) = run_nsga2(py, &self.study.ga, initial, checkpoint, |_, s| {
            Ok(checkpoint_json(config, s))
        });
        if let Some((state, reason)) = state {
            self.state = Some(state);
            self.reason = Some(reason);
        }
        result
    }

    /// Continues from a checkpoint's text (`run(checkpoint=…)` or `woodpile optimize`'s).
    fn restore(&mut self, json: &str) -> PyResult<()> {
        let state =
            restore_checkpoint(json, Path::new("checkpoint"), &self.study.config).map_err(|e| {
                PyErr::from(Failure::invalid(
                    "checkpoint",
                    "(as given)",
                    format!("not a checkpoint of this lattice study: {e}"),
                ))
            })?;
        self.study.ga.check_state(&state).map_err(ga_err)?;
        self.state = Some(state);
        self.reason = None;
        Ok(())
    }

    /// Why the study stopped, None before.
    fn stop_reason(&self) -> Option<&'static str> {
        self.reason.map(|r| match r {
            StopReason::GenerationLimit => "generation-limit",
            StopReason::Stalled => "stalled",
            StopReason::Interrupted => "interrupted",
            _ => "stopped",
        })
    }

    /// The feasible non-dominated designs, in the rows of `pareto.csv`: (genes, objectives,
    /// each layer's rod length in mm then the pitch in mm, as text).
    fn front(&self) -> PyResult<Vec<FrontRow>> {
        Ok(self
            .state()?
            .front()
            .into_iter()
            .map(|i| {
                let s = self.study.scenario(&i.genome);
                let mut labels: Vec<String> = s
                    .lattice
                    .layers
                    .iter()
                    .map(|l| format!("{}", l.length_mm.unwrap_or(f64::NAN)))
                    .collect();
                if let Some(p) = self.study.ga.designs().space().pitch_m(&i.genome) {
                    labels.push(format!("{}", p * 1e3));
                }
                (i.genome.clone(), i.objectives.clone(), labels)
            })
            .collect())
    }

    /// `pareto.csv` of the front, as `woodpile optimize` writes it.
    fn pareto_csv(&self) -> PyResult<String> {
        Ok(self.study.pareto_csv(&self.state()?.front()))
    }

    /// `history.csv` as `woodpile optimize` writes it.
    fn history_csv(&self) -> PyResult<String> {
        Ok(woodpile_io::pareto::history_csv(&self.state()?.history))
    }

    /// The hypervolume's reference point (one value per objective, SI units).
    fn reference_point(&self) -> PyResult<Vec<f64>> {
        Ok(self.state()?.reference_point.clone())
    }

    /// The lattice scenario of a design, as complete TOML.
    fn scenario_toml(&self, design: Vec<u8>) -> PyResult<String> {
        if !self.study.ga.designs().contains(&design) {
            return Err(Failure::invalid(
                "design",
                format!("{design:?}"),
                format!(
                    "one choice index per gene, below {:?}",
                    self.study.ga.designs().space().choice_counts()
                ),
            )
            .into());
        }
        crate::lattice::complete_toml(&self.study.scenario(&design))
    }
}

/// Adds this module's class to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<ParetoSession>()?;
    m.add_class::<LatticeParetoSession>()?;
    Ok(())
}

/// Runs NSGA-II from `initial` (or a fresh start) with the GIL released, its state written to
/// `checkpoint` after every generation as `to_json` makes it. Returns the final state and why it
/// stopped (kept even when an error is returned) and the error to raise: a failed checkpoint
/// write first, then a Python exception (Ctrl-C), then the algorithm's own.
fn run_nsga2<S: GenomeSpace>(
    py: Python<'_>,
    ga: &Nsga2<S>,
    initial: Option<Nsga2State>,
    checkpoint: Option<PathBuf>,
    to_json: impl Fn(&Path, &Nsga2State) -> Result<Vec<u8>, woodpile_io::Error> + Sync,
) -> (Option<(Nsga2State, StopReason)>, PyResult<()>) {
    let stop = std::sync::atomic::AtomicBool::new(false);
    let (outcome, raised) = crate::interrupt::detach_polling(py, || {
        let mut write_error: Option<woodpile_io::Error> = None;
        let mut observer = |s: &Nsga2State| {
            let Some(path) = &checkpoint else {
                return ControlFlow::Continue(());
            };
            match to_json(path, s).and_then(|json| write_file(path, &json)) {
                Ok(()) => ControlFlow::Continue(()),
                Err(e) => {
                    write_error = Some(e);
                    ControlFlow::Break(())
                }
            }
        };
        let outcome = ga.run(initial, &stop, &mut observer);
        (outcome, write_error)
    });
    woodpile::interrupt::clear();
    let (outcome, write_error) = outcome;
    let (state, result) = match outcome {
        Ok(done) => (Some(done), Ok(())),
        Err(e) => (None, Err(ga_err(e))),
    };
    let result = match (write_error, raised) {
        (Some(e), _) => Err(crate::errors::py_err(e)),
        (None, Some(raised)) => Err(raised),
        (None, None) => result,
    };
    (state, result)
}
