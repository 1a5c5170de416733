//! Claim: in the layer-by-layer protocol (paper §2, Fig. 7) the sub-chain of all N elements is
//! the full chain, so its wall-force history and peak equal those of a direct run of the chain;
//! the k runs come back in order of k whatever the thread scheduling.
//!
//! Tolerance: the same deterministic RK4 run on the same chain: the histories agree to round-off
//! (1e-12 relative to the peak; in practice bit for bit).

use woodpile::analysis::{layer_by_layer, sub_chain};
use woodpile::{
    simulate, BlastProfile, CellModel, ChainBuilder, Excitation, RunSettings, Striker, Trajectory,
    Wall,
};

fn check(lengths: &[u32], excitation: Excitation) {
    let chain = ChainBuilder::table1_rods(lengths, CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let settings = RunSettings {
        duration_s: 5e-4,
        ..RunSettings::paper_for(&excitation)
    };
    let n = chain.len();
    let mut t = Trajectory::default();
    let full = simulate(&chain, &excitation, &settings, &mut t).unwrap();
    let p = layer_by_layer(&chain, &excitation, &settings).unwrap();
    assert_eq!(p.wall_force_map.n_rows(), n);
    assert_eq!(p.wall_force_map.cols.values, t.times_s);
    let wall = t.contact_force_n(n);
    let peak = full.transmitted_peak_force_n;
    for (a, b) in p.wall_force_map.row(n - 1).iter().zip(&wall) {
        assert!((a - b).abs() <= 1e-12 * peak, "{a} vs {b}");
    }
    assert!((p.peak_wall_force_n[n - 1] - peak).abs() <= 1e-12 * peak);
    for (k, s) in p.summaries.iter().enumerate() {
        assert_eq!(
            s.contact_peak_forces_n.len(),
            k + 2,
            "row {k} is sub-chain k + 1"
        );
        assert!(p.peak_wall_force_n[k] > 0.0);
    }
}

#[test]
fn full_sub_chain_equals_the_chain_under_impact() {
    check(&[80, 70, 50, 30, 20], Excitation::Impact(Striker::paper()));
}

#[test]
fn full_sub_chain_equals_the_chain_under_blast() {
    check(&[40, 40, 60], Excitation::Blast(BlastProfile::paper()));
}

#[test]
fn sub_chains_keep_contact_overrides_and_need_a_wall() {
    let chain = ChainBuilder::table1_rods(&[20, 30, 40], CellModel::Rigid)
        .unwrap()
        .contact_beta(1, 1e9)
        .contact_beta(3, 5e9)
        .build()
        .unwrap();
    let two = sub_chain(&chain, 2).unwrap();
    assert_eq!(two.inner_betas(), &[1e9]);
    assert_eq!(two.wall_beta(), Some(5e9), "the sensor keeps its given β");
    assert!(sub_chain(&chain, 0).is_err() && sub_chain(&chain, 4).is_err());
    let free = ChainBuilder::table1_rods(&[20], CellModel::Rigid)
        .unwrap()
        .wall(Wall::Free)
        .build()
        .unwrap();
    assert!(sub_chain(&free, 1).is_err());
}
