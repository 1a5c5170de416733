//! Claim: the exact Hertz coefficients β reproduce docs/physics.md §5's reference table to 1e-4
//! relative, reduce to the circular closed form when the gap is axisymmetric, and do not depend
//! on which body is called first.
//!
//! Tolerance: the table gives five significant digits, so 1e-4 relative is the table's own
//! resolution; the circular limit and the symmetry are exact identities checked to 1e-12 (a few
//! ulps after the AGM and the bisection, which converge to ~1e-15).

use woodpile::model::{complete_elliptic_integrals, hertz_beta, Surface};
use woodpile::Material;

fn rod(axis_deg: f64) -> Surface {
    Surface::Cylinder {
        radius_m: 2.5e-3,
        axis_angle_rad: axis_deg.to_radians(),
    }
}

fn assert_rel(actual: f64, expected: f64, tol: f64, what: &str) {
    let rel = ((actual - expected) / expected).abs();
    assert!(
        rel <= tol,
        "{what}: got {actual:e}, expected {expected:e} (relative error {rel:.2e} > {tol:.0e})"
    );
}

#[test]
fn reference_table_of_physics_doc() {
    let quartz = Material::preset("fused-quartz").unwrap();
    let glass = Material::preset("soda-lime-glass").unwrap();
    let steel = Material::preset("stainless-steel").unwrap();
    for (angle, expected) in [
        (90.0, 2.4714e9),
        (75.0, 2.5293e9),
        (60.0, 2.7222e9),
        (45.0, 3.1276e9),
        (30.0, 3.9927e9),
    ] {
        let beta = hertz_beta(rod(0.0), &quartz, rod(angle), &quartz).unwrap();
        assert_rel(beta, expected, 1e-4, &format!("rod-rod at {angle} deg"));
    }
    let sphere = Surface::Sphere { radius_m: 5e-3 };
    assert_rel(
        hertz_beta(sphere, &glass, rod(0.0), &quartz).unwrap(),
        2.5683e9,
        1e-4,
        "rod-glass sphere",
    );
    assert_rel(
        hertz_beta(rod(0.0), &quartz, sphere, &steel).unwrap(),
        4.0644e9,
        1e-4,
        "rod-steel cap",
    );
}

#[test]
fn crossed_identical_cylinders_at_90_degrees_match_closed_form() {
    // docs/physics.md §5: β = 2 E sqrt(r) / (3 (1 − ν²)) for identical cylinders at 90°.
    let quartz = Material::preset("fused-quartz").unwrap();
    let expected = 2.0 * 72e9 * 2.5e-3_f64.sqrt() / (3.0 * (1.0 - 0.17 * 0.17));
    let beta = hertz_beta(rod(0.0), &quartz, rod(90.0), &quartz).unwrap();
    assert_rel(beta, expected, 1e-12, "90-degree closed form");
}

#[test]
fn circular_limit_sphere_on_sphere_and_on_flat() {
    // A = B: β = (4/3) E* sqrt(R_e) with 1/R_e = 1/R1 + 1/R2 (Johnson eq. 4.22).
    let steel = Material::preset("steel").unwrap();
    let brass = Material::preset("brass").unwrap();
    let e_star = 1.0 / ((1.0 - 0.3 * 0.3) / 210e9 + (1.0 - 0.34 * 0.34) / 100e9);
    let (r1, r2) = (4e-3, 7e-3);
    let r_e: f64 = 1.0 / (1.0 / r1 + 1.0 / r2);
    let beta = hertz_beta(
        Surface::Sphere { radius_m: r1 },
        &steel,
        Surface::Sphere { radius_m: r2 },
        &brass,
    )
    .unwrap();
    assert_rel(
        beta,
        4.0 / 3.0 * e_star * r_e.sqrt(),
        1e-12,
        "sphere-sphere",
    );
    let beta = hertz_beta(
        Surface::Sphere { radius_m: r1 },
        &steel,
        Surface::Flat,
        &brass,
    )
    .unwrap();
    assert_rel(beta, 4.0 / 3.0 * e_star * r1.sqrt(), 1e-12, "sphere-flat");
}

#[test]
fn coefficient_is_symmetric_in_the_two_bodies() {
    let quartz = Material::preset("fused-quartz").unwrap();
    let alu = Material::preset("aluminium").unwrap();
    let cases = [
        (
            Surface::Cylinder {
                radius_m: 2e-3,
                axis_angle_rad: 0.3,
            },
            Surface::Cylinder {
                radius_m: 3.5e-3,
                axis_angle_rad: 1.4,
            },
        ),
        (
            Surface::Sphere { radius_m: 6e-3 },
            Surface::Cylinder {
                radius_m: 1.5e-3,
                axis_angle_rad: 0.0,
            },
        ),
        (
            Surface::Cylinder {
                radius_m: 2.5e-3,
                axis_angle_rad: 0.0,
            },
            Surface::Sphere { radius_m: 5e-3 },
        ),
    ];
    for (a, b) in cases {
        let ab = hertz_beta(a, &quartz, b, &alu).unwrap();
        let ba = hertz_beta(b, &alu, a, &quartz).unwrap();
        assert_rel(ab, ba, 1e-12, &format!("{a:?} vs {b:?}"));
    }
}

#[test]
fn nearly_circular_contact_tends_to_the_circular_value() {
    // Two identical cylinders crossed at angle α → 90° ± ε: B/A → 1 continuously; the exact solver
    // must not lose precision there (β changes by O(ε²)).
    let quartz = Material::preset("fused-quartz").unwrap();
    let at_90 = hertz_beta(rod(0.0), &quartz, rod(90.0), &quartz).unwrap();
    let near = hertz_beta(rod(0.0), &quartz, rod(90.0 - 1e-6), &quartz).unwrap();
    assert_rel(near, at_90, 1e-9, "alpha = 90 deg - 1e-6 deg");
}

#[test]
fn elliptic_integrals_match_abramowitz_stegun() {
    for (deg, k_ref, e_ref) in [
        (45.0_f64, 1.854074677, 1.350643881),
        (80.0, 3.153385252, 1.040114396),
    ] {
        let (k, e) = complete_elliptic_integrals(deg.to_radians().sin());
        assert_rel(k, k_ref, 1e-9, "K");
        assert_rel(e, e_ref, 1e-9, "E");
    }
}

#[test]
fn parallel_cylinders_are_rejected_as_line_contact() {
    let quartz = Material::preset("fused-quartz").unwrap();
    let err = hertz_beta(rod(0.0), &quartz, rod(0.0), &quartz).unwrap_err();
    assert!(err.to_string().contains("not a point contact"), "{err}");
}
