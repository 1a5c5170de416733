//! Claim: contacts never pull — no contact force is negative at any sample or step of any run
//! (docs/physics.md §4: F = β [δ]_+^{3/2}), for impacts and blasts, resonant and rigid chains, spheres,
//! free ends and walls, over randomly drawn chains.
//!
//! Tolerance: none: the force law clips overlaps at zero, so any negative value is a bug.

use proptest::prelude::*;
use woodpile::{
    simulate, BlastProfile, CellModel, ChainBuilder, Element, Excitation, Material, RunSettings,
    Striker, Trajectory, Wall, TABLE1_LENGTHS_MM,
};

fn check(chain: &woodpile::Chain, excitation: &Excitation, duration_s: f64) {
    let settings = RunSettings {
        duration_s,
        ..RunSettings::paper_for(excitation)
    };
    let mut traj = Trajectory::default();
    let s = simulate(chain, excitation, &settings, &mut traj).unwrap();
    let skip_load = matches!(excitation, Excitation::Blast(_));
    for (k, row) in traj.contact_forces_n.chunks(traj.n_contacts()).enumerate() {
        for (c, &f) in row.iter().enumerate() {
            if !(skip_load && c == 0) {
                assert!(f >= 0.0, "contact {c} at sample {k}: {f} N");
            }
        }
    }
    assert!(s.contact_peak_forces_n.iter().all(|&f| f >= 0.0));
}

#[test]
fn fixed_cases_never_pull() {
    for model in [CellModel::Resonant, CellModel::Rigid] {
        let chain = ChainBuilder::table1_rods(&woodpile::PAPER_OPTIMIZED_CHAIN_MM, model)
            .unwrap()
            .build()
            .unwrap();
        check(&chain, &Excitation::Impact(Striker::paper()), 1e-3);
        check(&chain, &Excitation::Blast(BlastProfile::paper()), 1e-3);
    }
    let steel = Material::preset("steel").unwrap();
    let spheres = (0..6)
        .map(|_| Element::sphere(8e-3, steel.clone()).unwrap())
        .collect();
    let chain = ChainBuilder::new(spheres)
        .wall(Wall::Flat { material: steel })
        .build()
        .unwrap();
    check(&chain, &Excitation::Impact(Striker::paper()), 5e-4);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, failure_persistence: None, ..ProptestConfig::default() })]
    #[test]
    fn random_chains_never_pull(
        rods in prop::collection::vec(0usize..7, 1..8),
        rigid in any::<bool>(),
        free_end in any::<bool>(),
        height in 0.01f64..1.0,
    ) {
        let lengths: Vec<u32> = rods.iter().map(|&i| TABLE1_LENGTHS_MM[i]).collect();
        let model = if rigid { CellModel::Rigid } else { CellModel::Resonant };
        let mut builder = ChainBuilder::table1_rods(&lengths, model).unwrap();
        if free_end {
            builder = builder.wall(Wall::Free);
        }
        let chain = builder.build().unwrap();
        let striker = Striker { velocity_m_s: woodpile::velocity_from_drop_height(height), ..Striker::paper() };
        check(&chain, &Excitation::Impact(striker), 3e-4);
    }
}
