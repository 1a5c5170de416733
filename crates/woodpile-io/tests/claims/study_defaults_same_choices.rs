//! Claim: a design study's accuracy-targeted default (every contact peak within 1e-5, new designs
//! screened at 3e-4, runs stopped early past the breeding cutoff) makes the same choices as the
//! paper's RK4 at 0.1 µs on both built-in paper problems (20 Table 1 rods under the impact and
//! under the blast): in every generation the same breeding pool (the best ⌈0.3 · 12⌉ = 4), design
//! for design and in the same order, and so the same children. (The rest of a population is
//! ordered by screened values or early-stopping bounds, which never decide a choice.)
//!
//! Scale: the built-in problems themselves (20 positions, 2 ms and 3 ms windows), with a small
//! GA (population 12, 3 generations after the first; the paper's is 100 × up to 100, which
//! would take minutes at RK4 in a test; bench/README.md measures full runs). Tolerance: none —
//! the claim is identity of the choices, not of the values (those differ by up to the accuracy).

use std::ops::ControlFlow;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::BreederGa;
use woodpile_io::optimize::{OptimizeConfig, Problem};

fn pools(config: &OptimizeConfig) -> Vec<Vec<Vec<u8>>> {
    let problem = Problem::new(config, Path::new("."), 2).unwrap();
    let ga = BreederGa::new(
        problem.space.clone(),
        Box::new(problem.objective),
        problem.settings,
    )
    .unwrap();
    let mut generations = Vec::new();
    ga.run(None, &AtomicBool::new(false), &mut |s| {
        generations.push(s.population[..4].iter().map(|i| i.genome.clone()).collect());
        ControlFlow::Continue(())
    })
    .unwrap();
    generations
}

#[test]
fn the_paper_problems_choose_the_same_either_way() {
    for name in ["paper-impact", "paper-blast"] {
        let mut config = OptimizeConfig::builtin(name).unwrap();
        config.ga.population = Some(12);
        config.ga.generations = Some(3);
        config.ga.stall_generations = Some(0);
        let fast = config.accuracy_targeted();
        assert_eq!(
            fast.run.peak_tolerance,
            Some(1e-5),
            "{name}: the default is targeted"
        );
        assert_eq!(fast.ga.screen_peak_tolerance, Some(3e-4));
        assert_eq!(fast.ga.stop_early, Some(true));
        config.ga.paper_settings = Some(true);
        let paper = config.accuracy_targeted();
        assert_eq!(
            paper.run.peak_tolerance, None,
            "{name}: --paper-settings is RK4"
        );
        assert_eq!(pools(&fast), pools(&paper), "{name}");
    }
}
