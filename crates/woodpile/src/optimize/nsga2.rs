//! NSGA-II (Deb et al. 2002) over the breeder GA's genomes, operators and repair: a Pareto front
//! of several [`DesignFigure`]s, with constraint domination for constraints known only after a
//! run (`max_contact_pressure_pa`).
//!
//! Each generation: binary tournaments by crowded comparison (rank, then crowding distance) pick
//! two parents per child; discrete recombination, BGA mutation and repair as in the breeder GA
//! ([`super::operators`]); the children are evaluated (distinct new designs only, in SIMD lanes,
//! with the cache); parents and children together are sorted into non-dominated fronts and the
//! next population filled front by front, the last front cut by crowding distance. A design
//! present twice in parents ∪ children is kept once while enough distinct designs remain.
//!
//! Reproducibility as in the breeder GA: ChaCha8 seeded with the seed, stream g for generation
//! g, every draw on the calling thread, every tie broken by index or genome, so a run is
//! bit-identical for any thread count, lane width, cache setting, and across a resume.

use super::error::OptimizeError;
use super::figures::{DesignFigure, FigureEvaluator, NominalFigures};
use super::ga::StopReason;
use super::operators::{mutate, recombine};
use super::pareto::{crowded_order, crowding_distances, hypervolume, non_dominated_fronts};
use super::space::{DesignSpace, FeasibleSet, Genome};
use crate::clock::Stopwatch;
use crate::error::Error;
use crate::lanes::LaneWidth;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};

/// Parameters of NSGA-II.
#[derive(Debug, Clone, PartialEq)]
pub struct Nsga2Settings {
    /// Population size μ (≥ 4).
    pub population: usize,
    /// Generations bred after the initial population.
    pub generations: usize,
    /// Stop after this many generations without a larger hypervolume (None = never).
    pub stall_generations: Option<usize>,
    /// Seed of every random draw.
    pub seed: u64,
    /// Range of the BGA mutation in catalogue indices (None = the catalogue span).
    pub mutation_range: Option<f64>,
    /// Worker threads (0 = one per core). Does not change results.
    pub threads: usize,
    /// Fitness cache (no design simulated twice). Does not change results.
    pub cache: bool,
    /// Reference point of the hypervolume, one value per objective (None: from generation 0,
    /// see [`Nsga2::reference_point`]).
    pub reference_point: Option<Vec<f64>>,
}

impl Default for Nsga2Settings {
    /// μ = 100, 100 generations, stall limit 30, seed 1.
    fn default() -> Self {
        Nsga2Settings {
            population: 100,
            generations: 100,
            stall_generations: Some(30),
            seed: 1,
            mutation_range: None,
            threads: 0,
            cache: true,
            reference_point: None,
        }
    }
}

/// A design and its objective values.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MoIndividual {
    /// Catalogue indices, top to bottom.
    pub genome: Genome,
    /// One value per objective, in the order of the objectives.
    pub objectives: Vec<f64>,
    /// How far it breaks the constraints known only after a run (0 = feasible): the relative
    /// excess of the worst contact pressure over `max_contact_pressure_pa`.
    pub violation: f64,
}

/// One line of the history.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Nsga2Stats {
    /// Generation (0 = the initial population).
    pub generation: usize,
    /// Hypervolume of the population's feasible non-dominated designs w.r.t. the reference point.
    pub hypervolume: f64,
    /// Number of designs on the first front.
    pub front_size: usize,
    /// Feasible designs in the population.
    pub feasible: usize,
    /// Designs simulated so far (distinct evaluations).
    pub evaluations: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
    /// Wall-clock seconds so far (not reproducible).
    pub elapsed_s: f64,
}

/// Everything NSGA-II needs to continue (saved after every generation).
#[derive(Debug, Clone, PartialEq)]
pub struct Nsga2State {
    /// Generations completed.
    pub generation: usize,
    /// The population, sorted by crowded comparison (rank, then crowding distance, then genome).
    pub population: Vec<MoIndividual>,
    /// One line per generation.
    pub history: Vec<Nsga2Stats>,
    /// The hypervolume's reference point.
    pub reference_point: Vec<f64>,
    /// Values of every design evaluated (empty between generations without the cache).
    pub cache: HashMap<Genome, MoIndividual>,
    /// Designs evaluated so far.
    pub evaluations: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
    /// Generations since the hypervolume last grew.
    pub stalled: usize,
    /// Wall-clock seconds so far.
    pub elapsed_s: f64,
}

