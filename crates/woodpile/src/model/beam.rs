//! Unit cells from beam theory (docs/physics.md §13): a rod of any length, section and material
//! reduced to a primary mass M and l internal resonators (m_j, k_j).
//!
//! A rod in a woodpile is touched at its centre only, and only its symmetric bending modes move
//! the centre. Seen from the contact, the rod is its *effective mass* M_eff(ω) = F / (−ω² u) at
//! the centre:
//! - M_eff(0) = ρ·A·L, the total mass;
//! - M_eff = 0 at the free–free symmetric bending frequencies Ω_j (the rod rings with the centre
//!   force-free): [`Rod::free_symmetric_frequencies_hz`];
//! - M_eff = ±∞ at the frequencies of the rod with its centre held, the clamped–free half rod of
//!   length L/2 (ω_j): [`Rod::centre_blocked_frequencies_hz`].
//!
//! Both are solved from the Timoshenko beam (shear deformation with Cowper's shear coefficient,
//! and rotary inertia) in closed form: the frequency equations are evaluated exactly and their
//! roots found by scanning for sign changes and bisecting. [`BeamTheory::EulerBernoulli`] gives
//! the slender-beam limit (no shear, no rotary inertia), used to check the solver against the
//! textbook values βL = 4.7300, 10.9956 (free–free) and 1.8751, 4.6941 (clamped–free).
//!
//! The cell with l resonators has M_eff(ω) = M + Σ m_j ω_j² / (ω_j² − ω²). [`Reduction::PoleZero`]
//! (the default) matches the total mass, the first l poles and the first l zeros exactly
//! (2l + 1 conditions); [`Reduction::ModalMass`] keeps the poles and gives each resonator the
//! modal effective mass of its centre-blocked mode.

use super::cell::{Resonator, UnitCell};
use super::material::Material;
use crate::error::{require_non_negative, require_positive, Error, Result};
use crate::math::Libm;
use std::f64::consts::PI;

/// Which beam theory gives the rod's bending frequencies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BeamTheory {
    /// Shear deformation (Cowper's shear coefficient) and rotary inertia: right for the stubby
    /// rods of a woodpile (L/D = 4 for the paper's 20 mm rod).
    #[default]
    Timoshenko,
    /// The slender-beam limit: no shear deformation, no rotary inertia.
    EulerBernoulli,
}

/// How the rod's effective mass is reduced to a primary mass and l resonators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reduction {
    /// Total mass, the first l poles ω_j and the first l zeros Ω_j exactly.
    #[default]
    PoleZero,
    /// The first l poles exactly; each resonator carries the modal effective mass of its
    /// centre-blocked mode, the primary mass the rest (the zeros then fall near, not on, Ω_j).
    ModalMass,
}

impl Reduction {
    /// The name used in files: `pole-zero` or `modal-mass`.
    pub fn name(self) -> &'static str {
        match self {
            Reduction::PoleZero => "pole-zero",
            Reduction::ModalMass => "modal-mass",
        }
    }
}

/// The most resonators a derived cell may have.
pub const MAX_MODES: usize = 4;

/// A straight rod of circular (solid or hollow) section.
#[derive(Debug, Clone, PartialEq)]
pub struct Rod {
    /// Length L \[m\].
    pub length_m: f64,
    /// Outer diameter D \[m\].
    pub outer_diameter_m: f64,
    /// Inner diameter d \[m\]: 0 for a solid rod, 0 < d < D for a tube.
    pub inner_diameter_m: f64,
    /// Its material.
    pub material: Material,
}

/// The section constants and the flexural parameters of one frequency.
pub(super) struct Wave {
    /// Decaying wavenumber α \[1/m\] (cosh, sinh).
    pub(super) alpha: f64,
    /// Oscillating wavenumber β \[1/m\] (cos, sin).
    pub(super) beta: f64,
    /// Rotation per unit deflection of the e^{αx} branch: Ψ = a sinh when W = cosh.
    pub(super) a: f64,
    /// Rotation per unit deflection of the cos branch: Ψ = b sin when W = cos.
    pub(super) b: f64,
}

