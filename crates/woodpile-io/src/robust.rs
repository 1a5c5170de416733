//! `[ga] robust`: the breeder GA minimising a statistic of the transmitted force over the
//! scatter of the config's `[uncertainty]`. Every design is evaluated on the same draws (common
//! random numbers, [`crate::uncertainty::samples`]): its K sample scenarios are built from its
//! nominal scenario ([`crate::optimize::Problem::scenario`]), resolved and run together in SIMD
//! lanes, all designs × K runs in one [`woodpile::simulate_many`] call.
//!
//! For NSGA-II the same object is a [`FigureEvaluator`]: every figure of a run
//! (transmitted-force, transmission-ratio, transmitted-energy, transmitted-impulse,
//! max-contact-pressure) is the statistic of its K sample values, all designs × K runs
//! together ([`woodpile::optimize::run_figures_many`]); the simulation-free figures (total-mass,
//! stack-height, layers) are the nominal design's.

use crate::error::Error;
use crate::optimize_config::{scenario_of, OptimizeConfig};
use crate::scenario::{resolve, Scenario};
use crate::uncertainty::{samples, Samples, Uncertainty};
use std::path::PathBuf;
use woodpile::optimize::{run_figures_many, DesignFigure, DesignSpace, FigureEvaluator, Objective};
use woodpile::uncertainty::{cvar_of_sorted, quantile_of_sorted};
use woodpile::{Chain, Element, Excitation, Job, LaneWidth, RunSettings, RunSummary};

/// The statistic of `ga.robust`, over a design's K samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Robust {
    /// `mean`.
    Mean,
    /// `quantile:p`: the type-7 quantile at p ∈ (0, 1).
    Quantile(f64),
    /// `cvar:a`: the mean of the worst (largest) ⌈(1 − a) K⌉ samples, a ∈ (0, 1).
    Cvar(f64),
}

impl Robust {
    /// Parses `mean`, `quantile:p` or `cvar:a`; errors name `ga.robust`.
    pub fn parse(text: &str) -> Result<Self, Error> {
        let valid = "must be \"mean\", \"quantile:p\" or \"cvar:a\" with p, a in (0, 1), e.g. \"quantile:0.95\"";
        let level = |s: &str| {
            s.parse::<f64>()
                .ok()
                .filter(|p| *p > 0.0 && *p < 1.0)
                .ok_or_else(|| Error::invalid("ga.robust", text, valid))
        };
        match text.split_once(':') {
            None if text == "mean" => Ok(Robust::Mean),
            Some(("quantile", p)) => Ok(Robust::Quantile(level(p)?)),
            Some(("cvar", a)) => Ok(Robust::Cvar(level(a)?)),
            _ => Err(Error::invalid("ga.robust", text, valid)),
        }
    }

    /// The statistic of `values` (not empty).
    pub fn of(self, values: &[f64]) -> f64 {
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        match self {
            Robust::Mean => values.iter().sum::<f64>() / values.len() as f64,
            Robust::Quantile(p) => quantile_of_sorted(&sorted, p),
            Robust::Cvar(a) => cvar_of_sorted(&sorted, a),
        }
    }
}

/// The robust transmitted-force objective of a config: a design's value is [`Robust::of`] its
/// K samples' transmitted peak forces \[N\].
pub struct RobustObjective {
    /// The completed config (its scenario of a genome).
    pub config: OptimizeConfig,
    /// Where the config's files are found.
    pub base_dir: PathBuf,
    /// The catalogue as resolved elements, to read a chain's genome back.
    pub catalogue: Vec<Element>,
    /// The checked `[uncertainty]`.
    pub uncertainty: Uncertainty,
    /// The statistic.
    pub robust: Robust,
}

impl RobustObjective {
    /// The samples of a genome and their resolved runs' jobs' parts.
    pub fn samples(
        &self,
        genome: &[u8],
    ) -> Result<(Samples, Vec<crate::scenario::Resolved>), Error> {
        let scenario: Scenario = scenario_of(&self.config, &self.base_dir, genome, None);
        let drawn = samples(&scenario, &self.uncertainty)?;
        let resolved = drawn
            .samples
            .iter()
            .map(|s| resolve(&s.scenario, &self.base_dir))
            .collect::<Result<Vec<_>, _>>()?;
        Ok((drawn, resolved))
    }

    /// The genome of a chain built from the catalogue.
    fn genome(&self, chain: &Chain) -> Option<Vec<u8>> {
        chain
            .elements()
            .iter()
            .map(|e| {
                self.catalogue
                    .iter()
                    .position(|c| c == e)
                    .and_then(|i| u8::try_from(i).ok())
            })
            .collect()
    }
}

