//! A column run two ways (docs/physics.md §16, "A column"): five 80 mm quartz rods, each a
//! finite-element rod of 16 elements per half rod, under the paper's striker (0.5 ms, samples
//! every 1 µs), as a chain (`[chain]`, each rod its centre node and resonators, stepped by
//! `integrate::modal_step`) and as a lattice of one rod per layer (`[lattice]`, each rod its
//! whole free–free beam, stepped by `integrate::modal_graph`), both by the exact modal method at
//! each rtol given (default 1e-8): steps, median wall time of 7 runs with everything recorded
//! (the chain's `Trajectory`, the lattice's `LatticeRun`), and the largest difference of any
//! contact peak between the two.
//!
//! Run: `cargo run --release -p woodpile --example column_engines -- 1e-8`
//! (`CELLS=table1`: five 80 mm Table 1 cells instead, the contact graph
//! `LatticeOde::from_chain`'s one-point bodies; `SAMPLE_S=5e-4`: one sample at the end, as a
//! design study takes, instead of every µs; `LOAD=damped`: on-site damping (τ = 0.2 ms),
//! gravity and a 5 N preload on both forms, which the exact method takes;
//! `PROFILE=chain|lattice`: `RUNS` runs, 300 by default, for a profiler)

use woodpile::model::{LatticeBuilder, LatticeExcitation, LatticeLab, LayerSpec};
use woodpile::ode::LatticeOde;
use woodpile::simulate::{simulate_lattice, LatticeRun};
use woodpile::{
    simulate, Body, CellModel, Chain, ChainBuilder, Damping, Element, Excitation, Material, Method,
    Preload, Rod, RunSettings, RunSummary, Striker, Trajectory, UnitCell,
};

const RODS: usize = 5;
const LENGTH_M: f64 = 80e-3;
const DIAMETER_M: f64 = 5e-3;
const ELEMENTS: usize = 16;

fn settings(rtol: f64) -> RunSettings {
    RunSettings {
        duration_s: 5e-4,
        method: Method::ExactModes { rtol, atol: 1e-15 },
        sample_interval_s: std::env::var("SAMPLE_S")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(1e-6),
    }
}

/// Whether `LOAD=damped` asks for the lab terms.
fn damped() -> bool {
    std::env::var("LOAD").is_ok_and(|c| c == "damped")
}

fn damping() -> Damping {
    Damping {
        on_site_time_s: Some(2e-4),
        ..Damping::default()
    }
}

fn preload() -> Preload {
    Preload {
        force_n: 5.0,
        gravity_m_s2: 9.81,
    }
}

fn chain() -> woodpile::Result<Chain> {
    let builder = chain_builder()?;
    if damped() {
        return builder.damping(damping()).preload(preload()).build();
    }
    builder.build()
}

fn chain_builder() -> woodpile::Result<ChainBuilder> {
    if table1() {
        return ChainBuilder::table1_rods(&[80; RODS], CellModel::Resonant);
    }
    let quartz = Material::fused_quartz();
    let rod = Rod::new(LENGTH_M, DIAMETER_M, 0.0, quartz.clone())?;
    let cell = UnitCell::from_rod_fe(&rod, ELEMENTS)?;
    let element = Element {
        label: "80mm".into(),
        body: Body::Rod {
            diameter_m: DIAMETER_M,
            length_m: LENGTH_M,
        },
        material: quartz,
        cell,
    };
    Ok(ChainBuilder::new(vec![element; RODS]))
}

/// Whether `CELLS=table1` asks for Table 1 cells.
fn table1() -> bool {
    std::env::var("CELLS").is_ok_and(|c| c == "table1")
}

fn lattice_ode() -> woodpile::Result<LatticeOde> {
    if table1() {
        return LatticeOde::from_chain(&chain()?, &Excitation::Impact(Striker::paper()));
    }
    let layer = LayerSpec {
        rods: 1,
        pitch_m: 20e-3,
        length_m: LENGTH_M,
        diameter_m: DIAMETER_M,
        material: Material::fused_quartz(),
        angle_deg: 90.0,
    };
    let lattice = LatticeBuilder::new(vec![layer; RODS], ELEMENTS).build()?;
    let lab = if damped() {
        LatticeLab {
            damping: damping(),
            modal_ratio: 0.0,
            preload: preload(),
        }
    } else {
        LatticeLab::default()
    };
    let striker = Striker::paper();
    let impact = LatticeExcitation::Impact {
        striker,
        at_m: [0.0, 0.0],
    };
    LatticeOde::build(&lattice, &impact, &lab)
}

fn run_chain(chain: &Chain, rtol: f64) -> woodpile::Result<(RunSummary, f64)> {
    let mut trajectory = Trajectory::default();
    let start = std::time::Instant::now();
    let summary = simulate(
        chain,
        &Excitation::Impact(Striker::paper()),
        &settings(rtol),
        &mut trajectory,
    )?;
    Ok((summary, start.elapsed().as_secs_f64()))
}

fn run_lattice(built: &LatticeOde, rtol: f64) -> woodpile::Result<(LatticeRun, f64)> {
    let mut ode = built.clone();
    let start = std::time::Instant::now();
    let run = simulate_lattice(&mut ode, &settings(rtol))?;
    Ok((run, start.elapsed().as_secs_f64()))
}

fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn main() -> woodpile::Result<()> {
    let chain = chain()?;
    let lattice = lattice_ode()?;
    if let Ok(which) = std::env::var("PROFILE") {
        let runs: usize = std::env::var("RUNS").map_or(300, |r| r.parse().expect("RUNS"));
        for _ in 0..runs {
            match which.as_str() {
                "chain" => drop(run_chain(&chain, 1e-8)?),
                "lattice" => drop(run_lattice(&lattice, 1e-8)?),
                other => panic!("PROFILE={other}: chain or lattice"),
            }
        }
        return Ok(());
    }
    let rtols: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("an rtol"))
        .collect();
    let rtols = if rtols.is_empty() { vec![1e-8] } else { rtols };
    println!("| rtol | chain steps (rejected), evaluations | lattice steps (rejected), evaluations | chain ms | lattice ms | lattice / chain | largest peak difference |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    for rtol in rtols {
        let mut chain_ms = Vec::new();
        let mut lattice_ms = Vec::new();
        let mut last = None;
        for _ in 0..7 {
            let (summary, chain_s) = run_chain(&chain, rtol)?;
            let (run, lattice_s) = run_lattice(&lattice, rtol)?;
            chain_ms.push(chain_s * 1e3);
            lattice_ms.push(lattice_s * 1e3);
            last = Some((summary, run));
        }
        let (summary, run) = last.expect("seven runs");
        let largest = summary
            .contact_peak_forces_n
            .iter()
            .fold(0.0_f64, |a, &b| a.max(b));
        let difference = summary
            .contact_peak_forces_n
            .iter()
            .zip(&run.contact_peak_forces_n)
            .map(|(a, b)| (a - b).abs() / largest)
            .fold(0.0_f64, f64::max);
        let (c, l) = (median(chain_ms), median(lattice_ms));
        println!(
            "| {rtol:e} | {} ({}), {} | {} ({}), {} | {c:.3} | {l:.3} | {:.2} | {difference:.1e} |",
            summary.stats.steps,
            summary.stats.rejected_steps,
            summary.stats.rhs_evaluations,
            run.stats.steps,
            run.stats.rejected_steps,
            run.stats.rhs_evaluations,
            l / c
        );
    }
    Ok(())
}
