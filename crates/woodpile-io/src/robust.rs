//! `[ga] robust`: the breeder GA minimising a statistic of the transmitted force over the
//! scatter of the config's `[uncertainty]`. Every design is evaluated on the same draws (common
//! random numbers, [`crate::uncertainty::samples`]): its K sample scenarios are built from its
//! nominal scenario ([`crate::optimize::Problem::scenario`]), resolved and run together in SIMD
//! lanes, all designs × K runs in one [`woodpile::simulate_many`] call.

use crate::error::Error;
use crate::optimize::OptimizeConfig;
use crate::scenario::{resolve, Scenario};
use crate::uncertainty::{samples, Samples, Uncertainty};
use std::path::PathBuf;
use woodpile::optimize::Objective;
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
        let scenario: Scenario =
            crate::optimize::scenario_of(&self.config, &self.base_dir, genome, None);
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

/// Writes `robust/001.csv` under `out` for the design `genome`: each of its samples' drawn
/// values and figures (the `samples.csv` of `woodpile simulate --samples`), its samples run
/// again together as in the GA.
pub fn write_robust_csv(
    out: &std::path::Path,
    objective: &RobustObjective,
    genome: &[u8],
) -> Result<(), Error> {
    let dir = out.join("robust");
    std::fs::create_dir_all(&dir).map_err(crate::atomic::io_err(&dir))?;
    let (drawn, resolved) = objective.samples(genome)?;
    let runs = run_samples(&[&resolved], LaneWidth::detect())
        .remove(0)
        .map_err(Error::Model)?;
    let csv = crate::uncertainty::samples_csv(&drawn, &runs);
    crate::atomic::write_atomic(&dir, "001.csv", csv.as_bytes())
}
