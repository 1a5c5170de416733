//! `woodpile optimize`: the breeder genetic algorithm of docs/physics.md §11 over a design space read
//! from a config file (or a built-in problem), with a progress bar, a checkpoint after every
//! generation, exact resume and a clean stop on Ctrl-C.
//!
//! The config file is a scenario's `[excitation]`, `[wall]` and `[run]` tables plus:
//!
//! ```toml
//! [design]
//! positions = 20                 # N elements (default 20), or a range: { min = 8, max = 24 }
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
//! Outputs in the output directory: `checkpoint.json` and `history.csv` (rewritten atomically after every
//! generation), then `population.csv`, `best.toml` (a scenario `woodpile simulate` re-runs to
//! the same figures) and `summary.json`. A directory that holds anything is never written
//! into unless resuming continues the run it holds, with the same config.

use crate::atomic::{io_err, read_error, write_atomic};
use crate::error::Error;
use crate::scenario::{resolve, resolve_with_keys, ChainKeys, ChainSpec, Scenario};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};
use woodpile::optimize::{
    Constraints, DesignSpace, GaSettings, GaState, GenerationStats, Individual, Ledger,
    OptimizeError, StandardObjective, StopReason,
};
use woodpile::optimize::{DesignFigure, Nsga2Settings, Objective, Outcome};
use woodpile::simulate;

pub use crate::optimize_config::{
    scenario_of, ConstraintsSpec, CountSpec, DesignSpec, FixedSpec, GaSpec, OptimizeConfig,
    PositionsRange, PositionsSpec, RodRangeSpec, BUILTIN_PROBLEMS,
};

/// The checkpoint's format tag.
pub const CHECKPOINT_FORMAT: &str = "woodpile-optimize-checkpoint/1";

/// The file that marks a directory as an optimisation run.
pub const CHECKPOINT_FILE: &str = "checkpoint.json";

/// Which search a config asks for (`ga.algorithm`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Algorithm {
    /// The breeder GA: one objective of a run.
    Breeder,
    /// NSGA-II: a Pareto front of one or more objectives.
    Nsga2,
}

/// A config turned into what the library runs.
pub struct Problem {
    /// The completed config.
    pub config: OptimizeConfig,
    /// The design space.
    pub space: DesignSpace,
    /// The GA's settings.
    pub settings: GaSettings,
    /// The objective (the breeder GA's; for NSGA-II, the first objective of a run, else the
    /// default).
    pub objective: StandardObjective,
    /// The search.
    pub algorithm: Algorithm,
    /// The objectives, in order (one for the breeder GA).
    pub objectives: Vec<DesignFigure>,
    /// NSGA-II's settings (meaningful for [`Algorithm::Nsga2`]).
    pub nsga2: Nsga2Settings,
    /// Directory relative to which the config's files are found.
    pub base_dir: PathBuf,
    /// `ga.robust` and the checked `[uncertainty]`, when robust.
    pub robust: Option<(crate::robust::Robust, crate::uncertainty::Uncertainty)>,
}

fn catalogue_index(
    field: &str,
    rod_mm: Option<u32>,
    element: Option<usize>,
    cfg: &OptimizeConfig,
) -> Result<usize, Error> {
    let d = &cfg.design;
    let n = d
        .elements
        .as_ref()
        .map(Vec::len)
        .or(d.catalogue_mm.as_ref().map(Vec::len))
        .unwrap_or(0);
    match (rod_mm, element) {
        (Some(_), Some(_)) => Err(Error::invalid(
            field,
            "both rod_mm and element",
            "give one of them",
        )),
        (None, None) => Err(Error::invalid(
            field,
            "(no element)",
            "give rod_mm = <length in the catalogue> or element = <catalogue index>",
        )),
        (None, Some(e)) if e < n => Ok(e),
        (None, Some(e)) => Err(Error::invalid(
            format!("{field}.element"),
            e,
            format!("catalogue indices are 0..={}", n.saturating_sub(1)),
        )),
        (Some(l), None) => match &d.catalogue_mm {
            Some(rods) => rods.iter().position(|&r| r == l).ok_or_else(|| {
                Error::invalid(
                    format!("{field}.rod_mm"),
                    l,
                    format!(
                        "not in design.catalogue_mm = {:?}",
                        rods.iter().collect::<Vec<_>>()
                    ),
                )
            }),
            None => Err(Error::invalid(
                format!("{field}.rod_mm"),
                l,
                "rod_mm needs design.catalogue_mm; with design.elements use element = <index>",
            )),
        },
    }
}

/// Checks the catalogue of `design`: not empty, no entry twice, not too long.
fn check_catalogue(d: &DesignSpec) -> Result<(), Error> {
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
        let example = "e.g. catalogue_mm = [20, 30, 40, 50, 60, 70, 80]";
        return Err(Error::invalid(
            key,
            "[]",
            format!("the catalogue needs at least one element, {example}"),
        ));
    }
    if let Some((i, j)) = first_duplicate(d.catalogue_mm.as_deref().unwrap_or_default()) {
        return Err(Error::invalid(
            format!("design.catalogue_mm[{j}]"),
            d.catalogue_mm.as_ref().map_or(0, |c| c[j]),
            format!("repeats design.catalogue_mm[{i}]; list each rod once"),
        ));
    }
    if let Some((i, j)) = first_duplicate(d.elements.as_deref().unwrap_or_default()) {
        return Err(Error::invalid(
            format!("design.elements[{j}]"),
            "(the same element)",
            format!("repeats design.elements[{i}]; list each element once"),
        ));
    }
    if n_cat > woodpile::optimize::MAX_CATALOGUE_LEN {
        return Err(Error::invalid(
            "design.catalogue",
            n_cat,
            format!("at most {} entries", woodpile::optimize::MAX_CATALOGUE_LEN),
        ));
    }
    Ok(())
}