impl Nsga2State {
    /// The feasible non-dominated designs of the population, sorted by the first objective
    /// (then genome); empty when no design is feasible.
    pub fn front(&self) -> Vec<&MoIndividual> {
        front_of(&self.population)
    }
}

/// The feasible non-dominated designs of `population`, sorted by the objectives, then genome.
fn front_of(population: &[MoIndividual]) -> Vec<&MoIndividual> {
    let feasible: Vec<&MoIndividual> = population.iter().filter(|i| i.violation == 0.0).collect();
    let points: Vec<Vec<f64>> = feasible.iter().map(|i| i.objectives.clone()).collect();
    let zeros = vec![0.0; points.len()];
    let mut front: Vec<&MoIndividual> = non_dominated_fronts(&points, &zeros)
        .first()
        .map(|f| f.iter().map(|&k| feasible[k]).collect())
        .unwrap_or_default();
    front.sort_by(|a, b| {
        let by_values = a
            .objectives
            .iter()
            .zip(&b.objectives)
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal);
        by_values.then_with(|| a.genome.cmp(&b.genome))
    });
    front.dedup_by(|a, b| a.genome == b.genome);
    front
}

/// What NSGA-II searches: genomes of choice indices (a chain's catalogue entries, a lattice's
/// rod lengths and pitch), drawn, varied and repaired into the feasible set by the space, and
/// evaluated in batches. Every random draw is made on the calling thread from the generator
/// handed in, so a search is reproducible whatever the evaluation's threads.
pub trait GenomeSpace: Send + Sync {
    /// A random feasible genome.
    fn random(&self, rng: &mut ChaCha8Rng) -> Genome;
    /// Mutates a recombined child and repairs it into the feasible set; `range` is
    /// [`Nsga2Settings::mutation_range`] (choice indices; None: the space's default).
    fn vary(&self, child: &mut Genome, range: Option<f64>, rng: &mut ChaCha8Rng);
    /// Whether `genome` is a feasible design of this space (a saved state's check).
    fn contains(&self, genome: &[u8]) -> bool;
    /// Number of objectives each evaluation gives.
    fn objective_count(&self) -> usize;
    /// Evaluates designs, in order: their objectives and constraint violation.
    fn evaluate(&self, genomes: &[&[u8]]) -> Result<Vec<MoIndividual>, OptimizeError>;
}

/// The chains' design space as NSGA-II searches it: a [`DesignSpace`], its [`FeasibleSet`],
/// the objectives as [`DesignFigure`]s, evaluated in SIMD lanes on a thread pool by a
/// [`FigureEvaluator`].
pub struct ChainDesigns {
    space: DesignSpace,
    set: FeasibleSet,
    objectives: Vec<DesignFigure>,
    pool: rayon::ThreadPool,
    lanes: LaneWidth,
    evaluator: Box<dyn FigureEvaluator>,
}

/// NSGA-II over a [`GenomeSpace`] (see the module documentation); by default the chains'
/// [`ChainDesigns`], built by [`Nsga2::new`].
pub struct Nsga2<S = ChainDesigns> {
    designs: S,
    settings: Nsga2Settings,
}

impl std::fmt::Debug for ChainDesigns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ChainDesigns")
            .field("objectives", &self.objectives)
            .finish()
    }
}

impl<S: std::fmt::Debug> std::fmt::Debug for Nsga2<S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Nsga2")
            .field("designs", &self.designs)
            .field("settings", &self.settings)
            .finish()
    }
}

/// The checks of NSGA-II's settings every space shares, for `objectives` objectives.
pub(crate) fn check_settings(
    settings: &Nsga2Settings,
    objectives: usize,
) -> Result<(), OptimizeError> {
    if settings.population < 4 {
        return Err(Error::invalid(
            "ga.population",
            settings.population,
            "NSGA-II needs at least 4",
        )
        .into());
    }
    if let Some(r) = settings.mutation_range {
        if !(r.is_finite() && r > 0.0) {
            return Err(
                Error::invalid("ga.mutation_range", r, "must be a finite number > 0").into(),
            );
        }
    }
    if let Some(r) = &settings.reference_point {
        if r.len() != objectives || r.iter().any(|x| !x.is_finite()) {
            return Err(Error::invalid(
                "ga.reference_point",
                format!("{r:?}"),
                format!("give {objectives} finite numbers, one per objective"),
            )
            .into());
        }
    }
    Ok(())
}

