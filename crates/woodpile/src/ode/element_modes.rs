//! One element's undamped modes (docs/physics.md §8, "Exact linear vibrations"): a primary mass
//! M carrying resonators (m_j, k_j), decomposed into its free–free modes, rigid first.
//!
//! Ω_k² is found as ω_s² + τ with τ ∈ (0, ω_{s+1}² − ω_s²) the root of the secular equation
//! M + Σ_i m_i ω_i² / ((ω_i² − ω_s²) − τ) = 0 (one root above each pole ω_s², the function
//! increasing from −∞ to +∞ between poles), so that every gap ω_i² − Ω_k² is computed without
//! cancellation, however close a mode of tiny effective mass lies to its pole.

use crate::error::{Error, Result};

/// One element's modes: rigid first, then the flexible ones in ascending frequency.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ElementModes {
    /// Ω_k \[rad/s\] (0 for the rigid mode).
    pub omega: Vec<f64>,
    /// μ_k \[kg\], the modal mass of mode k scaled to unit primary amplitude.
    pub modal_mass: Vec<f64>,
    /// Primary mass M \[kg\].
    primary_mass: f64,
    /// Resonator masses m_j \[kg\], in the chain's order.
    res_mass: Vec<f64>,
    /// u_jk − 1 = Ω_k² / (ω_j² − Ω_k²): resonator j's extension per unit primary amplitude of
    /// flexible mode k (row j, R × R).
    extension: Vec<f64>,
}

impl ElementModes {
    /// The modes of a primary mass `primary_mass` carrying resonators (m_j, k_j). Resonators of
    /// equal frequency are refused (a mode then leaves the primary at rest: not coupled to the
    /// contacts, it needs no modal treatment, but its resonators cannot be told apart).
    pub fn new(primary_mass: f64, resonators: &[(f64, f64)]) -> Result<Self> {
        let r = resonators.len();
        let total = primary_mass + resonators.iter().map(|&(m, _)| m).sum::<f64>();
        let w2: Vec<f64> = resonators.iter().map(|&(m, k)| k / m).collect();
        let mut order: Vec<usize> = (0..r).collect();
        order.sort_by(|&a, &b| w2[a].total_cmp(&w2[b]));
        if let Some(pair) = order.windows(2).find(|p| w2[p[0]] == w2[p[1]]) {
            return Err(Error::invalid(
                "cell.resonators",
                format!("{} and {}", pair[0], pair[1]),
                "two resonators of one cell have the same frequency: the exact modal method needs \
                 distinct ones (merge them into one resonator of their summed mass and stiffness)",
            ));
        }
        let mut omega = vec![0.0];
        let mut modal_mass = vec![total];
        let mut extension = vec![0.0; r * r];
        for (k, &s) in order.iter().enumerate() {
            let above = order.get(k + 1).map(|&n| w2[n] - w2[s]);
            let tau = secular_root(primary_mass, resonators, &w2, s, above);
            let omega2 = w2[s] + tau;
            let mut mu = primary_mass;
            for (j, &(m, _)) in resonators.iter().enumerate() {
                let gap = (w2[j] - w2[s]) - tau; // ω_j² − Ω_k²
                let u = w2[j] / gap;
                mu += m * u * u;
                extension[j * r + k] = omega2 / gap;
            }
            omega.push(omega2.sqrt());
            modal_mass.push(mu);
        }
        Ok(ElementModes {
            omega,
            modal_mass,
            primary_mass,
            res_mass: resonators.iter().map(|&(m, _)| m).collect(),
            extension,
        })
    }

    /// Number of modes (rigid included).
    pub fn len(&self) -> usize {
        self.omega.len()
    }

    /// u_jk: resonator j's amplitude in mode k per unit primary amplitude (1 in the rigid
    /// mode k = 0).
    pub fn resonator_amplitude(&self, j: usize, k: usize) -> f64 {
        match k {
            0 => 1.0,
            _ => 1.0 + self.extension[j * self.res_mass.len() + k - 1],
        }
    }

