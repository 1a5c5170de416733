//! Claim: a lattice run's per-contact energies are each contact's Hertz potential and its own
//! dissipated energy over time (docs/physics.md §16).
//!
//! (1) Lossless: the 3 × 3-rod, 4-layer lattice struck off-centre (the paper's striker at
//! (13, 1) mm, a peak tolerance of 1e-6, the exact modal method, over 0.3 ms). At every sample every
//! contact's potential equals (2/5) F δ with δ = (F/β)^{2/3}, the Hertz law read backwards from
//! the sampled force, within 1e-12 of E(0) (rounding: two powers; measured 2.5e-16); the contacts' potentials
//! never exceed the total energy, which is what the modes hold besides them (their kinetic and
//! strain energy, ≥ 0); and a closed contact holds energy at some sample in every layer.
//!
//! (2) Damped: the same impact with restitution contacts (e = 0.7) and no modal or on-site
//! damping (DOPRI5 at rtol 1e-9): each contact's cumulative dissipated energy never falls (to
//! 1e-15 of E(0)), their sum is D(t) at every sample within 1e-12 of E(0) (all of D is at the
//! contacts; measured 0: the same sum), and their last sample is the run's per-contact total within 1e-12 of E(0).

use super::lattice_common::three_by_four;
use woodpile::model::{ContactDamping, Damping, LatticeExcitation, LatticeLab};
use woodpile::ode::LatticeOde;
use woodpile::simulate::simulate_lattice;
use woodpile::{Method, RunSettings, Striker};

fn excitation() -> LatticeExcitation {
    LatticeExcitation::Impact {
        striker: Striker::paper(),
        at_m: [13e-3, 1e-3],
    }
}

#[test]
fn contact_energies_are_the_hertz_potentials_of_the_forces() {
    let lattice = three_by_four(4);
    let mut ode = LatticeOde::build(&lattice, &excitation(), &LatticeLab::default()).unwrap();
    let settings = RunSettings {
        duration_s: 3e-4,
        method: Method::PeakTolerance {
            peak_tolerance: 1e-6,
        },
        sample_interval_s: 1e-6,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    let betas = ode.contact_betas().to_vec();
    let e0 = run.energy_j[0];
    let nc = run.contacts;
    let (mut worst, mut worst_excess) = (0.0_f64, f64::MIN);
    let mut held = vec![false; nc];
    for (k, total) in run.energy_j.iter().enumerate() {
        let row = &run.contact_energies_j[k * nc..(k + 1) * nc];
        let forces = &run.contact_forces_n[k * nc..(k + 1) * nc];
        for c in 0..nc {
            let f = forces[c];
            let hertz = 0.4 * f * (f / betas[c]).powf(2.0 / 3.0);
            worst = worst.max((row[c] - hertz).abs() / e0);
            held[c] |= row[c] > 0.0;
        }
        worst_excess = worst_excess.max((row.iter().sum::<f64>() - total) / e0);
    }
    eprintln!(
        "potential against (2/5) F δ: {worst:e} of E(0); largest Σ U_c − E: {worst_excess:e} of E(0); \
         {} of {nc} contacts held energy",
        held.iter().filter(|&&h| h).count()
    );
    assert!(worst < 1e-12, "{worst:e}");
    assert!(
        worst_excess <= 1e-12,
        "the contacts hold more than the total"
    );
    for layer in 1..=4 {
        assert!(
            lattice
                .contacts
                .iter()
                .enumerate()
                .any(|(i, k)| lattice.rods[k.above.rod].layer == layer && held[i + 1]),
            "no contact under layer {layer} held energy"
        );
    }
}

#[test]
fn contact_dissipation_over_time_adds_up_to_the_runs() {
    let lattice = three_by_four(4);
    let lab = LatticeLab {
        damping: Damping {
            contacts: ContactDamping::Restitution { coefficient: 0.7 },
            ..Damping::default()
        },
        ..LatticeLab::default()
    };
    let mut ode = LatticeOde::build(&lattice, &excitation(), &lab).unwrap();
    let settings = RunSettings {
        duration_s: 3e-4,
        method: Method::Dopri5 {
            rtol: 1e-9,
            atol: 1e-12,
        },
        sample_interval_s: 1e-6,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    let e0 = run.energy.initial_j;
    let nc = run.contacts;
    let samples = run.times_s.len();
    assert_eq!(run.contact_dissipated_samples_j.len(), samples * nc);
    let d = |k: usize, c: usize| run.contact_dissipated_samples_j[k * nc + c];
    let (mut fall, mut sum_error) = (0.0_f64, 0.0_f64);
    for k in 0..samples {
        let sum: f64 = (0..nc).map(|c| d(k, c)).sum();
        sum_error = sum_error.max((sum - run.dissipated_j[k]).abs() / e0);
        if k > 0 {
            for c in 0..nc {
                fall = fall.max((d(k - 1, c) - d(k, c)) / e0);
            }
        }
    }
    let last_error = (0..nc)
        .map(|c| (d(samples - 1, c) - run.contact_dissipated_j[c]).abs() / e0)
        .fold(0.0_f64, f64::max);
    eprintln!(
        "D = {:.3} of E(0); Σ_c D_c(t) − D(t): {sum_error:e}; largest fall {fall:e}; last sample \
         against the totals {last_error:e} (of E(0))",
        run.energy.dissipated_j / e0
    );
    assert!(run.energy.dissipated_j > 0.05 * e0);
    assert!(
        fall <= 1e-15,
        "a contact's dissipated energy fell by {fall:e}"
    );
    assert!(sum_error < 1e-12);
    assert!(last_error < 1e-12);
}
