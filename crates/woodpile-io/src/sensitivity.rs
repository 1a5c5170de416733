//! A sensitivity study's files: a scenario's `[uncertainty]` on a Saltelli design, and the
//! Sobol' indices of its figures of merit (`woodpile::sensitivity`).
//!
//! The parameters of the indices are the `[uncertainty]` keys, in the file's order; a key that
//! draws several values (`rod_length_mm`: one per rod, `crossing_angle_deg`: one per contact) is
//! one group, as SALib's `groups`. The output directory holds `samples.csv` (the Saltelli matrix
//! in SALib's row order, one column per drawn value, named as `simulate --samples` names them),
//! `outputs.csv` (one column per figure of [`crate::uncertainty::FIGURES`], same rows),
//! `indices.csv` (`parameter, figure, S1, S1_conf, ST, ST_conf`) and `summary.json`, written
//! last.

use crate::error::Error;
use crate::uncertainty::{figures, samples_at, Samples, Uncertainty, FIGURES};
use woodpile::sensitivity::{indices, saltelli_unit_cube, Bootstrap, Indices};

/// The files of a sensitivity directory; `summary.json`, written last, marks it complete.
pub const FILES: &[&str] = &["samples.csv", "outputs.csv", "indices.csv", "summary.json"];
/// The file that marks a complete sensitivity directory.
pub const MARKER: &str = "summary.json";

/// The fewest base samples of a study: below, the bootstrap resamples so few distinct points
/// that its intervals mean nothing (at N = 1 every resample is the one point, and an index of
/// 1.4 comes out as ± 1e-15), and an index is an estimate from a handful of runs.
pub const MIN_BASE_SAMPLES: usize = 8;

/// Why `base_samples` cannot be a study's N, or None when it can: at least
/// [`MIN_BASE_SAMPLES`], and a power of two (the balance of the Sobol' points, hence the
/// estimators' convergence, holds for powers of two; SALib only warns).
pub fn base_samples_refusal(base_samples: usize) -> Option<String> {
    if base_samples < MIN_BASE_SAMPLES {
        return Some(format!(
            "at least {MIN_BASE_SAMPLES}, a power of two (e.g. {MIN_BASE_SAMPLES}, 64): with fewer the bootstrap resamples so few distinct points that the indices' intervals mean nothing"
        ));
    }
    (!base_samples.is_power_of_two()).then(|| {
        let below = if base_samples < 2 {
            1
        } else {
            1usize << (usize::BITS - 1 - base_samples.leading_zeros())
        };
        format!(
            "a power of two of at least 1 (the Sobol' points are balanced only then), e.g. {below} or {}",
            below * 2
        )
    })
}

/// The scenario as a design study runs it: unless `paper_settings` or the scenario states how to
/// integrate (`run.peak_tolerance`, `integrator`, `time_step_s`, `rtol`, `atol`), every contact
/// peak within [`woodpile::defaults::STUDY_PEAK_TOLERANCE`]. Returns the words for how it is run,
/// and whether that default was applied.
pub fn accuracy_targeted(
    scenario: &mut crate::scenario::Scenario,
    paper_settings: bool,
) -> (String, bool) {
    let r = &mut scenario.run;
    let stated = r.peak_tolerance.is_some()
        || r.integrator.is_some()
        || r.time_step_s.is_some()
        || r.rtol.is_some()
        || r.atol.is_some();
    let applied = !paper_settings && !stated;
    if applied {
        r.peak_tolerance = Some(woodpile::defaults::STUDY_PEAK_TOLERANCE);
    }
    let text = r.accuracy_text();
    (text, applied)
}

/// A scenario's Saltelli design: the parameters (groups), and each row's scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// N, the base samples.
    pub base_samples: usize,
    /// Seed of the Sobol' points (`[uncertainty] seed`).
    pub seed: u32,
    /// The `[uncertainty]` keys, in the file's order: the parameters of the indices.
    pub parameters: Vec<String>,
    /// The group (index into `parameters`) of each drawn value, i.e. each column.
    pub group_of: Vec<usize>,
    /// The N·(G + 2) rows: drawn values and complete scenarios.
    pub samples: Samples,
}

