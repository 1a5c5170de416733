//! Contact laws: the force, the potential energy, the stiffness and the dissipated power of one
//! contact, defined once and used by every instance of the solver (one run in `f64`, several in
//! SIMD lanes) and by the energy audit.
//!
//! Every law is the tension-free Hertz contact F_e = β δ₊^{3/2} (docs/physics.md §4), plus, for
//! the damped laws of docs/physics.md §14, a force proportional to the rate of overlap δ̇. A law is
//! compiled per contact ([`ContactLaw::compile`]) into its kind and one coefficient; the kind is
//! shared by every run of a lane group, the coefficient is per run. Adding a law: a variant here,
//! its force in `ContactLaw::force`, its compilation from [`ContactDamping`] in
//! [`ContactLaw::compile`] (docs/extending.md).

use crate::math::Libm;
use crate::model::ContactDamping;
use crate::real::Real;

/// The law of one contact, as the solver evaluates it. A closed set: the coefficient's meaning
/// depends on the variant ([`ContactLaw::compile`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub enum ContactLaw {
    /// F = β δ₊^{3/2}: lossless Hertz (the paper). No coefficient.
    #[default]
    Elastic,
    /// F = F_e + η δ̇ with η = coef δ^{1/4} (a coefficient of restitution e, docs/physics.md §14).
    Restitution,
    /// F = F_e (1 + λ δ̇) with λ = coef = χ / v_in \[s/m\] (Hunt–Crossley).
    HuntCrossley,
    /// F = F_e + coef δ^{1/2} δ̇ (viscoelastic Hertz, coef = (3/2) τ β).
    Viscoelastic,
}

impl ContactLaw {
    /// The law and its coefficient for a contact of coefficient β [N/m^1.5] between bodies of
    /// reduced mass `reduced_mass_kg`, hit at `impact_speed_m_s` (Hunt–Crossley's v_in). A damping
    /// law that dissipates nothing (e = 1, τ = 0) compiles to [`ContactLaw::Elastic`], so that a
    /// run with zero damping is the lossless run bit for bit.
    pub fn compile(
        damping: ContactDamping,
        beta: f64,
        reduced_mass_kg: f64,
        impact_speed_m_s: f64,
    ) -> (ContactLaw, f64) {
        match damping {
            ContactDamping::Restitution { coefficient } if coefficient < 1.0 => (
                ContactLaw::Restitution,
                ContactDamping::restitution_prefactor(coefficient)
                    * (beta * reduced_mass_kg).sqrt(),
            ),
            ContactDamping::HuntCrossley { restitution } if restitution < 1.0 => (
                ContactLaw::HuntCrossley,
                8.0 * (1.0 - restitution) / (5.0 * restitution) / impact_speed_m_s,
            ),
            ContactDamping::Viscoelastic { time_s } if time_s > 0.0 => {
                (ContactLaw::Viscoelastic, 1.5 * time_s * beta)
            }
            _ => (ContactLaw::Elastic, 0.0),
        }
    }

    /// Whether the law dissipates (its force depends on δ̇).
    pub fn is_damped(self) -> bool {
        self != ContactLaw::Elastic
    }

    /// The elastic force β δ₊^{3/2} \[N\] at signed overlap δ \[m\] (0 while open).
    #[inline(always)]
    pub(crate) fn elastic_force<R: Real>(beta: R, overlap_m: R) -> R {
        let dp = overlap_m.max(R::ZERO);
        beta * dp * dp.sqrt()
    }

    /// The force \[N\] at overlap δ and overlap rate δ̇, and the power it dissipates \[W\]:
    /// (force, dissipated power), both 0 while the contact is open. Tension-free unless
    /// `allow_pull`: a damped force that would pull is cut to zero.
    #[inline(always)]
    pub(crate) fn force<R: Real>(
        self,
        coef: R,
        beta: R,
        overlap_m: R,
        rate_m_s: R,
        allow_pull: bool,
    ) -> (R, R) {
        let dp = overlap_m.max(R::ZERO);
        let root = dp.sqrt();
        // β δ₊^{3/2}: the operations of [`ContactLaw::elastic_force`].
        let elastic = beta * dp * root;
        if self == ContactLaw::Elastic {
            return (elastic, R::ZERO);
        }
        let damping = match self {
            ContactLaw::Elastic => R::ZERO,
            ContactLaw::Restitution => coef * root.sqrt() * rate_m_s,
            ContactLaw::HuntCrossley => elastic * coef * rate_m_s,
            ContactLaw::Viscoelastic => coef * root * rate_m_s,
        };
        let mut f = elastic + damping;
        if !allow_pull {
            f = f.if_negative(R::ZERO, f);
        }
        let dissipated = (f - elastic) * rate_m_s;
        (
            overlap_m.if_positive(f, R::ZERO),
            overlap_m.if_positive(dissipated, R::ZERO),
        )
    }

    /// The damping coefficient ∂F/∂δ̇ \[N s/m\] of the law linearised about a closed contact at
    /// rest at overlap δ > 0 (docs/physics.md §15): restitution coef δ^{1/4}, Hunt–Crossley
    /// β δ^{3/2} coef, viscoelastic coef δ^{1/2}; 0 while open or elastic.
    pub fn linear_damping_n_s_per_m(self, coef: f64, beta: f64, overlap_m: f64) -> f64 {
        if overlap_m <= 0.0 {
            return 0.0;
        }
        match self {
            ContactLaw::Elastic => 0.0,
            ContactLaw::Restitution => coef * overlap_m.sqrt().sqrt(),
            ContactLaw::HuntCrossley => beta * overlap_m * overlap_m.sqrt() * coef,
            ContactLaw::Viscoelastic => coef * overlap_m.sqrt(),
        }
    }

    /// The elastic potential (2/5) β δ₊^{5/2} \[J\].
    #[inline]
    pub(crate) fn potential_j(beta: f64, overlap_m: f64) -> f64 {
        if overlap_m > 0.0 {
            0.4 * beta * overlap_m * overlap_m * overlap_m.sqrt()
        } else {
            0.0
        }
    }

    /// The tangent stiffness dF_e/dδ = (3/2) β δ₊^{1/2} \[N/m\].
    #[inline]
    pub(crate) fn stiffness_n_per_m(beta: f64, overlap_m: f64) -> f64 {
        1.5 * beta * overlap_m.max(0.0).sqrt()
    }

    /// The Hertz contact time \[s\] of a mass `mass_kg` meeting a rigid half-space through β at
    /// `speed_m_s`: 2.94 δ_max / v with δ_max = (5 m v² / (4 β))^{2/5} (Johnson, *Contact
    /// Mechanics*, §11.4).
    pub fn elastic_contact_time_s(beta: f64, mass_kg: f64, speed_m_s: f64) -> f64 {
        let delta_max = (1.25 * mass_kg * speed_m_s * speed_m_s / beta).libm_powf(0.4);
        2.94 * delta_max / speed_m_s
    }

    /// The rate dF_e/dt [N/s] of the elastic force `force_n` at overlap δ and rate δ̇:
    /// (3/2) F δ̇ / δ while closed, 0 while open.
    #[inline(always)]
    pub(crate) fn elastic_force_rate(force_n: f64, overlap_m: f64, rate_m_s: f64) -> f64 {
        if overlap_m > 0.0 {
            1.5 * force_n * rate_m_s / overlap_m
        } else {
            0.0
        }
    }
}
