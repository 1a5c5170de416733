//! `woodpile optimize`: the breeder genetic algorithm of model.md §11 over a design space read
//! from a config file (or a built-in problem), with a progress bar, a checkpoint after every
//! generation, exact resume and a clean stop on Ctrl-C.
//!
//! The config file is a scenario's `[excitation]`, `[wall]` and `[run]` tables plus:
//!
//! ```toml
//! [design]
//! positions = 20                 # N elements (default 20)
//! catalogue_mm = [20, 30, 40, 50, 60, 70, 80]   # Table 1 rods (default), or:
//! # elements = [{ rod_mm = 20 }, { kind = "sphere", diameter_mm = 5 }]
//! model = "resonant"             # or "rigid"
//! [design.constraints]
//! max_total_mass_g = 50.0
//! fixed = [{ layer = 1, rod_mm = 80 }]          # layer 1 = top; or { layer = 1, element = 0 }
//! max_count = [{ rod_mm = 80, count = 5 }]      # or { element = 6, count = 5 }
//! [ga]
//! population = 100
//! generations = 100
//! truncation = 0.3
//! elites = 1
//! stall_generations = 30         # 0 = no stall limit
//! seed = 1
//! objective = "transmitted-force"   # transmission-ratio | transmitted-energy | transmitted-impulse
//! ```
//!
//! Outputs in `--out DIR`: `checkpoint.json` and `history.csv` (rewritten atomically after every
//! generation), then `population.csv`, `best.toml` (a scenario `woodpile simulate` re-runs to
//! the same figures) and `summary.json`. A directory that holds anything is never written
//! into unless `--resume` continues the run it holds, with the same config.

use crate::commands::Context;
use crate::error::CliError;
use crate::output::io_err;
use crate::scenario::{
    resolve, ChainSpec, ElementSpec, ExcitationKind, ExcitationSpec, ModelSpec, RunSpec, Scenario,
    WallSpec,
};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fs;
use std::io::Write;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use woodpile::optimize::{
    BreederGa, Constraints, DesignSpace, GaSettings, GaState, GenerationStats, Individual,
    Objective, OptimizeError, StandardObjective, StopReason,
};
use woodpile::{simulate, TABLE1_LENGTHS_MM};

/// Names of the built-in problems.
pub const BUILTIN_PROBLEMS: [&str; 2] = ["paper-impact", "paper-blast"];

/// The checkpoint's format tag.
pub const CHECKPOINT_FORMAT: &str = "woodpile-optimize-checkpoint/1";

/// The file that marks a directory as an optimisation run.
pub const CHECKPOINT_FILE: &str = "checkpoint.json";

/// Arguments of `woodpile optimize`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// Config file (TOML): a scenario's excitation, wall and run tables plus design and ga tables.
    #[arg(value_name = "CONFIG.toml", conflicts_with = "scenario")]
    pub file: Option<PathBuf>,
    /// A built-in problem: paper-impact or paper-blast (20 rods, Table 1 catalogue).
    #[arg(long, value_name = "NAME", required_unless_present = "file")]
    pub scenario: Option<String>,
    /// Cell model of the catalogue rods (overrides design.model): resonant or rigid.
    #[arg(long, value_name = "MODEL")]
    pub model: Option<String>,
    /// Output directory (must be absent or empty, unless --resume).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Seed of the GA (overrides ga.seed).
    #[arg(long, value_name = "S")]
    pub seed: Option<u64>,
    /// Worker threads for the simulations (default: one per core). Does not change results.
    #[arg(long, value_name = "T", default_value_t = 0)]
    pub threads: usize,
    /// Continue the run saved in DIR/checkpoint.json (same config and seed).
    #[arg(long)]
    pub resume: bool,
}

/// The config file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OptimizeConfig {
    /// One line saying what the problem is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// `[design]`: positions, catalogue, model, constraints.
    #[serde(default)]
    pub design: DesignSpec,
    /// `[excitation]` as in a scenario file.
    #[serde(default)]
    pub excitation: ExcitationSpec,
    /// `[wall]` as in a scenario file.
    #[serde(default)]
    pub wall: WallSpec,
    /// `[run]` as in a scenario file.
    #[serde(default)]
    pub run: RunSpec,
    /// `[ga]`: the GA's parameters and the objective.
    #[serde(default)]
    pub ga: GaSpec,
}

