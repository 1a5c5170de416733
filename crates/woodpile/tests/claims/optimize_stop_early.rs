//! Claim: early stopping (`ga.stop_early`) changes what a GA run costs, not what it chooses.
//! A design whose run is stopped once its transmitted peak exceeds the previous generation's
//! breeding cutoff is only known to be worse than that; the run breeds from the same pool, in
//! the same order, and reports the same best in every generation as the run that simulates
//! every design whole, with and without screening, on any thread count and lane width. The
//! lower bound kept for a stopped design is below its whole run's value.
//!
//! Tolerance: none (bit-identical choices: a stopped design that could breed is simulated
//! whole; the lower bound is exact arithmetic on the same steps, the running maximum of a
//! prefix of the whole run, times 1 − w with screening).

use crate::optimize_common::{self as common, pools_and_state as run};
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, OptimizeError, StandardObjective};
use woodpile::{simulate, simulate_many_stopping, Job, LaneWidth, Method, PeakWatch};

/// The shared small problem at `peak_tolerance = 1e-4`.
fn space() -> DesignSpace {
    common::space(Method::for_peak_tolerance(1e-4).unwrap())
}

/// The shared GA with the transmitted force as its objective.
fn ga(screen: Option<f64>, stop_early: bool, threads: usize, lanes: LaneWidth) -> BreederGa {
    common::ga(
        StandardObjective::TransmittedForce,
        screen,
        stop_early,
        threads,
        lanes,
    )
}

#[test]
fn stopping_early_keeps_every_choice_and_bounds_what_it_stopped() {
    let lanes = LaneWidth::detect();
    let (plain_pools, plain) = run(&ga(None, false, 2, lanes));
    for screen in [None, Some(1e-2)] {
        let stopping = ga(screen, true, 2, lanes);
        let (pools, state) = run(&stopping);
        for (g, (a, b)) in plain_pools.iter().zip(&pools).enumerate() {
            for (rank, (p, s)) in a.iter().zip(b).enumerate() {
                assert_eq!(
                    p.genome, s.genome,
                    "{screen:?}: generation {g}, rank {rank}"
                );
                assert!(!s.stopped, "{screen:?}: a stopped design in the pool");
                if s.bound == 0.0 {
                    assert_eq!(p.objective.to_bits(), s.objective.to_bits());
                }
            }
        }
        for (a, b) in plain.history.iter().zip(&state.history) {
            assert_eq!(
                a.best.to_bits(),
                b.best.to_bits(),
                "generation {}",
                a.generation
            );
        }
        // Runs were stopped: the claim is not vacuous.
        assert!(
            state.ledger.stopped.len() * 4 >= plain.ledger.evaluations as usize,
            "{screen:?}: {} of {} designs stopped",
            state.ledger.stopped.len(),
            plain.ledger.evaluations
        );
        // Each stopped design's lower bound is below its value at the run's settings.
        let stopped: Vec<(&Vec<u8>, &f64)> = state.ledger.stopped.iter().collect();
        let genomes: Vec<&[u8]> = stopped.iter().map(|(g, _)| &g[..]).collect();
        let whole = stopping.evaluate_designs(&genomes).unwrap();
        for ((g, &low), v) in stopped.iter().zip(whole) {
            assert!(
                low <= v,
                "{screen:?}: {g:?} stopped at {low} N, whole run {v} N"
            );
        }
    }
}

#[test]
fn a_stopping_run_does_not_depend_on_threads_or_lanes() {
    let (_, reference) = run(&ga(Some(1e-2), true, 2, LaneWidth::detect()));
    let (_, other) = run(&ga(Some(1e-2), true, 1, LaneWidth::One));
    assert_eq!(other.population, reference.population);
    assert_eq!(other.ledger, reference.ledger);
}

#[test]
fn a_stopped_run_is_a_prefix_of_the_whole_run() {
    let space = space();
    let chains: Vec<_> = [[0u8, 6, 3, 1, 5, 2, 4, 0], [6, 6, 5, 4, 3, 2, 1, 0]]
        .iter()
        .map(|g| space.chain(g).unwrap())
        .collect();
    let jobs = Job::for_each_chain(&chains, &space.excitation, &space.settings);
    for (chain, job) in chains.iter().zip(&jobs) {
        let whole = simulate(chain, &space.excitation, &space.settings, &mut ()).unwrap();
        let cutoff = 0.5 * whole.transmitted_peak_force_n;
        let mut stopped_by_width = Vec::new();
        for width in LaneWidth::ALL {
            let s = simulate_many_stopping(
                std::slice::from_ref(job),
                width,
                PeakWatch::FiguresOfMerit,
                cutoff,
            )
            .pop()
            .unwrap()
            .unwrap();
            let t = s.stopped_at_s.expect("stopped");
            assert!(t < space.settings.duration_s);
            assert!(s.transmitted_peak_force_n > cutoff);
            assert!(s.transmitted_peak_force_n <= whole.transmitted_peak_force_n);
            assert!(s.stats.steps < whole.stats.steps);
            stopped_by_width.push((t.to_bits(), s.transmitted_peak_force_n.to_bits()));
        }
        assert!(stopped_by_width.windows(2).all(|w| w[0] == w[1]));
    }
}

#[test]
fn stopping_early_needs_the_transmitted_peak() {
    let settings = GaSettings {
        stop_early: true,
        ..GaSettings::default()
    };
    let ratio = StandardObjective::TransmissionRatio;
    match BreederGa::new(space(), Box::new(ratio), settings) {
        Err(e @ OptimizeError::Model(_)) => {
            let text = e.to_string();
            assert!(
                text.contains("ga.stop_early") && text.contains("transmitted-force"),
                "{text}"
            );
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
}
