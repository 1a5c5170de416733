//! Claim: the exact modal method (`Method::ExactModes`, docs/physics.md §8 "Exact linear
//! vibrations") integrates the linear vibrations exactly and takes steps set by the contacts:
//! (1) with no force, a mode's step is the exact rotation, so a free rod's modes keep their
//! frequencies over 10⁶ periods (only rounding accumulates); (2) on a forced linear oscillator
//! c'' + Ω² c = f(t) its step (the cubic through four Lobatto nodes) is of order 6 where hΩ is
//! small and no worse where hΩ is large; (3) on five 80 mm quartz rods as finite-element beams
//! under the default impact, a stated peak tolerance of 1e-5 chooses it and every contact peak
//! lies within 1e-5 of a converged RKN 6(4) run in at most 1/8 of RKN 6(4)'s steps (5,008);
//! (4) its energy error stays bounded over a run 40 times longer; (5) the lanes, which run it on
//! the scalar path, give each run `simulate`'s bits.

use woodpile::integrate::exponential::{kernel, lagrange, nodes};
use woodpile::{
    simulate, CellModel, Chain, ChainBuilder, Element, Excitation, Material, Method, Rod,
    RunSettings, RunSummary, Striker, UnitCell,
};

fn fe_rods(count: usize) -> Chain {
    let rod = Rod::new(80e-3, 5e-3, 0.0, Material::fused_quartz()).unwrap();
    let cell = UnitCell::from_rod_fe(&rod, 16).unwrap();
    let elements = (0..count)
        .map(|_| {
            let mut e = Element::table1_rod(80, CellModel::Resonant).unwrap();
            e.cell = cell.clone();
            e
        })
        .collect();
    ChainBuilder::new(elements).build().unwrap()
}

fn run(chain: &Chain, method: Method, duration_s: f64) -> RunSummary {
    let settings = RunSettings {
        duration_s,
        method,
        ..RunSettings::paper_impact()
    };
    simulate(
        chain,
        &Excitation::Impact(Striker::paper()),
        &settings,
        &mut (),
    )
    .unwrap()
}

/// (1) The free flow: the step's matrix [[cos z, sin z / z], [−z sin z, cos z]] applied N times
/// against the rotation by N z, for the finite-element rod's lowest and highest free modes over
/// 10⁶ periods at an incommensurate step. Rounding alone accumulates, about N·ε per step: the
/// bound 1e-8 on the state (relative to its amplitude) is 10⁴ times the ~1e-12 a run of 10⁷
/// steps could drift by rounding, and 10⁶ periods of a frequency error of 1e-14 would show.
#[test]
fn free_modes_rotate_exactly() {
    let rod = Rod::new(80e-3, 5e-3, 0.0, Material::fused_quartz()).unwrap();
    let cell = UnitCell::from_rod_fe(&rod, 16).unwrap();
    let free = cell.free_resonances_hz();
    for f in [free[0], *free.last().unwrap()] {
        let omega = 2.0 * std::f64::consts::PI * f;
        let steps_per_period = 7.3;
        let h = 1.0 / f / steps_per_period;
        let n = (1e6 * steps_per_period) as usize;
        let k = kernel(1.0, h * omega);
        // State (c, ċ/Ω): starts at (1, 0).
        let (mut c, mut w) = (1.0_f64, 0.0_f64);
        for _ in 0..n {
            let c1 = k.cos * c + k.sinc * (h * omega) * w;
            let w1 = -k.zsin / (h * omega) * c + k.cos * w;
            c = c1;
            w = w1;
        }
        let phase = (n as f64 * h * omega) % std::f64::consts::TAU;
        let err = ((c - phase.cos()).powi(2) + (w + phase.sin()).powi(2)).sqrt();
        assert!(
            err < 1e-8,
            "mode at {f:.0} Hz: state error {err:.2e} after 10⁶ periods"
        );
    }
}

/// The step of c'' + Ω² c = f(t) with f given (the force cubic through the nodes), from (c, ċ).
fn forced_step(c: f64, cd: f64, t: f64, h: f64, omega: f64, f: &dyn Fn(f64) -> f64) -> (f64, f64) {
    let (nodes, l) = (nodes(), lagrange());
    let values: Vec<f64> = nodes.iter().map(|s| f(t + s * h)).collect();
    let a: Vec<f64> = (0..4)
        .map(|n| (0..4).map(|i| l[n][i] * values[i]).sum())
        .collect();
    let k = kernel(1.0, h * omega);
    let fs: f64 = (0..4).map(|n| k.s[n] * a[n]).sum();
    let fc: f64 = (0..4).map(|n| k.c[n] * a[n]).sum();
    (
        k.cos * c + h * k.sinc * cd + h * h * fs,
        -(k.zsin / h) * c + k.cos * cd + h * fc,
    )
}

