//! Claim: a numerical blow-up is reported as an error, never as data, and the error names the
//! contact that actually failed and the right cure.
//!
//! - A step that is simply too large (RK4 at Δt = 20 µs, about the striker's ~21 µs contact time,
//!   beyond the stability limit of the stiff Hertz contacts; rigid rods) is a step problem: the
//!   message says to reduce the time step. (At 10 µs the rigid run completes with a 40 % energy
//!   error, which the energy balance reports.) With resonant rods 10 µs is refused before the
//!   run: it exceeds RK4's stability limit 2√2/ω on the 20 mm rod's resonator (ω ≈ 3.5e5 rad/s,
//!   Δt ω ≈ 3.5), and the message gives the largest stable step.
//! - One absurdly stiff contact (β = 1e30 N/m^1.5 on contact 2 of a 5-rod chain: its linearised
//!   frequency is ~1e11 rad/s, so RK4 at 0.1 µs is unstable there first) is reported at contact 2,
//!   as a step problem: the energy in the system (2.6 mJ) could compress that contact by only
//!   (5E/2β)^{2/5} ≈ 1e-13 m, far inside its physical range, so no load is too large for it.
//! - A striker at 1000 m/s carries 654 J; the 1-2 mm overlap it would need is beyond the physical
//!   range of the striker contact (10 % of the 2.5 mm rod radius) at any step size: reported as a
//!   load the contact cannot take, at contact 0, with "a smaller time step will not help".
//! - A blast of 1e9 N would compress contact 1 (between crossed 20 mm rods, β ≈ 2.5e9 N/m^1.5)
//!   statically by (F/β)^{2/3} ≈ 0.55 m, two thousand times its 0.25 mm range: when it blows up it
//!   is reported as a load beyond contact 1 from that static overlap (`LoadExceedsContact`),
//!   every number printed finite, and not as a step problem.
//! - So is a force drive of 1e300 N on element 1, naming the drive's amplitude, and gravity of
//!   1e300 m/s² (the static load alone, (F_i/β_i)^{2/3} ≈ 1e192 m), naming the preload's keys:
//!   both overflow the state within a step, where a message blaming the step would send the user
//!   to the wrong cure.

use woodpile::{
    simulate, BlastProfile, CellModel, ChainBuilder, Drive, Error, Excitation, Method, Preload,
    RunSettings, Signal, Striker,
};

/// Δt of the rigid run: about the striker's contact time, so RK4 cannot resolve the contact.
const STEP: f64 = 2e-5;

fn short(time_step_s: f64) -> RunSettings {
    RunSettings {
        duration_s: 1e-3,
        method: Method::Rk4 { time_step_s },
        sample_interval_s: 1e-5,
    }
}

