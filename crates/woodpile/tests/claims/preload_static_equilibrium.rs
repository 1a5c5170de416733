//! Claims on a column under a static load (docs/physics.md §14):
//!
//! 1. The run starts from the exact static equilibrium: contact i carries
//!    F_i = F_p + g Σ_{k ≤ i} M_k and its overlap is δ_i = (F_i/β_i)^{2/3}, to 1e-9 relative
//!    (both are computed here from the chain's masses and β, not read from the runner; the bound
//!    is rounding in sums of overlaps, ~1e-15, with room).
//! 2. Left unexcited, the preloaded column stays at rest: over 2 ms every displacement stays
//!    within 1e-12 of its static value, relative to the largest static displacement (the
//!    equilibrium is exact up to rounding, ~1e-16 of the forces, and stable).
//! 3. Under an impact, the reported totals and dynamic parts differ by exactly the static
//!    forces, and the transmission ratio is that of the dynamic parts.

use woodpile::{
    simulate, CellModel, ChainBuilder, Excitation, Preload, RunSettings, Striker, Trajectory,
};

fn chain() -> woodpile::Chain {
    ChainBuilder::table1_rods(&[80, 40, 20, 60, 30, 50], CellModel::Resonant)
        .unwrap()
        .preload(Preload {
            force_n: 10.0,
            gravity_m_s2: 9.81,
        })
        .build()
        .unwrap()
}

#[test]
fn static_overlaps_are_the_closed_form() {
    let chain = chain();
    let settings = RunSettings {
        duration_s: 2e-3,
        ..RunSettings::paper_blast()
    };
    let mut traj = Trajectory::default();
    simulate(&chain, &Excitation::Rest, &settings, &mut traj).unwrap();
    let n = chain.len();
    let mut betas = chain.inner_betas().to_vec();
    betas.push(chain.wall_beta().unwrap());
    let mut carried = 10.0;
    let u0 = &traj.displacements_m[..n];
    for i in 0..n {
        carried += 9.81 * chain.elements()[i].cell.total_mass_kg();
        let delta = (carried / betas[i]).powf(2.0 / 3.0);
        let overlap = if i + 1 < n { u0[i] - u0[i + 1] } else { u0[i] };
        assert!(
            (overlap / delta - 1.0).abs() < 1e-9,
            "contact {}: overlap {overlap} vs closed form {delta}",
            i + 1
        );
        let force = traj.contact_forces_n[i + 1];
        assert!(
            (force / carried - 1.0).abs() < 1e-9,
            "contact {}: force {force}",
            i + 1
        );
    }
    // Claim 2: at rest over the whole run.
    let scale = u0.iter().fold(0.0_f64, |m, &u| m.max(u.abs()));
    let drift = traj
        .displacements_m
        .chunks(n)
        .flat_map(|row| row.iter().zip(u0).map(|(u, s)| (u - s).abs()))
        .fold(0.0_f64, f64::max);
    assert!(drift / scale < 1e-12, "drift {drift} m of {scale} m");
}

#[test]
fn impact_on_a_preloaded_column_reports_dynamic_parts() {
    let chain = chain();
    let settings = RunSettings::paper_impact();
    let s = simulate(
        &chain,
        &Excitation::Impact(Striker::paper()),
        &settings,
        &mut (),
    )
    .unwrap();
    let n = chain.len();
    let statics = &s.static_contact_forces_n;
    assert_eq!(statics.len(), n + 1);
    assert_eq!(statics[0], 0.0, "the striker carries no static load");
    assert!((statics[n] - (10.0 + 9.81 * chain.total_mass_kg())).abs() < 1e-9);
    let incident = s.incident_peak_force_n - statics[1];
    let transmitted = s.transmitted_peak_force_n - statics[n];
    assert!(incident > 0.0 && transmitted > 0.0);
    let ratio = s.transmission_ratio.expect("the wave arrives");
    assert!((ratio - transmitted / incident).abs() < 1e-12 * ratio);
    assert!(
        s.energy.max_relative_error < 1e-6,
        "{}",
        s.energy.max_relative_error
    );
}
