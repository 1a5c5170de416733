//! Claim: the lattice keys table (`woodpile_io::lattice::lattice_keys()`) is the lattice
//! scenario file (docs/physics.md §16). A file giving every key of the table at once parses
//! and resolves, and the keys it holds are exactly the table's (so no key is missing from
//! either side); the completed built-in `lattice` holds only keys of the table (and `[run]`,
//! a chain's, and `description`); and every number the table gives as a default is what
//! completion writes. No tolerance: names and defaults are compared exactly.

use std::collections::BTreeSet;
use toml::Value;
use woodpile_io::lattice::{builtin_lattice, lattice_keys, LatticeScenario};
use woodpile_io::scenario::{KeyDefault, KeyType};

/// Every key (tables as `A.B`, entries of arrays of tables as `A[].B`) of a TOML document.
fn names(prefix: &str, value: &Value, out: &mut BTreeSet<String>) {
    match value {
        Value::Table(t) => {
            for (k, v) in t {
                let name = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                out.insert(name.clone());
                names(&name, v, out);
            }
        }
        Value::Array(a) if !a.is_empty() && a.iter().all(Value::is_table) => {
            for v in a {
                names(&format!("{prefix}[]"), v, out);
            }
        }
        _ => {}
    }
}

const EVERY_KEY: &str = r#"
[lattice]
layers = [
  { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 3, angle_deg = 80.0, lengths_mm = [80.0, 60.0, 80.0], offsets_mm = [0.0, 5.0, 0.0] },
]
rod = { modes = 4 }
[excitation]
kind = "impact"
at_mm = [10.0, 0.0]
velocity_m_s = 1.0
striker = { diameter_mm = 8.0, material = "steel" }
[wall]
supports = [{ x_mm = 0.0, y_mm = 0.0 }]
"#;

#[test]
fn the_lattice_keys_table_is_the_file() {
    let table: BTreeSet<String> = lattice_keys().iter().map(|k| k.name.to_string()).collect();
    // `fe_elements` and `drop_height_m` are the alternatives of keys the file gives; `supports`
    // as a name is the alternative of the list the file gives.
    let mut given = BTreeSet::new();
    names(
        "",
        &EVERY_KEY.parse::<toml::Table>().map(Value::Table).unwrap(),
        &mut given,
    );
    for alternative in ["lattice.rod.fe_elements", "excitation.drop_height_m"] {
        given.insert(alternative.to_string());
    }
    assert_eq!(given, table, "the keys of the file and of the table");
    LatticeScenario::parse(EVERY_KEY, "every key")
        .unwrap()
        .resolve()
        .unwrap();

    let builtin = LatticeScenario::parse(builtin_lattice("lattice").unwrap(), "lattice").unwrap();
    let complete = builtin.complete();
    let text = toml::to_string(&complete).unwrap();
    let mut written = BTreeSet::new();
    names(
        "",
        &text.parse::<toml::Table>().map(Value::Table).unwrap(),
        &mut written,
    );
    for name in &written {
        assert!(
            table.contains(name) || name == "description" || name.starts_with("run"),
            "{name} is written but not in the table"
        );
    }
    let document: Value = toml::from_str(&text).unwrap();
    for k in lattice_keys() {
        let (KeyDefault::Float(x), KeyType::Float | KeyType::Integer) = (&k.default, k.ty) else {
            continue;
        };
        let mut v = &document;
        for part in k.name.split('.') {
            v = &v[part.trim_end_matches("[]")];
        }
        let written = v.as_float().or(v.as_integer().map(|i| i as f64)).unwrap();
        assert_eq!(written, *x, "{}", k.name);
    }
}
