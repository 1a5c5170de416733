//! Claim: the peak of a tabulated load is exact. The load is piecewise linear in time, so its
//! maximum over a step lies at an end of the step or at a table breakpoint inside it; a
//! breakpoint off the step grid (here 12.34 µs with RK4 steps of 0.1 µs) must not be missed.
//! Tolerance 1e-12 relative: the peak is read from the table itself, not interpolated.

use woodpile::{simulate, BlastProfile, CellModel, ChainBuilder, Excitation, Method, RunSettings};

#[test]
fn breakpoint_inside_a_step_gives_the_tabulated_peak() {
    let chain = ChainBuilder::table1_rods(&[40, 40, 40], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let load = BlastProfile::table(vec![0.0, 1.234e-5, 5e-5], vec![0.0, 180.0, 0.0]).unwrap();
    let settings = RunSettings {
        duration_s: 1e-4,
        method: Method::Rk4 { time_step_s: 1e-7 },
        sample_interval_s: 1e-6,
    };
    let s = simulate(&chain, &Excitation::Blast(load), &settings, &mut ()).unwrap();
    assert!(
        (s.contact_peak_forces_n[0] - 180.0).abs() <= 1e-12 * 180.0,
        "load peak {}",
        s.contact_peak_forces_n[0]
    );
    assert!(
        (s.contact_peak_times_s[0] - 1.234e-5).abs() <= 1e-18,
        "load peak time {}",
        s.contact_peak_times_s[0]
    );
}
