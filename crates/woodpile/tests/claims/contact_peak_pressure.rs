//! Claim: the Hertz peak pressure of a contact (the `max-contact-pressure` objective) is the
//! textbook one: for a circular contact p₀ = (6 F E*² / (π³ R²))^{1/3} (Johnson 1985, eq. 4.24),
//! which the paper's rods crossed at 90° form (equal radii: an equivalent sphere of radius r on
//! a flat); for the elliptical contact of a rod on the sensor's spherical cap (B/A = 3) it is
//! what Johnson's §4.2 relations give when solved independently: K(e) and E(e) by Simpson's
//! rule (not the library's arithmetic–geometric mean), e from B/A = [E/(1 − e²) − K]/(K − E) by
//! bisection, a³ = 3F(K − E)/(2π E* e² A), b = a sqrt(1 − e²), p₀ = 3F/(2π a b).
//!
//! Tolerances: 1e-12 relative for the circular case (closed forms in double precision); 1e-9
//! for the elliptical case (quadrature and bisection errors are far below it).

use std::f64::consts::PI;
use woodpile::model::{hertz_contact, EllipseSolution, Surface};
use woodpile::Material;

fn circular(force_n: f64, e_star: f64, radius_m: f64) -> f64 {
    (6.0 * force_n * e_star * e_star / (PI.powi(3) * radius_m * radius_m)).cbrt()
}

#[test]
fn crossed_rods_give_the_circular_hertz_pressure() {
    let quartz = Material::fused_quartz();
    let r = 2.5e-3;
    let c = hertz_contact(
        Surface::Cylinder {
            radius_m: r,
            axis_angle_rad: 0.0,
        },
        &quartz,
        Surface::Cylinder {
            radius_m: r,
            axis_angle_rad: PI / 2.0,
        },
        &quartz,
        EllipseSolution::Exact,
    )
    .unwrap();
    for force in [1.0, 24.0, 127.0, 1e4] {
        let p = c.peak_pressure_pa(force);
        let expected = circular(force, c.effective_modulus_pa, r);
        assert!(
            (p / expected - 1.0).abs() < 1e-12,
            "F = {force} N: {p} Pa vs {expected} Pa"
        );
    }
    assert_eq!(
        c.peak_pressure_pa(0.0),
        0.0,
        "an open contact carries no pressure"
    );
    assert_eq!(c.peak_pressure_pa(-1.0), 0.0);
}

/// Complete elliptic integrals K(e), E(e) of modulus e by composite Simpson's rule.
fn k_and_e(e: f64) -> (f64, f64) {
    let n = 4000;
    let h = 0.5 * PI / n as f64;
    let (mut k, mut ee) = (0.0, 0.0);
    for i in 0..=n {
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let s = (i as f64 * h).sin();
        let root = (1.0 - e * e * s * s).sqrt();
        k += w / root;
        ee += w * root;
    }
    (k * h / 3.0, ee * h / 3.0)
}

/// Johnson's elliptical Hertz peak pressure, solved independently (see the module docs).
fn johnson_peak_pressure(force_n: f64, a_per_m: f64, b_per_m: f64, e_star: f64) -> f64 {
    let ratio = |e: f64| {
        let (k, ee) = k_and_e(e);
        (ee / (1.0 - e * e) - k) / (k - ee)
    };
    let (mut lo, mut hi) = (1e-6, 1.0 - 1e-12);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if ratio(mid) < b_per_m / a_per_m {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let e = 0.5 * (lo + hi);
    let (k, ee) = k_and_e(e);
    let a = (3.0 * force_n * (k - ee) / (2.0 * PI * e_star * e * e * a_per_m)).cbrt();
    let b = a * (1.0 - e * e).sqrt();
    3.0 * force_n / (2.0 * PI * a * b)
}

#[test]
fn rod_on_the_sensor_cap_gives_johnsons_elliptical_pressure() {
    let quartz = Material::fused_quartz();
    let steel = Material::preset("stainless-steel").unwrap();
    let c = hertz_contact(
        Surface::Cylinder {
            radius_m: 2.5e-3,
            axis_angle_rad: 0.0,
        },
        &quartz,
        Surface::Sphere { radius_m: 5e-3 },
        &steel,
        EllipseSolution::Exact,
    )
    .unwrap();
    assert!(
        (c.b_per_m / c.a_per_m - 3.0).abs() < 1e-9,
        "B/A = 3 for this geometry"
    );
    for force in [10.0, 100.0] {
        let p = c.peak_pressure_pa(force);
        let expected = johnson_peak_pressure(force, c.a_per_m, c.b_per_m, c.effective_modulus_pa);
        assert!(
            (p / expected - 1.0).abs() < 1e-9,
            "F = {force} N: {p} Pa vs {expected} Pa"
        );
    }
    // p0 grows as F^{1/3} (the shape of the ellipse does not depend on the load).
    let ratio = c.peak_pressure_pa(80.0) / c.peak_pressure_pa(10.0);
    assert!(
        (ratio - 2.0).abs() < 1e-12,
        "8x the force, 2x the pressure: {ratio}"
    );
}