/// `[design]`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignSpec {
    /// Number of positions N (default 20).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub positions: Option<usize>,
    /// Table 1 rods \[mm\] a position can hold (default: all of 20, 30, …, 80).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub catalogue_mm: Option<Vec<u32>>,
    /// General catalogue, as a scenario's `chain.elements` entries (instead of catalogue_mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<Vec<ElementSpec>>,
    /// Cell model of the catalogue rods (default `resonant`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<ModelSpec>,
    /// Angle between neighbouring rods \[deg\] (default 90).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crossing_angle_deg: Option<f64>,
    /// `[design.constraints]`.
    #[serde(default)]
    pub constraints: ConstraintsSpec,
}

/// `[design.constraints]`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintsSpec {
    /// Largest total mass of the chain \[g\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_total_mass_g: Option<f64>,
    /// Layers whose element is fixed.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fixed: Vec<FixedSpec>,
    /// Largest number of copies of a catalogue entry.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub max_count: Vec<CountSpec>,
}

/// `{ layer = 1, rod_mm = 80 }` or `{ layer = 1, element = 0 }`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixedSpec {
    /// Layer 1..=N (1 = top, next to the striker).
    pub layer: usize,
    /// The catalogue rod by length \[mm\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod_mm: Option<u32>,
    /// The catalogue entry by index (0-based, in catalogue order).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub element: Option<usize>,
}

/// `{ rod_mm = 80, count = 5 }` or `{ element = 6, count = 5 }`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CountSpec {
    /// The catalogue rod by length \[mm\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod_mm: Option<u32>,
    /// The catalogue entry by index (0-based).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub element: Option<usize>,
    /// Most copies allowed.
    pub count: usize,
}

/// `[ga]`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GaSpec {
    /// Population size μ ≥ 2 (default 100).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub population: Option<usize>,
    /// Generations after the initial population (default 100).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub generations: Option<usize>,
    /// Truncation threshold T ∈ (0, 1] (default 0.3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truncation: Option<f64>,
    /// Individuals copied unchanged (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elites: Option<usize>,
    /// Stop after this many generations without improvement; 0 = never (default 30).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stall_generations: Option<usize>,
    /// Seed (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// BGA mutation range in catalogue indices (default: catalogue size − 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mutation_range: Option<f64>,
    /// Objective (default `transmitted-force`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objective: Option<String>,
    /// Fitness cache on (default true); off changes only the run time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cache: Option<bool>,
}

impl OptimizeConfig {
    /// Parses a config from TOML text; syntax errors and unknown keys give line and column.
    pub fn parse(text: &str, source_name: &str) -> Result<Self, CliError> {
        toml::from_str(text).map_err(|e| CliError::Parse {
            source_name: source_name.to_string(),
            message: e.to_string(),
        })
    }

    /// A built-in problem: the paper's 20 rods from Table 1 under its impact or blast.
    pub fn builtin(name: &str) -> Result<Self, CliError> {
        let kind = match name {
            "paper-impact" => ExcitationKind::Impact,
            "paper-blast" => ExcitationKind::Blast,
            _ => {
                return Err(CliError::UnknownScenario {
                    name: name.to_string(),
                    valid: BUILTIN_PROBLEMS.join(", "),
                })
            }
        };
        Ok(OptimizeConfig {
            description: Some(format!(
                "{name}: 20 positions, Table 1 rods 20-80 mm, least transmitted force"
            )),
            excitation: ExcitationSpec {
                kind,
                ..ExcitationSpec::default()
            },
            ..OptimizeConfig::default()
        })
    }

    /// The same config with every default written out.
    pub fn complete(&self) -> Self {
        let mut c = self.clone();
        let d = &mut c.design;
        d.positions.get_or_insert(20);
        if d.elements.is_none() {
            d.catalogue_mm
                .get_or_insert_with(|| TABLE1_LENGTHS_MM.to_vec());
        }
        d.model.get_or_insert(ModelSpec::Resonant);
        d.crossing_angle_deg.get_or_insert(90.0);
        let base = Scenario {
            description: None,
            chain: ChainSpec::default(),
            excitation: c.excitation.clone(),
            wall: c.wall.clone(),
            run: c.run.clone(),
        }
        .complete();
        c.excitation = base.excitation;
        c.wall = base.wall;
        c.run = base.run;
        let g = &mut c.ga;
        let defaults = GaSettings::default();
        g.population.get_or_insert(defaults.population);
        g.generations.get_or_insert(defaults.generations);
        g.truncation.get_or_insert(defaults.truncation);
        g.elites.get_or_insert(defaults.elites);
        g.stall_generations
            .get_or_insert(defaults.stall_generations.unwrap_or(0));
        g.seed.get_or_insert(defaults.seed);
        g.objective
            .get_or_insert_with(|| StandardObjective::default().as_str().to_string());
        g.cache.get_or_insert(true);
        c
    }

