//! Claim: a fitted `youngs_modulus_scale.MATERIAL` of s is that material with its Young's
//! modulus multiplied by s wherever the scenario uses it: the chain it builds (every cell's
//! masses and resonator stiffnesses, every contact β) and the striker are exactly those of the
//! scenario written with the scaled material inline. A name no body uses, and the Table 1
//! rods' fused quartz (their cells are tabulated), are refused naming the key.
//!
//! Tolerance: exact. Both paths compute s · E once and build from the same constants.

use std::path::Path;
use woodpile::Material;
use woodpile_io::fit::{setup, FitConfig};
use woodpile_io::scenario::{resolve, Scenario};

const SCALE: f64 = 1.2;

fn chain(quartz: &str, steel: &str) -> String {
    format!(
        "[chain]\nelements = [{{ kind = \"rod\", length_mm = 40.0, material = {quartz} }}, {{ kind = \"rod\", length_mm = 20.0, material = {quartz} }}]\n[wall]\nmaterial = {steel}\n[run]\nduration_s = 2e-4\n"
    )
}

fn inline(name: &str, scale: f64) -> String {
    let m = Material::preset(name).unwrap();
    format!(
        "{{ name = \"{name}\", youngs_modulus_pa = {:?}, poisson_ratio = {:?}, density_kg_m3 = {:?} }}",
        scale * m.youngs_modulus_pa,
        m.poisson_ratio,
        m.density_kg_m3
    )
}

fn fit_file(scenario: &str, key: &str) -> String {
    format!(
        "scenario = \"{scenario}\"\n[[data]]\nfile = \"data.csv\"\nsignals = {{ force = \"contact_2_n\" }}\n[fit]\nparameters = [{{ key = \"{key}\", bounds = [0.5, 2.0] }}]\n"
    )
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

#[test]
fn a_modulus_scale_is_the_material_with_its_modulus_scaled() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data: String = (0..50)
        .map(|i| format!("{:e},{}\n", i as f64 * 4e-6, i % 3))
        .collect();
    write(d, "data.csv", &format!("time_s,force\n{data}"));
    let quartz = "\"fused-quartz\"";
    let steel = "\"stainless-steel\"";
    write(d, "model.toml", &chain(quartz, steel));
    for (key, expected) in [
        (
            "youngs_modulus_scale.fused-quartz",
            chain(&inline("fused-quartz", SCALE), steel),
        ),
        (
            "youngs_modulus_scale.stainless-steel",
            chain(quartz, &inline("stainless-steel", SCALE)),
        ),
    ] {
        let config = FitConfig::parse(&fit_file("model.toml", key), "fit.toml").unwrap();
        let fitted = setup(&config, &d.join("fit.toml"), d)
            .unwrap()
            .build(&[SCALE])
            .unwrap();
        let written = resolve(&Scenario::parse(&expected).unwrap(), d).unwrap();
        assert_eq!(
            format!("{:?}", fitted.chain),
            format!("{:?}", written.chain),
            "{key}: the chain differs from the one written with the scaled material"
        );
        assert_eq!(
            format!("{:?}", fitted.excitation),
            format!("{:?}", written.excitation)
        );
    }
}

#[test]
fn a_modulus_scale_no_body_can_follow_is_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "data.csv", "time_s,force\n0.0,0.0\n1e-6,1.0\n2e-6,0.0\n");
    write(
        d,
        "model.toml",
        &chain("\"fused-quartz\"", "\"stainless-steel\""),
    );
    write(d, "table1.toml", "[chain]\nrods_mm = [40, 20]\n");
    for (scenario, key, says) in [
        (
            "model.toml",
            "youngs_modulus_scale.pmma",
            "no body of the scenario is made of `pmma`",
        ),
        (
            "table1.toml",
            "youngs_modulus_scale.fused-quartz",
            "Table 1 rods",
        ),
    ] {
        let config = FitConfig::parse(&fit_file(scenario, key), "fit.toml").unwrap();
        let err = setup(&config, &d.join("fit.toml"), d)
            .and_then(|s| s.build(&[1.0]))
            .unwrap_err();
        assert_eq!(err.field(), Some(key), "{err}");
        assert!(err.to_string().contains(says), "{err}");
    }
}