/// A thread pool of `threads` workers (0: one per core).
pub(crate) fn thread_pool(threads: usize) -> Result<rayon::ThreadPool, OptimizeError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| OptimizeError::ThreadPool {
            threads,
            reason: e.to_string(),
        })
}

impl Nsga2 {
    /// Validates the problem, proves the constraints that can be checked before a run can be
    /// met and starts the worker threads.
    pub fn new(
        space: DesignSpace,
        objectives: Vec<DesignFigure>,
        settings: Nsga2Settings,
    ) -> Result<Self, OptimizeError> {
        if objectives.is_empty() {
            return Err(
                Error::invalid("ga.objectives", "[]", "give at least one objective").into(),
            );
        }
        if let Some(k) = (1..objectives.len()).find(|&k| objectives[..k].contains(&objectives[k])) {
            return Err(Error::invalid(
                format!("ga.objectives[{k}]"),
                objectives[k].as_str(),
                "is listed twice; list each objective once",
            )
            .into());
        }
        check_settings(&settings, objectives.len())?;
        let set = FeasibleSet::new(&space)?;
        let pool = thread_pool(settings.threads)?;
        let designs = ChainDesigns {
            space,
            set,
            objectives,
            pool,
            lanes: LaneWidth::detect(),
            evaluator: Box::new(NominalFigures),
        };
        Ok(Nsga2 { designs, settings })
    }

    /// Advances designs `lanes` at a time; results are the same at every width.
    pub fn with_lanes(mut self, lanes: LaneWidth) -> Self {
        self.designs.lanes = lanes;
        self
    }

    /// Evaluates the figures with `evaluator` instead of [`NominalFigures`] (a robust study's
    /// statistics over scattered scenarios).
    pub fn with_evaluator(mut self, evaluator: Box<dyn FigureEvaluator>) -> Self {
        self.designs.evaluator = evaluator;
        self
    }

    /// The design space.
    pub fn space(&self) -> &DesignSpace {
        &self.designs.space
    }

    /// The objectives, in order.
    pub fn objectives(&self) -> &[DesignFigure] {
        &self.designs.objectives
    }

    /// Evaluates designs at the run's settings, in order (no cache).
    pub fn evaluate_designs<G: AsRef<[u8]> + Sync>(
        &self,
        genomes: &[G],
    ) -> Result<Vec<MoIndividual>, OptimizeError> {
        let refs: Vec<&[u8]> = genomes.iter().map(|g| g.as_ref()).collect();
        self.designs.evaluate(&refs)
    }
}

impl ChainDesigns {
    /// The figures each evaluation computes: the objectives, then the worst contact pressure
    /// where it is constrained and not an objective.
    fn evaluated_figures(&self) -> Vec<DesignFigure> {
        let mut f = self.objectives.clone();
        if self.space.constraints.max_contact_pressure_pa.is_some()
            && !f.contains(&DesignFigure::MaxContactPressure)
        {
            f.push(DesignFigure::MaxContactPressure);
        }
        f
    }
}

impl GenomeSpace for ChainDesigns {
    fn random(&self, rng: &mut ChaCha8Rng) -> Genome {
        self.set.random(rng)
    }

    /// BGA mutation (default range: the catalogue's span), then the feasible set's repair.
    fn vary(&self, child: &mut Genome, range: Option<f64>, rng: &mut ChaCha8Rng) {
        let range = range.unwrap_or(((self.set.catalogue_len() - 1) as f64).max(1.0));
        mutate(child, &self.set, range, rng);
        self.set.repair(child, rng);
    }

    fn contains(&self, genome: &[u8]) -> bool {
        self.set.contains(genome)
    }

    fn objective_count(&self) -> usize {
        self.objectives.len()
    }

