//! Claim: a lattice of one rod per layer is the finite-element-rod chain of the same rods
//! (docs/physics.md §16). Three quartz rods (80, 40, 20 mm, 4 elements per half rod) crossed at
//! 90° on the paper's sensor under the paper's striker, both run with RK4 at the same fixed step:
//! the chain holds each rod as its centre node plus one resonator per centre-blocked mode
//! (`UnitCell::from_rod_fe`), the lattice as the whole free–free beam in modal coordinates. The
//! two are linear changes of coordinates of the same finite-element model (the lattice's
//! antisymmetric modes are not loaded by centred contacts), and RK4 commutes with linear changes
//! of coordinates, so they differ only by rounding: the two eigen-decompositions (~1e-14 each)
//! and the sums in a different order, carried through 5,000 steps of a nonlinear system. Every
//! sampled contact force agrees within 1e-12 of the largest force, and every sampled energy —
//! the total, each body's (the striker's and each rod's: kinetic, strain and half of each of its
//! contacts' potential, the chain's layer energy), the support's half, and each contact's Hertz
//! potential against (2/5) β δ₊^{5/2} of the chain's overlaps (its primaries' and striker's
//! displacements) — within 1e-12 of the initial energy. The same column under the exact modal
//! method, through each engine's own stepper, agrees within the method's tolerance.

use super::lattice_common::fe_rod_elements;
use woodpile::model::LatticeBuilder;
use woodpile::ode::LatticeOde;
use woodpile::simulate::{simulate_lattice, LatticeRun};
use woodpile::{
    simulate, ChainBuilder, Excitation, Method, RunSettings, RunSummary, Striker, Trajectory,
};

const LENGTHS_MM: [f64; 3] = [80.0, 40.0, 20.0];
const ELEMENTS: usize = 4;

fn settings() -> RunSettings {
    RunSettings {
        duration_s: 2e-4,
        method: Method::Rk4 { time_step_s: 4e-8 },
        sample_interval_s: 1e-6,
    }
}

#[test]
fn one_rod_per_layer_is_the_fe_rod_chain() {
    let (_, trajectory, run, ode) = both_forms(&settings());
    assert_eq!(run.contacts, trajectory.n_contacts());
    assert_eq!(run.times_s.len(), trajectory.len());
    let peak = largest_peak(&run);
    assert!(
        run.contact_peak_forces_n[3] > 0.01 * peak,
        "the wave reached the wall"
    );
    let (worst_force, worst_energy) = force_and_energy_differences(&run, &trajectory);
    let e0 = run.energy_j[0];
    let mut worst_body = 0.0_f64;
    for layer in 0..run.bodies {
        let chain_layer = trajectory.layer_energy_j(layer);
        for (k, b) in chain_layer.iter().enumerate() {
            let a = run.body_energies_j[k * run.bodies + layer];
            worst_body = worst_body.max((a - b).abs() / e0);
        }
    }
    for (a, b) in run.support_energy_j.iter().zip(&trajectory.wall_energy_j) {
        worst_body = worst_body.max((a - b).abs() / e0);
    }
    // Each contact's Hertz potential against the chain's overlaps: the striker's x_s − u_1,
    // u_i − u_{i+1} between rods, u_N at the sensor.
    let n = trajectory.n_elements;
    let u = |k: usize, i: usize| trajectory.displacements_m[k * n + i];
    let mut worst_contact = 0.0_f64;
    for k in 0..run.times_s.len() {
        for c in 0..run.contacts {
            let overlap = match c {
                0 => trajectory.striker_position_m[k] - u(k, 0),
                c if c == n => u(k, n - 1),
                c => u(k, c - 1) - u(k, c),
            };
            let hertz = 0.4 * ode.contact_betas()[c] * overlap.max(0.0).powf(2.5);
            let value = run.contact_energies_j[k * run.contacts + c];
            worst_contact = worst_contact.max((value - hertz).abs() / e0);
        }
    }
    eprintln!(
        "largest force difference {worst_force:e} of the peak, energy {worst_energy:e}, per body {worst_body:e}, per contact {worst_contact:e}"
    );
    assert!(
        worst_contact < 1e-12,
        "contact energies differ by {worst_contact:e}"
    );
    assert!(worst_body < 1e-12, "body energies differ by {worst_body:e}");
    assert!(
        worst_force < 1e-12,
        "forces differ by {worst_force:e} of the peak"
    );
    assert!(worst_energy < 1e-12, "energies differ by {worst_energy:e}");
}

