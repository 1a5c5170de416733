//! Design-study throughput: how many designs of the paper's impact problem (20 positions, Table 1
//! rods, resonant cells, the default striker and sensor, 2 ms) the GA's evaluator simulates per
//! second, at each accuracy setting, one design at a time (`simulate` per design, as the GA did
//! before lanes) and in SIMD lanes (`BreederGa::evaluate_designs`), on 1 and 2 threads; the
//! worst relative error of the objective (transmitted peak) over a sample of the designs against
//! a converged run; the paper's whole GA with and without screening and early stopping (wall time,
//! simulations, whether its choices are unchanged); and the cost per element of long chains. Medians of
//! `--runs` repetitions.
//!
//! Run: `cargo run --release -p woodpile --example throughput [-- --designs 400 --runs 3]`
//! (`-- --screening-only`: only the GA with and without screening and early stopping)
//! (bench/throughput.sh runs it beside the peers.)

use rayon::prelude::*;
use std::time::Instant;
use woodpile::optimize::{
    BreederGa, DesignSpace, GaSettings, Genome, Objective, StandardObjective,
};
use woodpile::{
    simulate, CellModel, ChainBuilder, Excitation, LaneWidth, Method, RunSettings, Striker,
};

fn arg(name: &str, default: usize) -> usize {
    std::env::args()
        .skip_while(|a| a != name)
        .nth(1)
        .map(|s| s.parse().expect("an integer"))
        .unwrap_or(default)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The paper's whole impact GA (μ = 100, its operators, stopping after 30 generations without
/// improvement), every contact peak within 1e-5, with and without screening: wall time, the
/// simulations at each accuracy, and whether every generation's breeding pool (genomes, in
/// order) and best value equal the unscreened run's; first with the method `peak_tolerance =
/// 1e-5` chose before RKN 6(4) (event-aware DOPRI5 at rtol 7.84e-9), for comparison.
fn screened_ga(runs: usize) -> woodpile::Result<()> {
    let previous = Method::Dopri5Events {
        rtol: 7.84e-9,
        atol: 7.84e-15,
    };
    let ga = |method: Method, screen: Option<f64>, stop_early: bool| {
        let mut space = DesignSpace::paper_impact(CellModel::Resonant);
        space.settings.method = method;
        let settings = GaSettings {
            threads: 2,
            screen_peak_tolerance: screen,
            stop_early,
            ..GaSettings::default()
        };
        Ok::<_, woodpile::Error>(
            BreederGa::new(
                space,
                Box::new(StandardObjective::TransmittedForce),
                settings,
            )
            .expect("the paper's problem"),
        )
    };
    let pool =
        woodpile::optimize::operators::truncation_pool(100, GaSettings::default().truncation);
    println!(
        "\npaper impact GA (population 100, peak_tolerance 1e-5, 2 threads), with screening \
         and early stopping:"
    );
    print_screened_header();
    // Each generation's breeding pool, and the best values: the run's choices.
    type Choices = (Vec<Vec<Genome>>, Vec<f64>);
    let mut reference: Option<Choices> = None;
    // The reference run's best design, re-run alone to compare its transmitted peak with the
    // incident one (the optimum should stay at most 20 % of the incident force).
    let mut optimum: Option<Genome> = None;
    let tolerance = Method::for_peak_tolerance(1e-5)?;
    for (method, screen, stop_early) in [
        (previous, None, false),
        (tolerance, None, false),
        (tolerance, Some(1e-3), false),
        (tolerance, Some(3e-3), false),
        (tolerance, None, true),
        (tolerance, Some(1e-3), true),
        (tolerance, Some(3e-4), true),
        (tolerance, Some(1e-4), true),
    ] {
        let ga = ga(method, screen, stop_early)?;
        let (wall, pools, state) = timed_runs(&ga, runs, pool);
        let bests: Vec<f64> = state.history.iter().map(|h| h.best).collect();
        // Designs the GA obtained a value for: the distinct designs it met (exact, screened or
        // stopped).
        let ledger = &state.ledger;
        let designs = (ledger.cache.keys())
            .chain(ledger.screened.keys())
            .chain(ledger.stopped.keys())
            .collect::<std::collections::HashSet<_>>()
            .len();
        let same = match (&reference, method == previous) {
            (_, true) => "(previous)".to_string(),
            (None, false) => {
                reference = Some((pools.clone(), bests.clone()));
                optimum = Some(state.population[0].genome.clone());
                "(reference)".to_string()
            }
            (Some((p, b)), false) => (p == &pools && b == &bests).to_string(),
        };
        let name = if method == previous {
            "dopri5-events 7.84e-9"
        } else {
            "tolerance 1e-5"
        };
        println!(
            "{:<32} {:>6} {:>8.2} {:>8} {:>10} {:>10} {:>8} {:>10.1} {:>13} {:>9.4}",
            format!(
                "{name}, {}, {}",
                screen.map_or("none".to_string(), |t| format!("{t:e}")),
                if stop_early { "stop" } else { "whole" }
            ),
            state.generation,
            wall,
            designs,
            state.ledger.evaluations,
            state.ledger.screenings,
            state.ledger.stopped.len(),
            designs as f64 / wall,
            same,
            bests.last().copied().unwrap_or(f64::NAN)
        );
    }
    if let Some(genome) = optimum {
        print_optimum(&genome, tolerance)?;
    }
    Ok(())
}

fn main() -> woodpile::Result<()> {
    let n_designs = arg("--designs", 400);
    let runs = arg("--runs", 3);
    if std::env::args().any(|a| a == "--screening-only") {
        return screened_ga(runs);
    }
    let objective = StandardObjective::TransmittedForce;
    let settings_for = |method: Method| RunSettings {
        method,
        ..RunSettings::paper_impact()
    };
    let ga = |method: Method, threads: usize, lanes: LaneWidth| {
        let mut space = DesignSpace::paper_impact(CellModel::Resonant);
        space.settings = settings_for(method);
        let settings = GaSettings {
            population: n_designs,
            threads,
            seed: 1,
            ..GaSettings::default()
        };
        BreederGa::new(space, Box::new(objective), settings)
            .expect("the paper's problem")
            .with_lanes(lanes)
    };
    let designs = ga(Method::paper(), 1, LaneWidth::One).initial_designs();
    let space = DesignSpace::paper_impact(CellModel::Resonant);
    let chains: Vec<_> = designs
        .iter()
        .map(|g| space.chain(g))
        .collect::<woodpile::Result<_>>()?;
    let impact = Excitation::Impact(Striker::paper());

    // Accuracy of the objective on a sample of the designs, against a converged run.
    let sample = &chains[..chains.len().min(24)];
    let converged: Vec<f64> = sample
        .par_iter()
        .map(|c| {
            objective.evaluate(
                c,
                &impact,
                &settings_for(Method::Dopri5 {
                    rtol: 1e-12,
                    atol: 1e-18,
                }),
            )
        })
        .collect::<woodpile::Result<_>>()?;
    let settings = compared_methods()?;
    println!(
        "{n_designs} designs of the paper's impact problem (GA generation 0, seed 1); lane width {:?} detected",
        LaneWidth::detect()
    );
    println!(
        "{:<22} {:>12} {:>8} {:>14} {:>14} {:>10}",
        "setting", "objective_err", "threads", "one_by_one/s", "lanes/s", "lane_gain"
    );
    for (name, method) in settings {
        let worst = sample
            .par_iter()
            .zip(&converged)
            .map(|(c, &r)| {
                objective
                    .evaluate(c, &impact, &settings_for(method))
                    .map(|v| ((v - r) / r).abs())
            })
            .collect::<woodpile::Result<Vec<f64>>>()?
            .into_iter()
            .fold(0.0, f64::max);
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("threads");
            let one_by_one = median(
                (0..runs)
                    .map(|_| {
                        let t = Instant::now();
                        pool.install(|| {
                            chains.par_iter().for_each(|c| {
                                objective
                                    .evaluate(c, &impact, &settings_for(method))
                                    .expect("runs");
                            })
                        });
                        n_designs as f64 / t.elapsed().as_secs_f64()
                    })
                    .collect(),
            );
            let lanes = ga(method, threads, LaneWidth::detect());
            let in_lanes = median(
                (0..runs)
                    .map(|_| {
                        let t = Instant::now();
                        lanes.evaluate_designs(&designs).expect("runs");
                        n_designs as f64 / t.elapsed().as_secs_f64()
                    })
                    .collect(),
            );
            println!(
                "{name:<22} {worst:>12.2e} {threads:>8} {one_by_one:>14.1} {in_lanes:>14.1} {:>9.2}x",
                in_lanes / one_by_one
            );
        }
    }

    screened_ga(runs)?;

    long_chains(runs, &impact)
}