/// The constraints of the config, their layers and elements checked against the catalogue.
fn constraints(cfg: &OptimizeConfig, positions: PositionsSpec) -> Result<Constraints, Error> {
    let c = &cfg.design.constraints;
    let mut constraints = Constraints {
        max_total_mass_kg: c.max_total_mass_g.map(|g| g * 1e-3),
        max_stack_height_m: c.max_stack_height_mm.map(|mm| mm * 1e-3),
        max_contact_pressure_pa: c.max_contact_pressure_pa,
        ..Constraints::default()
    };
    for (key, value) in [
        ("max_total_mass_g", c.max_total_mass_g),
        ("max_stack_height_mm", c.max_stack_height_mm),
        ("max_contact_pressure_pa", c.max_contact_pressure_pa),
    ] {
        if let Some(v) = value.filter(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(Error::invalid(
                format!("design.constraints.{key}"),
                v,
                "must be a finite number > 0",
            ));
        }
    }
    for (k, f) in c.fixed.iter().enumerate() {
        let field = format!("design.constraints.fixed[{k}]");
        let n = positions.min();
        if f.layer == 0 || f.layer > n {
            let reason = match positions {
                PositionsSpec::Count(_) => format!("layers are 1..={n} (1 = top)"),
                PositionsSpec::Range(_) => format!(
                    "layers are 1..={n} (1 = top): with a variable number of layers a fixed \
                     layer must exist in every design, so at most design.positions.min = {n}"
                ),
            };
            return Err(Error::invalid(format!("{field}.layer"), f.layer, reason));
        }
        let e = catalogue_index(&field, f.rod_mm, f.element, cfg)?;
        constraints.fixed.push((f.layer - 1, e));
    }
    for (k, m) in c.max_count.iter().enumerate() {
        let field = format!("design.constraints.max_count[{k}]");
        let e = catalogue_index(&field, m.rod_mm, m.element, cfg)?;
        constraints.max_count.push((e, m.count));
    }
    Ok(constraints)
}

/// An infeasibility found at the fewest layers of a range says so: with a variable number of
/// layers, the lightest (lowest) design is one of `design.positions.min` layers.
fn fewest_layers(e: OptimizeError, positions: PositionsSpec) -> OptimizeError {
    let PositionsSpec::Range(r) = positions else {
        return e;
    };
    let note = |labels: String| {
        format!(
            "{labels}; {} layers, the fewest design.positions.min allows",
            r.min
        )
    };
    match e {
        OptimizeError::TooHeavy {
            max_total_mass_kg,
            lightest_kg,
            lightest,
        } => OptimizeError::TooHeavy {
            max_total_mass_kg,
            lightest_kg,
            lightest: note(lightest),
        },
        OptimizeError::TooTall {
            max_stack_height_m,
            lowest_m,
            lowest,
        } => OptimizeError::TooTall {
            max_stack_height_m,
            lowest_m,
            lowest: note(lowest),
        },
        other => other,
    }
}

/// `design.positions`: at least one layer; a range with min ≤ max.
fn check_positions(positions: PositionsSpec) -> Result<(), Error> {
    if positions.min() == 0 {
        return Err(Error::invalid(positions.min_key(), 0, "must be at least 1"));
    }
    if positions.max() < positions.min() {
        return Err(Error::invalid(
            "design.positions.max",
            positions.max(),
            format!(
                "must be at least design.positions.min = {}; did you mean {{ min = {}, max = {} }}?",
                positions.min(),
                positions.max(),
                positions.min()
            ),
        ));
    }
    Ok(())
}

/// The GA settings of `[ga]` with `threads` workers (checked by [`GaSettings::validate`]).
fn ga_settings(g: &GaSpec, threads: usize) -> GaSettings {
    GaSettings {
        population: g.population.unwrap_or(100),
        truncation: g.truncation.unwrap_or(0.3),
        elites: g.elites.unwrap_or(1),
        generations: g.generations.unwrap_or(100),
        stall_generations: g.stall_generations.filter(|&s| s > 0),
        seed: g.seed.unwrap_or(1),
        mutation_range: g.mutation_range,
        threads,
        cache: g.cache.unwrap_or(true),
        screen_peak_tolerance: g.screen_peak_tolerance,
        stop_early: g.stop_early.unwrap_or(false),
    }
}

