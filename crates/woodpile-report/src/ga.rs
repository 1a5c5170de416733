//! The report's GAs, the only expensive part: each result is kept in `OUT/cache/` under an
//! FNV-1a hash of the tool version and the complete problem (config, GA settings, seed), and a
//! rerun of the report reuses it.

use super::study::{join_mm, pct, ratio, Setup};
use crate::Error;
use serde::{Deserialize, Serialize};
use std::fs;
use std::path::{Path, PathBuf};
use woodpile::optimize::{BreederGa, GaState, GenerationStats, Objective};
use woodpile::{Chain, RunSummary};
use woodpile_io::atomic::write_atomic;
use woodpile_io::optimize::{fnv1a64, optimize_error, OptimizeConfig, Problem};

/// Tag of the report cache's format (part of every key).
const CACHE_FORMAT: &str = "woodpile-report-cache/1";

/// A GA result as kept in the cache.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CachedGa {
    /// The key's text (tool version, format, inputs): checked on load against collisions.
    pub inputs: String,
    /// Catalogue indices of the best design.
    pub best_genome: Vec<u8>,
    /// Its objective.
    pub best_objective: f64,
    /// One line per generation.
    pub history: Vec<GenerationStats>,
    /// Generations completed.
    pub generations: usize,
    /// Simulations run.
    pub evaluations: u64,
    /// Cache hits.
    pub cache_hits: u64,
    /// Wall-clock time \[s\].
    pub elapsed_s: f64,
    /// Why the GA stopped.
    pub stop_reason: String,
}

/// GA results kept between runs of the report.
pub struct Cache {
    /// The directory of the entries (`OUT/cache`).
    pub dir: PathBuf,
}

impl Cache {
    /// The key of an entry: the tool version, the format, the kind and the inputs as JSON.
    pub(crate) fn key_text(kind: &str, inputs: &impl Serialize) -> String {
        format!(
            "woodpile {} {CACHE_FORMAT} {kind}\n{}",
            env!("CARGO_PKG_VERSION"),
            serde_json::to_string(inputs).unwrap_or_default()
        )
    }

    /// The entry file of a key (its FNV-1a hash) and its name.
    pub(crate) fn file(&self, text: &str) -> (PathBuf, String) {
        let name = format!("{:016x}.json", fnv1a64(text.as_bytes()));
        (self.dir.join(&name), name)
    }

    /// The cached GA for these inputs, if an entry with exactly this key text exists.
    fn get(&self, text: &str) -> Option<CachedGa> {
        let (path, _) = self.file(text);
        let entry: CachedGa = serde_json::from_str(&fs::read_to_string(path).ok()?).ok()?;
        (entry.inputs == text).then_some(entry)
    }

    /// Stores an entry atomically.
    fn put(&self, entry: &CachedGa) -> Result<(), Error> {
        let (path, name) = self.file(&entry.inputs);
        let json = serde_json::to_vec(entry).map_err(|e| Error::Output {
            path,
            source: std::io::Error::other(e),
        })?;
        write_atomic(&self.dir, &name, &json)
    }
}

/// A GA of the report, with what the report says of it.
#[derive(Debug, Clone)]
pub struct GaRun {
    /// Its label (`resonant`, `rigid`, …).
    pub model: &'static str,
    /// The best chain.
    pub chain: Chain,
    /// The best chain's rod lengths \[mm\].
    pub rods: Vec<u32>,
    /// Whether the result came from the cache.
    pub cached: bool,
    /// The result.
    pub result: CachedGa,
    /// Population size.
    pub population: usize,
    /// Generation limit.
    pub generations_limit: usize,
    /// Stall limit.
    pub stall: Option<usize>,
    /// The objective's name.
    pub objective: String,
    /// Its unit.
    pub unit: String,
}

