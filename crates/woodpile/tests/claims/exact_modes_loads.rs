//! Claim: the exact modal method (docs/physics.md §8, "Exact linear vibrations") advances a
//! chain under the loads of docs/physics.md §14 — the paper's blast, a displacement drive
//! through an actuator's tip over a preload under gravity, the paper's impact under a preload
//! and gravity, a preloaded blast with on-site damping (τ = 0.2 ms: every mode, the rigid ones
//! included, decays at 1/τ) — to the contact peaks, the work and the dissipated energy of a
//! converged run, its energy audit closed; a preloaded column at rest stays at rest; resonator
//! damping is refused; and `peak_tolerance` keeps its promise
//! under a force drive whose contacts open and close. Three quartz rods (80, 40, 20 mm) as
//! finite-element beams (4 elements per half rod: modes up to 1.8 MHz, where an explicit
//! method's step is set by stability), 0.3 ms, against DOPRI5 with events at rtol 1e-11.

use super::lattice_common::fe_rod_elements;
use super::peak_common::worst_peak_error;
use woodpile::excitation::DriveQuantity;
use woodpile::model::{ContactDamping, Damping, Preload, Wall};
use woodpile::{
    simulate, BlastProfile, Chain, ChainBuilder, Drive, Excitation, Method, RunSettings,
    RunSummary, Signal, Striker,
};

fn chain(force_n: f64, gravity_m_s2: f64) -> Chain {
    damped_chain(force_n, gravity_m_s2, None, 0.0)
}

fn damped_chain(
    force_n: f64,
    gravity_m_s2: f64,
    on_site_time_s: Option<f64>,
    resonator_ratio: f64,
) -> Chain {
    let preload = Preload {
        force_n,
        gravity_m_s2,
    };
    let damping = Damping {
        on_site_time_s,
        resonator_ratio,
        ..Damping::default()
    };
    ChainBuilder::new(fe_rod_elements(&[80.0, 40.0, 20.0], 4))
        .preload(preload)
        .damping(damping)
        .build()
        .unwrap()
}

fn run(chain: &Chain, excitation: &Excitation, method: Method) -> RunSummary {
    let settings = RunSettings {
        duration_s: 3e-4,
        method,
        sample_interval_s: 1e-6,
    };
    simulate(chain, excitation, &settings, &mut ()).unwrap()
}

fn converged(chain: &Chain, excitation: &Excitation) -> RunSummary {
    run(
        chain,
        excitation,
        Method::Dopri5Events {
            rtol: 1e-11,
            atol: 1e-17,
        },
    )
}

fn worst_peak(a: &RunSummary, reference: &RunSummary) -> f64 {
    worst_peak_error(&a.contact_peak_forces_n, &reference.contact_peak_forces_n)
}

fn displacement_drive() -> Excitation {
    Excitation::Drive(Drive {
        quantity: DriveQuantity::Displacement {
            tip: Wall::paper_sensor(),
        },
        ramp_s: 1e-4,
        signal: Signal::Harmonic {
            amplitude: 2e-7,
            frequency_hz: 5e3,
        },
    })
}

/// At rtol 1e-9 every peak is within 1e-7 of the converged run's, the work within 1e-7 of it
/// (of the initial energy without a load) and the dissipated energy of it, the audit within
/// 1e-7: a hundred times rtol, the measured errors at that rtol (examples/exact_loads.rs) being
/// at most 10 rtol.
#[test]
fn loaded_runs_reach_the_converged_peaks_and_work() {
    let cases = [
        (
            "blast",
            chain(0.0, 0.0),
            Excitation::Blast(BlastProfile::paper()),
        ),
        (
            "displacement drive",
            chain(20.0, 9.81),
            displacement_drive(),
        ),
        (
            "preloaded impact",
            chain(5.0, 9.81),
            Excitation::Impact(Striker::paper()),
        ),
        (
            "damped preloaded blast",
            damped_chain(5.0, 9.81, Some(2e-4), 0.0),
            Excitation::Blast(BlastProfile::paper()),
        ),
        (
            "resonator-damped preloaded blast",
            damped_chain(5.0, 9.81, Some(2e-4), 0.01),
            Excitation::Blast(BlastProfile::paper()),
        ),
        (
            "resonator-damped impact",
            damped_chain(0.0, 0.0, None, 0.05),
            Excitation::Impact(Striker::paper()),
        ),
    ];
    let exact = Method::ExactModes {
        rtol: 1e-9,
        atol: 1e-15,
    };
    for (name, chain, excitation) in &cases {
        let reference = converged(chain, excitation);
        let s = run(chain, excitation, exact);
        let peak = worst_peak(&s, &reference);
        // Against the work, or the initial energy where no force works (an impact).
        let scale = (reference.energy.input_work_j.abs()).max(reference.energy.initial_j);
        let work = (s.energy.input_work_j - reference.energy.input_work_j).abs() / scale;
        eprintln!(
            "{name}: {} steps against {}, worst peak {peak:.2e}, work {work:.2e}, audit {:.2e}",
            s.stats.steps, reference.stats.steps, s.energy.max_relative_error
        );
        assert!(peak < 1e-7, "{name}: peaks differ by {peak:e}");
        assert!(work < 1e-7, "{name}: work differs by {work:e}");
        let (d, d_ref) = (s.energy.dissipated_j, reference.energy.dissipated_j);
        let dissipated = (d - d_ref).abs() / d_ref.abs().max(1e-300);
        eprintln!("  dissipated {d:.6e} J against {d_ref:.6e} J ({dissipated:.2e})");
        assert!(
            d_ref == 0.0 && d == 0.0 || dissipated < 1e-7,
            "{name}: dissipated energy differs by {dissipated:e}"
        );
        assert!(
            s.energy.max_relative_error < 1e-7,
            "{name}: audit {:e}",
            s.energy.max_relative_error
        );
    }
}

