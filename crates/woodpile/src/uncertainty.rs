//! Manufacturing scatter: quasi-Monte Carlo draws and the statistics of a design's samples.
//!
//! The draws are Owen-scrambled Sobol' points ([`sobol_burley`], Burley 2020): sample k,
//! dimension j, for a seed. They depend on (k, j, seed) only, so every design of a study sees the
//! same draws (common random numbers) and a sample can be drawn again on its own. A point is
//! mapped to a parameter by its inverse CDF: a uniform range directly, a normal through
//! [`standard_normal_quantile`].
//!
//! ```
//! use woodpile::uncertainty::{statistics, unit_cube};
//!
//! let u = unit_cube(8, 2, 1)?;
//! assert!(u.iter().flatten().all(|&x| x > 0.0 && x < 1.0));
//! let s = statistics(&[1.0, 2.0, 3.0, 4.0]);
//! assert_eq!(s.mean, 2.5);
//! # Ok::<(), woodpile::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::math::Libm;

/// The most dimensions (drawn parameters) one sample may have: those of [`sobol_burley`].
pub const MAX_DIMENSIONS: usize = sobol_burley::NUM_DIMENSIONS as usize;

/// The probability levels of [`Statistics::quantiles`].
pub const QUANTILE_LEVELS: [f64; 5] = [0.05, 0.25, 0.5, 0.75, 0.95];

/// The level of [`Statistics::cvar_95`].
pub const CVAR_LEVEL: f64 = 0.95;

/// `samples` points of the `dimensions`-dimensional unit cube for `seed`: row k is sample k.
///
/// Each coordinate is sobol_burley's single-precision point (a multiple of 2⁻²⁴ in [0, 1))
/// moved to the middle of its 2⁻²⁴ cell, so it lies strictly inside (0, 1) and every inverse
/// CDF is finite.
pub fn unit_cube(samples: usize, dimensions: usize, seed: u32) -> Result<Vec<Vec<f64>>> {
    if dimensions > MAX_DIMENSIONS {
        return Err(Error::invalid(
            "uncertainty.dimensions",
            dimensions,
            format!("at most {MAX_DIMENSIONS} drawn parameters per sample"),
        ));
    }
    let Ok(count) = u32::try_from(samples) else {
        return Err(Error::invalid(
            "uncertainty.samples",
            samples,
            "at most 2^32 - 1",
        ));
    };
    let half_cell = 0.5f64.powi(25);
    Ok((0..count)
        .map(|k| {
            (0..dimensions as u32)
                .map(|j| f64::from(sobol_burley::sample(k, j, seed)) + half_cell)
                .collect()
        })
        .collect())
}

/// Φ⁻¹(p), the standard normal quantile, for 0 < p < 1: Acklam's rational approximation
/// (relative error below 1.15e-9 over (0, 1)); ±∞ at 0 and 1, NaN outside.
pub fn standard_normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969683028665376e1,
        2.209460984245205e2,
        -2.759285104469687e2,
        1.38357751867269e2,
        -3.066479806614716e1,
        2.506628277459239,
    ];
    const B: [f64; 5] = [
        -5.447609879822406e1,
        1.615858368580409e2,
        -1.556989798598866e2,
        6.680131188771972e1,
        -1.328068155288572e1,
    ];
    const C: [f64; 6] = [
        -7.784894002430293e-3,
        -3.223964580411365e-1,
        -2.400758277161838,
        -2.549732539343734,
        4.374664141464968,
        2.938163982698783,
    ];
    const D: [f64; 4] = [
        7.784695709041462e-3,
        3.224671290700398e-1,
        2.445134137142996,
        3.754408661907416,
    ];
    const P_LOW: f64 = 0.02425;
    if !(0.0..=1.0).contains(&p) {
        return f64::NAN;
    }
    if p == 0.0 {
        return f64::NEG_INFINITY;
    }
    if p == 1.0 {
        return f64::INFINITY;
    }
    let tail = |q: f64| {
        let q = (-2.0 * q.libm_ln()).sqrt();
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < P_LOW {
        tail(p)
    } else if p > 1.0 - P_LOW {
        -tail(1.0 - p)
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
}

/// A figure of merit over a design's samples.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Statistics {
    /// Number of samples.
    pub samples: usize,
    /// Their mean.
    pub mean: f64,
    /// Their sample standard deviation (n − 1 in the denominator; 0 for one sample).
    pub sd: f64,
    /// (level, quantile) at [`QUANTILE_LEVELS`]: linear interpolation between order statistics
    /// (Hyndman & Fan type 7, numpy's default).
    pub quantiles: Vec<(f64, f64)>,
    /// Conditional value at risk at 0.95: the mean of the worst (largest) ⌈0.05 n⌉ samples —
    /// larger figures (forces) are worse.
    pub cvar_95: f64,
}

/// The statistics of `values` (at least one, all finite).
pub fn statistics(values: &[f64]) -> Statistics {
    let n = values.len();
    let mean = values.iter().sum::<f64>() / n as f64;
    let sd = if n > 1 {
        (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
    } else {
        0.0
    };
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    Statistics {
        samples: n,
        mean,
        sd,
        quantiles: QUANTILE_LEVELS
            .iter()
            .map(|&p| (p, quantile_of_sorted(&sorted, p)))
            .collect(),
        cvar_95: cvar_of_sorted(&sorted, CVAR_LEVEL),
    }
}

/// The p-quantile of ascending `sorted` values, type 7.
pub fn quantile_of_sorted(sorted: &[f64], p: f64) -> f64 {
    let h = (sorted.len() - 1) as f64 * p;
    let (lo, frac) = (h.floor() as usize, h - h.floor());
    match sorted.get(lo + 1) {
        Some(&next) if frac > 0.0 => sorted[lo] + frac * (next - sorted[lo]),
        _ => sorted[lo],
    }
}

/// The mean of the largest ⌈(1 − level) n⌉ of ascending `sorted` values (at least one).
pub fn cvar_of_sorted(sorted: &[f64], level: f64) -> f64 {
    let n = sorted.len();
    let tail = (((1.0 - level) * n as f64).ceil() as usize).clamp(1, n);
    sorted[n - tail..].iter().sum::<f64>() / tail as f64
}