    fn evaluate(&self, refs: &[&[u8]]) -> Result<Vec<MoIndividual>, OptimizeError> {
        let figures = self.evaluated_figures();
        let values = self.pool.install(|| {
            self.evaluator
                .figures_many(&self.space, &figures, refs, self.lanes)
        });
        let pressure_at = figures
            .iter()
            .position(|f| *f == DesignFigure::MaxContactPressure);
        let limit = self.space.constraints.max_contact_pressure_pa;
        let m = self.objectives.len();
        values
            .into_iter()
            .zip(refs)
            .map(|(v, g)| {
                let design = || self.space.labels(g).join(" ");
                let v = v.map_err(|source| OptimizeError::Simulation {
                    design: design(),
                    source,
                })?;
                if let Some(k) = v[..m].iter().position(|x| x.is_nan()) {
                    return Err(OptimizeError::NotANumber {
                        objective: self.objectives[k].as_str().to_string(),
                        design: design(),
                    });
                }
                let violation = match (limit, pressure_at) {
                    (Some(limit), Some(k)) => (v[k] / limit - 1.0).max(0.0),
                    _ => 0.0,
                };
                Ok(MoIndividual {
                    genome: g.to_vec(),
                    objectives: v[..m].to_vec(),
                    violation,
                })
            })
            .collect()
    }
}

impl<S: GenomeSpace> Nsga2<S> {
    /// NSGA-II over any [`GenomeSpace`] (a lattice's designs); the settings are checked.
    pub fn over(designs: S, settings: Nsga2Settings) -> Result<Self, OptimizeError> {
        check_settings(&settings, designs.objective_count())?;
        Ok(Nsga2 { designs, settings })
    }

    /// The searched space.
    pub fn designs(&self) -> &S {
        &self.designs
    }

    /// The settings.
    pub fn settings(&self) -> &Nsga2Settings {
        &self.settings
    }

