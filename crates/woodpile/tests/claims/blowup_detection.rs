//! Claim: a numerical blow-up is reported as an error naming the time and the contact, with the
//! fix (a smaller time step), instead of producing data.
//!
//! Setup: RK4 with Δt = 10 µs, half the striker's contact time (~21 µs), beyond the stability
//! limit of the stiff Hertz contacts (at 5 µs RK4 still runs, with a 3 % energy error that the
//! summary reports).

use woodpile::{
    simulate, CellModel, ChainBuilder, Error, Excitation, Method, RunSettings, Striker,
};

#[test]
fn oversized_step_is_reported_not_recorded() {
    let chain = ChainBuilder::table1_rods(&[20; 5], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let settings = RunSettings {
        duration_s: 1e-3,
        method: Method::Rk4 { time_step_s: 1e-5 },
        sample_interval_s: 1e-5,
    };
    let err = simulate(
        &chain,
        &Excitation::Impact(Striker::paper()),
        &settings,
        &mut (),
    )
    .unwrap_err();
    match &err {
        Error::RunawayOverlap {
            time_s, contact, ..
        }
        | Error::NonFiniteState { time_s, contact } => {
            assert!(*time_s > 0.0 && *time_s <= 1e-3, "time {time_s}");
            assert!(*contact <= 5, "contact {contact}");
        }
        other => panic!("expected a blow-up error, got {other:?}"),
    }
    let msg = err.to_string();
    assert!(
        msg.contains("reduce the time step") && msg.contains("t ="),
        "{msg}"
    );
}

#[test]
fn time_step_not_smaller_than_duration_is_invalid() {
    let chain = ChainBuilder::table1_rods(&[20], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let settings = RunSettings {
        duration_s: 1e-6,
        method: Method::Rk4 { time_step_s: 1e-6 },
        sample_interval_s: 1e-7,
    };
    let err = simulate(
        &chain,
        &Excitation::Impact(Striker::paper()),
        &settings,
        &mut (),
    )
    .unwrap_err();
    assert!(err.to_string().contains("run.time_step_s"), "{err}");
}
