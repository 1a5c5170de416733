//! Claim: with every term of docs/physics.md §14 at once — a preload and gravity, restitution
//! damping between elements, Hunt–Crossley at the wall, viscoelastic damping at the actuator,
//! damped resonators, on-site damping — and a displacement drive (a chirp through a steel cap),
//! the energy balance E(0) + W(t) = E(t) + D(t) closes to 1e-6 of the largest work, as it does
//! for the lossless model: W and D are integrated with the motion, so the balance measures the
//! integrator's error alone (RK4 at 0.1 µs, ~1e-9 here). Also: dissipation only grows, and it
//! accounts for a visible share of the input (so the test cannot pass with D ≡ 0).

use woodpile::{
    simulate, CellModel, ChainBuilder, ContactDamping, Damping, Drive, DriveQuantity, Excitation,
    Preload, ResonatorDamping, RunSettings, Signal, Sweep, Trajectory, Wall,
};

/// Every damping term of a chain at once: restitution between elements, Hunt–Crossley at the
/// wall (v_in = 1 cm/s), viscoelastic damping at the striker or actuator, damped resonators
/// (ζ = 2 %, element 1's second at 10 %) and on-site damping (τ = 1 ms).
pub(super) fn every_damping() -> Damping {
    Damping {
        contacts: ContactDamping::Restitution { coefficient: 0.8 },
        wall: Some(ContactDamping::HuntCrossley { restitution: 0.9 }),
        striker: Some(ContactDamping::Viscoelastic { time_s: 1e-7 }),
        allow_pull: false,
        resonator_ratio: 0.02,
        resonator_overrides: vec![ResonatorDamping {
            element: 1,
            resonator: 2,
            ratio: 0.1,
        }],
        on_site_time_s: Some(1e-3),
        impact_speed_m_s: Some(0.01),
    }
}

#[test]
fn energy_balance_closes_with_every_lab_term() {
    let chain = ChainBuilder::table1_rods(&[80, 40, 20, 60], CellModel::Resonant)
        .unwrap()
        .preload(Preload {
            force_n: 5.0,
            gravity_m_s2: 9.81,
        })
        .damping(every_damping())
        .build()
        .unwrap();
    let drive = Drive {
        quantity: DriveQuantity::Displacement {
            tip: Wall::paper_sensor(),
        },
        ..Drive::force(Signal::Chirp {
            amplitude: 2e-7,
            start_hz: 500.0,
            end_hz: 20e3,
            duration_s: 1e-3,
            sweep: Sweep::Logarithmic,
        })
    };
    let settings = RunSettings {
        duration_s: 1.5e-3,
        ..RunSettings::paper_impact()
    };
    let mut traj = Trajectory::default();
    let s = simulate(&chain, &Excitation::Drive(drive), &settings, &mut traj).unwrap();
    assert!(
        s.energy.max_relative_error < 1e-6,
        "balance {}",
        s.energy.max_relative_error
    );
    assert!(traj.dissipated_j.windows(2).all(|w| w[1] >= w[0]));
    let work = traj
        .input_work_j
        .iter()
        .fold(0.0_f64, |m, w| m.max(w.abs()));
    assert!(
        s.energy.dissipated_j > 0.01 * work,
        "dissipated {} of work {work}",
        s.energy.dissipated_j
    );
}
