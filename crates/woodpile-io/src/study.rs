//! The paper's study as data: the cases `woodpile report` runs, and every number the paper
//! reports (docs/physics.md §9), each stated once. A table shows a reference value through
//! [`PaperValue::text`], derived from the number, so the text and the number cannot disagree.

use crate::atomic::write_atomic;
use crate::optimize::{fnv1a64, OptimizeConfig};
use crate::scenario::ModelSpec;
use serde::{Deserialize, Serialize};
use std::fs;
use std::path::{Path, PathBuf};
use woodpile::CellModel;

/// How a reference value is read and compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// A force \[N\], shown with one decimal; compared in percent of the paper's value.
    ForceN,
    /// A fraction, shown in percent with one decimal; compared in percentage points.
    Fraction,
    /// A dimensionless coefficient, shown with four decimals; compared in percent.
    Coefficient,
    /// A time \[s\], shown in ms; compared in percent.
    DurationS,
}

/// One number the paper reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperValue {
    /// What it is.
    pub what: &'static str,
    /// The value, in SI units (a fraction for percentages).
    pub value: f64,
    /// How to read and compare it.
    pub quantity: Quantity,
    /// Whether the paper gives it only approximately ("~70 %").
    pub approximate: bool,
}

impl PaperValue {
    /// The value as the paper states it.
    pub fn text(&self) -> String {
        let number = match self.quantity {
            Quantity::ForceN => format!("{:.1} N", self.value),
            // "~70 %": an approximate value is stated to the percent.
            Quantity::Fraction if self.approximate => format!("{:.0} %", 100.0 * self.value),
            Quantity::Fraction => format!("{:.1} %", 100.0 * self.value),
            Quantity::Coefficient => format!("{:.4}", self.value),
            Quantity::DurationS => format!("{} ms", self.value * 1e3),
        };
        if self.approximate {
            format!("~{number}")
        } else {
            number
        }
    }

    /// A measured value in the same form as [`PaperValue::text`].
    pub fn format(&self, ours: f64) -> String {
        PaperValue {
            value: ours,
            approximate: false,
            ..*self
        }
        .text()
    }

    /// Our value against the paper's: percent of the paper's value, or percentage points for a
    /// fraction.
    pub fn difference(&self, ours: f64) -> String {
        match self.quantity {
            Quantity::Fraction => format!("{:+.1} pp", 100.0 * (ours - self.value)),
            _ => format!("{:+.1} %", 100.0 * (ours - self.value) / self.value),
        }
    }
}

const fn value(what: &'static str, value: f64, quantity: Quantity) -> PaperValue {
    PaperValue {
        what,
        value,
        quantity,
        approximate: false,
    }
}

