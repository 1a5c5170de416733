//! Hertzian point contact between two curved elastic bodies: F = β δ^{3/2}.
//!
//! The gap between two bodies with principal curvatures (1/R1', 1/R1''), (1/R2', 1/R2'') whose
//! principal planes meet at angle φ is h = A x² + B y² (A ≤ B) with
//!
//! ```text
//! A + B = ½ (1/R1' + 1/R1'' + 1/R2' + 1/R2'')
//! B − A = ½ sqrt[(1/R1' − 1/R1'')² + (1/R2' − 1/R2'')² + 2 (1/R1' − 1/R1'')(1/R2' − 1/R2'') cos 2φ]
//! ```
//!
//! The contact ellipse's eccentricity e solves B/A = [E(e)/(1 − e²) − K(e)] / [K(e) − E(e)]
//! exactly (bisection; the right side is monotonic in e), and
//! β = (2π E*/3) K(e)^{-3/2} sqrt((K(e) − E(e)) / (e² A)), 1/E* = Σ (1 − ν²)/E.
//!
//! ## References
//! - K. L. Johnson, *Contact Mechanics*, Cambridge University Press 1985, §4.2 (Hertz theory of
//!   elliptical contacts).
//! - Abramowitz & Stegun, *Handbook of Mathematical Functions*, §17.6 (arithmetic–geometric mean).
//! - docs/physics.md §5 (the project's specification, with reference values).

use super::material::Material;
use crate::error::{Error, Result};
use crate::math::Libm;

/// The local shape of a body at its contact point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Surface {
    /// A circular cylinder of radius r \[m\]: curvatures (1/r, 0). `axis_angle_rad` is the direction
    /// of its axis in the contact plane; only differences between two bodies matter.
    Cylinder {
        /// Radius r \[m\].
        radius_m: f64,
        /// Axis direction in the contact plane \[rad\].
        axis_angle_rad: f64,
    },
    /// A sphere (or spherical cap) of radius R \[m\]: curvatures (1/R, 1/R).
    Sphere {
        /// Radius R \[m\].
        radius_m: f64,
    },
    /// A flat: curvatures (0, 0).
    Flat,
}

/// A length in mm with three decimals, or three significant digits when that would print more
/// than a dozen digits or none at all.
fn millimetres(m: f64) -> String {
    let mm = m * 1e3;
    if mm.abs() >= 1e6 || (mm != 0.0 && mm.abs() < 1e-3) {
        format!("{mm:.3e}")
    } else {
        format!("{mm:.3}")
    }
}

impl std::fmt::Display for Surface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Surface::Cylinder {
                radius_m,
                axis_angle_rad,
            } => write!(
                f,
                "cylinder of radius {} mm (axis at {:.1} deg)",
                millimetres(radius_m),
                axis_angle_rad.to_degrees()
            ),
            Surface::Sphere { radius_m } => {
                write!(f, "sphere of radius {} mm", millimetres(radius_m))
            }
            Surface::Flat => write!(f, "flat"),
        }
    }
}

impl Surface {
    /// Principal curvatures (κ', κ'') [1/m] and the direction of the first principal plane \[rad\].
    fn curvatures(&self) -> (f64, f64, f64) {
        match *self {
            Surface::Cylinder {
                radius_m,
                axis_angle_rad,
            } => (1.0 / radius_m, 0.0, axis_angle_rad),
            Surface::Sphere { radius_m } => (1.0 / radius_m, 1.0 / radius_m, 0.0),
            Surface::Flat => (0.0, 0.0, 0.0),
        }
    }

    /// Smallest radius of curvature \[m\] (infinite for a flat).
    pub fn smallest_radius_m(&self) -> f64 {
        match *self {
            Surface::Cylinder { radius_m, .. } | Surface::Sphere { radius_m } => radius_m,
            Surface::Flat => f64::INFINITY,
        }
    }
}

/// Complete elliptic integrals K(k) and E(k) of the first and second kind, with **modulus**
/// k ∈ [0, 1) (not the parameter m = k²), by the arithmetic–geometric mean. Accurate to ~1e-15.
pub fn complete_elliptic_integrals(modulus: f64) -> (f64, f64) {
    let complement = (1.0 - modulus * modulus).sqrt();
    let (k, s) = agm_k_sigma(complement);
    (k, k * (1.0 - modulus * modulus * s))
}

/// For the complementary modulus k' = b/a, returns K and S = Σ_n 2^{n−1} c_n² / e², where the
/// AGM identity gives K − E = K e² S. Working with S keeps full relative precision as e → 0.
fn agm_k_sigma(complement: f64) -> (f64, f64) {
    let e2 = 1.0 - complement * complement;
    let (mut a, mut b) = (1.0_f64, complement);
    // c_0 = e, so the n = 0 term is 1/2; c_n/e is tracked directly.
    let mut sum = 0.5;
    let mut c_over_e = 1.0_f64;
    let mut weight = 0.5;
    let e = e2.sqrt();
    for _ in 0..60 {
        let a_next = 0.5 * (a + b);
        // c_{n+1} = (a_n − b_n)/2 = c_n² / (4 a_{n+1})
        c_over_e = if e > 0.0 {
            c_over_e * (c_over_e * e) / (4.0 * a_next)
        } else {
            0.0
        };
        b = (a * b).sqrt();
        a = a_next;
        weight *= 2.0;
        let term = weight * c_over_e * c_over_e;
        sum += term;
        if term < 1e-17 * sum && (a - b).abs() < 1e-15 * a {
            break;
        }
    }
    (std::f64::consts::PI / (2.0 * a), sum)
}

