//! Unit cells: a primary mass M carrying internal spring–mass resonators (m_j, k_j), the paper's
//! model of a rod and its symmetric bending modes (paper §3.1, Table 1; docs/physics.md §3).
//!
//! For harmonic motion at angular frequency ω, with ω_j² = k_j/m_j, the cell behaves as one mass
//!
//! ```text
//! M_eff(ω) = M + Σ_j m_j ω_j² / (ω_j² − ω²)
//! ```
//!
//! which is the total mass at ω = 0, has poles at the local resonances ω_j and is negative on
//! ω_j < ω < Ω_j, where the zeros Ω_j are the resonances of the free cell.
//!
//! ## References
//! - Kim, Yang et al., Int. J. Impact Eng. 2017, Eqs. 1–4 and Table 1.
//! - H. H. Huang, C. T. Sun, G. L. Huang, "On the negative effective mass density in acoustic
//!   metamaterials", Int. J. Eng. Sci. 47 (2009) 610–617.

use crate::error::{require_positive, Error, Result};
use std::f64::consts::PI;

/// One internal resonator: an auxiliary mass on a spring attached to the primary mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resonator {
    /// Auxiliary mass m_j \[kg\].
    pub mass_kg: f64,
    /// Spring stiffness k_j [N/m].
    pub stiffness_n_per_m: f64,
}

impl Resonator {
    /// Local resonance ω_j = sqrt(k_j/m_j) [rad/s].
    pub fn angular_frequency(&self) -> f64 {
        (self.stiffness_n_per_m / self.mass_kg).sqrt()
    }
}

/// A unit cell: primary mass M plus any number of resonators.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitCell {
    /// Primary mass M \[kg\].
    pub primary_mass_kg: f64,
    /// Internal resonators, in order of increasing frequency for the catalogue cells.
    pub resonators: Vec<Resonator>,
}

/// Rod lengths of the paper's Table 1 \[mm\].
pub const TABLE1_LENGTHS_MM: [u32; 7] = [20, 30, 40, 50, 60, 70, 80];

/// The paper's blast-optimised chain of Table 1 rods (docs/physics.md §9), top to bottom \[mm\]: the
/// default job and the benchmark problem.
pub const PAPER_OPTIMIZED_CHAIN_MM: [u32; 20] = [
    50, 80, 80, 80, 60, 70, 80, 80, 40, 30, 40, 40, 40, 30, 50, 40, 20, 20, 30, 50,
];

/// A Table 1 row: (length mm, M g, [(m_j g, k_j kN/mm)]).
type Table1Row = (u32, f64, &'static [(f64, f64)]);

/// Table 1 of the paper.
const TABLE1: [Table1Row; 7] = [
    (20, 0.423, &[(0.443, 26.27)]),
    (30, 0.570, &[(0.729, 8.782)]),
    (40, 0.838, &[(0.894, 3.961)]),
    (50, 0.450, &[(1.350, 2.008), (0.365, 18.31)]),
    (60, 0.600, &[(1.600, 1.172), (0.398, 11.31)]),
    (70, 0.750, &[(1.850, 0.748), (0.431, 7.263)]),
    (80, 1.00, &[(1.800, 0.532), (0.664, 6.423)]),
];

/// Whether a rod keeps its internal resonators or is one rigid body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CellModel {
    /// Primary mass plus resonators (the paper's locally resonant model).
    #[default]
    Resonant,
    /// One body of the total mass ("infinite k_ij": the paper's reference case).
    Rigid,
}

impl CellModel {
    /// Applies the model to a cell.
    pub fn apply(self, cell: UnitCell) -> UnitCell {
        match self {
            CellModel::Resonant => cell,
            CellModel::Rigid => cell.rigid(),
        }
    }
}

impl UnitCell {
    /// A validated user-defined cell.
    pub fn new(primary_mass_kg: f64, resonators: Vec<Resonator>) -> Result<Self> {
        require_positive("cell.primary_mass_kg", primary_mass_kg)?;
        for (j, r) in resonators.iter().enumerate() {
            require_positive(&format!("cell.resonators[{j}].mass_kg"), r.mass_kg)?;
            require_positive(
                &format!("cell.resonators[{j}].stiffness_n_per_m"),
                r.stiffness_n_per_m,
            )?;
        }
        Ok(UnitCell {
            primary_mass_kg,
            resonators,
        })
    }

    /// A single rigid body of mass `mass_kg`.
    pub fn rigid_body(mass_kg: f64) -> Result<Self> {
        Self::new(mass_kg, Vec::new())
    }

