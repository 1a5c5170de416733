//! Claim: the draws of `[uncertainty]` (woodpile::uncertainty) are what they say.
//! (1) Φ⁻¹ (Acklam's approximation) agrees with tabulated standard normal quantiles (Abramowitz &
//! Stegun 26.2; values to 15 digits as printed by R's qnorm) to 1.2e-9 relative: Acklam's stated
//! bound is 1.15e-9. (2) The scrambled Sobol' points are a (0, m, 1)-net in each coordinate: of
//! 32 points, exactly one falls in each interval [i/32, (i+1)/32) (Owen scrambling keeps the
//! net property; a pseudo-random sample would leave about 12 of the 32 intervals empty).
//! (3) They depend on (sample, dimension, seed) only: drawing 32 or 8 samples gives the same
//! first 8 rows, bit for bit, and another seed gives other points. (4) The statistics of a
//! design's samples: type-7 quantiles and CVaR₀.₉₅ against values worked by hand.

use woodpile::uncertainty::{standard_normal_quantile, statistics, unit_cube};

#[test]
fn normal_quantiles_match_the_table() {
    let table = [
        (0.5, 0.0),
        (0.8413447460685429, 1.0),
        (0.975, 1.959963984540054),
        (0.99, 2.326347874040841),
        (0.999, 3.090232306167814),
        (1e-6, -4.753424308822899),
        (0.01, -2.326347874040841),
    ];
    for (p, z) in table {
        let got = standard_normal_quantile(p);
        let err = if z == 0.0 {
            got.abs()
        } else {
            (got / z - 1.0).abs()
        };
        assert!(err < 1.2e-9, "Φ⁻¹({p}) = {got}, table {z}: error {err:e}");
    }
    assert_eq!(standard_normal_quantile(0.0), f64::NEG_INFINITY);
    assert!(standard_normal_quantile(1.5).is_nan());
}

#[test]
fn sobol_points_stratify_each_coordinate_and_depend_on_the_seed_only() {
    let u = unit_cube(32, 6, 7).unwrap();
    for j in 0..6 {
        let mut hits = [0u32; 32];
        for row in &u {
            assert!(row[j] > 0.0 && row[j] < 1.0);
            hits[(row[j] * 32.0) as usize] += 1;
        }
        assert!(hits.iter().all(|&h| h == 1), "coordinate {j}: {hits:?}");
    }
    let first = unit_cube(8, 6, 7).unwrap();
    assert_eq!(first[..], u[..8]);
    let other = unit_cube(8, 6, 8).unwrap();
    assert_ne!(other, first);
    assert!(unit_cube(1, woodpile::uncertainty::MAX_DIMENSIONS + 1, 0).is_err());
}

#[test]
fn statistics_of_samples_by_hand() {
    // numpy.quantile([1, 2, 3, 4], [0.05, 0.25, 0.5, 0.75, 0.95]) = 1.15, 1.75, 2.5, 3.25, 3.85.
    let s = statistics(&[4.0, 1.0, 3.0, 2.0]);
    let want = [1.15, 1.75, 2.5, 3.25, 3.85];
    for ((_, q), w) in s.quantiles.iter().zip(want) {
        assert!((q - w).abs() < 1e-14, "{q} vs {w}");
    }
    assert_eq!(s.mean, 2.5);
    // sd of 1..4 with n - 1: sqrt(5/3).
    assert!((s.sd - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
    // 32 samples 1..32: the worst ⌈0.05·32⌉ = 2 are 31 and 32.
    let v: Vec<f64> = (1..=32).map(f64::from).collect();
    assert_eq!(statistics(&v).cvar_95, 31.5);
}
