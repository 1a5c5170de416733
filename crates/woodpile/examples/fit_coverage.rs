//! Coverage of the fit's 95 % intervals: the synthetic calibration of the claims (restitution, a
//! wall β scale, the impact speed and a 3 µs time shift; 1 % Gaussian noise) fitted for 50 noise
//! seeds from the middle of the bounds; prints how often each interval holds the true value, the
//! mean and spread of (estimate − truth)/std_error (0 and 1 if the errors are right), the model
//! runs and the wall time per fit (median). The figures in docs/fit.md come from
//! `cargo run --release -p woodpile --example fit_coverage [SEEDS] [JACOBIAN_STEP]` (default 50
//! seeds, the default step).

#[path = "../tests/claims/fit_common.rs"]
#[allow(dead_code)]
mod fit_common;

use fit_common::{model, problem, synthetic, TRUTH};
use std::time::Instant;
use woodpile::fit::{fit, FitSettings};

fn main() {
    let seeds: u64 = std::env::args()
        .nth(1)
        .map_or(50, |s| s.parse().expect("a number of seeds"));
    let mut covered = [0usize; 4];
    let mut runs = Vec::new();
    let mut seconds = Vec::new();
    let mut rms_ratio = Vec::new();
    let mut z_scores = vec![Vec::new(); 4];
    for seed in 0..seeds {
        let measurements = synthetic(0.01, 1000 + seed);
        let problem = problem(measurements.clone(), &model);
        let settings = FitSettings {
            starts: 1,
            jacobian_step: std::env::args()
                .nth(2)
                .map_or(woodpile::defaults::FIT_JACOBIAN_STEP, |s| {
                    s.parse().expect("a step")
                }),
            ..FitSettings::default()
        };
        let started = Instant::now();
        let result = fit(&problem, &settings).expect("the fit runs");
        seconds.push(started.elapsed().as_secs_f64());
        runs.push(result.evaluations as f64);
        let u = result.uncertainty.expect("not interrupted");
        for (k, z) in z_scores.iter_mut().enumerate() {
            if let Some(se) = u.std_errors[k] {
                z.push((result.estimates[k] - TRUTH[k]) / se);
            }
        }
        for (k, c) in covered.iter_mut().enumerate() {
            if let Some([lo, hi]) = u.ci95[k] {
                if (lo..=hi).contains(&TRUTH[k]) {
                    *c += 1;
                }
            }
        }
        for (m, rms) in measurements.iter().zip(&result.residual_rms) {
            rms_ratio.push(rms / (0.01 * m.scale));
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let names = [
        "damping.restitution",
        "contact_beta_scale.wall",
        "excitation.velocity_m_s",
        "time_shift_s",
    ];
    println!("95 % interval coverage over {seeds} noise seeds (1 % noise):");
    for ((name, c), z) in names.iter().zip(covered).zip(&z_scores) {
        let mean = z.iter().sum::<f64>() / z.len() as f64;
        let sd = (z.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / (z.len() - 1) as f64).sqrt();
        println!(
            "  {name:<26} {c}/{seeds} = {:.0} %   (estimate - truth) / std_error: mean {mean:+.2}, sd {sd:.2}",
            100.0 * c as f64 / seeds as f64
        );
    }
    println!(
        "residual RMS / noise level: median {:.3}, range {:.3}..{:.3}",
        median(&mut rms_ratio.clone()),
        rms_ratio.iter().cloned().fold(f64::INFINITY, f64::min),
        rms_ratio.iter().cloned().fold(0.0, f64::max)
    );
    println!(
        "per fit: median {} model runs, median wall time {:.3} s",
        median(&mut runs),
        median(&mut seconds)
    );
}
