//! Claim: in the Euler–Bernoulli limit (no shear deformation, no rotary inertia) the rod's
//! frequency equations give the textbook eigenvalues: symmetric free–free modes at βL = 4.7300
//! and 10.9956 (L the whole rod), clamped–free modes of the half rod at βℓ = 1.8751 and 4.6941
//! (ℓ = L/2). Tolerance 1e-4 on βL: the reference values are rounded to four decimals (±5e-5);
//! the solver bisects to machine precision.

use woodpile::{BeamTheory, Material, Rod};

/// βL of a frequency f for a beam of length `length_m`: ω = (βL/L)² sqrt(EI/ρA).
fn beta_l(rod: &Rod, f_hz: f64, length_m: f64) -> f64 {
    let ei = rod.material.youngs_modulus_pa * rod.second_moment_m4();
    let rho_a = rod.material.density_kg_m3 * rod.area_m2();
    let omega = 2.0 * std::f64::consts::PI * f_hz;
    (omega / (ei / rho_a).sqrt()).sqrt() * length_m
}

#[test]
fn slender_limit_gives_textbook_eigenvalues() {
    let quartz = Material::preset("fused-quartz").unwrap();
    // A 5 mm rod 80 mm long; in this limit βL does not depend on the proportions.
    let rod = Rod::new(0.08, 0.005, 0.0, quartz).unwrap();
    let free = rod
        .free_symmetric_frequencies_hz(BeamTheory::EulerBernoulli, 2)
        .unwrap();
    let blocked = rod
        .centre_blocked_frequencies_hz(BeamTheory::EulerBernoulli, 2)
        .unwrap();
    for (f, reference) in free.iter().zip([4.7300, 10.9956]) {
        let bl = beta_l(&rod, *f, rod.length_m);
        assert!(
            (bl - reference).abs() < 1e-4,
            "free-free βL {bl} vs {reference}"
        );
    }
    for (f, reference) in blocked.iter().zip([1.8751, 4.6941]) {
        let bl = beta_l(&rod, *f, 0.5 * rod.length_m);
        assert!(
            (bl - reference).abs() < 1e-4,
            "clamped-free βℓ {bl} vs {reference}"
        );
    }
}