/// Runs every sample of every design in one [`woodpile::simulate_many`] call: per design, its
/// samples' runs.
pub fn run_samples(
    designs: &[&[crate::scenario::Resolved]],
    lanes: LaneWidth,
) -> Vec<woodpile::Result<Vec<RunSummary>>> {
    let jobs: Vec<Job<'_>> = designs
        .iter()
        .flat_map(|d| d.iter())
        .map(|r| Job {
            chain: &r.chain,
            excitation: &r.excitation,
            settings: &r.settings,
        })
        .collect();
    let mut runs = woodpile::simulate_many(&jobs, lanes).into_iter();
    designs
        .iter()
        .map(|d| runs.by_ref().take(d.len()).collect())
        .collect()
}

fn model_error(e: Error) -> woodpile::Error {
    woodpile::Error::InvalidParameter {
        field: "uncertainty".into(),
        value: "(a design's samples)".into(),
        reason: e.to_string(),
    }
}

impl Objective for RobustObjective {
    fn name(&self) -> &str {
        "transmitted-force"
    }

    fn unit(&self) -> &str {
        "N"
    }

    fn evaluate(&self, chain: &Chain, e: &Excitation, s: &RunSettings) -> woodpile::Result<f64> {
        let mut v = self.evaluate_many(std::slice::from_ref(chain), e, s, LaneWidth::detect());
        v.remove(0)
    }

    fn evaluate_many(
        &self,
        chains: &[Chain],
        _excitation: &Excitation,
        _settings: &RunSettings,
        lanes: LaneWidth,
    ) -> Vec<woodpile::Result<f64>> {
        let built: Vec<Result<Vec<crate::scenario::Resolved>, woodpile::Error>> = chains
            .iter()
            .map(|c| {
                let genome = self
                    .genome(c)
                    .ok_or_else(|| woodpile::Error::InvalidParameter {
                        field: "design".into(),
                        value: "(a chain)".into(),
                        reason: "an element not in the catalogue".into(),
                    })?;
                self.samples(&genome).map(|(_, r)| r).map_err(model_error)
            })
            .collect();
        let ok: Vec<&[crate::scenario::Resolved]> =
            built.iter().filter_map(|b| b.as_deref().ok()).collect();
        let mut runs = run_samples(&ok, lanes).into_iter();
        built
            .into_iter()
            .map(|b| {
                b?;
                let runs = runs.next().expect("one result per built design")?;
                let forces: Vec<f64> = runs.iter().map(|r| r.transmitted_peak_force_n).collect();
                Ok(self.robust.of(&forces))
            })
            .collect()
    }
}

impl RobustObjective {
    /// Each genome's samples and, per sample, the values of `figures` (NaN in the places of
    /// the simulation-free ones): every design × sample run together
    /// ([`run_figures_many`]). A design any of whose samples fails has that error.
    pub fn sample_figures(
        &self,
        figures: &[DesignFigure],
        genomes: &[&[u8]],
        lanes: LaneWidth,
    ) -> Vec<woodpile::Result<(Samples, Vec<Vec<f64>>)>> {
        let built: Vec<woodpile::Result<(Samples, Vec<crate::scenario::Resolved>)>> = genomes
            .iter()
            .map(|g| self.samples(g).map_err(model_error))
            .collect();
        let jobs: Vec<Job<'_>> = built
            .iter()
            .filter_map(|b| b.as_ref().ok())
            .flat_map(|(_, resolved)| resolved.iter())
            .map(|r| Job {
                chain: &r.chain,
                excitation: &r.excitation,
                settings: &r.settings,
            })
            .collect();
        let mut runs = run_figures_many(figures, &jobs, lanes).into_iter();
        built
            .iter()
            .map(|b| {
                let (drawn, resolved) = b.as_ref().map_err(Clone::clone)?;
                let values: Vec<woodpile::Result<Vec<f64>>> =
                    runs.by_ref().take(resolved.len()).collect();
                Ok((drawn.clone(), values.into_iter().collect::<Result<_, _>>()?))
            })
            .collect()
    }
}

/// The statistic of `values`, NaN where a sample's value is (a figure that means nothing).
fn statistic(robust: Robust, values: &[f64]) -> f64 {
    if values.iter().any(|v| v.is_nan()) {
        f64::NAN
    } else {
        robust.of(values)
    }
}