/// Impact, resonant GA optimum: the force on the sensor.
pub const RESONANT_TRANSMITTED: PaperValue = value(
    "Resonant optimum: transmitted (wall) force",
    28.5,
    Quantity::ForceN,
);
/// Impact, resonant GA optimum: the incident force (contact 1).
pub const RESONANT_INCIDENT: PaperValue = value(
    "Resonant optimum: incident force (contact 1)",
    159.6,
    Quantity::ForceN,
);
/// Impact, resonant GA optimum: transmitted / incident.
pub const RESONANT_RATIO: PaperValue = value(
    "Resonant optimum: transmitted / incident",
    0.179,
    Quantity::Fraction,
);
/// Impact, rigid GA optimum: the force on the sensor.
pub const RIGID_TRANSMITTED: PaperValue = value(
    "Rigid optimum: transmitted (wall) force",
    85.5,
    Quantity::ForceN,
);
/// Impact, rigid GA optimum: the incident force.
pub const RIGID_INCIDENT: PaperValue = value(
    "Rigid optimum: incident force (contact 1)",
    148.4,
    Quantity::ForceN,
);
/// Impact, rigid GA optimum: transmitted / incident.
pub const RIGID_RATIO: PaperValue = value(
    "Rigid optimum: transmitted / incident",
    0.576,
    Quantity::Fraction,
);
/// How much less the resonant optimum transmits than the rigid one: 1 − ratio_res/ratio_rigid.
pub const RESONANT_ADVANTAGE: PaperValue = value(
    "Resonant better than rigid (1 − ratio_res / ratio_rigid)",
    0.689,
    Quantity::Fraction,
);
/// Striker restitution of the resonant optimum.
pub const RESONANT_RESTITUTION: PaperValue = value(
    "Striker restitution, resonant optimum",
    0.2570,
    Quantity::Coefficient,
);
/// Striker restitution of the rigid optimum.
pub const RIGID_RESTITUTION: PaperValue = value(
    "Striker restitution, rigid optimum",
    0.4991,
    Quantity::Coefficient,
);
/// Impact on 80 mm rods: time between the two groups of the split wave.
pub const GAP_80MM: PaperValue = value(
    "Impact on 20 × 80 mm rods: time between the two pulse groups",
    0.2e-3,
    Quantity::DurationS,
);
/// Blast: peak transmitted energy of the 40 mm chain over the 20 mm chain's.
pub const BLAST_40MM: PaperValue = PaperValue {
    approximate: true,
    ..value(
        "Blast: peak transmitted energy (last layer), 40 mm chain / 20 mm chain",
        0.70,
        Quantity::Fraction,
    )
};
/// Blast: peak transmitted energy of the 80 mm chain over the 20 mm chain's.
pub const BLAST_80MM: PaperValue = PaperValue {
    approximate: true,
    ..value(
        "Blast: peak transmitted energy (last layer), 80 mm chain / 20 mm chain",
        0.70,
        Quantity::Fraction,
    )
};
/// Blast: peak transmitted energy of the paper's optimised chain over the 20 mm chain's.
pub const BLAST_OPTIMUM: PaperValue = value(
    "Blast: peak transmitted energy (last layer), paper optimum chain / 20 mm chain",
    0.083,
    Quantity::Fraction,
);

/// What the paper says of the wave at the wall of homogeneous chains under the impact, by rod
/// length \[mm\] (qualitative).
pub const WAVE_SHAPES: [(u32, &str); 3] = [
    (20, "one solitary wave with a small oscillating tail"),
    (40, "wave split into groups separated in time"),
    (80, "two groups ~0.2 ms apart"),
];

/// The low-energy bands the paper sees in the blast spectra, by rod length \[mm\] (as printed).
pub const BLAST_BANDS: [(u32, &str); 3] = [
    (20, "38–55 kHz"),
    (40, "10–15 kHz"),
    (80, "2.7–3.9 and 15–20 kHz"),
];

/// A homogeneous chain the report runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HomogeneousCase {
    /// Rod length \[mm\] (Table 1).
    pub rod_mm: u32,
    /// Cell model.
    pub model: CellModel,
    /// Short name for tables.
    pub name: &'static str,
    /// File-name part.
    pub slug: &'static str,
}

/// Number of rods in every chain of the paper.
pub const CHAIN_LENGTH: usize = 20;

/// The impact runs on homogeneous chains (paper Figs. 5 a–c, 6).
pub const IMPACT_HOMOGENEOUS: [HomogeneousCase; 4] = [
    HomogeneousCase {
        rod_mm: 20,
        model: CellModel::Resonant,
        name: "20 mm",
        slug: "20mm",
    },
    HomogeneousCase {
        rod_mm: 40,
        model: CellModel::Resonant,
        name: "40 mm",
        slug: "40mm",
    },
    HomogeneousCase {
        rod_mm: 80,
        model: CellModel::Resonant,
        name: "80 mm",
        slug: "80mm",
    },
    HomogeneousCase {
        rod_mm: 20,
        model: CellModel::Rigid,
        name: "20 mm rigid",
        slug: "20mm_rigid",
    },
];

/// The blast runs (paper Figs. 8, 9): homogeneous 20, 40, 80 mm resonant chains, and the
/// paper's blast-optimised chain (`None`: [`woodpile::PAPER_OPTIMIZED_CHAIN_MM`]).
pub const BLAST_CHAINS: [(Option<u32>, &str, &str); 4] = [
    (Some(20), "20 mm", "20mm"),
    (Some(40), "40 mm", "40mm"),
    (Some(80), "80 mm", "80mm"),
    (None, "paper optimum", "paper_optimum"),
];

