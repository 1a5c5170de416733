//! Lattice design studies (`woodpile optimize` of a config with a `[lattice]` table,
//! docs/optimization.md): the base lattice scenario's tables, a `[design]` naming what varies
//! and a `[ga]` for NSGA-II.
//!
//! ```toml
//! [lattice]                   # the base lattice, as in a lattice scenario
//! layers = [
//!   { rods = 3, pitch_mm = 16.0, length_mm = 60.0, diameter_mm = 5.0, material = "fused-quartz" },
//!   { rods = 3 },
//! ]
//! rod = { fe_elements = 2 }
//! [run]
//! duration_s = 1e-4
//! [design]
//! length_mm = [50.0, 60.0, 70.0]   # each varied layer's rod length: a list, or
//!                                  # { from_mm = 50.0, to_mm = 70.0, step_mm = 10.0 }
//! layers = [1, 2]                  # which layers' lengths vary (default: all), 1 = top
//! pitch_mm = [12.0, 16.0]          # every multi-rod layer's pitch: a list or a range
//! [ga]
//! objectives = ["transmitted-force", "total-mass"]
//! population = 6
//! generations = 12
//! ```
//!
//! A range holds from_mm, from_mm + step_mm, … up to to_mm (to_mm itself when the span is a
//! whole number of steps, to 1e-9 of a step), at most 256 values. The output directory holds
//! `checkpoint.json` (resumable), `history.csv` (as a chain's NSGA-II), `pareto.csv` (the
//! objectives, then `layer_1_length_mm` … `layer_L_length_mm` and `pitch_mm`), `pareto/NNN.toml`
//! (row NNN as a lattice scenario `woodpile simulate` re-runs to the row's figures) and
//! `summary.json`.

use crate::atomic::{io_err, write_atomic};
use crate::error::Error;
use crate::lattice::{
    LatticeExcitationSpec, LatticeScenario, LatticeSpec, LatticeWallSpec, ResolvedLattice,
};
use crate::pareto::{history_csv, parse_checkpoint, read_checkpoint, ParetoCheckpoint};
use crate::scenario::{DampingSpec, PreloadSpec, RunSpec};
use serde::{Deserialize, Serialize};
use std::path::Path;
use woodpile::optimize::{
    DesignFigure, LatticeDesignSpace, LatticeDesigns, MoIndividual, Nsga2, Nsga2Settings,
    Nsga2State, StopReason, MAX_LATTICE_CHOICES,
};

/// The lattice study checkpoint's format tag.
pub const LATTICE_CHECKPOINT_FORMAT: &str = "woodpile-optimize-lattice-checkpoint/1";

/// A lattice study's config file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeStudyConfig {
    /// One line saying what the study is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// `[lattice]`: the base lattice.
    pub lattice: LatticeSpec,
    /// `[excitation]`.
    #[serde(default)]
    pub excitation: LatticeExcitationSpec,
    /// `[wall]`.
    #[serde(default)]
    pub wall: LatticeWallSpec,
    /// `[damping]`, as in a lattice scenario (default: lossless).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingSpec>,
    /// `[preload]`, as in a lattice scenario (default: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload: Option<PreloadSpec>,
    /// `[run]`.
    #[serde(default)]
    pub run: RunSpec,
    /// `[design]`: what varies.
    #[serde(default)]
    pub design: LatticeDesignSpec,
    /// `[ga]`: NSGA-II.
    #[serde(default)]
    pub ga: LatticeGaSpec,
}

/// `[design]` of a lattice study.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeDesignSpec {
    /// The rod length choices of every varied layer \[mm\] (unset: no length varies).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length_mm: Option<ChoicesToml>,
    /// The layers whose length varies, 1 = top (default: all).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layers: Option<Vec<usize>>,
    /// The pitch choices of every layer of more than one rod \[mm\] (unset: each layer keeps
    /// its own).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_mm: Option<ChoicesToml>,
}

/// A list of values, or a range discretised by a step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ChoicesToml {
    /// `[a, b, …]` \[mm\].
    List(Vec<f64>),
    /// `{ from_mm, to_mm, step_mm }`.
    Range(RangeToml),
}

/// `{ from_mm, to_mm, step_mm }`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RangeToml {
    /// First value \[mm\].
    pub from_mm: f64,
    /// Last value \[mm\].
    pub to_mm: f64,
    /// Step \[mm\].
    pub step_mm: f64,
}

