//! NSGA-II's files (`ga.algorithm = "nsga2"`): its checksummed checkpoint, `history.csv` with the
//! hypervolume per generation, `pareto.csv` (one row per non-dominated design: one column per
//! objective, named as in `ga.objectives`, in SI units, then `layer_1` … `layer_N`, the element
//! of each layer top to bottom — a rod's length in mm, another element's label), `pareto/NNN.toml`
//! (row NNN of `pareto.csv` as a scenario `woodpile simulate` re-runs) and `summary.json` (the
//! objectives, their units, the hypervolume's reference point, the front).

use crate::atomic::{io_err, remove_stale, write_atomic};
use crate::error::Error;
use crate::optimize::{require_empty, stop_text, OptimizeConfig, Problem, CHECKPOINT_FILE};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fs;
use std::path::Path;
use woodpile::optimize::{MoIndividual, Nsga2State, Nsga2Stats, StopReason};
use woodpile::Body;

/// The NSGA-II checkpoint's format tag.
pub const PARETO_CHECKPOINT_FORMAT: &str = "woodpile-optimize-nsga2-checkpoint/1";

/// `checkpoint.json` of an NSGA-II run: the completed config and the whole state, floats in
/// shortest round-trip digits, with the version that wrote it and an FNV-1a 64 checksum of its
/// compact JSON with `checksum` empty (as the breeder's checkpoint).
///
/// `C` is the completed config: a chain study's [`OptimizeConfig`], or a lattice study's
/// ([`crate::lattice_study`], its own format tag).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParetoCheckpoint<C = OptimizeConfig> {
    /// [`PARETO_CHECKPOINT_FORMAT`].
    pub format: String,
    /// Version of woodpile that wrote it.
    pub tool_version: String,
    /// FNV-1a 64 of the content, 16 hex digits.
    pub checksum: String,
    /// The completed config.
    pub config: C,
    /// Generations completed.
    pub generation: usize,
    /// Generations since the hypervolume grew.
    pub stalled: usize,
    /// Designs simulated so far.
    pub evaluations: u64,
    /// Cache hits so far.
    pub cache_hits: u64,
    /// Wall-clock seconds so far.
    pub elapsed_s: f64,
    /// The hypervolume's reference point.
    pub reference_point: Vec<f64>,
    /// The population, in NSGA-II's order.
    pub population: Vec<MoIndividual>,
    /// One line per generation.
    pub history: Vec<Nsga2Stats>,
    /// Every design evaluated, sorted by genome.
    pub cache: Vec<MoIndividual>,
}

impl ParetoCheckpoint {
    /// The checkpoint of a state for `config`, its checksum computed.
    pub fn new(config: &OptimizeConfig, s: &Nsga2State) -> Self {
        Self::tagged(PARETO_CHECKPOINT_FORMAT, config, s)
    }
}

impl<C: Clone + Serialize> ParetoCheckpoint<C> {
    /// The checkpoint of a state for `config` in format `format`, its checksum computed.
    pub fn tagged(format: &str, config: &C, s: &Nsga2State) -> Self {
        let mut cache: Vec<MoIndividual> = s.cache.values().cloned().collect();
        cache.sort_by(|a, b| a.genome.cmp(&b.genome));
        let mut cp = ParetoCheckpoint {
            format: format.into(),
            tool_version: env!("CARGO_PKG_VERSION").into(),
            checksum: String::new(),
            config: config.clone(),
            generation: s.generation,
            stalled: s.stalled,
            evaluations: s.evaluations,
            cache_hits: s.cache_hits,
            elapsed_s: s.elapsed_s,
            reference_point: s.reference_point.clone(),
            population: s.population.clone(),
            history: s.history.clone(),
            cache,
        };
        cp.checksum = cp.content_checksum();
        cp
    }

    /// The checksum of the content (see the type's documentation).
    pub fn content_checksum(&self) -> String {
        let unsigned = ParetoCheckpoint {
            checksum: String::new(),
            ..self.clone()
        };
        crate::optimize::json_checksum(&unsigned)
    }

    /// The state it holds.
    pub fn into_state(self) -> Nsga2State {
        Nsga2State {
            generation: self.generation,
            population: self.population,
            history: self.history,
            reference_point: self.reference_point,
            cache: self
                .cache
                .into_iter()
                .map(|i| (i.genome.clone(), i))
                .collect::<HashMap<_, _>>(),
            evaluations: self.evaluations,
            cache_hits: self.cache_hits,
            stalled: self.stalled,
            elapsed_s: self.elapsed_s,
        }
    }
}