impl Rod {
    /// A solid or hollow rod; `inner_diameter_m` = 0 for a solid one. Checks every value.
    pub fn new(
        length_m: f64,
        outer_diameter_m: f64,
        inner_diameter_m: f64,
        material: Material,
    ) -> Result<Self> {
        require_positive("rod.length_m", length_m)?;
        require_positive("rod.outer_diameter_m", outer_diameter_m)?;
        require_non_negative("rod.inner_diameter_m", inner_diameter_m)?;
        if inner_diameter_m >= outer_diameter_m {
            return Err(Error::invalid(
                "rod.inner_diameter_m",
                inner_diameter_m,
                format!("must be smaller than the outer diameter ({outer_diameter_m} m)"),
            ));
        }
        Ok(Rod {
            length_m,
            outer_diameter_m,
            inner_diameter_m,
            material,
        })
    }

    /// Cross-section area A \[m²\].
    pub fn area_m2(&self) -> f64 {
        PI / 4.0 * (self.outer_diameter_m.powi(2) - self.inner_diameter_m.powi(2))
    }

    /// Second moment of area I \[m⁴\] about a diameter.
    pub fn second_moment_m4(&self) -> f64 {
        PI / 64.0 * (self.outer_diameter_m.powi(4) - self.inner_diameter_m.powi(4))
    }

    /// Total mass ρ·A·L \[kg\].
    pub fn mass_kg(&self) -> f64 {
        self.material.density_kg_m3 * self.area_m2() * self.length_m
    }

    /// Cowper's shear coefficient of a hollow circular section (m = d/D):
    /// κ = 6(1 + ν)(1 + m²)² / [(7 + 6ν)(1 + m²)² + (20 + 12ν) m²]; 6(1 + ν)/(7 + 6ν) when solid.
    pub fn shear_coefficient(&self) -> f64 {
        let nu = self.material.poisson_ratio;
        let m2 = (self.inner_diameter_m / self.outer_diameter_m).powi(2);
        let s = (1.0 + m2).powi(2);
        6.0 * (1.0 + nu) * s / ((7.0 + 6.0 * nu) * s + (20.0 + 12.0 * nu) * m2)
    }

    /// Shear modulus G = E / (2(1 + ν)) \[Pa\].
    fn shear_modulus_pa(&self) -> f64 {
        self.material.youngs_modulus_pa / (2.0 * (1.0 + self.material.poisson_ratio))
    }

    /// The frequency \[rad/s\] above which a second (shear) branch exists and this solver does not
    /// apply: ω_c = sqrt(κGA / ρI) (infinite for Euler–Bernoulli).
    pub fn cutoff_angular_frequency(&self, theory: BeamTheory) -> f64 {
        match theory {
            BeamTheory::EulerBernoulli => f64::INFINITY,
            BeamTheory::Timoshenko => {
                let rho = self.material.density_kg_m3;
                (self.shear_coefficient() * self.shear_modulus_pa() * self.area_m2()
                    / (rho * self.second_moment_m4()))
                .sqrt()
            }
        }
    }

    /// The wavenumbers and rotation ratios at angular frequency ω (below the cutoff).
    pub(super) fn wave(&self, theory: BeamTheory, omega: f64) -> Wave {
        let rho = self.material.density_kg_m3;
        let (area, inertia) = (self.area_m2(), self.second_moment_m4());
        let ei = self.material.youngs_modulus_pa * inertia;
        let rho_a = rho * area;
        // Shear compliance c = 1/(κGA) and rotary inertia ρI; both vanish for Euler–Bernoulli.
        let (c, rho_i) = match theory {
            BeamTheory::Timoshenko => (
                1.0 / (self.shear_coefficient() * self.shear_modulus_pa() * area),
                rho * inertia,
            ),
            BeamTheory::EulerBernoulli => (0.0, 0.0),
        };
        let w2 = omega * omega;
        // λ⁴ + p λ² + q = 0 for solutions e^{λx}.
        let p = w2 * (rho_a * c + rho_i / ei);
        let q = rho_a * w2 / ei * (rho_i * w2 * c - 1.0);
        let root = (p * p - 4.0 * q).sqrt();
        let alpha = (0.5 * (-p + root)).sqrt();
        let beta = (0.5 * (p + root)).sqrt();
        Wave {
            alpha,
            beta,
            a: alpha + rho_a * w2 * c / alpha,
            b: rho_a * w2 * c / beta - beta,
        }
    }

