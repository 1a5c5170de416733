//! Claim: a GA run is a function of its seed alone: with 1 and with 2 worker threads the whole
//! history, the final population and the cache are identical.
//!
//! Tolerance: none (bit-identical). Random draws happen on the calling thread and fitness values
//! are written back by index; only the wall-clock column may differ.

use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, GaState, StandardObjective};
use woodpile::{CellModel, Method, RunSettings};

fn run(threads: usize) -> GaState {
    let mut space = DesignSpace::paper_impact(CellModel::Resonant);
    space.positions = 6;
    space.settings = RunSettings {
        duration_s: 3e-4,
        method: Method::Rk4 { time_step_s: 2e-7 },
        sample_interval_s: 1e-6,
    };
    let settings = GaSettings {
        population: 12,
        generations: 6,
        seed: 42,
        threads,
        ..GaSettings::default()
    };
    let ga = BreederGa::new(
        space,
        Box::new(StandardObjective::TransmittedForce),
        settings,
    )
    .unwrap();
    ga.run(None, &AtomicBool::new(false), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap()
    .state
}

#[test]
fn one_and_two_threads_give_the_same_run() {
    let (a, b) = (run(1), run(2));
    assert_eq!(a.history.len(), 7);
    for (x, y) in a.history.iter().zip(&b.history) {
        assert!(x.same_result(y), "{x:?} != {y:?}");
    }
    assert_eq!(a.population, b.population);
    assert_eq!(a.cache, b.cache);
    assert_eq!((a.evaluations, a.cache_hits), (b.evaluations, b.cache_hits));
}
