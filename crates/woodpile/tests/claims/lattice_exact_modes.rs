//! Claim: on a lattice of finite-element rods the exact modal method (docs/physics.md §8 "Exact
//! linear vibrations", §16) meets a stated peak tolerance in steps set by the contacts, keeps
//! momentum to rounding and keeps the energy over long runs. The 3 × 3-rod, 4-layer lattice of
//! the lattice claims (4 elements per half rod: modes up to 0.45 MHz, above the 300 kHz where a
//! stated peak tolerance chooses the exact method) struck at (13, 1) mm.

use super::lattice_common::three_by_four;
use woodpile::ode::LatticeOde;
use woodpile::simulate::{simulate_lattice, LatticeRun};
use woodpile::{Method, RunSettings, Striker};

fn run(method: Method, duration_s: f64) -> LatticeRun {
    let lattice = three_by_four(4);
    let mut ode = LatticeOde::new(&lattice, &Striker::paper(), [13e-3, 1e-3]).unwrap();
    let settings = RunSettings {
        duration_s,
        method,
        sample_interval_s: 1e-6,
    };
    simulate_lattice(&mut ode, &settings).unwrap()
}

/// `peak_tolerance = 1e-5` chooses the exact modal method for these rods (at rtol 1e-8, the
/// lattices' rule). Against RKN 6(4) at rtol 1e-11 (converged: it agrees with the exact method at
/// 1e-12 to 3e-10, examples/lattice_exact.rs), every contact peak above 1 % of the largest is
/// within the stated 1e-5 (smaller peaks are the far supports', whose relative error is not what
/// the tolerance states), in at most a quarter of the steps RKN 6(4) takes at the rtol that
/// tolerance gives it (their step is set by the stiffest mode's stability; measured 1,374
/// against 6,434).
#[test]
fn exact_modes_meets_the_peak_tolerance_in_fewer_steps() {
    let tolerance = Method::PeakTolerance {
        peak_tolerance: 1e-5,
    };
    let exact = run(tolerance, 5e-4);
    assert!(
        matches!(exact.method, Method::ExactModes { .. }),
        "{:?}",
        exact.method
    );
    let reference = run(
        Method::Rkn64 {
            rtol: 1e-11,
            atol: 1e-17,
        },
        5e-4,
    );
    let largest = reference
        .contact_peak_forces_n
        .iter()
        .fold(0.0, |m: f64, &f| m.max(f));
    let mut worst = 0.0_f64;
    for (c, (&a, &b)) in exact
        .contact_peak_forces_n
        .iter()
        .zip(&reference.contact_peak_forces_n)
        .enumerate()
    {
        if b > 0.01 * largest {
            let e = (a / b - 1.0).abs();
            assert!(e <= 1e-5, "contact {c}: peak {a} N against {b} N ({e:e})");
            worst = worst.max(e);
        }
    }
    let rkn = run(tolerance.resolve(true), 5e-4);
    eprintln!(
        "worst peak {worst:.2e}; {} steps against RKN 6(4)'s {}; transmitted {} against {} N",
        exact.stats.steps,
        rkn.stats.steps,
        exact.transmitted_peak_force_n,
        reference.transmitted_peak_force_n
    );
    let e = (exact.transmitted_peak_force_n / reference.transmitted_peak_force_n - 1.0).abs();
    assert!(e <= 1e-5, "transmitted peak off by {e:e}");
    assert!(
        4 * exact.stats.steps <= rkn.stats.steps,
        "{} steps against RKN 6(4)'s {}",
        exact.stats.steps,
        rkn.stats.steps
    );
}

/// Every mode and the supports' impulses are advanced by the same cubics of the contact forces,
/// so momentum and its moment balance the supports' impulses to rounding, whatever the step's
/// accuracy (1e-12 of m v₀ and of m v₀ times the rod length, at a loose tolerance).
#[test]
fn exact_modes_balance_momentum_to_rounding() {
    let striker = Striker::paper();
    let run = run(
        Method::ExactModes {
            rtol: 1e-4,
            atol: 1e-10,
        },
        4e-4,
    );
    let p0 = striker.mass_kg() * striker.velocity_m_s;
    let (mut worst_p, mut worst_h) = (0.0_f64, 0.0_f64);
    for &(p, h, j, jh) in &run.momentum {
        worst_p = worst_p.max((p + j - p0).abs() / p0);
        for k in 0..2 {
            worst_h = worst_h.max((h[k] + jh[k]).abs() / (p0 * 80e-3));
        }
    }
    let &(_, _, j_end, _) = run.momentum.last().unwrap();
    eprintln!(
        "support impulse {:.3} of m v0; errors {worst_p:e}, {worst_h:e}",
        j_end / p0
    );
    assert!(
        j_end > 0.05 * p0,
        "the supports took a part of the momentum"
    );
    assert!(worst_p < 1e-12, "momentum off by {worst_p:e}");
    assert!(worst_h < 1e-12, "moment of momentum off by {worst_h:e}");
}

/// Lossless, the energy error of a long run (2 ms: the striker rebounds, the rods ring and
/// re-collide) at `peak_tolerance = 1e-5` stays below 1e-5: the method is not symplectic, but its
/// error per step is that of the contact forces' cubic, at the tolerance.
#[test]
fn exact_modes_keep_the_energy_over_long_runs() {
    let run = run(
        Method::PeakTolerance {
            peak_tolerance: 1e-5,
        },
        2e-3,
    );
    let e0 = run.energy.initial_j;
    let n = run.energy_j.len();
    let first_half = run.energy_j[..n / 2]
        .iter()
        .map(|e| (e - e0).abs() / e0)
        .fold(0.0, f64::max);
    eprintln!(
        "energy error {:.2e} (first half {first_half:.2e}) over {} steps",
        run.energy.max_relative_error, run.stats.steps
    );
    assert!(
        run.energy.max_relative_error < 1e-5,
        "energy off by {:e}",
        run.energy.max_relative_error
    );
}
