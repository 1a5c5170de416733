//! Does event-aware stepping (`Method::Dopri5Events`) buy accuracy for its work? For DOPRI5
//! with and without it, at a grid of tolerances, prints
//!
//! - on the paper's four kinds of run (the docs/physics.md §9 chain under the paper's impact and
//!   blast, resonant and rigid cells): the worst relative error over every contact peak against a
//!   converged run (DOPRI5, rtol = 1e-12), and the right-hand-side evaluations, per run and
//!   summed over the four (as `examples/peak_tolerance.rs` measures the rule);
//! - on the first `--designs` designs of the paper's impact GA (generation 0, seed 1): the worst
//!   relative error of the objective (the transmitted peak) against the converged run and the
//!   mean evaluations per design.
//!
//! Run: `cargo run --release -p woodpile --example event_stepping [-- --designs 48]`

use rayon::prelude::*;
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, StandardObjective};
use woodpile::{
    simulate, BlastProfile, CellModel, Chain, ChainBuilder, Excitation, Method, RunSettings,
    RunSummary, Striker, PAPER_OPTIMIZED_CHAIN_MM,
};

const RTOLS: [f64; 8] = [1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 1e-10];

fn methods(rtol: f64) -> [(&'static str, Method); 2] {
    let atol = rtol * 1e-6;
    [
        ("dopri5", Method::Dopri5 { rtol, atol }),
        ("dopri5-events", Method::Dopri5Events { rtol, atol }),
    ]
}

fn run(chain: &Chain, excitation: &Excitation, method: Method) -> woodpile::Result<RunSummary> {
    let base = RunSettings::paper_for(excitation);
    let settings = RunSettings {
        method,
        sample_interval_s: base.duration_s,
        ..base
    };
    simulate(chain, excitation, &settings, &mut ())
}

fn converged(chain: &Chain, excitation: &Excitation) -> woodpile::Result<RunSummary> {
    run(
        chain,
        excitation,
        Method::Dopri5 {
            rtol: 1e-12,
            atol: 1e-18,
        },
    )
}

fn worst_peak_error(s: &RunSummary, reference: &RunSummary) -> f64 {
    s.contact_peak_forces_n
        .iter()
        .zip(&reference.contact_peak_forces_n)
        .map(|(&a, &b)| ((a - b) / b).abs())
        .fold(0.0, f64::max)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n_designs: usize = std::env::args()
        .skip_while(|a| a != "--designs")
        .nth(1)
        .map(|s| s.parse().expect("an integer"))
        .unwrap_or(48);
    let mut cases = Vec::new();
    for cells in [CellModel::Resonant, CellModel::Rigid] {
        for excitation in [
            Excitation::Impact(Striker::paper()),
            Excitation::Blast(BlastProfile::paper()),
        ] {
            let chain = ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, cells)?.build()?;
            let reference = converged(&chain, &excitation)?;
            cases.push((cells, excitation, chain, reference));
        }
    }
    println!(
        "paper's four runs: worst contact-peak error (rhs evaluations) per run; worst and sum"
    );
    for rtol in RTOLS {
        for (name, method) in methods(rtol) {
            let mut line = format!("{name:<14} rtol {rtol:7.1e}");
            let (mut worst, mut sum) = (0.0_f64, 0);
            for (_, excitation, chain, reference) in &cases {
                let s = run(chain, excitation, method)?;
                let e = worst_peak_error(&s, reference);
                worst = worst.max(e);
                sum += s.stats.rhs_evaluations;
                line += &format!("  {e:.2e} ({:>6})", s.stats.rhs_evaluations);
            }
            println!("{line}  | worst {worst:.2e}  sum {sum:>7}");
        }
    }

    let space = DesignSpace::paper_impact(CellModel::Resonant);
    let ga = BreederGa::new(
        space.clone(),
        Box::new(StandardObjective::TransmittedForce),
        GaSettings {
            population: n_designs,
            threads: 1,
            seed: 1,
            ..GaSettings::default()
        },
    )?;
    let chains: Vec<Chain> = ga
        .initial_designs()
        .iter()
        .map(|g| space.chain(g))
        .collect::<woodpile::Result<_>>()?;
    let impact = Excitation::Impact(Striker::paper());
    let reference: Vec<f64> = chains
        .par_iter()
        .map(|c| converged(c, &impact).map(|s| s.transmitted_peak_force_n))
        .collect::<woodpile::Result<_>>()?;
    println!("\n{n_designs} GA designs (generation 0, seed 1): worst objective error, mean rhs evaluations");
    for rtol in RTOLS {
        for (name, method) in methods(rtol) {
            let runs: Vec<RunSummary> = chains
                .par_iter()
                .map(|c| run(c, &impact, method))
                .collect::<woodpile::Result<_>>()?;
            let worst = runs
                .iter()
                .zip(&reference)
                .map(|(s, r)| ((s.transmitted_peak_force_n - r) / r).abs())
                .fold(0.0, f64::max);
            let mean =
                runs.iter().map(|s| s.stats.rhs_evaluations).sum::<u64>() as f64 / n_designs as f64;
            println!("{name:<14} rtol {rtol:7.1e}  objective error {worst:.2e}  rhs {mean:>8.0}");
        }
    }
    Ok(())
}
