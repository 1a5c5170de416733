//! The breeder GA: settings, the detachable state, one generation (`next_generation`) and the
//! driver loop (`run`) that owns stopping, observers and checkpoints.

use super::objective::Objective;
use super::operators::{breed, truncation_pool};
use super::space::{DesignSpace, FeasibleSet, Genome};
use super::OptimizeError;
use crate::error::Error;
use crate::lanes::LaneWidth;
use crate::model::Chain;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::collections::HashMap;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

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
    /// Keep a fitness cache so a design is never simulated twice. Does not change results.
    pub cache: bool,
}

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
    /// Simulations run so far.
    pub evaluations: u64,
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
    /// Fitness cache: every design simulated so far (empty when the cache is off).
    pub cache: HashMap<Genome, f64>,
    /// Simulations run so far.
    pub evaluations: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
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
        let set = FeasibleSet::new(&space)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(settings.threads)
            .build()
            .map_err(|e| OptimizeError::ThreadPool {
                threads: settings.threads,
                reason: e.to_string(),
            })?;
        Ok(BreederGa {
            space,
            set,
            objective,
            settings,
            pool,
            lanes: LaneWidth::detect(),
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

    /// Simulates one design (no cache).
    pub fn evaluate(&self, genome: &[u8]) -> Result<f64, OptimizeError> {
        self.evaluate_batch(&[genome])
            .pop()
            .expect("one value per design")
    }

    /// Simulates designs together ([`Objective::evaluate_many`]: in SIMD lanes for the force
    /// objectives); one value per design, in order.
    fn evaluate_batch(&self, genomes: &[&[u8]]) -> Vec<Result<f64, OptimizeError>> {
        let design = |genome: &[u8]| self.space.labels(genome).join(" ");
        // The designs that build go to the objective together; the others keep their error.
        let mut built: Vec<Chain> = Vec::with_capacity(genomes.len());
        let unbuilt: Vec<Option<OptimizeError>> = genomes
            .iter()
            .map(|g| match self.space.chain(g) {
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
            .evaluate_many(
                &built,
                &self.space.excitation,
                &self.space.settings,
                self.lanes,
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
                if value.is_nan() {
                    return Err(OptimizeError::NotANumber {
                        objective: self.objective.name().to_string(),
                        design: design(g),
                    });
                }
                Ok(value)
            })
            .collect()
    }

    /// Objective values of designs in order, simulated on the GA's threads in batches of SIMD
    /// lanes (no cache); the first failure is the error. The values do not depend on the thread
    /// count, the lane width or the batching (claim `optimize_thread_determinism`).
    pub fn evaluate_designs<G: AsRef<[u8]> + Sync>(
        &self,
        genomes: &[G],
    ) -> Result<Vec<f64>, OptimizeError> {
        // Several batches per thread keep every thread busy; each batch fills its lanes.
        let threads = self.pool.current_num_threads().max(1);
        let batch = genomes.len().div_ceil(4 * threads).max(self.lanes.lanes());
        let values: Vec<Result<f64, OptimizeError>> = self.pool.install(|| {
            genomes
                .par_chunks(batch)
                .flat_map_iter(|chunk| {
                    let genomes: Vec<&[u8]> = chunk.iter().map(|g| g.as_ref()).collect();
                    self.evaluate_batch(&genomes)
                })
                .collect()
        });
        values.into_iter().collect()
    }

    /// Objective values of `genomes` in order: cached ones looked up, the others simulated in
    /// parallel (each distinct design once) and written back by index.
    fn evaluate_all(
        &self,
        genomes: &[Genome],
        cache: &mut HashMap<Genome, f64>,
        evaluations: &mut u64,
        cache_hits: &mut u64,
    ) -> Result<Vec<f64>, OptimizeError> {
        let use_cache = self.settings.cache;
        let mut todo: Vec<&Genome> = Vec::new();
        let mut slot: Vec<usize> = Vec::with_capacity(genomes.len());
        let mut pending: HashMap<&Genome, usize> = HashMap::new();
        for g in genomes {
            if use_cache {
                if cache.contains_key(g) {
                    *cache_hits += 1;
                    slot.push(usize::MAX);
                    continue;
                }
                if let Some(&k) = pending.get(g) {
                    *cache_hits += 1;
                    slot.push(k);
                    continue;
                }
                pending.insert(g, todo.len());
            }
            slot.push(todo.len());
            todo.push(g);
        }
        let values = self.evaluate_designs(&todo)?;
        *evaluations += values.len() as u64;
        if use_cache {
            for (g, &v) in todo.iter().zip(&values) {
                cache.insert((*g).clone(), v);
            }
        }
        Ok(genomes
            .iter()
            .zip(&slot)
            .map(|(g, &k)| if k == usize::MAX { cache[g] } else { values[k] })
            .collect())
    }

    fn stats(&self, state: &GaState) -> GenerationStats {
        let objectives = state.population.iter().map(|i| i.objective);
        GenerationStats {
            generation: state.generation,
            best: state.population[0].objective,
            mean: objectives.clone().sum::<f64>() / state.population.len() as f64,
            worst: objectives.fold(f64::NEG_INFINITY, f64::max),
            evaluations: state.evaluations,
            cache_hits: state.cache_hits,
            elapsed_s: state.elapsed_s,
        }
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

    /// Tell, generation 0: the state from the initial designs and their objective values (the
    /// caller's `cache`, evaluation count and cache hits are kept in it).
    pub fn start(
        &self,
        genomes: Vec<Genome>,
        values: Vec<f64>,
        cache: HashMap<Genome, f64>,
        evaluations: u64,
        cache_hits: u64,
        elapsed_s: f64,
    ) -> GaState {
        let mut state = GaState {
            generation: 0,
            population: sorted(genomes, values),
            history: Vec::new(),
            cache,
            evaluations,
            cache_hits,
            stalled: 0,
            elapsed_s,
        };
        state.history.push(self.stats(&state));
        state
    }

    /// Tell, generation g + 1: the elites and the evaluated `children` (from
    /// [`BreederGa::offspring`]) become the sorted population; the caller has already updated
    /// the state's cache and counters.
    pub fn advance(
        &self,
        state: &mut GaState,
        children: Vec<Genome>,
        values: Vec<f64>,
        elapsed_s: f64,
    ) {
        let previous_best = state.population[0].objective;
        let mut population: Vec<Individual> = state.population[..self.settings.elites].to_vec();
        population.extend(
            children
                .into_iter()
                .zip(values)
                .map(|(genome, objective)| Individual { genome, objective }),
        );
        sort(&mut population);
        state.generation += 1;
        state.population = population;
        state.stalled = if state.population[0].objective < previous_best {
            0
        } else {
            state.stalled + 1
        };
        state.elapsed_s += elapsed_s;
        state.history.push(self.stats(state));
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
        let started = Instant::now();
        let genomes = self.initial_designs();
        let (mut cache, mut evaluations, mut cache_hits) = (HashMap::new(), 0, 0);
        let values = self.evaluate_all(&genomes, &mut cache, &mut evaluations, &mut cache_hits)?;
        let elapsed = started.elapsed().as_secs_f64();
        Ok(self.start(genomes, values, cache, evaluations, cache_hits, elapsed))
    }

    /// Breeds, evaluates and sorts the next generation. On error `state` is unchanged.
    pub fn next_generation(&self, state: &mut GaState) -> Result<(), OptimizeError> {
        let started = Instant::now();
        let children = self.offspring(state);
        let mut cache = std::mem::take(&mut state.cache);
        let (mut evaluations, mut cache_hits) = (state.evaluations, state.cache_hits);
        let values = self.evaluate_all(&children, &mut cache, &mut evaluations, &mut cache_hits);
        state.cache = cache;
        let values = values?;
        state.evaluations = evaluations;
        state.cache_hits = cache_hits;
        self.advance(state, children, values, started.elapsed().as_secs_f64());
        Ok(())
    }

    /// Checks that a state (e.g. read from a checkpoint) belongs to this problem: population
    /// size, genome length, catalogue indices, constraints, history length.
    pub fn check_state(&self, state: &GaState) -> Result<(), OptimizeError> {
        let mismatch = |reason: String| Err(OptimizeError::StateMismatch { reason });
        if state.population.len() != self.settings.population {
            return mismatch(format!(
                "population has {} individuals, the settings ask for {}",
                state.population.len(),
                self.settings.population
            ));
        }
        if state.history.len() != state.generation + 1 {
            return mismatch(format!(
                "history has {} lines for generation {}",
                state.history.len(),
                state.generation
            ));
        }
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
        }
        if state
            .population
            .windows(2)
            .any(|w| order(&w[0], &w[1]).is_gt())
        {
            return mismatch("population is not sorted best first".to_string());
        }
        if let Some(g) = state.cache.keys().find(|g| g.len() != self.space.positions) {
            return mismatch(format!("cache holds a genome of length {}", g.len()));
        }
        Ok(())
    }

    /// Runs from `state` (None = a fresh start) until the generation limit, the stall limit, the
    /// stop flag (checked between generations) or the observer (called after every generation,
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
                stop.load(Ordering::SeqCst)
                    .then_some(StopReason::Interrupted)
            });
            if let Some(reason) = reason {
                return Ok(Outcome { state, reason });
            }
            self.next_generation(&mut state)?;
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

fn sorted(genomes: Vec<Genome>, values: Vec<f64>) -> Vec<Individual> {
    let mut p: Vec<Individual> = genomes
        .into_iter()
        .zip(values)
        .map(|(genome, objective)| Individual { genome, objective })
        .collect();
    sort(&mut p);
    p
}
