//! Claim: a blast on a lattice delivers the profile's impulse, split equally over its load
//! points (docs/physics.md §16). A Friedlander blast (F0 = 200 N, Td = 0.1 ms, b = 1) on every
//! top-layer crossing of the 3 × 3-rod, 4-layer lattice (9 points, F0/9 each; DOPRI5 at rtol
//! 1e-10 over 0.3 ms): (1) after the blast the lattice's vertical momentum plus the supports'
//! impulse equals the profile's impulse F0 Td (1/b − (1 − e^{−b})/b²) = F0 Td/e within 1e-8 (the
//! integrator's accuracy; measured 2.6e-10); (2) each load point's force is F(t)/9 at every sample
//! (to rounding, 1e-15 of F0); (3) the lattice and its load are symmetric under x → −x and y → −y, and every
//! contact's force equals its mirror image's within 1e-12 of the largest force (rounding); (4)
//! W(t) = E(t) (lossless) within 1e-8 of the largest W.

use super::lattice_common::three_by_four;
use woodpile::model::{LatticeExcitation, LatticeLab, LoadPoints};
use woodpile::ode::LatticeOde;
use woodpile::simulate::simulate_lattice;
use woodpile::{BlastProfile, Method, RunSettings};

#[test]
fn blast_on_top_crossings_delivers_its_impulse_symmetrically() {
    let lattice = three_by_four(4);
    let (f0, td) = (200.0, 1e-4);
    let profile = BlastProfile::Friedlander {
        peak_force_n: f0,
        duration_s: td,
        decay: 1.0,
    };
    let excitation = LatticeExcitation::Blast {
        profile: profile.clone(),
        points: LoadPoints::TopCrossings,
    };
    let mut ode = LatticeOde::build(&lattice, &excitation, &LatticeLab::default()).unwrap();
    let loads = ode.incident_contacts().len();
    assert_eq!(loads, 9);
    let settings = RunSettings {
        duration_s: 3e-4,
        method: Method::Dopri5 {
            rtol: 1e-10,
            atol: 1e-14,
        },
        sample_interval_s: 1e-6,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    // (1) Impulse.
    let impulse = f0 * td * (-1.0_f64).exp();
    let (p, _, j, _) = *run.momentum.last().unwrap();
    let impulse_error = ((p + j) - impulse).abs() / impulse;
    eprintln!(
        "P + J = {:.9e} N s against F0 Td/e = {impulse:.9e}: {impulse_error:.2e}",
        p + j
    );
    assert!(impulse_error < 1e-8);
    // (2) The split.
    for (k, &t) in run.times_s.iter().enumerate() {
        for c in 0..loads {
            let f = run.contact_forces_n[k * run.contacts + c];
            let share = profile.force_n(t) / 9.0;
            assert!(
                (f - share).abs() <= 1e-15 * f0,
                "load point {c} at t = {t:e}: {f} N"
            );
        }
    }
    // (3) Mirror symmetry of the lattice's contacts (after the load points).
    let peak = run
        .contact_peak_forces_n
        .iter()
        .fold(0.0_f64, |a, &b| a.max(b));
    let supports: f64 = run
        .supports
        .iter()
        .map(|&s| run.contact_peak_forces_n[s])
        .sum();
    assert!(supports > 0.05 * peak, "the load reached the supports");
    let contacts = &lattice.contacts;
    let (mut worst, mut pairs) = (0.0_f64, 0);
    for (i, a) in contacts.iter().enumerate() {
        for mirror in [[-1.0, 1.0], [1.0, -1.0]] {
            let image = [mirror[0] * a.point_m[0], mirror[1] * a.point_m[1]];
            let j = contacts
                .iter()
                .position(|b| {
                    b.support.is_some() == a.support.is_some()
                        && lattice.rods[b.above.rod].layer == lattice.rods[a.above.rod].layer
                        && (b.point_m[0] - image[0]).abs() < 1e-9
                        && (b.point_m[1] - image[1]).abs() < 1e-9
                })
                .expect("every contact has its mirror image");
            if i != j {
                pairs += 1;
                let (fa, fb) = (
                    run.contact_force_n(i + loads),
                    run.contact_force_n(j + loads),
                );
                for (x, y) in fa.iter().zip(&fb) {
                    worst = worst.max((x - y).abs() / peak);
                }
            }
        }
    }
    eprintln!("{pairs} mirror pairs, largest difference {worst:e} of the peak {peak:.3} N");
    assert!(pairs > 20);
    assert!(worst < 1e-12);
    // (4) Lossless: the work done is the energy held.
    eprintln!(
        "W = {:.4e} J at the end, balance error {:.2e}",
        run.energy.input_work_j, run.energy.max_relative_error
    );
    assert!(run.energy.input_work_j > 0.0 && run.energy.dissipated_j == 0.0);
    assert!(run.energy.max_relative_error < 1e-8);
}
