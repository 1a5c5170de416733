//! How accurate is a finite-difference Jacobian of the fit's residuals, with a fixed step
//! sequence (RK4) and with adaptive step control (DOPRI5)? Prints, per parameter, the relative
//! difference between the fit's Jacobian (second-order differences of step h, a fraction of the
//! parameter's range) and central differences of h = 1e-5 of the same model; for the adaptive
//! model, forward differences against central ones of h = 1e-4; and the model's own change
//! when its step is halved. The numbers in docs/fit.md come from
//! `cargo run --release -p woodpile --example fit_jacobian_noise`.

#[path = "../tests/claims/fit_common.rs"]
#[allow(dead_code)]
mod fit_common;

use fit_common::{model_with_step, problem, synthetic};
use woodpile::fit::{jacobian, residuals, Built, Problem};
use woodpile::Method;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn central(problem: &Problem<'_>, at: &[f64], k: usize, h: f64) -> Vec<f64> {
    let (mut up, mut down) = (at.to_vec(), at.to_vec());
    up[k] += h;
    down[k] -= h;
    let (ru, rd) = (
        residuals(problem, &up).unwrap(),
        residuals(problem, &down).unwrap(),
    );
    ru.iter()
        .zip(&rd)
        .map(|(a, b)| (a - b) / (2.0 * h))
        .collect()
}

fn relative(a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    norm(&d) / norm(b)
}

fn main() {
    let measurements = synthetic(0.0, 0);
    let rk4 = |v: &[f64]| model_with_step(v, 1e-7);
    let rk4_half = |v: &[f64]| model_with_step(v, 5e-8);
    let dopri = |v: &[f64]| -> woodpile::Result<Built> {
        let mut b = model_with_step(v, 1e-7)?;
        b.settings.method = Method::Dopri5 {
            rtol: 1e-9,
            atol: 1e-15,
        };
        Ok(b)
    };
    let at = [0.8, 1.2, 2.1, 1e-6];
    let p_rk4 = problem(measurements.clone(), &rk4);
    let p_half = problem(measurements.clone(), &rk4_half);
    let ranges: Vec<f64> = p_rk4
        .all_parameters()
        .iter()
        .map(|p| p.bounds.map_or(1.0, |(lo, hi)| hi - lo))
        .collect();
    let names: Vec<String> = p_rk4
        .all_parameters()
        .iter()
        .map(|p| p.name.clone())
        .collect();
    let reference: Vec<Vec<f64>> = (0..4)
        .map(|k| central(&p_rk4, &at, k, 1e-5 * ranges[k]))
        .collect();
    println!("fixed step (RK4, 0.1 us): the fit's Jacobian (second-order differences of step h) vs central differences of h = 1e-5, relative");
    for h in [1e-3, 1e-4, 1e-6, 1e-8] {
        let j = jacobian(&p_rk4, &at, h).unwrap();
        let row: Vec<String> = (0..4)
            .map(|k| format!("{:.1e}", relative(&j[k], &reference[k])))
            .collect();
        println!("  h = {h:.0e}: {}", row.join("  "));
    }
    println!("RK4 step halved (0.05 us): central differences vs those at 0.1 us, relative");
    let row: Vec<String> = (0..4)
        .map(|k| {
            format!(
                "{:.1e}",
                relative(&central(&p_half, &at, k, 1e-4 * ranges[k]), &reference[k])
            )
        })
        .collect();
    println!("  {}", row.join("  "));
    // Adaptive (the fit refuses it; its residuals can still be computed): forward differences
    // against central ones of the same adaptive model.
    let p_dopri = problem(measurements, &dopri);
    let reference: Vec<Vec<f64>> = (0..4)
        .map(|k| central(&p_dopri, &at, k, 1e-4 * ranges[k]))
        .collect();
    let r0 = residuals(&p_dopri, &at).unwrap();
    println!("adaptive (DOPRI5, rtol 1e-9): forward differences of step h vs central (h = 1e-4), relative");
    for h in [1e-3, 1e-5, 1e-7, 1e-9] {
        let row: Vec<String> = (0..4)
            .map(|k| {
                let mut x = at.to_vec();
                x[k] += h * ranges[k];
                let r = residuals(&p_dopri, &x).unwrap();
                let f: Vec<f64> = r
                    .iter()
                    .zip(&r0)
                    .map(|(a, b)| (a - b) / (h * ranges[k]))
                    .collect();
                format!("{:.1e}", relative(&f, &reference[k]))
            })
            .collect();
        println!("  h = {h:.0e}: {}", row.join("  "));
    }
    let row: Vec<String> = (0..4)
        .map(|k| {
            let h = 1e-7 * ranges[k];
            let mut x = at.to_vec();
            x[k] += h;
            let r = residuals(&p_dopri, &x).unwrap();
            let f: Vec<f64> = r.iter().zip(&r0).map(|(a, b)| (a - b) / h).collect();
            format!(
                "{:.1e}",
                relative(&f, &central(&p_dopri, &at, k, 1e-6 * ranges[k]))
            )
        })
        .collect();
    println!("  forward 1e-7 vs central h = 1e-6: {}", row.join("  "));
    println!("parameters: {}", names.join(", "));
}
