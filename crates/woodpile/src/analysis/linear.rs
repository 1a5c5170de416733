//! The exact linear frequency response of a finite preloaded chain (docs/physics.md §15): the
//! chain linearised about its static equilibrium, solved in the frequency domain.
//!
//! Each Hertz contact i carrying the static force F_i becomes a spring of tangent stiffness
//! K_i = (3/2) β_i δ_i^{1/2}, δ_i = (F_i/β_i)^{2/3}, with the damping ∂F/∂δ̇ of its law at δ_i
//! (`ContactLaw::linear_damping_n_s_per_m`); resonators keep their springs k_j and dampers
//! c_j = 2 ζ √(k_j m_j); on-site damping m/τ acts on every mass. With M, C, K the chain's mass,
//! damping and stiffness matrices and a force F on element 1,
//!
//! ```text
//! (K − ω² M + i ω C) X = F e_1,      F̂_wall = (K_N + i ω C_N) X_N,
//! ```
//!
//! solved per frequency without approximation: a resonator couples to its own primary mass only,
//! so its row is eliminated exactly (it adds s d / (s + d) to the primary's diagonal, s = k_j + iω
//! c_j, d = −ω² m_j + iω m_j/τ); the tridiagonal rest is eliminated from the wall up. The ratio
//! F̂_wall/F̂ is what `transmission` measures when the chirp is small and the record long enough.

use crate::error::{Error, Result};
use crate::math::Libm;
use crate::model::{Chain, ContactLaw};
use rustfft::num_complex::Complex64;
use std::f64::consts::PI;

/// One resonator, linear: mass, spring and the damper in parallel with it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearResonator {
    /// m_j \[kg\].
    pub mass_kg: f64,
    /// k_j \[N/m\].
    pub stiffness_n_per_m: f64,
    /// c_j = 2 ζ √(k_j m_j) \[N s/m\].
    pub damping_n_s_per_m: f64,
}

/// A chain linearised about its static equilibrium (elements top to bottom, contacts 1..=N, the
/// last one the wall's).
#[derive(Debug, Clone, PartialEq)]
pub struct LinearChain {
    /// Primary mass M_i of every element \[kg\].
    pub primary_mass_kg: Vec<f64>,
    /// Every element's resonators.
    pub resonators: Vec<Vec<LinearResonator>>,
    /// On-site damping rate 1/τ on every mass \[1/s\] (0: none).
    pub on_site_rate_per_s: f64,
    /// Tangent stiffness K_i of contacts 1..=N \[N/m\].
    pub contact_stiffness_n_per_m: Vec<f64>,
    /// Linearised damping C_i of contacts 1..=N \[N s/m\].
    pub contact_damping_n_s_per_m: Vec<f64>,
}

