//! How accurate are a design study's figures of merit (the incident and the transmitted peak) for
//! a given integrator setting? Over the paper's four kinds of run (docs/physics.md §9 chain:
//! impact and blast, resonant and rigid cells), the first `--designs` designs of the paper's
//! impact GA (generation 0, seed 1) and the final population of a short GA run from them (designs
//! a search converges to, whose transmitted peak is small), prints for event-aware DOPRI5 and for
//! RKN 6(4) (`--method rkn64`: the impacts only) at each rtol the worst relative error of either
//! figure against a converged run (DOPRI5, rtol = 1e-12), the ratio worst / rtol^0.75 and the
//! mean evaluations per run (docs/physics.md §8).
//!
//! Run: `cargo run --release -p woodpile --example figures_of_merit_accuracy [-- --designs 96
//! --method rkn64]`

use rayon::prelude::*;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, StandardObjective};
use woodpile::{
    simulate, BlastProfile, CellModel, Chain, ChainBuilder, Excitation, Method, RunSettings,
    RunSummary, Striker, PAPER_OPTIMIZED_CHAIN_MM,
};

const RTOLS: [f64; 12] = [
    1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11,
];

fn run(
    chain: &Chain,
    excitation: &Excitation,
    base: &RunSettings,
    method: Method,
) -> woodpile::Result<RunSummary> {
    let settings = RunSettings {
        method,
        sample_interval_s: base.duration_s,
        ..*base
    };
    simulate(chain, excitation, &settings, &mut ())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n_designs: usize = std::env::args()
        .skip_while(|a| a != "--designs")
        .nth(1)
        .map_or(Ok(96), |s| s.parse())?;
    let rkn = std::env::args().any(|a| a == "rkn64");
    let impact = Excitation::Impact(Striker::paper());
    let blast = Excitation::Blast(BlastProfile::paper());
    let mut cases: Vec<(Chain, &Excitation, RunSettings)> = Vec::new();
    for cells in [CellModel::Resonant, CellModel::Rigid] {
        let chain = ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, cells)?.build()?;
        cases.push((chain.clone(), &impact, RunSettings::paper_impact()));
        if !rkn {
            cases.push((chain, &blast, RunSettings::paper_blast()));
        }
    }
    let mut space = DesignSpace::paper_impact(CellModel::Resonant);
    space.settings.method = Method::for_peak_tolerance(1e-4)?;
    let ga = BreederGa::new(
        space.clone(),
        Box::new(StandardObjective::TransmittedForce),
        GaSettings {
            population: n_designs,
            generations: 15,
            seed: 1,
            ..GaSettings::default()
        },
    )?;
    let mut genomes = ga.initial_designs();
    let outcome = ga.run(None, &AtomicBool::new(false), &mut |_| {
        std::ops::ControlFlow::Continue(())
    })?;
    genomes.extend(outcome.state.population.iter().map(|i| i.genome.clone()));
    for g in &genomes {
        cases.push((space.chain(g)?, &impact, RunSettings::paper_impact()));
    }
    let figures = |s: &RunSummary| [s.incident_peak_force_n, s.transmitted_peak_force_n];
    let converged = Method::Dopri5 {
        rtol: 1e-12,
        atol: 1e-18,
    };
    let reference: Vec<[f64; 2]> = cases
        .par_iter()
        .map(|(c, e, b)| run(c, e, b, converged).map(|s| figures(&s)))
        .collect::<woodpile::Result<_>>()?;
    println!(
        "{} runs: {} paper cases, {n_designs} GA designs of generation 0 and {} of generation {}",
        cases.len(),
        if rkn { 2 } else { 4 },
        outcome.state.population.len(),
        outcome.state.generation
    );
    for rtol in RTOLS {
        let atol = rtol * 1e-6;
        let method = if rkn {
            Method::Rkn64 { rtol, atol }
        } else {
            Method::Dopri5Events { rtol, atol }
        };
        let runs: Vec<RunSummary> = cases
            .par_iter()
            .map(|(c, e, b)| run(c, e, b, method))
            .collect::<woodpile::Result<_>>()?;
        let mut worst = (0.0f64, 0usize);
        for (i, (s, r)) in runs.iter().zip(&reference).enumerate() {
            for (a, b) in figures(s).iter().zip(r) {
                let e = ((a - b) / b).abs();
                if e > worst.0 {
                    worst = (e, i);
                }
            }
        }
        let mean = runs
            .iter()
            .map(|s| s.stats.rhs_evaluations as f64)
            .sum::<f64>()
            / runs.len() as f64;
        println!(
            "{} rtol {rtol:7.1e}  worst figure-of-merit error {:.2e} (run {}), {:.3} rtol^0.75  mean rhs {mean:>7.0}",
            if rkn { "rkn64 " } else { "events" },
            worst.0,
            worst.1,
            worst.0 / rtol.powf(0.75)
        );
    }
    Ok(())
}
