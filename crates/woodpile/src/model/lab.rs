//! The physics of a real lab, beyond the paper's lossless, unloaded column (docs/physics.md §14):
//! dissipation ([`Damping`]) and a static load ([`Preload`]: a force on the top element and
//! gravity along the column).
//!
//! Both default to nothing, and then a run is the paper's model bit for bit (the runner keeps a
//! separate, unchanged code path for it).
//!
//! ## Contact damping laws
//! With δ the overlap, δ̇ its rate (positive while compressing) and F_el = β δ^{3/2}:
//!
//! | law | contact force | source |
//! | --- | --- | --- |
//! | restitution e | F_el + η δ̇, η = 2 √(5/6) (−ln e)/√(π² + ln² e) · √((3/2) β δ^{1/2} m_eff) | Tsuji et al. 1992; LAMMPS `coeff_restitution` |
//! | Hunt–Crossley e | F_el (1 + χ δ̇ / v_in), χ = 8 (1 − e) / (5 e), one v_in for all contacts | Hunt & Crossley 1975; Flores et al. 2011 |
//! | viscoelastic A | F_el + (3/2) A β δ^{1/2} δ̇ | Kuwabara & Kono 1987; Brilliantov et al. 1996 |
//!
//! m_eff is the reduced mass of the two *primary* masses in contact (the element's primary mass
//! alone at the wall or an actuator): resonators are bodies hidden inside the element. The
//! restitution law's damping grows as δ^{1/4}, which makes the rebound of a binary collision
//! exactly e at every impact speed while the force may pull; [`Damping::allow_pull`] says
//! whether it may.

use crate::error::{require_non_negative, require_positive, Error, Result};
use crate::math::Libm;

/// How a contact dissipates energy.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ContactDamping {
    /// Lossless Hertz contact (the paper).
    #[default]
    None,
    /// The damping that gives a binary Hertz collision the coefficient of restitution e
    /// (LAMMPS `coeff_restitution`): F = β δ^{3/2} + η δ̇ with η ∝ δ^{1/4}.
    Restitution {
        /// Coefficient of restitution e, 0 < e ≤ 1.
        coefficient: f64,
    },
    /// Hunt–Crossley with Flores' coefficient: F = β δ^{3/2} (1 + χ δ̇ / v_in), χ = 8(1 − e)/(5e),
    /// with one impact speed v_in for every contact ([`Damping::impact_speed_m_s`]).
    HuntCrossley {
        /// The coefficient of restitution e the χ of Flores et al. aims at, 0 < e ≤ 1.
        restitution: f64,
    },
    /// Viscoelastic spheres (Kuwabara–Kono, Brilliantov): F = β (δ^{3/2} + (3/2) A δ^{1/2} δ̇).
    Viscoelastic {
        /// Dissipative time A \[s\] (a function of the material's viscosities).
        time_s: f64,
    },
}

impl ContactDamping {
    /// Whether the law dissipates nothing.
    pub fn is_none(&self) -> bool {
        matches!(self, ContactDamping::None)
    }

    /// The name used in files.
    pub fn name(&self) -> &'static str {
        match self {
            ContactDamping::None => "none",
            ContactDamping::Restitution { .. } => "restitution",
            ContactDamping::HuntCrossley { .. } => "hunt-crossley",
            ContactDamping::Viscoelastic { .. } => "viscoelastic",
        }
    }

    fn validate(&self, field: &str) -> Result<()> {
        match *self {
            ContactDamping::None => Ok(()),
            ContactDamping::Restitution { coefficient: e }
            | ContactDamping::HuntCrossley { restitution: e } => {
                if e.is_finite() && e > 0.0 && e <= 1.0 {
                    Ok(())
                } else {
                    Err(Error::invalid(
                        format!("{field}.restitution"),
                        e,
                        "a coefficient of restitution lies in (0, 1] (1 = lossless)",
                    ))
                }
            }
            ContactDamping::Viscoelastic { time_s } => {
                require_non_negative(&format!("{field}.viscous_time_s"), time_s).map(|_| ())
            }
        }
    }

    /// Restitution-law prefactor 2 √(5/6) (−ln e)/√(π² + ln² e) · √(3/2): multiplied by
    /// √(β m_eff) δ^{1/4} it gives η.
    pub(crate) fn restitution_prefactor(e: f64) -> f64 {
        let l = e.libm_ln();
        2.0 * (5.0_f64 / 6.0).sqrt() * (-l) / (std::f64::consts::PI.powi(2) + l * l).sqrt()
            * 1.5_f64.sqrt()
    }
}

/// A damping ratio for one resonator, overriding [`Damping::resonator_ratio`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ResonatorDamping {
    /// Element, numbered from 1 at the top.
    pub element: usize,
    /// Resonator of that element's cell, numbered from 1.
    pub resonator: usize,
    /// Damping ratio ζ ≥ 0.
    pub ratio: f64,
}