    /// The scenario of a chain of this problem (`chain` top to bottom).
    fn scenario(&self, chain: ChainSpec, description: Option<String>) -> Scenario {
        Scenario {
            description,
            chain,
            excitation: self.excitation.clone(),
            wall: self.wall.clone(),
            run: self.run.clone(),
        }
    }

    /// The chain spec of a genome (catalogue indices).
    fn chain_spec(&self, genome: &[u8]) -> ChainSpec {
        let d = &self.design;
        let mut c = ChainSpec {
            model: d.model,
            crossing_angle_deg: d.crossing_angle_deg,
            ..ChainSpec::default()
        };
        match (&d.catalogue_mm, &d.elements) {
            (_, Some(list)) => {
                c.elements = Some(genome.iter().map(|&g| list[g as usize].clone()).collect())
            }
            (Some(rods), None) => {
                c.rods_mm = Some(genome.iter().map(|&g| rods[g as usize]).collect())
            }
            (None, None) => {}
        }
        c
    }
}

/// A config turned into what the library runs.
pub struct Problem {
    /// The completed config.
    pub config: OptimizeConfig,
    /// The design space.
    pub space: DesignSpace,
    /// The GA's settings.
    pub settings: GaSettings,
    /// The objective.
    pub objective: StandardObjective,
    /// Directory relative to which the config's files are found.
    pub base_dir: PathBuf,
}

fn catalogue_index(
    field: &str,
    rod_mm: Option<u32>,
    element: Option<usize>,
    cfg: &OptimizeConfig,
) -> Result<usize, CliError> {
    let d = &cfg.design;
    let n = d
        .elements
        .as_ref()
        .map(Vec::len)
        .or(d.catalogue_mm.as_ref().map(Vec::len))
        .unwrap_or(0);
    match (rod_mm, element) {
        (Some(_), Some(_)) => Err(CliError::invalid(
            field,
            "both rod_mm and element",
            "give one of them",
        )),
        (None, None) => Err(CliError::invalid(
            field,
            "(no element)",
            "give rod_mm = <length in the catalogue> or element = <catalogue index>",
        )),
        (None, Some(e)) if e < n => Ok(e),
        (None, Some(e)) => Err(CliError::invalid(
            format!("{field}.element"),
            e,
            format!("catalogue indices are 0..={}", n.saturating_sub(1)),
        )),
        (Some(l), None) => match &d.catalogue_mm {
            Some(rods) => rods.iter().position(|&r| r == l).ok_or_else(|| {
                CliError::invalid(
                    format!("{field}.rod_mm"),
                    l,
                    format!(
                        "not in design.catalogue_mm = {:?}",
                        rods.iter().collect::<Vec<_>>()
                    ),
                )
            }),
            None => Err(CliError::invalid(
                format!("{field}.rod_mm"),
                l,
                "rod_mm needs design.catalogue_mm; with design.elements use element = <index>",
            )),
        },
    }
}

