//! What the GA claims that compare two runs generation by generation share: one small problem,
//! its GA, and a run's pools. Not a claim.

use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{
    BreederGa, DesignSpace, GaSettings, GaState, Individual, StandardObjective,
};
use woodpile::{CellModel, LaneWidth, Method, RunSettings};

/// 8 Table 1 rods under the paper's striker for 0.6 ms, integrated by `method`.
pub fn space(method: Method) -> DesignSpace {
    let mut space = DesignSpace::paper_impact(CellModel::Resonant);
    space.positions = 8;
    space.settings = RunSettings {
        duration_s: 6e-4,
        method,
        sample_interval_s: 6e-4,
    };
    space
}

/// The GA over [`space`] with every contact peak within 1e-4: population 24, 12 generations,
/// seed 5, screening at `screen` and early stopping as given.
pub fn ga(
    objective: StandardObjective,
    screen: Option<f64>,
    stop_early: bool,
    threads: usize,
    lanes: LaneWidth,
) -> BreederGa {
    let settings = GaSettings {
        population: 24,
        generations: 12,
        stall_generations: None,
        seed: 5,
        threads,
        screen_peak_tolerance: screen,
        stop_early,
        ..GaSettings::default()
    };
    let method = Method::for_peak_tolerance(1e-4).unwrap();
    BreederGa::new(space(method), Box::new(objective), settings)
        .unwrap()
        .with_lanes(lanes)
}

/// Runs `ga` to its end: every generation's breeding pool (the best ⌈0.3 · 24⌉ = 8 of a
/// population of 24) and the final state.
pub fn pools_and_state(ga: &BreederGa) -> (Vec<Vec<Individual>>, GaState) {
    let mut pools = Vec::new();
    let outcome = ga
        .run(None, &AtomicBool::new(false), &mut |s| {
            pools.push(s.population[..8].to_vec());
            ControlFlow::Continue(())
        })
        .unwrap();
    (pools, outcome.state)
}
