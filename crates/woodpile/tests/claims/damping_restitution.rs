//! Claim: with the restitution law and pulling allowed, a striker hitting one free rigid sphere
//! rebounds with the requested coefficient of restitution e — relative separation speed over
//! approach speed — within 1 % for e = 0.5, 0.8, 0.95 at impact speeds 0.1, 1 and 3 m/s
//! (docs/physics.md §14). The law's damping η ∝ δ^{1/4} makes the rebound independent of the
//! speed and the LAMMPS coefficient makes it exactly e, so 1 % is a generous bound: RK4 at 2 ns
//! resolves a ≥ 20 µs contact with 1e4 steps, and the end velocities are read after separation.
//!
//! Second claim: without pulling (the default) the contact force is clipped at zero near
//! separation, so less energy is dissipated and the rebound is faster: e_measured ≥ e, by
//! 5–15 % at e = 0.5 (the clipped tail of the pulse; measured 10 % by the project's scripts).
//!
//! Third claim: the energy dissipated closes the balance, E(0) = E(t) + D(t), to 1e-6.

use crate::collision;
use woodpile::{ContactDamping, Damping};

fn rebound(e: f64, v0: f64, allow_pull: bool) -> (f64, f64) {
    let damping = Damping {
        contacts: ContactDamping::Restitution { coefficient: e },
        allow_pull,
        ..Damping::default()
    };
    collision::rebound(damping, v0)
}

#[test]
fn restitution_law_rebounds_with_e_when_pulling_is_allowed() {
    for e in [0.5, 0.8, 0.95] {
        for v0 in [0.1, 1.0, 3.0] {
            let (measured, balance) = rebound(e, v0, true);
            assert!(
                (measured / e - 1.0).abs() < 0.01,
                "e = {e}, v0 = {v0} m/s: rebound {measured}"
            );
            assert!(
                balance < 1e-6,
                "e = {e}, v0 = {v0}: energy balance {balance}"
            );
        }
    }
}

#[test]
fn tension_free_restitution_law_rebounds_faster() {
    let (measured, balance) = rebound(0.5, 1.0, false);
    assert!(
        measured > 0.5 * 1.05 && measured < 0.5 * 1.15,
        "rebound without pulling {measured}"
    );
    assert!(balance < 1e-6, "energy balance {balance}");
    for e in [0.8, 0.95] {
        let (measured, _) = rebound(e, 1.0, false);
        assert!(measured >= e, "e = {e}: rebound without pulling {measured}");
    }
}
