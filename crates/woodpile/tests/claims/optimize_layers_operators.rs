//! Claim: with the number of layers part of the design (`positions..=max_positions`), the GA's
//! genomes never leave [min, max] nor the constraints. A random genome, a child of two parents
//! of different lengths (recombined, mutated, repaired) and a repaired genome of any length and
//! any genes have a length in [min, max] and meet every constraint (mass and height limits,
//! fixed layers counted from the top, count limits); `FeasibleSet::lengths` is exactly the set
//! of lengths at which some design meets the constraints (checked by enumerating all 7^n
//! designs of every length n ≤ 5).
//!
//! Tolerance: the mass and height limits are compared with the library's documented relative
//! slack of 1e-12 (summing the same values in another order differs by a few ulps); everything
//! else is exact.

use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use woodpile::optimize::{operators, Constraints, DesignSpace, FeasibleSet, OptimizeError};
use woodpile::{CellModel, RunSettings};

/// Every Table 1 rod is 5 mm across (paper §2): a stack of n rods stands n × 5 mm.
const ROD_DIAMETER_M: f64 = 5e-3;

fn space(min: usize, max: usize, constraints: Constraints) -> DesignSpace {
    let mut s = DesignSpace::paper_impact(CellModel::Resonant);
    s.positions = min;
    s.max_positions = Some(max);
    s.settings = RunSettings {
        duration_s: 1e-4,
        ..s.settings
    };
    s.constraints = constraints;
    s
}

/// The constraints and the range of lengths, checked from their definition (independent of
/// the library's code).
fn meets(space: &DesignSpace, g: &[u8]) -> bool {
    let c = &space.constraints;
    let n = space.catalogue.len();
    if !(space.positions..=space.max_positions.unwrap()).contains(&g.len())
        || g.iter().any(|&x| usize::from(x) >= n)
    {
        return false;
    }
    if c.fixed.iter().any(|&(p, e)| usize::from(g[p]) != e) {
        return false;
    }
    if c.max_count
        .iter()
        .any(|&(e, k)| g.iter().filter(|&&x| usize::from(x) == e).count() > k)
    {
        return false;
    }
    let mass: f64 = g
        .iter()
        .map(|&x| space.catalogue[usize::from(x)].cell.total_mass_kg())
        .sum();
    let height = g.len() as f64 * ROD_DIAMETER_M;
    c.max_total_mass_kg
        .is_none_or(|m| mass <= m * (1.0 + 1e-12))
        && c.max_stack_height_m
            .is_none_or(|h| height <= h * (1.0 + 1e-12))
}

fn all_genomes(positions: usize, n: usize) -> impl Iterator<Item = Vec<u8>> {
    (0..n.pow(positions as u32)).map(move |mut k| {
        (0..positions)
            .map(|_| {
                let d = (k % n) as u8;
                k /= n;
                d
            })
            .collect()
    })
}

fn constraints(min: usize) -> impl Strategy<Value = Constraints> {
    (
        proptest::option::of(1.5e-3..35e-3_f64),
        proptest::option::of(4e-3..30e-3_f64),
        proptest::collection::vec((0..min, 0..7usize), 0..3),
        proptest::collection::vec((0..7usize, 0..4usize), 0..4),
    )
        .prop_map(|(mass, height, fixed, max_count)| Constraints {
            max_total_mass_kg: mass,
            max_stack_height_m: height,
            fixed,
            max_count,
            ..Constraints::default()
        })
}

fn case() -> impl Strategy<Value = (usize, usize, Constraints, u64)> {
    (1..=3usize, 0..=2usize).prop_flat_map(|(min, extra)| {
        (Just(min), Just(min + extra), constraints(min), any::<u64>())
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 150, ..ProptestConfig::default() })]

    #[test]
    fn feasible_lengths_match_enumeration((min, max, c, _seed) in case()) {
        let s = space(min, max, c);
        let feasible: Vec<usize> = (min..=max)
            .filter(|&n| all_genomes(n, 7).any(|g| meets(&s, &g)))
            .collect();
        match FeasibleSet::new(&s) {
            Ok(set) => {
                prop_assert_eq!(set.lengths().collect::<Vec<_>>(), feasible);
                prop_assert!(meets(&s, set.lightest()));
            }
            Err(OptimizeError::Infeasible { .. } | OptimizeError::TooHeavy { .. } | OptimizeError::TooTall { .. }) => {
                prop_assert!(!feasible.contains(&min), "refused, but {min} layers are feasible")
            }
            Err(e) => prop_assert!(false, "unexpected error {e}"),
        }
    }

    #[test]
    fn operators_stay_within_lengths_and_constraints((min, max, c, seed) in case(), range in 0.5..8.0_f64) {
        let s = space(min, max + 3, c);
        let Ok(set) = FeasibleSet::new(&s) else { return Ok(()) };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let population: Vec<Vec<u8>> = (0..8).map(|_| set.random(&mut rng)).collect();
        for g in &population {
            prop_assert!(meets(&s, g), "random genome {g:?}");
            prop_assert!(set.contains(g));
        }
        for _ in 0..30 {
            let (a, b) = (rng.random_range(0..8), rng.random_range(0..8));
            let (pa, pb) = (&population[a], &population[b]);
            let mut child = operators::recombine(pa, pb, &mut rng);
            prop_assert!(child.len() == pa.len() || child.len() == pb.len());
            prop_assert!(child.iter().enumerate().all(|(i, &x)| pa.get(i) == Some(&x) || pb.get(i) == Some(&x)));
            operators::mutate(&mut child, &set, range, &mut rng);
            prop_assert!(set.lengths().contains(&child.len()), "mutated {child:?}");
            prop_assert!(child.iter().all(|&x| x < 7), "mutated {child:?}");
            set.repair(&mut child, &mut rng);
            prop_assert!(meets(&s, &child), "repaired {child:?}");
            let parents: Vec<&[u8]> = population.iter().map(|g| &g[..]).collect();
            let bred = operators::breed(&parents, 8, &set, range, &mut rng);
            prop_assert!(meets(&s, &bred), "bred {bred:?}");
        }
        // Repair of any genome: any length from 0 to beyond the most, any genes.
        for _ in 0..10 {
            let len = rng.random_range(0..=max + 6);
            let mut g: Vec<u8> = (0..len).map(|_| rng.random_range(0..7)).collect();
            set.repair(&mut g, &mut rng);
            prop_assert!(meets(&s, &g), "repaired {g:?} (from {len} layers)");
        }
    }
}

#[test]
fn length_mutation_reaches_every_feasible_length() {
    // Without a claim that the length moves at all, the claims above would hold for a GA that
    // never left its initial lengths: from a single length, mutation alone reaches them all.
    let s = space(2, 6, Constraints::default());
    let set = FeasibleSet::new(&s).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut g = vec![0u8; 2];
    let mut seen = std::collections::BTreeSet::new();
    for _ in 0..2000 {
        operators::mutate(&mut g, &set, 3.0, &mut rng);
        seen.insert(g.len());
    }
    assert_eq!(seen.into_iter().collect::<Vec<_>>(), vec![2, 3, 4, 5, 6]);
}
