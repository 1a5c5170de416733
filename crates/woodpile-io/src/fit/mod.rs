//! The fit file (`woodpile fit FIT.toml`, docs/fit.md): a scenario, measured CSV files whose
//! columns are mapped to model outputs, and the parameters to fit; the setup it becomes
//! ([`FitSetup`]: the core's [`woodpile::fit::Problem`] pieces and the model as a function of the
//! parameter values), and the outputs of a fit (`fit.json`, `fitted.toml`, `residuals.csv`).
//!
//! ```toml
//! scenario = "chain.toml"                    # relative to this file
//! [[data]]
//! file = "measured.csv"                      # time_s plus signal columns
//! signals = { sensor_n = "contact_20_n" }    # column -> contact_N_n, element_K_m_s, element_K_m, striker_m_s
//! weights = { sensor_n = 1.0 }               # optional, default 1 (residuals are divided by the signal's peak)
//! sensor_cutoff_hz = 50e3                    # optional: first-order low-pass of the sensor
//! [fit]
//! parameters = [
//!   { key = "damping.restitution", bounds = [0.6, 1.0] },
//!   { key = "contact_beta_scale.wall", bounds = [0.5, 2.0], log = true },
//!   { key = "excitation.velocity_m_s", bounds = [1.5, 2.5], initial = 2.0 },
//!   { key = "youngs_modulus_scale.stainless-steel", bounds = [0.8, 1.2] },
//! ]
//! time_shift_s = { bounds = [-1e-5, 1e-5] }  # measured(t) = model(t - time_shift_s); omit: 0
//! window_s = [0.0, 4e-4]                     # optional: only rows in this window are fitted
//! starts = 8
//! ```

mod data;
mod keys;
mod output;

pub use data::{read_signals, SIGNAL_FLOOR};
pub use keys::{Scale, Target, MODULUS_PREFIX, SCALE_PREFIX};
pub use output::{check_output, fit_json, residuals_csv, write_outputs, FIT_MARKER};

use crate::error::Error;
use crate::scenario::{resolve, Scenario};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use woodpile::fit::{Built, Measurement, Output, Parameter, Problem};

/// The fit file as written.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitConfig {
    /// The model: a scenario file relative to the fit file, or a built-in scenario's name.
    pub scenario: String,
    /// The measured files.
    pub data: Vec<DataSpec>,
    /// What to fit and how.
    pub fit: FitSpec,
}

/// One `[[data]]` entry.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DataSpec {
    /// The CSV file, relative to the fit file: `time_s` and signal columns.
    pub file: String,
    /// CSV column → model output (`contact_N_n`, `element_K_m_s`, `element_K_m`, `striker_m_s`).
    pub signals: BTreeMap<String, String>,
    /// CSV column → relative weight (default 1).
    #[serde(default)]
    pub weights: BTreeMap<String, f64>,
    /// Cutoff of the sensors' first-order low-pass \[Hz\] (none: no filter).
    pub sensor_cutoff_hz: Option<f64>,
}

/// The `[fit]` table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitSpec {
    /// The fitted parameters.
    pub parameters: Vec<ParameterSpec>,
    /// The fitted trigger offset \[s\]; none: fixed at 0.
    pub time_shift_s: Option<ShiftSpec>,
    /// Only rows with t in this window \[s\] are fitted (default: every row).
    pub window_s: Option<[f64; 2]>,
    /// Number of starts (default [`woodpile::defaults::FIT_STARTS`]).
    pub starts: Option<usize>,
    /// Most model runs of one start's residuals (default
    /// [`woodpile::defaults::FIT_MAX_EVALUATIONS`]).
    pub max_evaluations: Option<usize>,
    /// Seed of the Sobol' scrambling of the starts (default 0).
    pub seed: Option<u32>,
}

/// One entry of `fit.parameters`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterSpec {
    /// A float key of the scenario (`damping.restitution`, `chain.elements[2].diameter_mm`), a
    /// contact scale (`contact_beta_scale.striker`, `.inner`, `.wall`) or a material's modulus
    /// scale (`youngs_modulus_scale.stainless-steel`).
    pub key: String,
    /// `[lower, upper]`; none: unbounded.
    pub bounds: Option<[f64; 2]>,
    /// The first start's value (default: the scenario's value, or the middle of the bounds).
    pub initial: Option<f64>,
    /// Fit ln of the value (default false).
    #[serde(default)]
    pub log: bool,
}

/// `fit.time_shift_s`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShiftSpec {
    /// `[lower, upper]` \[s\].
    pub bounds: Option<[f64; 2]>,
    /// The first start's value \[s\] (default 0, or the middle of the bounds if 0 is outside).
    pub initial: Option<f64>,
}

