//! Claim: `[design] rod_range` turns into a catalogue of derived rods: 20–80 mm by 1 mm is 61
//! rods, lengths ascending and exact to the millimetre (no 21.000000000000004 in labels), each
//! resolving to a cell of the rod's own mass ρ·A·L (1e-9: the derived cell keeps the total mass
//! to rounding); the optimisation problem over it has 61 catalogue entries. Bad ranges are errors
//! naming the key: a zero step, a range beyond the 256-entry catalogue limit (20–80 mm by 0.1 mm
//! is 601 rods), and a range given together with catalogue_mm. Exact checks otherwise.

use std::path::Path;
use woodpile_io::optimize::{OptimizeConfig, Problem};
use woodpile_io::Error;

fn config(extra: &str) -> OptimizeConfig {
    OptimizeConfig::parse(&format!("[design]\n{extra}\n"), "test.toml").unwrap()
}

fn field_of(e: Error) -> String {
    match e {
        Error::Invalid { field, .. } => field,
        other => panic!("expected an invalid-value error, got {other}"),
    }
}

#[test]
fn rod_range_is_a_catalogue_of_derived_rods() {
    let c = config("rod_range = { from_mm = 20.0, to_mm = 80.0, step_mm = 1.0 }");
    let elements = c.design.rod_range.as_ref().unwrap().elements().unwrap();
    assert_eq!(elements.len(), 61);
    for (i, e) in elements.iter().enumerate() {
        assert_eq!(e.length_mm, Some(20.0 + i as f64), "entry {i}");
    }
    let problem = Problem::new(&c, Path::new("."), 1).unwrap();
    assert_eq!(problem.space.catalogue.len(), 61);
    for (i, e) in problem.space.catalogue.iter().enumerate() {
        let length_m = (20.0 + i as f64) * 1e-3;
        let rho_a_l = 2200.0 * std::f64::consts::PI * 2.5e-3_f64.powi(2) * length_m;
        let m = e.cell.total_mass_kg();
        assert!(
            (m - rho_a_l).abs() < 1e-9 * rho_a_l,
            "entry {i}: {m} vs {rho_a_l}"
        );
        assert_eq!(e.label, format!("rod{}mm", 20 + i));
    }
    let bad = |extra: &str| {
        field_of(
            Problem::new(&config(extra), Path::new("."), 1)
                .err()
                .unwrap(),
        )
    };
    assert_eq!(
        bad("rod_range = { from_mm = 20.0, to_mm = 80.0, step_mm = 0.0 }"),
        "design.rod_range.step_mm"
    );
    assert_eq!(
        bad("rod_range = { from_mm = 20.0, to_mm = 80.0, step_mm = 0.1 }"),
        "design.rod_range"
    );
    assert_eq!(
        bad("catalogue_mm = [20, 40]\nrod_range = { from_mm = 20.0, to_mm = 80.0, step_mm = 1.0 }"),
        "design.rod_range"
    );
}
