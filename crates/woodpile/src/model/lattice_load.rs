//! What loads and dissipates a lattice (docs/physics.md §16): the striker, a blast or a force
//! drive split equally over load points of the top layer, a displacement actuator pressing on
//! them through a tip at each, or nothing; the chains' contact laws
//! at every contact, damping of the rods' modes, and a static load (a preload on the load points
//! and gravity) that the run starts in equilibrium with.

use super::lab::{Damping, Preload};
use super::lattice::{Lattice, RodPoint};
use super::Wall;
use crate::error::{require_non_negative, Error, Result};
use crate::excitation::{BlastProfile, Drive, DriveQuantity, Excitation, Striker};

/// Where a blast, a drive or a preload acts on the top layer.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum LoadPoints {
    /// Every crossing of the top layer with the layer below it (`points = "top-crossings"`):
    /// the points where the top rods bear on the lattice.
    #[default]
    TopCrossings,
    /// The given (x, y) points \[m\], each on a top rod (`points_mm = [[x, y], …]`).
    Points(Vec<[f64; 2]>),
}

impl LoadPoints {
    /// The points on the top rods' axes, in order (the crossings in the lattice's contact
    /// order); errors name `excitation.points` or `excitation.points_mm[k]`.
    pub fn on(&self, lattice: &Lattice) -> Result<Vec<RodPoint>> {
        match self {
            LoadPoints::TopCrossings => {
                let points: Vec<RodPoint> = lattice
                    .contacts
                    .iter()
                    .filter(|c| c.below.is_some() && lattice.rods[c.above.rod].layer == 1)
                    .map(|c| c.above)
                    .collect();
                if points.is_empty() {
                    return Err(Error::invalid(
                        "excitation.points",
                        "\"top-crossings\"",
                        "a lattice of one layer has no crossings: give the load points as points_mm = [[x, y], …] (mm, each on a rod)",
                    ));
                }
                Ok(points)
            }
            LoadPoints::Points(p) => {
                if p.is_empty() {
                    return Err(Error::invalid(
                        "excitation.points_mm",
                        "[]",
                        "give at least one point [x, y] (mm) on a rod of the top layer",
                    ));
                }
                p.iter()
                    .enumerate()
                    .map(|(k, &xy)| {
                        lattice.top_point(xy, "excitation.points_mm").map_err(|_| {
                            Error::invalid(
                                format!("excitation.points_mm[{k}]"),
                                format!("[{}, {}]", xy[0] * 1e3, xy[1] * 1e3),
                                "the load point (x, y in mm) lies on no rod of the top layer (within a rod's length and radius)",
                            )
                        })
                    })
                    .collect()
            }
        }
    }
}

/// What drives a lattice.
#[derive(Debug, Clone, PartialEq)]
pub enum LatticeExcitation {
    /// The striker hits the top rod under `at_m` = (x, y) \[m\].
    Impact {
        /// The striker.
        striker: Striker,
        /// The impact point \[m\].
        at_m: [f64; 2],
    },
    /// A blast: the profile's force F(t) is the total, F(t)/N on each of the N points.
    Blast {
        /// The force history of the whole lattice.
        profile: BlastProfile,
        /// Where it acts.
        points: LoadPoints,
    },
    /// A drive. A force: the ramped signal is the total force, 1/N of it on each point. A
    /// displacement: one rigid actuator whose prescribed position u(t) (the ramped signal,
    /// downward) presses on every point through a Hertz contact of its tip (a fixed-geometry
    /// support like the sensor, the chains' `excitation.tip`), tension-free, overlap
    /// δ_c = δ_c⁰ + u(t) − w_top(point) (δ_c⁰: the share 1/N of a preload).
    Drive {
        /// The drive (a force or a displacement).
        drive: Drive,
        /// Where it acts.
        points: LoadPoints,
    },
    /// Nothing moves the lattice (with a static load: a check of its equilibrium); a preload
    /// acts on the points.
    Rest {
        /// Where a preload acts.
        points: LoadPoints,
    },
}

impl LatticeExcitation {
    /// The load points of a blast, drive or rest (None for an impact).
    pub fn load_points(&self) -> Option<&LoadPoints> {
        match self {
            LatticeExcitation::Impact { .. } => None,
            LatticeExcitation::Blast { points, .. }
            | LatticeExcitation::Drive { points, .. }
            | LatticeExcitation::Rest { points } => Some(points),
        }
    }