impl Problem {
    /// Validates a config (after the command line's overrides) and builds the design space.
    pub fn new(config: &OptimizeConfig, base_dir: &Path, threads: usize) -> Result<Self, Error> {
        if config.design.rod_range.is_some()
            && (config.design.catalogue_mm.is_some() || config.design.elements.is_some())
        {
            return Err(Error::invalid(
                "design.rod_range",
                "with catalogue_mm or elements",
                "give one catalogue: rod_range, catalogue_mm or elements",
            ));
        }
        let cfg = config.complete_checked()?;
        let d = &cfg.design;
        let positions = d.positions.unwrap_or(PositionsSpec::Count(20));
        check_positions(positions)?;
        crate::limits::check_generation(
            cfg.ga
                .population
                .unwrap_or(GaSettings::default().population),
            positions.max(),
            positions.max_key(),
            cfg.ga.allow_large.unwrap_or(false),
        )?;
        if d.catalogue_mm.is_some() && d.elements.is_some() {
            return Err(Error::invalid(
                "design",
                "both catalogue_mm and elements",
                "give one catalogue: catalogue_mm (Table 1 rods) or elements (general form)",
            ));
        }
        check_catalogue(d)?;
        // The catalogue as a chain resolves every element, the wall, the load and the run;
        // the catalogue's errors name the design keys.
        let catalogue_chain = ChainSpec {
            rods_mm: d.catalogue_mm.clone(),
            elements: d.elements.clone(),
            model: d.model,
            crossing_angle_deg: d.crossing_angle_deg,
            ..ChainSpec::default()
        };
        let resolved =
            resolve_with_keys(&cfg.scenario(catalogue_chain, None), base_dir, &DESIGN_KEYS)?;
        let catalogue = resolved.chain.elements().to_vec();
        let constraints = constraints(&cfg, positions)?;
        let space = DesignSpace {
            positions: positions.min(),
            max_positions: matches!(positions, PositionsSpec::Range(_)).then(|| positions.max()),
            catalogue,
            wall: resolved.chain.wall().clone(),
            crossing_angle_rad: resolved.chain.crossing_angle_rad(),
            excitation: resolved.excitation,
            settings: resolved.settings,
            constraints,
        };
        let (algorithm, objectives, objective) = study(config, &cfg)?;
        let robust = robust_of(config, &cfg, algorithm, objective)?;
        let settings = ga_settings(&cfg.ga, threads);
        if algorithm == Algorithm::Breeder {
            settings.validate()?;
        }
        woodpile::optimize::FeasibleSet::new(&space)
            .map_err(|e| optimize_error(fewest_layers(e, positions)))?;
        let nsga2 = Nsga2Settings {
            population: settings.population,
            generations: settings.generations,
            stall_generations: settings.stall_generations,
            seed: settings.seed,
            mutation_range: settings.mutation_range,
            threads,
            cache: settings.cache,
            reference_point: cfg.ga.reference_point.clone(),
        };
        Ok(Problem {
            config: cfg,
            space,
            settings,
            objective,
            algorithm,
            objectives,
            nsga2,
            base_dir: base_dir.to_path_buf(),
            robust,
        })
    }

    /// The number of layers as the summary prints it: "20 positions", or with a range "8 to
    /// 24 positions", saying when the constraints leave fewer.
    pub fn positions_text(&self) -> String {
        let space = &self.space;
        if space.max_positions.is_none() {
            return format!("{} positions", space.positions);
        }
        let asked = space.lengths();
        let text = format!("{} to {} positions", asked.start(), asked.end());
        match woodpile::optimize::FeasibleSet::new(space).map(|s| s.lengths()) {
            Ok(feasible) if feasible.end() < asked.end() => {
                format!("{text}, at most {} meeting the constraints", feasible.end())
            }
            _ => text,
        }
    }

    /// The robust objective of a robust problem (`ga.robust`), else None.
    pub fn robust_objective(&self) -> Option<crate::robust::RobustObjective> {
        let (robust, u) = self.robust.clone()?;
        Some(crate::robust::RobustObjective {
            config: self.config.clone(),
            base_dir: self.base_dir.clone(),
            catalogue: self.space.catalogue.clone(),
            uncertainty: u,
            robust,
        })
    }

    /// The scenario of a genome: the problem's load, support and run with that chain. Files
    /// named in the config (a blast table) are made absolute so the scenario runs from anywhere.
    pub fn scenario(&self, genome: &[u8], description: Option<String>) -> Scenario {
        scenario_of(&self.config, &self.base_dir, genome, description)
    }
}

/// `ga.robust` checked against the rest of the config (`user`: as written, `cfg`: completed):
/// it needs `[uncertainty]`, the transmitted force for the breeder GA (NSGA-II takes the
/// statistic of every figure of a run), and no screening or early stopping; `[uncertainty]` needs `ga.robust`. The samples of the first catalogue entry in
/// every position are built and resolved, so a key that does not apply fails here.
fn robust_of(
    user: &OptimizeConfig,
    cfg: &OptimizeConfig,
    algorithm: Algorithm,
    objective: StandardObjective,
) -> Result<Option<(crate::robust::Robust, crate::uncertainty::Uncertainty)>, Error> {
    let (text, spec) = match (&user.ga.robust, &user.uncertainty) {
        (None, None) => return Ok(None),
        (None, Some(_)) => {
            return Err(Error::invalid(
                "uncertainty",
                "(given)",
                "is used by ga.robust: add ga.robust = \"mean\", \"quantile:0.95\" or \"cvar:0.95\"",
            ))
        }
        (Some(t), None) => {
            return Err(Error::invalid(
                "ga.robust",
                t,
                "needs an [uncertainty] table (the same as a scenario's, docs/optimization.md \"Scatter\")",
            ))
        }
        (Some(t), Some(s)) => (t, s),
    };
    let robust = crate::robust::Robust::parse(text)?;
    if algorithm == Algorithm::Breeder && objective != StandardObjective::TransmittedForce {
        return Err(Error::invalid(
            "ga.robust",
            text,
            format!(
                "is a statistic of the transmitted force; the objective is {}",
                objective.as_str()
            ),
        ));
    }
    if let Some(PositionsSpec::Range(r)) = cfg.design.positions {
        return Err(Error::invalid(
            "ga.robust",
            text,
            format!(
                "needs a fixed number of layers: with design.positions = {{ min = {}, max = {} }} \
                 the per-rod and per-contact draws of designs of different lengths would differ \
                 (common random numbers hold only among designs of one length)",
                r.min, r.max
            ),
        ));
    }
    for (k, given) in [
        (
            "screen_peak_tolerance",
            user.ga.screen_peak_tolerance.is_some(),
        ),
        ("stop_early", user.ga.stop_early == Some(true)),
    ] {
        if given {
            return Err(Error::invalid(
                format!("ga.{k}"),
                "(given)",
                "not with ga.robust: every sample is simulated whole",
            ));
        }
    }
    let u = spec.check()?;
    let positions = cfg.design.positions.map_or(20, PositionsSpec::max);
    let nominal = scenario_of(cfg, Path::new("."), &vec![0; positions], None);
    crate::uncertainty::samples(&nominal, &u)?;
    Ok(Some((robust, u)))
}