/// The Saltelli design of `scenario` under its checked `[uncertainty]` `u` with `base_samples`
/// base points, named `field` as the front end spells it (refused as [`base_samples_refusal`]
/// says). A design of more than [`crate::limits::MAX_GENERATION_ELEMENTS`] elements in all
/// (rows × chain elements: every row's scenario is built before the runs) is refused unless
/// `allow_large`.
pub fn design(
    scenario: &crate::scenario::Scenario,
    u: &Uncertainty,
    (field, base_samples): (&str, usize),
    allow_large: bool,
) -> Result<Design, Error> {
    if let Some(reason) = base_samples_refusal(base_samples) {
        return Err(Error::invalid(field, base_samples, reason));
    }
    if u.parameters.is_empty() {
        return Err(Error::invalid(
            "uncertainty",
            "{}",
            "at least one scattered parameter (e.g. impact_velocity_m_s = { uniform = [1.8, 2.2] })",
        ));
    }
    let parameters: Vec<String> = u.parameters.iter().map(|(p, _)| p.key().into()).collect();
    let mut group_of = Vec::new();
    // A pass with no rows names the drawn values (and checks the keys apply to the scenario).
    let samples = samples_at(scenario, u, |_| Ok(Vec::new()))?;
    for key in samples.column_keys() {
        let g = parameters.iter().position(|p| p == key).unwrap_or(0);
        group_of.push(g);
    }
    // A key that draws no value (crossing angles of a one-element chain) has no group.
    if let Some(unused) = (0..parameters.len()).find(|g| !group_of.contains(g)) {
        return Err(Error::invalid(
            format!("uncertainty.{}", parameters[unused]),
            "{…}",
            "draws no value in this scenario (e.g. crossing angles of a one-element chain): remove it",
        ));
    }
    let elements = crate::uncertainty::chain_elements(scenario);
    let runs = base_samples.saturating_mul(parameters.len() + 2);
    crate::limits::check_study(
        field,
        &format!(
            "{base_samples} × ({} parameter{} + 2) = {}",
            parameters.len(),
            if parameters.len() == 1 { "" } else { "s" },
            crate::limits::count(runs)
        ),
        runs,
        elements,
        allow_large,
    )?;
    let rows = saltelli_unit_cube(base_samples, &group_of, u.seed)
        .map_err(|e| Error::invalid("uncertainty", group_of.len(), e.to_string()))?;
    let samples = samples_at(scenario, u, move |_| Ok(rows))?;
    Ok(Design {
        base_samples,
        seed: u.seed,
        parameters,
        group_of,
        samples,
    })
}

/// One figure's indices, or why it has none.
#[derive(Debug, Clone, PartialEq)]
pub enum FigureIndices {
    /// One [`Indices`] per parameter of the design.
    Indices(Vec<Indices>),
    /// Why the figure has no indices (a run without it, or outputs that do not vary).
    Meaningless(String),
}

/// The indices of every figure of [`FIGURES`] from the design's runs (`runs[r]` row r's run).
pub fn figure_indices(
    d: &Design,
    runs: &[woodpile::RunSummary],
    bootstrap: &Bootstrap,
) -> Vec<(&'static str, FigureIndices)> {
    FIGURES
        .iter()
        .enumerate()
        .map(|(j, &name)| {
            let values: Option<Vec<f64>> = runs.iter().map(|r| figures(r)[j]).collect();
            let result = match values {
                None => FigureIndices::Meaningless(format!(
                    "not every one of the {} runs has this figure (the wave did not reach the wall within the run): lengthen run.duration_s",
                    runs.len()
                )),
                Some(y) => match indices(&y, d.base_samples, d.parameters.len(), bootstrap) {
                    Ok(s) => FigureIndices::Indices(s),
                    Err(e) => FigureIndices::Meaningless(e.to_string()),
                },
            };
            (name, result)
        })
        .collect()
}

fn cell(x: Option<f64>) -> String {
    x.map(|v| format!("{v:e}")).unwrap_or_default()
}

/// The text of `samples.csv`: one column per drawn value, one row per design row.
pub fn samples_csv(d: &Design) -> String {
    let mut csv = d.samples.columns.join(",");
    csv.push('\n');
    for s in &d.samples.samples {
        let row: Vec<String> = s.values.iter().map(|&v| cell(Some(v))).collect();
        csv += &row.join(",");
        csv.push('\n');
    }
    csv
}

/// The text of `outputs.csv`: one column per figure (an empty cell where it means nothing).
pub fn outputs_csv(runs: &[woodpile::RunSummary]) -> String {
    let mut csv = FIGURES.join(",");
    csv.push('\n');
    for r in runs {
        let row: Vec<String> = figures(r).into_iter().map(cell).collect();
        csv += &row.join(",");
        csv.push('\n');
    }
    csv
}

