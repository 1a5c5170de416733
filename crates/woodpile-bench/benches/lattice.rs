//! `cargo bench --manifest-path crates/woodpile-bench/Cargo.toml --bench lattice`: woodpile
//! lattices (docs/physics.md §16) struck by the default striker on the centre of a top rod,
//! 2 ms, at the default `peak_tolerance` (1e-5; the method it resolves to for a lattice is
//! printed with each run's step count).
//!
//! Printed first, medians of `LATTICE_BENCH_REPEATS` runs (default 3) on one thread, the cost
//! per step from the thread's CPU time (Linux; the wall time beside it includes any wait for a
//! core on a shared machine):
//!
//! - the cost per step of lattices of 2 × 2, 4 × 3 and 10 × 5 rods (layers × rods per layer) at
//!   4, 8 and 16 finite elements per half rod, with the time per contact per step and per
//!   contact-row entry per step (a contact reads and loads both rods' modal rows: cost ∝
//!   contacts × modes per rod, plus the modes' own term);
//! - runs per second of the 10-layer × 5-rod lattice at 16 elements per half rod (50 rods, 231
//!   contacts) on 1 and 2 threads (rayon over independent runs: lattices have no SIMD lanes).
//!
//! Then criterion's measurement of that 10 × 5 run (its throughput in contact-steps per second).
//! `LATTICE_BENCH_TABLE_ONLY=1` skips criterion.

// criterion_group! generates an undocumented entry point.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput};
use rayon::prelude::*;
use std::time::{Duration, Instant};
use woodpile::defaults::STUDY_PEAK_TOLERANCE;
use woodpile::model::{Lattice, LatticeBuilder, LayerSpec, Material};
use woodpile::ode::LatticeOde;
use woodpile::simulate::{simulate_lattice, LatticeRun};
use woodpile::{Method, RunSettings, Striker};

/// Rod length \[m\]: long enough that 5 rods at the pitch cross every rod of the next layer.
const LENGTH_M: f64 = 0.1;
const PITCH_M: f64 = 0.02;
const DIAMETER_M: f64 = 0.005;

/// `layers` layers of `rods` fused-quartz rods (100 mm long, 5 mm across, 20 mm pitch),
/// alternately along x and y, supports under every bottom rod's centre.
fn lattice(layers: usize, rods: usize, fe_elements: usize) -> Lattice {
    let spec = LayerSpec {
        rods,
        pitch_m: PITCH_M,
        length_m: LENGTH_M,
        diameter_m: DIAMETER_M,
        material: Material::fused_quartz(),
        angle_deg: 90.0,
    };
    LatticeBuilder::new(vec![spec; layers], fe_elements)
        .build()
        .expect("a valid lattice")
}

/// The centre of the top layer's middle rod (rod n/2 from 0: right of the centre for even n).
fn impact_point(rods: usize) -> [f64; 2] {
    [
        0.0,
        (rods / 2) as f64 * PITCH_M - 0.5 * (rods - 1) as f64 * PITCH_M,
    ]
}

fn settings() -> RunSettings {
    RunSettings {
        method: Method::for_peak_tolerance(STUDY_PEAK_TOLERANCE).expect("a valid tolerance"),
        // Samples every 10 µs: the run's cost is its steps, not its output.
        sample_interval_s: 1e-5,
        ..RunSettings::paper_impact()
    }
}

/// The compiled equations of a case: contacts, modal coordinates, contact-row entries.
struct Case {
    layers: usize,
    rods: usize,
    fe_elements: usize,
    ode: LatticeOde,
}

impl Case {
    fn new(layers: usize, rods: usize, fe_elements: usize) -> Self {
        let l = lattice(layers, rods, fe_elements);
        let ode = LatticeOde::new(&l, &Striker::paper(), impact_point(rods)).expect("on a rod");
        Case {
            layers,
            rods,
            fe_elements,
            ode,
        }
    }

    /// Modes per rod: 2 (w, θ) per node, 2n + 1 nodes.
    fn modes_per_rod(&self) -> usize {
        2 * (2 * self.fe_elements + 1)
    }

    /// Modal-row entries read (and loaded) per evaluation: each crossing two rods' rows, the
    /// striker's and a support's contact one.
    fn row_entries(&self) -> usize {
        let m = self.modes_per_rod();
        let contacts = self.ode.contacts();
        let supports = (0..contacts).filter(|&c| self.ode.is_support(c)).count();
        // Striker: 1 + m; crossings: 2m; supports: m.
        (1 + m) + 2 * m * (contacts - 1 - supports) + m * supports
    }

    fn run(&self) -> (LatticeRun, Duration) {
        self.run_timed().0
    }

