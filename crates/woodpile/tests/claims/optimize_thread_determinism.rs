//! Claim: a GA run is a function of its seed alone: with 1 and with 2 worker threads, designs
//! evaluated one by one or 2, 4 and 8 at a time in SIMD lanes, the whole history, the final
//! population and the cache are identical.
//!
//! Tolerance: none (bit-identical). Random draws happen on the calling thread, fitness values
//! are written back by index, and lanes compute what single runs compute (claim
//! `lanes_bit_identical`); only the wall-clock column may differ.

use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, GaState, StandardObjective};
use woodpile::{CellModel, LaneWidth, Method, RunSettings};

fn run(threads: usize, lanes: LaneWidth) -> GaState {
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
    .unwrap()
    .with_lanes(lanes);
    ga.run(None, &AtomicBool::new(false), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap()
    .state
}

#[test]
fn thread_counts_and_lane_widths_give_the_same_run() {
    let a = run(1, LaneWidth::One);
    assert_eq!(a.history.len(), 7);
    for (threads, lanes) in [
        (2, LaneWidth::One),
        (1, LaneWidth::Four),
        (2, LaneWidth::Eight),
    ] {
        let b = run(threads, lanes);
        for (x, y) in a.history.iter().zip(&b.history) {
            assert!(
                x.same_result(y),
                "{threads} threads, {lanes:?}: {x:?} != {y:?}"
            );
        }
        assert_eq!(a.population, b.population);
        assert_eq!(a.ledger.cache, b.ledger.cache);
        assert_eq!(
            (a.ledger.evaluations, a.ledger.cache_hits),
            (b.ledger.evaluations, b.ledger.cache_hits)
        );
    }
}
