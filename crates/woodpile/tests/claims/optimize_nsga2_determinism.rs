//! Claim: NSGA-II keeps the breeder GA's guarantees: a run is bit-identical on 1 or 2 threads, in
//! 1 or 4 SIMD lanes and with the cache on or off, and a run stopped after any generation and
//! resumed from its state ends exactly where the uninterrupted run ends. Every design it keeps
//! meets the constraints that are known before a run.
//!
//! Tolerance: none (bit for bit): every draw is on the calling thread from a per-generation
//! stream, values are written back by index and ties are broken by genome.

use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{
    DesignFigure, DesignSpace, Nsga2, Nsga2Settings, Nsga2State, StandardObjective,
};
use woodpile::{CellModel, LaneWidth, Method, RunSettings};

fn space() -> DesignSpace {
    let mut s = DesignSpace::paper_impact(CellModel::Resonant);
    s.positions = 6;
    s.settings = RunSettings {
        duration_s: 5e-4,
        method: Method::for_peak_tolerance(1e-4).unwrap(),
        sample_interval_s: 5e-4,
    };
    s.constraints.max_total_mass_kg = Some(12e-3);
    s
}

fn ga(threads: usize, lanes: LaneWidth, cache: bool) -> Nsga2 {
    let settings = Nsga2Settings {
        population: 12,
        generations: 6,
        stall_generations: None,
        seed: 7,
        threads,
        cache,
        ..Nsga2Settings::default()
    };
    let objectives = vec![
        DesignFigure::Run(StandardObjective::TransmittedForce),
        DesignFigure::TotalMass,
        DesignFigure::MaxContactPressure,
    ];
    Nsga2::new(space(), objectives, settings)
        .unwrap()
        .with_lanes(lanes)
}

fn run(ga: &Nsga2, from: Option<Nsga2State>) -> Nsga2State {
    ga.run(from, &AtomicBool::new(false), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap()
    .0
}

fn same(a: &Nsga2State, b: &Nsga2State) {
    assert_eq!(a.population, b.population);
    assert_eq!(a.reference_point, b.reference_point);
    let hv = |s: &Nsga2State| -> Vec<u64> {
        s.history.iter().map(|h| h.hypervolume.to_bits()).collect()
    };
    assert_eq!(hv(a), hv(b));
}

#[test]
fn nsga2_is_bit_identical_across_threads_lanes_cache_and_resume() {
    let reference = run(&ga(1, LaneWidth::One, true), None);
    for (threads, lanes, cache) in [(2, LaneWidth::Four, true), (2, LaneWidth::Four, false)] {
        same(&reference, &run(&ga(threads, lanes, cache), None));
    }
    let ga = ga(2, LaneWidth::Four, true);
    for stop_after in [0, 3] {
        let (partial, _) = ga
            .run(None, &AtomicBool::new(false), &mut |s| {
                if s.generation == stop_after {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            })
            .unwrap();
        assert_eq!(partial.generation, stop_after);
        same(&reference, &run(&ga, Some(partial)));
    }
    let mass = |g: &[u8]| ga.space().mass_kg(g);
    for ind in &reference.population {
        assert!(
            mass(&ind.genome) <= 12e-3 * (1.0 + 1e-12),
            "mass limit broken by {:?}",
            ind.genome
        );
        assert_eq!(ind.objectives[1].to_bits(), mass(&ind.genome).to_bits());
        assert!(
            ind.objectives[2] > 1e8,
            "a contact pressure of {} Pa under a 127 N impact is not Hertzian",
            ind.objectives[2]
        );
    }
}
