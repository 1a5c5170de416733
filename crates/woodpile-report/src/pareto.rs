//! Force against mass (beyond the paper): NSGA-II's front of transmitted force and total mass
//! over the paper's impact problem (20 positions, the seven Table 1 rods), where the breeder
//! GA's resonant optimum of the `optima` section sits against it, and the hypervolume per
//! generation. Kept cheap (a modest population and generation count, every contact peak within
//! 1e-5) and cached in `OUT/cache/` like the GAs.

use super::doc::Doc;
use super::ga::{Cache, GaRun};
use super::study::{join_mm, Setup};
use crate::Error;
use serde::{Deserialize, Serialize};
use std::fs;
use std::path::{Path, PathBuf};
use woodpile::optimize::{Nsga2, Nsga2State};
use woodpile_io::atomic::write_atomic;
use woodpile_io::optimize::{optimize_error, OptimizeConfig, Problem};
use woodpile_plot as plot;

/// Population and generations of the report's NSGA-II (`--quick`: 12 × 3).
const POPULATION: usize = 60;
const GENERATIONS: usize = 60;

/// The objectives of the section.
const OBJECTIVES: [&str; 2] = ["transmitted-force", "total-mass"];

/// The front as kept in the cache.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CachedFront {
    /// The key's text (checked on load against collisions).
    pub inputs: String,
    /// The front: (catalogue indices, [force N, mass kg]), in order of force.
    pub front: Vec<(Vec<u8>, Vec<f64>)>,
    /// (generation, hypervolume).
    pub history: Vec<(usize, f64)>,
    /// The hypervolume's reference point \[N, kg\].
    pub reference_point: Vec<f64>,
    /// The designs compared with it, evaluated at the same settings: the homogeneous chains,
    /// then the breeder GA's optimum.
    pub references: Vec<(String, Vec<f64>)>,
    /// Simulations run.
    pub evaluations: u64,
    /// Generations completed.
    pub generations: usize,
    /// Wall-clock time \[s\].
    pub elapsed_s: f64,
}

/// The section's results.
pub struct Front {
    /// The front and its references.
    pub result: CachedFront,
    /// Whether it came from the cache.
    pub cached: bool,
    /// Population and generation limit.
    pub population: usize,
    /// Generation limit.
    pub generations_limit: usize,
    /// The breeder optimum's rods \[mm\].
    pub optimum_rods: Vec<u32>,
    /// The front's figure, then the hypervolume's.
    pub files: Vec<PathBuf>,
}

/// The NSGA-II problem of the section.
fn problem_config(s: &Setup) -> Result<OptimizeConfig, Error> {
    let mut cfg = OptimizeConfig::builtin("paper-impact")?;
    cfg.ga.objective = None;
    cfg.ga.objectives = Some(OBJECTIVES.iter().map(|o| o.to_string()).collect());
    cfg.ga.algorithm = Some("nsga2".into());
    cfg.ga.seed = Some(s.seed);
    cfg.ga.population = Some(if s.quick { 12 } else { POPULATION });
    cfg.ga.generations = Some(if s.quick { 3 } else { GENERATIONS });
    Ok(cfg.accuracy_targeted())
}

/// Runs (or reads from the cache) NSGA-II and draws the front with the breeder optimum of
/// `resonant` marked.
pub fn run(s: &Setup, resonant: &GaRun) -> Result<Front, Error> {
    s.bar.stage("force vs mass front (NSGA-II)");
    let cfg = problem_config(s)?;
    let problem = Problem::new(&cfg, Path::new("."), s.threads)?;
    let cache = Cache {
        dir: s.out.join("cache"),
    };
    let key = Cache::key_text("nsga2", &(&problem.config, &resonant.result.best_genome));
    let (path, name) = cache.file(&key);
    let hit = fs::read_to_string(&path)
        .ok()
        .and_then(|t| serde_json::from_str::<CachedFront>(&t).ok())
        .filter(|c| c.inputs == key);
    let cached = hit.is_some();
    let result = match hit {
        Some(c) => c,
        None => {
            let c = compute(s, &problem, key, &resonant.result.best_genome)?;
            let json = serde_json::to_vec(&c).map_err(|e| Error::Output {
                path: path.clone(),
                source: std::io::Error::other(e),
            })?;
            fs::create_dir_all(&cache.dir).map_err(woodpile_io::atomic::io_err(&cache.dir))?;
            write_atomic(&cache.dir, &name, &json)?;
            c
        }
    };
    let files = figures(s, &result)?;
    s.bar.inc(1);
    Ok(Front {
        result,
        cached,
        population: problem.nsga2.population,
        generations_limit: problem.nsga2.generations,
        optimum_rods: resonant.rods.clone(),
        files,
    })
}