/// The output directory policy of an NSGA-II run: with `resume`, the checkpoint in `out`
/// checked against `config`; without, `out` must be absent or empty. Nothing is written.
pub fn prepare_output(
    out: &Path,
    resume: bool,
    config: &OptimizeConfig,
) -> Result<Option<Nsga2State>, Error> {
    if !resume {
        return require_empty(out).map(|()| None);
    }
    let (cp, path) = read_checkpoint::<OptimizeConfig>(out, PARETO_CHECKPOINT_FORMAT)?;
    if !cp.config.same_problem(config) {
        return Err(Error::ResumeRefused {
            path,
            reason: "the checkpoint belongs to a different problem (config, model or seed differ); resume with the same ones".into(),
        });
    }
    Ok(Some(cp.into_state()))
}

/// Reads and checks `out`'s NSGA-II checkpoint of format `format`: present, parsed, written by
/// this version, its checksum intact. The config is the caller's to compare.
pub(crate) fn read_checkpoint<C>(
    out: &Path,
    format: &str,
) -> Result<(ParetoCheckpoint<C>, std::path::PathBuf), Error>
where
    C: Clone + Serialize + serde::de::DeserializeOwned,
{
    let path = out.join(CHECKPOINT_FILE);
    if !path.is_file() {
        return Err(Error::NothingToResume {
            path: out.to_path_buf(),
            file: CHECKPOINT_FILE,
        });
    }
    let text = fs::read_to_string(&path).map_err(|e| Error::Read {
        path: path.clone(),
        source: e,
    })?;
    parse_checkpoint(&text, &path, format).map(|cp| (cp, path))
}

/// Parses and checks an NSGA-II checkpoint's text (read from `path`) of format `format`:
/// written by this version, its checksum intact. The config is the caller's to compare.
pub(crate) fn parse_checkpoint<C>(
    text: &str,
    path: &Path,
    format: &str,
) -> Result<ParetoCheckpoint<C>, Error>
where
    C: Clone + Serialize + serde::de::DeserializeOwned,
{
    let path = path.to_path_buf();
    let corrupt = |message: String| {
        Error::Parse {
        source_name: path.display().to_string(),
        message: format!(
            "{message}; not an NSGA-II checkpoint of this version: restore it or start a new run in another output directory"
        ),
    }
    };
    let cp: ParetoCheckpoint<C> = serde_json::from_str(text).map_err(|e| corrupt(e.to_string()))?;
    let refuse = |reason: String| Error::ResumeRefused {
        path: path.clone(),
        reason,
    };
    if cp.format != format {
        return Err(corrupt(format!("format `{}`", cp.format)));
    }
    let ours = env!("CARGO_PKG_VERSION");
    if cp.tool_version != ours {
        return Err(refuse(format!(
            "the checkpoint was written by woodpile {}, this is woodpile {ours}: finish it with that version or start a new run",
            cp.tool_version
        )));
    }
    if cp.checksum != cp.content_checksum() {
        return Err(refuse(format!(
            "the checkpoint's checksum is {} but its content hashes to {}: it was modified after woodpile wrote it",
            cp.checksum,
            cp.content_checksum()
        )));
    }
    Ok(cp)
}

/// `history.csv` of an NSGA-II run: one line per generation.
pub fn history_csv(history: &[Nsga2Stats]) -> String {
    let mut s = String::from(
        "generation,hypervolume,front_size,feasible,evaluations,cache_hits,elapsed_s\n",
    );
    for h in history {
        s.push_str(&format!(
            "{},{},{},{},{},{},{:.3}\n",
            h.generation,
            h.hypervolume,
            h.front_size,
            h.feasible,
            h.evaluations,
            h.cache_hits,
            h.elapsed_s
        ));
    }
    s
}

/// Why a study's hypervolume means nothing, or None: it is 0 at the last generation while the
/// front holds designs, so no design is below the reference point in every objective (a
/// reference point such as [-1, -1] for positive objectives), and the hypervolume can neither
/// show progress nor stop the study on convergence.
pub fn hypervolume_warning(state: &Nsga2State) -> Option<String> {
    let h = state.history.last()?;
    (h.hypervolume == 0.0 && !state.front().is_empty()).then(|| {
        format!(
            "the hypervolume is 0: no design of the front is below the reference point {:?} in every objective, so the hypervolume measures nothing; set ga.reference_point above the front's values (pareto.csv), or leave it out to take it from generation 0",
            state.reference_point
        )
    })
}