#[test]
fn oversized_step_is_reported_as_a_step_problem() {
    let resonant = ChainBuilder::table1_rods(&[20; 5], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let refused = simulate(
        &resonant,
        &Excitation::Impact(Striker::paper()),
        &short(1e-5),
        &mut (),
    )
    .unwrap_err();
    let msg = refused.to_string();
    assert!(
        matches!(&refused, Error::InvalidParameter { field, .. } if field == "run.time_step_s")
            && msg.contains("resonator 0 of element 1")
            && msg.contains("use run.time_step_s < 8.1"),
        "{msg}"
    );
    let chain = ChainBuilder::table1_rods(&[20; 5], CellModel::Rigid)
        .unwrap()
        .build()
        .unwrap();
    let err = simulate(
        &chain,
        &Excitation::Impact(Striker::paper()),
        &short(STEP),
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
        other => panic!("expected a step-size blow-up, got {other:?}"),
    }
    let msg = err.to_string();
    assert!(
        msg.contains("reduce run.time_step_s") && msg.contains("t ="),
        "{msg}"
    );
}

#[test]
fn stiff_contact_is_named_where_it_is() {
    let chain = ChainBuilder::table1_rods(&[20; 5], CellModel::Resonant)
        .unwrap()
        .contact_beta(2, 1e30)
        .build()
        .unwrap();
    let err = simulate(
        &chain,
        &Excitation::Impact(Striker::paper()),
        &short(1e-7),
        &mut (),
    )
    .unwrap_err();
    match err {
        Error::RunawayOverlap { contact, .. } | Error::NonFiniteState { contact, .. } => {
            assert_eq!(contact, 2, "{err}")
        }
        other => panic!("expected a step-size blow-up at contact 2, got {other:?}"),
    }
}

#[test]
fn impossible_load_is_not_blamed_on_the_step() {
    let chain = ChainBuilder::table1_rods(&[20; 5], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let striker = Striker {
        velocity_m_s: 1000.0,
        ..Striker::paper()
    };
    let err = simulate(&chain, &Excitation::Impact(striker), &short(1e-8), &mut ()).unwrap_err();
    match &err {
        Error::LoadBeyondContact {
            contact,
            overlap_m,
            limit_m,
            reachable_m,
            ..
        } => {
            assert_eq!(*contact, 0, "{err}");
            assert!(overlap_m > limit_m && reachable_m > limit_m, "{err}");
        }
        other => panic!("expected a load beyond the contact, got {other:?}"),
    }
    assert!(
        err.to_string()
            .contains("a smaller time step will not help"),
        "{err}"
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

#[test]
fn a_blast_beyond_the_contact_is_told_from_statics() {
    let chain = ChainBuilder::table1_rods(&[20; 3], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let blast = Excitation::Blast(BlastProfile::Friedlander {
        peak_force_n: 1e9,
        duration_s: 2e-4,
        decay: 1.0,
    });
    let err = simulate(&chain, &blast, &short(1e-7), &mut ()).unwrap_err();
    match &err {
        Error::LoadExceedsContact {
            contact,
            limit_m,
            needed,
            ..
        } => {
            assert_eq!(*contact, 1, "{err}");
            let needed_m: f64 = needed
                .trim_end_matches(" m")
                .parse()
                .expect("a finite overlap");
            assert!(needed_m > 100.0 * limit_m, "{err}");
        }
        other => panic!("expected a load beyond contact 1, got {other:?}"),
    }
    let text = err.to_string();
    assert!(text.contains("a smaller time step will not help"), "{text}");
    assert!(!text.contains("inf") && !text.contains("NaN"), "{text}");
}

/// The error of a run of three 20 mm rods under `preload`, driven by `excitation`: a load beyond
/// contact 1, whose message names `key` and says the step is not the cure.
fn refused_as_load(excitation: &Excitation, preload: Preload, key: &str) {
    let chain = ChainBuilder::table1_rods(&[20; 3], CellModel::Resonant)
        .unwrap()
        .preload(preload)
        .build()
        .unwrap();
    let err = simulate(&chain, excitation, &short(1e-7), &mut ()).unwrap_err();
    assert!(
        matches!(err, Error::LoadExceedsContact { contact: 1, .. }),
        "expected a load beyond contact 1, got {err:?}"
    );
    let text = err.to_string();
    assert!(text.contains(key), "{text}");
    assert!(text.contains("a smaller time step will not help"), "{text}");
}

#[test]
fn a_huge_force_drive_or_gravity_is_told_from_statics() {
    let drive = Excitation::Drive(Drive::force(Signal::Harmonic {
        amplitude: 1e300,
        frequency_hz: 1e3,
    }));
    refused_as_load(&drive, Preload::default(), "excitation.amplitude");
    let gentle = Excitation::Drive(Drive::force(Signal::Harmonic {
        amplitude: 1.0,
        frequency_hz: 1e3,
    }));
    let heavy = Preload {
        force_n: 0.0,
        gravity_m_s2: 1e300,
    };
    refused_as_load(&gentle, heavy, "gravity_m_s2");
}
