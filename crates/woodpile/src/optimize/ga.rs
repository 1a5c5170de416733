//! The breeder GA: settings, the detachable state, one generation (`next_generation`) and the
//! driver loop (`run`) that owns stopping, observers and checkpoints.

use super::error::OptimizeError;
use super::objective::{Objective, Valued};
use super::operators::{breed, truncation_pool};
use super::space::{DesignSpace, FeasibleSet, Genome};
use crate::clock::Stopwatch;
use crate::error::Error;
use crate::integrate::Method;
use crate::lanes::LaneWidth;
use crate::model::Chain;
use crate::simulate::RunSettings;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::collections::HashMap;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};

/// Parameters of the breeder GA.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaSettings {
    /// Population size μ (≥ 2).
    pub population: usize,
    /// Truncation threshold T ∈ (0, 1]: the best ⌈T μ⌉ breed.
    pub truncation: f64,
    /// Number of best individuals copied unchanged into the next generation (1 ≤ elites < μ).
    pub elites: usize,
    /// Generations bred after the initial population (generation 0).
    pub generations: usize,
    /// Stop after this many generations without a strictly better best (None = never).
    pub stall_generations: Option<usize>,
    /// Seed of every random draw.
    pub seed: u64,
    /// Range of the BGA mutation in catalogue indices (None = the catalogue span, len − 1).
    pub mutation_range: Option<f64>,
    /// Worker threads for fitness evaluation (0 = one per core). Does not change results.
    pub threads: usize,
    /// Keep a fitness cache so a design is never simulated twice. Does not change results
    /// (with screening, it can only change which values outside the breeding pool are exact).
    pub cache: bool,
    /// Screening (docs/physics.md §11): simulate each new design first with every contact peak
    /// within this relative tolerance, and again at the run's settings only where its rank
    /// could decide a selection. None = every design at the run's settings.
    pub screen_peak_tolerance: Option<f64>,
    /// Early stopping (docs/physics.md §11): a new design's run stops at the first step whose
    /// transmitted peak exceeds the previous generation's breeding cutoff by
    /// [`STOP_EARLY_MARGIN`], its value then known only to be larger; a stopped design that could
    /// still breed is simulated whole. The choices stay those of a run without it. Needs the
    /// `transmitted-force` objective.
    pub stop_early: bool,
}

/// How far above the previous generation's breeding cutoff (relative) a run of
/// [`GaSettings::stop_early`] stops. Any margin keeps the choices; a larger one stops fewer runs,
/// a smaller one simulates more stopped designs whole when a generation's cutoff rises.
pub const STOP_EARLY_MARGIN: f64 = 0.02;

impl Default for GaSettings {
    /// μ = 100, T = 0.3 (the middle of the 10–50 % Mühlenbein recommends), one elite,
    /// 100 generations, stop after 30 without improvement, seed 1.
    fn default() -> Self {
        GaSettings {
            population: 100,
            truncation: 0.3,
            elites: 1,
            generations: 100,
            stall_generations: Some(30),
            seed: 1,
            mutation_range: None,
            threads: 0,
            cache: true,
            screen_peak_tolerance: None,
            stop_early: false,
        }
    }
}

impl GaSettings {
    /// Checks every field (names as in a config file's `[ga]` table).
    pub fn validate(&self) -> crate::Result<()> {
        if self.population < 2 {
            return Err(Error::invalid(
                "ga.population",
                self.population,
                "must be at least 2",
            ));
        }
        if !(self.truncation > 0.0 && self.truncation <= 1.0) {
            return Err(Error::invalid(
                "ga.truncation",
                self.truncation,
                "must be in (0, 1]",
            ));
        }
        if self.elites == 0 || self.elites >= self.population {
            return Err(Error::invalid(
                "ga.elites",
                self.elites,
                format!("must be in 1..={}", self.population - 1),
            ));
        }
        if let Some(t) = self.screen_peak_tolerance {
            if !(t.is_finite() && t > 0.0 && t < 0.1) {
                return Err(Error::invalid(
                    "ga.screen_peak_tolerance",
                    t,
                    "is a relative error: give a value in (0, 0.1), e.g. 1e-3",
                ));
            }
        }
        if let Some(r) = self.mutation_range {
            if !(r.is_finite() && r > 0.0) {
                return Err(Error::invalid(
                    "ga.mutation_range",
                    r,
                    "must be a finite number > 0",
                ));
            }
        }
        Ok(())
    }
}