/// The text of `indices.csv`: `parameter, figure, S1, S1_conf, ST, ST_conf`, figure by figure;
/// a figure without indices has no rows (summary.json says why).
pub fn indices_csv(d: &Design, per_figure: &[(&'static str, FigureIndices)]) -> String {
    let mut csv = String::from("parameter,figure,S1,S1_conf,ST,ST_conf\n");
    for (figure, result) in per_figure {
        if let FigureIndices::Indices(s) = result {
            for (p, i) in d.parameters.iter().zip(s) {
                csv += &format!(
                    "{p},{figure},{:e},{:e},{:e},{:e}\n",
                    i.first_order, i.first_order_conf, i.total, i.total_conf
                );
            }
        }
    }
    csv
}

/// Writes a sensitivity study into `dir` (the files of [`FILES`], summary.json last);
/// `accuracy` states how the runs were integrated.
pub fn write(
    dir: &std::path::Path,
    d: &Design,
    runs: &[woodpile::RunSummary],
    bootstrap: &Bootstrap,
    per_figure: &[(&'static str, FigureIndices)],
    accuracy: &str,
) -> Result<(), Error> {
    use crate::atomic::write_atomic;
    write_atomic(dir, "samples.csv", samples_csv(d).as_bytes())?;
    write_atomic(dir, "outputs.csv", outputs_csv(runs).as_bytes())?;
    write_atomic(dir, "indices.csv", indices_csv(d, per_figure).as_bytes())?;
    let mut figures = serde_json::Map::new();
    for (name, result) in per_figure {
        let value = match result {
            FigureIndices::Indices(s) => serde_json::Value::Object(
                d.parameters
                    .iter()
                    .zip(s)
                    .map(|(p, i)| {
                        (
                            p.clone(),
                            serde_json::json!({
                                "S1": i.first_order, "S1_conf": i.first_order_conf,
                                "ST": i.total, "ST_conf": i.total_conf,
                            }),
                        )
                    })
                    .collect(),
            ),
            FigureIndices::Meaningless(reason) => {
                serde_json::json!({ "value": null, "reason": reason })
            }
        };
        figures.insert(name.to_string(), value);
    }
    let groups: serde_json::Map<String, serde_json::Value> = d
        .parameters
        .iter()
        .enumerate()
        .map(|(g, p)| {
            let columns: Vec<&String> = d
                .samples
                .columns
                .iter()
                .zip(&d.group_of)
                .filter(|(_, &h)| h == g)
                .map(|(c, _)| c)
                .collect();
            (p.clone(), serde_json::json!(columns))
        })
        .collect();
    let summary = serde_json::json!({
        "woodpile_version": crate::VERSION,
        "base_samples": d.base_samples,
        "rows": d.samples.samples.len(),
        "seed": d.seed,
        "layout": "SALib sobol.sample, calc_second_order=False: per base sample the rows A, AB_1..AB_G (A with parameter g's columns from B), B; a parameter's columns are one group",
        "draws": "Owen-scrambled Sobol' points (sobol_burley) of dimension 2D (A: the first D coordinates, B: the last D); normals by Acklam's inverse CDF",
        "estimators": "SALib sobol.analyze: outputs normalised to zero mean and unit variance; S1 Saltelli 2010, ST Jansen 1999, variance of [f_A, f_B]",
        "bootstrap": { "resamples": bootstrap.resamples, "confidence_level": bootstrap.level, "seed": bootstrap.seed },
        "accuracy": accuracy,
        "parameters": groups,
        "figures": figures,
    });
    let text = serde_json::to_string_pretty(&summary)
        .map_err(|e| Error::invalid("summary.json", "", e.to_string()))?;
    write_atomic(dir, "summary.json", text.as_bytes())
}

/// One row of `indices.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct IndexRow {
    /// The `[uncertainty]` key.
    pub parameter: String,
    /// The figure of merit.
    pub figure: String,
    /// First-order index.
    pub s1: f64,
    /// Half-width of its confidence interval.
    pub s1_conf: f64,
    /// Total index.
    pub st: f64,
    /// Half-width of its confidence interval.
    pub st_conf: f64,
}

/// Reads `dir/indices.csv` back.
pub fn read_indices(dir: &std::path::Path) -> Result<Vec<IndexRow>, Error> {
    let path = dir.join("indices.csv");
    let text = std::fs::read_to_string(&path).map_err(crate::atomic::io_err(&path))?;
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default();
    if header != "parameter,figure,S1,S1_conf,ST,ST_conf" {
        return Err(Error::invalid(
            format!("{}", path.display()),
            header,
            "the header parameter,figure,S1,S1_conf,ST,ST_conf",
        ));
    }
    lines
        .enumerate()
        .map(|(i, line)| {
            let cells: Vec<&str> = line.split(',').collect();
            let number = |k: usize| {
                cells
                    .get(k)
                    .and_then(|c| c.parse::<f64>().ok())
                    .ok_or_else(|| {
                        Error::invalid(
                            format!("{} line {}", path.display(), i + 2),
                            line,
                            "a parameter, a figure and four numbers",
                        )
                    })
            };
            Ok(IndexRow {
                parameter: cells[0].to_string(),
                figure: cells.get(1).copied().unwrap_or_default().to_string(),
                s1: number(2)?,
                s1_conf: number(3)?,
                st: number(4)?,
                st_conf: number(5)?,
            })
        })
        .collect()
}
