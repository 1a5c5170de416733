//! Accuracy against cost for the benchmark problem: the docs/physics.md §9 chain (20 rods, resonant)
//! under the default impact, 2 ms. Prints, for RK4 at several steps, DOPRI5 and RKN 6(4) at
//! several tolerances, and the settings `peak_tolerance` chooses (docs/physics.md §8), the median
//! wall time of several runs and the relative error of the transmitted peak (and the worst
//! contact peak) against a converged reference (DOPRI5, rtol = 1e-12).
//!
//! Run: `cargo run --release -p woodpile --example accuracy_speed [-- --runs 9]`

use woodpile::{
    simulate, CellModel, ChainBuilder, Excitation, Method, RunSettings, RunSummary, Striker,
    PAPER_OPTIMIZED_CHAIN_MM,
};

/// An adaptive method's row label, its constructor from (rtol, atol) and its tolerances.
type AdaptiveFamily = (&'static str, fn(f64, f64) -> Method, [f64; 5]);

fn main() -> woodpile::Result<()> {
    let runs: usize = std::env::args()
        .skip_while(|a| a != "--runs")
        .nth(1)
        .map(|s| s.parse().expect("--runs takes an integer"))
        .unwrap_or(7);
    let chain =
        ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, CellModel::Resonant)?.build()?;
    let impact = Excitation::Impact(Striker::paper());
    // `sample_interval_s` = 1 µs observes energies on the full grid (as `woodpile simulate` does);
    // = duration observes only the start and the end (peaks are still taken over every step).
    let run = |method: Method, sample_interval_s: f64| -> woodpile::Result<(f64, RunSummary)> {
        let settings = RunSettings {
            method,
            sample_interval_s,
            ..RunSettings::paper_impact()
        };
        let mut times = Vec::with_capacity(runs);
        let mut last = None;
        for _ in 0..runs {
            let s = simulate(&chain, &impact, &settings, &mut ())?;
            times.push(s.wall_time_s);
            last = Some(s);
        }
        times.sort_by(f64::total_cmp);
        Ok((times[runs / 2], last.expect("runs >= 1")))
    };
    let (_, reference) = run(
        Method::Dopri5 {
            rtol: 1e-12,
            atol: 1e-18,
        },
        1e-6,
    )?;
    println!(
        "reference (dopri5, rtol 1e-12): transmitted peak {:.9} N, incident {:.9} N",
        reference.transmitted_peak_force_n, reference.incident_peak_force_n
    );
    println!(
        "{:<24} {:>10} {:>14} {:>10} {:>12} {:>14}",
        "method", "median_ms", "median_ms_peaks", "rhs_evals", "transm_err", "worst_peak_err"
    );
    let mut methods: Vec<(String, Method)> = [1e-7, 2e-7, 2.5e-7, 4e-7, 5e-7]
        .iter()
        .map(|&dt| {
            (
                format!("rk4 dt={:.2}us", dt * 1e6),
                Method::Rk4 { time_step_s: dt },
            )
        })
        .collect();
    // The adaptive methods, each at its tolerances (atol = rtol · 1e-6 m).
    let adaptive: [AdaptiveFamily; 2] = [
        (
            "dopri5",
            |rtol, atol| Method::Dopri5 { rtol, atol },
            [1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
        ),
        (
            "rkn64",
            |rtol, atol| Method::Rkn64 { rtol, atol },
            [1e-5, 3e-6, 1e-6, 1e-7, 1e-8],
        ),
    ];
    for (family, method, rtols) in adaptive {
        for rtol in rtols {
            methods.push((format!("{family} rtol={rtol:e}"), method(rtol, rtol * 1e-6)));
        }
    }
    for tolerance in [1e-3, 1e-4, 1e-5] {
        methods.push((
            format!("peak_tolerance {tolerance:e}"),
            Method::for_peak_tolerance(tolerance)?,
        ));
    }
    for (name, method) in methods {
        let (t, s) = run(method, 1e-6)?;
        let (t_peaks, _) = run(method, 2e-3)?;
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        let worst = s
            .contact_peak_forces_n
            .iter()
            .zip(&reference.contact_peak_forces_n)
            .map(|(&a, &b)| rel(a, b))
            .fold(0.0, f64::max);
        println!(
            "{:<24} {:>10.3} {:>14.3} {:>10} {:>12.2e} {:>14.2e}",
            name,
            t * 1e3,
            t_peaks * 1e3,
            s.stats.rhs_evaluations,
            rel(
                s.transmitted_peak_force_n,
                reference.transmitted_peak_force_n
            ),
            worst
        );
    }
    Ok(())
}
