//! Claim: a run that tracks only the figures of merit (`PeakWatch::FiguresOfMerit`, what the GA's
//! force objectives ask for) reports bit for bit what a run that tracks every contact reports for
//! them: the incident (contact 1) and transmitted (contact N) peaks and their times, the
//! transmission ratio, `wave_arrived`, the restitution, the energy balance and the integrator's
//! counts; the other contacts' peaks are NaN, not stale numbers. Checked in lanes at every width
//! (`simulate_many_watching`) against `simulate`, on 12 random chains of Table 1 rods (1 or 2
//! resonators per cell; 1, 3, 8 and 20 rods, so one chain's incident contact is its wall contact;
//! resonant and rigid) under the paper's impact and blast, with Dormand–Prince and RK4. And a
//! blow-up is still detected and named with the same error as `simulate` gives: the lanes check
//! every contact at every step (vectorised), and hand a failing run to the scalar path.
//! Tolerance: none; anything but equality is a bug (and would make a GA's results depend on the
//! watch).

use crate::lanes_common::{alone, peaks_only, random_chains};
use woodpile::{
    simulate, simulate_many_watching, BlastProfile, CellModel, ChainBuilder, Excitation, Job,
    LaneWidth, Method, PeakWatch, RunSettings, RunSummary, Striker,
};

/// The figures of merit agree bit for bit; the untracked peaks are NaN.
fn assert_same_figures(light: &RunSummary, full: &RunSummary, what: &str) {
    let n = full.contact_peak_forces_n.len() - 1;
    let tracked = [1.min(n), n];
    for c in 0..=n {
        let (lf, lt) = (
            light.contact_peak_forces_n[c],
            light.contact_peak_times_s[c],
        );
        if tracked.contains(&c) {
            assert_eq!(
                (lf.to_bits(), lt.to_bits()),
                (
                    full.contact_peak_forces_n[c].to_bits(),
                    full.contact_peak_times_s[c].to_bits()
                ),
                "{what}: contact {c}"
            );
        } else {
            assert!(lf.is_nan() && lt.is_nan(), "{what}: contact {c} tracked");
        }
    }
    let figures = |s: &RunSummary| {
        format!(
            "{:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?}",
            s.incident_peak_force_n.to_bits(),
            s.transmitted_peak_force_n.to_bits(),
            s.transmission_ratio.map(f64::to_bits),
            s.wave_arrived,
            s.restitution
                .map(|r| (r.coefficient.to_bits(), r.separated)),
            s.energy,
            s.stats,
            s.n_samples
        )
    };
    assert_eq!(figures(light), figures(full), "{what}");
}

fn check(excitation: &Excitation, method: Method, duration_s: f64) {
    let chains = random_chains(11, 12, &[1, 3, 8, 20]);
    let settings = peaks_only(method, duration_s);
    let full = alone(&chains, excitation, &settings);
    let jobs = Job::for_each_chain(&chains, excitation, &settings);
    for width in LaneWidth::ALL {
        let light = simulate_many_watching(&jobs, width, PeakWatch::FiguresOfMerit);
        for (i, (l, f)) in light.iter().zip(&full).enumerate() {
            assert_same_figures(l.as_ref().unwrap(), f, &format!("chain {i}, {width:?}"));
        }
    }
}

#[test]
fn impact_and_blast_dopri5() {
    let method = Method::Dopri5 {
        rtol: 1e-7,
        atol: 1e-13,
    };
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

/// A step far too large for the rigid rods' contacts (blowup_detection's case) among good runs:
/// the lanes report the blow-up with exactly the error `simulate` gives, and the others unchanged.
#[test]
fn blow_up_is_detected_and_named() {
    let rigid = ChainBuilder::table1_rods(&[20; 5], CellModel::Rigid)
        .unwrap()
        .build()
        .unwrap();
    let good = ChainBuilder::table1_rods(&[40; 5], CellModel::Rigid)
        .unwrap()
        .build()
        .unwrap();
    let impact = Excitation::Impact(Striker::paper());
    let blows = RunSettings {
        duration_s: 1e-3,
        method: Method::Rk4 { time_step_s: 2e-5 },
        sample_interval_s: 1e-3,
    };
    let fine = RunSettings {
        method: Method::Rk4 { time_step_s: 1e-7 },
        ..blows
    };
    let expected = simulate(&rigid, &impact, &blows, &mut ()).unwrap_err();
    let jobs = [
        Job {
            chain: &good,
            excitation: &impact,
            settings: &fine,
        },
        Job {
            chain: &rigid,
            excitation: &impact,
            settings: &blows,
        },
    ];
    let full = simulate(&good, &impact, &fine, &mut ()).unwrap();
    for width in LaneWidth::ALL {
        let results = simulate_many_watching(&jobs, width, PeakWatch::FiguresOfMerit);
        assert_same_figures(results[0].as_ref().unwrap(), &full, &format!("{width:?}"));
        assert_eq!(results[1].as_ref().unwrap_err(), &expected, "{width:?}");
    }
}
