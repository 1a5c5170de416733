//! Claim: zero damping reproduces the paper's lossless model bit for bit. A chain whose damping
//! is switched on but zero in value (restitution e = 1, resonator ratio 0) runs through the lab
//! physics' separate evaluation (docs/physics.md §14), yet its contact forces, energies and
//! displacements at every sample equal the lossless run's exactly, on the paper's impact (five
//! rods, resonant cells) — and that run dissipates exactly nothing. Tolerance: none; both paths
//! do the same floating-point operations on the same numbers.

use woodpile::{
    simulate, CellModel, ChainBuilder, ContactDamping, Damping, Excitation, RunSettings, Striker,
    Trajectory,
};

#[test]
fn zero_damping_reproduces_the_lossless_run_bit_for_bit() {
    let rods = [80, 40, 20, 60, 30];
    let settings = RunSettings {
        duration_s: 4e-4,
        ..RunSettings::paper_impact()
    };
    let run = |damping: Damping| {
        let chain = ChainBuilder::table1_rods(&rods, CellModel::Resonant)
            .unwrap()
            .damping(damping)
            .build()
            .unwrap();
        let mut traj = Trajectory::default();
        let s = simulate(
            &chain,
            &Excitation::Impact(Striker::paper()),
            &settings,
            &mut traj,
        )
        .unwrap();
        (s, traj)
    };
    let (lossless, a) = run(Damping::default());
    let zero = Damping {
        contacts: ContactDamping::Restitution { coefficient: 1.0 },
        resonator_ratio: 0.0,
        ..Damping::default()
    };
    assert!(!zero.is_lossless(), "must take the lab path");
    let (damped, b) = run(zero);
    assert_eq!(lossless.contact_peak_forces_n, damped.contact_peak_forces_n);
    assert_eq!(lossless.contact_peak_times_s, damped.contact_peak_times_s);
    assert_eq!(a.contact_forces_n, b.contact_forces_n);
    assert_eq!(a.layer_energies_j, b.layer_energies_j);
    assert_eq!(a.displacements_m, b.displacements_m);
    assert!(b.dissipated_j.iter().all(|&d| d == 0.0));
    assert!(lossless.transmitted_peak_force_n > 0.0);
}
