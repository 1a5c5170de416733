//! How the chain is loaded: a striker sphere hitting the top element, or a prescribed blast force.

use crate::defaults;
use crate::error::{require_non_negative, require_positive, Error, Result};
use crate::model::{hertz_beta, Chain, Material, Surface};

/// Standard gravity g [m/s²] used to turn a drop height into a velocity (docs/physics.md §2).
pub const STANDARD_GRAVITY_M_S2: f64 = defaults::GRAVITY_M_S2;

/// A sphere striking the top element; a body of the simulation with its own Hertz contact.
#[derive(Debug, Clone, PartialEq)]
pub struct Striker {
    /// Diameter \[m\].
    pub diameter_m: f64,
    /// Material.
    pub material: Material,
    /// Initial velocity v0 toward the chain [m/s].
    pub velocity_m_s: f64,
    /// Contact coefficient with the top element [N/m^1.5]; None = computed by Hertz theory.
    pub beta_override: Option<f64>,
}

impl Striker {
    /// The paper's striker: a 10 mm soda-lime glass sphere dropped from 0.20 m (docs/physics.md §2).
    pub fn paper() -> Self {
        Striker {
            diameter_m: defaults::STRIKER_DIAMETER_MM * 1e-3,
            material: Material::preset(defaults::STRIKER_MATERIAL).expect("preset exists"),
            velocity_m_s: velocity_from_drop_height(defaults::DROP_HEIGHT_M),
            beta_override: None,
        }
    }

    /// Mass ρ π d³/6 \[kg\].
    pub fn mass_kg(&self) -> f64 {
        self.material.density_kg_m3 * std::f64::consts::PI * self.diameter_m.powi(3) / 6.0
    }

    /// Contact coefficient with the top element of `chain` [N/m^1.5].
    pub fn contact_beta(&self, chain: &Chain) -> Result<f64> {
        match self.beta_override {
            Some(b) => require_positive("excitation.beta", b),
            None => hertz_beta(
                Surface::Sphere {
                    radius_m: 0.5 * self.diameter_m,
                },
                &self.material,
                chain.top_surface(),
                &chain.elements()[0].material,
            ),
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        require_positive("excitation.striker.diameter_m", self.diameter_m)?;
        require_positive("excitation.velocity_m_s", self.velocity_m_s)?;
        Ok(())
    }
}

/// v0 = sqrt(2 g h) [m/s] for a drop height h \[m\].
pub fn velocity_from_drop_height(height_m: f64) -> f64 {
    (2.0 * STANDARD_GRAVITY_M_S2 * height_m).sqrt()
}

/// A prescribed force history F(t) on the top element \[N\].
#[derive(Debug, Clone, PartialEq)]
pub enum BlastProfile {
    /// Friedlander positive phase F0 (1 − t/Td) exp(−b t/Td) on [0, Td], zero after (docs/physics.md §6).
    Friedlander {
        /// Peak force F0 \[N\].
        peak_force_n: f64,
        /// Positive-phase duration Td \[s\].
        duration_s: f64,
        /// Decay parameter b [-] (1 = classic Friedlander, 0 = triangle).
        decay: f64,
    },
    /// A table (t_k, F_k), linearly interpolated, zero outside [t_0, t_last].
    Table {
        /// Times, strictly increasing \[s\].
        times_s: Vec<f64>,
        /// Forces \[N\].
        forces_n: Vec<f64>,
    },
}

impl BlastProfile {
    /// The default blast of docs/physics.md §6: F0 = 200 N, Td = 0.2 ms, b = 1.
    pub fn paper() -> Self {
        BlastProfile::Friedlander {
            peak_force_n: defaults::BLAST_PEAK_FORCE_N,
            duration_s: defaults::BLAST_DURATION_S,
            decay: defaults::BLAST_DECAY,
        }
    }

    /// A validated table profile.
    pub fn table(times_s: Vec<f64>, forces_n: Vec<f64>) -> Result<Self> {
        let p = BlastProfile::Table { times_s, forces_n };
        p.validate()?;
        Ok(p)
    }

    /// Force F(t) \[N\].
    #[inline]
    pub fn force_n(&self, t: f64) -> f64 {
        match self {
            BlastProfile::Friedlander {
                peak_force_n,
                duration_s,
                decay,
            } => {
                if (0.0..=*duration_s).contains(&t) {
                    let x = t / duration_s;
                    peak_force_n * (1.0 - x) * (-decay * x).exp()
                } else {
                    0.0
                }
            }
            BlastProfile::Table { times_s, forces_n } => {
                let n = times_s.len();
                if t < times_s[0] || t > times_s[n - 1] {
                    return 0.0;
                }
                let k = times_s.partition_point(|&tk| tk <= t);
                if k >= n {
                    return forces_n[n - 1];
                }
                let (t0, t1) = (times_s[k - 1], times_s[k]);
                let (f0, f1) = (forces_n[k - 1], forces_n[k]);
                f0 + (f1 - f0) * (t - t0) / (t1 - t0)
            }
        }
    }

    /// Validates the parameters (fields named as in a scenario file).
    pub fn validate(&self) -> Result<()> {
        match self {
            BlastProfile::Friedlander {
                peak_force_n,
                duration_s,
                decay,
            } => {
                require_positive("excitation.peak_force_n", *peak_force_n)?;
                require_positive("excitation.duration_s", *duration_s)?;
                require_non_negative("excitation.decay", *decay)?;
            }
            BlastProfile::Table { times_s, forces_n } => {
                if times_s.len() < 2 || times_s.len() != forces_n.len() {
                    return Err(Error::invalid(
                        "excitation.table",
                        format!("{} times, {} forces", times_s.len(), forces_n.len()),
                        "needs at least two (t, F) rows",
                    ));
                }
                for (k, (&t, &f)) in times_s.iter().zip(forces_n).enumerate() {
                    if !t.is_finite() || !f.is_finite() {
                        return Err(Error::invalid(
                            format!("excitation.table row {}", k + 1),
                            format!("({t}, {f})"),
                            "time and force must be finite numbers",
                        ));
                    }
                    if k > 0 && t <= times_s[k - 1] {
                        return Err(Error::invalid(
                            format!("excitation.table row {} time", k + 1),
                            t,
                            format!(
                                "times must increase strictly (previous row has {})",
                                times_s[k - 1]
                            ),
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}

/// What drives the chain.
#[derive(Debug, Clone, PartialEq)]
pub enum Excitation {
    /// A striker sphere with an initial velocity.
    Impact(Striker),
    /// A prescribed force on the top element.
    Blast(BlastProfile),
}

impl Excitation {
    /// Validates the parameters.
    pub fn validate(&self) -> Result<()> {
        match self {
            Excitation::Impact(s) => s.validate(),
            Excitation::Blast(b) => b.validate(),
        }
    }
}