    /// The chain's excitation of the same kind and history (for its checks against a run).
    pub fn as_chain_excitation(&self) -> Excitation {
        match self {
            LatticeExcitation::Impact { striker, .. } => Excitation::Impact(striker.clone()),
            LatticeExcitation::Blast { profile, .. } => Excitation::Blast(profile.clone()),
            LatticeExcitation::Drive { drive, .. } => Excitation::Drive(drive.clone()),
            LatticeExcitation::Rest { .. } => Excitation::Rest,
        }
    }

    /// The tip of a displacement drive's actuator (None for any other excitation).
    pub fn actuator_tip(&self) -> Option<&Wall> {
        match self {
            LatticeExcitation::Drive {
                drive:
                    Drive {
                        quantity: DriveQuantity::Displacement { tip },
                        ..
                    },
                ..
            } => Some(tip),
            _ => None,
        }
    }

    /// Validates the excitation: a displacement actuator needs a tip that touches (not free).
    pub fn validate(&self) -> Result<()> {
        if self.actuator_tip() == Some(&Wall::Free) {
            return Err(Error::invalid(
                "excitation.tip.kind",
                "\"free\"",
                "a displacement actuator pushes through its tip: give kind = \"cap\", \"flat\" or \"beta\"",
            ));
        }
        self.as_chain_excitation().validate()
    }

    /// The total prescribed force at t \[N\] (a blast's F(t), a force drive's ramped signal; 0
    /// for an impact, rest or a displacement drive), before the preload is added.
    #[inline]
    pub fn total_force_n(&self, t: f64) -> f64 {
        match self {
            LatticeExcitation::Blast { profile, .. } => profile.force_n(t),
            LatticeExcitation::Drive { drive, .. } if drive.quantity == DriveQuantity::Force => {
                drive.value_and_rate(t).0
            }
            _ => 0.0,
        }
    }
}

/// The dissipation and static load of a lattice. `LatticeLab::default()` is none: the lossless,
/// unloaded lattice of the paper's physics.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LatticeLab {
    /// The chain's damping: contact laws (`contacts` at every crossing, `striker` at the
    /// striker's contact or a displacement actuator's tips, `wall` at every support), `allow_pull`, the Hunt–Crossley
    /// `impact_speed_m_s`, and `on_site_time_s` (−m u̇/τ on every point of every rod: in modal
    /// coordinates −q̇_j/τ on every mode). Its resonator ratios must be zero (a lattice's rods
    /// have no resonators: [`LatticeLab::modal_ratio`] damps their modes).
    pub damping: Damping,
    /// Damping ratio ζ of every elastic free–free mode of every rod: −2 ζ ω_j q̇_j.
    pub modal_ratio: f64,
    /// Preload (on the load points, 1/N on each — through the actuator's tips under a
    /// displacement drive, in the shares of the static equilibrium — or every top-layer
    /// crossing beside a striker) and gravity.
    pub preload: Preload,
}

impl LatticeLab {
    /// Whether the lattice is lossless and unloaded.
    pub fn is_none(&self) -> bool {
        self.damping.is_lossless() && self.modal_ratio == 0.0 && self.preload.is_none()
    }

    /// Validates every field, named as in a scenario's `[damping]` and `[preload]` tables.
    pub fn validate(&self) -> Result<()> {
        let d = &self.damping;
        if d.resonator_ratio != 0.0 {
            return Err(Error::invalid(
                "damping.resonator_ratio",
                d.resonator_ratio,
                "a lattice's rods have no resonators: damp their modes with damping.modal_ratio (ζ of every elastic mode) or damping.on_site_time_s",
            ));
        }
        if !d.resonator_overrides.is_empty() {
            return Err(Error::invalid(
                "damping.resonators",
                format!("{} entries", d.resonator_overrides.len()),
                "a lattice's rods have no resonators: damp their modes with damping.modal_ratio or damping.on_site_time_s",
            ));
        }
        d.validate(&[])?;
        require_non_negative("damping.modal_ratio", self.modal_ratio)?;
        self.preload.validate()
    }
}
