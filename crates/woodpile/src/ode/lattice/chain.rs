//! A chain as a contact graph (docs/physics.md §16, "A column"): every element — a Table 1
//! cell, a beam-theory or finite-element rod's cell, a sphere, a user's cell — a body of one
//! point, its primary, in the free–free modes of its primary and resonators
//! ([`crate::ode::modal`]'s `ElementModes`, mass-normalised: q_k = √μ_k c_k, so the primary's
//! row is 1/√μ_k); the striker a body of one coordinate; the chain's contacts, striker to wall,
//! in the chain's order, the wall a support under the last element. The graph then runs any
//! lossless chain under its striker by the lattice's path ([`crate::simulate::simulate_lattice`])
//! with the chain's numbers.

use super::{LatticeOde, Side};
use crate::error::{Error, Result};
use crate::excitation::{Excitation, Striker};
use crate::model::Chain;
use crate::ode::modal::ElementModes;
use crate::ode::ChainOde;

impl LatticeOde {
    /// The lossless chain `chain` on its wall struck by `striker` as a contact graph. Errors
    /// name the keys: damping or a static load (`damping`, `preload`, gravity), a free end
    /// (`wall`), two resonators of one cell at one frequency (`cell.resonators`).
    pub fn from_chain(chain: &Chain, striker: &Striker) -> Result<Self> {
        let compiled = ChainOde::new(chain, &Excitation::Impact(striker.clone()))?;
        if compiled.has_lab_physics() {
            return Err(Error::invalid(
                "damping",
                "lab physics",
                "a chain becomes a contact graph lossless and unloaded (no damping, preload or \
                 gravity)",
            ));
        }
        if chain.wall_beta().is_none() {
            return Err(Error::invalid(
                "wall",
                "free",
                "a chain becomes a contact graph on a wall (its support)",
            ));
        }
        let m_s = striker.mass_kg();
        let mut ode = LatticeOde {
            omega2: vec![0.0],
            above: Vec::new(),
            below: Vec::new(),
            beta: Vec::new(),
            rows: vec![1.0 / m_s.sqrt()],
            supports: Vec::new(),
            bodies: vec![(0, 1, [0.0, 0.0], [1.0, 0.0])],
            translation: vec![m_s.sqrt()],
            rocking: vec![0.0],
            overlap_limit_m: Vec::new(),
            striker_mass_kg: m_s,
            striker_velocity_m_s: striker.velocity_m_s,
            loads: 0,
            struck: true,
            actuator: false,
            force_n: Vec::new(),
            overlap_m: Vec::new(),
            lab: None,
        };
        let mut points = vec![Side {
            offset: 0,
            len: 1,
            row: 0,
        }];
        for element in chain.elements() {
            let cell = &element.cell;
            let resonators: Vec<(f64, f64)> = cell
                .resonators
                .iter()
                .map(|r| (r.mass_kg, r.stiffness_n_per_m))
                .collect();
            let modes = ElementModes::new(cell.primary_mass_kg, &resonators)?;
            let (offset, len, row) = (ode.omega2.len(), modes.omega.len(), ode.rows.len());
            for (k, (&omega, &mu)) in modes.omega.iter().zip(&modes.modal_mass).enumerate() {
                ode.omega2.push(omega * omega);
                ode.rows.push(1.0 / mu.sqrt());
                // A flexible mode carries no momentum (M + Σ m_j u_jk = 0, its secular
                // equation); the rigid mode all of it, μ_0 being the element's whole mass.
                ode.translation.push(if k == 0 { mu.sqrt() } else { 0.0 });
                ode.rocking.push(0.0);
            }
            ode.bodies.push((offset, len, [0.0, 0.0], [1.0, 0.0]));
            points.push(Side { offset, len, row });
        }
        // The chain's slots 1..=N+1 (slot 0 is a blast's): striker on element 1, element i on
        // element i + 1, element N on the wall.
        let n = chain.len();
        for c in 0..=n {
            ode.above.push(points[c]);
            ode.below.push(points.get(c + 1).copied());
            ode.beta.push(compiled.eq.beta[c + 1]);
            ode.overlap_limit_m.push(compiled.overlap_limit_m[c + 1]);
        }
        ode.supports.push((n, 0.0, 0.0));
        ode.force_n = vec![0.0; n + 1];
        ode.overlap_m = vec![0.0; n + 1];
        Ok(ode)
    }
}