/// What a fit file becomes: the pieces of the core's problem and the model function.
#[derive(Debug, Clone)]
pub struct FitSetup {
    /// The fit file.
    pub path: PathBuf,
    /// The scenario as read (before any fitted value is applied).
    pub scenario: Scenario,
    /// The directory the scenario's own files are relative to.
    pub scenario_dir: PathBuf,
    /// The model's parameters (the time shift is [`FitSetup::time_shift_s`]).
    pub parameters: Vec<Parameter>,
    /// How each parameter is applied to the scenario, in the same order.
    pub targets: Vec<Target>,
    /// The fitted time shift.
    pub time_shift_s: Option<Parameter>,
    /// The measured signals.
    pub measurements: Vec<Measurement>,
    /// Per measurement: its file (as written in the fit file) and column.
    pub sources: Vec<(String, String)>,
    /// Per measurement: the index of its `[[data]]` entry.
    pub data_of: Vec<usize>,
    /// The window.
    pub window_s: Option<(f64, f64)>,
    /// Number of starts.
    pub starts: usize,
    /// Most residual evaluations of one start.
    pub max_evaluations: usize,
    /// Seed of the starts.
    pub seed: u32,
}

impl FitConfig {
    /// Parses a fit file's text (`source_name` names it in errors).
    pub fn parse(text: &str, source_name: &str) -> Result<Self, Error> {
        toml::from_str(text).map_err(|e| Error::Parse {
            source_name: source_name.into(),
            message: e.to_string(),
        })
    }
}

/// Reads a fit file and everything it names, checking every key, column and row.
pub fn load(path: &Path) -> Result<FitSetup, Error> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::Read {
        path: path.to_path_buf(),
        source: e,
    })?;
    let config = FitConfig::parse(&text, &path.display().to_string())?;
    let base = path.parent().unwrap_or(Path::new("")).to_path_buf();
    setup(&config, path, &base)
}

/// The setup of a parsed fit file whose relative paths are relative to `base`.
pub fn setup(config: &FitConfig, path: &Path, base: &Path) -> Result<FitSetup, Error> {
    let (scenario, scenario_dir) = load_scenario(&config.scenario, base)?;
    let resolved = resolve(&scenario, &scenario_dir)?;
    let window_s = window(config.fit.window_s)?;
    let mut measurements = Vec::new();
    let mut sources = Vec::new();
    let mut data_of = Vec::new();
    for (i, spec) in config.data.iter().enumerate() {
        let signals = data::measurements(spec, i, base, window_s, &resolved)?;
        for m in signals {
            sources.push((spec.file.clone(), m.label.clone()));
            data_of.push(i);
            measurements.push(m);
        }
    }
    if measurements.is_empty() {
        return Err(Error::invalid(
            "data",
            "(no signals)",
            "give at least one [[data]] entry with signals = { column = \"contact_N_n\" }",
        ));
    }
    if config.fit.parameters.is_empty() && config.fit.time_shift_s.is_none() {
        return Err(Error::invalid(
            "fit.parameters",
            "[]",
            "at least one parameter to fit (or fit.time_shift_s), e.g. { key = \"excitation.velocity_m_s\", bounds = [1.5, 2.5] }",
        ));
    }
    let mut parameters = Vec::new();
    let mut targets = Vec::new();
    for (i, spec) in config.fit.parameters.iter().enumerate() {
        let field = format!("fit.parameters[{i}]");
        if let Some(j) = config.fit.parameters[..i]
            .iter()
            .position(|p| p.key == spec.key)
        {
            return Err(Error::invalid(
                format!("{field}.key"),
                &spec.key,
                format!("fit.parameters[{j}] fits this key already: a key fitted twice has no one value"),
            ));
        }
        let target = keys::Target::parse(&spec.key, &format!("{field}.key"))?;
        let current = target.current(&scenario);
        parameters.push(parameter(spec, &field, current)?);
        targets.push(target);
    }
    let time_shift_s = config
        .fit
        .time_shift_s
        .as_ref()
        .map(shift_parameter)
        .transpose()?;
    check_duration(
        &resolved.settings,
        &measurements,
        time_shift_s.as_ref(),
        &config.data,
    )?;
    let starts = config.fit.starts.unwrap_or(woodpile::defaults::FIT_STARTS);
    if starts == 0 {
        return Err(Error::invalid("fit.starts", 0, "must be at least 1"));
    }
    let max_evaluations = config
        .fit
        .max_evaluations
        .unwrap_or(woodpile::defaults::FIT_MAX_EVALUATIONS);
    if max_evaluations == 0 {
        return Err(Error::invalid(
            "fit.max_evaluations",
            0,
            "at least 1 model run per start (default 200): with none, no start would move from its initial values",
        ));
    }
    Ok(FitSetup {
        path: path.to_path_buf(),
        scenario,
        scenario_dir,
        parameters,
        targets,
        time_shift_s,
        measurements,
        sources,
        data_of,
        window_s,
        starts,
        max_evaluations,
        seed: config.fit.seed.unwrap_or(0),
    })
}