/// Every dissipation of a run. `Damping::default()` is the paper's lossless model.
#[derive(Debug, Clone, PartialEq)]
pub struct Damping {
    /// Law of the contacts between elements.
    pub contacts: ContactDamping,
    /// Law of the striker's (or an actuator's) contact; `None` = [`Damping::contacts`].
    pub striker: Option<ContactDamping>,
    /// Law of the wall contact; `None` = [`Damping::contacts`].
    pub wall: Option<ContactDamping>,
    /// Whether the total contact force may become tensile near separation (LAMMPS without
    /// `limit_damping`). Default false: contacts never pull, as the model's Hertz contacts are
    /// tension-free; the restitution law then rebounds slightly faster than e (docs/physics.md §14).
    pub allow_pull: bool,
    /// Damping ratio ζ of every resonator: c_j = 2 ζ √(k_j m_j).
    pub resonator_ratio: f64,
    /// Per-resonator ratios.
    pub resonator_overrides: Vec<ResonatorDamping>,
    /// On-site (background) damping time τ \[s\]: a force −m u̇/τ on every mass of every element.
    pub on_site_time_s: Option<f64>,
    /// The impact speed v_in of the Hunt–Crossley law [m/s], the same for every contact; `None`
    /// = the striker's speed v0 (required without a striker). A chain's contacts touch at rest
    /// and close smoothly, so their own approach speeds would be ~0: one reference speed keeps
    /// the damping coefficient λ = χ / v_in a constant of the material, as Hunt and Crossley had it.
    pub impact_speed_m_s: Option<f64>,
}

impl Default for Damping {
    fn default() -> Self {
        Damping {
            contacts: ContactDamping::None,
            striker: None,
            wall: None,
            allow_pull: false,
            resonator_ratio: 0.0,
            resonator_overrides: Vec::new(),
            on_site_time_s: None,
            impact_speed_m_s: None,
        }
    }
}

impl Damping {
    /// Whether nothing dissipates.
    pub fn is_lossless(&self) -> bool {
        self.contacts.is_none()
            && self.striker.is_none_or(|d| d.is_none())
            && self.wall.is_none_or(|d| d.is_none())
            && self.resonator_ratio == 0.0
            && self.resonator_overrides.iter().all(|o| o.ratio == 0.0)
            && self.on_site_time_s.is_none()
    }

    /// The law of the striker's or actuator's contact.
    pub fn striker_law(&self) -> ContactDamping {
        self.striker.unwrap_or(self.contacts)
    }

    /// The law of the wall contact.
    pub fn wall_law(&self) -> ContactDamping {
        self.wall.unwrap_or(self.contacts)
    }

    /// Damping ratio of resonator `resonator` (from 1) of element `element` (from 1).
    pub fn ratio_of(&self, element: usize, resonator: usize) -> f64 {
        self.resonator_overrides
            .iter()
            .rev()
            .find(|o| o.element == element && o.resonator == resonator)
            .map_or(self.resonator_ratio, |o| o.ratio)
    }

    /// Validates every field against a chain whose element `i` (from 0) has `resonators[i]`
    /// resonators. Fields are named as in a scenario's `[damping]` table.
    pub fn validate(&self, resonators: &[usize]) -> Result<()> {
        self.contacts.validate("damping")?;
        if let Some(d) = &self.striker {
            d.validate("damping.striker")?;
        }
        if let Some(d) = &self.wall {
            d.validate("damping.wall")?;
        }
        require_non_negative("damping.resonator_ratio", self.resonator_ratio)?;
        for (k, o) in self.resonator_overrides.iter().enumerate() {
            let field = format!("damping.resonators[{k}]");
            let n = resonators.len();
            if o.element == 0 || o.element > n {
                return Err(Error::invalid(
                    format!("{field}.element"),
                    o.element,
                    format!("elements are numbered 1..={n} from the top"),
                ));
            }
            let r = resonators[o.element - 1];
            if o.resonator == 0 || o.resonator > r {
                return Err(Error::invalid(
                    format!("{field}.resonator"),
                    o.resonator,
                    if r == 0 {
                        format!("element {} has no resonators (a rigid cell)", o.element)
                    } else {
                        format!("element {} has resonators 1..={r}", o.element)
                    },
                ));
            }
            require_non_negative(&format!("{field}.ratio"), o.ratio)?;
            let earlier = self.resonator_overrides[..k]
                .iter()
                .position(|e| (e.element, e.resonator) == (o.element, o.resonator));
            if let Some(j) = earlier {
                return Err(Error::invalid(
                    format!("{field}.resonator"),
                    o.resonator,
                    format!(
                        "resonator {} of element {} is already damped by damping.resonators[{j}] (ratio {}); give each resonator once",
                        o.resonator, o.element, self.resonator_overrides[j].ratio
                    ),
                ));
            }
        }
        if let Some(tau) = self.on_site_time_s {
            require_positive("damping.on_site_time_s", tau)?;
        }
        if let Some(v) = self.impact_speed_m_s {
            require_positive("damping.impact_speed_m_s", v)?;
        }
        Ok(())
    }
}

/// A static load on the column: a force on the top element and gravity along the column (the
/// column standing vertically, top element highest). `Preload::default()` is none (the paper).
///
/// The run starts from the exact static equilibrium: contact i carries
/// F_i = F_p + g Σ_{k ≤ i} M_k (M_k the total mass of element k) and its overlap is
/// δ_i = (F_i/β_i)^{2/3}.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Preload {
    /// Static force F_p on the top element, toward the wall \[N\].
    pub force_n: f64,
    /// Gravity g along the column, toward the wall \[m/s²\] (9.81 for a column on a table).
    pub gravity_m_s2: f64,
}

impl Preload {
    /// Whether there is no static load.
    pub fn is_none(&self) -> bool {
        self.force_n == 0.0 && self.gravity_m_s2 == 0.0
    }

    /// Validates the fields (named as in a scenario's `[preload]` table).
    pub fn validate(&self) -> Result<()> {
        require_non_negative("preload.force_n", self.force_n)?;
        require_non_negative("preload.gravity_m_s2", self.gravity_m_s2)?;
        Ok(())
    }
}