/// The methods the evaluator is measured with.
fn compared_methods() -> woodpile::Result<Vec<(&'static str, Method)>> {
    Ok(vec![
        ("rk4 0.1us (paper)", Method::paper()),
        ("peak_tolerance 1e-5", Method::for_peak_tolerance(1e-5)?),
        ("peak_tolerance 1e-4", Method::for_peak_tolerance(1e-4)?),
        ("peak_tolerance 1e-3", Method::for_peak_tolerance(1e-3)?),
        (
            "events 7.84e-9 (was 1e-5)",
            Method::Dopri5Events {
                rtol: 7.84e-9,
                atol: 7.84e-15,
            },
        ),
        (
            "rkn64 rtol 1e-6",
            Method::Rkn64 {
                rtol: 1e-6,
                atol: 1e-12,
            },
        ),
        (
            "rkn64 rtol 3e-7",
            Method::Rkn64 {
                rtol: 3e-7,
                atol: 3e-13,
            },
        ),
        (
            "events rtol 3e-7",
            Method::Dopri5Events {
                rtol: 3e-7,
                atol: 3e-13,
            },
        ),
        (
            "events rtol 1e-7",
            Method::Dopri5Events {
                rtol: 1e-7,
                atol: 1e-13,
            },
        ),
        (
            "dopri5 rtol 1e-8",
            Method::Dopri5 {
                rtol: 1e-8,
                atol: 1e-14,
            },
        ),
    ])
}