/// The solved geometry of one Hertz contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzContact {
    /// Smaller gap coefficient A [1/m].
    pub a_per_m: f64,
    /// Larger gap coefficient B [1/m].
    pub b_per_m: f64,
    /// Eccentricity e of the contact ellipse [-].
    pub eccentricity: f64,
    /// Effective modulus E* \[Pa\].
    pub effective_modulus_pa: f64,
    /// Contact coefficient β of F = β δ^{3/2} [N/m^1.5].
    pub beta: f64,
}

impl HertzContact {
    /// The Hertz peak pressure p₀ \[Pa\] at the centre of the contact ellipse under a normal
    /// force F \[N\] (0 for F ≤ 0). With the approach δ = (F/β)^{2/3}, the ellipse's semi-axes
    /// a = sqrt(δ S/A) and b = a sqrt(1 − e²) and p₀ = E* δ / (b K(e)) (Johnson 1985 §4.2:
    /// δ = p₀ b K(e)/E*, F = (2/3)π a b p₀), S as in the module's AGM identity K − E = K e² S.
    /// For a circular contact this is (2E*/π) sqrt(δ/R).
    pub fn peak_pressure_pa(&self, force_n: f64) -> f64 {
        if force_n <= 0.0 || force_n.is_nan() {
            return 0.0;
        }
        let complement = (1.0 - self.eccentricity * self.eccentricity)
            .max(0.0)
            .sqrt();
        let (k, s) = agm_k_sigma(complement);
        let approach_m = (force_n / self.beta).libm_powf(2.0 / 3.0);
        let semi_major_m = (approach_m * s / self.a_per_m).sqrt();
        self.effective_modulus_pa * approach_m / (complement * semi_major_m * k)
    }
}

/// How the ellipse's shape is found from B/A.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EllipseSolution {
    /// Exact: solve the elliptic-integral relation (default).
    #[default]
    Exact,
    /// Greenwood's approximation b/a ≈ (B/A)^{-2/3}, as quoted by the paper.
    Greenwood,
}

/// Contact coefficient β [N/m^1.5] between two bodies, exact Hertz theory.
pub fn hertz_beta(s1: Surface, m1: &Material, s2: Surface, m2: &Material) -> Result<f64> {
    Ok(hertz_contact(s1, m1, s2, m2, EllipseSolution::Exact)?.beta)
}

/// Solves the Hertz contact of two bodies (see the module docs).
pub fn hertz_contact(
    s1: Surface,
    m1: &Material,
    s2: Surface,
    m2: &Material,
    solution: EllipseSolution,
) -> Result<HertzContact> {
    let (k1a, k1b, th1) = s1.curvatures();
    let (k2a, k2b, th2) = s2.curvatures();
    for (r, what) in [
        (s1.smallest_radius_m(), "first"),
        (s2.smallest_radius_m(), "second"),
    ] {
        if r.is_nan() || r <= 0.0 {
            return Err(Error::invalid(
                format!("{what} body radius_m"),
                r,
                "must be a finite number > 0",
            ));
        }
    }
    let d1 = k1a - k1b;
    let d2 = k2a - k2b;
    let phi = th1 - th2;
    let sum = 0.5 * (k1a + k1b + k2a + k2b);
    let diff_sq = d1 * d1 + d2 * d2 + 2.0 * d1 * d2 * (2.0 * phi).libm_cos();
    let diff = 0.5 * diff_sq.max(0.0).sqrt();
    let a = 0.5 * (sum - diff);
    let b = 0.5 * (sum + diff);
    if a.is_nan() || a <= 1e-9 * b || a <= 0.0 {
        return Err(Error::NotPointContact {
            what: format!("{s1} on {s2}"),
            reason: "one principal gap curvature is zero (line contact, e.g. parallel cylinders or a cylinder on a flat)".into(),
        });
    }
    let e_star = 1.0 / (m1.contact_compliance() + m2.contact_compliance());
    let ratio = b / a;
    let complement = match solution {
        EllipseSolution::Exact => solve_axis_ratio(ratio),
        EllipseSolution::Greenwood => ratio.libm_powf(-2.0 / 3.0),
    };
    let (k, s) = agm_k_sigma(complement);
    let beta = 2.0 * std::f64::consts::PI * e_star / 3.0 * (s / a).sqrt() / k;
    Ok(HertzContact {
        a_per_m: a,
        b_per_m: b,
        eccentricity: (1.0 - complement * complement).sqrt(),
        effective_modulus_pa: e_star,
        beta,
    })
}

/// The axis ratio b/a of the contact ellipse for a gap ratio B/A ≥ 1, by bisection on ln(b/a).
/// In terms of S (see [`agm_k_sigma`]), B/A = (1 − S) / ((b/a)² S), decreasing in b/a.
fn solve_axis_ratio(gap_ratio: f64) -> f64 {
    if gap_ratio <= 1.0 {
        return 1.0;
    }
    let g = |ln_s: f64| {
        let s = ln_s.libm_exp();
        let (_, sig) = agm_k_sigma(s);
        (1.0 - sig) / (s * s * sig)
    };
    // b/a from 4e-18 to 1; g decreases in ln(b/a).
    crate::root::bisect(-40.0, 0.0, |ln_s| g(ln_s) > gap_ratio).libm_exp()
}
