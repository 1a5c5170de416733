//! Claim: the lab physics of docs/physics.md §14 runs in SIMD lanes, and the lanes report bit for
//! bit what each run reports alone. Damped contacts (restitution between elements, Hunt–Crossley
//! at the wall, viscoelastic at the striker), damped resonators and on-site damping, a preload
//! with gravity, a blast on a damped column, a force drive and a displacement drive through an
//! actuator's tip: each problem's 12 random chains (1 or 2 resonators per cell, so lanes carry
//! padding; 3 and 8 rods, two groups) at every lane width, on one thread and on three. Also:
//! every one of these jobs is taken by the lanes (`Job::in_lanes`), so the equality is not that
//! of the scalar path with itself; and a problem mixing two damping laws splits into groups
//! that still agree. Tolerance: none — the lanes run the scalar path's own equations.

use crate::lanes_common::{alone, assert_lanes_agree, peaks_only, random_builders};
use woodpile::{
    BlastProfile, Chain, ContactDamping, Damping, Drive, DriveQuantity, Excitation, Job, Method,
    Preload, RunSettings, RunSummary, Signal, Striker, Wall,
};

fn bits(s: &RunSummary) -> String {
    let s = RunSummary {
        wall_time_s: 0.0,
        ..s.clone()
    };
    // {:?} prints every f64 exactly (shortest round-trip form), so equal text is equal bits
    // but for the sign of zero, which the peaks' bits cover.
    let peaks: Vec<u64> = s
        .contact_peak_forces_n
        .iter()
        .map(|x| x.to_bits())
        .collect();
    format!("{s:?} {peaks:?}")
}

fn damping() -> Damping {
    Damping {
        contacts: ContactDamping::Restitution { coefficient: 0.9 },
        wall: Some(ContactDamping::HuntCrossley { restitution: 0.8 }),
        striker: Some(ContactDamping::Viscoelastic { time_s: 2e-7 }),
        resonator_ratio: 0.01,
        on_site_time_s: Some(2e-3),
        impact_speed_m_s: Some(0.5),
        ..Damping::default()
    }
}

fn lab_chains(damping: &Damping, preload: &Preload) -> Vec<Chain> {
    random_builders(11, 12, &[3, 8])
        .into_iter()
        .map(|b| {
            b.damping(damping.clone())
                .preload(*preload)
                .build()
                .unwrap()
        })
        .collect()
}

fn check(chains: &[Chain], excitation: &Excitation, settings: &RunSettings) {
    let alone = alone(chains, excitation, settings);
    let jobs = Job::for_each_chain(chains, excitation, settings);
    assert!(
        jobs.iter().all(|j| j.in_lanes().unwrap()),
        "every job runs in lanes"
    );
    assert_lanes_agree(&jobs, &alone, |t, a| bits(t) == bits(a));
}

fn dopri5() -> RunSettings {
    peaks_only(
        Method::Dopri5 {
            rtol: 1e-7,
            atol: 1e-13,
        },
        4e-4,
    )
}

#[test]
fn damped_impact_with_preload_and_gravity() {
    let preload = Preload {
        force_n: 5.0,
        gravity_m_s2: 9.81,
    };
    let chains = lab_chains(&damping(), &preload);
    check(&chains, &Excitation::Impact(Striker::paper()), &dopri5());
    // A stated peak tolerance resolves to event-aware DOPRI5 for lab physics.
    let settings = peaks_only(Method::for_peak_tolerance(1e-4).unwrap(), 4e-4);
    check(&chains, &Excitation::Impact(Striker::paper()), &settings);
}

#[test]
fn damped_blast() {
    let chains = lab_chains(&damping(), &Preload::default());
    check(
        &chains,
        &Excitation::Blast(BlastProfile::paper()),
        &dopri5(),
    );
}

#[test]
fn force_and_displacement_drives() {
    let preload = Preload {
        force_n: 2.0,
        gravity_m_s2: 0.0,
    };
    let chains = lab_chains(&damping(), &preload);
    let signal = Signal::Harmonic {
        amplitude: 1.0,
        frequency_hz: 4e3,
    };
    check(&chains, &Excitation::Drive(Drive::force(signal)), &dopri5());
    let displacement = Drive {
        quantity: DriveQuantity::Displacement {
            tip: Wall::paper_sensor(),
        },
        ..Drive::force(Signal::Harmonic {
            amplitude: 1e-7,
            frequency_hz: 4e3,
        })
    };
    let rk4 = peaks_only(Method::Rk4 { time_step_s: 2e-7 }, 2e-4);
    check(&chains, &Excitation::Drive(displacement), &rk4);
}

#[test]
fn mixed_laws_split_into_groups() {
    let mut chains = lab_chains(&damping(), &Preload::default());
    let elastic_wall = Damping {
        wall: None,
        ..damping()
    };
    chains.extend(lab_chains(&elastic_wall, &Preload::default()));
    check(&chains, &Excitation::Impact(Striker::paper()), &dopri5());
}
