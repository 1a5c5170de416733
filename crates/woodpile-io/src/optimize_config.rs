//! The optimisation config file as written and completed ([`OptimizeConfig`]: `[design]`,
//! `[ga]` and a scenario's `[excitation]`, `[wall]`, `[run]`; its format in `crate::optimize`),
//! and the scenario it gives a genome.

use crate::error::Error;
use crate::scenario::{
    ChainSpec, ElementKind, ElementSpec, ExcitationKind, ExcitationSpec, ModelSpec, RunSpec,
    Scenario, WallSpec,
};
use serde::{Deserialize, Serialize};
use std::path::Path;
use woodpile::optimize::{GaSettings, StandardObjective};
use woodpile::TABLE1_LENGTHS_MM;

/// Names of the built-in problems.
pub const BUILTIN_PROBLEMS: [&str; 2] = ["paper-impact", "paper-blast"];

/// An optimisation config file: what to search (`[design]`), under which load, support and run
/// (the scenario's `[excitation]`, `[wall]`, `[run]`) and how (`[ga]`).
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
    /// `[uncertainty]` as in a scenario file: the scatter `ga.robust` is taken over.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uncertainty: Option<crate::uncertainty::UncertaintySpec>,
}

/// `[design]`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignSpec {
    /// Number of positions N (default 20), or the range a design's number of layers is chosen
    /// from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub positions: Option<PositionsSpec>,
    /// Table 1 rods \[mm\] a position can hold (default: all of 20, 30, …, 80).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub catalogue_mm: Option<Vec<u32>>,
    /// General catalogue, as a scenario's `chain.elements` entries (instead of catalogue_mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<Vec<ElementSpec>>,
    /// A fine design space: rods of every length in a range (and the listed diameters and
    /// materials), each with its cell derived by beam theory (docs/physics.md §13). Expanded into
    /// `elements` when the config is completed; instead of catalogue_mm and elements.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod_range: Option<RodRangeSpec>,
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

/// `design.positions`: a fixed number of layers, or `{ min, max }` when the number of layers is
/// part of the design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(untagged)]
pub enum PositionsSpec {
    /// Exactly this many layers.
    Count(usize),
    /// Any number of layers from `min` to `max`.
    Range(PositionsRange),
}

/// `design.positions = { min, max }`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PositionsRange {
    /// The fewest layers.
    pub min: usize,
    /// The most layers.
    pub max: usize,
}

/// What `design.positions` may be, as a parse error says it.
const POSITIONS_EXPECTED: &str =
    "a number of layers (e.g. 20) or a range of them, { min = 8, max = 24 }";

impl<'de> Deserialize<'de> for PositionsSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::{self, MapAccess, Unexpected, Visitor};
        struct Positions;
        impl<'de> Visitor<'de> for Positions {
            type Value = PositionsSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(POSITIONS_EXPECTED)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<PositionsSpec, E> {
                usize::try_from(v)
                    .map(PositionsSpec::Count)
                    .map_err(|_| E::invalid_value(Unexpected::Unsigned(v), &self))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<PositionsSpec, E> {
                usize::try_from(v)
                    .map(PositionsSpec::Count)
                    .map_err(|_| E::invalid_value(Unexpected::Signed(v), &self))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<PositionsSpec, A::Error> {
                let (mut min, mut max) = (None, None);
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        "min" => min = Some(map.next_value::<usize>()?),
                        "max" => max = Some(map.next_value::<usize>()?),
                        other => return Err(de::Error::unknown_field(other, &["min", "max"])),
                    }
                }
                match (min, max) {
                    (Some(min), Some(max)) => Ok(PositionsSpec::Range(PositionsRange { min, max })),
                    (None, _) => Err(de::Error::missing_field("min")),
                    (_, None) => Err(de::Error::missing_field("max")),
                }
            }
        }
        d.deserialize_any(Positions)
    }
}

impl PositionsSpec {
    /// The fewest layers.
    pub fn min(self) -> usize {
        match self {
            PositionsSpec::Count(n) => n,
            PositionsSpec::Range(r) => r.min,
        }
    }

    /// The most layers.
    pub fn max(self) -> usize {
        match self {
            PositionsSpec::Count(n) => n,
            PositionsSpec::Range(r) => r.max,
        }
    }

