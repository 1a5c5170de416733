//! Calibration: the parameters of a model that best explain measured signals, with their
//! uncertainties (docs/fit.md).
//!
//! A [`Problem`] is a set of [`Measurement`]s (a time grid and values, each mapped to a model
//! [`Output`]: a contact force, an element's velocity or displacement, the striker's velocity), a
//! list of [`Parameter`]s (bounds, an initial value, optional log scaling), an optional fitted
//! time shift (measured(t) = model(t − s)) and a function that builds the run for a vector of
//! parameter values (the file-format layer sets scenario keys there; the core knows no keys).
//!
//! [`fit`] minimises ½ Σ r² with r = w (model − measured) / scale over the rows inside the
//! window, by Levenberg–Marquardt (MINPACK's trust region, crate `levenberg-marquardt`) from
//! several starts: the initial values, then Sobol' points within the bounds. Bounds are kept by a
//! transform: each bounded parameter u (or ln u when log-scaled) is x ∈ [0, 1] of its bounds, and
//! the optimiser moves z with x = (1 + sin z)/2 (MINUIT's transform), so every trial point is
//! inside the bounds and the optimiser itself is unconstrained.
//!
//! **Smooth residuals.** The model is sampled on a uniform grid finer than the measurement's (a
//! quarter of its smallest spacing) by the integrator's dense output and interpolated onto the
//! shifted measurement times by cubic Hermite (Catmull–Rom) interpolation, which is C¹ in the time
//! shift. Runs must use a fixed step (`Method::Rk4`): with a fixed step sequence the discrete
//! model is a smooth function of the parameters but for small kinks where a contact opens or
//! closes between stages, so the Jacobian is central differences over 1e-4 of a parameter's
//! range, wide enough to average over the kinks (claim `fit_jacobian`); the adaptive methods
//! change their step sequence with the parameters, which makes finite differences noisy
//! (measured in docs/fit.md, `examples/fit_jacobian_noise.rs`).
//!
//! **Uncertainty.** At the optimum, J is recomputed in the fitting coordinates u (or ln u), σ² =
//! Σ r² / (m − n), the covariance σ² (JᵀJ)⁻¹, 95 % intervals ±1.96 σ (m ≫ n), correlations, the
//! condition number of J with unit-length columns, and warnings for pairs with |corr| > 0.95 and
//! parameters at a bound. Parameters the data cannot determine (J numerically rank deficient)
//! get no standard error at all rather than a meaningless number.
//!
//! ## References
//! - J. J. Moré, "The Levenberg–Marquardt algorithm: implementation and theory", Lecture Notes
//!   in Mathematics 630 (1978).
//! - F. James, M. Roos, "MINUIT", Comput. Phys. Commun. 10 (1975) 343 (the sine transform).
//! - I. M. Sobol', USSR Comput. Math. Math. Phys. 7 (1967) 86; B. Burley, "Practical hash-based
//!   Owen scrambling", JCGT 9 (2020) (the scrambled sequence used).
//! - Bates & Watts, "Nonlinear Regression Analysis and Its Applications" (1988), §2.3 (linearised
//!   confidence intervals).

mod predict;
mod solve;
mod uncertainty;

pub use predict::{low_pass, Prediction};
pub use solve::{fit, jacobian, predict, residuals};
pub use uncertainty::Uncertainty;

use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::model::Chain;
use crate::record::Sample;
use crate::simulate::RunSettings;

/// A model quantity a measured signal is compared with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Output {
    /// Force of contact i \[N\] (0 = striker–element 1, N = the wall sensor): `contact_i_n`.
    ContactForce {
        /// Contact number 0..=N.
        contact: usize,
    },
    /// Velocity of element k's primary mass [m/s]: `element_k_m_s`.
    ElementVelocity {
        /// Element number 1..=N.
        element: usize,
    },
    /// Displacement of element k's primary mass \[m\]: `element_k_m`.
    ElementDisplacement {
        /// Element number 1..=N.
        element: usize,
    },
    /// The striker's velocity [m/s]: `striker_m_s`.
    StrikerVelocity,
}

impl Output {
    /// The forms of a name, for error messages.
    pub const FORMS: &'static str = "contact_N_n, element_K_m_s, element_K_m or striker_m_s";

    /// Parses `contact_20_n`, `element_3_m_s`, `element_3_m` or `striker_m_s`.
    pub fn parse(name: &str) -> Option<Self> {
        if name == "striker_m_s" {
            return Some(Output::StrikerVelocity);
        }
        let number =
            |rest: &str, suffix: &str| -> Option<usize> { rest.strip_suffix(suffix)?.parse().ok() };
        if let Some(rest) = name.strip_prefix("contact_") {
            return number(rest, "_n").map(|contact| Output::ContactForce { contact });
        }
        let rest = name.strip_prefix("element_")?;
        if let Some(element) = number(rest, "_m_s") {
            return Some(Output::ElementVelocity { element });
        }
        number(rest, "_m").map(|element| Output::ElementDisplacement { element })
    }