/// Claim: under the exact modal method the same column gives the chain's forces through the
/// contact graph's stepper (`integrate::modal_graph`, which carries only the modes some contact
/// moves — a centred column's symmetric ones — and computes each rod's centre once for the
/// contacts above and below it) as through the chain's (`integrate::modal_step`). Each puts its
/// contact peaks within about 1.3 rtol of the truth (docs/physics.md §8; claims `exact_modes`,
/// `lattice_exact_modes`), so at rtol = 1e-9 the two runs' peaks agree within 1e-8 of the
/// largest (4 times the sum of both envelopes). A sample on a steep flank carries the step's
/// error in time as well: every sampled force and energy within 1e-7 (a hundred times rtol).
#[test]
fn one_rod_per_layer_under_the_exact_method_is_the_chain_under_it() {
    let settings = RunSettings {
        duration_s: 2e-4,
        method: Method::ExactModes {
            rtol: 1e-9,
            atol: 1e-18,
        },
        sample_interval_s: 1e-6,
    };
    let (summary, trajectory, run, _) = both_forms(&settings);
    assert!(matches!(run.method, Method::ExactModes { .. }));
    let (worst_force, worst_energy) = force_and_energy_differences(&run, &trajectory);
    let worst_peak = peak_difference(&run, &summary);
    eprintln!("exact method: largest force difference {worst_force:e} of the peak, peaks {worst_peak:e}, energy {worst_energy:e}");
    assert!(
        worst_peak < 1e-8,
        "peaks differ by {worst_peak:e} of the largest"
    );
    assert!(
        worst_force < 1e-7,
        "forces differ by {worst_force:e} of the peak"
    );
    assert!(worst_energy < 1e-7, "energies differ by {worst_energy:e}");
}

/// The column run as a chain and as a lattice of one rod per layer under `settings`: the chain's
/// summary and trajectory, the lattice's run and equations.
fn both_forms(settings: &RunSettings) -> (RunSummary, Trajectory, LatticeRun, LatticeOde) {
    let chain = ChainBuilder::new(fe_rod_elements(&LENGTHS_MM, ELEMENTS))
        .build()
        .unwrap();
    let mut trajectory = Trajectory::default();
    let striker = Striker::paper();
    let excitation = Excitation::Impact(striker.clone());
    let summary = simulate(&chain, &excitation, settings, &mut trajectory).unwrap();
    let layers = LENGTHS_MM
        .iter()
        .map(|&l| super::lattice_common::quartz_layer(1, l * 1e-3))
        .collect();
    let lattice = LatticeBuilder::new(layers, ELEMENTS).build().unwrap();
    let mut ode = LatticeOde::new(&lattice, &striker, [0.0, 0.0]).unwrap();
    let run = simulate_lattice(&mut ode, settings).unwrap();
    (summary, trajectory, run, ode)
}

pub(super) fn largest_peak(run: &LatticeRun) -> f64 {
    run.contact_peak_forces_n
        .iter()
        .fold(0.0_f64, |a, &b| a.max(b))
}

/// The largest difference of any contact peak between the two forms, of the largest peak.
pub(super) fn peak_difference(run: &LatticeRun, summary: &RunSummary) -> f64 {
    let peak = largest_peak(run);
    run.contact_peak_forces_n
        .iter()
        .zip(&summary.contact_peak_forces_n)
        .map(|(a, b)| (a - b).abs() / peak)
        .fold(0.0_f64, f64::max)
}

/// The largest difference of any sampled contact force (of the largest peak) and of the total
/// energy (of the initial energy) between the two forms.
pub(super) fn force_and_energy_differences(
    run: &LatticeRun,
    trajectory: &Trajectory,
) -> (f64, f64) {
    let peak = largest_peak(run);
    let mut worst_force = 0.0_f64;
    for c in 0..run.contacts {
        let (a, b) = (run.contact_force_n(c), trajectory.contact_force_n(c));
        for (x, y) in a.iter().zip(&b) {
            worst_force = worst_force.max((x - y).abs() / peak);
        }
    }
    let e0 = run.energy_j[0];
    let worst_energy = run
        .energy_j
        .iter()
        .zip(&trajectory.total_energy_j())
        .map(|(a, b)| (a - b).abs() / e0)
        .fold(0.0_f64, f64::max);
    (worst_force, worst_energy)
}
