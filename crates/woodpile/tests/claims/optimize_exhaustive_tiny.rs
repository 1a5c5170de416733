//! Claim: on a problem small enough to enumerate (4 positions, 3 rods: 81 designs, a 0.3 ms
//! impact) the breeder GA finds the true optimum, for several seeds.
//!
//! Tolerance: none. The GA evaluates designs with the same deterministic simulation as the
//! enumeration, so the best value must be bit-identical to the exhaustive minimum.

use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, StandardObjective};
use woodpile::{CellModel, Element, Method, RunSettings};

fn tiny() -> DesignSpace {
    let mut s = DesignSpace::paper_impact(CellModel::Resonant);
    s.positions = 4;
    s.catalogue = [20, 50, 80]
        .iter()
        .map(|&l| Element::table1_rod(l, CellModel::Resonant).unwrap())
        .collect();
    s.settings = RunSettings {
        duration_s: 3e-4,
        method: Method::Rk4 { time_step_s: 2e-7 },
        sample_interval_s: 1e-6,
    };
    s
}

#[test]
fn ga_finds_the_exhaustive_optimum_of_81_designs() {
    let settings = GaSettings {
        population: 16,
        truncation: 0.5,
        generations: 40,
        stall_generations: Some(20),
        threads: 2,
        ..GaSettings::default()
    };
    let reference = BreederGa::new(
        tiny(),
        Box::new(StandardObjective::TransmittedForce),
        settings,
    )
    .unwrap();
    let mut values: Vec<(f64, Vec<u8>)> = (0..81u32)
        .map(|k| {
            let g: Vec<u8> = (0..4).map(|i| ((k / 3u32.pow(i)) % 3) as u8).collect();
            (reference.evaluate(&g).unwrap(), g)
        })
        .collect();
    values.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (best, best_genome) = values[0].clone();
    assert!(
        values[1].0 > best,
        "the optimum must be unique for this test to mean something"
    );
    for seed in 1..=5 {
        let ga = BreederGa::new(
            tiny(),
            Box::new(StandardObjective::TransmittedForce),
            GaSettings { seed, ..settings },
        )
        .unwrap();
        let out = ga
            .run(None, &AtomicBool::new(false), &mut |_| {
                ControlFlow::Continue(())
            })
            .unwrap();
        let found = out.state.best();
        assert_eq!(
            found.objective.to_bits(),
            best.to_bits(),
            "seed {seed}: GA best {:?} = {} N, exhaustive best {:?} = {} N",
            found.genome,
            found.objective,
            best_genome,
            best
        );
        assert_eq!(found.genome, best_genome);
        assert!(
            out.state.ledger.evaluations <= 81,
            "the cache simulates each design once"
        );
        let at = out.state.history.iter().position(|h| h.best == best);
        eprintln!(
            "seed {seed}: optimum from generation {at:?}, {} evaluations, {} generations",
            out.state.ledger.evaluations, out.state.generation
        );
    }
}