    /// Its name in files (the inverse of [`Output::parse`]).
    pub fn name(&self) -> String {
        match self {
            Output::ContactForce { contact } => format!("contact_{contact}_n"),
            Output::ElementVelocity { element } => format!("element_{element}_m_s"),
            Output::ElementDisplacement { element } => format!("element_{element}_m"),
            Output::StrikerVelocity => "striker_m_s".into(),
        }
    }

    /// Its unit.
    pub fn unit(&self) -> &'static str {
        match self {
            Output::ContactForce { .. } => "N",
            Output::ElementVelocity { .. } | Output::StrikerVelocity => "m/s",
            Output::ElementDisplacement { .. } => "m",
        }
    }

    /// Checks that the run has this output; `field` names where it was asked for.
    pub fn check(&self, field: &str, n_elements: usize, has_striker: bool) -> Result<()> {
        let bad = |what: String| Err(Error::invalid(field, self.name(), what));
        match *self {
            Output::ContactForce { contact } if contact > n_elements => bad(format!(
                "the chain has contacts 0..={n_elements} (0 = striker, {n_elements} = wall)"
            )),
            Output::ElementVelocity { element } | Output::ElementDisplacement { element }
                if element == 0 || element > n_elements =>
            {
                bad(format!("the chain has elements 1..={n_elements}"))
            }
            Output::StrikerVelocity if !has_striker => {
                bad("the excitation has no striker (striker_m_s needs an impact)".into())
            }
            _ => Ok(()),
        }
    }

    /// Its value in a sample.
    fn value(&self, sample: &Sample<'_>) -> f64 {
        match *self {
            Output::ContactForce { contact } => sample.contact_forces_n[contact],
            Output::ElementVelocity { element } => sample.velocities_m_s[element - 1],
            Output::ElementDisplacement { element } => sample.displacements_m[element - 1],
            Output::StrikerVelocity => sample.striker.map_or(f64::NAN, |(_, v)| v),
        }
    }
}

/// A measured signal.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// What the user calls it (errors and outputs name it), e.g. `measured.csv:sensor_n`.
    pub label: String,
    /// The model quantity it is compared with.
    pub output: Output,
    /// Sample times t_i \[s\], strictly increasing.
    pub times_s: Vec<f64>,
    /// Measured values, in the output's unit.
    pub values: Vec<f64>,
    /// Residual unit: r = weight (model − measured) / scale; the front ends default it to the
    /// signal's peak |value| within the window.
    pub scale: f64,
    /// Relative weight of this signal's residuals (default 1).
    pub weight: f64,
    /// The sensor: a first-order low-pass of this cutoff \[Hz\] applied to the model's signal
    /// at the measurement's own sampling ([`low_pass`]); none: the model is compared directly.
    pub sensor_cutoff_hz: Option<f64>,
}

impl Measurement {
    /// The peak |value| at times inside `window_s` (the default `scale`).
    pub fn peak_in(&self, window_s: (f64, f64)) -> f64 {
        self.times_s
            .iter()
            .zip(&self.values)
            .filter(|(t, _)| (window_s.0..=window_s.1).contains(*t))
            .fold(0.0, |m, (_, v)| f64::max(m, v.abs()))
    }
}

/// One fitted parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Its name (a scenario key as the user wrote it, or `time_shift_s`).
    pub name: String,
    /// The value the first start begins at.
    pub initial: f64,
    /// Lower and upper bound; none: unbounded (every start then begins at `initial`).
    pub bounds: Option<(f64, f64)>,
    /// Fit ln u instead of u (positive parameters spanning decades); intervals are then
    /// symmetric in ln u.
    pub log_scale: bool,
}

impl Parameter {
    /// Checks the bounds, the initial value and log scaling; errors name the parameter.
    pub fn validate(&self) -> Result<()> {
        let field = &self.name;
        if let Some((lo, hi)) = self.bounds {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(Error::invalid(
                    format!("{field}.bounds"),
                    format!("[{lo}, {hi}]"),
                    "must be two finite numbers, lower < upper",
                ));
            }
            if self.log_scale && lo <= 0.0 {
                return Err(Error::invalid(
                    format!("{field}.bounds"),
                    format!("[{lo}, {hi}]"),
                    "a log-scaled parameter needs a lower bound > 0",
                ));
            }
            if !(lo..=hi).contains(&self.initial) {
                return Err(Error::invalid(
                    format!("{field}.initial"),
                    self.initial,
                    format!("must lie within its bounds [{lo}, {hi}]"),
                ));
            }
        }
        if !self.initial.is_finite() || (self.log_scale && self.initial <= 0.0) {
            return Err(Error::invalid(
                format!("{field}.initial"),
                self.initial,
                "must be a finite number (> 0 when log-scaled)",
            ));
        }
        Ok(())
    }
}

