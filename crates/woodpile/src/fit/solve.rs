//! The least-squares solve: coordinates and bounds, residuals and Jacobians, multi-start
//! Levenberg–Marquardt.

use super::predict::{run_model, Grid, Prediction};
use super::uncertainty::Uncertainty;
use super::{FitProgress, FitResult, FitSettings, Parameter, Problem, StartResult};
use crate::error::{Error, Result};
use crate::math::Libm;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DMatrix, DVector, Dyn, Owned};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Residual given to the optimiser for a trial point whose run failed (a blow-up): far larger
/// than any residual of a run (those are of order 1, normalised by the signal's peak), so the
/// trust region shrinks away from it.
const FAILED_RUN_RESIDUAL: f64 = 1e3;

/// The optimiser's variables are offset from zero: MINPACK sizes its first trust region by
/// the norm of the starting point, and a start at the middle of every bound (z = 0) made the
/// first steps vanish (measured: the first trial moved by 1e-15 and the solve stopped there).
/// sin is 2π-periodic, so the offset changes nothing else.
const Z_OFFSET: f64 = 2.0 * std::f64::consts::PI;

/// A normalised parameter: x ∈ [0, 1] across the bounds of u (u = p, or ln p when log-scaled);
/// unbounded, x = (u − u₀)/scale. The optimiser moves z, x = (1 + sin z)/2 when bounded.
#[derive(Debug, Clone, Copy)]
struct Coordinate {
    origin: f64,
    width: f64,
    bounded: bool,
    log: bool,
}

impl Coordinate {
    fn new(p: &Parameter) -> Self {
        let u = |v: f64| if p.log_scale { v.libm_ln() } else { v };
        match p.bounds {
            Some((lo, hi)) => Coordinate {
                origin: u(lo),
                width: u(hi) - u(lo),
                bounded: true,
                log: p.log_scale,
            },
            None => {
                let u0 = u(p.initial);
                let width = if p.log_scale || u0 == 0.0 {
                    1.0
                } else {
                    u0.abs()
                };
                Coordinate {
                    origin: u0,
                    width,
                    bounded: false,
                    log: p.log_scale,
                }
            }
        }
    }

    fn value(&self, x: f64) -> f64 {
        let u = self.origin + self.width * x;
        if self.log {
            u.libm_exp()
        } else {
            u
        }
    }

    fn x_of(&self, value: f64) -> f64 {
        let u = if self.log { value.libm_ln() } else { value };
        (u - self.origin) / self.width
    }

    fn x_of_z(&self, z: f64) -> f64 {
        if self.bounded {
            0.5 * (1.0 + z.libm_sin())
        } else {
            z - Z_OFFSET
        }
    }

    fn z_of_x(&self, x: f64) -> f64 {
        if self.bounded {
            (2.0 * x - 1.0).clamp(-1.0, 1.0).libm_asin() + Z_OFFSET
        } else {
            x + Z_OFFSET
        }
    }

    fn dx_dz(&self, z: f64) -> f64 {
        if self.bounded {
            0.5 * z.libm_cos()
        } else {
            1.0
        }
    }

    /// d value / dx.
    fn dvalue_dx(&self, x: f64) -> f64 {
        if self.log {
            self.width * self.value(x)
        } else {
            self.width
        }
    }
}

/// Runs the model for one problem, counting runs and keeping the best point.
struct Evaluator<'p, 'a> {
    problem: &'p Problem<'a>,
    coordinates: Vec<Coordinate>,
    grid: Grid,
    step: f64,
    evaluations: AtomicUsize,
    failed: AtomicUsize,
    /// (cost, values) of the best point so far: of every start, and of the current start.
    best: Mutex<[(f64, Vec<f64>); 2]>,
    settings: Option<FitSettings<'p>>,
    start: AtomicUsize,
}

impl<'p, 'a> Evaluator<'p, 'a> {
    /// `step`: of the Jacobian (0: none is computed); the fit and the Jacobian need a fixed
    /// integration step, a prediction does not.
    fn new(problem: &'p Problem<'a>, step: f64) -> Result<Self> {
        if problem.measurements.is_empty() {
            return Err(Error::invalid(
                "data",
                "(none)",
                "give at least one measured signal",
            ));
        }
        for p in problem.all_parameters() {
            p.validate()?;
        }
        let n_model = problem.parameters.len();
        let built = (problem.model)(&problem.initial_values()[..n_model])?;
        if step > 0.0 {
            super::predict::require_fixed_step(&built.settings)?;
        }
        let grid = Grid::for_problem(problem, built.settings.sample_interval_s)?;
        let all = problem.all_parameters();
        Ok(Evaluator {
            problem,
            coordinates: all.iter().map(|p| Coordinate::new(p)).collect(),
            grid,
            step,
            evaluations: AtomicUsize::new(0),
            failed: AtomicUsize::new(0),
            best: Mutex::new([(f64::INFINITY, Vec::new()), (f64::INFINITY, Vec::new())]),
            settings: None,
            start: AtomicUsize::new(0),
        })
    }