/// The GA problem of the paper's Fig. 5 d, e: the built-in `paper-impact` problem with the given
/// cell model and seed; `quick` shrinks the GA to population 10 × 5 generations (for CI).
pub fn ga_problem(
    model: ModelSpec,
    seed: u64,
    quick: bool,
) -> Result<OptimizeConfig, crate::Error> {
    let mut cfg = OptimizeConfig::builtin("paper-impact")?;
    cfg.design.model = Some(model);
    cfg.ga.seed = Some(seed);
    if quick {
        cfg.ga.population = Some(10);
        cfg.ga.generations = Some(5);
    }
    Ok(cfg)
}

/// The paper's impact problem (20 positions, resonant) over rods with cells derived from beam
/// theory (docs/physics.md §13): lengths 20–80 mm every `step_mm` (10: the paper's seven lengths;
/// 1: the fine design space of 61 lengths).
pub fn derived_ga_problem(
    step_mm: f64,
    seed: u64,
    quick: bool,
) -> Result<OptimizeConfig, crate::Error> {
    let mut cfg = ga_problem(ModelSpec::Resonant, seed, quick)?;
    cfg.description = Some(format!(
        "paper impact problem over rods 20-80 mm every {step_mm} mm, cells from beam theory"
    ));
    cfg.design.catalogue_mm = None;
    cfg.design.rod_range = Some(crate::optimize::RodRangeSpec {
        from_mm: 20.0,
        to_mm: 80.0,
        step_mm,
        diameters_mm: Vec::new(),
        materials: Vec::new(),
        modes: None,
    });
    Ok(cfg)
}

/// Mean rod length of a chain \[mm\].
pub fn mean_length_mm(rods_mm: &[u32]) -> f64 {
    rods_mm.iter().map(|&r| f64::from(r)).sum::<f64>() / rods_mm.len().max(1) as f64
}

/// Fraction of interior positions whose rod is longer or shorter than both neighbours (1 for a
/// strictly alternating heavy/light chain, the paper's rigid optimum).
pub fn alternation(rods_mm: &[u32]) -> f64 {
    if rods_mm.len() < 3 {
        return 0.0;
    }
    let n = rods_mm
        .windows(3)
        .filter(|w| (w[1] > w[0] && w[1] > w[2]) || (w[1] < w[0] && w[1] < w[2]))
        .count();
    n as f64 / (rods_mm.len() - 2) as f64
}

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
    pub history: Vec<woodpile::optimize::GenerationStats>,
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
    pub fn key_text(kind: &str, inputs: &impl Serialize) -> String {
        format!(
            "woodpile {} {CACHE_FORMAT} {kind}\n{}",
            env!("CARGO_PKG_VERSION"),
            serde_json::to_string(inputs).unwrap_or_default()
        )
    }

    /// The entry file of a key: its FNV-1a hash.
    fn file(&self, text: &str) -> (PathBuf, String) {
        let name = format!("{:016x}.json", fnv1a64(text.as_bytes()));
        (self.dir.join(&name), name)
    }

    /// The cached GA for these inputs, if an entry with exactly this key text exists.
    pub fn get(&self, text: &str) -> Option<CachedGa> {
        let (path, _) = self.file(text);
        let entry: CachedGa = serde_json::from_str(&fs::read_to_string(path).ok()?).ok()?;
        (entry.inputs == text).then_some(entry)
    }

    /// Stores an entry atomically.
    pub fn put(&self, entry: &CachedGa) -> Result<(), crate::Error> {
        let (path, name) = self.file(&entry.inputs);
        let json = serde_json::to_vec(entry).map_err(|e| crate::Error::Output {
            path,
            source: std::io::Error::other(e),
        })?;
        write_atomic(&self.dir, &name, &json)
    }
}

/// The output policy of `woodpile report`: `out` is created if absent; an existing directory must
/// be empty or hold an earlier report (report.md, report.html, figures/, cache/), which is then
/// updated in place; `figures/` and `cache/` are created and the directory is proved writable
/// before any work is done.
pub fn prepare_report_dir(out: &Path) -> Result<(), crate::Error> {
    if out.exists() && !out.is_dir() {
        return Err(crate::Error::invalid(
            "--out",
            out.display(),
            "is a file, not a directory; choose a directory",
        ));
    }
    if out.is_dir() {
        let mut entries = fs::read_dir(out).map_err(crate::atomic::io_err(out))?;
        let known = ["report.md", "report.html", "figures", "cache"];
        let earlier = known.iter().any(|k| out.join(k).exists());
        if entries.next().is_some() && !earlier {
            return Err(crate::Error::invalid(
                "--out",
                out.display(),
                "exists, is not empty and holds no earlier report: refusing to write into it; choose another --out",
            ));
        }
    }
    for d in [out.to_path_buf(), out.join("figures"), out.join("cache")] {
        fs::create_dir_all(&d).map_err(crate::atomic::io_err(&d))?;
    }
    write_atomic(out, ".write-test", b"")?;
    let _ = fs::remove_file(out.join(".write-test"));
    Ok(())
}