    /// The free–free frequency equation for symmetric modes, divided by cosh(αL/2): zero at Ω_j.
    /// Rows: bending moment EIΨ' = 0 and shear force κGA(W' − Ψ) = 0 at the free end x = L/2 of
    /// W = C₁ cosh αx + C₂ cos βx, Ψ = C₁ a sinh αx + C₂ b sin βx.
    pub(super) fn free_free(&self, theory: BeamTheory, omega: f64) -> f64 {
        let w = self.wave(theory, omega);
        let half = 0.5 * self.length_m;
        let (s, c) = (w.beta * half).libm_sin_cos();
        let th = (w.alpha * half).libm_tanh();
        // moment row [aα, bβ cos βl / cosh αl], shear row [tanh αl / α, sin βl / (β cosh αl)]:
        // multiplied through by cosh αl, the determinant is
        (w.a * w.alpha / w.beta) * s - (w.b * w.beta / w.alpha) * th * c
    }

    /// The clamped–free frequency equation of the half rod, divided by cosh²(αL/2): zero at ω_j.
    /// Clamped at the centre (W = Ψ = 0), free at x = L/2.
    fn centre_blocked(&self, theory: BeamTheory, omega: f64) -> f64 {
        let w = self.wave(theory, omega);
        let half = 0.5 * self.length_m;
        let (s, c) = (w.beta * half).libm_sin_cos();
        let th = (w.alpha * half).libm_tanh();
        let sech = 1.0 / (w.alpha * half).libm_cosh();
        let (a, b, al, be) = (w.a, w.b, w.alpha, w.beta);
        // Unknowns C₁ (cosh − cos) and D (b sinh + a sin), from W(0) = Ψ(0) = 0.
        let m1 = a * al - b * be * c * sech;
        let m2 = a * b * (al * th + be * s * sech);
        let v1 = th / al - s * sech / be;
        let v2 = b / al - a * c * sech / be;
        m1 * v2 - m2 * v1
    }

    /// The first `count` roots \[rad/s\] of `equation` below `max_omega` and below the shear
    /// cutoff (fewer if there are fewer), scanned on a grid fine in the slender-beam wavenumber
    /// (so no two roots are skipped) and bisected to machine precision.
    pub(super) fn scan(
        &self,
        theory: BeamTheory,
        count: usize,
        max_omega: f64,
        equation: impl Fn(&Self, BeamTheory, f64) -> f64,
    ) -> Vec<f64> {
        let rho_a = self.material.density_kg_m3 * self.area_m2();
        let ei = self.material.youngs_modulus_pa * self.second_moment_m4();
        // ω = (x / L)² sqrt(EI/ρA): x is the Euler–Bernoulli βL; its roots are ≥ 0.8 apart.
        let scale = (ei / rho_a).sqrt() / self.length_m.powi(2);
        let limit = max_omega.min(self.cutoff_angular_frequency(theory));
        let mut roots = Vec::with_capacity(count);
        let step = 0.004;
        let mut x = step;
        let mut prev = (x * x * scale, equation(self, theory, x * x * scale));
        while roots.len() < count {
            x += step;
            let omega = x * x * scale;
            if omega >= limit {
                break;
            }
            let value = equation(self, theory, omega);
            if value == 0.0 || (value > 0.0) != (prev.1 > 0.0) {
                let (mut lo, mut hi) = (prev.0, omega);
                let lo_sign = prev.1 > 0.0;
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        break;
                    }
                    if (equation(self, theory, mid) > 0.0) == lo_sign {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                roots.push(0.5 * (lo + hi));
            }
            prev = (omega, value);
        }
        roots
    }

    /// The first `count` roots \[rad/s\] of `equation`; an error names the shear cutoff when
    /// fewer lie below it.
    fn roots(
        &self,
        theory: BeamTheory,
        count: usize,
        what: &str,
        equation: impl Fn(&Self, BeamTheory, f64) -> f64,
    ) -> Result<Vec<f64>> {
        let roots = self.scan(theory, count, f64::INFINITY, equation);
        if roots.len() < count {
            return Err(Error::invalid(
                "rod.modes",
                count,
                format!(
                    "only {} {what} frequencies lie below the rod's shear cutoff {:.1} kHz, where the Timoshenko solution changes form; use fewer modes",
                    roots.len(),
                    self.cutoff_angular_frequency(theory) / (2.0 * PI) / 1e3
                ),
            ));
        }
        Ok(roots)
    }

