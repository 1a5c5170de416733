//! Claim: the GA's operators never leave the design space. A random genome, a recombined child,
//! a BGA-mutated child and a repaired genome always index the catalogue and meet every
//! constraint (mass limit, fixed positions, count limits); and `FeasibleSet::new` accepts a
//! constraint set exactly when some design meets it (checked by enumerating all 7^n designs).
//!
//! Tolerance: the mass limit is compared with the library's documented relative slack of 1e-12
//! (summing the same masses in another order differs by a few ulps); everything else is exact.

use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use woodpile::optimize::{operators, Constraints, DesignSpace, FeasibleSet, OptimizeError};
use woodpile::{CellModel, RunSettings};

fn space(positions: usize, constraints: Constraints) -> DesignSpace {
    let mut s = DesignSpace::paper_impact(CellModel::Resonant);
    s.positions = positions;
    s.settings = RunSettings {
        duration_s: 1e-4,
        ..s.settings
    };
    s.constraints = constraints;
    s
}

/// The constraints, checked from their definition (independent of the library's code).
fn meets(space: &DesignSpace, g: &[u8]) -> bool {
    let c = &space.constraints;
    let n = space.catalogue.len();
    if g.len() != space.positions || g.iter().any(|&x| usize::from(x) >= n) {
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
    match c.max_total_mass_kg {
        Some(m) => mass <= m * (1.0 + 1e-12),
        None => true,
    }
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

fn constraints(positions: usize) -> impl Strategy<Value = Constraints> {
    (
        proptest::option::of(1.5e-3..25e-3_f64),
        proptest::collection::vec((0..positions, 0..7usize), 0..3),
        proptest::collection::vec((0..7usize, 0..4usize), 0..4),
    )
        .prop_map(|(mass, fixed, max_count)| Constraints {
            max_total_mass_kg: mass,
            fixed,
            max_count,
            ..Constraints::default()
        })
}

fn case() -> impl Strategy<Value = (usize, Constraints, u64)> {
    (1..=4usize).prop_flat_map(|n| (Just(n), constraints(n), any::<u64>()))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn feasibility_check_matches_enumeration((n, c, _seed) in case()) {
        let s = space(n, c);
        let exists = all_genomes(n, 7).any(|g| meets(&s, &g));
        match FeasibleSet::new(&s) {
            Ok(set) => {
                prop_assert!(exists);
                prop_assert!(meets(&s, set.lightest()));
            }
            Err(OptimizeError::Infeasible { .. } | OptimizeError::TooHeavy { .. }) => {
                prop_assert!(!exists)
            }
            Err(e) => prop_assert!(false, "unexpected error {e}"),
        }
    }

    #[test]
    fn operators_stay_feasible((n, c, seed) in case(), range in 0.5..8.0_f64, pool in 1..6usize) {
        let s = space(n, c);
        let Ok(set) = FeasibleSet::new(&s) else { return Ok(()) };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let population: Vec<Vec<u8>> = (0..6).map(|_| set.random(&mut rng)).collect();
        for g in &population {
            prop_assert!(meets(&s, g), "random genome {g:?}");
            prop_assert!(set.contains(g));
        }
        let parents: Vec<&[u8]> = population.iter().map(|g| &g[..]).collect();
        for _ in 0..20 {
            let (a, b) = operators::select_parents(pool, &mut rng);
            prop_assert!(a < pool && b < pool);
            let mut child = operators::recombine(parents[a], parents[b], &mut rng);
            prop_assert!(child.iter().all(|&x| x < 7));
            prop_assert!(child.iter().enumerate().all(|(i, &x)| x == parents[a][i] || x == parents[b][i]));
            operators::mutate(&mut child, &set, range, &mut rng);
            prop_assert!(child.iter().all(|&x| x < 7), "mutated {child:?}");
            set.repair(&mut child, &mut rng);
            prop_assert!(meets(&s, &child), "repaired {child:?}");
            let bred = operators::breed(&parents, pool, &set, range, &mut rng);
            prop_assert!(meets(&s, &bred), "bred {bred:?}");
        }
        // Repair of arbitrary in-catalogue genomes (e.g. all heaviest rods).
        let mut heavy = vec![6u8; n];
        set.repair(&mut heavy, &mut rng);
        prop_assert!(meets(&s, &heavy), "repaired heavy {heavy:?}");
    }
}
