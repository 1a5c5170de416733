//! Claim: for an impact the energy map accounts for all the energy: at every sample the layer
//! energies over the injected energy (the striker's ½ m_s v0²), plus the wall's half of the last
//! contact, sum to 1 — the model has no damping (docs/physics.md §7). At t = 0 everything is in layer 0.
//!
//! Tolerance: the sum is the run's total energy, which RK4 with dt = 0.1 µs conserves to the
//! relative error the runner itself reports (`EnergyBalance::max_relative_error`, ~1e-9 here);
//! we require both that bound (plus round-off 1e-12) and the docs/physics.md figure 1e-6.

use woodpile::analysis::{energy_map, force_map, injected_energy_j};
use woodpile::{simulate, CellModel, ChainBuilder, Excitation, RunSettings, Striker, Trajectory};

#[test]
fn energy_map_sums_to_the_injected_energy_for_an_impact() {
    let chain = ChainBuilder::table1_rods(&[80, 70, 40, 20, 50], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let striker = Striker::paper();
    let e_in = 0.5 * striker.mass_kg() * striker.velocity_m_s.powi(2);
    let settings = RunSettings {
        duration_s: 6e-4,
        ..RunSettings::paper_impact()
    };
    let mut t = Trajectory::default();
    let summary = simulate(&chain, &Excitation::Impact(striker), &settings, &mut t).unwrap();
    assert!((injected_energy_j(&t) / e_in - 1.0).abs() < 1e-12);

    let map = energy_map(&t).unwrap();
    assert_eq!((map.n_rows(), map.n_cols()), (6, t.len()));
    assert_eq!(map.rows.name, "layer");
    assert!((map.at(0, 0) - 1.0).abs() < 1e-12, "layer 0 at t = 0");
    let bound = (summary.energy.max_relative_error + 1e-12).min(1e-6);
    let mut worst = 0.0_f64;
    for (col, sum) in map.column_sums().iter().enumerate() {
        let total = sum + t.wall_energy_j[col] / e_in;
        worst = worst.max((total - 1.0).abs());
    }
    assert!(worst <= bound, "worst |Σ − 1| = {worst:e} > {bound:e}");
    // The wave must have reached the wall, or the test proves little.
    let last_layer_peak = map.row(5).iter().copied().fold(0.0, f64::max);
    assert!(last_layer_peak > 1e-3, "last layer peak {last_layer_peak}");

    let forces = force_map(&t).unwrap();
    assert_eq!(forces.row(5), t.contact_force_n(5).as_slice());
}