impl LinearChain {
    /// Linearises `chain` about its static equilibrium. Every contact must carry a static force
    /// (a preload) and the chain must stand on a wall.
    pub fn new(chain: &Chain) -> Result<Self> {
        let n = chain.len();
        let forces = chain.static_contact_forces_n();
        let wall_beta = chain.wall_beta().ok_or_else(|| {
            Error::invalid(
                "chain.wall",
                "free",
                "a linear response to the wall needs a wall contact",
            )
        })?;
        if let Some(c) = forces.iter().position(|&f| f.is_nan() || f <= 0.0) {
            return Err(Error::invalid(
                "preload.force_n",
                chain.preload().force_n,
                format!("contact {} carries no static force: a linearised Hertz contact has no stiffness without one (give preload.force_n > 0)", c + 1),
            ));
        }
        let damping = chain.damping();
        let v_in = damping.impact_speed_m_s.unwrap_or(f64::NAN);
        let primary: Vec<f64> = chain
            .elements()
            .iter()
            .map(|e| e.cell.primary_mass_kg)
            .collect();
        let mut stiffness = Vec::with_capacity(n);
        let mut dampers = Vec::with_capacity(n);
        for c in 0..n {
            let (beta, kind, reduced) = if c + 1 == n {
                (wall_beta, damping.wall_law(), primary[c])
            } else {
                let (a, b) = (primary[c], primary[c + 1]);
                (chain.inner_betas()[c], damping.contacts, a * b / (a + b))
            };
            let (law, coef) = ContactLaw::compile(kind, beta, reduced, v_in);
            if law == ContactLaw::HuntCrossley && v_in.is_nan() {
                return Err(Error::invalid(
                    "damping.impact_speed_m_s",
                    "(none)",
                    "the Hunt–Crossley law needs the impact speed v_in of its contacts: give it",
                ));
            }
            let overlap_m = (forces[c] / beta).libm_powf(2.0 / 3.0);
            stiffness.push(ContactLaw::stiffness_n_per_m(beta, overlap_m));
            dampers.push(law.linear_damping_n_s_per_m(coef, beta, overlap_m));
        }
        let resonators = chain
            .elements()
            .iter()
            .enumerate()
            .map(|(i, e)| {
                e.cell
                    .resonators
                    .iter()
                    .enumerate()
                    .map(|(j, r)| LinearResonator {
                        mass_kg: r.mass_kg,
                        stiffness_n_per_m: r.stiffness_n_per_m,
                        damping_n_s_per_m: 2.0
                            * damping.ratio_of(i + 1, j + 1)
                            * (r.stiffness_n_per_m * r.mass_kg).sqrt(),
                    })
                    .collect()
            })
            .collect();
        Ok(LinearChain {
            primary_mass_kg: primary,
            resonators,
            on_site_rate_per_s: damping.on_site_time_s.map_or(0.0, |tau| 1.0 / tau),
            contact_stiffness_n_per_m: stiffness,
            contact_damping_n_s_per_m: dampers,
        })
    }

    /// Dynamic stiffness of element `i` on its own (primary, on-site damping and its resonators
    /// eliminated) at angular frequency ω \[N/m\].
    fn element_dynamic_stiffness(&self, i: usize, omega: f64) -> Complex64 {
        let iw = Complex64::new(0.0, omega);
        let body = |m: f64| -omega * omega * m + iw * (m * self.on_site_rate_per_s);
        let mut d = body(self.primary_mass_kg[i]);
        for r in &self.resonators[i] {
            let s = r.stiffness_n_per_m + iw * r.damping_n_s_per_m;
            let own = body(r.mass_kg);
            d += s * own / (s + own);
        }
        d
    }

    /// F̂_wall / F̂_drive at `frequency_hz` for a force on element 1: the exact solution of
    /// (K − ω² M + iω C) X = F e_1.
    pub fn wall_per_drive(&self, frequency_hz: f64) -> Complex64 {
        let omega = 2.0 * PI * frequency_hz;
        let iw = Complex64::new(0.0, omega);
        let n = self.primary_mass_kg.len();
        let z =
            |c: usize| self.contact_stiffness_n_per_m[c] + iw * self.contact_damping_n_s_per_m[c];
        // Elimination from the wall up with X_N = 1: (below, here) = (X_{i+1}, X_i).
        let mut wall = z(n - 1);
        let (mut below, mut here) = (Complex64::new(0.0, 0.0), Complex64::new(1.0, 0.0));
        for i in (1..n).rev() {
            // Element i's balance gives the displacement of element i − 1 (indices from 0).
            let residual = self.element_dynamic_stiffness(i, omega) * here + z(i) * (here - below);
            let above = here + residual / z(i - 1);
            (below, here) = (here, above);
            let scale = here.norm();
            if scale > 1e100 {
                (below, here, wall) = (below / scale, here / scale, wall / scale);
            }
        }
        let drive = self.element_dynamic_stiffness(0, omega) * here + z(0) * (here - below);
        wall / drive
    }

    /// |F̂_wall / F̂_drive| at every frequency.
    pub fn transmission(&self, frequencies_hz: &[f64]) -> Vec<f64> {
        frequencies_hz
            .iter()
            .map(|&f| self.wall_per_drive(f).norm())
            .collect()
    }
}