/// The algorithm, the objectives and the breeder's objective of a config (`user`: as written,
/// `cfg`: completed), every combination that cannot run refused with the key to change.
fn study(
    user: &OptimizeConfig,
    cfg: &OptimizeConfig,
) -> Result<(Algorithm, Vec<DesignFigure>, StandardObjective), Error> {
    let objectives = objectives_of(user, cfg)?;
    let algorithm = algorithm_of(cfg, objectives.len())?;
    if algorithm == Algorithm::Breeder {
        let Some(DesignFigure::Run(o)) = objectives.first().copied() else {
            return Err(Error::invalid(
                if cfg.ga.objectives.is_some() { "ga.objectives[0]" } else { "ga.objective" },
                objectives[0].as_str(),
                "the breeder GA minimises a figure of a run (transmitted-force, transmission-ratio, transmitted-energy, transmitted-impulse); use ga.algorithm = \"nsga2\" for the others",
            ));
        };
        if let Some(p) = cfg.design.constraints.max_contact_pressure_pa {
            return Err(Error::invalid(
                "design.constraints.max_contact_pressure_pa",
                p,
                "is known only after a run: set ga.algorithm = \"nsga2\", whose constraint domination handles it",
            ));
        }
        return Ok((algorithm, objectives, o));
    }
    check_nsga2_settings(user, cfg, objectives.len())?;
    let first_run = objectives.iter().find_map(|f| match f {
        DesignFigure::Run(o) => Some(*o),
        _ => None,
    });
    Ok((algorithm, objectives, first_run.unwrap_or_default()))
}

/// The objectives of `ga.objective` or `ga.objectives` (not both; none: the default), each
/// known and listed once.
fn objectives_of(user: &OptimizeConfig, cfg: &OptimizeConfig) -> Result<Vec<DesignFigure>, Error> {
    let g = &user.ga;
    if g.objective.is_some() && g.objectives.is_some() {
        return Err(Error::invalid(
            "ga.objectives",
            format!("{:?}", g.objectives.as_deref().unwrap_or_default()),
            "give ga.objective (one) or ga.objectives (a list), not both",
        ));
    }
    let names = match (&cfg.ga.objectives, &cfg.ga.objective) {
        (Some(list), _) => list.clone(),
        (None, Some(one)) => vec![one.clone()],
        (None, None) => vec![StandardObjective::default().as_str().to_string()],
    };
    let key = if cfg.ga.objectives.is_some() {
        "ga.objectives"
    } else {
        "ga.objective"
    };
    if names.is_empty() {
        return Err(Error::invalid(
            key,
            "[]",
            "give at least one objective, e.g. [\"transmitted-force\", \"total-mass\"]",
        ));
    }
    let mut objectives = Vec::with_capacity(names.len());
    for (k, name) in names.iter().enumerate() {
        let field = if cfg.ga.objectives.is_some() {
            format!("{key}[{k}]")
        } else {
            key.to_string()
        };
        let f = DesignFigure::from_name(name).map_err(Error::at(&field))?;
        if objectives.contains(&f) {
            return Err(Error::invalid(
                field,
                name,
                "is listed twice; list each objective once",
            ));
        }
        objectives.push(f);
    }
    Ok(objectives)
}

/// `ga.algorithm` (default: the breeder GA for one objective, NSGA-II for more).
fn algorithm_of(cfg: &OptimizeConfig, objectives: usize) -> Result<Algorithm, Error> {
    match cfg.ga.algorithm.as_deref() {
        None | Some("breeder") if objectives == 1 => Ok(Algorithm::Breeder),
        None | Some("nsga2") => Ok(Algorithm::Nsga2),
        Some("breeder") => Err(Error::invalid(
            "ga.algorithm",
            "breeder",
            format!(
                "the breeder GA minimises one objective, {objectives} are given: use \"nsga2\""
            ),
        )),
        Some(other) => Err(Error::invalid(
            "ga.algorithm",
            other,
            "must be \"breeder\" or \"nsga2\"",
        )),
    }
}

/// NSGA-II's settings: none of the breeder's, a population of at least 4, a reference point of
/// one finite number per objective.
fn check_nsga2_settings(
    user: &OptimizeConfig,
    cfg: &OptimizeConfig,
    objectives: usize,
) -> Result<(), Error> {
    let g = &user.ga;
    for (k, given) in [
        ("truncation", g.truncation.is_some()),
        ("elites", g.elites.is_some()),
        ("screen_peak_tolerance", g.screen_peak_tolerance.is_some()),
        ("stop_early", g.stop_early == Some(true)),
    ] {
        if given {
            return Err(Error::invalid(
                format!("ga.{k}"),
                "(given)",
                "is a setting of the breeder GA; NSGA-II has none (remove it, or set ga.algorithm = \"breeder\" with one objective)",
            ));
        }
    }
    if cfg.ga.population.is_some_and(|p| p < 4) {
        return Err(Error::invalid(
            "ga.population",
            cfg.ga.population.unwrap_or(0),
            "NSGA-II needs at least 4",
        ));
    }
    if let Some(r) = &cfg.ga.reference_point {
        if r.len() != objectives || r.iter().any(|x| !x.is_finite()) {
            return Err(Error::invalid(
                "ga.reference_point",
                format!("{r:?}"),
                format!("give {objectives} finite numbers, one per objective, in SI units"),
            ));
        }
    }
    Ok(())
}

