//! How accurate are the contact peaks for a given integrator setting? On the docs/physics.md §9
//! chain, resonant and rigid cells, under the paper's blast and under impacts at the paper's
//! striker speed, 1 m/s and 3 m/s, prints the worst relative error over every contact peak against
//! a converged reference (DOPRI5, rtol = 1e-13), the contact it occurs at, and the work
//! (right-hand-side evaluations), then per setting the worst over the runs it applies to and the
//! evaluations summed. The settings: `peak_tolerance` 1e-3 … 1e-6 (family `tolerance`: RKN 6(4)
//! for the impacts, event-aware DOPRI5 for the blasts), plain (`dopri5`) and event-aware
//! (`events`) DOPRI5 and RKN 6(4) (`rkn64`, impacts only: a blast's work integral needs the
//! velocity) at rtol 1e-5 … 3e-11; `previous`: event-aware DOPRI5 at the rule of `peak_tolerance`
//! for every run, as before RKN 6(4). This is the measurement behind `Method::resolve`'s rules
//! (docs/physics.md §8).
//!
//! Run: `cargo run --release -p woodpile --example peak_tolerance [-- --families tolerance,rkn64]`

use rayon::prelude::*;
use woodpile::{
    simulate, BlastProfile, CellModel, Chain, ChainBuilder, Excitation, Method, RunSettings,
    RunSummary, Striker, PAPER_OPTIMIZED_CHAIN_MM,
};

fn main() -> woodpile::Result<()> {
    let families: Vec<String> = std::env::args()
        .skip_while(|a| a != "--families")
        .nth(1)
        .unwrap_or_else(|| "tolerance,dopri5,events,rkn64".to_string())
        .split(',')
        .map(str::to_string)
        .collect();
    let methods = compared_methods(&families)?;
    let cases = cases()?;
    let run = |chain: &Chain, excitation: &Excitation, base: &RunSettings, method: Method| {
        let settings = RunSettings {
            method,
            sample_interval_s: base.duration_s,
            ..*base
        };
        simulate(chain, excitation, &settings, &mut ())
    };
    // Per setting, over the runs it applies to: the worst error and the evaluations summed.
    let mut totals = vec![(0.0f64, 0u64); methods.len()];
    for (name, chain, excitation, base) in &cases {
        let converged = Method::Dopri5 {
            rtol: 1e-13,
            atol: 1e-19,
        };
        let reference = run(chain, excitation, base, converged)?;
        println!(
            "{name}: transmitted peak {:.9} N",
            reference.transmitted_peak_force_n
        );
        let applies =
            |m: &Method| !(m.needs_second_order() && matches!(excitation, Excitation::Blast(_)));
        let runs: Vec<Option<RunSummary>> = methods
            .par_iter()
            .map(|(_, m)| {
                applies(m)
                    .then(|| run(chain, excitation, base, *m))
                    .transpose()
            })
            .collect::<woodpile::Result<_>>()?;
        for (((label, method), total), s) in methods.iter().zip(&mut totals).zip(runs) {
            let Some(s) = s else { continue };
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
            let settings = RunSettings {
                method: *method,
                ..*base
            };
            let rtol = rtol_of(&settings.method_for(chain, excitation)?);
            total.0 = total.0.max(worst);
            total.1 += s.stats.rhs_evaluations;
            println!(
                "  {label:<22} rtol {rtol:>8.2e}  rhs {:>7}  worst peak error {worst:.2e} (contact {contact}), {:.2} rtol^0.75",
                s.stats.rhs_evaluations,
                worst / rtol.powf(0.75)
            );
        }
    }
    println!("over the runs each applies to:");
    for ((label, method), (worst, rhs)) in methods.iter().zip(&totals) {
        let rtol = rtol_of(method);
        println!(
            "  {label:<26} rhs {rhs:>8}  worst peak error {worst:.2e}, {:.2} rtol^0.75",
            worst / rtol.powf(0.75)
        );
    }
    Ok(())
}

/// The rtol a method runs at (NaN for RK4 and for an unresolved peak tolerance).
fn rtol_of(method: &Method) -> f64 {
    match method {
        Method::Dopri5 { rtol, .. }
        | Method::Dopri5Events { rtol, .. }
        | Method::Rkn64 { rtol, .. }
        | Method::ExactModes { rtol, .. } => *rtol,
        Method::Rk4 { .. } | Method::PeakTolerance { .. } => f64::NAN,
    }
}

/// The methods of the `families` asked for: `tolerance`, `previous` (what `peak_tolerance` chose
/// before RKN 6(4)), `dopri5`, `events`, `rkn64`.
fn compared_methods(families: &[String]) -> woodpile::Result<Vec<(String, Method)>> {
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
    if want("previous") {
        // What `peak_tolerance` chose for every run before RKN 6(4): event-aware DOPRI5.
        for tol in [1e-3, 1e-4, 1e-5, 1e-6] {
            let method = Method::for_peak_tolerance(tol)?.resolve(false);
            methods.push((format!("previous {tol:e}"), method));
        }
    }
    for rtol in [
        1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11,
    ] {
        let atol = rtol * 1e-6;
        for (family, method) in [
            ("dopri5", Method::Dopri5 { rtol, atol }),
            ("events", Method::Dopri5Events { rtol, atol }),
            ("rkn64", Method::Rkn64 { rtol, atol }),
        ] {
            if want(family) {
                methods.push((format!("{family} rtol={rtol:e}"), method));
            }
        }
    }
    Ok(methods)
}

/// The runs: impacts at three striker speeds and the paper's blast, on resonant and rigid cells.
fn cases() -> woodpile::Result<Vec<(String, Chain, Excitation, RunSettings)>> {
    let mut cases: Vec<(String, Chain, Excitation, RunSettings)> = Vec::new();
    for cells in [CellModel::Resonant, CellModel::Rigid] {
        let chain = ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, cells)?.build()?;
        for speed in [Striker::paper().velocity_m_s, 1.0, 3.0] {
            let striker = Striker {
                velocity_m_s: speed,
                ..Striker::paper()
            };
            let name = format!("impact {cells:?} {speed:.2} m/s");
            let base = RunSettings::paper_impact();
            cases.push((name, chain.clone(), Excitation::Impact(striker), base));
        }
        let blast = Excitation::Blast(BlastProfile::paper());
        let base = RunSettings::paper_blast();
        cases.push((format!("blast {cells:?}"), chain, blast, base));
    }
    Ok(cases)
}
