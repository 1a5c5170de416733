//! Claim: the fit's Jacobian (forward differences of 1e-7 of each parameter's range, RK4 at the
//! model's 0.1 µs) agrees to 1e-4 relative, column by column, with central differences of 1e-4
//! of the range computed with a twice finer step (0.05 µs).
//!
//! Tolerance: with a fixed step sequence the discrete model is a smooth function of the
//! parameters, so the forward differences err by O(h) ≈ 1e-7 and by rounding ≈ ε/h ≈ 1e-9,
//! the central ones by O(h²) ≈ 1e-8; the finer step changes the model's derivative by the
//! RK4 error, O(Δt⁴). 1e-4 leaves room for all of these; an adaptive step sequence misses it
//! by orders of magnitude (docs/fit.md).

use crate::fit_common::{model, model_with_step, problem, synthetic, TRUTH};
use woodpile::fit::{jacobian, residuals};

#[test]
fn the_jacobian_matches_central_differences() {
    let measurements = synthetic(0.0, 0);
    let coarse = problem(measurements.clone(), &model);
    let fine_model = |v: &[f64]| model_with_step(v, 5e-8);
    let fine = problem(measurements, &fine_model);
    let at = [0.8, 1.2, 2.1, 1e-6];
    let j = jacobian(&coarse, &at, 1e-7).unwrap();
    let ranges: Vec<f64> = fine
        .all_parameters()
        .iter()
        .map(|p| p.bounds.map_or(1.0, |(lo, hi)| hi - lo))
        .collect();
    for (k, column) in j.iter().enumerate() {
        let h = 1e-4 * ranges[k];
        let (mut up, mut down) = (at.to_vec(), at.to_vec());
        up[k] += h;
        down[k] -= h;
        let (ru, rd) = (residuals(&fine, &up).unwrap(), residuals(&fine, &down).unwrap());
        let central: Vec<f64> = ru.iter().zip(&rd).map(|(a, b)| (a - b) / (2.0 * h)).collect();
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let diff: Vec<f64> = column.iter().zip(&central).map(|(a, b)| a - b).collect();
        let relative = norm(&diff) / norm(&central);
        assert!(
            relative < 1e-4,
            "parameter {k}: forward vs central differ by {relative:.2e} relative"
        );
        eprintln!("parameter {k}: {relative:.2e}");
    }
    let _ = TRUTH;
}