impl Problem {
    /// Validates a config (after the command line's overrides) and builds the design space.
    pub fn new(config: &OptimizeConfig, base_dir: &Path, threads: usize) -> Result<Self, CliError> {
        let cfg = config.complete();
        let d = &cfg.design;
        let positions = d.positions.unwrap_or(20);
        if positions == 0 {
            return Err(CliError::invalid(
                "design.positions",
                0,
                "must be at least 1",
            ));
        }
        if d.catalogue_mm.is_some() && d.elements.is_some() {
            return Err(CliError::invalid(
                "design",
                "both catalogue_mm and elements",
                "give one catalogue: catalogue_mm (Table 1 rods) or elements (general form)",
            ));
        }
        let n_cat = d
            .elements
            .as_ref()
            .map(Vec::len)
            .or(d.catalogue_mm.as_ref().map(Vec::len))
            .unwrap_or(0);
        if n_cat == 0 {
            let key = if d.elements.is_some() {
                "design.elements"
            } else {
                "design.catalogue_mm"
            };
            return Err(CliError::invalid(
                key,
                "[]",
                "the catalogue needs at least one element, e.g. catalogue_mm = [20, 30, 40, 50, 60, 70, 80]",
            ));
        }
        if n_cat > woodpile::optimize::MAX_CATALOGUE_LEN {
            return Err(CliError::invalid(
                "design.catalogue",
                n_cat,
                format!("at most {} entries", woodpile::optimize::MAX_CATALOGUE_LEN),
            ));
        }
        // The catalogue as a chain resolves every element, the wall, the load and the run
        // under the scenario keys; its errors are renamed to the design keys.
        let catalogue_chain = ChainSpec {
            rods_mm: d.catalogue_mm.clone(),
            elements: d.elements.clone(),
            model: d.model,
            crossing_angle_deg: d.crossing_angle_deg,
            ..ChainSpec::default()
        };
        let resolved =
            resolve(&cfg.scenario(catalogue_chain, None), base_dir).map_err(rename_chain_keys)?;
        let catalogue = resolved.chain.elements().to_vec();
        let c = &d.constraints;
        let mut constraints = Constraints {
            max_total_mass_kg: c.max_total_mass_g.map(|g| g * 1e-3),
            ..Constraints::default()
        };
        for (k, f) in c.fixed.iter().enumerate() {
            let field = format!("design.constraints.fixed[{k}]");
            if f.layer == 0 || f.layer > positions {
                return Err(CliError::invalid(
                    format!("{field}.layer"),
                    f.layer,
                    format!("layers are 1..={positions} (1 = top)"),
                ));
            }
            let e = catalogue_index(&field, f.rod_mm, f.element, &cfg)?;
            constraints.fixed.push((f.layer - 1, e));
        }
        for (k, m) in c.max_count.iter().enumerate() {
            let field = format!("design.constraints.max_count[{k}]");
            let e = catalogue_index(&field, m.rod_mm, m.element, &cfg)?;
            constraints.max_count.push((e, m.count));
        }
        let space = DesignSpace {
            positions,
            catalogue,
            wall: resolved.chain.wall().clone(),
            crossing_angle_rad: resolved.chain.crossing_angle_rad(),
            excitation: resolved.excitation,
            settings: resolved.settings,
            constraints,
        };
        let g = &cfg.ga;
        let objective_name = g.objective.clone().unwrap_or_default();
        let objective =
            StandardObjective::from_name(&objective_name).map_err(CliError::at("ga.objective"))?;
        let settings = GaSettings {
            population: g.population.unwrap_or(100),
            truncation: g.truncation.unwrap_or(0.3),
            elites: g.elites.unwrap_or(1),
            generations: g.generations.unwrap_or(100),
            stall_generations: g.stall_generations.filter(|&s| s > 0),
            seed: g.seed.unwrap_or(1),
            mutation_range: g.mutation_range,
            threads,
            cache: g.cache.unwrap_or(true),
        };
        settings.validate()?;
        woodpile::optimize::FeasibleSet::new(&space).map_err(optimize_error)?;
        Ok(Problem {
            config: cfg,
            space,
            settings,
            objective,
            base_dir: base_dir.to_path_buf(),
        })
    }

    /// The scenario of a genome: the problem's load, support and run with that chain. Files
    /// named in the config (a blast table) are made absolute so the scenario runs from anywhere.
    pub fn scenario(&self, genome: &[u8], description: Option<String>) -> Scenario {
        let mut s = self
            .config
            .scenario(self.config.chain_spec(genome), description);
        if let Some(file) = &s.excitation.file {
            let p = self.base_dir.join(file);
            let p = p.canonicalize().unwrap_or(p);
            s.excitation.file = Some(p.display().to_string());
        }
        s
    }
}

/// Renames `chain.*` keys of a resolution error to the `design.*` keys of the config.
fn rename_chain_keys(e: CliError) -> CliError {
    let rename = |f: String| {
        f.replace("chain.rods_mm", "design.catalogue_mm")
            .replace("chain.elements", "design.elements")
            .replace("chain.crossing_angle_deg", "design.crossing_angle_deg")
    };
    match e {
        CliError::Invalid {
            field,
            value,
            reason,
        } => CliError::Invalid {
            field: rename(field),
            value,
            reason,
        },
        CliError::Field { field, source } => CliError::Field {
            field: rename(field),
            source,
        },
        CliError::Model(woodpile::Error::InvalidParameter {
            field,
            value,
            reason,
        }) => CliError::Model(woodpile::Error::InvalidParameter {
            field: rename(field),
            value,
            reason,
        }),
        other => other,
    }
}