/// Writes what changes after every generation, atomically: the checkpoint and `history.csv`.
pub fn write_generation(
    out: &Path,
    config: &OptimizeConfig,
    state: &Nsga2State,
) -> Result<(), Error> {
    let cp = ParetoCheckpoint::new(config, state);
    let json = serde_json::to_vec(&cp)
        .map_err(|e| io_err(&out.join(CHECKPOINT_FILE))(std::io::Error::other(e)))?;
    write_atomic(out, CHECKPOINT_FILE, &json)?;
    write_atomic(out, "history.csv", history_csv(&state.history).as_bytes())
}

/// The element of each layer as `pareto.csv` writes it: a rod's length in mm, else the label.
fn layer_text(problem: &Problem, g: u8) -> String {
    let e = &problem.space.catalogue[usize::from(g)];
    match e.body {
        Body::Rod { length_m, .. } => {
            let mm = (length_m * 1e3 * 1e9).round() / 1e9;
            format!("{mm}")
        }
        Body::Sphere { .. } => e.label.clone(),
    }
}

/// `pareto.csv` of a front (see the module documentation).
pub fn pareto_csv(problem: &Problem, front: &[&MoIndividual]) -> String {
    let mut s: Vec<String> = problem
        .objectives
        .iter()
        .map(|f| f.as_str().to_string())
        .collect();
    let n = front.iter().map(|i| i.genome.len()).max().unwrap_or(0);
    s.extend((1..=n).map(|l| format!("layer_{l}")));
    let mut text = s.join(",") + "\n";
    for ind in front {
        let mut row: Vec<String> = ind.objectives.iter().map(|v| format!("{v}")).collect();
        row.extend(ind.genome.iter().map(|&g| layer_text(problem, g)));
        row.resize(problem.objectives.len() + n, String::new());
        text.push_str(&row.join(","));
        text.push('\n');
    }
    text
}

/// One design of the front in `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FrontDesign {
    /// `pareto/NNN.toml`.
    pub file: String,
    /// One value per objective, SI units.
    pub objectives: Vec<f64>,
    /// Element labels, top to bottom.
    pub labels: Vec<String>,
    /// Catalogue indices.
    pub genome: Vec<u8>,
}

/// An objective's name and unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectiveSpec {
    /// As in `ga.objectives`.
    pub name: String,
    /// SI unit of its column.
    pub unit: String,
}

/// `summary.json` of an NSGA-II run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParetoSummary {
    /// `woodpile optimize`.
    pub tool: String,
    /// Version of woodpile.
    pub version: String,
    /// Problem name.
    pub problem: String,
    /// `nsga2`.
    pub algorithm: String,
    /// `finished` or `interrupted`.
    pub status: String,
    /// Why it stopped.
    pub stop_reason: String,
    /// The objectives, in column order.
    pub objectives: Vec<ObjectiveSpec>,
    /// The hypervolume's reference point (one value per objective, SI units): `ga.reference_point`,
    /// or by default from generation 0 (the worst feasible value of each objective plus a tenth
    /// of its range).
    pub reference_point: Vec<f64>,
    /// Hypervolume of the final front.
    pub hypervolume: f64,
    /// Feasible designs in the final population (a pressure limit can leave none).
    pub feasible: usize,
    /// Seed.
    pub seed: u64,
    /// Generations completed.
    pub generations_completed: usize,
    /// Designs simulated.
    pub evaluations: u64,
    /// Designs found in the cache.
    pub cache_hits: u64,
    /// Wall-clock time \[s\].
    pub elapsed_s: f64,
    /// Designs simulated per second.
    pub evaluations_per_s: f64,
    /// The front, in the rows of `pareto.csv`.
    pub front: Vec<FrontDesign>,
    /// The completed config.
    pub config: OptimizeConfig,
}