    /// Modal amplitudes c (rigid first) of the primary's value `x0` and the resonators' `w`
    /// (positions or velocities): c_k = (M x0 + Σ m_j u_jk w_j) / μ_k, the mass-weighted
    /// projection.
    pub fn project(&self, x0: f64, w: &[f64], c: &mut [f64]) {
        let r = self.res_mass.len();
        let m0 = self.primary_mass * x0;
        c[0] = (m0 + self.res_mass.iter().zip(w).map(|(m, w)| m * w).sum::<f64>())
            / self.modal_mass[0];
        for k in 0..r {
            let s: f64 = (0..r)
                .map(|j| self.res_mass[j] * (1.0 + self.extension[j * r + k]) * w[j])
                .sum();
            c[k + 1] = (m0 + s) / self.modal_mass[k + 1];
        }
    }
}

/// τ = Ω² − ω_s² of the mode above pole s (`above`: the gap to the next pole, None for the last).
/// M_eff(τ) rises from −∞ to +∞ between the poles; Newton's steps are taken on
/// φ(τ) = τ (g − τ) M_eff(τ) (g the gap above; τ M_eff(τ) for the last mode), which has the same
/// root and sign but no pole at either end, so that they converge from anywhere in the bracket.
/// Each evaluation narrows the bracket; a step that would leave it is a bisection instead
/// (geometric while the bracket spans decades: a mode of tiny effective mass lies very close to
/// its pole). Stops when a step moves τ by no more than a few rounding errors, or the bracket
/// has no double left inside.
fn secular_root(
    primary_mass: f64,
    resonators: &[(f64, f64)],
    w2: &[f64],
    s: usize,
    above: Option<f64>,
) -> f64 {
    // M_eff(τ) and its slope.
    let meff = |tau: f64| {
        let (mut f, mut slope) = (primary_mass, 0.0);
        for (&(m, _), &wi) in resonators.iter().zip(w2) {
            let inv_gap = 1.0 / ((wi - w2[s]) - tau);
            let term = m * wi * inv_gap;
            f += term;
            slope += term * inv_gap;
        }
        (f, slope)
    };
    // φ(τ) and its slope.
    let phi = |tau: f64| {
        let (f, slope) = meff(tau);
        let (w, dw) = match above {
            Some(gap) => (tau * (gap - tau), gap - 2.0 * tau),
            None => (tau, 1.0),
        };
        (w * f, dw * f + w * slope)
    };
    let mut hi = match above {
        Some(gap) => gap,
        None => {
            let mut hi = w2[s].max(f64::MIN_POSITIVE);
            while meff(hi).0 < 0.0 {
                hi *= 2.0;
            }
            hi
        }
    };
    let mut lo = 0.0_f64;
    let bisect = |lo: f64, hi: f64| {
        if hi > 16.0 * lo {
            (lo.max(hi * 1e-30) * hi).sqrt()
        } else {
            0.5 * (lo + hi)
        }
    };
    let mut tau = 0.5 * hi;
    for _ in 0..SECULAR_ITERATIONS {
        if tau <= lo || tau >= hi {
            return 0.5 * (lo + hi);
        }
        let (f, slope) = phi(tau);
        if f == 0.0 {
            return tau;
        }
        if f < 0.0 {
            lo = tau;
        } else {
            hi = tau;
        }
        let newton = tau - f / slope;
        if newton > lo && newton < hi {
            if (newton - tau).abs() <= 4.0 * f64::EPSILON * tau {
                return newton;
            }
            tau = newton;
        } else {
            tau = bisect(lo, hi);
        }
    }
    tau
}

/// Most evaluations of the secular equation per root: Newton's steps converge in a few (9 on
/// average, at most 37, on a 16-element rod's 32 modes), the bisections that guard them halve
/// the bracket (or its decades) each; far more than either needs for a double.
const SECULAR_ITERATIONS: usize = 3000;
