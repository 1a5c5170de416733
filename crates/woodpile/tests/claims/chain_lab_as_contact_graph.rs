//! Claim: a chain's lab physics (docs/physics.md §14) runs on the contact graph with the chain's
//! numbers (docs/physics.md §16, "A column"). `LatticeOde::from_chain` turns the chain's contact
//! laws, on-site damping, resonator dashpots (a damping matrix over each cell's modes), gravity,
//! preload, blast and drives into the graph's lab terms, and the graph finds the static
//! equilibrium by its own solve. With RK4 at one fixed step both forms are linear changes of
//! coordinates of one system (RK4 commutes with them), so they differ by rounding and by the
//! static solve's residual (≤ 1e-12 of the static forces; Newton's last step leaves rounding):
//! every sampled contact force within 1e-11 of the largest peak, and the sampled total energy,
//! the work of the loads and the energy dissipated within 1e-11 of the largest of them, under a
//! striker, a blast, a force drive and a displacement drive. The bound is ten times the lossless
//! claim's (`chain_as_contact_graph`), for the static solve and the dissipative terms' sums in
//! another order. Under the exact method (elastic contacts; damping of each mode on its own, a
//! static load) both steppers meet rtol 1e-9, so their peaks agree within 1e-8 of the largest;
//! resonator dashpots couple a cell's modes, which the graph's exact stepper refuses, naming
//! `run.integrator`. And the graph's static solve finds the chain's static contact forces (summed
//! in closed form from the top down) within 1e-11 of the largest. Drawn chains (one to six
//! elements of any kind, any contact law and damping, gravity and a preload, struck, blasted or
//! driven) agree within 1e-10 (the static solve's tolerance under a preload sets it); they found
//! two faults, both mended: the static solve did
//! not start on a chain of rigid cells (nothing stiff: its regularisation had no scale), and
//! rounding could leave the striker pressed in by an ulp at t = 0, where a damped law pushes at
//! once.

use super::lab_energy_balance::every_damping;
use super::lattice_common::fe_rod_elements;
use super::lattice_single_column::{largest_peak, peak_difference};
use proptest::prelude::*;
use woodpile::ode::LatticeOde;
use woodpile::simulate::{simulate_lattice, LatticeRun};
use woodpile::{
    simulate, BlastProfile, CellModel, Chain, ChainBuilder, ContactDamping, Damping, Drive,
    DriveQuantity, Element, Excitation, Material, Method, Preload, RunSettings, RunSummary, Signal,
    Striker, Sweep, Trajectory, Wall, TABLE1_LENGTHS_MM,
};

/// RK4 at 40 ns over 0.3 ms, sampled every µs.
fn rk4() -> RunSettings {
    RunSettings {
        duration_s: 3e-4,
        method: Method::Rk4 { time_step_s: 4e-8 },
        sample_interval_s: 1e-6,
    }
}

fn preload() -> Preload {
    Preload {
        force_n: 5.0,
        gravity_m_s2: 9.81,
    }
}

/// Four Table 1 rods with resonators, every lab term and a preload.
fn table1_chain() -> Chain {
    ChainBuilder::table1_rods(&[80, 40, 20, 60], CellModel::Resonant)
        .unwrap()
        .preload(preload())
        .damping(every_damping())
        .build()
        .unwrap()
}

/// A Table 1 rod, a steel sphere, a finite-element rod and a rigid rod, with every lab term.
fn mixed_chain() -> Chain {
    let mut elements = vec![Element::table1_rod(80, CellModel::Resonant).unwrap()];
    elements.push(Element::sphere(9.525e-3, Material::preset("steel").unwrap()).unwrap());
    elements.extend(fe_rod_elements(&[40.0], 4));
    elements.push(Element::table1_rod(20, CellModel::Rigid).unwrap());
    ChainBuilder::new(elements)
        .preload(preload())
        .damping(every_damping())
        .build()
        .unwrap()
}

/// `chain` under `excitation` as a chain and as a contact graph.
fn both_forms(
    chain: &Chain,
    excitation: &Excitation,
    settings: &RunSettings,
) -> (RunSummary, Trajectory, LatticeRun) {
    let mut trajectory = Trajectory::default();
    let summary = simulate(chain, excitation, settings, &mut trajectory).unwrap();
    let mut ode = LatticeOde::from_chain(chain, excitation).unwrap();
    let run = simulate_lattice(&mut ode, settings).unwrap();
    assert_eq!(run.contacts, trajectory.n_contacts());
    (summary, trajectory, run)
}

