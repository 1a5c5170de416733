//! What the lane claims share: random chains of Table 1 rods, their runs one by one, and the
//! check that runs advanced together in lanes agree with them. Not a claim.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use woodpile::{
    simulate, simulate_many, CellModel, Chain, ChainBuilder, Excitation, Job, LaneWidth,
    RunSettings, RunSummary, TABLE1_LENGTHS_MM,
};

/// `count` chains of random Table 1 rods (seeded), chain i of `lengths[i % lengths.len()]` rods,
/// every fifth rigid, the others resonant (1 or 2 resonators per cell: lanes carry padding).
pub fn random_chains(seed: u64, count: usize, lengths: &[usize]) -> Vec<Chain> {
    random_builders(seed, count, lengths)
        .into_iter()
        .map(|b| b.build().unwrap())
        .collect()
}

/// The builders of [`random_chains`], for chains with more physics.
pub fn random_builders(seed: u64, count: usize, lengths: &[usize]) -> Vec<ChainBuilder> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|i| {
            let n = lengths[i % lengths.len()];
            let rods: Vec<u32> = (0..n)
                .map(|_| TABLE1_LENGTHS_MM[rng.random_range(0..TABLE1_LENGTHS_MM.len())])
                .collect();
            let model = if i % 5 == 4 {
                CellModel::Rigid
            } else {
                CellModel::Resonant
            };
            ChainBuilder::table1_rods(&rods, model).unwrap()
        })
        .collect()
}

/// Peaks-only settings of `duration_s`.
pub fn peaks_only(method: woodpile::Method, duration_s: f64) -> RunSettings {
    RunSettings {
        duration_s,
        method,
        sample_interval_s: duration_s,
    }
}

/// Each chain run alone with `simulate`.
pub fn alone(chains: &[Chain], excitation: &Excitation, settings: &RunSettings) -> Vec<RunSummary> {
    chains
        .iter()
        .map(|c| simulate(c, excitation, settings, &mut ()).unwrap())
        .collect()
}

/// Runs `jobs` together at every lane width, on one thread and on three (each group's runs then
/// shared by three threads' lanes through one queue), and asserts that each result is `same` as
/// its run alone (`alone`, in the order of `jobs`).
pub fn assert_lanes_agree(
    jobs: &[Job<'_>],
    alone: &[RunSummary],
    same: impl Fn(&RunSummary, &RunSummary) -> bool,
) {
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        for width in LaneWidth::ALL {
            let together = pool.install(|| simulate_many(jobs, width));
            for (i, (t, a)) in together.iter().zip(alone).enumerate() {
                let t = t.as_ref().unwrap();
                assert!(
                    same(t, a),
                    "chain {i}, {width:?}, {threads} threads: lanes {:?} vs alone {:?}",
                    t.contact_peak_forces_n,
                    a.contact_peak_forces_n
                );
            }
        }
    }
}