/// Writes `pareto.csv`, `pareto/NNN.toml`, `robust/NNN.csv` (a robust study's samples of
/// each front design) and `summary.json`; returns the summary.
pub fn write_final_outputs(
    problem: &Problem,
    name: &str,
    state: &Nsga2State,
    reason: StopReason,
    out: &Path,
) -> Result<ParetoSummary, Error> {
    let front = state.front();
    // Also after a resume with nothing left to run, which writes no generation.
    write_atomic(out, "history.csv", history_csv(&state.history).as_bytes())?;
    write_atomic(out, "pareto.csv", pareto_csv(problem, &front).as_bytes())?;
    let dir = out.join("pareto");
    fs::create_dir_all(&dir).map_err(io_err(&dir))?;
    remove_stale(&dir, front.len(), "toml")?;
    let mut designs = Vec::with_capacity(front.len());
    for (k, ind) in front.iter().enumerate() {
        let file = format!("{:03}.toml", k + 1);
        let values: Vec<String> = problem
            .objectives
            .iter()
            .zip(&ind.objectives)
            .map(|(f, v)| format!("{} = {v} {}", f.as_str(), f.unit()))
            .collect();
        let mut description = format!(
            "Pareto design {} of `woodpile optimize` ({name}, NSGA-II, seed {}): {}",
            k + 1,
            problem.nsga2.seed,
            values.join(", ")
        );
        if let Some(robust) = &problem.config.ga.robust {
            description += &format!(
                " (the figures of a run: their {robust} over the [uncertainty] samples, robust/{:03}.csv)",
                k + 1
            );
        }
        let scenario = problem.scenario(&ind.genome, Some(description));
        write_atomic(&dir, &file, scenario.to_toml().as_bytes())?;
        designs.push(FrontDesign {
            file: format!("pareto/{file}"),
            objectives: ind.objectives.clone(),
            labels: problem.space.labels(&ind.genome),
            genome: ind.genome.clone(),
        });
    }
    if let Some(robust) = problem.robust_objective() {
        let genomes: Vec<&[u8]> = front.iter().map(|i| i.genome.as_slice()).collect();
        let mut extra = problem.objectives.clone();
        let pressure = woodpile::optimize::DesignFigure::MaxContactPressure;
        if problem.space.constraints.max_contact_pressure_pa.is_some() && !extra.contains(&pressure)
        {
            extra.push(pressure);
        }
        crate::robust::write_robust_csvs(out, &robust, &genomes, &extra)?;
    }
    let last = state.history.last();
    let summary = ParetoSummary {
        tool: "woodpile optimize".into(),
        version: env!("CARGO_PKG_VERSION").into(),
        problem: name.into(),
        algorithm: "nsga2".into(),
        status: if reason == StopReason::Interrupted {
            "interrupted"
        } else {
            "finished"
        }
        .into(),
        stop_reason: stop_text(reason).into(),
        objectives: problem
            .objectives
            .iter()
            .map(|f| ObjectiveSpec {
                name: f.as_str().into(),
                unit: f.unit().into(),
            })
            .collect(),
        reference_point: state.reference_point.clone(),
        hypervolume: last.map_or(0.0, |h| h.hypervolume),
        feasible: last.map_or(0, |h| h.feasible),
        seed: problem.nsga2.seed,
        generations_completed: state.generation,
        evaluations: state.evaluations,
        cache_hits: state.cache_hits,
        elapsed_s: state.elapsed_s,
        evaluations_per_s: if state.elapsed_s > 0.0 {
            state.evaluations as f64 / state.elapsed_s
        } else {
            0.0
        },
        front: designs,
        config: problem.config.clone(),
    };
    let json = serde_json::to_vec_pretty(&summary)
        .map_err(|e| io_err(&out.join("summary.json"))(std::io::Error::other(e)))?;
    write_atomic(out, "summary.json", &json)?;
    Ok(summary)
}

/// The designs a front is compared with in its figures: every homogeneous chain of the
/// catalogue (`"20 × 40mm"`) and, when the problem is the paper's (the seven Table 1 rods on 20
/// positions), the paper's blast-optimised chain ([`woodpile::PAPER_OPTIMIZED_CHAIN_MM`]).
pub fn reference_designs(problem: &Problem) -> Vec<(String, Vec<u8>)> {
    let space = &problem.space;
    let n = space.positions;
    let mut designs: Vec<(String, Vec<u8>)> = (0..space.catalogue.len())
        .map(|c| {
            let label = &space.catalogue[c].label;
            (format!("{n} × {label}"), vec![c as u8; n])
        })
        .collect();
    let lengths_mm: Vec<Option<u32>> = space
        .catalogue
        .iter()
        .map(|e| match e.body {
            Body::Rod { length_m, .. } => Some((length_m * 1e3).round() as u32),
            Body::Sphere { .. } => None,
        })
        .collect();
    let paper = woodpile::TABLE1_LENGTHS_MM.map(Some);
    if n == woodpile::PAPER_OPTIMIZED_CHAIN_MM.len() && lengths_mm == paper {
        let genome = woodpile::PAPER_OPTIMIZED_CHAIN_MM
            .iter()
            .map(|mm| paper.iter().position(|l| *l == Some(*mm)).unwrap_or(0) as u8)
            .collect();
        designs.push(("paper's blast-optimised chain".to_string(), genome));
    }
    designs
}

