//! A chain as a contact graph (docs/physics.md §16, "A column"): every element — a Table 1
//! cell, a beam-theory or finite-element rod's cell, a sphere, a user's cell — a body of one
//! point, its primary, in the free–free modes of its primary and resonators
//! ([`crate::ode::element_modes`]'s `ElementModes`, mass-normalised: q_k = √μ_k c_k, so the primary's
//! row is 1/√μ_k); the striker a body of one coordinate, or a blast or drive a load contact on
//! element 1; the chain's contacts, top to wall, in the chain's order, the wall a support under
//! the last element. The chain's lab physics becomes the graph's lab terms: its contact laws as
//! the chain compiles them, on-site damping (1/τ on every mode), gravity and a preload (their
//! modal forces), the static equilibrium (the graph's own solve), and each cell's resonator
//! dashpots as a damping matrix over its modes. The graph then runs the chain by the lattice's
//! path ([`crate::simulate::simulate_lattice`]) with the chain's numbers.

use super::graph::{ContactGraph, Side};
use super::LatticeOde;
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::model::{Chain, LatticeExcitation, LatticeLab, LoadPoints};
use crate::ode::element_modes::ElementModes;
use crate::ode::lattice_lab::{DampingBlock, LabTerms};
use crate::ode::ChainOde;

impl LatticeOde {
    /// The chain `chain` on its wall under `excitation` (a striker, a blast, a drive or rest),
    /// with its damping and static load, as a contact graph. Errors name the keys: a free end
    /// (`wall`), two resonators of one cell at one frequency (`cell.resonators`), and the
    /// chain's own ([`ChainOde::new`]).
    pub fn from_chain(chain: &Chain, excitation: &Excitation) -> Result<Self> {
        let compiled = ChainOde::new(chain, excitation)?;
        if chain.wall_beta().is_none() {
            return Err(Error::invalid(
                "wall",
                "free",
                "a chain becomes a contact graph on a wall (its support)",
            ));
        }
        let (mut ode, modes) = Self::chain_graph(chain, &compiled, excitation)?;
        if compiled.has_lab_physics() || !ode.graph.struck {
            let terms = chain_lab(&ode, chain, &compiled, excitation, &modes)?;
            ode.lab = Some(Box::new(terms));
        }
        Ok(ode)
    }

    /// The graph of the chain's bodies and contacts (no lab terms), and each element's modes.
    fn chain_graph(
        chain: &Chain,
        compiled: &ChainOde,
        excitation: &Excitation,
    ) -> Result<(Self, Vec<ElementModes>)> {
        let striker = match excitation {
            Excitation::Impact(s) => Some(s),
            _ => None,
        };
        let m_s = striker.map_or(0.0, |s| s.mass_kg());
        let mut ode = LatticeOde {
            graph: ContactGraph {
                omega2: Vec::new(),
                above: Vec::new(),
                below: Vec::new(),
                beta: Vec::new(),
                rows: Vec::new(),
                supports: Vec::new(),
                translation: Vec::new(),
                loads: usize::from(striker.is_none()),
                struck: striker.is_some(),
                actuator: compiled.actuator_rest_m().is_some(),
                force_n: Vec::new(),
                overlap_m: Vec::new(),
            },
            bodies: Vec::new(),
            rocking: Vec::new(),
            overlap_limit_m: Vec::new(),
            striker_mass_kg: m_s,
            striker_velocity_m_s: striker.map_or(0.0, |s| s.velocity_m_s),
            lab: None,
        };
        // The top side: the striker's coordinate, or a load's empty side.
        let mut points = vec![Side {
            offset: 0,
            len: usize::from(striker.is_some()),
            row: 0,
        }];
        if striker.is_some() {
            ode.graph.omega2.push(0.0);
            ode.graph.rows.push(1.0 / m_s.sqrt());
            ode.bodies.push((0, 1, [0.0, 0.0], [1.0, 0.0]));
            ode.graph.translation.push(m_s.sqrt());
            ode.rocking.push(0.0);
        }
        let mut all_modes = Vec::with_capacity(chain.len());
        for element in chain.elements() {
            let modes = ElementModes::new(element.cell.primary_mass_kg, &resonators(element))?;
            let (offset, len, row) = (
                ode.graph.omega2.len(),
                modes.omega.len(),
                ode.graph.rows.len(),
            );
            for (k, (&omega, &mu)) in modes.omega.iter().zip(&modes.modal_mass).enumerate() {
                ode.graph.omega2.push(omega * omega);
                ode.graph.rows.push(1.0 / mu.sqrt());
                // A flexible mode carries no momentum (M + Σ m_j u_jk = 0, its secular
                // equation); the rigid mode all of it, μ_0 being the element's whole mass.
                ode.graph
                    .translation
                    .push(if k == 0 { mu.sqrt() } else { 0.0 });
                ode.rocking.push(0.0);
            }
            ode.bodies.push((offset, len, [0.0, 0.0], [1.0, 0.0]));
            points.push(Side { offset, len, row });
            all_modes.push(modes);
        }
        // The chain's paper contacts 0..=N: the striker's or the load's on element 1 (slot 1 or
        // 0 of the chain's equations), element i on element i + 1, element N on the wall.
        let n = chain.len();
        for c in 0..=n {
            let slot = c + 1 - compiled.shift;
            ode.graph.above.push(points[c]);
            ode.graph.below.push(points.get(c + 1).copied());
            ode.graph.beta.push(compiled.eq.beta[slot]);
            ode.overlap_limit_m.push(compiled.overlap_limit_m[slot]);
        }
        ode.graph.supports.push((n, 0.0, 0.0));
        ode.graph.force_n = vec![0.0; n + 1];
        ode.graph.overlap_m = vec![0.0; n + 1];
        Ok((ode, all_modes))
    }

