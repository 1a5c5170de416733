//! Claim: struck off its centre, the lattice's vertical momentum and its moment about the impact
//! point follow the impulses of the supports (docs/physics.md §16): P(t) + J(t) = P(0) = m v₀ and
//! H(t) + J_H(t) = H(0) = 0, where P sums the striker's and every rod's momentum (the rods'
//! from their rigid translation modes), H = Σ (r − r₀) p (the rods' rocking modes carry their
//! moment about their centres) and J, J_H are the supports' impulse and its moment, integrated
//! with the motion. Every Runge–Kutta(–Nyström) step keeps a linear invariant up to rounding, so
//! both hold within 1e-9 (of m v₀, and of m v₀ times the rod length) unless the modal rows, the
//! participations or the rigid modes are wrong; checked with RKN 6(4) (adaptive, rtol 1e-8) on
//! the 3 × 3-rod, 4-layer lattice struck at (13, 1) mm, on the middle top rod 13 mm off its
//! centre and 1 mm off its axis.

use super::lattice_common::three_by_four;
use woodpile::ode::LatticeOde;
use woodpile::simulate::simulate_lattice;
use woodpile::{Method, RunSettings, Striker};

#[test]
fn momentum_and_its_moment_follow_the_support_impulses() {
    let lattice = three_by_four(4);
    let striker = Striker::paper();
    let mut ode = LatticeOde::new(&lattice, &striker, [13e-3, 1e-3]).unwrap();
    let settings = RunSettings {
        duration_s: 4e-4,
        method: Method::Rkn64 {
            rtol: 1e-8,
            atol: 1e-15,
        },
        sample_interval_s: 1e-6,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    let p0 = striker.mass_kg() * striker.velocity_m_s;
    let lever = 80e-3;
    let (mut worst_p, mut worst_h) = (0.0_f64, 0.0_f64);
    let mut largest_moment = 0.0_f64;
    for &(p, h, j, jh) in &run.momentum {
        worst_p = worst_p.max((p + j - p0).abs() / p0);
        for k in 0..2 {
            worst_h = worst_h.max((h[k] + jh[k]).abs() / (p0 * lever));
            largest_moment = largest_moment.max(jh[k].abs() / (p0 * lever));
        }
    }
    let &(_, _, j_end, _) = run.momentum.last().unwrap();
    eprintln!(
        "support impulse {:.3} of m v0, moment up to {largest_moment:.3e} of m v0 L; errors {worst_p:e}, {worst_h:e}",
        j_end / p0
    );
    assert!(
        j_end > 0.05 * p0,
        "the supports took a part of the momentum"
    );
    assert!(largest_moment > 1e-3, "the supports exerted a moment");
    assert!(worst_p < 1e-9, "momentum off by {worst_p:e}");
    assert!(worst_h < 1e-9, "moment of momentum off by {worst_h:e}");
}