    fn values_of_x(&self, x: &[f64]) -> Vec<f64> {
        self.coordinates
            .iter()
            .zip(x)
            .map(|(c, &x)| c.value(x))
            .collect()
    }

    /// The front end's stop flag, or the process-wide stop request ([`crate::interrupt`]: the
    /// runs of the model end at once then, so the fit must stop too).
    fn stopped(&self) -> bool {
        crate::interrupt::requested()
            || self
                .settings
                .and_then(|s| s.stop)
                .is_some_and(|s| s.load(Ordering::Relaxed))
    }

    fn prediction(&self, values: &[f64]) -> Result<Prediction> {
        let n = self.problem.parameters.len();
        let built = (self.problem.model)(&values[..n])?;
        let shift = values.get(n).copied().unwrap_or(0.0);
        let prediction = run_model(self.problem, &self.grid, &built, shift);
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        prediction
    }

    fn residuals(&self, values: &[f64]) -> Result<Vec<f64>> {
        let r = residual_vector(self.problem, &self.prediction(values)?);
        let cost = 0.5 * r.iter().map(|r| r * r).sum::<f64>();
        let mut best = self.best.lock().unwrap_or_else(|e| e.into_inner());
        for b in best.iter_mut() {
            if cost < b.0 {
                *b = (cost, values.to_vec());
            }
        }
        if let Some(progress) = self.settings.and_then(|s| s.progress) {
            progress(FitProgress {
                start: self.start.load(Ordering::Relaxed),
                starts: self.settings.map_or(1, |s| s.starts),
                evaluations: self.evaluations.load(Ordering::Relaxed),
                best_cost: best[0].0,
            });
        }
        Ok(r)
    }

    /// ∂r/∂x by second-order differences of `step`, two runs per column, the columns in
    /// parallel on the current rayon pool: central, or the one-sided three-point formula
    /// (−3 r₀ + 4 r₁ − r₂)/(2h) where x ± h would leave a bounded coordinate's [0, 1].
    fn jacobian_x(&self, x: &[f64], r0: &[f64]) -> Result<Vec<Vec<f64>>> {
        (0..x.len())
            .into_par_iter()
            .map(|j| {
                let h = self.step;
                let at = |dx: f64| {
                    let mut xj = x.to_vec();
                    xj[j] += dx;
                    self.residuals(&self.values_of_x(&xj))
                };
                let bounded = self.coordinates[j].bounded;
                let column = if !bounded || (x[j] - h >= 0.0 && x[j] + h <= 1.0) {
                    let (up, down) = (at(h)?, at(-h)?);
                    up.iter()
                        .zip(&down)
                        .map(|(u, d)| (u - d) / (2.0 * h))
                        .collect()
                } else {
                    let s = if x[j] + 2.0 * h > 1.0 { -h } else { h };
                    let (r1, r2) = (at(s)?, at(2.0 * s)?);
                    r0.iter()
                        .zip(&r1)
                        .zip(&r2)
                        .map(|((a, b), c)| (-3.0 * a + 4.0 * b - c) / (2.0 * s))
                        .collect()
                };
                Ok(column)
            })
            .collect()
    }
}

/// The weighted residuals r = w (model − measured)/scale of every row inside the window, the
/// measurements one after the other.
fn residual_vector(problem: &Problem<'_>, prediction: &Prediction) -> Vec<f64> {
    let (t0, t1) = problem.window();
    let mut r = Vec::new();
    for (m, model) in problem.measurements.iter().zip(&prediction.values) {
        for ((t, measured), model) in m.times_s.iter().zip(&m.values).zip(model) {
            if (t0..=t1).contains(t) {
                r.push(m.weight * (model - measured) / m.scale);
            }
        }
    }
    r
}

/// RMS of model − measured within the window, per measurement, in its unit.
fn residual_rms(problem: &Problem<'_>, prediction: &Prediction) -> Vec<f64> {
    let (t0, t1) = problem.window();
    let rms = |(m, model): (&super::Measurement, &Vec<f64>)| {
        let (mut sum, mut n) = (0.0, 0usize);
        for ((t, measured), model) in m.times_s.iter().zip(&m.values).zip(model) {
            if (t0..=t1).contains(t) {
                sum += (model - measured).powi(2);
                n += 1;
            }
        }
        (sum / n.max(1) as f64).sqrt()
    };
    problem
        .measurements
        .iter()
        .zip(&prediction.values)
        .map(rms)
        .collect()
}

