//! The analytic free–free bending modes of a Timoshenko rod (docs/physics.md §16): the exact
//! solutions of the beam equations, not of a mesh, used for `rod = { modes = l }` and as the
//! reference the finite-element rod ([`super::FreeRodModes`]) converges to.
//!
//! On x ∈ [−L/2, L/2] at angular frequency ω (below the shear cutoff; wavenumbers
//! α, β and rotation ratios a, b), a symmetric mode is
//! W = P cosh αx / cosh(αL/2) + Q cos βx, Ψ = P a sinh αx / cosh(αL/2) + Q b sin βx, and an
//! antisymmetric one W = P sinh αx / cosh(αL/2) + Q sin βx,
//! Ψ = P a cosh αx / cosh(αL/2) − Q b cos βx. Both ends are free: the bending moment EIΨ' and the
//! shear force κGA(W' − Ψ) vanish at x = ±L/2. The moment condition fixes (P, Q); the shear
//! condition is the frequency equation (for symmetric modes that of §13, for
//! antisymmetric ones `antisymmetric_equation`), whose roots are bisected to machine
//! precision. Each mode is mass-normalised, ∫(ρA W² + ρI Ψ²) dx = 1 (composite Simpson rule,
//! 4000 panels on smooth shapes). Elastic modes are orthogonal to the rigid translation and
//! rocking by the free ends, so they carry no momentum.

use super::beam::{BeamTheory, Rod};
use crate::error::{Error, Result};
use crate::math::Libm;

/// One free–free bending mode of a Timoshenko rod, mass-normalised.
#[derive(Debug, Clone, PartialEq)]
pub struct TimoshenkoMode {
    /// Angular frequency ω \[rad/s\].
    pub omega_rad_s: f64,
    /// Whether W(−x) = W(x).
    pub symmetric: bool,
    alpha: f64,
    beta: f64,
    a: f64,
    b: f64,
    half_m: f64,
    /// Amplitudes of the hyperbolic (over cosh αL/2) and the trigonometric branch.
    p: f64,
    q: f64,
}

impl TimoshenkoMode {
    /// Deflection W(s) at axial coordinate s ∈ [−L/2, L/2] \[kg^-½\].
    pub fn deflection(&self, s_m: f64) -> f64 {
        let (hyp, trig) = if self.symmetric {
            (self.cosh_ratio(s_m), (self.beta * s_m).libm_cos())
        } else {
            (self.sinh_ratio(s_m), (self.beta * s_m).libm_sin())
        };
        self.p * hyp + self.q * trig
    }

    /// Rotation Ψ(s) of the section \[kg^-½ m^-1\].
    pub fn rotation(&self, s_m: f64) -> f64 {
        if self.symmetric {
            self.p * self.a * self.sinh_ratio(s_m) + self.q * self.b * (self.beta * s_m).libm_sin()
        } else {
            self.p * self.a * self.cosh_ratio(s_m) - self.q * self.b * (self.beta * s_m).libm_cos()
        }
    }

    /// cosh αs / cosh αL/2 without overflow.
    fn cosh_ratio(&self, s: f64) -> f64 {
        let (x, l) = (self.alpha * s.abs(), self.alpha * self.half_m);
        ((x - l).libm_exp() + (-x - l).libm_exp()) / (1.0 + (-2.0 * l).libm_exp())
    }

    /// sinh αs / cosh αL/2 without overflow.
    fn sinh_ratio(&self, s: f64) -> f64 {
        let (x, l) = (self.alpha * s.abs(), self.alpha * self.half_m);
        s.signum() * ((x - l).libm_exp() - (-x - l).libm_exp()) / (1.0 + (-2.0 * l).libm_exp())
    }
}

/// The free–free frequency equation of antisymmetric modes, divided by cosh(αL/2): zero at
/// their ω. Rows at x = L/2: moment [aα sinh αl, bβ sin βl], shear (over ρAω²/κGA)
/// [cosh αl / α, −cos βl / β].
fn antisymmetric_equation(rod: &Rod, theory: BeamTheory, omega: f64) -> f64 {
    let w = rod.wave(theory, omega);
    let half = 0.5 * rod.length_m;
    let (s, c) = (w.beta * half).libm_sin_cos();
    let th = (w.alpha * half).libm_tanh();
    -(w.a * w.alpha / w.beta) * th * c - (w.b * w.beta / w.alpha) * s
}

impl Rod {
    /// The `count` lowest free–free bending modes of the Timoshenko rod, ascending, symmetric
    /// and antisymmetric together; an error (naming `rod.modes`) when fewer lie below the shear
    /// cutoff, where the solution changes form.
    pub fn free_free_modes(&self, count: usize) -> Result<Vec<TimoshenkoMode>> {
        let t = BeamTheory::Timoshenko;
        let symmetric = self.scan(t, count, f64::INFINITY, Rod::free_free);
        let antisymmetric = self.scan(t, count, f64::INFINITY, antisymmetric_equation);
        let mut roots: Vec<(f64, bool)> = symmetric
            .iter()
            .map(|&w| (w, true))
            .chain(antisymmetric.iter().map(|&w| (w, false)))
            .collect();
        roots.sort_by(|x, y| x.0.total_cmp(&y.0));
        if roots.len() < count {
            return Err(Error::invalid(
                "rod.modes",
                count,
                format!(
                    "only {} free-free bending modes of this rod lie below its shear cutoff {:.1} kHz, where the Timoshenko solution changes form; use at most that many",
                    roots.len(),
                    self.cutoff_angular_frequency(t) / (2.0 * std::f64::consts::PI) / 1e3
                ),
            ));
        }
        Ok(roots[..count]
            .iter()
            .map(|&(omega, symmetric)| self.free_free_mode(omega, symmetric))
            .collect())
    }

    /// The mode at a root ω of the frequency equation, mass-normalised.
    fn free_free_mode(&self, omega: f64, symmetric: bool) -> TimoshenkoMode {
        let w = self.wave(BeamTheory::Timoshenko, omega);
        let half_m = 0.5 * self.length_m;
        let (sb, cb) = (w.beta * half_m).libm_sin_cos();
        // The null vector of the moment row at x = L/2.
        let (p, q) = if symmetric {
            (w.b * w.beta * cb, -w.a * w.alpha)
        } else {
            (
                w.b * w.beta * sb,
                -w.a * w.alpha * (w.alpha * half_m).libm_tanh(),
            )
        };
        let mut mode = TimoshenkoMode {
            omega_rad_s: omega,
            symmetric,
            alpha: w.alpha,
            beta: w.beta,
            a: w.a,
            b: w.b,
            half_m,
            p,
            q,
        };
        let rho = self.material.density_kg_m3;
        let (rho_a, rho_i) = (rho * self.area_m2(), rho * self.second_moment_m4());
        let norm = simpson(self.length_m, |s| {
            rho_a * mode.deflection(s).powi(2) + rho_i * mode.rotation(s).powi(2)
        })
        .sqrt();
        mode.p /= norm;
        mode.q /= norm;
        mode
    }
}

/// ∫ f ds over [−L/2, L/2], composite Simpson rule on 4000 panels.
pub(crate) fn simpson(length_m: f64, f: impl Fn(f64) -> f64) -> f64 {
    let n = 4000;
    let h = length_m / n as f64;
    let sum: f64 = (0..=n)
        .map(|i| {
            let weight = match i {
                0 => 1.0,
                i if i == n => 1.0,
                i if i % 2 == 1 => 4.0,
                _ => 2.0,
            };
            weight * f(-0.5 * length_m + i as f64 * h)
        })
        .sum();
    sum * h / 3.0
}