/// Where the catalogue of an optimisation config lives: errors of its elements name these keys.
pub const DESIGN_KEYS: ChainKeys = ChainKeys {
    rods_mm: "design.catalogue_mm",
    elements: "design.elements",
    crossing_angle_deg: "design.crossing_angle_deg",
};

/// woodpile-io's error for a library optimisation error.
pub fn optimize_error(e: OptimizeError) -> Error {
    match e {
        OptimizeError::Model(m) => Error::Model(m),
        OptimizeError::Infeasible { reason } => Error::invalid(
            "design.constraints",
            "(as given)",
            format!("no design meets them: {reason}"),
        ),
        OptimizeError::TooHeavy {
            max_total_mass_kg,
            lightest_kg,
            lightest,
        } => Error::invalid(
            // The config states the limit in grams.
            "design.constraints.max_total_mass_g",
            grams(max_total_mass_kg),
            format!(
                "no design meets it: the lightest design meeting the other constraints weighs {} g ({lightest})",
                grams(lightest_kg)
            ),
        ),
        OptimizeError::TooTall {
            max_stack_height_m,
            lowest_m,
            lowest,
        } => Error::invalid(
            "design.constraints.max_stack_height_mm",
            millimetres(max_stack_height_m),
            format!(
                "no design meets it: the lowest design meeting the other constraints stands {} mm ({lowest})",
                millimetres(lowest_m)
            ),
        ),
        OptimizeError::Simulation { design, source } => Error::Evaluation { design, source },
        OptimizeError::NotANumber { objective, design } => Error::invalid(
            "ga.objective",
            objective,
            format!("returned NaN for design [{design}]"),
        ),
        OptimizeError::StateMismatch { reason } => Error::ResumeRefused {
            path: CHECKPOINT_FILE.into(),
            reason,
        },
        OptimizeError::ThreadPool { threads, reason } => Error::ThreadPool { threads, reason },
    }
}

/// A mass \[kg\] in grams, to nine significant decimals (no binary-conversion tail).
fn grams(kg: f64) -> String {
    let text = format!("{:.9}", kg * 1e3);
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A length \[m\] in millimetres, to nine significant decimals.
fn millimetres(m: f64) -> String {
    grams(m)
}

/// The first pair (i, j), i < j, of equal entries.
fn first_duplicate<T: PartialEq>(list: &[T]) -> Option<(usize, usize)> {
    (1..list.len()).find_map(|j| list[..j].iter().position(|x| *x == list[j]).map(|i| (i, j)))
}

/// The checksum of a value's JSON (FNV-1a 64, 16 hex digits): a checkpoint's `checksum`,
/// computed with that field empty.
pub(crate) fn json_checksum(value: &impl Serialize) -> String {
    let json = serde_json::to_vec(value).unwrap_or_default();
    format!("{:016x}", fnv1a64(&json))
}

/// FNV-1a, 64 bits, of `bytes`: a stable content hash (the same on every platform and version
/// of Rust), for checkpoint checksums and cache keys. Not a cryptographic hash: it detects edits
/// and corruption, not a determined forger.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// `checkpoint.json`: the complete config and the GA's whole state. Floats are written with
/// shortest round-trip digits and read back exactly, so a resumed run continues bit for bit.
///
/// It records the version of woodpile that wrote it and a checksum: the FNV-1a 64 hash
/// ([`fnv1a64`]) of its compact JSON serialisation with `checksum` set to the empty string. A
/// checkpoint that was edited, written by another version, or saved for a different problem is
/// refused on resume, with the reason.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checkpoint {
    /// [`CHECKPOINT_FORMAT`].
    pub format: String,
    /// Version of woodpile that wrote it.
    pub tool_version: String,
    /// FNV-1a 64 of the content, 16 hex digits (see the type's documentation).
    pub checksum: String,
    /// The completed config the run was started with (seed included).
    pub config: OptimizeConfig,
    /// Generations completed.
    pub generation: usize,
    /// Generations since the best improved.
    pub stalled: usize,
    /// Simulations at the run's settings so far.
    pub evaluations: u64,
    /// Screening simulations so far (absent when 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub screenings: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
    /// Wall-clock seconds so far.
    pub elapsed_s: f64,
    /// Population, best first.
    pub population: Vec<Individual>,
    /// History, one line per generation.
    pub history: Vec<GenerationStats>,
    /// Fitness cache, sorted by genome.
    pub cache: Vec<Individual>,
    /// Screened values, sorted by genome (absent when empty).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub screened: Vec<Individual>,
    /// Lower bounds of the designs whose run stopped early, sorted by genome (absent when
    /// empty).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stopped: Vec<Individual>,
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}

/// A value map as a list sorted by genome (the checkpoint's form).
fn sorted_values(map: &HashMap<Vec<u8>, f64>) -> Vec<Individual> {
    let mut list: Vec<Individual> = map
        .iter()
        .map(|(g, &objective)| Individual {
            genome: g.clone(),
            objective,
            bound: 0.0,
            stopped: false,
        })
        .collect();
    list.sort_by(|a, b| a.genome.cmp(&b.genome));
    list
}

