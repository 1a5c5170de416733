//! Claim: with Gaussian noise of 1 % of each signal's peak (fixed seed), the fit started at the
//! middle of the bounds brackets every true value within its reported 95 % interval, and the
//! residual RMS it reports for each signal equals the noise level (1 % of the peak) within 10 %.
//!
//! Tolerance: with m = 301 rows per signal the RMS of the noise itself scatters by
//! 1/√(2m) ≈ 4 % around its level and fitting four parameters lowers it by √((m − n)/m) < 1 %,
//! so 10 % is about 2.5 standard deviations. One seed checks the interval once; the coverage
//! over 50 seeds is measured by the example `fit_coverage` (bench/README.md).

use crate::fit_common::{model, problem, synthetic, TRUTH};
use woodpile::fit::{fit, FitSettings};

#[test]
fn one_percent_noise_is_bracketed_and_its_level_reported() {
    let measurements = synthetic(0.01, 7);
    let problem = problem(measurements.clone(), &model);
    let settings = FitSettings {
        starts: 1,
        ..FitSettings::default()
    };
    let result = fit(&problem, &settings).unwrap();
    let uncertainty = result.uncertainty.as_ref().unwrap();
    for (k, name) in result.names.iter().enumerate() {
        let [lo, hi] = uncertainty.ci95[k].unwrap();
        assert!(
            (lo..=hi).contains(&TRUTH[k]),
            "{name}: true {:e} outside the 95 % interval [{lo:e}, {hi:e}] of the estimate {:e}",
            TRUTH[k],
            result.estimates[k]
        );
    }
    for (m, rms) in measurements.iter().zip(&result.residual_rms) {
        let noise = 0.01 * m.scale;
        assert!(
            (rms / noise - 1.0).abs() < 0.1,
            "{}: residual RMS {rms:e} against the noise level {noise:e}",
            m.label
        );
    }
}