/// Runs NSGA-II to its end and evaluates the reference designs at its settings.
fn compute(
    s: &Setup,
    problem: &Problem,
    key: String,
    optimum: &[u8],
) -> Result<CachedFront, Error> {
    let ga = Nsga2::new(
        problem.space.clone(),
        problem.objectives.clone(),
        problem.nsga2.clone(),
    )
    .map_err(optimize_error)?;
    let total = problem.nsga2.generations;
    let mut observer = |st: &Nsga2State| {
        let h = st.history.last().map_or(0.0, |h| h.hypervolume);
        s.bar.detail(&format!(
            "NSGA-II: generation {}/{total}, hypervolume {h:.4}, {} evaluations",
            st.generation, st.evaluations
        ));
        std::ops::ControlFlow::Continue(())
    };
    let never = std::sync::atomic::AtomicBool::new(false);
    let (state, _) = ga
        .run(None, &never, &mut observer)
        .map_err(optimize_error)?;
    let mut designs = woodpile_io::pareto::reference_designs(problem);
    // The paper's chain is the blast optimum: this section compares with the impact optimum.
    designs.retain(|(name, _)| !name.starts_with("paper"));
    designs.push(("breeder GA optimum".into(), optimum.to_vec()));
    let genomes: Vec<&[u8]> = designs.iter().map(|(_, g)| g.as_slice()).collect();
    let values = ga.evaluate_designs(&genomes).map_err(optimize_error)?;
    Ok(CachedFront {
        inputs: key,
        front: state
            .front()
            .iter()
            .map(|i| (i.genome.clone(), i.objectives.clone()))
            .collect(),
        history: state
            .history
            .iter()
            .map(|h| (h.generation, h.hypervolume))
            .collect(),
        reference_point: state.reference_point.clone(),
        references: designs
            .into_iter()
            .zip(values)
            .map(|((name, _), v)| (name, v.objectives))
            .collect(),
        evaluations: state.evaluations,
        generations: state.generation,
        elapsed_s: state.elapsed_s,
    })
}

/// The front with its references, and the hypervolume history.
fn figures(s: &Setup, r: &CachedFront) -> Result<Vec<PathBuf>, Error> {
    let axes: Vec<plot::ObjectiveAxis> = [("transmitted-force", "N"), ("total-mass", "kg")]
        .iter()
        .map(|(n, u)| plot::ObjectiveAxis::new(n, u))
        .collect();
    let front: Vec<Vec<f64>> = r.front.iter().map(|(_, v)| v.clone()).collect();
    let marked: Vec<plot::MarkedDesign> = r
        .references
        .iter()
        .map(|(name, v)| plot::MarkedDesign {
            name: name.clone(),
            values: v.clone(),
            feasible: true,
            highlight: name.starts_with("breeder"),
        })
        .collect();
    let mut files = Vec::new();
    if !front.is_empty() {
        files.extend(plot::pareto_front(
            &axes,
            &front,
            &marked,
            &format!(
                "Force vs mass, paper impact (resonant): NSGA-II front of {} designs",
                front.len()
            ),
            &s.figs.join("pareto_force_mass"),
        )?);
    }
    files.extend(plot::hypervolume_history(
        &r.history,
        "NSGA-II, force vs mass: hypervolume per generation",
        &s.figs.join("pareto_hypervolume"),
    )?);
    Ok(files)
}

