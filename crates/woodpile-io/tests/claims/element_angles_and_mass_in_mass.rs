//! Claim: an element's own `crossing_angle_deg` (relative to the element above) sets that
//! contact's geometry exactly as a chain-wide angle would: the β of a 40 mm rod on an 80 mm rod
//! at 60° is the same number (compared with `==`: the same arithmetic) whether 60° is the chain's
//! angle or the second rod's own, and in a three-rod chain the other contact keeps the chain's
//! 90° (exactly) while the turned one gets 60° (to 1e-12: its angle is a difference of two
//! accumulated axes). The top element has no element above it, so an angle there is an error naming its key.
//! A sphere may carry resonators (a mass-in-mass sphere): its given cell is used as given, with a
//! warning when its mass is more than 1 % off ρπd³/6.

use std::path::Path;
use woodpile_io::scenario::{resolve, Scenario};
use woodpile_io::Error;

fn resolved(chain: &str) -> woodpile_io::scenario::Resolved {
    let s = Scenario::parse(&format!("[chain]\n{chain}\n[run]\nduration_s = 1e-4\n")).unwrap();
    resolve(&s, Path::new(".")).unwrap()
}

#[test]
fn element_angles_and_mass_in_mass_spheres() {
    let global =
        resolved("crossing_angle_deg = 60.0\nelements = [{ rod_mm = 80 }, { rod_mm = 40 }]");
    let own = resolved("elements = [{ rod_mm = 80 }, { rod_mm = 40, crossing_angle_deg = 60.0 }]");
    assert_eq!(global.chain.inner_betas(), own.chain.inner_betas());
    let right = resolved("elements = [{ rod_mm = 40 }, { rod_mm = 80 }]");
    let three = resolved(
        "elements = [{ rod_mm = 40 }, { rod_mm = 80 }, { rod_mm = 40, crossing_angle_deg = 60.0 }]",
    );
    assert_eq!(three.chain.inner_betas()[0], right.chain.inner_betas()[0]);
    // Here the third rod's axis is 90° + 60° and the angle between the two is a difference of
    // radians: equal to rounding (1e-12 relative).
    let (b3, bg) = (three.chain.inner_betas()[1], global.chain.inner_betas()[0]);
    assert!((b3 - bg).abs() < 1e-12 * bg, "{b3} vs {bg}");
    assert_ne!(global.chain.inner_betas()[0], right.chain.inner_betas()[0]);

    let s = Scenario::parse(
        "[chain]\nelements = [{ rod_mm = 40, crossing_angle_deg = 60.0 }, { rod_mm = 80 }]\n",
    )
    .unwrap();
    match resolve(&s, Path::new(".")) {
        Err(Error::Invalid { field, .. }) => {
            assert_eq!(field, "chain.elements[0].crossing_angle_deg")
        }
        other => panic!("expected an error naming the top element's angle, got {other:?}"),
    }

    // A 10 mm steel sphere weighs ρπd³/6 = 4.11 g; a 1.0 g shell with a 3.1 g resonator fits,
    // a 1.0 g shell with a 1.0 g resonator does not (warning).
    let sphere = |resonator_g: f64| {
        resolved(&format!(
            "elements = [{{ rod_mm = 40 }}, {{ kind = \"sphere\", diameter_mm = 10.0, material = \"steel\", cell = {{ primary_mass_g = 1.0, resonators = [{{ mass_g = {resonator_g}, stiffness_kn_per_mm = 2.0 }}] }} }}]"
        ))
    };
    let fits = sphere(3.1);
    let cell = &fits.chain.elements()[1].cell;
    assert_eq!(cell.resonators.len(), 1);
    assert_eq!(cell.primary_mass_kg, 1e-3);
    assert!(fits.warnings.is_empty(), "{:?}", fits.warnings);
    let light = sphere(1.0);
    assert!(
        light
            .warnings
            .iter()
            .any(|w| w.starts_with("chain.elements[1].cell") && w.contains("ρπd³/6")),
        "{:?}",
        light.warnings
    );
}