/// `[ga]` of a lattice study (NSGA-II; defaults as for chains' NSGA-II).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeGaSpec {
    /// `transmitted-force` and/or `total-mass` (default both).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objectives: Option<Vec<String>>,
    /// Population size μ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub population: Option<usize>,
    /// Generations after the first.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub generations: Option<usize>,
    /// Stop after this many generations without a larger hypervolume (0: no stall limit).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stall_generations: Option<usize>,
    /// Seed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// BGA mutation range in choice indices (default: each gene's span).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mutation_range: Option<f64>,
    /// The hypervolume's reference point, one value per objective (default: from generation 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_point: Option<Vec<f64>>,
}

/// A resolved lattice study: its completed config, base scenario and NSGA-II over its designs.
#[derive(Debug)]
pub struct LatticeStudy {
    /// The config with every default written out.
    pub config: LatticeStudyConfig,
    /// The base scenario.
    pub base: LatticeScenario,
    /// NSGA-II over the designs.
    pub ga: Nsga2<LatticeDesigns>,
}

/// Whether a config text describes a lattice study (has a top-level `lattice` table).
pub fn is_lattice_study(text: &str) -> bool {
    crate::lattice::is_lattice(text)
}

impl LatticeStudyConfig {
    /// Parses a lattice study config; syntax errors and unknown keys give the line and column.
    pub fn parse(text: &str, source_name: &str) -> Result<Self, Error> {
        toml::from_str(text).map_err(|e| Error::Parse {
            source_name: source_name.into(),
            message: e.to_string(),
        })
    }

    /// The base lattice scenario.
    pub fn base(&self) -> LatticeScenario {
        LatticeScenario {
            description: self.description.clone(),
            lattice: self.lattice.clone(),
            excitation: self.excitation.clone(),
            wall: self.wall.clone(),
            damping: self.damping.clone(),
            preload: self.preload,
            run: self.run.clone(),
        }
    }

    /// The config with every default written out (the scenario's and NSGA-II's).
    pub fn complete(&self) -> Self {
        let base = self.base().complete();
        let d = Nsga2Settings::default();
        let mut ga = self.ga.clone();
        ga.objectives
            .get_or_insert_with(|| vec!["transmitted-force".to_string(), "total-mass".to_string()]);
        ga.population.get_or_insert(d.population);
        ga.generations.get_or_insert(d.generations);
        ga.stall_generations
            .get_or_insert(d.stall_generations.unwrap_or(0));
        ga.seed.get_or_insert(d.seed);
        LatticeStudyConfig {
            description: base.description,
            lattice: base.lattice,
            excitation: base.excitation,
            wall: base.wall,
            damping: base.damping,
            preload: base.preload,
            run: base.run,
            design: self.design.clone(),
            ga,
        }
    }

