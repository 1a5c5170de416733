//! The model on the measurement's time grid: one run sampled finely, interpolated onto the
//! shifted measured times, and filtered like the sensor.

use super::{Built, Measurement, Output, Problem};
use crate::defaults;
use crate::error::{Error, Result};
use crate::math::Libm;
use crate::record::{Layout, Recorder, Sample};
use crate::simulate::{simulate, RunSettings};

/// The model's signals on each measurement's own times (the whole record, not only the window).
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    /// One vector per measurement, aligned with its `times_s`.
    pub values: Vec<Vec<f64>>,
}

/// Records the outputs the measurements need, on the run's uniform grid.
struct SignalRecorder {
    outputs: Vec<Output>,
    values: Vec<Vec<f64>>,
}

impl Recorder for SignalRecorder {
    fn start(&mut self, layout: &Layout) {
        for v in &mut self.values {
            v.reserve(layout.n_samples);
        }
    }

    fn record(&mut self, sample: &Sample<'_>) {
        for (output, values) in self.outputs.iter().zip(&mut self.values) {
            values.push(output.value(sample));
        }
    }
}

/// The sampling of the model's runs: fine enough for every measurement, long enough for the
/// latest measured time under the most negative allowed shift. Fixed for a whole fit, so that
/// every run has the same grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Grid {
    pub interval_s: f64,
    pub duration_s: f64,
}

impl Grid {
    pub(super) fn for_problem(problem: &Problem<'_>, model_interval_s: f64) -> Result<Self> {
        let mut finest = model_interval_s;
        let mut last = 0.0_f64;
        for m in &problem.measurements {
            for w in m.times_s.windows(2) {
                finest = finest.min((w[1] - w[0]) / defaults::FIT_OVERSAMPLING);
            }
            last = last.max(*m.times_s.last().unwrap_or(&0.0));
        }
        let earliest_shift = match &problem.time_shift_s {
            Some(p) => p.bounds.map_or(p.initial, |b| b.0).min(0.0),
            None => 0.0,
        };
        let duration_s = last - earliest_shift + 3.0 * finest;
        if duration_s <= 0.0 {
            return Err(Error::invalid(
                "time_s",
                last,
                "the measurements must extend past t = 0 (the start of the run)",
            ));
        }
        Ok(Grid {
            interval_s: finest,
            duration_s,
        })
    }

    fn settings(&self, base: &RunSettings) -> RunSettings {
        RunSettings {
            duration_s: self.duration_s,
            sample_interval_s: self.interval_s,
            ..*base
        }
    }
}

/// Refuses an adaptive method: its step sequence changes with the parameters, which makes the
/// finite-difference Jacobian noisy (docs/fit.md).
pub(super) fn require_fixed_step(settings: &RunSettings) -> Result<()> {
    if settings.method.adaptive() {
        let value = match settings.method {
            crate::Method::PeakTolerance { peak_tolerance } => {
                format!("adaptive (run.peak_tolerance = {peak_tolerance})")
            }
            _ => "dopri5".into(),
        };
        return Err(Error::invalid(
            "run.integrator",
            value,
            "a fit needs a fixed step (rk4, the default): an adaptive step sequence changes with the parameters and makes the Jacobian noisy (docs/fit.md)",
        ));
    }
    Ok(())
}

/// Runs the model built for `model_values` and returns its signals at each measurement's times
/// t − `shift_s`, filtered like each sensor.
pub(super) fn run_model(
    problem: &Problem<'_>,
    grid: &Grid,
    built: &Built,
    shift_s: f64,
) -> Result<Prediction> {
    let mut recorder = SignalRecorder {
        outputs: problem.measurements.iter().map(|m| m.output).collect(),
        values: vec![Vec::new(); problem.measurements.len()],
    };
    let has_striker = matches!(built.excitation, crate::Excitation::Impact(_));
    for m in &problem.measurements {
        m.output.check(&m.label, built.chain.len(), has_striker)?;
    }
    simulate(
        &built.chain,
        &built.excitation,
        &grid.settings(&built.settings),
        &mut recorder,
    )?;
    let values = problem
        .measurements
        .iter()
        .zip(&recorder.values)
        .map(|(m, model)| on_measured_times(m, model, grid.interval_s, shift_s))
        .collect();
    Ok(Prediction { values })
}

/// The model signal `model` (uniform grid of spacing `interval_s` from t = 0) at the times of
/// `m` shifted by `shift_s`, through the sensor's filter.
fn on_measured_times(m: &Measurement, model: &[f64], interval_s: f64, shift_s: f64) -> Vec<f64> {
    let at: Vec<f64> = m
        .times_s
        .iter()
        .map(|t| catmull_rom(model, (t - shift_s) / interval_s))
        .collect();
    match m.sensor_cutoff_hz {
        Some(fc) => low_pass(&m.times_s, &at, fc),
        None => at,
    }
}

/// Cubic Hermite interpolation of uniformly sampled `y` at fractional index `s`, with
/// central-difference slopes (Catmull–Rom) inside and zero slopes at both ends, where the
/// signal continues as a constant (before the run: its initial value, the chain at rest or the
/// striker at its speed; after: its last): C¹ in `s` everywhere, so the residuals are smooth in
/// the time shift (a one-sided slope at the start made a kink there).
fn catmull_rom(y: &[f64], s: f64) -> f64 {
    let n = y.len();
    if s <= 0.0 || n < 2 {
        return y[0];
    }
    if s >= (n - 1) as f64 {
        return y[n - 1];
    }
    let k = s.floor() as usize;
    let u = s - k as f64;
    let slope = |i: usize| {
        if i == 0 || i == n - 1 {
            0.0
        } else {
            0.5 * (y[i + 1] - y[i - 1])
        }
    };
    let (p1, p2, m1, m2) = (y[k], y[k + 1], slope(k), slope(k + 1));
    let (u2, u3) = (u * u, u * u * u);
    (2.0 * u3 - 3.0 * u2 + 1.0) * p1
        + (u3 - 2.0 * u2 + u) * m1
        + (-2.0 * u3 + 3.0 * u2) * p2
        + (u3 - u2) * m2
}

/// A first-order low-pass (an RC sensor of cutoff f_c) over a sampled signal: y_0 = x_0,
/// y_i = y_{i−1} + α_i (x_i − y_{i−1}) with α_i = 1 − exp(−2π f_c (t_i − t_{i−1})), the exact
/// response of the filter to a signal held constant over each sampling interval.
pub fn low_pass(times_s: &[f64], x: &[f64], cutoff_hz: f64) -> Vec<f64> {
    let mut y = Vec::with_capacity(x.len());
    for (i, &xi) in x.iter().enumerate() {
        let next = match y.last() {
            None => xi,
            Some(&prev) => {
                let dt = times_s[i] - times_s[i - 1];
                let alpha = 1.0 - (-2.0 * std::f64::consts::PI * cutoff_hz * dt).libm_exp();
                prev + alpha * (xi - prev)
            }
        };
        y.push(next);
    }
    y
}