    /// The run, its wall time and the CPU time its thread used (None where Linux's
    /// `/proc/thread-self/stat` is not readable).
    fn run_timed(&self) -> ((LatticeRun, Duration), Option<f64>) {
        let mut ode = self.ode.clone();
        let cpu0 = thread_cpu_s();
        let start = Instant::now();
        let run = simulate_lattice(&mut ode, &settings()).expect("the run succeeds");
        let wall = start.elapsed();
        let cpu = thread_cpu_s().zip(cpu0).map(|(b, a)| b - a);
        ((run, wall), cpu)
    }
}

/// CPU time of the calling thread \[s\] (user + system, in clock ticks of 10 ms: Linux's
/// USER_HZ = 100), from `/proc/thread-self/stat`. On a machine shared with other work the wall
/// time includes the time the thread waited for a core; this does not.
fn thread_cpu_s() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    // Fields after the command name (in parentheses, possibly with spaces): state is field 3,
    // utime and stime fields 14 and 15.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i - 3)?.parse::<f64>().ok();
    Some((ticks(14)? + ticks(15)?) / 100.0)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn repeats() -> usize {
    std::env::var("LATTICE_BENCH_REPEATS")
        .ok()
        .and_then(|s| s.parse().ok())
        .filter(|&n| n > 0)
        .unwrap_or(3)
}

/// The method the default peak tolerance becomes for a lattice (its short name).
fn resolved_method(ode: &LatticeOde) -> &'static str {
    match woodpile::simulate::lattice_method(ode, settings().method) {
        Method::ExactModes { .. } => "exact-modes",
        Method::Rkn64 { .. } => "rkn64",
        Method::Dopri5Events { .. } => "dopri5-events",
        _ => "other",
    }
}

fn scaling_table() {
    println!(
        "lattice cost per step: 2 ms at peak_tolerance {STUDY_PEAK_TOLERANCE:e}, one thread, median of {} runs; per step from the thread's CPU time",
        repeats()
    );
    println!(
        "| layers × rods | elements per half rod | method | contacts | modal coordinates | row entries | steps | rhs evaluations | wall ms per run | CPU ms per run | µs per step | ns per contact per step | ns per row entry per evaluation |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for (layers, rods) in [(2, 2), (4, 3), (10, 5)] {
        for fe in [4, 8, 16] {
            let case = Case::new(layers, rods, fe);
            let (mut walls, mut cpus) = (Vec::new(), Vec::new());
            let mut stats = None;
            for _ in 0..repeats() {
                let ((run, wall), cpu) = case.run_timed();
                walls.push(wall.as_secs_f64());
                cpus.extend(cpu);
                stats = Some(run.stats);
            }
            let stats = stats.expect("at least one run");
            let wall = median(walls);
            // The thread's CPU time where known (the machine may be shared), else wall time.
            let t = if cpus.is_empty() { wall } else { median(cpus) };
            let per_step = t / stats.steps as f64;
            println!(
                "| {} × {} | {} | {} | {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.2} | {:.1} | {:.2} |",
                case.layers,
                case.rods,
                case.fe_elements,
                resolved_method(&case.ode),
                case.ode.contacts(),
                case.ode.coordinates(),
                case.row_entries(),
                stats.steps,
                stats.rhs_evaluations,
                wall * 1e3,
                t * 1e3,
                per_step * 1e6,
                per_step * 1e9 / case.ode.contacts() as f64,
                t * 1e9 / (stats.rhs_evaluations as f64 * case.row_entries() as f64),
            );
        }
    }
}

/// Runs per second of `runs` independent 10 × 5 runs on 1 and 2 threads.
fn throughput(case: &Case) {
    let runs = 2 * repeats().max(2);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        let start = Instant::now();
        let steps: u64 = pool.install(|| {
            (0..runs)
                .into_par_iter()
                .map(|_| case.run().0.stats.steps)
                .sum()
        });
        let t = start.elapsed().as_secs_f64();
        println!(
            "10 × 5 rods, 16 elements per half rod: {runs} runs on {threads} thread(s) in {t:.2} s: {:.3} runs/s ({} steps each)",
            runs as f64 / t,
            steps / runs as u64
        );
    }
}

fn main() {
    scaling_table();
    let case = Case::new(10, 5, 16);
    throughput(&case);
    if std::env::var_os("LATTICE_BENCH_TABLE_ONLY").is_some() {
        return;
    }
    let (run, _) = case.run();
    let mut c = Criterion::default().configure_from_args();
    let mut group = c.benchmark_group("lattice_10x5_rods_16_elements_2ms");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(30));
    group.throughput(Throughput::Elements(
        run.stats.steps * case.ode.contacts() as u64,
    ));
    group.bench_function("peak_tolerance_1e-5", |b| b.iter(|| case.run().0.stats));
    group.finish();
    c.final_summary();
}
