//! Claim: under gravity and a preload a lattice starts from its static equilibrium
//! (docs/physics.md §16). On the 3 × 3-rod, 4-layer lattice (g = 9.81 m/s², a preload of 5 N on
//! the 9 top-layer crossings, left at rest): (1) the static solve's residual |∇Π| / |f| is below
//! 1e-12; (2) the supports carry the total weight plus the preload within 1e-9 (Σ F_s − M g − F_p
//! is bounded by the residual); (3) the crossings of one layer with the next carry that layer's
//! share: the four interfaces' forces sum to F_p + g × the mass above them, within 1e-9; (4) left
//! at rest for 1 ms (DOPRI5 at rtol 1e-10) every contact's force stays at its static value
//! within 1e-7 of the largest static force (the integrator's error on a state that should not
//! move; measured 2.5e-10). Measured: residual 1.4e-13, supports 5.0e-13, interfaces ≤ 3.8e-13.

use super::lattice_common::three_by_four;
use woodpile::model::{LatticeExcitation, LatticeLab, LoadPoints, Preload};
use woodpile::ode::LatticeOde;
use woodpile::simulate::simulate_lattice;
use woodpile::{Method, RunSettings};

#[test]
fn preloaded_lattice_under_gravity_stays_in_equilibrium() {
    let lattice = three_by_four(4);
    let (g, fp) = (9.81, 5.0);
    let lab = LatticeLab {
        preload: Preload {
            force_n: fp,
            gravity_m_s2: g,
        },
        ..LatticeLab::default()
    };
    let excitation = LatticeExcitation::Rest {
        points: LoadPoints::TopCrossings,
    };
    let mut ode = LatticeOde::build(&lattice, &excitation, &lab).unwrap();
    let (forces, residual) = ode.static_forces_n();
    let forces = forces.to_vec();
    eprintln!("static residual {residual:e}");
    assert!(residual < 1e-12);
    let loads = ode.incident_contacts().len();
    // (2) Supports against weight + preload.
    let weight = lattice.mass_kg() * g;
    let supports: f64 = (0..ode.contacts())
        .filter(|&c| ode.is_support(c))
        .map(|c| forces[c])
        .sum();
    let error = (supports - weight - fp).abs() / (weight + fp);
    eprintln!(
        "supports {supports:.12} N against M g + F_p = {:.12} N: {error:.2e}",
        weight + fp
    );
    assert!(error < 1e-9);
    // (3) Every interface carries what lies above it.
    for layer in 1..lattice.layers {
        let carried: f64 = lattice
            .contacts
            .iter()
            .enumerate()
            .filter(|(_, c)| c.below.is_some() && lattice.rods[c.above.rod].layer == layer)
            .map(|(i, _)| forces[i + loads])
            .sum();
        let above: f64 = lattice
            .rods
            .iter()
            .filter(|r| r.layer <= layer)
            .map(|r| r.rod.mass_kg() * g)
            .sum();
        let error = (carried - above - fp).abs() / (above + fp);
        eprintln!(
            "interface {layer}|{}: {carried:.9} N, error {error:.2e}",
            layer + 1
        );
        assert!(error < 1e-9);
    }
    // (4) Left alone, nothing moves.
    let settings = RunSettings {
        duration_s: 1e-3,
        method: Method::Dopri5 {
            rtol: 1e-10,
            atol: 1e-14,
        },
        sample_interval_s: 1e-5,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    let largest = forces.iter().fold(0.0_f64, |a, &b| a.max(b));
    let mut drift = 0.0_f64;
    for row in run.contact_forces_n.chunks(run.contacts) {
        for (f, f0) in row.iter().zip(&forces) {
            drift = drift.max((f - f0).abs() / largest);
        }
    }
    eprintln!("largest drift {drift:e} of the largest static force {largest:.4} N");
    assert!(drift < 1e-7);
}

/// Gravity alone (no preload, so no load points): the same equilibrium checks.
#[test]
fn lattice_under_gravity_alone_stays_at_rest() {
    let lattice = three_by_four(4);
    let g = 9.81;
    let lab = LatticeLab {
        preload: Preload {
            force_n: 0.0,
            gravity_m_s2: g,
        },
        ..LatticeLab::default()
    };
    let excitation = LatticeExcitation::Rest {
        points: LoadPoints::TopCrossings,
    };
    let mut ode = LatticeOde::build(&lattice, &excitation, &lab).unwrap();
    assert_eq!(ode.incident_contacts().len(), 0);
    let (forces, residual) = ode.static_forces_n();
    let forces = forces.to_vec();
    let weight = lattice.mass_kg() * g;
    let supports: f64 = (0..ode.contacts())
        .filter(|&c| ode.is_support(c))
        .map(|c| forces[c])
        .sum();
    let error = (supports - weight).abs() / weight;
    eprintln!("gravity alone: residual {residual:e}, supports {error:.2e} off M g");
    assert!(residual < 1e-12 && error < 1e-9);
    let settings = RunSettings {
        duration_s: 1e-3,
        method: Method::Dopri5 {
            rtol: 1e-10,
            atol: 1e-14,
        },
        sample_interval_s: 1e-5,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    let largest = forces.iter().fold(0.0_f64, |a, &b| a.max(b));
    let drift = run
        .contact_forces_n
        .chunks(run.contacts)
        .flat_map(|row| {
            row.iter()
                .zip(&forces)
                .map(|(f, f0)| (f - f0).abs() / largest)
        })
        .fold(0.0_f64, f64::max);
    eprintln!("gravity alone: largest drift {drift:e} of {largest:.4} N");
    assert!(drift < 1e-7);
}