    /// [`Rod::roots`] in Hz.
    fn frequencies_hz(
        &self,
        theory: BeamTheory,
        count: usize,
        what: &str,
        equation: impl Fn(&Self, BeamTheory, f64) -> f64,
    ) -> Result<Vec<f64>> {
        let roots = self.roots(theory, count, what, equation)?;
        Ok(roots.into_iter().map(|w| w / (2.0 * PI)).collect())
    }

    /// The first `count` symmetric free–free bending frequencies Ω_j/2π \[Hz\]: the zeros of the
    /// effective mass at the centre.
    pub fn free_symmetric_frequencies_hz(
        &self,
        theory: BeamTheory,
        count: usize,
    ) -> Result<Vec<f64>> {
        self.frequencies_hz(theory, count, "free-free", Rod::free_free)
    }

    /// The first `count` frequencies ω_j/2π \[Hz\] of the rod with its centre held (the
    /// clamped–free half rod): the poles of the effective mass at the centre.
    pub fn centre_blocked_frequencies_hz(
        &self,
        theory: BeamTheory,
        count: usize,
    ) -> Result<Vec<f64>> {
        self.frequencies_hz(theory, count, "centre-blocked", Rod::centre_blocked)
    }

    /// The most resonators a derived cell of this rod can have: [`MAX_MODES`], or fewer when
    /// fewer centre-blocked and free–free modes lie below the shear cutoff (3 for the 20 mm
    /// quartz rod).
    pub fn max_modes(&self) -> usize {
        let t = BeamTheory::Timoshenko;
        let poles = self
            .scan(t, MAX_MODES, f64::INFINITY, Rod::centre_blocked)
            .len();
        let zeros = self.scan(t, MAX_MODES, f64::INFINITY, Rod::free_free).len();
        poles.min(zeros)
    }

    /// The number of resonators of the default rule: one per centre-blocked mode below
    /// [`crate::defaults::CELL_MODE_CUTOFF_HZ`], at least 1 and at most [`MAX_MODES`].
    pub fn default_modes(&self) -> usize {
        let below = self.scan(
            BeamTheory::Timoshenko,
            MAX_MODES,
            2.0 * PI * crate::defaults::CELL_MODE_CUTOFF_HZ,
            Rod::centre_blocked,
        );
        below.len().max(1)
    }

    /// Refuses a rod that is no beam (shorter than its diameter: a disc, whose bending modes the
    /// scan cannot find) or so slender that its bending modes mean nothing to a chain (more than
    /// [`crate::defaults::ROD_MAX_SLENDERNESS`] diameters: its first frequency is 6.4 mHz at the
    /// limit for a 5 mm fused-quartz rod, and falls as 1/L²). Named `rod.length_m`.
    pub fn check_slenderness(&self) -> Result<()> {
        let ratio = self.length_m / self.outer_diameter_m;
        let max = crate::defaults::ROD_MAX_SLENDERNESS;
        if ratio < 1.0 {
            return Err(Error::invalid(
                "rod.length_m",
                self.length_m,
                format!("shorter than its diameter {:e} m (length/diameter = {ratio:.3e}): a disc, not a beam; beam theory needs a length of at least one diameter (the paper's rods: 4 to 16)", self.outer_diameter_m),
            ));
        }
        if ratio > max {
            return Err(Error::invalid(
                "rod.length_m",
                self.length_m,
                format!("{ratio:.1} diameters long (at most {max}): its bending frequencies fall as 1/length², below any time scale of a chain run (a 5 mm fused-quartz rod at the limit: 6.4 mHz); model it as rigid or shorten it"),
            ));
        }
        Ok(())
    }

