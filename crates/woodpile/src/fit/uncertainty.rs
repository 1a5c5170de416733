//! Linearised uncertainty at the optimum: σ² (JᵀJ)⁻¹, intervals, correlations, identifiability.

use crate::defaults;
use crate::error::{Error, Result};
use crate::math::Libm;
use nalgebra::DMatrix;

/// Two-sided 95 % quantile of the normal distribution (the residuals number hundreds, so
/// Student's t with m − n degrees of freedom differs by less than 1 %).
const Z95: f64 = 1.959_963_984_540_054;

/// A singular value of J (unit-length columns) below this fraction of the largest is
/// numerically zero: the parameters along its singular vector are not determined at all.
const RANK_CUTOFF: f64 = 1e-8;

/// The uncertainty of a fit's estimates.
#[derive(Debug, Clone, PartialEq)]
pub struct Uncertainty {
    /// Standard error of each estimate, in its unit (log-scaled: p σ_{ln p}); none where the data
    /// do not determine the parameter at all (J rank deficient along it).
    pub std_errors: Vec<Option<f64>>,
    /// 95 % interval of each estimate (log-scaled: symmetric in ln p); none as for the errors.
    pub ci95: Vec<Option<[f64; 2]>>,
    /// Correlation matrix of the estimates (fitting coordinates).
    pub correlation: Vec<Vec<f64>>,
    /// Condition number of J with unit-length columns (scale-free: large means some combination
    /// of parameters hardly changes the residuals); infinite when J is singular.
    pub condition_number: f64,
    /// σ: the residuals' standard deviation √(Σ r² / (m − n)), in residual units.
    pub sigma: f64,
    /// Degrees of freedom m − n.
    pub degrees_of_freedom: usize,
}

impl Uncertainty {
    /// From the Jacobian columns `ju` (∂r/∂u, u = p or ln p as `logs` says), the residuals `r`
    /// and the estimates.
    pub(super) fn new(
        ju: &[Vec<f64>],
        r: &[f64],
        estimates: &[f64],
        logs: &[bool],
    ) -> Result<Self> {
        let (m, n) = (r.len(), ju.len());
        if m <= n {
            return Err(Error::invalid(
                "data",
                format!("{m} rows in the window"),
                format!("a fit of {n} parameters needs more rows than parameters"),
            ));
        }
        let norms: Vec<f64> = ju
            .iter()
            .map(|c| c.iter().map(|v| v * v).sum::<f64>().sqrt())
            .collect();
        // J D with D = diag(1/|J_j|): the columns at unit length.
        let jn = DMatrix::from_fn(m, n, |i, j| {
            if norms[j] > 0.0 {
                ju[j][i] / norms[j]
            } else {
                0.0
            }
        });
        let svd = jn.svd(false, true);
        let v_t = svd.v_t.as_ref().expect("requested V");
        let s = &svd.singular_values;
        let s_max = s.max();
        let s_min = s.min();
        let condition_number = if s_min > 0.0 {
            s_max / s_min
        } else {
            f64::INFINITY
        };
        let dof = m - n;
        let sigma = (r.iter().map(|r| r * r).sum::<f64>() / dof as f64).sqrt();
        // (JnᵀJn)⁻¹ = V S⁻² Vᵀ, the numerically zero singular values floored so that the
        // correlations stay finite; the parameters along them are marked undetermined.
        let floor = RANK_CUTOFF * s_max;
        let mut undetermined = vec![false; n];
        let mut cn = DMatrix::<f64>::zeros(n, n);
        for k in 0..n {
            let sk = s[k].max(floor).max(f64::MIN_POSITIVE);
            for a in 0..n {
                if s[k] < floor && v_t[(k, a)].abs() > 0.1 {
                    undetermined[a] = true;
                }
                for b in 0..n {
                    cn[(a, b)] += v_t[(k, a)] * v_t[(k, b)] / (sk * sk);
                }
            }
        }
        let correlation = (0..n)
            .map(|a| {
                (0..n)
                    .map(|b| cn[(a, b)] / (cn[(a, a)] * cn[(b, b)]).sqrt())
                    .collect()
            })
            .collect();
        let mut std_errors = Vec::with_capacity(n);
        let mut ci95 = Vec::with_capacity(n);
        for j in 0..n {
            // Var(u_j) = σ² [(JᵀJ)⁻¹]_jj = σ² cn_jj / |J_j|².
            let su = sigma * cn[(j, j)].sqrt() / norms[j];
            if undetermined[j] || !su.is_finite() {
                std_errors.push(None);
                ci95.push(None);
            } else if logs[j] {
                let p = estimates[j];
                std_errors.push(Some(p * su));
                ci95.push(Some([
                    p * (-Z95 * su).libm_exp(),
                    p * (Z95 * su).libm_exp(),
                ]));
            } else {
                let p = estimates[j];
                std_errors.push(Some(su));
                ci95.push(Some([p - Z95 * su, p + Z95 * su]));
            }
        }
        Ok(Uncertainty {
            std_errors,
            ci95,
            correlation,
            condition_number,
            sigma,
            degrees_of_freedom: dof,
        })
    }

    /// Plain-language warnings: pairs the data cannot separate (|corr| above
    /// [`defaults::FIT_CORRELATION_WARN`]) and parameters the data do not determine.
    pub fn warnings(&self, names: &[String]) -> Vec<String> {
        let mut w = Vec::new();
        let n = names.len();
        for a in 0..n {
            for b in a + 1..n {
                let c = self.correlation[a][b];
                if c.abs() > defaults::FIT_CORRELATION_WARN {
                    w.push(format!(
                        "{} and {} cannot be separated by these data (correlation {c:+.4}): only a combination of them is determined; fix one of them, or add a measurement that tells them apart",
                        names[a], names[b]
                    ));
                }
            }
        }
        for (j, e) in self.std_errors.iter().enumerate() {
            if e.is_none() {
                w.push(format!(
                    "{}: the data do not determine it (the Jacobian is singular along it, condition number {:.3e}); no standard error is given",
                    names[j], self.condition_number
                ));
            }
        }
        w
    }
}
