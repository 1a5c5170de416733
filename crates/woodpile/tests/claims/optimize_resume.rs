//! Claim: a run stopped after generation 3 and resumed from its saved state (by a new GA object,
//! as after a restart) ends exactly where an uninterrupted run ends: same history, population,
//! cache and counters. Generation g draws from ChaCha8(seed) on stream g, so the state needs no
//! generator position.
//!
//! Tolerance: none (bit-identical), except the wall-clock column of the history.

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, StandardObjective, StopReason};
use woodpile::{CellModel, Method, RunSettings};

fn ga() -> BreederGa {
    let mut space = DesignSpace::paper_impact(CellModel::Resonant);
    space.positions = 5;
    space.settings = RunSettings {
        duration_s: 3e-4,
        method: Method::Rk4 { time_step_s: 2e-7 },
        sample_interval_s: 1e-6,
    };
    let settings = GaSettings {
        population: 10,
        generations: 8,
        stall_generations: None,
        seed: 7,
        threads: 2,
        ..GaSettings::default()
    };
    BreederGa::new(
        space,
        Box::new(StandardObjective::TransmittedForce),
        settings,
    )
    .unwrap()
}

#[test]
fn resumed_run_equals_uninterrupted_run() {
    let straight = ga()
        .run(None, &AtomicBool::new(false), &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap();
    assert_eq!(straight.reason, StopReason::GenerationLimit);

    // Interrupt with the stop flag after generation 3, as Ctrl-C does.
    let stop = AtomicBool::new(false);
    let first = ga()
        .run(None, &stop, &mut |s| {
            if s.generation == 3 {
                stop.store(true, Ordering::SeqCst);
            }
            ControlFlow::Continue(())
        })
        .unwrap();
    assert_eq!(first.reason, StopReason::Interrupted);
    assert_eq!(first.state.generation, 3);

    let saved = first.state.clone();
    let resumed = ga()
        .run(Some(saved), &AtomicBool::new(false), &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap();
    assert_eq!(resumed.reason, StopReason::GenerationLimit);
    let (a, b) = (&straight.state, &resumed.state);
    assert_eq!(a.generation, b.generation);
    assert_eq!(a.history.len(), b.history.len());
    for (x, y) in a.history.iter().zip(&b.history) {
        assert!(x.same_result(y), "{x:?} != {y:?}");
    }
    assert_eq!(a.population, b.population);
    assert_eq!(a.ledger.cache, b.ledger.cache);
    assert_eq!(
        (a.ledger.evaluations, a.ledger.cache_hits, a.stalled),
        (b.ledger.evaluations, b.ledger.cache_hits, b.stalled)
    );
}

#[test]
fn a_state_of_another_problem_is_refused() {
    let first = ga()
        .run(None, &AtomicBool::new(false), &mut |s| {
            if s.generation == 1 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })
        .unwrap();
    let mut wrong = first.state.clone();
    wrong.population[0].genome.push(0);
    let err = ga()
        .run(Some(wrong), &AtomicBool::new(false), &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap_err();
    assert!(err.to_string().contains("does not match"), "{err}");
}