/// A genome and its objective value.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Individual {
    /// Catalogue indices, top to bottom.
    pub genome: Genome,
    /// Objective value (smaller is better).
    pub objective: f64,
    /// Half-width of the interval known to hold the value at the run's settings: 0 when the
    /// design was simulated at them, > 0 when `objective` is its screened value.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "is_exact"))]
    pub bound: f64,
    /// The design's run stopped early ([`GaSettings::stop_early`]): its value at the run's
    /// settings is at least `objective` (and `bound` is 0).
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "is_false"))]
    pub stopped: bool,
}

#[cfg(feature = "serde")]
fn is_false(b: &bool) -> bool {
    !*b
}

impl Individual {
    /// The smallest value the design can have at the run's settings.
    fn low(&self) -> f64 {
        if self.stopped {
            self.objective
        } else {
            self.objective - self.bound
        }
    }

    /// The largest value the design can have at the run's settings (infinite when stopped).
    fn high(&self) -> f64 {
        if self.stopped {
            f64::INFINITY
        } else {
            self.objective + self.bound
        }
    }

    /// Whether the value is not yet known at the run's settings (screened or stopped).
    fn uncertain(&self) -> bool {
        self.bound > 0.0 || self.stopped
    }
}

#[cfg(feature = "serde")]
fn is_exact(bound: &f64) -> bool {
    *bound == 0.0
}

#[cfg(feature = "serde")]
fn is_none_run(count: &u64) -> bool {
    *count == 0
}

/// One line of the history.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GenerationStats {
    /// Generation (0 = the initial population).
    pub generation: usize,
    /// Best objective in the population.
    pub best: f64,
    /// Mean objective.
    pub mean: f64,
    /// Worst objective.
    pub worst: f64,
    /// Simulations at the run's settings so far.
    pub evaluations: u64,
    /// Screening simulations so far (0 without screening; then absent from the serialised
    /// form, which stays that of a run before screening existed).
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "is_none_run"))]
    pub screenings: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
    /// Wall-clock seconds so far (not reproducible; excluded from comparisons of runs).
    pub elapsed_s: f64,
}

impl GenerationStats {
    /// Whether two lines agree in everything but the wall-clock time.
    pub fn same_result(&self, other: &Self) -> bool {
        GenerationStats {
            elapsed_s: 0.0,
            ..*self
        } == GenerationStats {
            elapsed_s: 0.0,
            ..*other
        }
    }
}

/// Everything the GA needs to continue: save it after a generation and resume from it later to
/// exactly the result of an uninterrupted run. The random draws of generation g come from a
/// ChaCha8 generator seeded with the run's seed on stream g, so no generator state is stored.
#[derive(Debug, Clone, PartialEq)]
pub struct GaState {
    /// Generations completed (0 = the initial population is evaluated).
    pub generation: usize,
    /// The population, sorted best first (objective, then genome).
    pub population: Vec<Individual>,
    /// One line per generation 0..=generation.
    pub history: Vec<GenerationStats>,
    /// What has been simulated: the caches and the counts.
    pub ledger: Ledger,
    /// Generations since the best last improved.
    pub stalled: usize,
    /// Wall-clock seconds spent so far.
    pub elapsed_s: f64,
}

impl GaState {
    /// The best individual found (elitism keeps it first).
    pub fn best(&self) -> &Individual {
        &self.population[0]
    }
}

/// What a GA run has simulated: the values it keeps and the counts. A generation's evaluation
/// reads it and adds to it ([`BreederGa::new_designs`], [`BreederGa::record_new`],
/// [`BreederGa::settle`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Ledger {
    /// Fitness cache: every design simulated at the run's settings so far (empty between
    /// generations when the cache is off).
    pub cache: HashMap<Genome, f64>,
    /// Screened values of the designs screened so far (empty without screening, and between
    /// generations when the cache is off).
    pub screened: HashMap<Genome, f64>,
    /// Lower bounds of the values at the run's settings of the designs whose run stopped early
    /// ([`GaSettings::stop_early`]; empty without it, and between generations when the cache is
    /// off).
    pub stopped: HashMap<Genome, f64>,
    /// Simulations at the run's settings so far.
    pub evaluations: u64,
    /// Screening simulations so far.
    pub screenings: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
}

/// Why [`BreederGa::run`] returned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum StopReason {
    /// The generation limit was reached.
    GenerationLimit,
    /// The best did not improve for the stall limit.
    Stalled,
    /// The stop flag was set.
    Interrupted,
    /// The observer asked to stop.
    Observer,
}

/// The final state and why the run stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// The state after the last completed generation.
    pub state: GaState,
    /// Why it stopped.
    pub reason: StopReason,
}

