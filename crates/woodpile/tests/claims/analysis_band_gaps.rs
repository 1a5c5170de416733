//! Claim: the band gaps of a homogeneous chain from the dispersion relation
//! 4 K_c sin²(qa/2) = ω² M_eff(ω) agree with the sign changes of M_eff exactly as the analysis
//! in `analysis::bands` derives: gap j is (ω_c,j, Ω_j) where the upper edge Ω_j is the zero of M_eff
//! (the paper's F_j, independent of K_c), the lower edge ω_c,j < ω_j solves ω² M_eff = 4K_c, so
//! every negative-mass band [f_j, F_j] lies inside a gap; and as K_c → ∞ the gaps shrink onto the
//! negative-mass bands. A dense frequency scan confirms "in a gap ⇔ s ∉ [0, 1]".
//!
//! Tolerances: the edges are bisection roots in ω² to machine precision, so F_j agrees with the
//! cell's own zeros to 1e-12 and s(ω_c) = 1 to 1e-9; the scan skips points within 1e-9 of an edge.
//! For K_c → ∞ (F_p = 1e12 N) the lower edge sits at ω_j(1 − O(m ω_j²/K_c)): 1e-3 is generous.

use woodpile::analysis::{contact_stiffness_n_per_m, linspace, BandStructure, EffectiveMassCurve};
use woodpile::model::TABLE1_LENGTHS_MM;
use woodpile::UnitCell;

const ROD_ROD_BETA: f64 = 2.4714e9;

#[test]
fn gap_edges_are_the_zeros_of_the_effective_mass() {
    for length in TABLE1_LENGTHS_MM {
        let cell = UnitCell::table1(length).unwrap();
        let bands = BandStructure::homogeneous(&cell, ROD_ROD_BETA, 1.0).unwrap();
        let local = cell.local_resonances_hz();
        let zeros = cell.free_resonances_hz();
        let l = local.len();
        assert_eq!(bands.gaps_hz.len(), l + 1, "{length} mm");
        assert_eq!(bands.pass_bands_hz.len(), l + 1);
        assert_eq!(bands.pass_bands_hz[0].0, 0.0);
        assert!(bands.gaps_hz[l].1.is_infinite());
        for j in 0..l {
            let (lo, hi) = bands.gaps_hz[j];
            assert!(
                (hi / zeros[j] - 1.0).abs() < 1e-12,
                "{length} mm gap {j}: {hi}"
            );
            assert!(
                lo < local[j],
                "{length} mm gap {j}: {lo} ≥ f_j {}",
                local[j]
            );
            assert!((bands.dispersion_ratio(lo) - 1.0).abs() < 1e-9);
            // Bands tile the axis: pass, gap, pass, …
            assert_eq!(bands.pass_bands_hz[j].1, lo);
            assert_eq!(bands.pass_bands_hz[j + 1].0, hi);
        }
        // The negative-mass bands of the effective-mass curve lie inside the gaps.
        let curve = EffectiveMassCurve::of(&cell, &[]);
        for (j, &(f, big_f)) in curve.negative_bands_hz.iter().enumerate() {
            assert!(bands.gaps_hz[j].0 < f && big_f == zeros[j]);
        }
    }
}

#[test]
fn a_dense_scan_agrees_with_the_gaps() {
    for length in [20, 40, 80] {
        let cell = UnitCell::table1(length).unwrap();
        let bands = BandStructure::homogeneous(&cell, ROD_ROD_BETA, 5.0).unwrap();
        let near_edge = |f: f64| {
            bands
                .gaps_hz
                .iter()
                .any(|&(lo, hi)| (f - lo).abs() < 1e-9 * lo || (f - hi).abs() < 1e-9 * hi)
        };
        for f in linspace(10.0, 120e3, 20_000) {
            if near_edge(f) {
                continue;
            }
            let s = bands.dispersion_ratio(f);
            let propagates = (0.0..=1.0).contains(&s);
            assert_eq!(
                bands.in_gap(f),
                !propagates,
                "{length} mm at {f} Hz: s = {s}"
            );
            assert_eq!(bands.wavenumber(f).is_some(), propagates);
            // In a gap with negative mass ⇔ M_eff < 0.
            let negative = cell.effective_mass_kg(2.0 * std::f64::consts::PI * f) < 0.0;
            assert_eq!(s < 0.0, negative);
        }
    }
}

#[test]
fn stiff_contacts_shrink_the_gaps_onto_the_negative_mass_bands() {
    for length in TABLE1_LENGTHS_MM {
        let cell = UnitCell::table1(length).unwrap();
        let soft = BandStructure::homogeneous(&cell, ROD_ROD_BETA, 1.0).unwrap();
        let stiff = BandStructure::homogeneous(&cell, ROD_ROD_BETA, 1e12).unwrap();
        for (j, (f, big_f)) in cell.negative_mass_bands_hz().into_iter().enumerate() {
            assert!((stiff.gaps_hz[j].0 / f - 1.0).abs() < 1e-3, "{length} mm");
            assert!(stiff.gaps_hz[j].0 > soft.gaps_hz[j].0);
            assert_eq!(stiff.gaps_hz[j].1, big_f);
        }
    }
    let kc = contact_stiffness_n_per_m(ROD_ROD_BETA, 8.0).unwrap();
    assert!((kc / (1.5 * ROD_ROD_BETA.powf(2.0 / 3.0) * 2.0) - 1.0).abs() < 1e-14);
}