/// The result of `problem`'s GA: from `cache` when it holds one for the same inputs (`true`),
/// else run now (with `progress` after every generation) and stored.
pub fn cached_ga(
    problem: &crate::optimize::Problem,
    cache: &Cache,
    progress: &mut dyn FnMut(&woodpile::optimize::GaState),
) -> Result<(CachedGa, bool), crate::Error> {
    use woodpile::optimize::BreederGa;
    let key = Cache::key_text("ga", &problem.config);
    if let Some(entry) = cache.get(&key) {
        if entry.best_genome.len() == problem.space.positions {
            return Ok((entry, true));
        }
    }
    let ga = BreederGa::new(
        problem.space.clone(),
        Box::new(problem.objective),
        problem.settings,
    )
    .map_err(crate::optimize::optimize_error)?;
    let mut observer = |s: &woodpile::optimize::GaState| {
        progress(s);
        std::ops::ControlFlow::Continue(())
    };
    let outcome = ga
        .run(
            None,
            &std::sync::atomic::AtomicBool::new(false),
            &mut observer,
        )
        .map_err(crate::optimize::optimize_error)?;
    let s = &outcome.state;
    let entry = CachedGa {
        inputs: key,
        best_genome: s.best().genome.clone(),
        best_objective: s.best().objective,
        history: s.history.clone(),
        generations: s.generation,
        evaluations: s.ledger.evaluations,
        cache_hits: s.ledger.cache_hits,
        elapsed_s: s.elapsed_s,
        stop_reason: format!("{:?}", outcome.reason),
    };
    cache.put(&entry)?;
    Ok((entry, false))
}

/// Peak forces F0 \[N\] of the blast sweep (docs/physics.md §6: the paper gives none).
pub const BLAST_SWEEP_PEAKS_N: [f64; 8] = [50.0, 100.0, 150.0, 200.0, 300.0, 400.0, 800.0, 1600.0];
/// Positive-phase durations Td \[s\] of the blast sweep (the paper says its blast lasted about
/// 0.5 ms; the default is 0.2 ms).
pub const BLAST_SWEEP_DURATIONS_S: [f64; 6] = [1e-4, 2e-4, 3e-4, 4e-4, 5e-4, 6e-4];

/// One Friedlander load of the blast sweep and the paper's three blast ratios it gives.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BlastSweepPoint {
    /// F0 \[N\].
    pub peak_force_n: f64,
    /// Td \[s\].
    pub duration_s: f64,
    /// Peak energy of the last layer over the 20 mm chain's: 40 mm chain, 80 mm chain, the
    /// paper's blast-optimised chain (the paper: ~70 %, ~70 %, 8.3 %).
    pub ratios: [f64; 3],
    /// The largest factor by which one of the three misses the paper's value
    /// (max over the three of max(ours/paper, paper/ours)): 1 when all three agree.
    pub worst_factor: f64,
}

/// The paper's three blast ratios (40 mm, 80 mm, optimised chain over the 20 mm chain).
pub const BLAST_RATIOS: [PaperValue; 3] = [BLAST_40MM, BLAST_80MM, BLAST_OPTIMUM];

/// The blast sweep: every F0 × Td of a grid (rows F0, columns Td).
#[derive(Debug, Clone, PartialEq)]
pub struct BlastSweep {
    /// F0 of the rows \[N\].
    pub peaks_n: Vec<f64>,
    /// Td of the columns \[s\].
    pub durations_s: Vec<f64>,
    /// The points, row-major.
    pub points: Vec<BlastSweepPoint>,
}

impl BlastSweep {
    /// The points, closest to the paper first.
    pub fn ranked(&self) -> Vec<&BlastSweepPoint> {
        let mut v: Vec<&BlastSweepPoint> = self.points.iter().collect();
        v.sort_by(|a, b| a.worst_factor.total_cmp(&b.worst_factor));
        v
    }