/// The largest difference of any sampled contact force (of the largest peak), and of the
/// sampled total energy, work and dissipation (of the largest of any of them).
fn differences(run: &LatticeRun, trajectory: &Trajectory) -> (f64, f64) {
    let peak = largest_peak(run);
    let mut force = 0.0_f64;
    for c in 0..run.contacts {
        for (a, b) in run
            .contact_force_n(c)
            .iter()
            .zip(&trajectory.contact_force_n(c))
        {
            force = force.max((a - b).abs() / peak);
        }
    }
    let energy = trajectory.total_energy_j();
    let pairs = [
        (&run.energy_j, &energy),
        (&run.work_j, &trajectory.input_work_j),
        (&run.dissipated_j, &trajectory.dissipated_j),
    ];
    let scale = pairs
        .iter()
        .flat_map(|(a, b)| a.iter().chain(b.iter()))
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let mut worst = 0.0_f64;
    for (a, b) in pairs {
        assert_eq!(a.len(), b.len(), "sample counts");
        for (x, y) in a.iter().zip(b) {
            worst = worst.max((x - y).abs() / scale);
        }
    }
    (force, worst)
}

/// Runs both forms under RK4 and asserts the claim's bounds; returns the run for further
/// checks.
fn agree(label: &str, chain: &Chain, excitation: &Excitation) -> (Trajectory, LatticeRun) {
    let (_, trajectory, run) = both_forms(chain, excitation, &rk4());
    let (force, energy) = differences(&run, &trajectory);
    let dissipated = *run.dissipated_j.last().unwrap();
    eprintln!(
        "{label}: forces {force:e} of the peak, energies {energy:e}; dissipated {dissipated:e} J"
    );
    assert!(
        force < 1e-11,
        "{label}: forces differ by {force:e} of the peak"
    );
    assert!(energy < 1e-11, "{label}: energies differ by {energy:e}");
    // The comparison means something only if the lab terms act.
    assert!(dissipated > 0.0, "{label}: nothing was dissipated");
    (trajectory, run)
}

#[test]
fn struck_chain_with_every_lab_term_is_the_chain() {
    let (_, run) = agree(
        "Table 1, striker",
        &table1_chain(),
        &Excitation::Impact(Striker::paper()),
    );
    assert!(
        run.static_residual <= 1e-12,
        "static residual {:e}",
        run.static_residual
    );
    agree(
        "mixed, striker",
        &mixed_chain(),
        &Excitation::Impact(Striker::paper()),
    );
}

/// The graph's static solve (damped Newton on the potential, `ode::lattice_static`) finds the
/// chain's static contact forces, which the chain sums from the top down in closed form: under
/// gravity and a 5 N preload, struck and at rest, every contact within 1e-11 of the largest:
/// ten times the residual, 1e-12 of the static forces, at which the solve may stop (it stops
/// lower: 1.9e-13 here).
#[test]
fn the_graphs_static_solve_finds_the_chains_static_forces() {
    let chain = table1_chain();
    for excitation in [Excitation::Impact(Striker::paper()), Excitation::Rest] {
        let ode = LatticeOde::from_chain(&chain, &excitation).unwrap();
        let (graph, residual) = ode.static_forces_n();
        let expected = woodpile::ode::ChainOde::new(&chain, &excitation)
            .unwrap()
            .static_contact_forces_n();
        let largest = expected.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
        let worst = graph
            .iter()
            .zip(&expected)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs() / largest));
        eprintln!(
            "static forces: {worst:e} of the largest ({largest:.4} N), residual {residual:e}"
        );
        assert_eq!(graph.len(), expected.len());
        assert!(
            largest > 5.0,
            "the preload and the rods' weight load every contact"
        );
        assert!(
            worst < 1e-11,
            "static forces differ by {worst:e} of the largest"
        );
    }
}

#[test]
fn blasted_chain_is_the_chain() {
    agree(
        "mixed, blast",
        &mixed_chain(),
        &Excitation::Blast(BlastProfile::paper()),
    );
}