/// The command line's error for a library optimisation error.
fn optimize_error(e: OptimizeError) -> CliError {
    match e {
        OptimizeError::Model(m) => CliError::Model(m),
        OptimizeError::Infeasible { reason } => CliError::invalid(
            "design.constraints",
            "(as given)",
            format!("no design meets them: {reason}"),
        ),
        OptimizeError::Simulation { design, source } => {
            eprintln!("error while evaluating design [{design}]");
            CliError::Model(source)
        }
        OptimizeError::NotANumber { objective, design } => CliError::invalid(
            "ga.objective",
            objective,
            format!("returned NaN for design [{design}]"),
        ),
        OptimizeError::StateMismatch { reason } => {
            CliError::invalid("--resume", CHECKPOINT_FILE, reason)
        }
        OptimizeError::ThreadPool { threads, reason } => {
            CliError::invalid("--threads", threads, reason)
        }
    }
}

/// One individual in the checkpoint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IndividualJson {
    /// Catalogue indices, top to bottom.
    pub genome: Vec<u8>,
    /// Objective value.
    pub objective: f64,
}

/// One line of the history in the checkpoint (and `history.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HistoryJson {
    /// Generation.
    pub generation: usize,
    /// Best objective.
    pub best: f64,
    /// Mean objective.
    pub mean: f64,
    /// Worst objective.
    pub worst: f64,
    /// Simulations so far.
    pub evaluations: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
    /// Wall-clock seconds so far.
    pub elapsed_s: f64,
}

/// `checkpoint.json`: the complete config and the GA's whole state. Floats are written with
/// shortest round-trip digits and read back exactly, so a resumed run continues bit for bit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checkpoint {
    /// [`CHECKPOINT_FORMAT`].
    pub format: String,
    /// The completed config the run was started with (seed included).
    pub config: OptimizeConfig,
    /// Generations completed.
    pub generation: usize,
    /// Generations since the best improved.
    pub stalled: usize,
    /// Simulations so far.
    pub evaluations: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
    /// Wall-clock seconds so far.
    pub elapsed_s: f64,
    /// Population, best first.
    pub population: Vec<IndividualJson>,
    /// History, one line per generation.
    pub history: Vec<HistoryJson>,
    /// Fitness cache, sorted by genome.
    pub cache: Vec<IndividualJson>,
}

impl Checkpoint {
    fn new(config: &OptimizeConfig, s: &GaState) -> Self {
        let ind = |genome: &Vec<u8>, objective: f64| IndividualJson {
            genome: genome.clone(),
            objective,
        };
        let mut cache: Vec<IndividualJson> = s.cache.iter().map(|(g, &v)| ind(g, v)).collect();
        cache.sort_by(|a, b| a.genome.cmp(&b.genome));
        Checkpoint {
            format: CHECKPOINT_FORMAT.to_string(),
            config: config.clone(),
            generation: s.generation,
            stalled: s.stalled,
            evaluations: s.evaluations,
            cache_hits: s.cache_hits,
            elapsed_s: s.elapsed_s,
            population: s
                .population
                .iter()
                .map(|i| ind(&i.genome, i.objective))
                .collect(),
            history: s.history.iter().map(HistoryJson::from).collect(),
            cache,
        }
    }

    fn into_state(self) -> GaState {
        GaState {
            generation: self.generation,
            population: self
                .population
                .into_iter()
                .map(|i| Individual {
                    genome: i.genome,
                    objective: i.objective,
                })
                .collect(),
            history: self
                .history
                .iter()
                .map(|h| GenerationStats {
                    generation: h.generation,
                    best: h.best,
                    mean: h.mean,
                    worst: h.worst,
                    evaluations: h.evaluations,
                    cache_hits: h.cache_hits,
                    elapsed_s: h.elapsed_s,
                })
                .collect(),
            cache: self
                .cache
                .into_iter()
                .map(|i| (i.genome, i.objective))
                .collect::<HashMap<_, _>>(),
            evaluations: self.evaluations,
            cache_hits: self.cache_hits,
            stalled: self.stalled,
            elapsed_s: self.elapsed_s,
        }
    }
}