    /// The smallest and largest of ratio `k` (0: 40 mm, 1: 80 mm, 2: optimum) over the loads
    /// lasting at least `min_duration_s`.
    pub fn ratio_range(&self, k: usize, min_duration_s: f64) -> Option<(f64, f64)> {
        self.points
            .iter()
            .filter(|p| p.duration_s >= min_duration_s)
            .map(|p| p.ratios[k])
            .fold(None, |acc, r| match acc {
                None => Some((r, r)),
                Some((lo, hi)) => Some((lo.min(r), hi.max(r))),
            })
    }

    /// The worst factor over F0 (rows) × Td (columns), for a heat map.
    pub fn worst_factor_map(&self) -> Result<woodpile::analysis::Map2, crate::Error> {
        use woodpile::analysis::{Axis, Map2};
        Ok(Map2::new(
            Axis::new("peak force F0", "N", self.peaks_n.clone()),
            Axis::new("duration Td", "s", self.durations_s.clone()),
            "worst factor off the paper",
            "1",
            self.points.iter().map(|p| p.worst_factor).collect(),
        )?)
    }
}

/// Runs the four blast chains (20, 40, 80 mm and the paper's optimum, resonant Table 1 rods, on
/// the paper's sensor) under a Friedlander load (decay 1) for every F0 × Td, in parallel, each
/// for `settings` (the run must outlast the slowest wave: 3 ms by default).
pub fn blast_sweep(
    peaks_n: &[f64],
    durations_s: &[f64],
    settings: &woodpile::RunSettings,
) -> Result<BlastSweep, crate::Error> {
    use rayon::prelude::*;
    use woodpile::{analysis::peak_layer_energy, ChainBuilder, Excitation, Trajectory};
    let chains = BLAST_CHAINS
        .iter()
        .map(|&(rod_mm, _, _)| {
            let rods = rod_mm.map_or(woodpile::PAPER_OPTIMIZED_CHAIN_MM.to_vec(), |l| {
                vec![l; CHAIN_LENGTH]
            });
            Ok(ChainBuilder::table1_rods(&rods, CellModel::Resonant)?.build()?)
        })
        .collect::<Result<Vec<_>, crate::Error>>()?;
    let grid: Vec<(f64, f64)> = peaks_n
        .iter()
        .flat_map(|&f| durations_s.iter().map(move |&t| (f, t)))
        .collect();
    grid.par_iter()
        .map(|&(peak_force_n, duration_s)| {
            let load = Excitation::Blast(woodpile::BlastProfile::Friedlander {
                peak_force_n,
                duration_s,
                decay: 1.0,
            });
            let energies = chains
                .iter()
                .map(|chain| {
                    let mut t = Trajectory::default();
                    woodpile::simulate(chain, &load, settings, &mut t)?;
                    Ok(peak_layer_energy(&t, chain.len()))
                })
                .collect::<Result<Vec<f64>, crate::Error>>()?;
            let ratios = [1, 2, 3].map(|k| energies[k] / energies[0]);
            let worst_factor = ratios
                .iter()
                .zip(&BLAST_RATIOS)
                .map(|(r, p)| (r / p.value).max(p.value / r))
                .fold(1.0, f64::max);
            Ok(BlastSweepPoint {
                peak_force_n,
                duration_s,
                ratios,
                worst_factor,
            })
        })
        .collect::<Result<Vec<_>, crate::Error>>()
        .map(|points| BlastSweep {
            peaks_n: peaks_n.to_vec(),
            durations_s: durations_s.to_vec(),
            points,
        })
}

/// Rod lengths of a chain, top to bottom \[mm\] (sphere diameters for spheres), rounded.
pub fn rods_mm(chain: &woodpile::Chain) -> Vec<u32> {
    chain
        .elements()
        .iter()
        .map(|e| match e.body {
            woodpile::Body::Rod { length_m, .. } => (length_m * 1e3).round() as u32,
            woodpile::Body::Sphere { diameter_m } => (diameter_m * 1e3).round() as u32,
        })
        .collect()
}