/// A column at rest under its preload and gravity starts in static equilibrium; the exact flow
/// of its modes keeps it there: every contact's peak is its static force to 1e-9 (the static
/// solve stops at |∇Π| ≤ 1e-12 |f|; the step's fixed-point iteration at 1e-3 rtol).
#[test]
fn preloaded_column_stays_at_rest() {
    let chain = chain(5.0, 9.81);
    let s = run(
        &chain,
        &Excitation::Rest,
        Method::ExactModes {
            rtol: 1e-8,
            atol: 1e-14,
        },
    );
    let statics = chain.static_contact_forces_n();
    let worst = s
        .contact_peak_forces_n
        .iter()
        .skip(1)
        .zip(&statics)
        .map(|(p, f)| (p / f - 1.0).abs())
        .fold(0.0, f64::max);
    eprintln!("at rest: worst peak against the static force {worst:.2e}");
    assert!(worst < 1e-9, "the column moved: {worst:e}");
}

/// `peak_tolerance = 1e-5` chooses the exact method for these rods under a 10 N, 5 kHz force
/// drive with no preload (its contacts open and close with the drive: the hardest case
/// measured) and meets the tolerance.
#[test]
fn peak_tolerance_holds_under_a_force_drive() {
    let chain = chain(0.0, 0.0);
    let excitation = Excitation::Drive(Drive::force(Signal::Harmonic {
        amplitude: 10.0,
        frequency_hz: 5e3,
    }));
    let reference = converged(&chain, &excitation);
    let s = run(
        &chain,
        &excitation,
        Method::PeakTolerance {
            peak_tolerance: 1e-5,
        },
    );
    let peak = worst_peak(&s, &reference);
    eprintln!(
        "force drive: {} steps against {}, worst peak {peak:.2e}",
        s.stats.steps, reference.stats.steps
    );
    assert!(
        s.stats.steps * 5 < reference.stats.steps,
        "not the exact method's steps"
    );
    assert!(peak < 1e-5, "peaks differ by {peak:e}");
}

/// With a damped contact law (its force needs the overlap rates at the nodes) the exact method
/// refuses the run, naming what to use instead.
#[test]
fn damped_contact_law_is_refused() {
    let chain = chain(0.0, 0.0)
        .with_damping(Damping {
            contacts: ContactDamping::Restitution { coefficient: 0.9 },
            ..Damping::default()
        })
        .unwrap();
    let e = simulate(
        &chain,
        &Excitation::Blast(BlastProfile::paper()),
        &RunSettings {
            duration_s: 1e-4,
            method: Method::ExactModes {
                rtol: 1e-8,
                atol: 1e-14,
            },
            sample_interval_s: 1e-6,
        },
        &mut (),
    )
    .unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("run.method") && text.contains("dopri5"),
        "{text}"
    );
}

/// An overdamped cell (ζ = 3 on every resonator: its damped modes are not oscillations) cannot
/// be followed: the exact method refuses it naming `damping.resonator_ratio`, and a stated peak
/// tolerance falls back to what it resolves to without the exact method (DOPRI5 with events),
/// the same run bit for bit.
#[test]
fn overdamped_cell_falls_back_under_a_peak_tolerance() {
    let chain = damped_chain(0.0, 0.0, None, 3.0);
    let excitation = Excitation::Impact(Striker::paper());
    let settings = |method| RunSettings {
        duration_s: 1e-4,
        method,
        sample_interval_s: 1e-6,
    };
    let exact = Method::ExactModes {
        rtol: 1e-7,
        atol: 1e-13,
    };
    let e = simulate(&chain, &excitation, &settings(exact), &mut ()).unwrap_err();
    assert!(e.to_string().contains("damping.resonator_ratio"), "{e}");
    let tolerance = Method::PeakTolerance {
        peak_tolerance: 1e-5,
    };
    let chosen = simulate(&chain, &excitation, &settings(tolerance), &mut ()).unwrap();
    let dopri = simulate(
        &chain,
        &excitation,
        &settings(tolerance.resolve(false)),
        &mut (),
    )
    .unwrap();
    assert_eq!(chosen.contact_peak_forces_n, dopri.contact_peak_forces_n);
    assert_eq!(chosen.stats.steps, dopri.stats.steps);
}
