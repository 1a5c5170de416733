//! Claim: the exact modal method computes the energy of a cell with resonator dashpots (not a
//! sum over its complex modes) only where a sample reads it, and carries the dissipated energy
//! D between samples as each element's balance without those cells' energy change, subtracted
//! where D is read (docs/physics.md §8). What it gives at a sample does not depend on where
//! else it was read: on three finite-element rods with resonator damping (ζ = 1 %) and on-site
//! damping (τ = 0.2 ms) under the paper's blast over a 5 N preload and gravity, the internal
//! energies, positions, velocities, W and D at every fourth microsecond over 0.1 ms are the
//! same, bit for bit, whether the run read them only there or also at every microsecond and at
//! every step's end. Tolerance: none; the steps do not depend on the reads, and each read is
//! computed from the state at the ends of the step that holds it.

use super::lattice_common::fe_rod_elements;
use woodpile::model::{Damping, Preload};
use woodpile::ode::ChainOde;
use woodpile::{BlastProfile, ChainBuilder, Excitation};

#[test]
fn energies_read_sparsely_are_those_read_at_every_step() {
    let damping = Damping {
        on_site_time_s: Some(2e-4),
        resonator_ratio: 0.01,
        ..Damping::default()
    };
    let preload = Preload {
        force_n: 5.0,
        gravity_m_s2: 9.81,
    };
    let chain = ChainBuilder::new(fe_rod_elements(&[80.0, 40.0, 20.0], 4))
        .preload(preload)
        .damping(damping)
        .build()
        .unwrap();
    let ode = ChainOde::new(&chain, &Excitation::Blast(BlastProfile::paper())).unwrap();
    let tolerances = (1e-8, 1e-14, 1e-8);
    let dense: Vec<f64> = (1..=100).map(|k| k as f64 * 1e-6).collect();
    let sparse: Vec<f64> = dense.iter().copied().skip(3).step_by(4).collect();
    let observe = |times: &[f64], every_step| {
        woodpile::integrate::exact_modes_observations(&ode, tolerances, times, every_step).unwrap()
    };
    let (everywhere, sparsely) = (observe(&dense, true), observe(&sparse, false));
    assert_eq!(sparsely.len(), 25);
    for (k, read) in sparsely.iter().enumerate() {
        let reference = &everywhere[4 * k + 3];
        let same = read
            .iter()
            .zip(reference)
            .all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(same, "sample {k}: {read:?} against {reference:?}");
    }
    // D is read and moving: the dashpots dissipate the blast's energy.
    let p = chain.elements().len();
    let dissipated = |read: &[f64]| read[p + 2 * ode.n_dof() + 1];
    let (first, last) = (dissipated(&sparsely[0]), dissipated(&sparsely[24]));
    assert!(
        last.is_finite() && last > first && last > 0.0,
        "D {first:e} -> {last:e}"
    );
}