/// Cost per element of long chains: 40 mm rods, RK4 at 0.1 µs, 50 µs of simulated time.
fn long_chains(runs: usize, impact: &Excitation) -> woodpile::Result<()> {
    println!("\nlong chains (40 mm rods, rk4 0.1 us, 50 us simulated, one thread):");
    println!(
        "{:>10} {:>12} {:>22}",
        "elements", "median_ms", "ns/element/us_sim"
    );
    for n in [10usize, 100, 1_000, 10_000] {
        let chain = ChainBuilder::table1_rods(&vec![40; n], CellModel::Resonant)?.build()?;
        let settings = RunSettings {
            duration_s: 5e-5,
            method: Method::paper(),
            sample_interval_s: 5e-5,
        };
        let ms = median(
            (0..runs)
                .map(|_| {
                    simulate(&chain, impact, &settings, &mut ())
                        .map(|s| s.wall_time_s * 1e3)
                        .expect("runs")
                })
                .collect(),
        );
        println!(
            "{n:>10} {ms:>12.3} {:>22.2}",
            ms * 1e6 / (n as f64 * settings.duration_s * 1e6)
        );
    }
    Ok(())
}

/// The reference run's best design, re-run alone: its transmitted peak against the incident one.
fn print_optimum(genome: &Genome, method: Method) -> woodpile::Result<()> {
    let mut space = DesignSpace::paper_impact(CellModel::Resonant);
    space.settings.method = method;
    let settings = RunSettings {
        sample_interval_s: space.settings.duration_s,
        ..space.settings
    };
    let run = simulate(&space.chain(genome)?, &space.excitation, &settings, &mut ())?;
    println!(
        "optimum {}: transmitted peak {:.4} N of {:.2} N incident ({:.1} %)",
        space.labels(genome).join(" "),
        run.transmitted_peak_force_n,
        run.incident_peak_force_n,
        100.0 * run.transmitted_peak_force_n / run.incident_peak_force_n
    );
    Ok(())
}

/// `runs` runs of `ga`: the median wall time \[s\], and the last run's breeding pools (the first
/// `pool` of each generation) and final state.
fn timed_runs(
    ga: &BreederGa,
    runs: usize,
    pool: usize,
) -> (f64, Vec<Vec<Genome>>, woodpile::optimize::GaState) {
    let mut walls = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let mut pools: Vec<Vec<Genome>> = Vec::new();
        let t = Instant::now();
        let outcome = ga
            .run(None, &Default::default(), &mut |s| {
                pools.push(
                    s.population[..pool]
                        .iter()
                        .map(|i| i.genome.clone())
                        .collect(),
                );
                std::ops::ControlFlow::Continue(())
            })
            .expect("the paper's GA runs");
        walls.push(t.elapsed().as_secs_f64());
        last = Some((pools, outcome.state));
    }
    let (pools, state) = last.expect("at least one run");
    (median(walls), pools, state)
}

/// The header of the screened GA's table.
fn print_screened_header() {
    println!(
        "{:<32} {:>6} {:>8} {:>8} {:>10} {:>10} {:>8} {:>10} {:>13} {:>9}",
        "method, screen, stop",
        "gens",
        "wall_s",
        "designs",
        "exact_runs",
        "screenings",
        "stopped",
        "designs/s",
        "same_choices",
        "best_N"
    );
}