    fn rng(&self, generation: usize) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.settings.seed);
        rng.set_stream(generation as u64);
        rng
    }

    /// The individuals of `genomes`, simulating only designs the cache does not hold.
    fn evaluate_cached(
        &self,
        genomes: &[Genome],
        state_cache: &mut HashMap<Genome, MoIndividual>,
        evaluations: &mut u64,
        cache_hits: &mut u64,
    ) -> Result<Vec<MoIndividual>, OptimizeError> {
        let mut seen = std::collections::HashSet::new();
        let new: Vec<&[u8]> = genomes
            .iter()
            .filter(|g| !(self.settings.cache && state_cache.contains_key(*g)) && seen.insert(*g))
            .map(|g| g.as_slice())
            .collect();
        let values = self.designs.evaluate(&new)?;
        *evaluations += new.len() as u64;
        *cache_hits += (genomes.len() - new.len()) as u64;
        let mut fresh: HashMap<Genome, MoIndividual> = HashMap::new();
        for ind in values {
            fresh.insert(ind.genome.clone(), ind);
        }
        let out = genomes
            .iter()
            .map(|g| {
                fresh
                    .get(g)
                    .or_else(|| state_cache.get(g))
                    .cloned()
                    .expect("every design evaluated")
            })
            .collect();
        if self.settings.cache {
            state_cache.extend(fresh);
        }
        Ok(out)
    }

    /// The default reference point from generation 0's population: per objective, the largest
    /// value of its feasible designs (all designs if none is feasible) plus a tenth of the
    /// objective's range there (a tenth of its magnitude, or 1, where the range is 0).
    pub fn reference_point(&self, population: &[MoIndividual]) -> Vec<f64> {
        if let Some(r) = &self.settings.reference_point {
            return r.clone();
        }
        let feasible: Vec<&MoIndividual> =
            population.iter().filter(|i| i.violation == 0.0).collect();
        let pool: Vec<&MoIndividual> = if feasible.is_empty() {
            population.iter().collect()
        } else {
            feasible
        };
        (0..self.designs.objective_count())
            .map(|k| {
                let hi = pool
                    .iter()
                    .map(|i| i.objectives[k])
                    .fold(f64::NEG_INFINITY, f64::max);
                let lo = pool
                    .iter()
                    .map(|i| i.objectives[k])
                    .fold(f64::INFINITY, f64::min);
                let margin = if hi > lo {
                    0.1 * (hi - lo)
                } else if hi != 0.0 {
                    0.1 * hi.abs()
                } else {
                    1.0
                };
                hi + margin
            })
            .collect()
    }

    /// Generation 0: a random feasible population (stream 0), evaluated and sorted.
    pub fn initialize(&self) -> Result<Nsga2State, OptimizeError> {
        let started = Stopwatch::start();
        let mut rng = self.rng(0);
        let genomes: Vec<Genome> = (0..self.settings.population)
            .map(|_| self.designs.random(&mut rng))
            .collect();
        let mut cache = HashMap::new();
        let (mut evaluations, mut cache_hits) = (0, 0);
        let individuals =
            self.evaluate_cached(&genomes, &mut cache, &mut evaluations, &mut cache_hits)?;
        let reference_point = self.reference_point(&individuals);
        let population = self.select(individuals);
        let mut state = Nsga2State {
            generation: 0,
            population,
            history: Vec::new(),
            reference_point,
            cache: if self.settings.cache {
                cache
            } else {
                HashMap::new()
            },
            evaluations,
            cache_hits,
            stalled: 0,
            elapsed_s: started.elapsed_s(),
        };
        state.history.push(self.stats(&state));
        Ok(state)
    }

    /// The children of generation g + 1: parents by binary tournament on the crowded comparison,
    /// recombined, mutated and repaired (stream g + 1).
    pub fn offspring(&self, state: &Nsga2State) -> Vec<Genome> {
        let mut rng = self.rng(state.generation + 1);
        let keys = rank_and_crowding(&state.population);
        let n = state.population.len();
        let tournament = |rng: &mut ChaCha8Rng| {
            let a = rng.random_range(0..n);
            let mut b = rng.random_range(0..n - 1);
            if b >= a {
                b += 1;
            }
            if crowded_order(keys[b], keys[a]).is_lt() {
                b
            } else {
                a
            }
        };
        (0..self.settings.population)
            .map(|_| {
                let (a, b) = (tournament(&mut rng), tournament(&mut rng));
                let mut child = recombine(
                    &state.population[a].genome,
                    &state.population[b].genome,
                    &mut rng,
                );
                self.designs
                    .vary(&mut child, self.settings.mutation_range, &mut rng);
                child
            })
            .collect()
    }

    /// Environmental selection: the best μ of `all` by fronts, the last front cut by crowding
    /// distance; a genome present twice is kept once while enough distinct designs remain.
    fn select(&self, all: Vec<MoIndividual>) -> Vec<MoIndividual> {
        let mu = self.settings.population;
        let mut seen = std::collections::HashSet::new();
        let (mut distinct, mut repeats): (Vec<MoIndividual>, Vec<MoIndividual>) =
            all.into_iter().partition(|i| seen.insert(i.genome.clone()));
        if distinct.len() < mu {
            repeats.truncate(mu - distinct.len());
            distinct.extend(repeats);
        }
        let points: Vec<Vec<f64>> = distinct.iter().map(|i| i.objectives.clone()).collect();
        let violations: Vec<f64> = distinct.iter().map(|i| i.violation).collect();
        let mut chosen: Vec<(usize, f64, usize)> = Vec::with_capacity(mu);
        for (rank, front) in non_dominated_fronts(&points, &violations)
            .iter()
            .enumerate()
        {
            let refs: Vec<&[f64]> = front.iter().map(|&k| points[k].as_slice()).collect();
            let crowding = crowding_distances(&refs);
            let mut members: Vec<(usize, f64, usize)> = front
                .iter()
                .zip(crowding)
                .map(|(&k, d)| (rank, d, k))
                .collect();
            if chosen.len() + members.len() > mu {
                members.sort_by(|a, b| {
                    crowded_order((a.0, a.1), (b.0, b.1))
                        .then_with(|| distinct[a.2].genome.cmp(&distinct[b.2].genome))
                });
                members.truncate(mu - chosen.len());
            }
            chosen.extend(members);
            if chosen.len() == mu {
                break;
            }
        }
        chosen.sort_by(|a, b| {
            crowded_order((a.0, a.1), (b.0, b.1))
                .then_with(|| distinct[a.2].genome.cmp(&distinct[b.2].genome))
        });
        chosen
            .into_iter()
            .map(|(_, _, k)| distinct[k].clone())
            .collect()
    }

    fn stats(&self, state: &Nsga2State) -> Nsga2Stats {
        let front = state.front();
        let points: Vec<Vec<f64>> = front.iter().map(|i| i.objectives.clone()).collect();
        Nsga2Stats {
            generation: state.generation,
            hypervolume: hypervolume(&points, &state.reference_point),
            front_size: front.len(),
            feasible: state
                .population
                .iter()
                .filter(|i| i.violation == 0.0)
                .count(),
            evaluations: state.evaluations,
            cache_hits: state.cache_hits,
            elapsed_s: state.elapsed_s,
        }
    }

    /// Breeds, evaluates and selects the next generation. On error `state` is unchanged.
    pub fn next_generation(&self, state: &mut Nsga2State) -> Result<(), OptimizeError> {
        let started = Stopwatch::start();
        let children = self.offspring(state);
        let mut cache = std::mem::take(&mut state.cache);
        let (mut evaluations, mut cache_hits) = (state.evaluations, state.cache_hits);
        let evaluated =
            self.evaluate_cached(&children, &mut cache, &mut evaluations, &mut cache_hits);
        let children = match evaluated {
            Ok(c) => c,
            Err(e) => {
                state.cache = cache;
                return Err(e);
            }
        };
        let mut all = state.population.clone();
        all.extend(children);
        let previous = state.history.last().map_or(0.0, |h| h.hypervolume);
        state.population = self.select(all);
        state.cache = if self.settings.cache {
            cache
        } else {
            HashMap::new()
        };
        state.generation += 1;
        state.evaluations = evaluations;
        state.cache_hits = cache_hits;
        state.elapsed_s += started.elapsed_s();
        let stats = self.stats(state);
        state.stalled = if stats.hypervolume > previous {
            0
        } else {
            state.stalled + 1
        };
        state.history.push(stats);
        Ok(())
    }

    /// Why a run stops at `state`, or None to go on.
    pub fn stop_reason(&self, state: &Nsga2State) -> Option<StopReason> {
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

    /// Checks that a saved state belongs to this problem.
    pub fn check_state(&self, state: &Nsga2State) -> Result<(), OptimizeError> {
        let mismatch = |reason: String| Err(OptimizeError::StateMismatch { reason });
        super::error::check_counts(
            state.population.len(),
            self.settings.population,
            state.history.len(),
            state.generation,
        )?;
        let m = self.designs.objective_count();
        if state.reference_point.len() != m {
            return mismatch(format!(
                "the reference point has {} values for {m} objectives",
                state.reference_point.len()
            ));
        }
        for (k, ind) in state
            .population
            .iter()
            .chain(state.cache.values())
            .enumerate()
        {
            if !self.designs.contains(&ind.genome) {
                return mismatch(format!(
                    "individual {k} ({:?}) is not a feasible design of this problem",
                    ind.genome
                ));
            }
            if ind.objectives.len() != m || ind.objectives.iter().any(|x| x.is_nan()) {
                return mismatch(format!(
                    "individual {k} has objectives {:?}",
                    ind.objectives
                ));
            }
        }
        Ok(())
    }

    /// Runs from `state` (None = a fresh start) until the generation or stall limit, the stop
    /// flag (checked between generations) or the observer (called after every generation,
    /// generation 0 included) ends it.
    pub fn run(
        &self,
        state: Option<Nsga2State>,
        stop: &AtomicBool,
        observer: &mut dyn FnMut(&Nsga2State) -> ControlFlow<()>,
    ) -> Result<(Nsga2State, StopReason), OptimizeError> {
        let mut state = match state {
            Some(s) => {
                self.check_state(&s)?;
                s
            }
            None => {
                let s = self.initialize()?;
                if observer(&s).is_break() {
                    return Ok((s, StopReason::Observer));
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
                return Ok((state, reason));
            }
            match self.next_generation(&mut state) {
                // A generation cut short leaves the state at the last complete one.
                Err(e) if e.is_interrupted() => return Ok((state, StopReason::Interrupted)),
                other => other?,
            }
            if observer(&state).is_break() {
                return Ok((state, StopReason::Observer));
            }
        }
    }
}

/// (rank, crowding distance) of each individual of a population, in order.
fn rank_and_crowding(population: &[MoIndividual]) -> Vec<(usize, f64)> {
    let points: Vec<Vec<f64>> = population.iter().map(|i| i.objectives.clone()).collect();
    let violations: Vec<f64> = population.iter().map(|i| i.violation).collect();
    let mut keys = vec![(0, 0.0); population.len()];
    for (rank, front) in non_dominated_fronts(&points, &violations)
        .iter()
        .enumerate()
    {
        let refs: Vec<&[f64]> = front.iter().map(|&k| points[k].as_slice()).collect();
        for (&k, d) in front.iter().zip(crowding_distances(&refs)) {
            keys[k] = (rank, d);
        }
    }
    keys
}