/// The breeder genetic algorithm of docs/physics.md §11 over a [`DesignSpace`].
///
/// Each generation: sort by objective; keep the `elites` best unchanged; breed the rest from
/// two parents drawn from the best ⌈T μ⌉ (truncation selection), by discrete recombination and
/// the BGA mutation on catalogue indices, repaired into the constraints ([`FeasibleSet`]);
/// evaluate the new designs in parallel.
///
/// Reproducibility: all draws come from ChaCha8 seeded with `settings.seed` (stream g for
/// generation g) on the calling thread; fitness values are written back by index, so the run is
/// bit-identical for any thread count, with or without the cache.
///
/// ## References
/// - H. Mühlenbein, D. Schlierkamp-Voosen, "Predictive models for the breeder genetic algorithm
///   I. Continuous parameter optimization", Evolutionary Computation 1 (1993) 25–49.
/// - Kim, Yang et al., Int. J. Impact Eng. 2017, §4.
pub struct BreederGa {
    space: DesignSpace,
    set: FeasibleSet,
    objective: Box<dyn Objective>,
    settings: GaSettings,
    pool: rayon::ThreadPool,
    lanes: LaneWidth,
    screen: Option<Screen>,
}

/// Screening's cheaper settings and how far a screened value can lie from the value at the
/// run's settings.
#[derive(Debug, Clone, Copy)]
struct Screen {
    settings: RunSettings,
    /// |screened − run value| ≤ half_width · |screened|.
    half_width: f64,
}

impl Screen {
    /// Screening at `peak_tolerance` for a GA whose runs use `run` and whose objective is
    /// `objective`; an error names what is missing for a bound.
    fn new(
        peak_tolerance: f64,
        run: &RunSettings,
        objective: &dyn Objective,
    ) -> Result<Self, OptimizeError> {
        let field = "ga.screen_peak_tolerance";
        let run_tolerance = run.method.peak_tolerance().ok_or_else(|| {
            Error::invalid(
                field,
                peak_tolerance,
                "needs the run's accuracy stated: set run.peak_tolerance (the peak error of a \
                 fixed-step or plain dopri5 integrator has no calibrated bound)",
            )
        })?;
        if peak_tolerance <= run_tolerance {
            return Err(Error::invalid(
                field,
                peak_tolerance,
                format!(
                    "must be looser than the run's peak tolerance {run_tolerance:.3e} (e.g. 1e-3)"
                ),
            )
            .into());
        }
        let (Some(screened), Some(exact)) = (
            objective.relative_error(peak_tolerance),
            objective.relative_error(run_tolerance),
        ) else {
            return Err(Error::invalid(
                field,
                peak_tolerance,
                format!(
                    "objective `{}` has no error bound from contact peaks: screening works \
                     with transmitted-force and transmission-ratio",
                    objective.name()
                ),
            )
            .into());
        };
        Ok(Screen {
            settings: RunSettings {
                method: Method::for_peak_tolerance(peak_tolerance)?,
                ..*run
            },
            // |s − v| ≤ |s − c| + |v − c| ≤ (e_s + e_v)|c|, and |c| ≤ |s| / (1 − e_s).
            half_width: (screened + exact) / (1.0 - screened),
        })
    }
}

impl std::fmt::Debug for BreederGa {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BreederGa")
            .field("space", &self.space)
            .field("objective", &self.objective.name())
            .field("settings", &self.settings)
            .finish()
    }
}

impl BreederGa {
    /// Validates the problem, proves the constraints can be met and starts the worker threads.
    pub fn new(
        space: DesignSpace,
        objective: Box<dyn Objective>,
        settings: GaSettings,
    ) -> Result<Self, OptimizeError> {
        settings.validate()?;
        if let Some(p) = space.constraints.max_contact_pressure_pa {
            return Err(Error::invalid(
                "design.constraints.max_contact_pressure_pa",
                p,
                "is known only after a run: set ga.algorithm = \"nsga2\", whose constraint \
                 domination handles it",
            )
            .into());
        }
        let set = FeasibleSet::new(&space)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(settings.threads)
            .build()
            .map_err(|e| OptimizeError::ThreadPool {
                threads: settings.threads,
                reason: e.to_string(),
            })?;
        let screen = settings
            .screen_peak_tolerance
            .map(|t| Screen::new(t, &space.settings, objective.as_ref()))
            .transpose()?;
        if settings.stop_early && !objective.is_transmitted_peak() {
            return Err(Error::invalid(
                "ga.stop_early",
                true,
                format!(
                    "objective `{}` is not the transmitted peak, which a run can only raise: \
                     early stopping works with transmitted-force (or set ga.stop_early = false)",
                    objective.name()
                ),
            )
            .into());
        }
        Ok(BreederGa {
            space,
            set,
            objective,
            settings,
            pool,
            lanes: LaneWidth::detect(),
            screen,
        })
    }

