//! How accurate are the contact peaks for a given integrator setting? For the paper's four kinds
//! of run (impact and blast, resonant and rigid cells, on the docs/physics.md §9 chain), prints the
//! worst relative error over every contact peak against a converged reference (DOPRI5,
//! rtol = 1e-12), the contact it occurs at, and the work (right-hand-side evaluations).
//! This is the measurement behind `Method::for_peak_tolerance` (docs/physics.md §8).
//!
//! Run: `cargo run --release -p woodpile --example peak_tolerance`

use woodpile::{
    simulate, BlastProfile, CellModel, ChainBuilder, Excitation, Method, RunSettings, RunSummary,
    Striker, PAPER_OPTIMIZED_CHAIN_MM,
};

fn main() -> woodpile::Result<()> {
    let cases = [
        ("impact resonant", CellModel::Resonant, true),
        ("impact rigid", CellModel::Rigid, true),
        ("blast resonant", CellModel::Resonant, false),
        ("blast rigid", CellModel::Rigid, false),
    ];
    let mut methods: Vec<(String, Method)> = Vec::new();
    for tol in [1e-3, 1e-4, 1e-5, 1e-6] {
        methods.push((
            format!("tolerance {tol:e}"),
            Method::for_peak_tolerance(tol)?,
        ));
    }
    for rtol in [
        1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11,
    ] {
        methods.push((
            format!("dopri5 rtol={rtol:e}"),
            Method::Dopri5 {
                rtol,
                atol: rtol * 1e-6,
            },
        ));
        methods.push((
            format!("events rtol={rtol:e}"),
            Method::Dopri5Events {
                rtol,
                atol: rtol * 1e-6,
            },
        ));
    }
    for (name, cells, impact) in cases {
        let chain = ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, cells)?.build()?;
        let (excitation, base) = if impact {
            (
                Excitation::Impact(Striker::paper()),
                RunSettings::paper_impact(),
            )
        } else {
            (
                Excitation::Blast(BlastProfile::paper()),
                RunSettings::paper_blast(),
            )
        };
        let run = |method: Method| -> woodpile::Result<RunSummary> {
            let settings = RunSettings {
                method,
                sample_interval_s: base.duration_s,
                ..base
            };
            simulate(&chain, &excitation, &settings, &mut ())
        };
        let reference = run(Method::Dopri5 {
            rtol: 1e-12,
            atol: 1e-18,
        })?;
        println!(
            "{name}: transmitted peak {:.9} N",
            reference.transmitted_peak_force_n
        );
        for (label, method) in &methods {
            let s = run(*method)?;
            let (contact, worst) = s
                .contact_peak_forces_n
                .iter()
                .zip(&reference.contact_peak_forces_n)
                .map(|(&a, &b)| ((a - b) / b).abs())
                .enumerate()
                .fold(
                    (0, 0.0),
                    |best, (c, e)| if e > best.1 { (c, e) } else { best },
                );
            let rtol = match method {
                Method::Dopri5 { rtol, .. } | Method::Dopri5Events { rtol, .. } => *rtol,
                Method::Rk4 { .. } => f64::NAN,
            };
            println!(
                "  {label:<22} rtol {rtol:>8.2e}  rhs {:>7}  worst peak error {worst:.2e} (contact {contact}), {:.2} rtol^0.6, {:.2} rtol^0.75",
                s.stats.rhs_evaluations,
                worst / rtol.powf(0.6),
                worst / rtol.powf(0.75)
            );
        }
    }
    Ok(())
}