impl From<&GenerationStats> for HistoryJson {
    fn from(h: &GenerationStats) -> Self {
        HistoryJson {
            generation: h.generation,
            best: h.best,
            mean: h.mean,
            worst: h.worst,
            evaluations: h.evaluations,
            cache_hits: h.cache_hits,
            elapsed_s: h.elapsed_s,
        }
    }
}

/// Writes `bytes` to `dir/name` atomically: a temporary file in the same directory, flushed to
/// disk, then renamed over the old one.
pub fn write_atomic(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), CliError> {
    let path = dir.join(name);
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        fs::rename(&tmp, &path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result.map_err(io_err(&path))
}

fn history_csv(history: &[GenerationStats]) -> String {
    let mut s = String::from("generation,best,mean,worst,evaluations,cache_hits,elapsed_s\n");
    for h in history {
        s.push_str(&format!(
            "{},{},{},{},{},{},{:.3}\n",
            h.generation, h.best, h.mean, h.worst, h.evaluations, h.cache_hits, h.elapsed_s
        ));
    }
    s
}

fn population_csv(space: &DesignSpace, population: &[Individual]) -> String {
    let mut s = String::from("rank,objective");
    for l in 1..=space.positions {
        s.push_str(&format!(",layer_{l}"));
    }
    s.push('\n');
    for (r, i) in population.iter().enumerate() {
        s.push_str(&format!("{},{}", r + 1, i.objective));
        for l in space.labels(&i.genome) {
            s.push(',');
            s.push_str(&l);
        }
        s.push('\n');
    }
    s
}

/// `summary.json`.
#[derive(Debug, Clone, Serialize)]
struct SummaryJson<'a> {
    tool: &'static str,
    version: &'static str,
    problem: &'a str,
    status: &'static str,
    stop_reason: &'static str,
    objective: &'a str,
    objective_unit: &'a str,
    best_objective: f64,
    best_chain_labels: Vec<String>,
    best_rods_mm: Option<Vec<u32>>,
    best_genome: &'a [u8],
    best_total_mass_g: f64,
    incident_peak_force_n: f64,
    transmitted_peak_force_n: f64,
    transmission_ratio: f64,
    restitution_coefficient: Option<f64>,
    seed: u64,
    generations_completed: usize,
    evaluations: u64,
    cache_hits: u64,
    elapsed_s: f64,
    evaluations_per_s: f64,
    config: &'a OptimizeConfig,
}

fn stop_text(reason: StopReason) -> &'static str {
    match reason {
        StopReason::GenerationLimit => "generation limit",
        StopReason::Stalled => "stall limit",
        StopReason::Interrupted => "interrupted",
        StopReason::Observer => "output error",
    }
}

/// Loads the config the arguments name, with the command line's overrides.
pub fn load_config(args: &Args) -> Result<(OptimizeConfig, String, PathBuf), CliError> {
    let (mut cfg, name, base) = match (&args.file, &args.scenario) {
        (Some(file), _) => {
            let text = fs::read_to_string(file).map_err(|e| CliError::Read {
                path: file.clone(),
                source: e,
            })?;
            let cfg = OptimizeConfig::parse(&text, &file.display().to_string())?;
            let base = match file.parent() {
                Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
                _ => PathBuf::from("."),
            };
            let name = file
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "optimize".into());
            (cfg, name, base)
        }
        (None, Some(name)) => (
            OptimizeConfig::builtin(name)?,
            name.clone(),
            PathBuf::from("."),
        ),
        (None, None) => {
            return Err(CliError::invalid(
                "CONFIG.toml",
                "(none)",
                format!(
                    "give a config file or --scenario {}",
                    BUILTIN_PROBLEMS.join("|")
                ),
            ))
        }
    };
    if let Some(m) = &args.model {
        cfg.design.model = Some(match m.as_str() {
            "resonant" => ModelSpec::Resonant,
            "rigid" => ModelSpec::Rigid,
            other => {
                return Err(CliError::invalid(
                    "--model",
                    other,
                    "must be resonant or rigid",
                ))
            }
        });
    }
    if let Some(seed) = args.seed {
        cfg.ga.seed = Some(seed);
    }
    Ok((cfg, name, base))
}