    /// Advances designs `lanes` at a time ([`crate::lanes`]; default [`LaneWidth::detect`]).
    /// Results are the same, bit for bit, at every width.
    pub fn with_lanes(mut self, lanes: LaneWidth) -> Self {
        self.lanes = lanes;
        self
    }

    /// The design space.
    pub fn space(&self) -> &DesignSpace {
        &self.space
    }

    /// The settings.
    pub fn settings(&self) -> &GaSettings {
        &self.settings
    }

    /// The objective.
    pub fn objective(&self) -> &dyn Objective {
        self.objective.as_ref()
    }

    /// The feasible set (constraints).
    pub fn feasible_set(&self) -> &FeasibleSet {
        &self.set
    }

    /// The generator of generation g's draws.
    fn rng(&self, generation: usize) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.settings.seed);
        rng.set_stream(generation as u64);
        rng
    }

    fn mutation_range(&self) -> f64 {
        self.settings
            .mutation_range
            .unwrap_or(((self.set.catalogue_len() - 1) as f64).max(1.0))
    }

    /// Simulates one design at the run's settings (no cache).
    pub fn evaluate(&self, genome: &[u8]) -> Result<f64, OptimizeError> {
        self.evaluate_designs_stopping(&[genome], &self.space.settings, f64::INFINITY)
            .pop()
            .expect("one value per design")
            .map(Valued::value_or_bound)
    }

    /// Simulates designs together under `settings` ([`Objective::evaluate_many`]: in SIMD lanes
    /// for the force objectives); one value per design, in order.
    fn evaluate_batch(
        &self,
        genomes: &[&[u8]],
        settings: &RunSettings,
        stop_above_n: f64,
    ) -> Vec<Result<Valued, OptimizeError>> {
        let design = |genome: &[u8]| self.space.labels(genome).join(" ");
        // The designs that build go to the objective together; the others keep their error.
        let chains: Vec<crate::Result<Chain>> =
            genomes.par_iter().map(|g| self.space.chain(g)).collect();
        let mut built: Vec<Chain> = Vec::with_capacity(genomes.len());
        let unbuilt: Vec<Option<OptimizeError>> = chains
            .into_iter()
            .zip(genomes)
            .map(|(chain, g)| match chain {
                Ok(chain) => {
                    built.push(chain);
                    None
                }
                Err(source) => Some(OptimizeError::Simulation {
                    design: design(g),
                    source,
                }),
            })
            .collect();
        let mut values = self
            .objective
            .evaluate_many_stopping(
                &built,
                &self.space.excitation,
                settings,
                self.lanes,
                stop_above_n,
            )
            .into_iter();
        unbuilt
            .into_iter()
            .zip(genomes)
            .map(|(failure, g)| {
                if let Some(e) = failure {
                    return Err(e);
                }
                let value = values
                    .next()
                    .expect("one value per chain")
                    .map_err(|source| OptimizeError::Simulation {
                        design: design(g),
                        source,
                    })?;
                if value.value_or_bound().is_nan() {
                    return Err(OptimizeError::NotANumber {
                        objective: self.objective.name().to_string(),
                        design: design(g),
                    });
                }
                Ok(value)
            })
            .collect()
    }

    /// Objective values of designs in order, simulated at the run's settings on the GA's
    /// threads in batches of SIMD lanes (no cache); the first failure is the error. The values
    /// do not depend on the thread count, the lane width or the batching (claim
    /// `optimize_thread_determinism`).
    pub fn evaluate_designs<G: AsRef<[u8]> + Sync>(
        &self,
        genomes: &[G],
    ) -> Result<Vec<f64>, OptimizeError> {
        self.evaluate_designs_at(genomes, &self.space.settings)
            .into_iter()
            .collect()
    }

    /// [`BreederGa::evaluate_designs`] under `settings`, one result per design.
    fn evaluate_designs_at<G: AsRef<[u8]> + Sync>(
        &self,
        genomes: &[G],
        settings: &RunSettings,
    ) -> Vec<Result<f64, OptimizeError>> {
        self.evaluate_designs_stopping(genomes, settings, f64::INFINITY)
            .into_iter()
            .map(|v| v.map(Valued::value_or_bound))
            .collect()
    }

    /// [`BreederGa::evaluate_designs_at`], each run stopped once its transmitted peak exceeds
    /// `stop_above_n` ([`Objective::evaluate_many_stopping`]; infinite: never).
    fn evaluate_designs_stopping<G: AsRef<[u8]> + Sync>(
        &self,
        genomes: &[G],
        settings: &RunSettings,
        stop_above_n: f64,
    ) -> Vec<Result<Valued, OptimizeError>> {
        // One batch: the lanes share one queue of runs per group over every thread.
        let genomes: Vec<&[u8]> = genomes.iter().map(|g| g.as_ref()).collect();
        self.pool
            .install(|| self.evaluate_batch(&genomes, settings, stop_above_n))
    }

    /// Whether new designs are screened first (`ga.screen_peak_tolerance`).
    pub fn screens(&self) -> bool {
        self.screen.is_some()
    }

    /// Ask, part 2: the designs of `genomes` (a generation's, from
    /// [`BreederGa::initial_designs`] or [`BreederGa::offspring`]) to simulate first: with the
    /// cache, the distinct ones the ledger holds no value for, in order of first appearance;
    /// without it, all of them.
    pub fn new_designs<'g>(&self, genomes: &'g [Genome], ledger: &Ledger) -> Vec<&'g Genome> {
        if !self.settings.cache {
            return genomes.iter().collect();
        }
        let mut seen = std::collections::HashSet::new();
        genomes
            .iter()
            .filter(|g| {
                !ledger.cache.contains_key(*g)
                    && !ledger.screened.contains_key(*g)
                    && !ledger.stopped.contains_key(*g)
                    && seen.insert(*g)
            })
            .collect()
    }

    /// The first simulation of new designs, in order: the screening run with screening (a
    /// design whose screening run fails is simulated at the run's settings instead, and its
    /// value is then treated as screened), the run's settings otherwise.
    pub fn evaluate_new<G: AsRef<[u8]> + Sync>(
        &self,
        genomes: &[G],
    ) -> Result<Vec<f64>, OptimizeError> {
        Ok(self
            .evaluate_new_stopping(genomes, f64::INFINITY)?
            .into_iter()
            .map(Valued::value_or_bound)
            .collect())
    }

    /// Tell, part 1: enters the first values of the `new` designs of a generation of
    /// `generation_size` designs into the ledger (screened or exact) and counts them.
    pub fn record_new<G: AsRef<[u8]>>(
        &self,
        generation_size: usize,
        new: &[G],
        values: &[f64],
        ledger: &mut Ledger,
    ) {
        let values: Vec<Valued> = values.iter().map(|&v| Valued::Exact(v)).collect();
        self.record_valued(generation_size, new, &values, ledger);
    }

    /// [`BreederGa::record_new`] with stopped runs: a run stopped at a peak p bounds the
    /// design's value at the run's settings from below by p (1 − w), w the screening half-width
    /// (0 without screening): the whole run's value is at least p, and with screening the value
    /// at the run's settings is at least (1 − w) times the screened one.
    fn record_valued<G: AsRef<[u8]>>(
        &self,
        generation_size: usize,
        new: &[G],
        values: &[Valued],
        ledger: &mut Ledger,
    ) {
        if self.settings.cache {
            ledger.cache_hits += generation_size.saturating_sub(new.len()) as u64;
        }
        let half_width = self.screen.map_or(0.0, |s| s.half_width);
        if self.screen.is_some() {
            ledger.screenings += new.len() as u64;
        } else {
            ledger.evaluations += new.len() as u64;
        }
        for (g, &v) in new.iter().zip(values) {
            let g = g.as_ref().to_vec();
            match v {
                Valued::Exact(x) if self.screen.is_some() => ledger.screened.insert(g, x),
                Valued::Exact(x) => ledger.cache.insert(g, x),
                Valued::AtLeast(p) => ledger.stopped.insert(g, p * (1.0 - half_width)),
            };
        }
    }

    /// [`BreederGa::evaluate_new`], each run stopped once its value surely exceeds `cutoff`
    /// (see [`BreederGa::record_valued`] for the bound; infinite: never).
    fn evaluate_new_stopping<G: AsRef<[u8]> + Sync>(
        &self,
        genomes: &[G],
        cutoff: f64,
    ) -> Result<Vec<Valued>, OptimizeError> {
        let (settings, half_width) = match &self.screen {
            Some(screen) => (&screen.settings, screen.half_width),
            None => (&self.space.settings, 0.0),
        };
        self.evaluate_designs_stopping(genomes, settings, cutoff / (1.0 - half_width))
            .into_iter()
            .zip(genomes)
            .map(|(value, g)| match value {
                // A failed screening run is simulated at the run's settings.
                Err(_) if self.screen.is_some() => self.evaluate(g.as_ref()).map(Valued::Exact),
                other => other,
            })
            .collect()
    }

    /// Tell, part 2: the individuals of `genomes` from the ledger's values, after simulating at
    /// the run's settings every screened design whose rank could decide a selection
    /// (`carried`: the elites that join them, simulated at the run's settings).
    ///
    /// A screened value s stands for an interval s ± half_width·|s| that holds the value at the
    /// run's settings (docs/physics.md §11). A design is confirmed when it could be among the
    /// best max(⌈Tμ⌉, elites) and its interval meets another design's, or when it ranks among
    /// the elites; this repeats until no such design is left. The breeding pool, its order and
    /// the elites are then those that values at the run's settings give: screening changes the
    /// cost of a run, not its choices (claim `optimize_screening`).
    pub fn settle(
        &self,
        carried: &[Individual],
        genomes: &[Genome],
        ledger: &mut Ledger,
    ) -> Result<Vec<Individual>, OptimizeError> {
        let half_width = self.screen.map_or(0.0, |s| s.half_width);
        let lookup = |g: &Genome, ledger: &Ledger| {
            if let Some(&objective) = ledger.cache.get(g) {
                return Some(Individual {
                    genome: g.clone(),
                    objective,
                    bound: 0.0,
                    stopped: false,
                });
            }
            if let Some(&objective) = ledger.screened.get(g) {
                return Some(Individual {
                    genome: g.clone(),
                    objective,
                    bound: half_width * objective.abs(),
                    stopped: false,
                });
            }
            ledger.stopped.get(g).map(|&objective| Individual {
                genome: g.clone(),
                objective,
                bound: 0.0,
                stopped: true,
            })
        };
        let mut all: Vec<Individual> = carried.to_vec();
        for g in genomes {
            all.push(
                lookup(g, ledger).ok_or_else(|| OptimizeError::StateMismatch {
                    reason: format!(
                        "design {:?} of this generation has no value",
                        self.space.labels(g)
                    ),
                })?,
            );
        }
        let keep = self.deciding(all.len());
        // Without screening or stopping every value is at the run's settings: nothing to confirm.
        while self.screen.is_some() || self.settings.stop_early {
            let confirm = contested(&all, keep, self.settings.elites);
            if confirm.is_empty() {
                break;
            }
            let values = self.evaluate_designs(&confirm)?;
            ledger.evaluations += confirm.len() as u64;
            for (g, v) in confirm.into_iter().zip(values) {
                ledger.cache.insert(g, v);
            }
            for ind in all.iter_mut().filter(|i| i.uncertain()) {
                if let Some(&v) = ledger.cache.get(&ind.genome) {
                    ind.objective = v;
                    ind.bound = 0.0;
                    ind.stopped = false;
                }
            }
        }
        Ok(all.split_off(carried.len()))
    }

    /// The generation's individuals: new designs simulated (in parallel, each distinct design
    /// once with the cache), then settled.
    fn evaluate_generation(
        &self,
        carried: &[Individual],
        genomes: &[Genome],
        ledger: &mut Ledger,
        cutoff: f64,
    ) -> Result<Vec<Individual>, OptimizeError> {
        let new = self.new_designs(genomes, ledger);
        let values = self.evaluate_new_stopping(&new, cutoff)?;
        self.record_valued(genomes.len(), &new, &values, ledger);
        self.settle(carried, genomes, ledger)
    }

    /// With [`GaSettings::stop_early`], the value above which a design of the generation after
    /// `state` cannot breed in all likelihood: the largest value the best max(⌈Tμ⌉, elites) of
    /// `state` can have, raised by [`STOP_EARLY_MARGIN`]. Infinite without early stopping. Only
    /// the cost depends on it: [`BreederGa::settle`] simulates whole every stopped design that
    /// could still breed.
    fn stop_cutoff(&self, state: &GaState) -> f64 {
        if !self.settings.stop_early {
            return f64::INFINITY;
        }
        let keep = self.deciding(state.population.len());
        largest_of_best(&state.population, keep) * (1.0 + STOP_EARLY_MARGIN)
    }

    /// How many of `n` individuals decide a generation's choices: max(⌈Tμ⌉, elites), at most n.
    fn deciding(&self, n: usize) -> usize {
        truncation_pool(self.settings.population, self.settings.truncation)
            .max(self.settings.elites)
            .min(n)
    }

    fn stats(&self, state: &GaState) -> GenerationStats {
        let objectives = state.population.iter().map(|i| i.objective);
        GenerationStats {
            generation: state.generation,
            best: state.population[0].objective,
            mean: objectives.clone().sum::<f64>() / state.population.len() as f64,
            worst: objectives.fold(f64::NEG_INFINITY, f64::max),
            evaluations: state.ledger.evaluations,
            screenings: state.ledger.screenings,
            cache_hits: state.ledger.cache_hits,
            elapsed_s: state.elapsed_s,
        }
    }

    /// The ledger to carry into the next generation: without the cache, only the counts.
    fn carried_ledger(&self, mut ledger: Ledger) -> Ledger {
        if !self.settings.cache {
            ledger.cache.clear();
            ledger.screened.clear();
            ledger.stopped.clear();
        }
        ledger
    }

    /// Ask, generation 0: a random feasible population drawn from the seed (stream 0).
    pub fn initial_designs(&self) -> Vec<Genome> {
        let mut rng = self.rng(0);
        (0..self.settings.population)
            .map(|_| self.set.random(&mut rng))
            .collect()
    }

    /// Ask, generation g + 1 of a state at generation g: the children to evaluate (the elites
    /// are kept unevaluated), drawn from the seed on stream g + 1.
    pub fn offspring(&self, state: &GaState) -> Vec<Genome> {
        let mut rng = self.rng(state.generation + 1);
        let mu = self.settings.population;
        let parents: Vec<&[u8]> = state.population.iter().map(|i| &i.genome[..]).collect();
        let pool = truncation_pool(mu, self.settings.truncation);
        let range = self.mutation_range();
        (self.settings.elites..mu)
            .map(|_| breed(&parents, pool, &self.set, range, &mut rng))
            .collect()
    }

    /// Tell, generation 0: the state from the initial designs' individuals (from
    /// [`BreederGa::settle`]) and the ledger they were evaluated into.
    pub fn start(&self, individuals: Vec<Individual>, ledger: Ledger, elapsed_s: f64) -> GaState {
        let mut population = individuals;
        sort(&mut population);
        let mut state = GaState {
            generation: 0,
            population,
            history: Vec::new(),
            ledger: self.carried_ledger(ledger),
            stalled: 0,
            elapsed_s,
        };
        state.history.push(self.stats(&state));
        state
    }

    /// Tell, generation g + 1: the elites and the `children`'s individuals (from
    /// [`BreederGa::offspring`], then [`BreederGa::settle`] with the elites carried) become the
    /// sorted population; `ledger` is the state's, with this generation's simulations added.
    pub fn advance(
        &self,
        state: &mut GaState,
        children: Vec<Individual>,
        ledger: Ledger,
        elapsed_s: f64,
    ) {
        let previous_best = state.population[0].objective;
        let mut population: Vec<Individual> = self.elites(state).to_vec();
        population.extend(children);
        sort(&mut population);
        state.generation += 1;
        state.population = population;
        state.ledger = self.carried_ledger(ledger);
        state.stalled = if state.population[0].objective < previous_best {
            0
        } else {
            state.stalled + 1
        };
        state.elapsed_s += elapsed_s;
        state.history.push(self.stats(state));
    }

    /// The individuals of `state` that join the next generation unchanged.
    pub fn elites<'s>(&self, state: &'s GaState) -> &'s [Individual] {
        &state.population[..self.settings.elites]
    }

    /// Why a run stops at `state` (the generation or the stall limit), or None to go on.
    pub fn stop_reason(&self, state: &GaState) -> Option<StopReason> {
        if state.generation >= self.settings.generations {
            Some(StopReason::GenerationLimit)
        } else if self
            .settings
            .stall_generations
            .is_some_and(|g| state.stalled >= g)
        {
            Some(StopReason::Stalled)
        } else {
            None
        }
    }

    /// Generation 0: a random feasible population, evaluated and sorted.
    pub fn initialize(&self) -> Result<GaState, OptimizeError> {
        let started = Stopwatch::start();
        let genomes = self.initial_designs();
        let mut ledger = Ledger::default();
        let individuals = self.evaluate_generation(&[], &genomes, &mut ledger, f64::INFINITY)?;
        Ok(self.start(individuals, ledger, started.elapsed_s()))
    }

    /// Breeds, evaluates and sorts the next generation. On error `state` is unchanged.
    pub fn next_generation(&self, state: &mut GaState) -> Result<(), OptimizeError> {
        let started = Stopwatch::start();
        let children = self.offspring(state);
        let mut ledger = state.ledger.clone();
        let cutoff = self.stop_cutoff(state);
        let individuals =
            self.evaluate_generation(self.elites(state), &children, &mut ledger, cutoff)?;
        self.advance(state, individuals, ledger, started.elapsed_s());
        Ok(())
    }

    /// Checks that a state (e.g. read from a checkpoint) belongs to this problem: population
    /// size, genome length, catalogue indices, constraints, history length.
    pub fn check_state(&self, state: &GaState) -> Result<(), OptimizeError> {
        let mismatch = |reason: String| Err(OptimizeError::StateMismatch { reason });
        super::error::check_counts(
            state.population.len(),
            self.settings.population,
            state.history.len(),
            state.generation,
        )?;
        for (k, ind) in state.population.iter().enumerate() {
            if !self.set.contains(&ind.genome) {
                return mismatch(format!(
                    "individual {k} ({:?}) is not a feasible design of this problem",
                    ind.genome
                ));
            }
            if ind.objective.is_nan() {
                return mismatch(format!("individual {k} has a NaN objective"));
            }
            if !(ind.bound >= 0.0 && ind.bound.is_finite()) {
                return mismatch(format!("individual {k} has a bound of {}", ind.bound));
            }
        }
        if state
            .population
            .windows(2)
            .any(|w| order(&w[0], &w[1]).is_gt())
        {
            return mismatch("population is not sorted best first".to_string());
        }
        if let Some(g) = (state.ledger.cache.keys())
            .chain(state.ledger.screened.keys())
            .chain(state.ledger.stopped.keys())
            .find(|g| !self.space.lengths().contains(&g.len()))
        {
            return mismatch(format!("cache holds a genome of length {}", g.len()));
        }
        Ok(())
    }

    /// Runs from `state` (None = a fresh start) until the generation limit, the stall limit, the
    /// stop flag or a stop request ([`crate::interrupt`]: checked between generations, and within
    /// one by every run, the generation then abandoned) or the observer (called after every generation,
    /// including generation 0, e.g. to write a checkpoint) ends it.
    pub fn run(
        &self,
        state: Option<GaState>,
        stop: &AtomicBool,
        observer: &mut dyn FnMut(&GaState) -> ControlFlow<()>,
    ) -> Result<Outcome, OptimizeError> {
        let mut state = match state {
            Some(s) => {
                self.check_state(&s)?;
                s
            }
            None => {
                let s = self.initialize()?;
                if observer(&s).is_break() {
                    return Ok(Outcome {
                        state: s,
                        reason: StopReason::Observer,
                    });
                }
                s
            }
        };
        loop {
            let reason = self.stop_reason(&state).or_else(|| {
                (stop.load(Ordering::SeqCst) || crate::interrupt::requested())
                    .then_some(StopReason::Interrupted)
            });
            if let Some(reason) = reason {
                return Ok(Outcome { state, reason });
            }
            match self.next_generation(&mut state) {
                // A generation cut short leaves the state at the last complete one.
                Err(e) if e.is_interrupted() => {
                    return Ok(Outcome {
                        state,
                        reason: StopReason::Interrupted,
                    })
                }
                other => other?,
            }
            if observer(&state).is_break() {
                return Ok(Outcome {
                    state,
                    reason: StopReason::Observer,
                });
            }
        }
    }
}