/// Refuses a fit whose model runs would exceed [`crate::limits::MAX_STEPS`] steps: each run
/// lasts from the earliest allowed shift to the last measured time (seconds of record at a
/// 0.1 µs step are 1e7 steps per run, and a fit makes hundreds of runs). Names the time shift's
/// bounds when they make most of it, else the data.
fn check_duration(
    settings: &woodpile::RunSettings,
    measurements: &[Measurement],
    shift: Option<&Parameter>,
    data: &[DataSpec],
) -> Result<(), Error> {
    let last = measurements
        .iter()
        .filter_map(|m| m.times_s.last().copied())
        .fold(0.0_f64, f64::max);
    let earliest = shift.map_or(0.0, |p| p.bounds.map_or(p.initial, |b| b.0).min(0.0));
    let mut run = *settings;
    run.duration_s = last - earliest;
    let Some(steps) = run.estimated_steps() else {
        return Ok(());
    };
    if steps <= crate::limits::MAX_STEPS {
        return Ok(());
    }
    let (field, value) = match shift.and_then(|p| p.bounds) {
        Some((lo, hi)) if -earliest > last => (
            "fit.time_shift_s.bounds".to_string(),
            format!("[{lo}, {hi}]"),
        ),
        _ => {
            let files: Vec<&str> = data.iter().map(|d| d.file.as_str()).collect();
            (
                "data".to_string(),
                format!("{} (time_s up to {last:e} s)", files.join(", ")),
            )
        }
    };
    Err(Error::invalid(
        field,
        value,
        format!(
            "each model run would last {:.4e} s (from the earliest shift to the last measured time): {steps:.3e} steps, more than {:.0e}, at the scenario's step; fit a record of at most {:.3e} s, with shifts as small",
            run.duration_s,
            crate::limits::MAX_STEPS as f64,
            crate::limits::MAX_STEPS as f64 * run.duration_s / steps as f64
        ),
    ))
}

/// The scenario named by the fit file: a file relative to `base`, else a built-in name.
fn load_scenario(name: &str, base: &Path) -> Result<(Scenario, PathBuf), Error> {
    let path = base.join(name);
    if path.is_file() {
        let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
        return Ok((Scenario::load(&path)?, dir));
    }
    match crate::scenario::builtin(name) {
        Some(s) => Ok((s, base.to_path_buf())),
        None => Err(Error::invalid(
            "scenario",
            name,
            format!(
                "no such file ({}) and not a built-in scenario",
                path.display()
            ),
        )),
    }
}

fn window(w: Option<[f64; 2]>) -> Result<Option<(f64, f64)>, Error> {
    match w {
        Some([a, b]) if !(a.is_finite() && b.is_finite() && a < b) => Err(Error::invalid(
            "fit.window_s",
            format!("[{a}, {b}]"),
            "must be two finite times [s], start < end",
        )),
        Some([a, b]) => Ok(Some((a, b))),
        None => Ok(None),
    }
}

/// Checks bounds as written: two finite numbers, lower < upper; `field` names the entry.
fn bounds(field: &str, b: Option<[f64; 2]>) -> Result<Option<(f64, f64)>, Error> {
    match b {
        Some([lo, hi]) if !(lo.is_finite() && hi.is_finite() && lo < hi) => Err(Error::invalid(
            format!("{field}.bounds"),
            format!("[{lo}, {hi}]"),
            "must be [lower, upper], two finite numbers with lower < upper",
        )),
        Some([lo, hi]) => Ok(Some((lo, hi))),
        None => Ok(None),
    }
}