    /// The key of the fewest layers as the config writes it.
    pub(crate) fn min_key(self) -> &'static str {
        match self {
            PositionsSpec::Count(_) => "design.positions",
            PositionsSpec::Range(_) => "design.positions.min",
        }
    }

    /// The key of the most layers as the config writes it.
    pub(crate) fn max_key(self) -> &'static str {
        match self {
            PositionsSpec::Count(_) => "design.positions",
            PositionsSpec::Range(_) => "design.positions.max",
        }
    }
}

/// `[design.rod_range]`: lengths `from_mm`, `from_mm + step_mm`, … up to `to_mm`, for every
/// listed diameter and material; cells derived from the rods (`cell = { modes }` when given).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodRangeSpec {
    /// Shortest rod \[mm\].
    pub from_mm: f64,
    /// Longest rod \[mm\] (included when the steps reach it).
    pub to_mm: f64,
    /// Step in length \[mm\].
    pub step_mm: f64,
    /// Diameters \[mm\] (default: the paper's 5 mm).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub diameters_mm: Vec<f64>,
    /// Material presets (default: fused quartz).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<String>,
    /// Resonators per derived cell (default: the rule of docs/physics.md §13).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
}

impl RodRangeSpec {
    /// The catalogue: every length for every diameter and material, lengths ascending within
    /// each (so that the GA's mutation, which moves by catalogue index, changes length by steps).
    pub fn elements(&self) -> Result<Vec<ElementSpec>, Error> {
        let key = |k: &str| format!("design.rod_range.{k}");
        for (k, v) in [
            ("from_mm", self.from_mm),
            ("to_mm", self.to_mm),
            ("step_mm", self.step_mm),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(key(k), v, "must be a finite number > 0"));
            }
        }
        if self.to_mm < self.from_mm {
            return Err(Error::invalid(
                key("to_mm"),
                self.to_mm,
                format!("must not be below from_mm ({})", self.from_mm),
            ));
        }
        // Tolerate rounding in (to − from)/step: 20..80 by 0.1 has 601 lengths, not 600.
        let steps = ((self.to_mm - self.from_mm) / self.step_mm + 1e-9).floor() as usize;
        let diameters = if self.diameters_mm.is_empty() {
            vec![woodpile::defaults::ROD_DIAMETER_MM]
        } else {
            self.diameters_mm.clone()
        };
        let materials = if self.materials.is_empty() {
            vec![woodpile::defaults::ELEMENT_MATERIAL.to_string()]
        } else {
            self.materials.clone()
        };
        let count = (steps + 1) * diameters.len() * materials.len();
        if count > woodpile::optimize::MAX_CATALOGUE_LEN {
            return Err(Error::invalid(
                "design.rod_range",
                format!("{count} rods"),
                format!(
                    "at most {} catalogue entries: use a larger step_mm or fewer diameters or materials",
                    woodpile::optimize::MAX_CATALOGUE_LEN
                ),
            ));
        }
        let mut out = Vec::with_capacity(count);
        for material in &materials {
            for &diameter in &diameters {
                for i in 0..=steps {
                    // Rounded to 1e-9 mm so that labels and files read 21 rather than 21.000000000000004.
                    let length = ((self.from_mm + i as f64 * self.step_mm) * 1e9).round() / 1e9;
                    out.push(ElementSpec {
                        kind: Some(ElementKind::Rod),
                        length_mm: Some(length),
                        diameter_mm: Some(diameter),
                        material: Some(crate::scenario::MaterialSpec::preset(material)),
                        cell: self.modes.map(|l| crate::scenario::CellSpec {
                            modes: Some(l),
                            ..crate::scenario::CellSpec::default()
                        }),
                        ..ElementSpec::default()
                    });
                }
            }
        }
        Ok(out)
    }
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
    /// Largest height of the stack \[mm\] (the sum of the elements' diameters).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_stack_height_mm: Option<f64>,
    /// Largest Hertz peak pressure of any contact of the structure \[Pa\] (known after a run:
    /// needs `ga.algorithm = "nsga2"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_contact_pressure_pa: Option<f64>,
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
    /// Objectives, one or more of the names of [`DesignFigure`](woodpile::optimize::DesignFigure) (instead of `objective`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objectives: Option<Vec<String>>,
    /// `breeder` (one objective; the default for one) or `nsga2` (the default for several).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub algorithm: Option<String>,
    /// The paper's integration (RK4 at 0.1 µs, every design simulated whole) instead of a design
    /// study's accuracy-targeted defaults ([`OptimizeConfig::accuracy_targeted`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paper_settings: Option<bool>,
    /// NSGA-II: the hypervolume's reference point, one value per objective in SI units
    /// (default: from generation 0, stated in `summary.json`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_point: Option<Vec<f64>>,
    /// Fitness cache on (default true); off changes only the run time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cache: Option<bool>,
    /// Screening: each new design is simulated first with every contact peak within this
    /// relative tolerance, and again at the run's settings only where its rank could decide a
    /// selection (default: off). Needs `run.peak_tolerance` and a force objective.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub screen_peak_tolerance: Option<f64>,
    /// Early stopping: a new design's run stops once its transmitted peak exceeds the previous
    /// generation's breeding cutoff (2 % above it), its value then only known to be larger;
    /// the choices stay those of a run without it (default: off). Needs `transmitted-force`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stop_early: Option<bool>,
    /// Robust design: the objective is this statistic of the transmitted force over the
    /// `[uncertainty]` samples (`mean`, `quantile:p`, `cvar:a`), every design on the same draws
    /// (NSGA-II: every figure of a run is; mass, height and layers stay nominal); no screening
    /// or early stopping.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robust: Option<String>,
    /// Goes ahead with a generation above the up-front limit
    /// (`limits::MAX_GENERATION_ELEMENTS` elements simulated per generation; default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub allow_large: Option<bool>,
}