/// `references.csv`: one row per reference design (see [`reference_designs`]): `design` (its
/// name), then one column per objective as in `pareto.csv`, then `feasible` (whether it meets
/// the design's constraints).
pub fn references_csv(problem: &Problem, rows: &[(String, Vec<f64>, bool)]) -> String {
    let mut head = vec!["design".to_string()];
    head.extend(problem.objectives.iter().map(|f| f.as_str().to_string()));
    head.push("feasible".into());
    let mut text = head.join(",") + "\n";
    for (name, values, feasible) in rows {
        let mut row = vec![name.clone()];
        row.extend(values.iter().map(|v| format!("{v}")));
        row.push(feasible.to_string());
        text.push_str(&row.join(","));
        text.push('\n');
    }
    text
}

/// One row of `references.csv` read back.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceDesign {
    /// Its name (`20 × 40mm`, `paper's blast-optimised chain`).
    pub name: String,
    /// One value per objective, SI units.
    pub objectives: Vec<f64>,
    /// Whether it meets the design's constraints.
    pub feasible: bool,
}

/// Reads `references.csv` (None when the directory has none).
pub fn read_references(path: &Path) -> Result<Option<Vec<ReferenceDesign>>, Error> {
    if !path.is_file() {
        return Ok(None);
    }
    let bad = |reason: String| crate::atomic::read_error(path, reason);
    let text = fs::read_to_string(path).map_err(|e| bad(e.to_string()))?;
    let mut r = crate::table::csv_reader(text.as_bytes());
    let mut rows = Vec::new();
    for rec in r.records() {
        let rec = rec.map_err(|e| bad(e.to_string()))?;
        let n = rec.len();
        if n < 3 {
            return Err(bad(format!(
                "a row of {n} columns: design, objectives, feasible"
            )));
        }
        let objectives = (1..n - 1)
            .map(|i| rec[i].trim().parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
            .map_err(|e| bad(format!("{}: {e}", &rec[0])))?;
        rows.push(ReferenceDesign {
            name: rec[0].to_string(),
            objectives,
            feasible: rec[n - 1].trim() == "true",
        });
    }
    Ok(Some(rows))
}

/// What `woodpile plot` reads of an NSGA-II output directory.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoOutput {
    /// `summary.json` (the front, the objectives, the reference point).
    pub summary: ParetoSummary,
    /// (generation, hypervolume) from `history.csv`.
    pub hypervolume: Vec<(usize, f64)>,
    /// `references.csv`, where written.
    pub references: Option<Vec<ReferenceDesign>>,
}

/// Whether `dir` holds an NSGA-II run (its `history.csv` has a `hypervolume` column).
pub fn is_pareto_dir(dir: &Path) -> bool {
    fs::read_to_string(dir.join("history.csv")).is_ok_and(|t| {
        t.lines()
            .next()
            .is_some_and(|h| h.split(',').any(|c| c == "hypervolume"))
    })
}

/// The hypervolume of each generation in an NSGA-II output's `history.csv` (a chain's or a
/// lattice's study).
pub fn read_hypervolume(dir: &Path) -> Result<Vec<(usize, f64)>, Error> {
    let history = dir.join("history.csv");
    let bad = |reason: String| crate::atomic::read_error(&history, reason);
    let text = fs::read_to_string(&history).map_err(|e| bad(e.to_string()))?;
    let mut r = crate::table::csv_reader(text.as_bytes());
    let mut hypervolume = Vec::new();
    for rec in r.records() {
        let rec = rec.map_err(|e| bad(e.to_string()))?;
        let g = rec.get(0).and_then(|s| s.trim().parse::<usize>().ok());
        let h = rec.get(1).and_then(|s| s.trim().parse::<f64>().ok());
        match (g, h) {
            (Some(g), Some(h)) => hypervolume.push((g, h)),
            _ => return Err(bad(format!("not a generation and a hypervolume: {rec:?}"))),
        }
    }
    Ok(hypervolume)
}

/// Reads an NSGA-II output directory; one that has not finished (no `summary.json`) is refused
/// with what to do.
pub fn read_pareto_output(dir: &Path) -> Result<ParetoOutput, Error> {
    let path = dir.join("summary.json");
    if !path.is_file() {
        return Err(crate::atomic::read_error(
            &path,
            "missing: the NSGA-II run has not finished; its front is drawn once it stops (resume the study to finish it)",
        ));
    }
    let text = fs::read_to_string(&path).map_err(|e| Error::Read {
        path: path.clone(),
        source: e,
    })?;
    let summary: ParetoSummary = serde_json::from_str(&text).map_err(|e| Error::Parse {
        source_name: path.display().to_string(),
        message: e.to_string(),
    })?;
    let hypervolume = read_hypervolume(dir)?;
    Ok(ParetoOutput {
        summary,
        hypervolume,
        references: read_references(&dir.join("references.csv"))?,
    })
}