impl Checkpoint {
    /// The checkpoint of a GA state for `config`, its checksum computed.
    pub fn new(config: &OptimizeConfig, s: &GaState) -> Self {
        let mut cp = Checkpoint {
            format: CHECKPOINT_FORMAT.to_string(),
            tool_version: crate::VERSION.to_string(),
            checksum: String::new(),
            config: config.clone(),
            generation: s.generation,
            stalled: s.stalled,
            evaluations: s.ledger.evaluations,
            screenings: s.ledger.screenings,
            cache_hits: s.ledger.cache_hits,
            elapsed_s: s.elapsed_s,
            population: s.population.clone(),
            history: s.history.clone(),
            cache: sorted_values(&s.ledger.cache),
            screened: sorted_values(&s.ledger.screened),
            stopped: sorted_values(&s.ledger.stopped),
        };
        cp.checksum = cp.content_checksum();
        cp
    }

    /// The checksum of the content as it is now (with `checksum` itself left out).
    pub fn content_checksum(&self) -> String {
        let unsigned = Checkpoint {
            checksum: String::new(),
            ..self.clone()
        };
        json_checksum(&unsigned)
    }

    /// The GA state it holds.
    pub fn into_state(self) -> GaState {
        GaState {
            generation: self.generation,
            population: self.population,
            history: self.history,
            ledger: Ledger {
                cache: values_map(self.cache),
                screened: values_map(self.screened),
                stopped: values_map(self.stopped),
                evaluations: self.evaluations,
                screenings: self.screenings,
                cache_hits: self.cache_hits,
            },
            stalled: self.stalled,
            elapsed_s: self.elapsed_s,
        }
    }
}

fn values_map(list: Vec<Individual>) -> HashMap<Vec<u8>, f64> {
    list.into_iter().map(|i| (i.genome, i.objective)).collect()
}

/// Writes `history.csv`: one line per generation.
pub fn history_csv(history: &[GenerationStats]) -> String {
    let mut s =
        String::from("generation,best,mean,worst,evaluations,screenings,cache_hits,elapsed_s\n");
    for h in history {
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{:.3}\n",
            h.generation,
            h.best,
            h.mean,
            h.worst,
            h.evaluations,
            h.screenings,
            h.cache_hits,
            h.elapsed_s
        ));
    }
    s
}

/// Writes `population.csv`: the final population, best first, one column per layer (empty
/// beyond a shorter design's last layer);
/// `objective_bound` is 0 where the objective was simulated at the run's settings, and the
/// half-width of the interval that holds it where it is a screened value; `stopped` is 1 where
/// the design's run stopped early and the objective is a lower bound of its value (0 otherwise).
pub fn population_csv(space: &DesignSpace, population: &[Individual]) -> String {
    let mut s = String::from("rank,objective,objective_bound,stopped");
    // One column per layer of the longest design; a shorter design's cells beyond its last
    // layer are empty.
    let layers = population.iter().map(|i| i.genome.len()).max().unwrap_or(0);
    for l in 1..=layers {
        s.push_str(&format!(",layer_{l}"));
    }
    s.push('\n');
    for (r, i) in population.iter().enumerate() {
        s.push_str(&format!(
            "{},{},{},{}",
            r + 1,
            i.objective,
            i.bound,
            u8::from(i.stopped)
        ));
        for l in space.labels(&i.genome) {
            s.push(',');
            s.push_str(&l);
        }
        s.push_str(&",".repeat(layers - i.genome.len()));
        s.push('\n');
    }
    s
}

/// `summary.json` of an optimisation: written by [`write_final_outputs`], read back by
/// [`read_output`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OptimizeSummary {
    /// `woodpile optimize`.
    pub tool: String,
    /// Version of woodpile.
    pub version: String,
    /// Problem name (config file stem or built-in name).
    pub problem: String,
    /// `finished` or `interrupted`.
    pub status: String,
    /// Why the GA stopped ([`stop_text`]).
    pub stop_reason: String,
    /// Objective name.
    pub objective: String,
    /// Unit of the objective.
    pub objective_unit: String,
    /// Objective of the best design.
    pub best_objective: f64,
    /// Element labels of the best design, top to bottom.
    pub best_chain_labels: Vec<String>,
    /// Rod lengths of the best design \[mm\] (catalogue rods only).
    pub best_rods_mm: Option<Vec<u32>>,
    /// Catalogue indices of the best design.
    pub best_genome: Vec<u8>,
    /// Total mass of the best design \[g\].
    pub best_total_mass_g: f64,
    /// Incident peak force of the best design \[N\].
    pub incident_peak_force_n: f64,
    /// Transmitted peak force of the best design \[N\].
    pub transmitted_peak_force_n: f64,
    /// Transmitted / incident (null when it means nothing).
    pub transmission_ratio: Option<f64>,
    /// Striker restitution (null unless the striker had left).
    pub restitution_coefficient: Option<f64>,
    /// Seed of the GA.
    pub seed: u64,
    /// Generations completed.
    pub generations_completed: usize,
    /// Simulations run at the run's settings.
    pub evaluations: u64,
    /// Screening simulations run (0 without screening).
    #[serde(default)]
    pub screenings: u64,
    /// Designs found in the cache.
    pub cache_hits: u64,
    /// Wall-clock time \[s\].
    pub elapsed_s: f64,
    /// Simulations (screening ones included) per second.
    pub evaluations_per_s: f64,
    /// The completed config.
    pub config: OptimizeConfig,
}

/// Why a GA stopped, in words.
pub fn stop_text(reason: StopReason) -> &'static str {
    match reason {
        StopReason::GenerationLimit => "generation limit",
        StopReason::Stalled => "stall limit",
        StopReason::Interrupted => "interrupted",
        StopReason::Observer => "output error",
    }
}

