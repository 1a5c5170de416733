//! Claim: `[uncertainty]` reads exactly the documented distributions and refuses what means nothing,
//! naming the key as the user wrote it: a negative sd, `samples = 0`, a reversed range, two
//! distributions at once (at resolve), an unknown distribution or parameter (when the file is
//! read). A scenario with `[uncertainty]` emits and parses back to the same scenario.

use woodpile_io::scenario::{resolve, Scenario};
use woodpile_io::uncertainty::{Distribution, Parameter};

const BASE: &str = "[chain]\nrods_mm = [80, 40]\n[run]\nduration_s = 1e-4\n";

fn with(uncertainty: &str) -> String {
    format!("{BASE}[uncertainty]\n{uncertainty}\n")
}

#[test]
fn the_issues_distributions_parse_and_round_trip() {
    let text = with(
        "samples = 32\nrod_length_mm = { sd = 0.2 }\ncrossing_angle_deg = { sd = 2.0 }\n\
         youngs_modulus = { relative_sd = 0.02 }\nimpact_velocity_m_s = { uniform = [1.8, 2.2] }\n\
         restitution = { uniform = [0.6, 0.8] }",
    );
    let s = Scenario::parse(&text).unwrap();
    let u = s.uncertainty.as_ref().unwrap().check().unwrap();
    assert_eq!(u.samples, 32);
    assert_eq!(
        u.parameters,
        vec![
            (Parameter::RodLength, Distribution::Normal { sd: 0.2 }),
            (Parameter::CrossingAngle, Distribution::Normal { sd: 2.0 }),
            (
                Parameter::YoungsModulus,
                Distribution::RelativeNormal { relative_sd: 0.02 }
            ),
            (
                Parameter::ImpactVelocity,
                Distribution::Uniform {
                    low: 1.8,
                    high: 2.2
                }
            ),
            (
                Parameter::Restitution,
                Distribution::Uniform {
                    low: 0.6,
                    high: 0.8
                }
            ),
        ]
    );
    let emitted = s.to_toml();
    assert_eq!(
        Scenario::parse(&emitted).unwrap(),
        s.complete(),
        "{emitted}"
    );
}

#[test]
fn bad_uncertainty_names_the_key() {
    let refused = |u: &str, field: &str, value: &str| {
        let s = Scenario::parse(&with(u)).unwrap();
        let e = resolve(&s, std::path::Path::new(".")).unwrap_err();
        assert_eq!(e.field(), Some(field), "{u}: {e}");
        assert_eq!(e.value().as_deref(), Some(value), "{u}: {e}");
    };
    refused(
        "rod_length_mm = { sd = -0.2 }",
        "uncertainty.rod_length_mm.sd",
        "-0.2",
    );
    refused("samples = 0", "uncertainty.samples", "0");
    refused(
        "impact_velocity_m_s = { uniform = [2.2, 1.8] }",
        "uncertainty.impact_velocity_m_s.uniform",
        "[2.2, 1.8]",
    );
    refused(
        "youngs_modulus = { sd = 1e9, relative_sd = 0.02 }",
        "uncertainty.youngs_modulus",
        "{…}",
    );
    // Unknown names are refused by the reader, which quotes them.
    for (u, name) in [
        ("rod_length_mm = { normal = 0.2 }", "normal"),
        ("rod_diameter_mm = { sd = 0.2 }", "rod_diameter_mm"),
    ] {
        let e = Scenario::parse(&with(u)).unwrap_err().to_string();
        assert!(e.contains(name), "{u}: {e}");
    }
}
