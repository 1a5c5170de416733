//! Claim: the lattice keys table (`woodpile_io::lattice::lattice_keys()`) is the lattice
//! scenario file (docs/physics.md §16). Four files (an impact with every contact law and a
//! static load, a blast, a force drive, a displacement drive) parse and resolve, and the keys
//! they hold, with the alternatives none of them can give at once, are exactly the table's (so
//! no key is missing from either side); the completed built-in `lattice` holds only keys of the table (and `[run]`,
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

/// An impact giving every `[lattice]`, striker and `[wall]` key, every contact law and a static
/// load.
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
[damping]
contact = "hunt-crossley"
restitution = 0.9
impact_speed_m_s = 1.0
allow_pull = false
striker = { contact = "restitution", restitution = 0.8 }
wall = { contact = "viscoelastic", viscous_time_s = 1e-7 }
on_site_time_s = 1e-2
modal_ratio = 0.01
[preload]
force_n = 1.0
gravity_m_s2 = 9.81
[run]
duration_s = 1e-4
integrator = "dopri5"
rtol = 1e-6
atol = 1e-12
sample_interval_s = 1e-5
"#;

/// The keys of a blast (on given points) and of two drives (a chirped force on every top
/// crossing; a harmonic displacement through a tip, with the other contact laws' keys), each
/// added to the lattice above.
const BLAST: &str = r#"
[excitation]
kind = "blast"
points_mm = [[0.0, 0.0], [20.0, 0.0]]
profile = "friedlander"
peak_force_n = 10.0
duration_s = 1e-4
decay = 1.0
"#;
const FORCE_DRIVE: &str = r#"
[excitation]
kind = "drive"
drive = "force"
points = "top-crossings"
signal = "chirp"
amplitude = 1.0
start_hz = 1000.0
end_hz = 5000.0
sweep_duration_s = 1e-4
sweep = "linear"
ramp_s = 1e-5
"#;
const DISPLACEMENT_DRIVE: &str = r#"
[excitation]
kind = "drive"
drive = "displacement"
signal = "harmonic"
amplitude = 1e-7
frequency_hz = 2000.0
ramp_s = 1e-5
tip = { kind = "cap", material = "stainless-steel", cap_radius_mm = 5.0 }
[preload]
force_n = 1.0
[damping]
contact = "viscoelastic"
viscous_time_s = 1e-7
striker = { contact = "viscoelastic", viscous_time_s = 1e-7 }
wall = { contact = "restitution", restitution = 0.9 }
"#;

/// The lattice of [`EVERY_KEY`] with the excitation (and preload) `excitation`.
fn with_excitation(excitation: &str) -> String {
    let lattice = &EVERY_KEY[..EVERY_KEY.find("[excitation]").unwrap()];
    let wall = &EVERY_KEY[EVERY_KEY.find("[wall]").unwrap()..EVERY_KEY.find("[damping]").unwrap()];
    format!("{lattice}{excitation}{wall}[run]\nduration_s = 1e-4\n")
}

#[test]
fn the_lattice_keys_table_is_the_file() {
    let table: BTreeSet<String> = lattice_keys().iter().map(|k| k.name.to_string()).collect();
    // The alternatives of keys the files give (a table's profile or signal reads `file`, a tip
    // given by its beta, rk4's step, `peak_tolerance`'s integrators, a supports' name) are
    // named by the table but given by no file.
    let mut given = BTreeSet::new();
    let files = [
        EVERY_KEY.to_string(),
        with_excitation(BLAST),
        with_excitation(FORCE_DRIVE),
        with_excitation(DISPLACEMENT_DRIVE),
    ];
    for file in &files {
        names(
            "",
            &file.parse::<toml::Table>().map(Value::Table).unwrap(),
            &mut given,
        );
        LatticeScenario::parse(file, "every key")
            .unwrap()
            .resolve()
            .unwrap_or_else(|e| panic!("{e}\n{file}"));
    }
    for alternative in [
        "lattice.rod.fe_elements",
        "excitation.drop_height_m",
        "excitation.file",
        "excitation.tip.beta",
        "run.time_step_s",
        "run.peak_tolerance",
    ] {
        given.insert(alternative.to_string());
    }
    assert_eq!(given, table, "the keys of the files and of the table");

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
            table.contains(name) || name == "description",
            "{name} is written but not in the table"
        );
    }
    // Every numeric default the completed impact writes is the table's. Keys of a table the
    // impact leaves out ([damping], a blast's or drive's) or that completion leaves unset (an
    // integrator's settings under `peak_tolerance`) are not written, so not compared; the list
    // of those compared is checked to hold the lattice's, the striker's and the run's.
    let document: Value = toml::from_str(&text).unwrap();
    let mut compared = BTreeSet::new();
    for k in lattice_keys() {
        let (KeyDefault::Float(x), KeyType::Float | KeyType::Integer) = (&k.default, k.ty) else {
            continue;
        };
        let mut v = Some(&document);
        for part in k.name.split('.') {
            v = v.and_then(|v| v.get(part.trim_end_matches("[]")));
        }
        let Some(v) = v else { continue };
        let written = v.as_float().or(v.as_integer().map(|i| i as f64)).unwrap();
        assert_eq!(written, *x, "{}", k.name);
        compared.insert(k.name);
    }
    eprintln!("defaults compared: {compared:?}");
    for name in [
        "lattice.rod.fe_elements",
        "excitation.drop_height_m",
        "excitation.striker.diameter_mm",
        "run.sample_interval_s",
    ] {
        assert!(compared.contains(name), "{name}'s default was not compared");
    }
}
