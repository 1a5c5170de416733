//! Claim: the Timoshenko rod (Cowper's shear coefficient, rotary inertia) gives the bending
//! frequencies of the paper's 5 mm fused-quartz rods (E 72 GPa, ν 0.17, ρ 2200 kg/m³): symmetric
//! free–free 55.76 kHz (20 mm), 15.32 kHz (40 mm), 9.94 and 48.84 kHz (50 mm), 3.94 and
//! 20.42 kHz (80 mm); centre-blocked 35.68 kHz (20 mm), 2.48 and 14.84 kHz (80 mm). Tolerance
//! 0.2 %: the reference values are independent solutions of the same frequency equations,
//! rounded to 4 significant digits (±0.1 % for 2.48 kHz).

use woodpile::{BeamTheory, Material, Rod};

fn rod(length_mm: f64) -> Rod {
    let quartz = Material::new("quartz", 72e9, 0.17, 2200.0).unwrap();
    Rod::new(length_mm * 1e-3, 0.005, 0.0, quartz).unwrap()
}

fn check(what: &str, computed_hz: &[f64], reference_khz: &[f64]) {
    assert_eq!(computed_hz.len(), reference_khz.len());
    for (f, r) in computed_hz.iter().zip(reference_khz) {
        let rel = (f / 1e3 - r).abs() / r;
        assert!(
            rel < 2e-3,
            "{what}: {:.3} kHz vs {r} kHz ({rel:.1e})",
            f / 1e3
        );
    }
}

#[test]
fn paper_rods_ring_at_the_timoshenko_frequencies() {
    let t = BeamTheory::Timoshenko;
    for (length, free) in [
        (20.0, vec![55.76]),
        (40.0, vec![15.32]),
        (50.0, vec![9.94, 48.84]),
        (80.0, vec![3.94, 20.42]),
    ] {
        let computed = rod(length)
            .free_symmetric_frequencies_hz(t, free.len())
            .unwrap();
        check(&format!("{length} mm free-free"), &computed, &free);
    }
    for (length, blocked) in [(20.0, vec![35.68]), (80.0, vec![2.48, 14.84])] {
        let computed = rod(length)
            .centre_blocked_frequencies_hz(t, blocked.len())
            .unwrap();
        check(&format!("{length} mm centre-blocked"), &computed, &blocked);
    }
}
