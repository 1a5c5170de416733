//! How accurate are the contact peaks for a given integrator setting? For the paper's four kinds
//! of run (impact and blast, resonant and rigid cells, on the docs/physics.md §9 chain), prints the
//! worst relative error over every contact peak against a converged reference (DOPRI5,
//! rtol = 1e-12), the contact it occurs at, and the work (right-hand-side evaluations), then per
//! setting the worst over the four runs and the evaluations summed. The settings: `peak_tolerance`
//! 1e-3 … 1e-6 (family `tolerance`), and plain (`dopri5`) and event-aware (`events`) DOPRI5 at
//! rtol 1e-5 … 3e-11. This is the measurement behind `Method::for_peak_tolerance`
//! (docs/physics.md §8).
//!
//! Run: `cargo run --release -p woodpile --example peak_tolerance [-- --families tolerance,events]`

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
    // Which families of settings to measure: `--families tolerance,dopri5,events` (default: all).
    let families: Vec<String> = std::env::args()
        .skip_while(|a| a != "--families")
        .nth(1)
        .unwrap_or_else(|| "tolerance,dopri5,events".to_string())
        .split(',')
        .map(str::to_string)
        .collect();
    let want = |f: &str| families.iter().any(|g| g == f);
    let mut methods: Vec<(String, Method)> = Vec::new();
    if want("tolerance") {
        for tol in [1e-3, 1e-4, 1e-5, 1e-6] {
            methods.push((
                format!("tolerance {tol:e}"),
                Method::for_peak_tolerance(tol)?,
            ));
        }
    }
    for rtol in [
        1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11,
    ] {
        let atol = rtol * 1e-6;
        for (family, method) in [
            ("dopri5", Method::Dopri5 { rtol, atol }),
            ("events", Method::Dopri5Events { rtol, atol }),
        ] {
            if want(family) {
                methods.push((format!("{family} rtol={rtol:e}"), method));
            }
        }
    }
    // Per setting, over the four runs: the worst error and the evaluations summed.
    let mut totals = vec![(0.0f64, 0u64); methods.len()];
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
        for ((label, method), total) in methods.iter().zip(&mut totals) {
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
            let rtol = rtol_of(method);
            total.0 = total.0.max(worst);
            total.1 += s.stats.rhs_evaluations;
            println!(
                "  {label:<22} rtol {rtol:>8.2e}  rhs {:>7}  worst peak error {worst:.2e} (contact {contact}), {:.2} rtol^0.6, {:.2} rtol^0.75",
                s.stats.rhs_evaluations,
                worst / rtol.powf(0.6),
                worst / rtol.powf(0.75)
            );
        }
    }
    println!("over the four runs:");
    for ((label, method), (worst, rhs)) in methods.iter().zip(&totals) {
        let rtol = rtol_of(method);
        println!(
            "  {label:<26} rhs {rhs:>8}  worst peak error {worst:.2e}, {:.2} rtol^0.75",
            worst / rtol.powf(0.75)
        );
    }
    Ok(())
}

fn rtol_of(method: &Method) -> f64 {
    match method {
        Method::Dopri5 { rtol, .. } | Method::Dopri5Events { rtol, .. } => *rtol,
        Method::Rk4 { .. } => f64::NAN,
    }
}
