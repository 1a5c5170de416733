//! Claim: a chain of any cells is a contact graph of one-point bodies (docs/physics.md §16, "A
//! column"). `LatticeOde::from_chain` holds each element in the free–free modes of its primary
//! and resonators (mass-normalised, the primary's row 1/√μ_k), the striker as one coordinate and
//! the wall as a support, and `simulate_lattice` runs it by the lattice's path. With RK4 at one
//! fixed step both forms are linear changes of coordinates of one system of equations (RK4
//! commutes with them), so they differ by rounding only: the secular roots of each cell's modes
//! (to a few ulp) and the sums in another order, carried through 5,000 steps of a nonlinear
//! system. Every sampled contact force agrees within 1e-12 of the largest peak and the total
//! energy within 1e-12 of the initial energy, for the paper's Table 1 cells and for a mixed
//! chain of a Table 1 rod, a steel sphere, a finite-element rod and a rigid rod. The graph's
//! momentum audit holds too: RK4 keeps linear invariants, so the bodies' momentum (each
//! element's rigid mode alone carries it) plus the wall's impulse stays the striker's m v₀
//! within 1e-12 (rounding).

use super::lattice_common::fe_rod_elements;
use super::lattice_single_column::{force_and_energy_differences, largest_peak, peak_difference};
use woodpile::ode::LatticeOde;
use woodpile::simulate::simulate_lattice;
use woodpile::{
    simulate, CellModel, Chain, ChainBuilder, Element, Excitation, Material, Method, RunSettings,
    Striker, Trajectory,
};

fn settings() -> RunSettings {
    RunSettings {
        duration_s: 2e-4,
        method: Method::Rk4 { time_step_s: 4e-8 },
        sample_interval_s: 1e-6,
    }
}

/// The largest force and energy differences between `chain` run as a chain and as a contact
/// graph under the paper's striker, and whether the wave reached the wall (its contact's peak
/// above 1 % of the largest); asserts the graph's momentum audit.
fn both_forms(chain: &Chain) -> (f64, f64, bool) {
    let striker = Striker::paper();
    let mut trajectory = Trajectory::default();
    simulate(
        chain,
        &Excitation::Impact(striker.clone()),
        &settings(),
        &mut trajectory,
    )
    .unwrap();
    let mut ode = LatticeOde::from_chain(chain, &Excitation::Impact(striker.clone())).unwrap();
    let run = simulate_lattice(&mut ode, &settings()).unwrap();
    assert_eq!(run.contacts, trajectory.n_contacts());
    let arrived = run.contact_peak_forces_n[run.contacts - 1] > 0.01 * largest_peak(&run);
    let (force, energy) = force_and_energy_differences(&run, &trajectory);
    let p0 = striker.mass_kg() * striker.velocity_m_s;
    let momentum = run
        .momentum
        .iter()
        .map(|&(p, _, j, _)| (p + j - p0).abs() / p0)
        .fold(0.0_f64, f64::max);
    eprintln!("momentum audit: {momentum:e} of m v0");
    assert!(momentum < 1e-12, "momentum off by {momentum:e} of m v0");
    (force, energy, arrived)
}

#[test]
fn table1_chain_as_a_contact_graph_is_the_chain() {
    let chain = ChainBuilder::table1_rods(&[80, 60, 40, 30, 20], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let (force, energy, arrived) = both_forms(&chain);
    eprintln!("Table 1 chain: forces {force:e} of the peak, energy {energy:e}");
    assert!(arrived, "the wave reached the wall");
    assert!(force < 1e-12, "forces differ by {force:e} of the peak");
    assert!(energy < 1e-12, "energies differ by {energy:e}");
}

#[test]
fn mixed_chain_as_a_contact_graph_is_the_chain() {
    let mut elements = vec![Element::table1_rod(80, CellModel::Resonant).unwrap()];
    elements.push(Element::sphere(9.525e-3, Material::preset("steel").unwrap()).unwrap());
    elements.extend(fe_rod_elements(&[40.0], 4));
    elements.push(Element::table1_rod(20, CellModel::Rigid).unwrap());
    let chain = ChainBuilder::new(elements).build().unwrap();
    let (force, energy, arrived) = both_forms(&chain);
    eprintln!("mixed chain: forces {force:e} of the peak, energy {energy:e}");
    assert!(arrived, "the wave reached the wall");
    assert!(force < 1e-12, "forces differ by {force:e} of the peak");
    assert!(energy < 1e-12, "energies differ by {energy:e}");
}

/// A chain the graph cannot hold is refused naming the key: a free end.
#[test]
fn a_chain_without_a_wall_is_refused_naming_the_key() {
    let chain = ChainBuilder::table1_rods(&[80, 40], CellModel::Resonant)
        .unwrap()
        .wall(woodpile::Wall::Free)
        .build()
        .unwrap();
    let error = LatticeOde::from_chain(&chain, &Excitation::Impact(Striker::paper())).unwrap_err();
    assert!(error.to_string().contains("wall"), "{error}");
}

/// Claim: under the exact modal method the contact graph's stepper (`integrate::modal_graph`)
/// gives the Table 1 chain's contact peaks as the chain's own (`integrate::modal_step`) does.
/// Each puts its peaks within about 1.3 rtol of the truth (docs/physics.md §8; claims
/// `exact_modes`, `lattice_exact_modes`), so at rtol 1e-9 the two agree within 1e-8 of the
/// largest (4 times the sum of both envelopes).
#[test]
fn table1_chain_as_a_contact_graph_under_the_exact_method_is_the_chain_under_it() {
    let chain = ChainBuilder::table1_rods(&[80, 60, 40, 30, 20], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let settings = RunSettings {
        method: Method::ExactModes {
            rtol: 1e-9,
            atol: 1e-18,
        },
        ..settings()
    };
    let striker = Striker::paper();
    let summary = simulate(
        &chain,
        &Excitation::Impact(striker.clone()),
        &settings,
        &mut Trajectory::default(),
    )
    .unwrap();
    let mut ode = LatticeOde::from_chain(&chain, &Excitation::Impact(striker.clone())).unwrap();
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    assert!(matches!(run.method, Method::ExactModes { .. }));
    let worst = peak_difference(&run, &summary);
    eprintln!("exact method: peaks differ by {worst:e} of the largest");
    assert!(worst < 1e-8, "peaks differ by {worst:e} of the largest");
}
