//! Claim: the integrators converge at their design order on a problem with a known solution —
//! RK4 at order 4, Dormand–Prince at order 5 (its solution weights), the Runge–Kutta–Nyström
//! pair RKN6(4) at order 6 in positions and velocities — and their dense outputs are at least
//! 4th-order accurate between steps.
//!
//! Problem: the harmonic oscillator x'' = −ω² x, x(0) = 1, x'(0) = 0, exact x = cos ωt, over 2
//! periods. The observed order log2(e(h)/e(h/2)) is measured between steps large enough that
//! rounding (1e-16) is far below the error; ±0.2 allows for the asymptotic regime not being
//! reached exactly.

use woodpile::{Integrator, OdeSystem, Tableau};

struct Oscillator {
    omega: f64,
}

impl OdeSystem for Oscillator {
    fn dimension(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = y[1];
        dydt[1] = -self.omega * self.omega * y[0];
    }
}

const OMEGA: f64 = 2.0 * std::f64::consts::PI;
const T_END: f64 = 2.0;

/// Largest error at the steps and at the mid-points of the steps (dense output).
fn errors(tableau: Tableau, steps: usize) -> (f64, f64) {
    let mut sys = Oscillator { omega: OMEGA };
    let h = T_END / steps as f64;
    let mut integ = Integrator::fixed_step(tableau, h, &mut sys, 0.0, vec![1.0, 0.0]);
    let (mut at_steps, mut between) = (0.0_f64, 0.0_f64);
    let mut mid = [0.0; 2];
    while integ.t() < T_END * (1.0 - 1e-12) {
        integ.step(&mut sys, T_END).unwrap();
        at_steps = at_steps.max((integ.y()[0] - (OMEGA * integ.t()).cos()).abs());
        let tm = 0.5 * (integ.t_prev() + integ.t());
        integ.interpolate(tm, &mut mid);
        between = between.max((mid[0] - (OMEGA * tm).cos()).abs());
    }
    (at_steps, between)
}

fn observed_order(tableau: fn() -> Tableau, steps: usize) -> (f64, f64) {
    let (e1, d1) = errors(tableau(), steps);
    let (e2, d2) = errors(tableau(), 2 * steps);
    ((e1 / e2).log2(), (d1 / d2).log2())
}

#[test]
fn rk4_is_fourth_order() {
    let (order, dense) = observed_order(Tableau::rk4, 200);
    assert!((order - 4.0).abs() < 0.2, "observed RK4 order {order:.3}");
    assert!(
        dense > 3.8,
        "observed order of the Hermite dense output {dense:.3}"
    );
}

#[test]
fn dopri5_is_fifth_order() {
    let (order, dense) = observed_order(Tableau::dopri5, 100);
    assert!(
        (order - 5.0).abs() < 0.2,
        "observed Dormand-Prince order {order:.3}"
    );
    assert!(
        dense > 3.8,
        "observed order of the Dormand-Prince dense output {dense:.3}"
    );
}

#[test]
fn rkn64_is_sixth_order() {
    // A typo in one of its coefficients (published as fractions) drops the observed order to 4 or
    // less: each of the order conditions up to 6 uses them.
    let (order, dense) = observed_order(Tableau::rkn64, 100);
    assert!(
        (order - 6.0).abs() < 0.2,
        "observed RKN6(4) order {order:.3}"
    );
    assert!(
        dense > 3.8,
        "observed order of the RKN Hermite dense output {dense:.3}"
    );
}

#[test]
fn rkn64_velocities_are_sixth_order() {
    let velocity_error = |steps: usize| {
        let mut sys = Oscillator { omega: OMEGA };
        let h = T_END / steps as f64;
        let mut integ = Integrator::fixed_step(Tableau::rkn64(), h, &mut sys, 0.0, vec![1.0, 0.0]);
        let mut worst = 0.0_f64;
        while integ.t() < T_END * (1.0 - 1e-12) {
            integ.step(&mut sys, T_END).unwrap();
            let exact = -OMEGA * (OMEGA * integ.t()).sin();
            worst = worst.max((integ.y()[1] - exact).abs());
        }
        worst
    };
    let order = (velocity_error(100) / velocity_error(200)).log2();
    assert!(
        (order - 6.0).abs() < 0.2,
        "observed RKN6(4) velocity order {order:.3}"
    );
}

#[test]
fn tableaux_are_consistent() {
    // Row sums of A equal c (the stage times), and the weights sum to 1: necessary for any order.
    for tab in [Tableau::rk4(), Tableau::dopri5()] {
        for (i, row) in tab.a.iter().enumerate() {
            let sum: f64 = row.iter().sum();
            assert!((sum - tab.c[i]).abs() < 1e-14, "{} row {i}", tab.name);
        }
        assert!(
            (tab.b.iter().sum::<f64>() - 1.0).abs() < 1e-14,
            "{} weights",
            tab.name
        );
    }
    // A Nyström tableau: row sums of A equal c²/2, position weights sum to 1/2, velocity
    // weights to 1, and both embedded estimates' weights to 0 (the two formulas agree on a
    // constant acceleration).
    let rkn = Tableau::rkn64();
    for (i, row) in rkn.a.iter().enumerate() {
        let sum: f64 = row.iter().sum();
        assert!(
            (sum - 0.5 * rkn.c[i] * rkn.c[i]).abs() < 1e-14,
            "rkn64 row {i}"
        );
    }
    let velocity = rkn.nystrom.as_ref().unwrap();
    let total = |w: &[f64]| w.iter().sum::<f64>();
    assert!((total(&rkn.b) - 0.5).abs() < 1e-14);
    assert!((total(&velocity.b) - 1.0).abs() < 1e-14);
    assert!(total(rkn.error.as_ref().unwrap()).abs() < 1e-14);
    assert!(total(&velocity.error).abs() < 1e-14);
}
