//! Claim: the Table 1 unit cells reproduce docs/physics.md §3's local resonances f_j and free-cell
//! resonances F_j to 0.01 kHz, their total masses to 1 mg·1e-3, M_eff(0) equals the total mass,
//! and M_eff is negative exactly on the bands f_j < f < F_j.
//!
//! Tolerance: the table rounds frequencies to 0.01 kHz, so |ours − table| ≤ 0.005 kHz plus
//! rounding; we allow 0.01 kHz, the table's last digit. M_eff(0) = Σ masses is exact up to rounding
//! (1e-12 relative).

use woodpile::UnitCell;

/// (length mm, total mass g, f_j kHz, F_j kHz) from docs/physics.md §3.
const TABLE: [(u32, f64, &[f64], &[f64]); 7] = [
    (20, 0.866, &[38.76], &[55.45]),
    (30, 1.299, &[17.47], &[26.37]),
    (40, 1.732, &[10.59], &[15.23]),
    (50, 2.165, &[6.14, 35.65], &[9.89, 48.52]),
    (60, 2.598, &[4.31, 26.83], &[6.89, 34.90]),
    (70, 3.031, &[3.20, 20.66], &[5.09, 26.11]),
    (80, 3.464, &[2.74, 15.65], &[3.92, 20.33]),
];

#[test]
fn frequencies_and_masses_match_table_1() {
    for (len, mass_g, f, big_f) in TABLE {
        let cell = UnitCell::table1(len).unwrap();
        assert!(
            (cell.total_mass_kg() * 1e3 - mass_g).abs() < 1e-9,
            "{len} mm total mass"
        );
        let ours_f = cell.local_resonances_hz();
        let ours_big = cell.free_resonances_hz();
        assert_eq!(ours_f.len(), f.len(), "{len} mm: number of resonators");
        for (a, b) in ours_f.iter().zip(f) {
            assert!(
                (a / 1e3 - b).abs() <= 0.01,
                "{len} mm: f_j = {:.4} kHz vs table {b}",
                a / 1e3
            );
        }
        for (a, b) in ours_big.iter().zip(big_f) {
            assert!(
                (a / 1e3 - b).abs() <= 0.01,
                "{len} mm: F_j = {:.4} kHz vs table {b}",
                a / 1e3
            );
        }
    }
}

#[test]
fn static_effective_mass_is_total_mass() {
    for (len, ..) in TABLE {
        let cell = UnitCell::table1(len).unwrap();
        let rel = (cell.effective_mass_kg(0.0) / cell.total_mass_kg() - 1.0).abs();
        assert!(rel < 1e-12, "{len} mm: M_eff(0)/M_total - 1 = {rel:e}");
    }
}

#[test]
fn effective_mass_is_negative_exactly_on_the_bands() {
    let two_pi = 2.0 * std::f64::consts::PI;
    for (len, ..) in TABLE {
        let cell = UnitCell::table1(len).unwrap();
        let bands = cell.negative_mass_bands_hz();
        // Scan 0..1.5 × highest F_j on a fine grid, skipping points within 1e-6 of an edge.
        let top = bands.last().unwrap().1 * 1.5;
        for i in 1..20_000 {
            let f = top * i as f64 / 20_000.0;
            let near_edge = bands
                .iter()
                .any(|&(lo, hi)| (f / lo - 1.0).abs() < 1e-6 || (f / hi - 1.0).abs() < 1e-6);
            if near_edge {
                continue;
            }
            let inside = bands.iter().any(|&(lo, hi)| f > lo && f < hi);
            let m = cell.effective_mass_kg(two_pi * f);
            assert_eq!(
                m < 0.0,
                inside,
                "{len} mm at {f:.1} Hz: M_eff = {m:e}, in band = {inside}"
            );
        }
    }
}

#[test]
fn rigid_variant_has_no_resonance_and_the_same_mass() {
    let cell = UnitCell::table1(80).unwrap();
    let rigid = cell.rigid();
    assert!(rigid.resonators.is_empty());
    assert!((rigid.total_mass_kg() - cell.total_mass_kg()).abs() < 1e-15);
    assert!(UnitCell::table1(25).is_err(), "25 mm is not in Table 1");
}