/// A GA of the paper study, with what the report says of it.
#[derive(Debug, Clone)]
pub struct GaRun {
    /// Its label (`resonant`, `rigid`, …).
    pub model: &'static str,
    /// The best chain.
    pub chain: woodpile::Chain,
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

/// Builds `cfg`'s problem and gets its GA result through [`cached_ga`]; `progress` gets each
/// generation's state and the generation limit.
pub fn ga_run(
    cfg: &OptimizeConfig,
    label: &'static str,
    threads: usize,
    cache: &Cache,
    progress: &mut dyn FnMut(&woodpile::optimize::GaState, usize),
) -> Result<GaRun, crate::Error> {
    use woodpile::optimize::Objective;
    let problem = crate::optimize::Problem::new(cfg, Path::new("."), threads)?;
    let total = problem.settings.generations;
    let (result, cached) = cached_ga(&problem, cache, &mut |s| progress(s, total))?;
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

/// One run of the study, kept with its trajectory for the figures.
#[derive(Debug, Clone)]
pub struct Case {
    /// Short name, e.g. `20 mm`.
    pub name: String,
    /// File stem part, e.g. `20mm`.
    pub slug: String,
    /// Title part naming the chain, e.g. `20 × 20 mm rods (resonant)`.
    pub chain_title: String,
    /// The chain.
    pub chain: woodpile::Chain,
    /// Its figures of merit.
    pub summary: woodpile::RunSummary,
    /// Its trajectory on the sample grid.
    pub trajectory: woodpile::Trajectory,
    /// The chain's negative-mass bands to mark ([`woodpile::analysis::chain_bands_hz`]).
    pub bands: Vec<(f64, f64)>,
}

/// Runs `chain` under `excitation` for a [`Case`].
pub fn simulate_case(
    name: &str,
    slug: &str,
    chain_title: &str,
    chain: woodpile::Chain,
    excitation: &woodpile::Excitation,
    settings: &woodpile::RunSettings,
) -> Result<Case, crate::Error> {
    let mut trajectory = woodpile::Trajectory::default();
    let summary = woodpile::simulate(&chain, excitation, settings, &mut trajectory)?;
    let bands = woodpile::analysis::chain_bands_hz(chain.elements().iter().map(|e| &e.cell));
    Ok(Case {
        name: name.to_string(),
        slug: slug.to_string(),
        chain_title: chain_title.to_string(),
        chain,
        summary,
        trajectory,
        bands,
    })
}

/// The damping the report states for the layer-by-layer protocol (docs/physics.md §14):
/// restitution e = 0.9 at every contact (tension-free) and resonators damped at ζ = 0.01 — an
/// illustration of a lossy laboratory column, not a measured property of fused quartz.
pub fn stated_damping() -> woodpile::Damping {
    woodpile::Damping {
        contacts: woodpile::ContactDamping::Restitution { coefficient: 0.9 },
        resonator_ratio: 0.01,
        ..woodpile::Damping::default()
    }
}

/// The report's transmission case (docs/physics.md §15): twenty 80 mm rods on the sensor under a
/// static force of [`TRANSMISSION_PRELOAD_N`] on the top rod, on-site damping
/// [`TRANSMISSION_ON_SITE_S`], and the spectrum's settings (the defaults, RK4 at 0.2 µs).
pub fn transmission_case(
) -> Result<(woodpile::Chain, woodpile::analysis::TransmissionSettings), crate::Error> {
    let chain = woodpile::ChainBuilder::table1_rods(&[80; 20], woodpile::CellModel::Resonant)?
        .preload(woodpile::Preload {
            force_n: TRANSMISSION_PRELOAD_N,
            gravity_m_s2: 0.0,
        })
        .damping(woodpile::Damping {
            on_site_time_s: Some(TRANSMISSION_ON_SITE_S),
            ..woodpile::Damping::default()
        })
        .build()?;
    let settings = woodpile::analysis::TransmissionSettings {
        method: woodpile::Method::Rk4 { time_step_s: 2e-7 },
        ..woodpile::analysis::TransmissionSettings::standard()
    };
    Ok((chain, settings))
}

/// Static force on the top rod of the report's transmission case \[N\].
pub const TRANSMISSION_PRELOAD_N: f64 = 10.0;
/// On-site damping time of the report's transmission case \[s\].
pub const TRANSMISSION_ON_SITE_S: f64 = 0.02;
