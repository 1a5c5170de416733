//! Claim: runs advanced together in SIMD lanes (`simulate_many`) report bit for bit what each
//! run reports alone (`simulate`): every contact peak and its time, the energy balance, the
//! restitution, the integrator's step counts. Checked on 27 random chains of Table 1 rods (1 or 2
//! resonators per cell, so lanes carry padding; 3, 8 and 20 rods, so runs fall into several
//! groups; resonant and rigid), under the paper's impact and blast, with Dormand–Prince (with
//! and without event-aware stepping, which must land on the same steps in the lanes), RKN 6(4)
//! (impact), a stated peak tolerance and RK4, at every lane width, on one thread and on three
//! (each group's nine runs then shared by three threads' lanes through one queue, and at width
//! eight run one lane wide). Tolerance: none. The lanes perform the scalar path's operations in
//! its order, so anything but equality is a bug (and would make GA results depend on the lane
//! width, the thread count and the grouping of designs).

use crate::lanes_common::{alone, assert_lanes_agree, peaks_only, random_chains};
use woodpile::{BlastProfile, Excitation, Job, Method, RunSummary, Striker};

fn same(a: &RunSummary, b: &RunSummary) -> bool {
    let a = RunSummary {
        wall_time_s: 0.0,
        ..a.clone()
    };
    let b = RunSummary {
        wall_time_s: 0.0,
        ..b.clone()
    };
    // Bits, not values: -0.0 vs 0.0 or a changed last bit are both differences here.
    format!("{a:?}") == format!("{b:?}")
        && a.contact_peak_forces_n
            .iter()
            .zip(&b.contact_peak_forces_n)
            .all(|(x, y)| x.to_bits() == y.to_bits())
        && a.energy.final_j.to_bits() == b.energy.final_j.to_bits()
}

fn check(excitation: &Excitation, method: Method, duration_s: f64) {
    let chains = random_chains(7, 27, &[3, 8, 20]);
    let settings = peaks_only(method, duration_s);
    let alone = alone(&chains, excitation, &settings);
    let jobs = Job::for_each_chain(&chains, excitation, &settings);
    assert_lanes_agree(&jobs, &alone, same);
}

#[test]
fn impact_dopri5() {
    let method = Method::Dopri5 {
        rtol: 1e-7,
        atol: 1e-13,
    };
    check(&Excitation::Impact(Striker::paper()), method, 6e-4);
}

#[test]
fn blast_dopri5() {
    let method = Method::Dopri5 {
        rtol: 1e-7,
        atol: 1e-13,
    };
    check(&Excitation::Blast(BlastProfile::paper()), method, 6e-4);
}

#[test]
fn impact_dopri5_events() {
    let method = Method::Dopri5Events {
        rtol: 1e-7,
        atol: 1e-13,
    };
    check(&Excitation::Impact(Striker::paper()), method, 6e-4);
}

#[test]
fn blast_dopri5_events() {
    let method = Method::Dopri5Events {
        rtol: 1e-7,
        atol: 1e-13,
    };
    check(&Excitation::Blast(BlastProfile::paper()), method, 6e-4);
}

#[test]
fn impact_rkn64() {
    // RKN 6(4): its own landing rule and its retaken steps must happen on the same steps.
    let method = Method::Rkn64 {
        rtol: 1e-7,
        atol: 1e-13,
    };
    check(&Excitation::Impact(Striker::paper()), method, 6e-4);
}

#[test]
fn peak_tolerance_resolved_per_group() {
    // A stated peak tolerance: RKN 6(4) for the impacts, event-aware DOPRI5 for the blasts.
    let method = Method::for_peak_tolerance(1e-4).unwrap();
    check(&Excitation::Impact(Striker::paper()), method, 6e-4);
    check(&Excitation::Blast(BlastProfile::paper()), method, 6e-4);
}

#[test]
fn impact_rk4() {
    check(
        &Excitation::Impact(Striker::paper()),
        Method::Rk4 { time_step_s: 2e-7 },
        3e-4,
    );
}