    /// The cell of a fused-quartz rod (diameter 5 mm) of the paper's Table 1.
    pub fn table1(length_mm: u32) -> Result<Self> {
        let (_, m, res) = TABLE1
            .iter()
            .find(|row| row.0 == length_mm)
            .ok_or_else(|| Error::Unknown {
                what: "rod length (mm) of the Table 1 catalogue",
                name: length_mm.to_string(),
                valid: TABLE1_LENGTHS_MM.map(|l| l.to_string()).join(", "),
            })?;
        Ok(UnitCell {
            primary_mass_kg: m * 1e-3,
            resonators: res
                .iter()
                .map(|&(mj, kj)| Resonator {
                    mass_kg: mj * 1e-3,
                    stiffness_n_per_m: kj * 1e6,
                })
                .collect(),
        })
    }

    /// The rigid variant: one body of the total mass.
    pub fn rigid(&self) -> UnitCell {
        UnitCell {
            primary_mass_kg: self.total_mass_kg(),
            resonators: Vec::new(),
        }
    }

    /// Total mass M + Σ m_j \[kg\].
    pub fn total_mass_kg(&self) -> f64 {
        self.primary_mass_kg + self.resonators.iter().map(|r| r.mass_kg).sum::<f64>()
    }

    /// Damped effective mass M_eff(ω) = M + Σ_j m_j (k_j + iωc_j)/(k_j + iωc_j − ω² m_j) \[kg\], with
    /// c_j = 2 ζ √(k_j m_j) for every resonator (docs/physics.md §14): complex, Im ≤ 0 (the cell
    /// absorbs power), finite at the local resonances for ζ > 0; ζ = 0 gives
    /// [`UnitCell::effective_mass_kg`].
    pub fn damped_effective_mass_kg(
        &self,
        omega: f64,
        ratio: f64,
    ) -> rustfft::num_complex::Complex64 {
        use rustfft::num_complex::Complex64;
        let w2 = omega * omega;
        self.resonators
            .iter()
            .map(|r| {
                let c = 2.0 * ratio * (r.stiffness_n_per_m * r.mass_kg).sqrt();
                let spring = Complex64::new(r.stiffness_n_per_m, omega * c);
                r.mass_kg * spring / (spring - w2 * r.mass_kg)
            })
            .sum::<Complex64>()
            + self.primary_mass_kg
    }

    /// Effective mass M_eff(ω) \[kg\] at angular frequency ω [rad/s] (infinite at a local resonance).
    pub fn effective_mass_kg(&self, omega: f64) -> f64 {
        let w2 = omega * omega;
        self.primary_mass_kg
            + self
                .resonators
                .iter()
                .map(|r| {
                    let wj2 = r.stiffness_n_per_m / r.mass_kg;
                    r.mass_kg * wj2 / (wj2 - w2)
                })
                .sum::<f64>()
    }

    /// Local resonances f_j = ω_j/2π \[Hz\], ascending.
    pub fn local_resonances_hz(&self) -> Vec<f64> {
        let mut f: Vec<f64> = self
            .resonators
            .iter()
            .map(|r| r.angular_frequency() / (2.0 * PI))
            .collect();
        f.sort_by(f64::total_cmp);
        f
    }

    /// Free-cell resonances F_j \[Hz\]: the zeros of M_eff, ascending. M_eff increases with ω between
    /// consecutive poles (every term does), going from −∞ to +∞ (or to M > 0 above the last pole),
    /// so there is exactly one zero above each pole: found by bisection in ω².
    pub fn free_resonances_hz(&self) -> Vec<f64> {
        let poles: Vec<f64> = self
            .local_resonances_hz()
            .iter()
            .map(|f| (2.0 * PI * f).powi(2))
            .collect();
        let meff = |w2: f64| self.effective_mass_kg(w2.sqrt());
        (0..poles.len())
            .map(|j| {
                let lo0 = poles[j];
                let hi0 = if j + 1 < poles.len() {
                    poles[j + 1]
                } else {
                    // Above the last pole M_eff ≤ M + Σ m_j ω_j²/(ω_j² − ω²) → M; find a bracket.
                    let mut hi = 2.0 * lo0;
                    while meff(hi) < 0.0 {
                        hi *= 2.0;
                    }
                    hi
                };
                crate::root::bisect(lo0, hi0, |w2| meff(w2) < 0.0).sqrt() / (2.0 * PI)
            })
            .collect()
    }

    /// Negative-effective-mass bands (f_j, F_j) \[Hz\].
    pub fn negative_mass_bands_hz(&self) -> Vec<(f64, f64)> {
        self.local_resonances_hz()
            .into_iter()
            .zip(self.free_resonances_hz())
            .collect()
    }
}
