//! What the GA claims that compare two runs generation by generation share. Not a claim.

use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{BreederGa, GaState, Individual};

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