#[test]
fn driven_chain_is_the_chain() {
    let chirp = |amplitude: f64| Signal::Chirp {
        amplitude,
        start_hz: 2e3,
        end_hz: 40e3,
        duration_s: 3e-4,
        sweep: Sweep::Logarithmic,
    };
    agree(
        "Table 1, force drive",
        &table1_chain(),
        &Excitation::Drive(Drive::force(chirp(2.0))),
    );
    let displacement = Drive {
        quantity: DriveQuantity::Displacement {
            tip: Wall::paper_sensor(),
        },
        ..Drive::force(chirp(2e-7))
    };
    agree(
        "Table 1, displacement drive",
        &table1_chain(),
        &Excitation::Drive(displacement),
    );
}

#[test]
fn exact_method_on_a_damped_loaded_chain_is_the_chains() {
    // Elastic contacts, on-site damping, gravity and a preload: what both exact steppers take.
    let chain = ChainBuilder::table1_rods(&[80, 60, 40, 30, 20], CellModel::Resonant)
        .unwrap()
        .preload(preload())
        .damping(Damping {
            on_site_time_s: Some(2e-4),
            ..Damping::default()
        })
        .build()
        .unwrap();
    let settings = RunSettings {
        duration_s: 3e-4,
        method: Method::ExactModes {
            rtol: 1e-9,
            atol: 1e-18,
        },
        sample_interval_s: 1e-6,
    };
    for excitation in [
        Excitation::Impact(Striker::paper()),
        Excitation::Blast(BlastProfile::paper()),
    ] {
        let (summary, _, run) = both_forms(&chain, &excitation, &settings);
        assert!(matches!(run.method, Method::ExactModes { .. }));
        let peaks = peak_difference(&run, &summary);
        eprintln!("exact method: peaks differ by {peaks:e} of the largest");
        assert!(peaks < 1e-8, "peaks differ by {peaks:e} of the largest");
    }
}

#[test]
fn resonator_dashpots_are_refused_by_the_graphs_exact_stepper() {
    // Elastic contacts: the dashpots alone stand in the way.
    let chain = ChainBuilder::table1_rods(&[80, 40, 20, 60], CellModel::Resonant)
        .unwrap()
        .damping(Damping {
            resonator_ratio: 0.02,
            ..Damping::default()
        })
        .build()
        .unwrap();
    let mut ode = LatticeOde::from_chain(&chain, &Excitation::Impact(Striker::paper())).unwrap();
    let settings = RunSettings {
        method: Method::ExactModes {
            rtol: 1e-8,
            atol: 1e-18,
        },
        ..rk4()
    };
    let error = simulate_lattice(&mut ode, &settings).unwrap_err();
    assert!(error.to_string().contains("run.integrator"), "{error}");
}

/// The damping of a drawn chain: `law` picks the contacts' law (0 none, 1 restitution 0.8, 2
/// Hunt–Crossley 0.9, 3 viscoelastic 0.1 µs), with resonator dashpots of ratio `zeta` and
/// on-site damping if `on_site`.
fn drawn_damping(law: usize, zeta: f64, on_site: bool) -> Damping {
    let contacts = match law {
        0 => ContactDamping::None,
        1 => ContactDamping::Restitution { coefficient: 0.8 },
        2 => ContactDamping::HuntCrossley { restitution: 0.9 },
        _ => ContactDamping::Viscoelastic { time_s: 1e-7 },
    };
    Damping {
        contacts,
        resonator_ratio: zeta,
        on_site_time_s: on_site.then_some(5e-4),
        impact_speed_m_s: Some(0.5),
        ..Damping::default()
    }
}

/// A drawn element: `kind` 0 a Table 1 rod with resonators, 1 a rigid Table 1 rod, 2 a steel
/// sphere, 3 a finite-element rod (4 elements per half rod) of the drawn length.
fn drawn_element(length: usize, kind: usize) -> Element {
    let length_mm = TABLE1_LENGTHS_MM[length];
    match kind {
        0 => Element::table1_rod(length_mm, CellModel::Resonant).unwrap(),
        1 => Element::table1_rod(length_mm, CellModel::Rigid).unwrap(),
        2 => Element::sphere(9.525e-3, Material::preset("steel").unwrap()).unwrap(),
        _ => fe_rod_elements(&[f64::from(length_mm)], 4).remove(0),
    }
}

/// A chain of drawn elements ((length, kind) as [`drawn_element`]) with `damping`, a preload of
/// `preload_n` and gravity if `gravity`.
fn drawn_chain(
    elements: &[(usize, usize)],
    damping: Damping,
    preload_n: f64,
    gravity: bool,
) -> Chain {
    let elements = elements
        .iter()
        .map(|&(l, kind)| drawn_element(l, kind))
        .collect();
    ChainBuilder::new(elements)
        .damping(damping)
        .preload(Preload {
            force_n: preload_n,
            gravity_m_s2: if gravity { 9.81 } else { 0.0 },
        })
        .build()
        .unwrap()
}