    /// Each element's body: its first coordinate and its number of modes.
    fn element_bodies(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.bodies[usize::from(self.graph.struck)..]
            .iter()
            .map(|&(offset, len, ..)| (offset, len))
    }
}

/// An element's resonators as (m_j, k_j).
fn resonators(element: &crate::model::Element) -> Vec<(f64, f64)> {
    element
        .cell
        .resonators
        .iter()
        .map(|r| (r.mass_kg, r.stiffness_n_per_m))
        .collect()
}

/// The chain's lab physics as the graph's lab terms: compiled as a lattice's (on-site damping,
/// gravity, a preload on element 1 beside a striker or on the load point, the static
/// equilibrium), then the chain's own contact laws and its resonator dashpots.
fn chain_lab(
    ode: &LatticeOde,
    chain: &Chain,
    compiled: &ChainOde,
    excitation: &Excitation,
    modes: &[ElementModes],
) -> Result<LabTerms> {
    // Element 1's primary is the column's one top point.
    let top = LoadPoints::TopCrossings;
    let load = match excitation {
        Excitation::Impact(striker) => LatticeExcitation::Impact {
            striker: striker.clone(),
            at_m: [0.0, 0.0],
        },
        Excitation::Blast(profile) => LatticeExcitation::Blast {
            profile: profile.clone(),
            points: top,
        },
        Excitation::Drive(drive) => LatticeExcitation::Drive {
            drive: drive.clone(),
            points: top,
        },
        Excitation::Rest => LatticeExcitation::Rest { points: top },
    };
    let lab = LatticeLab {
        damping: chain.damping().clone(),
        modal_ratio: 0.0,
        preload: *chain.preload(),
    };
    let first = ode.graph.above[1];
    let preload_points = vec![(
        first.offset,
        ode.graph.rows[first.row..first.row + first.len].to_vec(),
    )];
    let mut terms = LabTerms::compile(&ode.graph, &preload_points, &load, &lab)?;
    if let Some(eq) = &compiled.eq.lab {
        let slots = (0..ode.contacts()).map(|c| c + 1 - compiled.shift);
        let (laws, coef) = slots
            .map(|slot| (eq.shape.laws[slot], eq.law_coef[slot]))
            .unzip();
        terms.set_laws(laws, coef);
        let mut dashpots = eq.res_damping.iter();
        for ((offset, len), element_modes) in ode.element_bodies().zip(modes) {
            let r = len - 1;
            let c: Vec<f64> = dashpots.by_ref().take(r).copied().collect();
            if c.iter().any(|&c| c != 0.0) {
                terms.add_damping_block(dashpot_block(offset, element_modes, &c));
            }
        }
    }
    Ok(terms)
}

/// A cell's resonator dashpots c_j (between resonator j and its primary) over its
/// mass-normalised modes: C_kl = Σ_j c_j d_jk d_jl, d_jk = (u_jk − 1)/√μ_k the dashpot's
/// extension per unit q_k (0 in the rigid mode).
fn dashpot_block(offset: usize, modes: &ElementModes, c: &[f64]) -> DampingBlock {
    let len = modes.len();
    let d =
        |j: usize, k: usize| (modes.resonator_amplitude(j, k) - 1.0) / modes.modal_mass[k].sqrt();
    let mut matrix = vec![0.0; len * len];
    for k in 0..len {
        for l in 0..len {
            matrix[k * len + l] = c
                .iter()
                .enumerate()
                .map(|(j, &cj)| cj * d(j, k) * d(j, l))
                .sum();
        }
    }
    DampingBlock {
        offset,
        len,
        matrix,
    }
}
