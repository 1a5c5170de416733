//! Steps set by the contacts (docs/physics.md §8, "Exact linear vibrations"): five 80 mm quartz
//! rods under the default impact (0.5 ms, samples every 1 µs) as Table 1 cells and as
//! finite-element rods (16 elements per half rod). For each chain: the exact modal method at rtol
//! 1e-12 against RKN 6(4) at 1e-12 (both converged), then `peak_tolerance = 1e-5` (what woodpile
//! chooses), RKN 6(4) at the rtol that tolerance gave it before the exact method existed, and the
//! exact method at each rtol given as an argument: steps, evaluations (the exact method: contact
//! forces at one node), median wall time of 7 runs, the worst relative error of any contact peak
//! against RKN 6(4) at 1e-12, the energy error.
//!
//! Run: `cargo run --release -p woodpile --example exact_linear -- 1e-5 1e-6 1e-7`
//! (`SPARSE=1`: one sample at the end; `PROFILE=fe|table1|fe-rkn`: `RUNS` runs, 300 by default,
//! at `peak_tolerance` 1e-5, for `time` or a profiler)

use woodpile::{
    simulate, CellModel, Chain, ChainBuilder, Element, Excitation, Material, Method, Rod,
    RunSettings, RunSummary, Striker, UnitCell,
};

fn fe_chain(elements: usize) -> woodpile::Result<Chain> {
    let rod = Rod::new(80e-3, 5e-3, 0.0, Material::fused_quartz())?;
    let cell = UnitCell::from_rod_fe(&rod, elements)?;
    let mut list = Vec::new();
    for _ in 0..5 {
        let mut e = Element::table1_rod(80, CellModel::Resonant)?;
        e.cell = cell.clone();
        list.push(e);
    }
    ChainBuilder::new(list).build()
}

fn run(chain: &Chain, method: Method) -> woodpile::Result<RunSummary> {
    let sparse = std::env::var("SPARSE").is_ok();
    let settings = RunSettings {
        duration_s: 5e-4,
        method,
        sample_interval_s: if sparse { 5e-4 } else { 1e-6 },
    };
    simulate(
        chain,
        &Excitation::Impact(Striker::paper()),
        &settings,
        &mut (),
    )
}

fn worst(a: &RunSummary, b: &RunSummary) -> f64 {
    a.contact_peak_forces_n
        .iter()
        .zip(&b.contact_peak_forces_n)
        .map(|(x, y)| (x / y - 1.0).abs())
        .fold(0.0, f64::max)
}

fn median_run(chain: &Chain, method: Method) -> woodpile::Result<RunSummary> {
    let mut runs: Vec<RunSummary> = (0..7)
        .map(|_| run(chain, method))
        .collect::<woodpile::Result<_>>()?;
    runs.sort_by(|a, b| a.wall_time_s.total_cmp(&b.wall_time_s));
    Ok(runs.swap_remove(3))
}

fn main() -> woodpile::Result<()> {
    let table1 = ChainBuilder::table1_rods(&[80; 5], CellModel::Resonant)?.build()?;
    let fe = fe_chain(16)?;
    let cell = &fe.elements()[0].cell;
    let top = cell
        .resonators
        .iter()
        .map(|r| r.angular_frequency())
        .fold(0.0, f64::max);
    println!(
        "FE cell: {} resonators, primary {:.3e} kg, top {:.3} MHz",
        cell.resonators.len(),
        cell.primary_mass_kg,
        top / std::f64::consts::TAU / 1e6
    );
    // PROFILE=fe|table1|fe-rkn: RUNS (300) runs of that chain at peak_tolerance 1e-5 (fe-rkn: RKN 6(4)
    // as that tolerance chose it before), for `time` (user time is robust to other load) or a
    // profiler.
    if let Ok(which) = std::env::var("PROFILE") {
        let tolerance = Method::PeakTolerance {
            peak_tolerance: 1e-5,
        };
        let (chain, method) = match which.as_str() {
            "table1" => (&table1, tolerance),
            "fe-rkn" => (&fe, tolerance.resolve(true)),
            _ => (&fe, tolerance),
        };
        for _ in 0..std::env::var("RUNS")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(300)
        {
            run(chain, method)?;
        }
        return Ok(());
    }
    let tight = Method::Rkn64 {
        rtol: 1e-12,
        atol: 1e-18,
    };
    let args: Vec<String> = std::env::args().collect();
    let rtols: Vec<f64> = args.iter().skip(1).filter_map(|a| a.parse().ok()).collect();
    for (name, chain) in [("table1", &table1), ("fe16", &fe)] {
        let reference = run(chain, tight)?;
        let exact_ref = run(
            chain,
            Method::ExactModes {
                rtol: 1e-12,
                atol: 1e-18,
            },
        )?;
        println!("{name}: exact-modes at rtol 1e-12 against rkn64 at 1e-12: worst peak {:.2e} ({} steps)", worst(&exact_ref, &reference), exact_ref.stats.steps);
        let tolerance = Method::PeakTolerance {
            peak_tolerance: 1e-5,
        };
        let mut methods = vec![
            ("peak_tolerance 1e-5".to_string(), tolerance),
            (
                "rkn64 as peak_tolerance 1e-5 chose it before".to_string(),
                tolerance.resolve(true),
            ),
        ];
        for &r in &rtols {
            methods.push((
                format!("exact-modes rtol {r:e}"),
                Method::ExactModes {
                    rtol: r,
                    atol: r * 1e-6,
                },
            ));
        }
        for (label, method) in methods {
            let s = median_run(chain, method)?;
            println!(
                "  {label}: {} steps ({} rejected), {} evaluations, {:.3} ms, worst peak {:.2e}, energy {:.1e}",
                s.stats.steps, s.stats.rejected_steps, s.stats.rhs_evaluations, s.wall_time_s * 1e3, worst(&s, &reference), s.energy.max_relative_error
            );
        }
    }
    Ok(())
}