impl Front {
    /// The breeder optimum's (force N, mass kg) at the section's settings.
    fn optimum(&self) -> Option<(f64, f64)> {
        let (_, v) = self.result.references.last()?;
        Some((v[0], v[1]))
    }

    /// The section.
    pub fn write(&self, doc: &mut Doc) {
        let r = &self.result;
        doc.h2("Force against mass: the Pareto front (beyond the paper)");
        let cached = if self.cached { " (from cache/)" } else { "" };
        doc.p(format!(
            "NSGA-II (docs/physics.md §11; `ga.objectives = [\"transmitted-force\", \"total-mass\"]`, `ga.algorithm = \"nsga2\"`) over the paper's impact problem: 20 positions, the seven Table 1 rods (resonant), population {}, at most {} generations, every contact peak within 1e-5 (the default of `woodpile optimize`). It ran {} generations and {} simulations in {:.1} s{cached}; its final front holds {} designs, hypervolume {:.4e} N·kg against the reference point ({:.2} N, {:.2} g).",
            self.population,
            self.generations_limit,
            r.generations,
            r.evaluations,
            r.elapsed_s,
            r.front.len(),
            r.history.last().map_or(0.0, |h| h.1),
            r.reference_point.first().copied().unwrap_or(f64::NAN),
            r.reference_point.get(1).copied().unwrap_or(f64::NAN) * 1e3,
        ));
        if let Some((force, mass)) = self.optimum() {
            doc.p(self.optimum_text(force, mass));
        }
        // The front is in order of force: first the least force, last the lightest design.
        if let (Some((_, least)), Some((_, lightest))) = (r.front.first(), r.front.last()) {
            doc.p(format!(
                "The front runs from {:.2} N at {:.1} g to {:.2} N at {:.1} g. NSGA-II starts from a random feasible population; seeding it with the breeder optimum is not offered.",
                least[0],
                least[1] * 1e3,
                lightest[0],
                lightest[1] * 1e3,
            ));
        }
        if self.files.len() >= 4 {
            doc.figure(&self.files[..2], "Transmitted force against total mass: NSGA-II's final front (blue), the homogeneous 20-rod chains (grey crosses) and the breeder GA's resonant optimum of the section above (red triangle), all evaluated at the same settings. What to see: lighter chains transmit more; how far the front is from the breeder optimum at its mass.");
        }
        let hv = &self.files[self.files.len().saturating_sub(2)..];
        doc.figure(hv, "Hypervolume of NSGA-II's front per generation (larger is better). What to see: whether the front was still improving when the budget ended.");
    }

    /// Where the breeder optimum sits against the front, in numbers.
    fn optimum_text(&self, force: f64, mass: f64) -> String {
        let r = &self.result;
        let dominated = r
            .front
            .iter()
            .any(|(_, v)| v[0] <= force && v[1] <= mass && (v[0] < force || v[1] < mass));
        let at_mass = r
            .front
            .iter()
            .filter(|(_, v)| v[1] <= mass)
            .min_by(|a, b| a.1[0].total_cmp(&b.1[0]));
        let head = format!(
            "The breeder GA's resonant optimum ({}) transmits {force:.2} N at {:.1} g at these settings.",
            join_mm(&self.optimum_rods),
            mass * 1e3
        );
        let verdict = if dominated {
            "A design of the front dominates it (as light or lighter and transmitting less)."
                .to_string()
        } else {
            "No design of the front dominates it: at this budget NSGA-II does not reach the breeder optimum.".to_string()
        };
        let nearest = match at_mass {
            Some((_, v)) => format!(
                " The front's least force at a mass no larger than the optimum's is {:.2} N (at {:.1} g), {:+.1} % against the optimum.",
                v[0],
                v[1] * 1e3,
                (v[0] / force - 1.0) * 100.0
            ),
            None => " No design of the front is as light as the optimum.".to_string(),
        };
        format!("{head} {verdict}{nearest}")
    }
}