/// A parameter from its entry; the default initial value is the scenario's (`current`) when
/// within the bounds, else the bounds' middle.
fn parameter(spec: &ParameterSpec, field: &str, current: Option<f64>) -> Result<Parameter, Error> {
    let b = bounds(field, spec.bounds)?;
    let middle = b.map(|(lo, hi)| {
        if spec.log && lo > 0.0 {
            (lo * hi).sqrt()
        } else {
            0.5 * (lo + hi)
        }
    });
    let inside = |v: f64| b.is_none_or(|(lo, hi)| (lo..=hi).contains(&v));
    let initial = match (spec.initial, current, middle) {
        (Some(v), _, _) => v,
        (None, Some(v), _) if inside(v) => v,
        (None, _, Some(m)) => m,
        (None, _, None) => {
            return Err(Error::invalid(
                format!("{field}.initial"),
                "(missing)",
                format!(
                "{} has no value in the scenario and no bounds: give an initial value or bounds",
                spec.key
            ),
            ))
        }
    };
    let p = Parameter {
        name: spec.key.clone(),
        initial,
        bounds: b,
        log_scale: spec.log,
    };
    p.validate().map_err(|e| rename(e, &spec.key, field))?;
    Ok(p)
}

/// A core validation error names the parameter by its key; in the file it is `field`.
fn rename(e: woodpile::Error, key: &str, field: &str) -> Error {
    match e {
        woodpile::Error::InvalidParameter {
            field: f,
            value,
            reason,
        } => Error::Invalid {
            field: f.replacen(key, field, 1),
            value,
            reason,
        },
        other => Error::Model(other),
    }
}

fn shift_parameter(spec: &ShiftSpec) -> Result<Parameter, Error> {
    let field = "fit.time_shift_s";
    let b = bounds(field, spec.bounds)?;
    let initial = spec.initial.unwrap_or(match b {
        Some((lo, hi)) if !(lo..=hi).contains(&0.0) => 0.5 * (lo + hi),
        _ => 0.0,
    });
    let p = Parameter {
        name: "time_shift_s".into(),
        initial,
        bounds: b,
        log_scale: false,
    };
    p.validate().map_err(|e| rename(e, "time_shift_s", field))?;
    Ok(p)
}

impl FitSetup {
    /// The scenario with the model's parameter values applied (the scales as explicit β).
    pub fn scenario_at(&self, values: &[f64]) -> Result<Scenario, Error> {
        keys::apply(&self.scenario, &self.scenario_dir, &self.targets, values)
    }

    /// The run the model's parameter values give.
    pub fn build(&self, values: &[f64]) -> Result<Built, Error> {
        let scenario = self.scenario_at(values)?;
        let r = resolve(&scenario, &self.scenario_dir)?;
        Ok(Built {
            chain: r.chain,
            excitation: r.excitation,
            settings: r.settings,
        })
    }

    /// [`FitSetup::build`] with the error as the core's (its key, value and reason kept).
    pub fn model(&self, values: &[f64]) -> woodpile::Result<Built> {
        self.build(values).map_err(|e| match e {
            Error::Model(e) => e,
            e => woodpile::Error::invalid(
                e.field().unwrap_or("scenario"),
                e.value().unwrap_or_default(),
                e.reason(),
            ),
        })
    }

    /// The core's problem over `model` (pass `&|v| setup.model(v)`).
    pub fn problem<'a>(&self, model: &'a woodpile::fit::ModelFn<'a>) -> Problem<'a> {
        Problem {
            parameters: self.parameters.clone(),
            time_shift_s: self.time_shift_s.clone(),
            measurements: self.measurements.clone(),
            window_s: self.window_s,
            model,
        }
    }

    /// Refuses a measured signal whose peak is below [`SIGNAL_FLOOR`] of the model's
    /// peak of the same output at the initial values (one run of the scenario): rounding noise,
    /// or a signal in another unit, which carries nothing to fit, as an all-zero signal. A model
    /// that does not run at the initial values is left to the fit, which reports it.
    pub fn check_signals(&self) -> Result<(), Error> {
        let initial: Vec<f64> = self.parameters.iter().map(|p| p.initial).collect();
        let Ok(built) = self.build(&initial) else {
            return Ok(());
        };
        let Some(peaks) = data::model_peaks(&built, &self.outputs()) else {
            return Ok(());
        };
        for (k, (m, model)) in self.measurements.iter().zip(peaks).enumerate() {
            if model > 0.0 && m.scale < data::SIGNAL_FLOOR * model {
                let (file, column) = &self.sources[k];
                return Err(Error::invalid(
                    format!("data[{}].signals.{column}", self.data_of[k]),
                    format!("{file} (peak {:.3e} {})", m.scale, m.output.unit()),
                    format!(
                        "below {:e} of the model's peak of {} at the initial values ({model:.3e} {}): rounding noise, or a signal in another unit, which carries no information to fit; give the signal in {}",
                        data::SIGNAL_FLOOR,
                        m.output.name(),
                        m.output.unit(),
                        m.output.unit()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The model outputs the measurements map to.
    pub fn outputs(&self) -> Vec<Output> {
        self.measurements.iter().map(|m| m.output).collect()
    }
}