/// The output directory policy of `woodpile optimize`: with `resume`, the checkpoint in `out`
/// (checked against `config`); without, `out` must be absent or empty (an earlier run there is
/// [`Error::CheckpointExists`]: resuming continues it). Nothing is written.
pub fn prepare_output(
    out: &Path,
    resume: bool,
    config: &OptimizeConfig,
) -> Result<Option<GaState>, Error> {
    if resume {
        if !out.join(CHECKPOINT_FILE).is_file() {
            return Err(Error::NothingToResume {
                path: out.to_path_buf(),
                file: CHECKPOINT_FILE,
            });
        }
        return read_checkpoint(out, config).map(Some);
    }
    require_empty(out).map(|()| None)
}

/// A new run's output directory must be absent or empty (an earlier run there is
/// [`Error::CheckpointExists`]: resuming continues it).
pub(crate) fn require_empty(out: &Path) -> Result<(), Error> {
    match fs::read_dir(out) {
        Ok(mut entries) => {
            if entries.next().is_some() {
                let path = out.to_path_buf();
                return Err(if out.join(CHECKPOINT_FILE).is_file() {
                    Error::CheckpointExists { path }
                } else {
                    Error::OutputNotEmpty {
                        path,
                        marker: CHECKPOINT_FILE,
                    }
                });
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(io_err(out)(e)),
    }
}

/// Writes what changes after every generation, each file replaced atomically: the checkpoint
/// and `history.csv`.
pub fn write_generation(out: &Path, config: &OptimizeConfig, state: &GaState) -> Result<(), Error> {
    let checkpoint = Checkpoint::new(config, state);
    let json = serde_json::to_vec(&checkpoint)
        .map_err(|e| io_err(&out.join(CHECKPOINT_FILE))(std::io::Error::other(e)))?;
    write_atomic(out, CHECKPOINT_FILE, &json)?;
    write_atomic(out, "history.csv", history_csv(&state.history).as_bytes())
}

/// Reads and checks the checkpoint in `dir` against the config of this invocation.
pub fn read_checkpoint(dir: &Path, config: &OptimizeConfig) -> Result<GaState, Error> {
    let path = dir.join(CHECKPOINT_FILE);
    let text = fs::read_to_string(&path).map_err(|e| Error::Read {
        path: path.clone(),
        source: e,
    })?;
    let corrupt = |message: String| {
        Error::Parse {
        source_name: path.display().to_string(),
        message: format!(
            "{message}; the checkpoint is corrupt: restore it or start a new run in another output directory"
        ),
    }
    };
    let cp: Checkpoint = serde_json::from_str(&text).map_err(|e| corrupt(e.to_string()))?;
    if cp.format != CHECKPOINT_FORMAT {
        return Err(corrupt(format!(
            "format `{}`, expected `{CHECKPOINT_FORMAT}`",
            cp.format
        )));
    }
    let refuse = |reason: String| Error::ResumeRefused {
        path: path.clone(),
        reason,
    };
    let ours = crate::VERSION;
    if cp.tool_version != ours {
        return Err(refuse(format!(
            "the checkpoint was written by woodpile {}, this is woodpile {ours}: a run resumes exactly only with the version that started it; finish it with woodpile {}, or start a new run in another output directory",
            cp.tool_version, cp.tool_version
        )));
    }
    let actual = cp.content_checksum();
    if cp.checksum != actual {
        return Err(refuse(format!(
            "the checkpoint's checksum is {} but its content hashes to {actual}: it was modified after woodpile wrote it, so its objectives cannot be trusted; restore it or start a new run in another output directory",
            cp.checksum
        )));
    }
    if !cp.config.same_problem(config) {
        let json = |v: &OptimizeConfig| serde_json::to_value(v).unwrap_or_default();
        let (a, b) = (json(&cp.config), json(config));
        let differing: Vec<String> = ["design", "excitation", "wall", "run", "ga"]
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
        return Err(refuse(format!(
            "the checkpoint belongs to a different problem: {}; resume with the same config, model and seed",
            differing.join("; ")
        )));
    }
    Ok(cp.into_state())
}

/// One line of `history.csv` as `woodpile plot` needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryPoint {
    /// Generation (0 = the initial population).
    pub generation: usize,
    /// Best objective.
    pub best: f64,
    /// Mean objective.
    pub mean: f64,
}

/// Reads `history.csv` of `woodpile optimize`: one point per generation.
pub fn read_history(path: &Path) -> Result<Vec<HistoryPoint>, Error> {
    let cols = ["best".to_string(), "mean".to_string()];
    let csv_err = |e: csv::Error| read_error(path, e.to_string());
    let mut r = csv::Reader::from_path(path).map_err(csv_err)?;
    let header = r.headers().map_err(csv_err)?.clone();
    if header.iter().any(|h| h == "hypervolume") {
        return Err(read_error(
            path,
            "the history of an NSGA-II run (a hypervolume per generation): its figures are not \
             drawn yet; the front is in pareto.csv and pareto/NNN.toml",
        ));
    }
    let index = |name: &str| {
        header.iter().position(|h| h == name).ok_or_else(|| {
            read_error(
                path,
                format!("no column `{name}`: not a history.csv of `woodpile optimize`"),
            )
        })
    };
    let g_col = index("generation")?;
    let (b_col, m_col) = (index(&cols[0])?, index(&cols[1])?);
    let mut points = Vec::new();
    for (line, rec) in r.records().enumerate() {
        let rec = rec.map_err(csv_err)?;
        let field = |i: usize| {
            rec.get(i).map(str::trim).ok_or_else(|| {
                read_error(path, format!("line {}: missing column {}", line + 2, i + 1))
            })
        };
        let not_number = |i: usize| {
            read_error(
                path,
                format!("line {}: not a number in column {}", line + 2, i + 1),
            )
        };
        let generation = field(g_col)?
            .parse::<usize>()
            .map_err(|_| not_number(g_col))?;
        let best = field(b_col)?
            .parse::<f64>()
            .map_err(|_| not_number(b_col))?;
        let mean = field(m_col)?
            .parse::<f64>()
            .map_err(|_| not_number(m_col))?;
        points.push(HistoryPoint {
            generation,
            best,
            mean,
        });
    }
    if points.is_empty() {
        return Err(read_error(
            path,
            "no generation recorded yet: nothing to plot",
        ));
    }
    Ok(points)
}

/// Writes the final outputs of an optimisation into `out`: `population.csv`, `best.toml` (the
/// best design as a scenario that `woodpile simulate` re-runs to the same figures) and
/// `summary.json`; returns the best design's figures of merit (re-simulated).
pub fn write_final_outputs(
    problem: &Problem,
    name: &str,
    outcome: &Outcome,
    out: &Path,
) -> Result<woodpile::RunSummary, Error> {
    let state = &outcome.state;
    let best = state.best();
    let unit = problem.objective.unit().to_string();
    let interrupted = outcome.reason == StopReason::Interrupted;
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
    if let Some(robust) = problem.robust_objective() {
        crate::robust::write_robust_csv(out, &robust, &best.genome)?;
    }
    let resolved = resolve(&scenario, &problem.base_dir)?;
    let figures = simulate(
        &resolved.chain,
        &resolved.excitation,
        &resolved.settings,
        &mut (),
    )?;
    let summary = OptimizeSummary {
        tool: "woodpile optimize".into(),
        version: crate::VERSION.into(),
        problem: name.into(),
        status: if interrupted {
            "interrupted"
        } else {
            "finished"
        }
        .into(),
        stop_reason: stop_text(outcome.reason).into(),
        objective: problem.objective.as_str().into(),
        objective_unit: unit,
        best_objective: best.objective,
        best_chain_labels: labels.clone(),
        best_rods_mm: scenario.chain.rods_mm.clone(),
        best_genome: best.genome.clone(),
        best_total_mass_g: problem.space.mass_kg(&best.genome) * 1e3,
        incident_peak_force_n: figures.incident_peak_force_n,
        transmitted_peak_force_n: figures.transmitted_peak_force_n,
        transmission_ratio: figures.transmission_ratio,
        restitution_coefficient: figures.restitution_coefficient(),
        seed: problem.settings.seed,
        generations_completed: state.generation,
        evaluations: state.ledger.evaluations,
        screenings: state.ledger.screenings,
        cache_hits: state.ledger.cache_hits,
        elapsed_s: state.elapsed_s,
        evaluations_per_s: if state.elapsed_s > 0.0 {
            (state.ledger.evaluations + state.ledger.screenings) as f64 / state.elapsed_s
        } else {
            0.0
        },
        config: problem.config.clone(),
    };
    let json = serde_json::to_vec_pretty(&summary)
        .map_err(|e| io_err(&out.join("summary.json"))(std::io::Error::other(e)))?;
    write_atomic(out, "summary.json", &json)?;

    Ok(figures)
}

/// What an optimisation output directory holds, read back (for `woodpile plot` and notebooks).
#[derive(Debug, Clone, PartialEq)]
pub struct OptimizeOutput {
    /// `history.csv`: one point per generation.
    pub history: Vec<HistoryPoint>,
    /// `summary.json`, once the run has finished or stopped.
    pub summary: Option<OptimizeSummary>,
    /// The completed config: the summary's, else the checkpoint's.
    pub config: Option<OptimizeConfig>,
    /// `best.toml` and its path, once the run has finished or stopped.
    pub best: Option<(PathBuf, Scenario)>,
}

/// Reads `path` as JSON of type `T`; `None` when there is no such file.
fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<Option<T>, Error> {
    if !path.is_file() {
        return Ok(None);
    }
    let text = fs::read_to_string(path).map_err(|e| Error::Read {
        path: path.to_path_buf(),
        source: e,
    })?;
    serde_json::from_str(&text)
        .map(Some)
        .map_err(|e| Error::Parse {
            source_name: path.display().to_string(),
            message: e.to_string(),
        })
}

/// Reads an optimisation output directory: `history.csv` (required), and `summary.json`,
/// `best.toml` and the config (the summary's, else the checkpoint's) where present.
pub fn read_output(dir: &Path) -> Result<OptimizeOutput, Error> {
    let history = read_history(&dir.join("history.csv"))?;
    let summary: Option<OptimizeSummary> = read_json(&dir.join("summary.json"))?;
    let config = match &summary {
        Some(s) => Some(s.config.clone()),
        None => {
            // Only the config is needed: a checkpoint of any version that has one will do.
            #[derive(Deserialize)]
            struct ConfigOnly {
                config: OptimizeConfig,
            }
            read_json::<ConfigOnly>(&dir.join(CHECKPOINT_FILE))?.map(|c| c.config)
        }
    };
    let best_path = dir.join("best.toml");
    let best = if best_path.is_file() {
        Some((best_path.clone(), Scenario::load(&best_path)?))
    } else {
        None
    };
    Ok(OptimizeOutput {
        history,
        summary,
        config,
        best,
    })
}