/// Reads and checks the checkpoint in `dir` against the config of this invocation.
fn read_checkpoint(dir: &Path, config: &OptimizeConfig) -> Result<GaState, CliError> {
    let path = dir.join(CHECKPOINT_FILE);
    let text = fs::read_to_string(&path).map_err(|e| CliError::Read {
        path: path.clone(),
        source: e,
    })?;
    let corrupt = |message: String| CliError::Parse {
        source_name: path.display().to_string(),
        message: format!(
            "{message}; the checkpoint is corrupt: restore it or start a new run in another --out"
        ),
    };
    let cp: Checkpoint = serde_json::from_str(&text).map_err(|e| corrupt(e.to_string()))?;
    if cp.format != CHECKPOINT_FORMAT {
        return Err(corrupt(format!(
            "format `{}`, expected `{CHECKPOINT_FORMAT}`",
            cp.format
        )));
    }
    if cp.config != *config {
        let json = |v: &OptimizeConfig| serde_json::to_value(v).unwrap_or_default();
        let (a, b) = (json(&cp.config), json(config));
        let differing: Vec<String> = ["design", "excitation", "wall", "run", "ga", "description"]
            .iter()
            .filter(|k| a.get(**k) != b.get(**k))
            .map(|k| {
                format!(
                    "[{k}] saved {} vs now {}",
                    a.get(*k).cloned().unwrap_or_default(),
                    b.get(*k).cloned().unwrap_or_default()
                )
            })
            .collect();
        return Err(CliError::invalid(
            "--resume",
            path.display(),
            format!(
                "the checkpoint belongs to a different problem: {}; resume with the same config, --model and --seed",
                differing.join("; ")
            ),
        ));
    }
    Ok(cp.into_state())
}