/// The model's signals at `values` (every fitted parameter, the time shift last) on each
/// measurement's times.
pub fn predict(problem: &Problem<'_>, values: &[f64]) -> Result<Prediction> {
    Evaluator::new(problem, 0.0)?.prediction(values)
}

/// The weighted residual vector at `values` (the rows inside the window).
pub fn residuals(problem: &Problem<'_>, values: &[f64]) -> Result<Vec<f64>> {
    Evaluator::new(problem, 0.0)?.residuals(values)
}

/// The fit's Jacobian ∂r_i/∂p_j at `values`, one vector per parameter (in the parameter's own
/// units, not its fitting coordinate): second-order differences of `step` of each bounded
/// parameter's range, as [`fit`] computes it.
pub fn jacobian(problem: &Problem<'_>, values: &[f64], step: f64) -> Result<Vec<Vec<f64>>> {
    let ev = Evaluator::new(problem, step)?;
    let x: Vec<f64> = ev
        .coordinates
        .iter()
        .zip(values)
        .map(|(c, &v)| c.x_of(v))
        .collect();
    let r0 = ev.residuals(values)?;
    let jx = ev.jacobian_x(&x, &r0)?;
    Ok(jx
        .into_iter()
        .zip(&ev.coordinates)
        .zip(&x)
        .map(|((col, c), &x)| {
            let d = c.dvalue_dx(x);
            col.into_iter().map(|v| v / d).collect()
        })
        .collect())
}

/// One start's problem for the optimiser, in z.
struct Start<'e, 'p, 'a> {
    ev: &'e Evaluator<'p, 'a>,
    z: DVector<f64>,
    r: Option<DVector<f64>>,
}

impl Start<'_, '_, '_> {
    fn x(&self) -> Vec<f64> {
        self.ev
            .coordinates
            .iter()
            .zip(self.z.iter())
            .map(|(c, &z)| c.x_of_z(z))
            .collect()
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Start<'_, '_, '_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, z: &DVector<f64>) {
        self.z.copy_from(z);
        self.r = if self.ev.stopped() {
            None
        } else {
            let m = self.r.as_ref().map_or(0, |r| r.len());
            match self.ev.residuals(&self.ev.values_of_x(&self.x())) {
                Ok(r) => Some(DVector::from_vec(r)),
                Err(_) if m > 0 => {
                    self.ev.failed.fetch_add(1, Ordering::Relaxed);
                    Some(DVector::from_element(m, FAILED_RUN_RESIDUAL))
                }
                Err(_) => None,
            }
        };
    }

    fn params(&self) -> DVector<f64> {
        self.z.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.r.clone()
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let r0 = self.r.as_ref()?;
        if self.ev.stopped() {
            return None;
        }
        let jx = self.ev.jacobian_x(&self.x(), r0.as_slice()).ok()?;
        let mut j = DMatrix::zeros(r0.len(), jx.len());
        for (k, (col, c)) in jx.iter().zip(&self.ev.coordinates).enumerate() {
            let d = c.dx_dz(self.z[k]);
            for (i, v) in col.iter().enumerate() {
                j[(i, k)] = v * d;
            }
        }
        Some(j)
    }
}

/// The normalised start points: the initial values, then Sobol' points in the bounds (an
/// unbounded parameter starts at its initial value every time).
fn start_points(ev: &Evaluator<'_, '_>, starts: usize, seed: u32) -> Vec<Vec<f64>> {
    let initial: Vec<f64> = ev
        .coordinates
        .iter()
        .zip(ev.problem.initial_values())
        .map(|(c, v)| c.x_of(v))
        .collect();
    let mut points = vec![initial.clone()];
    for k in 1..starts {
        points.push(
            ev.coordinates
                .iter()
                .enumerate()
                .map(|(d, c)| {
                    if c.bounded {
                        f64::from(sobol_burley::sample(k as u32, d as u32, seed))
                    } else {
                        initial[d]
                    }
                })
                .collect(),
        );
    }
    points
}

