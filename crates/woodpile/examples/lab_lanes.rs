//! A lab-physics design study in SIMD lanes: the same random designs of the paper's impact problem
//! (20 Table 1 rods, resonant, the default striker and sensor, 2 ms, peaks only) evaluated
//! without and with the lab physics of docs/physics.md §14 (restitution e = 0.9 at every contact,
//! resonator damping ratio 0.01, a 5 N preload), all through `simulate_many` (one queue, every
//! thread's lanes), and the lab designs also one at a time (`simulate` per design on the same
//! threads: how they ran before the lanes took lab physics). Prints the medians of `--runs`
//! repetitions (interleaved), the ratio lab / lossless in lanes, and checks that each lab
//! design's lane result is bit for bit its run alone.
//!
//! Run: `cargo run --release -p woodpile --example lab_lanes [-- --designs 400 --runs 3 --tol T]`
//! (default: the paper's RK4 at 0.1 µs; `--tol T`: `[run] peak_tolerance = T`).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::time::Instant;
use woodpile::{
    simulate, simulate_many, CellModel, Chain, ChainBuilder, ContactDamping, Damping, Excitation,
    Job, LaneWidth, Method, Preload, RunSettings, RunSummary, Striker, TABLE1_LENGTHS_MM,
};

fn arg<T: std::str::FromStr>(name: &str) -> Option<T> {
    std::env::args()
        .skip_while(|a| a != name)
        .nth(1)
        .map(|s| s.parse().ok().expect("a number"))
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn designs(count: usize, lab: bool) -> Vec<Chain> {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    (0..count)
        .map(|_| {
            let rods: Vec<u32> = (0..20)
                .map(|_| TABLE1_LENGTHS_MM[rng.random_range(0..TABLE1_LENGTHS_MM.len())])
                .collect();
            let mut b = ChainBuilder::table1_rods(&rods, CellModel::Resonant).unwrap();
            if lab {
                b = b
                    .damping(Damping {
                        contacts: ContactDamping::Restitution { coefficient: 0.9 },
                        resonator_ratio: 0.01,
                        ..Damping::default()
                    })
                    .preload(Preload {
                        force_n: 5.0,
                        gravity_m_s2: 0.0,
                    });
            }
            b.build().unwrap()
        })
        .collect()
}

fn same_bits(a: &RunSummary, b: &RunSummary) -> bool {
    let strip = |s: &RunSummary| {
        format!(
            "{:?}",
            RunSummary {
                wall_time_s: 0.0,
                ..s.clone()
            }
        )
    };
    strip(a) == strip(b)
}

fn main() {
    let count = arg("--designs").unwrap_or(400);
    let runs = arg("--runs").unwrap_or(3);
    let method = arg::<f64>("--tol").map_or(Method::paper(), |t| {
        Method::for_peak_tolerance(t).expect("a valid tolerance")
    });
    let settings = RunSettings {
        method,
        sample_interval_s: RunSettings::paper_impact().duration_s,
        ..RunSettings::paper_impact()
    };
    let excitation = Excitation::Impact(Striker::paper());
    let (lossless, lab) = (designs(count, false), designs(count, true));
    let (lossless_jobs, lab_jobs) = (
        Job::for_each_chain(&lossless, &excitation, &settings),
        Job::for_each_chain(&lab, &excitation, &settings),
    );
    assert!(lab_jobs.iter().all(|j| j.in_lanes().unwrap()));
    let width = LaneWidth::detect();
    let (mut t_lossless, mut t_lab, mut t_alone) = (vec![], vec![], vec![]);
    for _ in 0..runs {
        let start = Instant::now();
        let r = simulate_many(&lossless_jobs, width);
        t_lossless.push(start.elapsed().as_secs_f64());
        assert!(r.iter().all(|r| r.is_ok()));
        let start = Instant::now();
        let lab_results = simulate_many(&lab_jobs, width);
        t_lab.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        let alone: Vec<RunSummary> = lab
            .par_iter()
            .map(|c| simulate(c, &excitation, &settings, &mut ()).unwrap())
            .collect();
        t_alone.push(start.elapsed().as_secs_f64());
        for (lanes, alone) in lab_results.iter().zip(&alone) {
            assert!(same_bits(lanes.as_ref().unwrap(), alone), "lanes = alone");
        }
    }
    let (a, b, c) = (median(t_lossless), median(t_lab), median(t_alone));
    println!(
        "{count} designs, {method:?}, {} threads, {width:?} lanes, medians of {runs}:",
        rayon::current_num_threads()
    );
    println!(
        "  lossless, lanes:           {a:.3} s ({:.0} designs/s)",
        count as f64 / a
    );
    println!(
        "  lab physics, lanes:        {b:.3} s ({:.0} designs/s)",
        count as f64 / b
    );
    println!(
        "  lab physics, one at a time: {c:.3} s ({:.0} designs/s)",
        count as f64 / c
    );
    println!(
        "  lab / lossless in lanes: {:.2}x; lanes speed-up on lab physics: {:.2}x",
        b / a,
        c / b
    );
    println!("  every lab design's lane result is bit for bit its run alone: yes");
}
