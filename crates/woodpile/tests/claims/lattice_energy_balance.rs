//! Claim: a lossless lattice keeps its energy (docs/physics.md §16): kinetic energy of every
//! modal coordinate, the rods' strain energy ½ Σ ω_j² q_j² and the contacts' (2/5) β δ^{5/2}
//! sum to the striker's initial kinetic energy within 1e-8 at every sample, on the 3 × 3-rod,
//! 4-layer lattice struck off-centre (RK4 at 20 ns over 0.3 ms; RK4's energy error falls as
//! Δt⁴: measured 2.4e-9 at 20 ns, so the bound holds with a margin of four).

use super::lattice_common::three_by_four;
use woodpile::ode::LatticeOde;
use woodpile::simulate::simulate_lattice;
use woodpile::{Method, RunSettings, Striker};

#[test]
fn lossless_lattice_keeps_its_energy() {
    let lattice = three_by_four(4);
    let striker = Striker::paper();
    let mut ode = LatticeOde::new(&lattice, &striker, [13e-3, 1e-3]).unwrap();
    let settings = RunSettings {
        duration_s: 3e-4,
        method: Method::Rk4 { time_step_s: 2e-8 },
        sample_interval_s: 1e-6,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    let e0 = 0.5 * striker.mass_kg() * striker.velocity_m_s.powi(2);
    assert!((run.energy.initial_j - e0).abs() < 1e-15 * e0);
    let strain_and_contacts = run.energy_j.iter().fold(0.0_f64, |a, &e| a.max(e));
    eprintln!(
        "largest energy error {:e} of E(0)",
        run.energy.max_relative_error
    );
    assert!(strain_and_contacts > 0.0);
    assert!(run.energy.max_relative_error < 1e-8);
}