impl OptimizeConfig {
    /// Parses a config from TOML text; syntax errors and unknown keys give line and column.
    pub fn parse(text: &str, source_name: &str) -> Result<Self, Error> {
        toml::from_str(text).map_err(|e| Error::Parse {
            source_name: source_name.to_string(),
            message: e.to_string(),
        })
    }

    /// A built-in problem: the paper's 20 rods from Table 1 under its impact or blast.
    pub fn builtin(name: &str) -> Result<Self, Error> {
        let kind = match name {
            "paper-impact" => ExcitationKind::Impact,
            "paper-blast" => ExcitationKind::Blast,
            _ => {
                return Err(Error::UnknownScenario {
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

    /// The config a design study runs by default: unless `ga.paper_settings = true` or `[run]`
    /// names an integrator or a peak tolerance, every contact peak within
    /// [`woodpile::defaults::STUDY_PEAK_TOLERANCE`]; for the breeder GA on a force objective also
    /// screening at [`woodpile::defaults::STUDY_SCREEN_PEAK_TOLERANCE`] and, on the transmitted
    /// force, early stopping (unless set). Both keep every choice of the GA (docs/physics.md §11).
    pub fn accuracy_targeted(&self) -> Self {
        let mut c = self.clone();
        let r = &c.run;
        let stated = r.peak_tolerance.is_some()
            || r.integrator.is_some()
            || r.time_step_s.is_some()
            || r.rtol.is_some()
            || r.atol.is_some();
        if c.ga.paper_settings == Some(true) || stated {
            return c;
        }
        c.run.peak_tolerance = Some(woodpile::defaults::STUDY_PEAK_TOLERANCE);
        if c.ga.robust.is_some() {
            // A statistic over samples has no screening bound and is no running maximum.
            return c;
        }
        let g = &mut c.ga;
        let several = g.objectives.as_ref().is_some_and(|o| o.len() > 1)
            || g.algorithm.as_deref() == Some("nsga2");
        if several {
            return c;
        }
        let objective = g
            .objectives
            .as_ref()
            .and_then(|o| o.first().cloned())
            .or_else(|| g.objective.clone())
            .unwrap_or_else(|| StandardObjective::default().as_str().to_string());
        if matches!(
            objective.as_str(),
            "transmitted-force" | "transmission-ratio"
        ) {
            g.screen_peak_tolerance
                .get_or_insert(woodpile::defaults::STUDY_SCREEN_PEAK_TOLERANCE);
        }
        if objective == "transmitted-force" {
            g.stop_early.get_or_insert(true);
        }
        c
    }

    /// In words: how accurately the designs of a completed config are simulated.
    pub fn accuracy_text(&self) -> String {
        let mut text = self.run.accuracy_text();
        if let Some(t) = self.ga.screen_peak_tolerance {
            text.push_str(&format!(", screened at {t:e}"));
        }
        if self.ga.stop_early == Some(true) {
            text.push_str(", runs stopped early");
        }
        if self.ga.paper_settings != Some(true) && self.run.peak_tolerance.is_some() {
            text.push_str(" (--paper-settings: the paper's rk4 at 1e-7 s)");
        }
        text
    }

    /// Whether two configs pose the same problem: equal in everything but descriptive text.
    pub fn same_problem(&self, other: &Self) -> bool {
        // The limit's override changes no result.
        let bare = |c: &Self| OptimizeConfig {
            description: None,
            ga: GaSpec {
                allow_large: None,
                ..c.ga.clone()
            },
            ..c.clone()
        };
        bare(self) == bare(other)
    }

    /// [`OptimizeConfig::complete`], with a `rod_range` expanded into `elements` (its errors
    /// name its keys).
    pub fn complete_checked(&self) -> Result<Self, Error> {
        let mut c = self.clone();
        if let (Some(range), None, None) = (
            &c.design.rod_range,
            &c.design.catalogue_mm,
            &c.design.elements,
        ) {
            c.design.elements = Some(range.elements()?);
        }
        Ok(c.complete())
    }

    /// The same config with every default written out (a `rod_range` is expanded by
    /// [`OptimizeConfig::complete_checked`]).
    pub fn complete(&self) -> Self {
        let mut c = self.clone();
        let d = &mut c.design;
        d.positions.get_or_insert(PositionsSpec::Count(20));
        // The default catalogue is Table 1, unless a rod range (expanded by complete_checked)
        // or a general list says otherwise.
        if d.elements.is_none() && d.rod_range.is_none() {
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
            ..Scenario::default()
        }
        .complete();
        c.excitation = base.excitation;
        c.wall = base.wall;
        c.run = base.run;
        let g = &mut c.ga;
        let defaults = GaSettings::default();
        g.population.get_or_insert(defaults.population);
        g.generations.get_or_insert(defaults.generations);
        g.stall_generations
            .get_or_insert(defaults.stall_generations.unwrap_or(0));
        g.seed.get_or_insert(defaults.seed);
        g.cache.get_or_insert(true);
        if g.objectives.is_some() || g.algorithm.is_some() {
            // A study written with the list form: the objectives and the algorithm stated.
            let objectives = g.objectives.get_or_insert_with(|| {
                vec![g
                    .objective
                    .take()
                    .unwrap_or_else(|| StandardObjective::default().as_str().to_string())]
            });
            let algorithm = if objectives.len() > 1 {
                "nsga2"
            } else {
                "breeder"
            };
            let algorithm = g.algorithm.get_or_insert_with(|| algorithm.to_string());
            if algorithm == "nsga2" {
                return c;
            }
        } else {
            g.objective
                .get_or_insert_with(|| StandardObjective::default().as_str().to_string());
        }
        g.truncation.get_or_insert(defaults.truncation);
        g.elites.get_or_insert(defaults.elites);
        c
    }

    /// The scenario of a chain of this problem (`chain` top to bottom).
    pub(crate) fn scenario(&self, chain: ChainSpec, description: Option<String>) -> Scenario {
        Scenario {
            description,
            chain,
            excitation: self.excitation.clone(),
            wall: self.wall.clone(),
            run: self.run.clone(),
            ..Scenario::default()
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

/// The scenario of a genome under a completed config (`Problem::scenario`): its load, support
/// and run with that chain, files it names (a blast table) made absolute.
pub fn scenario_of(
    config: &OptimizeConfig,
    base_dir: &Path,
    genome: &[u8],
    description: Option<String>,
) -> Scenario {
    let mut s = config.scenario(config.chain_spec(genome), description);
    if let Some(file) = &s.excitation.file {
        let p = base_dir.join(file);
        let p = p.canonicalize().unwrap_or(p);
        s.excitation.file = Some(p.display().to_string());
    }
    s
}