/// Best first: by objective, then by genome so that equal values have one order.
fn order(a: &Individual, b: &Individual) -> std::cmp::Ordering {
    a.objective
        .total_cmp(&b.objective)
        .then_with(|| a.genome.cmp(&b.genome))
}

fn sort(population: &mut [Individual]) {
    population.sort_by(order);
}

/// The largest value the best `keep` of `all` can have: the keep-th smallest upper end of their
/// intervals.
fn largest_of_best(all: &[Individual], keep: usize) -> f64 {
    let mut highs: Vec<f64> = all.iter().map(Individual::high).collect();
    highs.sort_by(f64::total_cmp);
    highs[keep - 1]
}

/// The individuals whose screened values must be confirmed at the run's settings (see
/// [`BreederGa::settle`]): those that could rank among the best `keep` and whose interval meets
/// another design's, and those that rank among the `elites`; distinct, sorted.
fn contested(all: &[Individual], keep: usize, elites: usize) -> Vec<Genome> {
    let threshold = largest_of_best(all, keep);
    let low = Individual::low;
    let high = Individual::high;
    let mut ranked: Vec<&Individual> = all.iter().collect();
    ranked.sort_by(|a, b| order(a, b));
    let mut confirm: Vec<Genome> = ranked
        .iter()
        .enumerate()
        .filter(|&(rank, a)| {
            a.uncertain()
                && low(a) <= threshold
                && (rank < elites
                    || all
                        .iter()
                        .any(|b| b.genome != a.genome && low(a) <= high(b) && low(b) <= high(a)))
        })
        .map(|(_, a)| a.genome.clone())
        .collect();
    confirm.sort();
    confirm.dedup();
    confirm
}
