//! A fixed amount of work for instruction counts (`valgrind --tool=callgrind`), which repeat
//! whatever the load on a shared machine, unlike times. Two workloads:
//!
//! - `single`: one run of the benchmark problem (docs/physics.md §9 chain, resonant, the default
//!   impact, 2 ms, peaks only), `--repeat` times;
//! - `ga`: the first `--designs` designs of the paper's impact GA (generation 0, seed 1) through
//!   `BreederGa::evaluate_designs` on `--threads` threads (default 1), lanes `--lanes` wide (1, 2,
//!   4 or 8; default 4).
//!
//! The method: `--rk4 DT` (fixed step \[s\]), `--rtol R` (DOPRI5, atol = R·1e-6; with `--events`
//! event-aware, `Method::Dopri5Events`; with `--rkn` RKN 6(4), `Method::Rkn64`) or `--tol T`
//! (`Method::for_peak_tolerance`); default `--tol 1e-4`. Prints the objective values' sum and the
//! RHS evaluations so that two builds can be checked to do the same work.
//!
//! Run: `cargo build --release -p woodpile --example workload && valgrind --tool=callgrind
//! target/release/examples/workload ga --designs 48 --tol 1e-4`

use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, StandardObjective};
use woodpile::{
    simulate, CellModel, ChainBuilder, Excitation, LaneWidth, Method, RunSettings, Striker,
    PAPER_OPTIMIZED_CHAIN_MM,
};

fn arg<T: std::str::FromStr>(name: &str) -> Option<T> {
    std::env::args()
        .skip_while(|a| a != name)
        .nth(1)
        .map(|s| s.parse().ok().expect("a number"))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mode = std::env::args().nth(1).unwrap_or_else(|| "ga".to_string());
    let method = if let Some(dt) = arg::<f64>("--rk4") {
        Method::Rk4 { time_step_s: dt }
    } else if let Some(rtol) = arg::<f64>("--rtol") {
        if std::env::args().any(|a| a == "--rkn") {
            Method::Rkn64 {
                rtol,
                atol: rtol * 1e-6,
            }
        } else if std::env::args().any(|a| a == "--events") {
            Method::Dopri5Events {
                rtol,
                atol: rtol * 1e-6,
            }
        } else {
            Method::Dopri5 {
                rtol,
                atol: rtol * 1e-6,
            }
        }
    } else {
        Method::for_peak_tolerance(arg::<f64>("--tol").unwrap_or(1e-4))?
    };
    let settings = RunSettings {
        method,
        ..RunSettings::paper_impact()
    };
    match mode.as_str() {
        "single" => {
            let chain = ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, CellModel::Resonant)?
                .build()?;
            let settings = RunSettings {
                sample_interval_s: settings.duration_s,
                ..settings
            };
            let impact = Excitation::Impact(Striker::paper());
            for _ in 0..arg::<usize>("--repeat").unwrap_or(1) {
                let s = simulate(&chain, &impact, &settings, &mut ())?;
                println!(
                    "transmitted {:.12e} N, rhs {}",
                    s.transmitted_peak_force_n, s.stats.rhs_evaluations
                );
            }
        }
        _ => {
            let mut space = DesignSpace::paper_impact(CellModel::Resonant);
            space.settings = settings;
            let n = arg::<usize>("--designs").unwrap_or(48);
            let lanes = LaneWidth::from_lanes(arg::<usize>("--lanes").unwrap_or(4))?;
            let ga = BreederGa::new(
                space,
                Box::new(StandardObjective::TransmittedForce),
                GaSettings {
                    population: n,
                    threads: arg::<usize>("--threads").unwrap_or(1),
                    seed: 1,
                    ..GaSettings::default()
                },
            )?
            .with_lanes(lanes);
            let designs = ga.initial_designs();
            let values = ga.evaluate_designs(&designs)?;
            println!(
                "{n} designs, sum of objectives {:.12e}",
                values.iter().sum::<f64>()
            );
        }
    }
    Ok(())
}
