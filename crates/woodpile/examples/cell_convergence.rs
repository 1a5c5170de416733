//! How reduced unit cells converge to the rod itself (docs/physics.md §13).
//!
//! 1. The finite-element rod's centre-blocked and free–free frequencies against the exact
//!    Timoshenko solution, for 4 to 32 elements per half rod.
//! 2. The paper's optimised 20-rod chain under the default impact (2 ms) with derived pole–zero
//!    cells of l = 1..4 resonators and with the paper's Table 1 cells, against the same chain of
//!    finite-element rods: the incident (contact 1) and transmitted (wall) peak forces and the
//!    largest relative difference over every contact's peak.
//!
//! Run: `cargo run --release -p woodpile --example cell_convergence`

use woodpile::{
    simulate, BeamTheory, CellModel, ChainBuilder, Element, Excitation, Material, Method,
    Reduction, Rod, RunSettings, RunSummary, Striker, UnitCell, PAPER_OPTIMIZED_CHAIN_MM,
};

/// The finite-element rod's elements per half rod used as the reference.
const FE_ELEMENTS: usize = 24;

fn rod(length_mm: u32) -> Rod {
    Rod::new(
        f64::from(length_mm) * 1e-3,
        5e-3,
        0.0,
        Material::fused_quartz(),
    )
    .expect("valid rod")
}

fn chain_with(cell: impl Fn(u32) -> woodpile::Result<UnitCell>) -> woodpile::Result<RunSummary> {
    let elements = PAPER_OPTIMIZED_CHAIN_MM
        .iter()
        .map(|&l| {
            let mut e = Element::table1_rod(l, CellModel::Resonant)?;
            e.cell = cell(l)?;
            Ok(e)
        })
        .collect::<woodpile::Result<Vec<_>>>()?;
    let chain = ChainBuilder::new(elements).build()?;
    // The finite-element rods have modes up to a few MHz: RK4 at 10 ns is stable and resolves
    // them; the same step for every cell keeps the comparison about the cells alone.
    let settings = RunSettings {
        method: Method::Rk4 { time_step_s: 1e-8 },
        ..RunSettings::paper_impact()
    };
    simulate(
        &chain,
        &Excitation::Impact(Striker::paper()),
        &settings,
        &mut (),
    )
}

fn main() -> woodpile::Result<()> {
    println!("1. finite-element rod against the exact Timoshenko frequencies [kHz]");
    for length in [20, 80] {
        let r = rod(length);
        let exact = r.centre_blocked_frequencies_hz(BeamTheory::Timoshenko, 3)?;
        println!("{length} mm, centre-blocked exact: {exact:.3?}");
        for n in [4, 8, 16, 32] {
            let fe: Vec<f64> = r
                .fe_centre_blocked_modes(n)?
                .iter()
                .take(3)
                .map(|m| m.0 / (2.0 * std::f64::consts::PI))
                .collect();
            let err: Vec<String> = fe
                .iter()
                .zip(&exact)
                .map(|(a, b)| format!("{:.1e}", a / b - 1.0))
                .collect();
            println!("  n = {n:>2}: {fe:.3?}  relative error {err:?}");
        }
        let fe_cell = UnitCell::from_rod_fe(&r, FE_ELEMENTS)?;
        let zeros = r.free_symmetric_frequencies_hz(BeamTheory::Timoshenko, 3)?;
        let fe_zeros: Vec<f64> = fe_cell.free_resonances_hz().into_iter().take(3).collect();
        println!("  free-free exact {zeros:.3?}, FE ({FE_ELEMENTS} elements) {fe_zeros:.3?}");
    }

    println!("\n2. paper optimised chain, impact: peak forces against FE rods ({FE_ELEMENTS} elements per half)");
    let reference = chain_with(|l| UnitCell::from_rod_fe(&rod(l), FE_ELEMENTS))?;
    let row = |name: &str, s: &RunSummary| {
        let worst = s
            .contact_peak_forces_n
            .iter()
            .zip(&reference.contact_peak_forces_n)
            .map(|(a, b)| (a / b - 1.0).abs())
            .fold(0.0, f64::max);
        println!(
            "| {name} | {:.2} | {:+.1} % | {:.2} | {:+.1} % | {:.1} % |",
            s.incident_peak_force_n,
            100.0 * (s.incident_peak_force_n / reference.incident_peak_force_n - 1.0),
            s.transmitted_peak_force_n,
            100.0 * (s.transmitted_peak_force_n / reference.transmitted_peak_force_n - 1.0),
            100.0 * worst
        );
    };
    println!(
        "| cells | incident [N] | vs FE | transmitted [N] | vs FE | worst contact peak vs FE |"
    );
    println!("| --- | --- | --- | --- | --- | --- |");
    row(&format!("FE rods, {FE_ELEMENTS} elements"), &reference);
    for l in 1..=4 {
        // The 20 mm rod has only three modes below its shear cutoff.
        let s = chain_with(|len| {
            let r = rod(len);
            UnitCell::from_rod(&r, Some(l.min(r.max_modes())), Reduction::PoleZero)
        })?;
        let note = if l == 4 { " (3 for 20 mm)" } else { "" };
        row(&format!("pole-zero, l = {l}{note}"), &s);
    }
    let s = chain_with(|len| UnitCell::from_rod(&rod(len), None, Reduction::PoleZero))?;
    row("pole-zero, default l", &s);
    for l in [1, 2, 3] {
        let s = chain_with(|len| UnitCell::from_rod(&rod(len), Some(l), Reduction::ModalMass))?;
        row(&format!("modal-mass, l = {l}"), &s);
    }
    let s = chain_with(UnitCell::table1)?;
    row("Table 1 (paper)", &s);
    Ok(())
}