/// (2) Order on a linear test: c'' + Ω² c = cos(νt), exact solution from rest
/// c = (cos νt − cos Ωt)/(Ω² − ν²). With Ω = 3, ν = 1 and steps T/n, halving the step must divide
/// the error by at least 2^5.5 (order 6, Lobatto collocation; the asymptotic ratio is 64): the
/// slow mode. With Ω = 300 (hΩ from 3 to 0.4: the fast mode, integrated exactly against the
/// force's cubic) the error must stay below the slow mode's at the same step (the force's
/// interpolation error, answered quasi-statically, ∝ 1/Ω²).
#[test]
fn sixth_order_on_a_forced_oscillator() {
    let nu = 1.0_f64;
    let f = |t: f64| (nu * t).cos();
    let t_end = 4.0;
    let error = |omega: f64, n: usize| {
        let h = t_end / n as f64;
        let (mut c, mut cd) = (0.0, 0.0);
        for i in 0..n {
            (c, cd) = forced_step(c, cd, i as f64 * h, h, omega, &f);
        }
        let exact = ((nu * t_end).cos() - (omega * t_end).cos()) / (omega * omega - nu * nu);
        (c - exact).abs()
    };
    let slow: Vec<f64> = [8, 16, 32].iter().map(|&n| error(3.0, n)).collect();
    for pair in slow.windows(2) {
        assert!(
            pair[0] / pair[1] > 2f64.powf(5.5),
            "slow mode errors {slow:?}: not of order 6"
        );
    }
    for (&n, &e_slow) in [8, 16, 32].iter().zip(&slow) {
        let e_fast = error(300.0, n);
        assert!(
            e_fast < e_slow,
            "fast mode at n = {n}: {e_fast:.2e} ≥ slow {e_slow:.2e}"
        );
    }
}

/// (3) The five-rod finite-element chain, 0.5 ms of the default impact: `peak_tolerance = 1e-5`
/// resolves to the exact modal method, every contact peak within 1e-5 of RKN 6(4) at rtol 1e-12
/// (converged: the exact method at rtol 1e-12 agrees with it to ~3e-12, bench/README.md), in at
/// most 626 steps (RKN 6(4) took 5,008 at this tolerance, issue figure and bench/README.md).
#[test]
fn fe_chain_peaks_within_tolerance_in_an_eighth_of_the_steps() {
    let chain = fe_rods(5);
    let settings = RunSettings {
        duration_s: 5e-4,
        method: Method::PeakTolerance {
            peak_tolerance: 1e-5,
        },
        ..RunSettings::paper_impact()
    };
    let impact = Excitation::Impact(Striker::paper());
    assert!(matches!(
        settings.method_for(&chain, &impact).unwrap(),
        Method::ExactModes { .. }
    ));
    let fast = run(&chain, settings.method, 5e-4);
    let reference = run(
        &chain,
        Method::Rkn64 {
            rtol: 1e-12,
            atol: 1e-18,
        },
        5e-4,
    );
    let worst = fast
        .contact_peak_forces_n
        .iter()
        .zip(&reference.contact_peak_forces_n)
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst <= 1e-5, "worst contact peak error {worst:.2e}");
    assert!(fast.stats.steps <= 5008 / 8, "{} steps", fast.stats.steps);
}

/// (4) Energy over a long run: two finite-element rods, 20 ms (40 times the test above, the
/// striker long gone, the rods ringing), at rtol 1e-6. The energy balance is audited at every
/// sample from the modal state; it must stay within 1e-5 of the impact energy (the error of a
/// run at this rtol over 0.5 ms is ~1e-7, bench/README.md; a drift that grew with time would
/// exceed it).
#[test]
fn energy_error_bounded_over_a_long_run() {
    let chain = fe_rods(2);
    let s = run(
        &chain,
        Method::ExactModes {
            rtol: 1e-6,
            atol: 1e-12,
        },
        2e-2,
    );
    assert!(
        s.energy.max_relative_error < 1e-5,
        "energy error {:.2e}",
        s.energy.max_relative_error
    );
}

/// (5) The lanes: a design study mixing Table 1 chains (RKN 6(4) in lanes) and finite-element
/// chains (the exact modal method, run on the scalar path) gives every run bit for bit what
/// `simulate` gives it (peaks, their times, the energy balance and the step counts), at the
/// default settings of a study (one sample at the end).
#[test]
fn lanes_give_simulate_s_bits() {
    let fe = fe_rods(2);
    let table1 = ChainBuilder::table1_rods(&[80, 40], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let chains = vec![fe.clone(), table1.clone(), fe, table1];
    let settings = RunSettings {
        duration_s: 2e-4,
        method: Method::PeakTolerance {
            peak_tolerance: 1e-5,
        },
        sample_interval_s: 2e-4,
    };
    let impact = Excitation::Impact(Striker::paper());
    let jobs = woodpile::Job::for_each_chain(&chains, &impact, &settings);
    let many = woodpile::simulate_many(&jobs, woodpile::LaneWidth::Four);
    for (chain, got) in chains.iter().zip(many) {
        let got = got.unwrap();
        let alone = simulate(chain, &impact, &settings, &mut ()).unwrap();
        assert_eq!(got.contact_peak_forces_n, alone.contact_peak_forces_n);
        assert_eq!(got.contact_peak_times_s, alone.contact_peak_times_s);
        assert_eq!(got.energy, alone.energy);
        assert_eq!(got.stats, alone.stats);
    }
}