impl FigureEvaluator for RobustObjective {
    fn figures_many(
        &self,
        space: &DesignSpace,
        figures: &[DesignFigure],
        genomes: &[&[u8]],
        lanes: LaneWidth,
    ) -> Vec<woodpile::Result<Vec<f64>>> {
        let nominal: Vec<DesignFigure> =
            figures.iter().copied().filter(|f| !f.needs_run()).collect();
        let mut nominal_values =
            woodpile::optimize::figures_many(space, &nominal, genomes, &space.settings, lanes)
                .into_iter();
        self.sample_figures(figures, genomes, lanes)
            .into_iter()
            .map(|per_sample| {
                let nominal_values = nominal_values.next().expect("one per genome")?;
                let (_, runs) = per_sample?;
                let mut fixed = nominal_values.into_iter();
                Ok(figures
                    .iter()
                    .enumerate()
                    .map(|(j, f)| {
                        if f.needs_run() {
                            let values: Vec<f64> = runs.iter().map(|r| r[j]).collect();
                            statistic(self.robust, &values)
                        } else {
                            fixed.next().expect("a nominal value")
                        }
                    })
                    .collect())
            })
            .collect()
    }
}

/// The column of a figure in `robust/NNN.csv`: its name in snake case with its unit
/// (`transmitted_energy_j`, `max_contact_pressure_pa`).
pub fn figure_column(figure: DesignFigure) -> String {
    format!(
        "{}_{}",
        figure.as_str().replace('-', "_"),
        figure.unit().to_lowercase().replace(' ', "_")
    )
}

/// Writes `robust/NNN.csv` under `out` for each design of `genomes` (NNN from 001, in order):
/// each of its samples' drawn values and figures (the `samples.csv` of `woodpile simulate
/// --samples`), then a column per figure of `extra` that needs a run ([`figure_column`];
/// the transmitted force and the ratio are among the first), its samples run again together
/// as in the study. Files `robust/NNN.csv` beyond the count, left by an earlier stop, are
/// removed.
pub fn write_robust_csvs(
    out: &std::path::Path,
    objective: &RobustObjective,
    genomes: &[&[u8]],
    extra: &[DesignFigure],
) -> Result<(), Error> {
    let dir = out.join("robust");
    std::fs::create_dir_all(&dir).map_err(crate::atomic::io_err(&dir))?;
    crate::atomic::remove_stale(&dir, genomes.len(), "csv")?;
    let extra: Vec<DesignFigure> = extra
        .iter()
        .copied()
        .filter(|f| {
            f.needs_run()
                && !matches!(
                    f,
                    DesignFigure::Run(
                        woodpile::StandardObjective::TransmittedForce
                            | woodpile::StandardObjective::TransmissionRatio
                    )
                )
        })
        .collect();
    let drawn: Vec<(Samples, Vec<crate::scenario::Resolved>)> = genomes
        .iter()
        .map(|g| objective.samples(g))
        .collect::<Result<_, _>>()?;
    let designs: Vec<&[crate::scenario::Resolved]> =
        drawn.iter().map(|(_, r)| r.as_slice()).collect();
    let runs = run_samples(&designs, LaneWidth::detect());
    let extras = if extra.is_empty() {
        genomes.iter().map(|_| Ok(None)).collect()
    } else {
        objective
            .sample_figures(&extra, genomes, LaneWidth::detect())
            .into_iter()
            .map(|r| r.map(|(_, v)| Some(v)))
            .collect::<Vec<_>>()
    };
    for (k, (((samples, _), runs), extras)) in drawn.iter().zip(runs).zip(extras).enumerate() {
        let runs = runs.map_err(Error::Model)?;
        let mut csv = crate::uncertainty::samples_csv(samples, &runs);
        if let Some(values) = extras.map_err(Error::Model)? {
            csv = append_columns(&csv, &extra, &values);
        }
        crate::atomic::write_atomic(&dir, &format!("{:03}.csv", k + 1), csv.as_bytes())?;
    }
    Ok(())
}

/// `csv` with a column per figure appended: its header, then `values[row][figure]`.
fn append_columns(csv: &str, figures: &[DesignFigure], values: &[Vec<f64>]) -> String {
    let mut text = String::with_capacity(csv.len() * 2);
    for (row, line) in csv.lines().enumerate() {
        text += line;
        for (j, f) in figures.iter().enumerate() {
            text += ",";
            if row == 0 {
                text += &figure_column(*f);
            } else if values[row - 1][j].is_finite() {
                text += &format!("{:e}", values[row - 1][j]);
            }
        }
        text.push('\n');
    }
    text
}

/// Writes `robust/001.csv` under `out` for the breeder's best design `genome`.
pub fn write_robust_csv(
    out: &std::path::Path,
    objective: &RobustObjective,
    genome: &[u8],
) -> Result<(), Error> {
    write_robust_csvs(out, objective, &[genome], &[])
}
