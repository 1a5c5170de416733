//! Claim: the fit's Jacobian (forward differences of 1e-7 of each parameter's range, on RK4's
//! fixed step sequence) agrees to 1e-4 relative, column by column, with central differences of
//! a ten times larger step (1e-6 of the range) of the same model.
//!
//! Tolerance: with a fixed step sequence the discrete model is smooth in the parameters at
//! these scales, so the forward differences err by O(h) and by rounding ε/h ≈ 1e-9 (measured:
//! 7e-6 to 2.4e-5); with adaptive step control (DOPRI5, rtol 1e-9) the same comparison is off by
//! a factor 28 and more, which is why the fit refuses adaptive runs (docs/fit.md, example
//! `fit_jacobian_noise`). What this does not claim: that the discrete model's derivative is the
//! continuous model's (halving the step changes it by a few per cent, docs/fit.md).

use crate::fit_common::{model, problem, synthetic};
use woodpile::fit::{jacobian, residuals};

#[test]
fn the_jacobian_matches_central_differences() {
    let problem = problem(synthetic(0.0, 0), &model);
    let at = [0.8, 1.2, 2.1, 1e-6];
    let j = jacobian(&problem, &at, 1e-7).unwrap();
    let ranges: Vec<f64> = problem
        .all_parameters()
        .iter()
        .map(|p| p.bounds.map_or(1.0, |(lo, hi)| hi - lo))
        .collect();
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    for (k, column) in j.iter().enumerate() {
        let h = 1e-6 * ranges[k];
        let (mut up, mut down) = (at.to_vec(), at.to_vec());
        up[k] += h;
        down[k] -= h;
        let (ru, rd) = (
            residuals(&problem, &up).unwrap(),
            residuals(&problem, &down).unwrap(),
        );
        let central: Vec<f64> = ru
            .iter()
            .zip(&rd)
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect();
        let diff: Vec<f64> = column.iter().zip(&central).map(|(a, b)| a - b).collect();
        let relative = norm(&diff) / norm(&central);
        assert!(
            relative < 1e-4,
            "{}: forward and central differences differ by {relative:.2e} relative",
            problem.all_parameters()[k].name
        );
    }
}
