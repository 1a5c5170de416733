//! Claim: a lattice symmetric under the mirrors x → −x and y → −y and struck at its centre
//! answers symmetrically (docs/physics.md §16). On the 3 × 3-rod, 4-layer lattice (4 elements
//! per half rod, RK4 at 40 ns, 0.3 ms: the wave reaches the supports) every contact's force
//! equals its mirror image's at every sample within 1e-12 of the largest force. Only rounding
//! separates them: the eigenvectors are symmetric or antisymmetric to ~1e-15, and the layers
//! along y have cos 90° = 6e-17 in their axes.

use super::lattice_common::three_by_four;
use woodpile::ode::LatticeOde;
use woodpile::simulate::simulate_lattice;
use woodpile::{Method, RunSettings, Striker};

#[test]
fn centre_impact_gives_mirror_equal_forces() {
    let lattice = three_by_four(4);
    let mut ode = LatticeOde::new(&lattice, &Striker::paper(), [0.0, 0.0]).unwrap();
    let settings = RunSettings {
        duration_s: 3e-4,
        method: Method::Rk4 { time_step_s: 4e-8 },
        sample_interval_s: 1e-6,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    let peak = run
        .contact_peak_forces_n
        .iter()
        .fold(0.0_f64, |a, &b| a.max(b));
    let supports: f64 = run
        .supports
        .iter()
        .map(|&s| run.contact_peak_forces_n[s])
        .sum();
    assert!(supports > 0.01 * peak, "the wave reached the supports");
    // Output order: striker, then the lattice's contacts.
    let contacts = &lattice.contacts;
    let mut worst = 0.0_f64;
    let mut pairs = 0;
    for (i, a) in contacts.iter().enumerate() {
        for mirror in [[-1.0, 1.0], [1.0, -1.0]] {
            let image = [mirror[0] * a.point_m[0], mirror[1] * a.point_m[1]];
            let j = contacts
                .iter()
                .position(|b| {
                    b.support == a.support.map(|_| b.support.unwrap_or(0))
                        && lattice.rods[b.above.rod].layer == lattice.rods[a.above.rod].layer
                        && (b.point_m[0] - image[0]).abs() < 1e-9
                        && (b.point_m[1] - image[1]).abs() < 1e-9
                })
                .expect("every contact has its mirror image");
            if i == j {
                continue;
            }
            pairs += 1;
            let (fa, fb) = (run.contact_force_n(i + 1), run.contact_force_n(j + 1));
            for (x, y) in fa.iter().zip(&fb) {
                worst = worst.max((x - y).abs() / peak);
            }
        }
    }
    eprintln!("{pairs} mirror pairs, largest difference {worst:e} of the peak force {peak:.3} N");
    assert!(pairs > 20);
    assert!(
        worst < 1e-12,
        "mirror images differ by {worst:e} of the peak"
    );
}
