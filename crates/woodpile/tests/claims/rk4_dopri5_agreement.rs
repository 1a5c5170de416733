//! Claim: the paper's fixed-step RK4 (Δt = 0.1 µs) and the adaptive Dormand–Prince 5(4)
//! (rtol = 1e-10) agree on the peak force of every contact of the 20-rod resonant impact to
//! 1e-5 relative, and both conserve energy.
//!
//! Tolerance: 1e-5 is the stated bound. Both methods' peak errors are ~1e-7 against a converged
//! reference (measured with `examples/accuracy_speed.rs`); the peaks between steps are refined by
//! Hermite interpolation, whose error is O(h⁴) of the pulse's time scale.

use woodpile::{
    simulate, CellModel, ChainBuilder, Excitation, Method, RunSettings, Striker,
    PAPER_OPTIMIZED_CHAIN_MM,
};

#[test]
fn every_contact_peak_agrees_to_1e5() {
    let chain = ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let impact = Excitation::Impact(Striker::paper());
    let rk4 = simulate(&chain, &impact, &RunSettings::paper_impact(), &mut ()).unwrap();
    let adaptive = RunSettings {
        method: Method::Dopri5 {
            rtol: 1e-10,
            atol: 1e-16,
        },
        ..RunSettings::paper_impact()
    };
    let dp = simulate(&chain, &impact, &adaptive, &mut ()).unwrap();
    assert!(
        dp.stats.steps < rk4.stats.steps,
        "the adaptive method takes fewer steps"
    );
    for (c, (a, b)) in rk4
        .contact_peak_forces_n
        .iter()
        .zip(&dp.contact_peak_forces_n)
        .enumerate()
    {
        let rel = (a / b - 1.0).abs();
        assert!(
            rel < 1e-5,
            "contact {c}: rk4 {a} N vs dopri5 {b} N (relative {rel:.2e})"
        );
    }
    assert!(
        dp.energy.max_relative_error < 1e-6,
        "dopri5 energy drift {:e}",
        dp.energy.max_relative_error
    );
}