impl GaRun {
    /// The GA of `cfg` labelled `label`: from the cache when it holds one for the same inputs,
    /// else run now (each generation shown on the progress bar) and stored.
    pub fn cached_or_run(
        cfg: &OptimizeConfig,
        label: &'static str,
        s: &Setup,
    ) -> Result<GaRun, Error> {
        let problem = Problem::new(cfg, Path::new("."), s.threads)?;
        let total = problem.settings.generations;
        let cache = Cache {
            dir: s.out.join("cache"),
        };
        let key = Cache::key_text("ga", &problem.config);
        let (result, cached) = match cache.get(&key) {
            Some(entry) if entry.best_genome.len() == problem.space.positions => (entry, true),
            _ => {
                let entry = run(&problem, key, &mut |g: &GaState| {
                    s.bar.detail(&format!(
                        "{label} GA: generation {}/{total}, best {:.3}, {} evaluations",
                        g.generation,
                        g.best().objective,
                        g.ledger.evaluations
                    ))
                })?;
                cache.put(&entry)?;
                (entry, false)
            }
        };
        let chain = problem.space.chain(&result.best_genome)?;
        Ok(GaRun {
            model: label,
            rods: rods_mm(&chain),
            chain,
            cached,
            result,
            population: problem.settings.population,
            generations_limit: total,
            stall: problem.settings.stall_generations,
            objective: problem.objective.as_str().to_string(),
            unit: problem.objective.unit().to_string(),
        })
    }
}

impl GaRun {
    /// A row of a table of optima: `name`, the best chain, its incident and transmitted peak
    /// forces and their ratio (from its re-simulated `summary`), `extra`, and `search`.
    pub fn row(
        &self,
        name: &str,
        summary: &RunSummary,
        extra: String,
        search: String,
    ) -> Vec<String> {
        vec![
            name.to_string(),
            join_mm(&self.rods),
            format!("{:.2} N", summary.incident_peak_force_n),
            format!("{:.2} N", summary.transmitted_peak_force_n),
            pct(ratio(summary)),
            extra,
            search,
        ]
    }

    /// `12 generations, 610 simulations[, 3.2 s][ (from cache)]`.
    pub fn search_text(&self, with_time: bool) -> String {
        let r = &self.result;
        let time = if with_time {
            format!(", {:.1} s", r.elapsed_s)
        } else {
            String::new()
        };
        let cached = if self.cached { " (from cache)" } else { "" };
        format!(
            "{} generations, {} simulations{time}{cached}",
            r.generations, r.evaluations
        )
    }
}

/// Runs `problem`'s GA to its end, `progress` after every generation.
fn run(
    problem: &Problem,
    key: String,
    progress: &mut dyn FnMut(&GaState),
) -> Result<CachedGa, Error> {
    let ga = BreederGa::new(
        problem.space.clone(),
        Box::new(problem.objective),
        problem.settings,
    )
    .map_err(optimize_error)?;
    let mut observer = |g: &GaState| {
        progress(g);
        std::ops::ControlFlow::Continue(())
    };
    let never = std::sync::atomic::AtomicBool::new(false);
    let outcome = ga
        .run(None, &never, &mut observer)
        .map_err(optimize_error)?;
    let s = &outcome.state;
    Ok(CachedGa {
        inputs: key,
        best_genome: s.best().genome.clone(),
        best_objective: s.best().objective,
        history: s.history.clone(),
        generations: s.generation,
        evaluations: s.ledger.evaluations,
        cache_hits: s.ledger.cache_hits,
        elapsed_s: s.elapsed_s,
        stop_reason: format!("{:?}", outcome.reason),
    })
}

/// Rod lengths of a chain, top to bottom \[mm\] (sphere diameters for spheres), rounded.
fn rods_mm(chain: &Chain) -> Vec<u32> {
    chain
        .elements()
        .iter()
        .map(|e| match e.body {
            woodpile::Body::Rod { length_m, .. } => (length_m * 1e3).round() as u32,
            woodpile::Body::Sphere { diameter_m } => (diameter_m * 1e3).round() as u32,
        })
        .collect()
}
