//! Claim: the fitness cache only saves work: with the cache on and off the history (best, mean,
//! worst), the final population and the stopping generation are identical, and with it on no
//! design is simulated twice (evaluations = distinct designs seen).
//!
//! Tolerance: none (bit-identical): a simulation is a deterministic function of the design.

use std::collections::HashSet;
use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, GaState, StandardObjective};
use woodpile::{CellModel, Method, RunSettings};

fn run(cache: bool, seen: &mut HashSet<Vec<u8>>) -> GaState {
    let mut space = DesignSpace::paper_impact(CellModel::Rigid);
    space.positions = 4;
    space.settings = RunSettings {
        duration_s: 3e-4,
        method: Method::Rk4 { time_step_s: 2e-7 },
        sample_interval_s: 1e-6,
    };
    let settings = GaSettings {
        population: 10,
        generations: 10,
        seed: 3,
        threads: 2,
        cache,
        ..GaSettings::default()
    };
    let ga = BreederGa::new(
        space,
        Box::new(StandardObjective::TransmittedImpulse),
        settings,
    )
    .unwrap();
    ga.run(None, &AtomicBool::new(false), &mut |s| {
        seen.extend(s.population.iter().map(|i| i.genome.clone()));
        ControlFlow::Continue(())
    })
    .unwrap()
    .state
}

#[test]
fn cache_on_and_off_give_the_same_run() {
    let (mut seen_on, mut seen_off) = (HashSet::new(), HashSet::new());
    let on = run(true, &mut seen_on);
    let off = run(false, &mut seen_off);
    assert_eq!(on.generation, off.generation);
    for (x, y) in on.history.iter().zip(&off.history) {
        assert_eq!(
            (x.best.to_bits(), x.mean.to_bits(), x.worst.to_bits()),
            (y.best.to_bits(), y.mean.to_bits(), y.worst.to_bits()),
            "generation {}",
            x.generation
        );
    }
    assert_eq!(on.population, off.population);
    assert!(on.ledger.cache_hits > 0, "this run revisits designs");
    assert_eq!(off.ledger.cache_hits, 0);
    assert!(off.ledger.cache.is_empty());
    assert_eq!(on.ledger.cache.len() as u64, on.ledger.evaluations);
    assert!(on.ledger.evaluations < off.ledger.evaluations);
    // Every child joins the next population, so the designs simulated are exactly the
    // distinct designs seen.
    assert_eq!(on.ledger.evaluations as usize, seen_on.len());
    assert!(seen_on.iter().all(|g| on.ledger.cache.contains_key(g)));
}