/// Runs `woodpile optimize`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let (cfg, name, base_dir) = load_config(args)?;
    let problem = Problem::new(&cfg, &base_dir, args.threads)?;
    let out = &args.out;
    let initial = if args.resume {
        if !out.join(CHECKPOINT_FILE).is_file() {
            return Err(CliError::invalid(
                "--resume",
                out.display(),
                format!("holds no {CHECKPOINT_FILE}: nothing to resume; drop --resume to start a new run"),
            ));
        }
        Some(read_checkpoint(out, &problem.config)?)
    } else {
        match fs::read_dir(out) {
            Ok(mut entries) => {
                if entries.next().is_some() {
                    let what = if out.join(CHECKPOINT_FILE).is_file() {
                        "holds an earlier optimisation run: add --resume to continue it (same config and seed), or choose another --out"
                    } else {
                        "exists and is not empty: refusing to write into it; choose another --out"
                    };
                    return Err(CliError::invalid("--out", out.display(), what));
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(io_err(out)(e)),
        }
        None
    };
    let ga = BreederGa::new(
        problem.space.clone(),
        Box::new(problem.objective),
        problem.settings,
    )
    .map_err(optimize_error)?;
    if let Some(state) = &initial {
        ga.check_state(state).map_err(optimize_error)?;
    }
    fs::create_dir_all(out).map_err(io_err(out))?;

    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = Arc::clone(&stop);
        // Fails only if a handler is already set (e.g. a second call in one process): the
        // earlier handler stays in charge.
        let _ = ctrlc::set_handler(move || stop.store(true, Ordering::SeqCst));
    }
    let bar = progress_bar(ctx.quiet, problem.settings.generations);
    let unit = problem.objective.unit().to_string();
    let mut write_error: Option<CliError> = None;
    let mut last_elapsed = initial.as_ref().map_or(0.0, |s| s.elapsed_s);
    let mut last_evals = initial.as_ref().map_or(0, |s| s.evaluations);
    let mut observer = |s: &GaState| {
        let cp = Checkpoint::new(&problem.config, s);
        let written = serde_json::to_vec(&cp)
            .map_err(|e| io_err(&out.join(CHECKPOINT_FILE))(std::io::Error::other(e)))
            .and_then(|json| write_atomic(out, CHECKPOINT_FILE, &json))
            .and_then(|_| write_atomic(out, "history.csv", history_csv(&s.history).as_bytes()));
        if let Err(e) = written {
            write_error = Some(e);
            return ControlFlow::Break(());
        }
        let dt = s.elapsed_s - last_elapsed;
        let rate = if dt > 0.0 {
            (s.evaluations - last_evals) as f64 / dt
        } else {
            0.0
        };
        (last_elapsed, last_evals) = (s.elapsed_s, s.evaluations);
        bar.set_position(s.generation as u64);
        bar.set_message(format!(
            "best {:.6} {unit} | {rate:.0} eval/s | {} evaluations, {} cache hits",
            s.best().objective,
            s.evaluations,
            s.cache_hits
        ));
        ControlFlow::Continue(())
    };
    let outcome = ga.run(initial, &stop, &mut observer);
    bar.finish_and_clear();
    if let Some(e) = write_error {
        return Err(e);
    }
    let outcome = outcome.map_err(optimize_error)?;
    let state = &outcome.state;
    let best = state.best();

    // Final outputs: the population, the best design as a scenario, the summary.
    write_atomic(
        out,
        "population.csv",
        population_csv(&problem.space, &state.population).as_bytes(),
    )?;
    let labels = problem.space.labels(&best.genome);
    let description = format!(
        "best design of `woodpile optimize` ({name}, seed {}, {} generations): {} = {} {unit}",
        problem.settings.seed,
        state.generation,
        problem.objective.as_str(),
        best.objective
    );
    let scenario = problem.scenario(&best.genome, Some(description));
    write_atomic(out, "best.toml", scenario.to_toml().as_bytes())?;
    let resolved = resolve(&scenario, &problem.base_dir)?;
    let figures = simulate(
        &resolved.chain,
        &resolved.excitation,
        &resolved.settings,
        &mut (),
    )?;
    let interrupted = outcome.reason == StopReason::Interrupted;
    let summary = SummaryJson {
        tool: "woodpile optimize",
        version: env!("CARGO_PKG_VERSION"),
        problem: &name,
        status: if interrupted {
            "interrupted"
        } else {
            "finished"
        },
        stop_reason: stop_text(outcome.reason),
        objective: problem.objective.as_str(),
        objective_unit: &unit,
        best_objective: best.objective,
        best_chain_labels: labels.clone(),
        best_rods_mm: scenario.chain.rods_mm.clone(),
        best_genome: &best.genome,
        best_total_mass_g: problem.space.mass_kg(&best.genome) * 1e3,
        incident_peak_force_n: figures.incident_peak_force_n,
        transmitted_peak_force_n: figures.transmitted_peak_force_n,
        transmission_ratio: figures.transmission_ratio,
        restitution_coefficient: figures.restitution.map(|r| r.coefficient),
        seed: problem.settings.seed,
        generations_completed: state.generation,
        evaluations: state.evaluations,
        cache_hits: state.cache_hits,
        elapsed_s: state.elapsed_s,
        evaluations_per_s: if state.elapsed_s > 0.0 {
            state.evaluations as f64 / state.elapsed_s
        } else {
            0.0
        },
        config: &problem.config,
    };
    let json = serde_json::to_vec_pretty(&summary)
        .map_err(|e| io_err(&out.join("summary.json"))(std::io::Error::other(e)))?;
    write_atomic(out, "summary.json", &json)?;

    if !ctx.quiet {
        println!(
            "problem      {name} ({} positions, {} catalogue entries, seed {})",
            problem.space.positions,
            problem.space.catalogue.len(),
            problem.settings.seed
        );
        println!(
            "stopped      {} after generation {}: {} evaluations, {} cache hits, {:.1} s",
            stop_text(outcome.reason),
            state.generation,
            state.evaluations,
            state.cache_hits,
            state.elapsed_s
        );
        println!("best         {}", labels.join(" "));
        println!(
            "objective    {} = {} {unit}",
            problem.objective.as_str(),
            best.objective
        );
        println!(
            "forces       incident {:.4} N, transmitted {:.4} N, ratio {:.4}",
            figures.incident_peak_force_n,
            figures.transmitted_peak_force_n,
            figures.transmission_ratio
        );
        println!("output       {}", out.display());
    }
    if interrupted {
        eprintln!(
            "interrupted: generation {} is saved in {}; continue with the same command and --resume",
            state.generation,
            out.join(CHECKPOINT_FILE).display()
        );
    }
    Ok(())
}

fn progress_bar(quiet: bool, generations: usize) -> indicatif::ProgressBar {
    if quiet {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(generations as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "generation {pos}/{len} [{bar:25}] {msg} | ETA {eta}",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}
