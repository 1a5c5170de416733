//! Claims: a run says up front how much work it is, refuses settings that would give a run
//! without end, and never accepts the same contact twice.
//!
//! - A fixed-step run of T = 1e6 s at Δt = 0.1 µs is 1e13 steps: `estimated_steps` says so
//!   (exact integer arithmetic on a power of ten, so equality), which lets a front end refuse it.
//! - A resonator of k = 1e20 N/m on m = 1e-9 kg (ω ≈ 3e14 rad/s) under Dormand–Prince would need
//!   steps of ~1e-14 s, ~1e11 of them for 2 ms: it must stop at once with a typed error naming
//!   the stiffness problem, not run for days (bounded here by the test finishing at all).
//! - A run of 1e300 s is refused naming run.duration_s = 1e300 (it was blamed on the sample
//!   interval, and the value printed as 301 digits), with the sample count it would give.
//! - Two overrides of one contact coefficient are an error naming both entries; so are two damping
//!   ratios of one resonator (the second was silently taken before).

use woodpile::{
    simulate, Body, ChainBuilder, Element, Error, Excitation, Material, Method, Resonator,
    RunSettings, Striker, UnitCell,
};

#[test]
fn estimated_steps_of_a_fixed_step_run() {
    let settings = RunSettings {
        duration_s: 1e6,
        ..RunSettings::paper_impact()
    };
    assert_eq!(settings.estimated_steps(), Some(10_000_000_000_000));
    assert_eq!(RunSettings::paper_impact().estimated_steps(), Some(20_000));
}

#[test]
fn stiff_cell_under_the_adaptive_method_stops_at_once() {
    let cell = UnitCell::new(
        1e-3,
        vec![Resonator {
            mass_kg: 1e-9,
            stiffness_n_per_m: 1e20,
        }],
    )
    .unwrap();
    let rod = Element {
        label: "stiff".into(),
        body: Body::Rod {
            diameter_m: 5e-3,
            length_m: 40e-3,
        },
        material: Material::preset("fused-quartz").unwrap(),
        cell,
    };
    let chain = ChainBuilder::new(vec![rod.clone(), rod]).build().unwrap();
    let settings = RunSettings {
        method: Method::Dopri5 {
            rtol: 1e-9,
            atol: 1e-15,
        },
        ..RunSettings::paper_impact()
    };
    let err = simulate(
        &chain,
        &Excitation::Impact(Striker::paper()),
        &settings,
        &mut (),
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            Error::StepSizeTooSmall { .. } | Error::TooManySteps { .. }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("stiff"), "{err}");
}

#[test]
fn one_contact_overridden_twice_is_refused() {
    let err = ChainBuilder::table1_rods(&[20, 30, 40], woodpile::CellModel::Resonant)
        .unwrap()
        .contact_beta(2, 1e9)
        .contact_beta(2, 2e9)
        .build()
        .unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("chain.contact_beta[1]") && msg.contains("chain.contact_beta[0]"),
        "{msg}"
    );
}

#[test]
fn one_resonator_damped_twice_is_refused() {
    let once = |ratio| woodpile::ResonatorDamping {
        element: 2,
        resonator: 1,
        ratio,
    };
    let err = ChainBuilder::table1_rods(&[20, 30, 40], woodpile::CellModel::Resonant)
        .unwrap()
        .damping(woodpile::Damping {
            resonator_overrides: vec![once(0.01), once(0.02)],
            ..woodpile::Damping::default()
        })
        .build()
        .unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("damping.resonators[1]") && msg.contains("damping.resonators[0]"),
        "{msg}"
    );
}

#[test]
fn an_endless_run_names_its_duration() {
    let settings = RunSettings {
        duration_s: 1e300,
        ..RunSettings::paper_impact()
    };
    let msg = settings.validate().unwrap_err().to_string();
    assert!(
        msg.contains("run.duration_s = 1e300") && msg.contains("1.0e306 samples"),
        "{msg}"
    );
}