    /// Checks the config and builds NSGA-II's space (proving every design buildable) with
    /// `threads` workers (0: one per core); errors name the keys.
    pub fn resolve(&self, threads: usize) -> Result<LatticeStudy, Error> {
        let config = self.complete();
        let base = config.base();
        let resolved = base.resolve()?;
        let space = design_space(&config.design, &resolved)?;
        let ga = &config.ga;
        let objectives = ga
            .objectives
            .as_ref()
            .expect("completed")
            .iter()
            .enumerate()
            .map(|(k, name)| {
                DesignFigure::from_name(name).map_err(|_| {
                    Error::invalid(
                        format!("ga.objectives[{k}]"),
                        format!("\"{name}\""),
                        "a lattice study minimises \"transmitted-force\" or \"total-mass\"",
                    )
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let settings = Nsga2Settings {
            population: ga.population.expect("completed"),
            generations: ga.generations.expect("completed"),
            stall_generations: ga.stall_generations.filter(|&s| s > 0),
            seed: ga.seed.expect("completed"),
            mutation_range: ga.mutation_range,
            threads,
            cache: true,
            reference_point: ga.reference_point.clone(),
        };
        let designs = LatticeDesigns::new(space, objectives, threads)
            .map_err(crate::optimize::optimize_error)?;
        let ga = Nsga2::over(designs, settings).map_err(crate::optimize::optimize_error)?;
        Ok(LatticeStudy { config, base, ga })
    }
}

/// The space of `[design]` over the base lattice.
fn design_space(
    d: &LatticeDesignSpec,
    resolved: &ResolvedLattice,
) -> Result<LatticeDesignSpace, Error> {
    let layers = resolved.builder.layers.len();
    let varied: Vec<usize> = match &d.layers {
        Some(list) => {
            for (k, &l) in list.iter().enumerate() {
                if l == 0 || l > layers || list[..k].contains(&l) {
                    return Err(Error::invalid(
                        format!("design.layers[{k}]"),
                        l,
                        format!("a layer number 1..={layers} (1 = top), each once"),
                    ));
                }
            }
            if d.length_mm.is_none() {
                return Err(Error::invalid(
                    "design.layers",
                    format!("{list:?}"),
                    "give design.length_mm, the lengths these layers choose from",
                ));
            }
            list.clone()
        }
        None => (1..=layers).collect(),
    };
    let lengths = match &d.length_mm {
        Some(c) => choices_m("design.length_mm", c)?,
        None => Vec::new(),
    };
    let lengths_m = (1..=layers)
        .map(|l| {
            if varied.contains(&l) && !lengths.is_empty() {
                lengths.clone()
            } else {
                vec![resolved.builder.layers[l - 1].length_m]
            }
        })
        .collect();
    let pitches_m = match &d.pitch_mm {
        Some(c) => choices_m("design.pitch_mm", c)?,
        None => Vec::new(),
    };
    Ok(LatticeDesignSpace {
        base: resolved.builder.clone(),
        excitation: resolved.excitation.clone(),
        lab: resolved.lab.clone(),
        settings: resolved.settings,
        lengths_m,
        pitches_m,
    })
}

/// A list's or a range's values \[m\]; errors name `field`.
fn choices_m(field: &str, c: &ChoicesToml) -> Result<Vec<f64>, Error> {
    let values_mm = match c {
        ChoicesToml::List(v) => v.clone(),
        ChoicesToml::Range(r) => range_values_mm(field, r)?,
    };
    if values_mm.is_empty() || values_mm.len() > MAX_LATTICE_CHOICES {
        return Err(Error::invalid(
            field,
            format!("{} values", values_mm.len()),
            format!("give 1 to {MAX_LATTICE_CHOICES} values"),
        ));
    }
    for (k, &v) in values_mm.iter().enumerate() {
        if !(v.is_finite() && v > 0.0) || values_mm[..k].contains(&v) {
            return Err(Error::invalid(
                format!("{field}[{k}]"),
                v,
                "every value a finite length > 0 [mm], each once",
            ));
        }
    }
    Ok(values_mm.iter().map(|v| v * 1e-3).collect())
}

/// from_mm, from_mm + step_mm, … up to to_mm (to 1e-9 of a step).
fn range_values_mm(field: &str, r: &RangeToml) -> Result<Vec<f64>, Error> {
    let bad = |key: &str, v: f64, why: &str| Err(Error::invalid(format!("{field}.{key}"), v, why));
    if !(r.from_mm.is_finite() && r.from_mm > 0.0) {
        return bad("from_mm", r.from_mm, "a finite length > 0 [mm]");
    }
    if !(r.to_mm.is_finite() && r.to_mm >= r.from_mm) {
        return bad("to_mm", r.to_mm, "a finite length ≥ from_mm [mm]");
    }
    if !(r.step_mm.is_finite() && r.step_mm > 0.0) {
        return bad("step_mm", r.step_mm, "a finite step > 0 [mm]");
    }
    let steps = ((r.to_mm - r.from_mm) / r.step_mm + 1e-9).floor();
    if steps + 1.0 > MAX_LATTICE_CHOICES as f64 {
        return bad(
            "step_mm",
            r.step_mm,
            "the range would hold more than 256 values: a larger step",
        );
    }
    Ok((0..=steps as usize)
        .map(|k| r.from_mm + k as f64 * r.step_mm)
        .collect())
}

impl LatticeStudy {
    /// Design `genome` as a lattice scenario (the base with its lengths and pitch).
    pub fn scenario(&self, genome: &[u8]) -> LatticeScenario {
        let space = self.ga.designs().space();
        let mut s = self.base.complete();
        let pitch = space.pitch_m(genome);
        for (k, layer) in s.lattice.layers.iter_mut().enumerate() {
            layer.length_mm = Some(space.lengths_m[k][usize::from(genome[k])] * 1e3);
            if let (true, Some(p)) = (space.base.layers[k].rods > 1, pitch) {
                layer.pitch_mm = Some(p * 1e3);
            }
        }
        s
    }

    /// `pareto.csv` of a front (see the module documentation).
    pub fn pareto_csv(&self, front: &[&MoIndividual]) -> String {
        let layers = self.ga.designs().space().lengths_m.len();
        let mut head: Vec<String> = self
            .ga
            .designs()
            .objectives()
            .iter()
            .map(|f| f.as_str().to_string())
            .collect();
        head.extend((1..=layers).map(|l| format!("layer_{l}_length_mm")));
        head.push("pitch_mm".into());
        let mut text = head.join(",") + "\n";
        for ind in front {
            let s = self.scenario(&ind.genome);
            let mut row: Vec<String> = ind.objectives.iter().map(|v| format!("{v}")).collect();
            row.extend(
                s.lattice
                    .layers
                    .iter()
                    .map(|l| format!("{}", l.length_mm.expect("set"))),
            );
            let pitch = self.ga.designs().space().pitch_m(&ind.genome);
            row.push(pitch.map_or(String::new(), |p| format!("{}", p * 1e3)));
            text.push_str(&(row.join(",") + "\n"));
        }
        text
    }
}

/// `summary.json` of a lattice study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LatticeStudySummary {
    /// The objectives, in `pareto.csv`'s order.
    pub objectives: Vec<String>,
    /// Their SI units.
    pub units: Vec<String>,
    /// The hypervolume's reference point.
    pub reference_point: Vec<f64>,
    /// The final front's hypervolume.
    pub hypervolume: f64,
    /// Why it stopped.
    pub stop_reason: String,
    /// Generations completed.
    pub generations: usize,
    /// Designs simulated.
    pub evaluations: u64,
    /// The seed.
    pub seed: u64,
    /// Designs in the space.
    pub designs_in_space: usize,
    /// `pareto/NNN.toml` of each front row, in order.
    pub front: Vec<String>,
}

/// A finished lattice study read back (`woodpile plot` draws it).
#[derive(Debug, Clone, PartialEq)]
pub struct LatticeStudyOutput {
    /// `summary.json`.
    pub summary: LatticeStudySummary,
    /// The hypervolume of each generation (`history.csv`).
    pub hypervolume: Vec<(usize, f64)>,
    /// The objectives of each row of `pareto.csv`, SI units.
    pub front: Vec<Vec<f64>>,
}

/// Reads a lattice study's output directory; None when its `summary.json` is not a lattice
/// study's (a chain's NSGA-II, or none). A `pareto.csv` objective that is not a finite number is
/// refused naming the line and the column: a front drawn through it would mean nothing.
pub fn read_study_output(dir: &Path) -> Result<Option<LatticeStudyOutput>, Error> {
    let Ok(text) = std::fs::read_to_string(dir.join("summary.json")) else {
        return Ok(None);
    };
    let Ok(summary) = serde_json::from_str::<LatticeStudySummary>(&text) else {
        return Ok(None);
    };
    let path = dir.join("pareto.csv");
    let table = |line: u64, message: String| Error::Table {
        path: path.clone(),
        line,
        message,
    };
    let file = std::fs::File::open(&path).map_err(|e| Error::Read {
        path: path.clone(),
        source: e,
    })?;
    let mut r = crate::table::csv_reader(file);
    let header = r.headers().map_err(|e| table(1, e.to_string()))?.clone();
    let m = summary.objectives.len();
    if header
        .iter()
        .take(m)
        .ne(summary.objectives.iter().map(String::as_str))
    {
        return Err(table(
            1,
            format!(
                "its first columns are not the objectives of summary.json ({})",
                summary.objectives.join(", ")
            ),
        ));
    }
    let mut front = Vec::new();
    for rec in r.records() {
        let rec = rec.map_err(|e| table(e.position().map_or(0, |p| p.line()), e.to_string()))?;
        let line = rec.position().map_or(0, |p| p.line());
        let mut row = Vec::with_capacity(m);
        for (j, name) in summary.objectives.iter().enumerate() {
            let cell = rec.get(j).unwrap_or("");
            match cell.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => row.push(v),
                _ => return Err(table(line, format!("column `{name}` is `{cell}`, not a finite number: every design of a front has a value of each objective"))),
            }
        }
        front.push(row);
    }
    Ok(Some(LatticeStudyOutput {
        hypervolume: crate::pareto::read_hypervolume(dir)?,
        summary,
        front,
    }))
}

/// The output directory policy: with `resume`, the checkpoint in `out` of the same completed
/// config; without, `out` absent or empty. Nothing is written.
pub fn prepare_output(
    out: &Path,
    resume: bool,
    config: &LatticeStudyConfig,
) -> Result<Option<Nsga2State>, Error> {
    if !resume {
        return crate::optimize::require_empty(out).map(|()| None);
    }
    let (cp, path) = read_checkpoint::<LatticeStudyConfig>(out, LATTICE_CHECKPOINT_FORMAT)?;
    if cp.config != *config {
        return Err(Error::ResumeRefused {
            path,
            reason: "the checkpoint belongs to a different lattice study (config or seed differ); resume with the same ones".into(),
        });
    }
    Ok(Some(cp.into_state()))
}

/// The state of a checkpoint's text (read from `path`), checked: this version's, intact, of
/// the same completed config.
pub fn restore_checkpoint(
    text: &str,
    path: &Path,
    config: &LatticeStudyConfig,
) -> Result<Nsga2State, Error> {
    let cp = parse_checkpoint::<LatticeStudyConfig>(text, path, LATTICE_CHECKPOINT_FORMAT)?;
    if cp.config != *config {
        return Err(Error::ResumeRefused {
            path: path.to_path_buf(),
            reason: "the checkpoint belongs to a different lattice study (config or seed differ); resume with the same ones".into(),
        });
    }
    Ok(cp.into_state())
}

/// The checkpoint of `state` as JSON.
pub fn checkpoint_json(config: &LatticeStudyConfig, state: &Nsga2State) -> Vec<u8> {
    let cp = ParetoCheckpoint::tagged(LATTICE_CHECKPOINT_FORMAT, config, state);
    serde_json::to_vec(&cp).unwrap_or_default()
}

/// Writes what changes after every generation, atomically: the checkpoint and `history.csv`.
pub fn write_generation(
    out: &Path,
    config: &LatticeStudyConfig,
    state: &Nsga2State,
) -> Result<(), Error> {
    let file = crate::optimize::CHECKPOINT_FILE;
    let cp = ParetoCheckpoint::tagged(LATTICE_CHECKPOINT_FORMAT, config, state);
    let json =
        serde_json::to_vec(&cp).map_err(|e| io_err(&out.join(file))(std::io::Error::other(e)))?;
    write_atomic(out, file, &json)?;
    write_atomic(out, "history.csv", history_csv(&state.history).as_bytes())
}

/// Writes the final outputs: `pareto.csv`, `pareto/NNN.toml`, `summary.json`.
pub fn write_final_outputs(
    out: &Path,
    study: &LatticeStudy,
    state: &Nsga2State,
    stop: StopReason,
) -> Result<LatticeStudySummary, Error> {
    let front = state.front();
    // Also after a resume with nothing left to run, which writes no generation.
    write_atomic(out, "history.csv", history_csv(&state.history).as_bytes())?;
    write_atomic(out, "pareto.csv", study.pareto_csv(&front).as_bytes())?;
    let dir = out.join("pareto");
    std::fs::create_dir_all(&dir).map_err(io_err(&dir))?;
    let summary = summary_of(study, state, stop);
    for (name, ind) in summary.front.iter().zip(&front) {
        let file = name.trim_start_matches("pareto/");
        let text = toml::to_string(&study.scenario(&ind.genome))
            .map_err(|e| io_err(&dir.join(file))(std::io::Error::other(e)))?;
        write_atomic(&dir, file, text.as_bytes())?;
    }
    let json = serde_json::to_vec_pretty(&summary)
        .map_err(|e| io_err(&out.join("summary.json"))(std::io::Error::other(e)))?;
    write_atomic(out, "summary.json", &json)?;
    Ok(summary)
}

/// `summary.json` of a study stopped at `state` for `stop`.
pub fn summary_of(
    study: &LatticeStudy,
    state: &Nsga2State,
    stop: StopReason,
) -> LatticeStudySummary {
    let front = state.front();
    let names = (1..=front.len())
        .map(|k| format!("pareto/{k:03}.toml"))
        .collect();
    let points: Vec<Vec<f64>> = front.iter().map(|i| i.objectives.clone()).collect();
    let objectives = study.ga.designs().objectives();
    LatticeStudySummary {
        objectives: objectives.iter().map(|f| f.as_str().to_string()).collect(),
        units: objectives.iter().map(|f| f.unit().to_string()).collect(),
        reference_point: state.reference_point.clone(),
        hypervolume: woodpile::optimize::pareto::hypervolume(&points, &state.reference_point),
        stop_reason: crate::optimize::stop_text(stop).to_string(),
        generations: state.generation,
        evaluations: state.evaluations,
        seed: study.ga.settings().seed,
        designs_in_space: study.ga.designs().space().size(),
        front: names,
    }
}
