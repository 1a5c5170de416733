//! Where does an adaptive run spend its steps? Integrates the benchmark chain (docs/physics.md §9
//! chain under the default impact, 2 ms) with event-aware DOPRI5 (`--plain`: without events;
//! `--rkn`: RKN 6(4), which lands on crossings too) at the rtol given as the first argument,
//! resonant cells (`--rigid`: rigid ones), and prints the
//! steps, the contact openings and closings, and the mean step grouped by how many steps ago a
//! contact last opened or closed. If the kinks where contacts open and close set the step size,
//! steps right after a crossing are shorter than the others.
//!
//! Run: `cargo run --release -p woodpile --example step_trace -- 3e-7 [--rigid] [--plain | --rkn]`

use woodpile::ode::ChainOde;
use woodpile::{
    CellModel, ChainBuilder, Excitation, Integrator, Method, OdeSystem, Striker,
    PAPER_OPTIMIZED_CHAIN_MM,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let rtol: f64 = match std::env::args().nth(1) {
        Some(s) if !s.starts_with("--") => s.parse()?,
        _ => 3e-7,
    };
    let flag = |name: &str| std::env::args().any(|a| a == name);
    let (events, cells) = (
        !flag("--plain"),
        if flag("--rigid") {
            CellModel::Rigid
        } else {
            CellModel::Resonant
        },
    );
    let chain = ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, cells)?.build()?;
    let mut ode = ChainOde::new(&chain, &Excitation::Impact(Striker::paper()))?;
    if let Some((element, mode, omega)) = ode.stiffest_resonator() {
        println!(
            "stiffest resonator: element {element}, mode {mode}, {:.1} kHz against its rod held fixed",
            omega / std::f64::consts::TAU / 1e3
        );
    }
    let atol = rtol * 1e-6;
    let method = if flag("--rkn") {
        Method::Rkn64 { rtol, atol }
    } else if events {
        Method::Dopri5Events { rtol, atol }
    } else {
        Method::Dopri5 { rtol, atol }
    };
    let duration_s = 2e-3;
    let (units, y0) = (ode.tolerance_units(), ode.initial_state());
    let mut integrator = Integrator::new(method, &mut ode, 0.0, y0, &units, duration_s);
    let m = ode.switch_count();
    let (mut before, mut after) = (vec![0.0; m], vec![0.0; m]);
    ode.switches(integrator.y(), &mut before);
    let mut crossings = 0;
    let mut since = usize::MAX;
    // Steps (count, summed size) by steps since the last crossing: 0, 1, …, 6, 7 or more.
    let mut groups = [(0usize, 0.0f64); 8];
    while integrator.t() < duration_s * (1.0 - 1e-14) {
        let h = integrator.step(&mut ode, duration_s)?;
        ode.switches(integrator.y(), &mut after);
        let n = before
            .iter()
            .zip(&after)
            .filter(|(a, b)| (**a > 0.0) != (**b > 0.0))
            .count();
        let group = &mut groups[since.min(7)];
        group.0 += 1;
        group.1 += h;
        crossings += n;
        since = if n > 0 { 0 } else { since.saturating_add(1) };
        std::mem::swap(&mut before, &mut after);
    }
    let stats = integrator.stats();
    println!(
        "rtol {rtol:e}, {cells:?} cells, {method:?}: {} steps ({} rejected), {} evaluations, {crossings} contact openings and closings",
        stats.steps, stats.rejected_steps, stats.rhs_evaluations
    );
    for (b, (count, sum)) in groups.iter().enumerate() {
        let label = if b == 7 {
            "7+".to_string()
        } else {
            b.to_string()
        };
        println!(
            "  {label:>2} steps after a crossing: {count:>5} steps, mean {:.3} µs",
            sum / (*count).max(1) as f64 * 1e6
        );
    }
    Ok(())
}