/// Fits `problem` (module documentation): multi-start Levenberg–Marquardt, then the
/// uncertainty at the best point. Stopped through [`FitSettings::stop`], it returns the best
/// point so far without an uncertainty.
pub fn fit(problem: &Problem<'_>, settings: &FitSettings<'_>) -> Result<FitResult> {
    if settings.starts == 0 {
        return Err(Error::invalid("starts", 0, "must be at least 1"));
    }
    let mut ev = Evaluator::new(problem, settings.jacobian_step)?;
    ev.settings = Some(*settings);
    let n = ev.coordinates.len();
    let patience = (settings.max_evaluations / (n + 1)).max(1);
    let lm = LevenbergMarquardt::new()
        .with_ftol(settings.tolerance)
        .with_xtol(settings.tolerance)
        .with_patience(patience);
    let mut starts = Vec::new();
    for (k, x0) in start_points(&ev, settings.starts, settings.seed)
        .into_iter()
        .enumerate()
    {
        if ev.stopped() {
            break;
        }
        ev.start.store(k, Ordering::Relaxed);
        ev.best.lock().unwrap_or_else(|e| e.into_inner())[1] = (f64::INFINITY, Vec::new());
        let before = ev.evaluations.load(Ordering::Relaxed);
        let z0 = x0.iter().zip(&ev.coordinates).map(|(&x, c)| c.z_of_x(x));
        let mut start = Start {
            ev: &ev,
            z: DVector::from_iterator(n, z0),
            r: None,
        };
        start.set_params(&start.z.clone());
        let (_, report) = lm.minimize(start);
        let (cost, estimate) = ev.best.lock().unwrap_or_else(|e| e.into_inner())[1].clone();
        starts.push(StartResult {
            initial: ev.values_of_x(&x0),
            estimate,
            cost,
            evaluations: ev.evaluations.load(Ordering::Relaxed) - before,
            termination: format!("{:?}", report.termination),
        });
    }
    finish(&ev, starts)
}

/// The result at the best point of every start: uncertainty (unless stopped), bounds, warnings.
fn finish(ev: &Evaluator<'_, '_>, starts: Vec<StartResult>) -> Result<FitResult> {
    let problem = ev.problem;
    let names: Vec<String> = problem
        .all_parameters()
        .iter()
        .map(|p| p.name.clone())
        .collect();
    let (cost, estimates) = ev.best.lock().unwrap_or_else(|e| e.into_inner())[0].clone();
    if estimates.is_empty() {
        return Err(Error::invalid(
            "parameters",
            "(every start)",
            "the model failed to run at every start point; narrow the bounds",
        ));
    }
    let interrupted = ev.stopped();
    let x: Vec<f64> = ev
        .coordinates
        .iter()
        .zip(&estimates)
        .map(|(c, &v)| c.x_of(v))
        .collect();
    let at_bound: Vec<bool> = ev
        .coordinates
        .iter()
        .zip(&x)
        .map(|(c, &x)| c.bounded && !(1e-3..=1.0 - 1e-3).contains(&x))
        .collect();
    let prediction = ev.prediction(&estimates)?;
    let r = residual_vector(problem, &prediction);
    let uncertainty = if interrupted {
        None
    } else {
        let jx = ev.jacobian_x(&x, &r)?;
        // Columns in the fitting coordinate u (= p or ln p): dr/du = dr/dx / width.
        let ju: Vec<Vec<f64>> = jx
            .into_iter()
            .zip(&ev.coordinates)
            .map(|(col, c)| col.into_iter().map(|v| v / c.width).collect())
            .collect();
        let logs: Vec<bool> = ev.coordinates.iter().map(|c| c.log).collect();
        Some(Uncertainty::new(&ju, &r, &estimates, &logs)?)
    };
    let mut warnings = Vec::new();
    if let Some(u) = &uncertainty {
        warnings.extend(u.warnings(&names));
    }
    for (k, p) in problem.all_parameters().iter().enumerate() {
        if let (true, Some((lo, hi))) = (at_bound[k], p.bounds) {
            let side = if x[k] < 0.5 { "lower" } else { "upper" };
            warnings.push(format!(
                "{} = {:.6e} is at its {side} bound (bounds [{lo}, {hi}]): the best fit may lie outside them; widen the bounds if that is physical, and do not trust its interval",
                p.name, estimates[k]
            ));
        }
    }
    let failed = ev.failed.load(Ordering::Relaxed);
    if failed > 0 {
        warnings.push(format!("{failed} model runs failed (blow-up) and were treated as rejected steps: the bounds allow values the model cannot run"));
    }
    if interrupted {
        warnings.push("the fit was stopped before it finished: the estimates are the best point so far, without uncertainties".into());
    }
    Ok(FitResult {
        names,
        residual_rms: residual_rms(problem, &prediction),
        estimates,
        uncertainty,
        at_bound,
        cost,
        evaluations: ev.evaluations.load(Ordering::Relaxed),
        starts,
        warnings,
        interrupted,
    })
}