/// What the model function builds for a vector of parameter values.
#[derive(Debug, Clone)]
pub struct Built {
    /// The chain.
    pub chain: Chain,
    /// Its excitation.
    pub excitation: Excitation,
    /// Its run settings: the method (fixed step) is used; duration and sampling are set by the
    /// fit from the measurements.
    pub settings: RunSettings,
}

/// The model as a function of the parameter values (in [`Problem::parameters`]' order, the
/// time shift excluded).
pub type ModelFn<'a> = dyn Fn(&[f64]) -> Result<Built> + Sync + 'a;

/// A calibration problem.
pub struct Problem<'a> {
    /// The model's parameters.
    pub parameters: Vec<Parameter>,
    /// The fitted time shift s \[s\], measured(t) = model(t − s); none: s = 0.
    pub time_shift_s: Option<Parameter>,
    /// The measured signals.
    pub measurements: Vec<Measurement>,
    /// Only rows with t in this window \[s\] enter the residuals; none: every row.
    pub window_s: Option<(f64, f64)>,
    /// Builds the run for parameter values.
    pub model: &'a ModelFn<'a>,
}

impl Problem<'_> {
    /// Every fitted parameter: the model's, then the time shift (named `time_shift_s`).
    pub fn all_parameters(&self) -> Vec<&Parameter> {
        self.parameters
            .iter()
            .chain(self.time_shift_s.as_ref())
            .collect()
    }

    /// The window (every row when none was given).
    pub fn window(&self) -> (f64, f64) {
        self.window_s.unwrap_or((f64::NEG_INFINITY, f64::INFINITY))
    }

    /// The initial values of every fitted parameter.
    pub fn initial_values(&self) -> Vec<f64> {
        self.all_parameters().iter().map(|p| p.initial).collect()
    }
}

/// How the fit runs.
#[derive(Clone, Copy)]
pub struct FitSettings<'a> {
    /// Number of starts: the initial values, then Sobol' points within the bounds.
    pub starts: usize,
    /// Most residual evaluations of one start (besides its Jacobians).
    pub max_evaluations: usize,
    /// Central-difference step of the Jacobian, as a fraction of each bounded parameter's range
    /// (of |initial| for an unbounded one).
    pub jacobian_step: f64,
    /// Relative tolerance on the cost and on the parameters (MINPACK's ftol and xtol).
    pub tolerance: f64,
    /// Seed of the Sobol' scrambling (the starts are reproducible).
    pub seed: u32,
    /// Set by the front end (Ctrl-C): the fit stops and returns the best point so far.
    pub stop: Option<&'a std::sync::atomic::AtomicBool>,
    /// Called after every model run (from any thread), for a progress display.
    pub progress: Option<&'a (dyn Fn(FitProgress) + Sync)>,
}

impl Default for FitSettings<'_> {
    fn default() -> Self {
        FitSettings {
            starts: crate::defaults::FIT_STARTS,
            max_evaluations: crate::defaults::FIT_MAX_EVALUATIONS,
            jacobian_step: crate::defaults::FIT_JACOBIAN_STEP,
            tolerance: crate::defaults::FIT_TOLERANCE,
            seed: 0,
            stop: None,
            progress: None,
        }
    }
}

/// Where the fit is, for a progress display.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitProgress {
    /// The start running (0-based) and the number of starts.
    pub start: usize,
    /// Number of starts.
    pub starts: usize,
    /// Model runs so far (residuals and Jacobians).
    pub evaluations: usize,
    /// The lowest cost ½ Σ r² so far.
    pub best_cost: f64,
}

/// One start of a multi-start fit.
#[derive(Debug, Clone, PartialEq)]
pub struct StartResult {
    /// Where it began.
    pub initial: Vec<f64>,
    /// Where it ended (its best point).
    pub estimate: Vec<f64>,
    /// Its cost ½ Σ r² there.
    pub cost: f64,
    /// Model runs it took.
    pub evaluations: usize,
    /// Why it stopped, in words.
    pub termination: String,
}

/// The result of [`fit`].
#[derive(Debug, Clone, PartialEq)]
pub struct FitResult {
    /// Parameter names, the model's then `time_shift_s`.
    pub names: Vec<String>,
    /// The estimates (the best point of every start).
    pub estimates: Vec<f64>,
    /// Uncertainty at the estimates; none when the fit was stopped before it could be computed.
    pub uncertainty: Option<Uncertainty>,
    /// Whether each estimate lies at a bound (within 1e-3 of its range).
    pub at_bound: Vec<bool>,
    /// The cost ½ Σ r² at the estimates.
    pub cost: f64,
    /// RMS of model − measured per measurement within the window, in its unit.
    pub residual_rms: Vec<f64>,
    /// Model runs in all.
    pub evaluations: usize,
    /// Every start.
    pub starts: Vec<StartResult>,
    /// Plain-language warnings: inseparable pairs, parameters at a bound, failed runs.
    pub warnings: Vec<String>,
    /// True when the fit was stopped ([`FitSettings::stop`]) before it finished.
    pub interrupted: bool,
}