    /// The modal effective masses \[kg\] of the centre-blocked modes at `omegas` \[rad/s\] of the
    /// whole rod: (∫ρA W dx)² / ∫(ρA W² + ρI Ψ²) dx over both halves.
    fn modal_masses_kg(&self, theory: BeamTheory, omegas: &[f64]) -> Vec<f64> {
        let rho = self.material.density_kg_m3;
        let rho_a = rho * self.area_m2();
        let rho_i = match theory {
            BeamTheory::Timoshenko => rho * self.second_moment_m4(),
            BeamTheory::EulerBernoulli => 0.0,
        };
        let half = 0.5 * self.length_m;
        omegas
            .iter()
            .map(|&omega| {
                let w = self.wave(theory, omega);
                let (a, b, al, be) = (w.a, w.b, w.alpha, w.beta);
                let (s, c) = (be * half).libm_sin_cos();
                let (sh, ch) = ((al * half).libm_sinh(), (al * half).libm_cosh());
                // The null vector of the moment row (the shear row is then satisfied).
                let (mut c1, mut d) = (a * b * (al * sh + be * s), -(a * al * ch - b * be * c));
                if c1.abs() + d.abs() == 0.0 {
                    (c1, d) = (b / al * ch - a / be * c, -(sh / al - s / be));
                }
                // Simpson's rule on the half rod; the shape is smooth, 2000 panels are ample.
                let n = 2000;
                let h = half / n as f64;
                let (mut first, mut second) = (0.0, 0.0);
                for i in 0..=n {
                    let x = i as f64 * h;
                    let (sx, cx) = (be * x).libm_sin_cos();
                    let (shx, chx) = ((al * x).libm_sinh(), (al * x).libm_cosh());
                    let deflection = c1 * (chx - cx) + d * (b * shx + a * sx);
                    let rotation = a * c1 * shx + a * b * d * chx - b * c1 * sx - a * b * d * cx;
                    let weight = if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    first += weight * rho_a * deflection;
                    second += weight * (rho_a * deflection.powi(2) + rho_i * rotation.powi(2));
                }
                let (first, second) = (2.0 * first * h / 3.0, 2.0 * second * h / 3.0);
                first * first / second
            })
            .collect()
    }
}

impl UnitCell {
    /// The unit cell of `rod` with `modes` resonators (None: [`Rod::default_modes`]) from the
    /// Timoshenko beam, reduced as `reduction` says. Errors if `modes` is not 1..=4 or the
    /// reduction gives a mass that is not positive.
    pub fn from_rod(rod: &Rod, modes: Option<usize>, reduction: Reduction) -> Result<Self> {
        rod.check_slenderness()?;
        let l = match modes {
            Some(l) => l,
            None => rod.default_modes(),
        };
        if !(1..=MAX_MODES).contains(&l) {
            return Err(Error::invalid(
                "rod.modes",
                l,
                format!("must be 1..={MAX_MODES}"),
            ));
        }
        let theory = BeamTheory::Timoshenko;
        let total = rod.mass_kg();
        let omegas = rod.roots(theory, l, "centre-blocked", Rod::centre_blocked)?;
        let poles: Vec<f64> = omegas.iter().map(|w| w * w).collect();
        let (primary, masses) = match reduction {
            Reduction::PoleZero => {
                let zeros: Vec<f64> = rod
                    .roots(theory, l, "free-free", Rod::free_free)?
                    .into_iter()
                    .map(|w| w * w)
                    .collect();
                pole_zero_masses(total, &poles, &zeros)
            }
            Reduction::ModalMass => {
                let masses = rod.modal_masses_kg(theory, &omegas);
                (total - masses.iter().sum::<f64>(), masses)
            }
        };
        if !(primary > 0.0 && masses.iter().all(|&m| m > 0.0)) {
            return Err(Error::invalid(
                "rod.modes",
                l,
                format!(
                    "the {} reduction gives a mass that is not positive (primary {primary:e} kg, resonators {masses:?} kg); use fewer modes",
                    reduction.name()
                ),
            ));
        }
        let resonators = masses
            .iter()
            .zip(&poles)
            .map(|(&m, &p)| Resonator {
                mass_kg: m,
                stiffness_n_per_m: m * p,
            })
            .collect();
        UnitCell::new(primary, resonators)
    }
}

/// Primary mass M and resonator masses m_j \[kg\] of M_eff(ω) = M + Σ m_j p_j / (p_j − ω²) with total mass `total`,
/// poles p_j = ω_j² and zeros z_j = Ω_j² (interlaced p₁ < z₁ < p₂ < …): M = total · Π p_j/z_j and
/// m_j = −M Π_i (p_j − z_i) / (p_j Π_{k≠j} (p_j − p_k)), the residues of the rational function.
fn pole_zero_masses(total: f64, poles: &[f64], zeros: &[f64]) -> (f64, Vec<f64>) {
    let primary = total * poles.iter().zip(zeros).map(|(p, z)| p / z).product::<f64>();
    let masses = poles
        .iter()
        .enumerate()
        .map(|(j, &pj)| {
            let num: f64 = zeros.iter().map(|&z| pj - z).product();
            let den: f64 = poles
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != j)
                .map(|(_, &pk)| pj - pk)
                .product();
            -primary * num / (pj * den)
        })
        .collect();
    (primary, masses)
}