/// A drawn excitation: `kind` 0 the striker at `speed_m_s`, 1 the paper's blast, 2 a 2 N
/// harmonic force drive at 5 kHz.
fn drawn_excitation(kind: usize, speed_m_s: f64) -> Excitation {
    match kind {
        0 => Excitation::Impact(Striker {
            velocity_m_s: speed_m_s,
            ..Striker::paper()
        }),
        1 => Excitation::Blast(BlastProfile::paper()),
        _ => Excitation::Drive(Drive::force(Signal::Harmonic {
            amplitude: 2.0,
            frequency_hz: 5e3,
        })),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, failure_persistence: None, ..ProptestConfig::default() })]
    /// Drawn chains — one to six elements, each a Table 1 rod with or without resonators, a
    /// sphere or a finite-element rod, any contact law, resonator dashpots, on-site damping,
    /// gravity and a preload — struck at a drawn speed, blasted or driven: the graph gives the
    /// chain's numbers (RK4 at 40 ns, 0.1 ms) within 1e-10, ten times the fixed cases' bound.
    /// The static solve stops at |∇Π| ≤ 1e-12 |f|, and under a preload the static state's
    /// energy sets the scale: on drawn chains of finite-element rods its difference from the
    /// chain's reaches 6e-12 at t = 0 and 1.1e-11 over the run; over 4 000 draws the forces
    /// reached 7.9e-12 of the peak.
    #[test]
    fn drawn_chains_with_lab_physics_are_the_chain(
        elements in prop::collection::vec((0usize..7, 0usize..4), 1..7),
        law in 0usize..4,
        zeta in 0.0f64..0.1,
        on_site in any::<bool>(),
        preload_n in 0.0f64..10.0,
        gravity in any::<bool>(),
        speed_m_s in 0.2f64..3.0,
        load in 0usize..3,
    ) {
        let chain = drawn_chain(&elements, drawn_damping(law, zeta, on_site), preload_n, gravity);
        let excitation = drawn_excitation(load, speed_m_s);
        let settings = RunSettings { duration_s: 1e-4, ..rk4() };
        let (_, trajectory, run) = both_forms(&chain, &excitation, &settings);
        let (force, energy) = differences(&run, &trajectory);
        prop_assert!(force < 1e-10, "forces differ by {:e} of the peak", force);
        prop_assert!(energy < 1e-10, "energies differ by {:e}", energy);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, failure_persistence: None, ..ProptestConfig::default() })]
    /// Drawn chains the exact method takes on both forms — elastic contacts, on-site damping,
    /// gravity and a preload — struck, blasted or driven, at rtol 1e-9: every contact peak
    /// agrees within 1e-6 of the largest, the lattices' rule (a peak tolerance of 1000 × rtol).
    /// rtol bounds each step's error, not the peaks', and the two error norms differ (the
    /// graph's the largest over the points, the chain's their mean): on a drawn chain of
    /// spheres and finite-element rods under a preload the chain's peaks lay 4.6e-8 of the
    /// largest from DOPRI5 at rtol 1e-12, the graph's 1.5e-9; over 3 000 draws the two forms
    /// differed by at most 6.5e-8.
    #[test]
    fn drawn_chains_under_the_exact_method_are_the_chains(
        elements in prop::collection::vec((0usize..7, 0usize..4), 1..7),
        on_site in any::<bool>(),
        preload_n in 0.0f64..10.0,
        gravity in any::<bool>(),
        speed_m_s in 0.2f64..3.0,
        load in 0usize..3,
    ) {
        let chain = drawn_chain(&elements, drawn_damping(0, 0.0, on_site), preload_n, gravity);
        let excitation = drawn_excitation(load, speed_m_s);
        let settings = RunSettings {
            duration_s: 2e-4,
            method: Method::ExactModes { rtol: 1e-9, atol: 1e-18 },
            sample_interval_s: 1e-6,
        };
        let (summary, _, run) = both_forms(&chain, &excitation, &settings);
        let peaks = peak_difference(&run, &summary);
        prop_assert!(peaks < 1e-6, "peaks differ by {:e} of the largest", peaks);
    }
}
