//! Claim: with the number of layers part of the design, every design NSGA-II and the breeder GA
//! hold in every generation has 3 to 8 layers, its top layer fixed and its mass and height
//! within their limits, and the runs do mix lengths (a generation holds designs of several
//! lengths, which the lanes run in separate groups). The runs keep their guarantees: the same
//! seed gives the same state bit for bit on 1 or 2 threads and with the cache on or off, and
//! each final design's value is what simulating that design alone gives.
//!
//! Tolerance: the limits are compared with the library's relative slack of 1e-12; everything
//! else is bit for bit (draws on the calling thread, values written back by index).

use std::collections::BTreeSet;
use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{
    BreederGa, DesignFigure, DesignSpace, GaSettings, GaState, Nsga2, Nsga2Settings, Nsga2State,
    StandardObjective,
};
use woodpile::{CellModel, Method, RunSettings};

const MAX_MASS_KG: f64 = 25e-3;
const MAX_HEIGHT_M: f64 = 35e-3;
/// Every Table 1 rod is 5 mm across (paper §2).
const ROD_DIAMETER_M: f64 = 5e-3;

fn space() -> DesignSpace {
    let mut s = DesignSpace::paper_impact(CellModel::Resonant);
    s.positions = 3;
    s.max_positions = Some(8);
    s.settings = RunSettings {
        duration_s: 4e-4,
        method: Method::for_peak_tolerance(1e-4).unwrap(),
        sample_interval_s: 4e-4,
    };
    s.constraints.max_total_mass_kg = Some(MAX_MASS_KG);
    s.constraints.max_stack_height_m = Some(MAX_HEIGHT_M);
    s.constraints.fixed = vec![(0, 6)];
    s
}

/// Checks every design of a generation from the constraints' definitions; returns its lengths.
fn check_generation(space: &DesignSpace, genomes: &[&[u8]]) -> BTreeSet<usize> {
    for g in genomes {
        assert!((3..=8).contains(&g.len()), "{g:?}");
        assert_eq!(g[0], 6, "top layer fixed: {g:?}");
        let mass: f64 = g
            .iter()
            .map(|&x| space.catalogue[usize::from(x)].cell.total_mass_kg())
            .sum();
        assert!(mass <= MAX_MASS_KG * (1.0 + 1e-12), "{g:?}: {mass} kg");
        let height = g.len() as f64 * ROD_DIAMETER_M;
        assert!(height <= MAX_HEIGHT_M * (1.0 + 1e-12), "{g:?}: {height} m");
    }
    genomes.iter().map(|g| g.len()).collect()
}

fn nsga2(threads: usize, cache: bool) -> Nsga2 {
    let settings = Nsga2Settings {
        population: 16,
        generations: 6,
        stall_generations: None,
        seed: 3,
        threads,
        cache,
        ..Nsga2Settings::default()
    };
    let objectives = vec![
        DesignFigure::Run(StandardObjective::TransmittedForce),
        DesignFigure::Layers,
    ];
    Nsga2::new(space(), objectives, settings).unwrap()
}

fn run_nsga2(ga: &Nsga2, lengths: &mut BTreeSet<usize>) -> Nsga2State {
    let (mut state, _) = ga
        .run(None, &AtomicBool::new(false), &mut |s| {
            let genomes: Vec<&[u8]> = s.population.iter().map(|i| &i.genome[..]).collect();
            let seen = check_generation(ga.space(), &genomes);
            if s.generation > 0 {
                assert!(seen.len() > 1, "generation {} has one length", s.generation);
            }
            lengths.extend(seen);
            ControlFlow::Continue(())
        })
        .unwrap();
    state.elapsed_s = 0.0;
    state.history.iter_mut().for_each(|h| h.elapsed_s = 0.0);
    state
}

#[test]
fn nsga2_keeps_lengths_and_limits_in_every_generation() {
    let mut lengths = BTreeSet::new();
    let two = run_nsga2(&nsga2(2, true), &mut lengths);
    // 7 layers are 35 mm: the height limit leaves 3..=7.
    assert!(
        lengths.len() >= 3 && lengths.iter().all(|&n| n <= 7),
        "{lengths:?}"
    );
    assert_eq!(run_nsga2(&nsga2(1, true), &mut lengths), two);
    // Without the cache: the same designs and fronts (the counters and the cache differ).
    let uncached = run_nsga2(&nsga2(2, false), &mut lengths);
    assert_eq!(uncached.population, two.population);
    let hv = |s: &Nsga2State| s.history.iter().map(|h| h.hypervolume).collect::<Vec<_>>();
    assert_eq!(hv(&uncached), hv(&two));
}

fn breeder(threads: usize) -> BreederGa {
    let settings = GaSettings {
        population: 16,
        generations: 6,
        stall_generations: None,
        seed: 3,
        threads,
        ..GaSettings::default()
    };
    BreederGa::new(
        space(),
        Box::new(StandardObjective::TransmittedForce),
        settings,
    )
    .unwrap()
}

fn run_breeder(ga: &BreederGa, lengths: &mut BTreeSet<usize>) -> GaState {
    let mut state = ga
        .run(None, &AtomicBool::new(false), &mut |s| {
            let genomes: Vec<&[u8]> = s.population.iter().map(|i| &i.genome[..]).collect();
            lengths.extend(check_generation(ga.space(), &genomes));
            ControlFlow::Continue(())
        })
        .unwrap()
        .state;
    state.elapsed_s = 0.0;
    state.history.iter_mut().for_each(|h| h.elapsed_s = 0.0);
    state
}

#[test]
fn breeder_keeps_lengths_and_limits_in_every_generation() {
    let mut lengths = BTreeSet::new();
    let ga = breeder(2);
    let two = run_breeder(&ga, &mut lengths);
    assert!(lengths.len() >= 3, "{lengths:?}");
    assert_eq!(run_breeder(&breeder(1), &mut lengths), two);
    // A generation of mixed lengths, evaluated together, gives each design its own value.
    for ind in &two.population {
        assert_eq!(ga.evaluate(&ind.genome).unwrap(), ind.objective);
    }
}
