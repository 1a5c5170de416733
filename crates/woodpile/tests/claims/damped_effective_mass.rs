//! Claim: the damped effective mass of a cell (docs/physics.md §14),
//! M_eff(ω) = M + Σ_j m_j (k_j + iωc_j)/(k_j + iωc_j − ω² m_j), c_j = 2ζ√(k_j m_j), is the cell's
//! dynamic mass: driving the primary mass at X e^{iωt}, the power it absorbs,
//! P = −½ ω³ Im(M_eff) |X|², equals the power its dashpots dissipate, Σ ½ c_j ω² |W_j − X|², where
//! each resonator's amplitude W_j comes from its own equation of motion,
//! −ω² m_j W_j = −(k_j + iωc_j)(W_j − X). Checked to 1e-12 relative (rounding) on the paper's
//! 80 mm cell at ζ = 0.02 over 0.1–40 kHz; and ζ = 0 gives the undamped M_eff (to 1e-12, the
//! two formulas round differently).

use rustfft::num_complex::Complex64;
use woodpile::UnitCell;

#[test]
fn absorbed_power_equals_dashpot_dissipation() {
    let cell = UnitCell::table1(80).unwrap();
    let zeta = 0.02;
    let x = Complex64::new(1e-6, 0.0);
    for k in 1..=400 {
        let omega = 2.0 * std::f64::consts::PI * 100.0 * k as f64;
        let m_eff = cell.damped_effective_mass_kg(omega, zeta);
        let absorbed = -0.5 * omega.powi(3) * m_eff.im * x.norm_sqr();
        let dissipated: f64 = cell
            .resonators
            .iter()
            .map(|r| {
                let c = 2.0 * zeta * (r.stiffness_n_per_m * r.mass_kg).sqrt();
                let spring = Complex64::new(r.stiffness_n_per_m, omega * c);
                // −ω² m W = −spring (W − X)  ⇒  W = spring X / (spring − ω² m)
                let w = spring * x / (spring - omega * omega * r.mass_kg);
                0.5 * c * omega * omega * (w - x).norm_sqr()
            })
            .sum();
        assert!(absorbed > 0.0, "{omega}: the cell must absorb power");
        assert!(
            (absorbed / dissipated - 1.0).abs() < 1e-12,
            "ω = {omega}: absorbed {absorbed}, dissipated {dissipated}"
        );
        let undamped = cell.damped_effective_mass_kg(omega, 0.0);
        let real = cell.effective_mass_kg(omega);
        assert!(
            (undamped.re / real - 1.0).abs() < 1e-12,
            "ω = {omega}: {undamped} vs {real}"
        );
        assert_eq!(undamped.im, 0.0);
    }
}
