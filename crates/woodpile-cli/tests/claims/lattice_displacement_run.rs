//! Claim: `woodpile simulate` runs a lattice under a displacement drive (docs/physics.md §16)
//! and writes every contact's energy over time.
//!
//! A 3 × 2-rod lattice preloaded with 6 N through the actuator's tip (the chains' `excitation.tip`,
//! a steel cap of 5 mm) on its six top-layer crossings, driven by a harmonic displacement with
//! restitution contacts and modal damping: `run.json` lists the six tips first (layer 0, each on
//! the top rod under it); in the static state (`static_contact_forces_n`) they carry the
//! rigid actuator's shares, summing to 6 N and equal at mirror images (to 1e-9), and each starts
//! from its share at t = 0 (`forces.csv`, to 1e-9); the audit E + D − E(0) − W closes below 1e-6 (the run's own,
//! `summary.json`) with W > 0; `rod_energies.csv` has the actuator's column `actuator_j`.
//!
//! Per-contact energies: `contact_energies.csv` / `contact_energy_j.npy` and
//! `contact_dissipated.csv` / `contact_dissipated_j.npy` have a row per sample and a column per
//! contact of `run.json`; each body's modes' energy, its `rod_energies.csv` energy less half of
//! each of its contacts' potential (`run.json` says which), is ≥ 0 (kinetic and strain energy;
//! to 1e-12 of E's scale), and the modes' energies plus every contact's potential are
//! `energy.csv`'s `total_j` within 1e-12 of its largest value (rounding of sums in another
//! order; measured 2.3e-16); the last row of `contact_dissipated.csv` is `summary.json`'s `contact_dissipated_j`
//! (exact: both print the shortest round-trip decimal).
//!
//! Bad input — a free tip, a tip under a force drive, a negative ramp, a flat tip (a line contact
//! on a rod), a cap of zero radius —
//! exits 2 naming the dotted key.

use crate::common;

const DRIVE: &str = r#"
[lattice]
layers = [
  { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 2 },
]
rod = { fe_elements = 2 }
[excitation]
kind = "drive"
drive = "displacement"
signal = "harmonic"
amplitude = 4e-7
frequency_hz = 8e3
ramp_s = 5e-5
tip = { kind = "cap", material = "steel", cap_radius_mm = 5.0 }
[damping]
contact = "restitution"
restitution = 0.8
modal_ratio = 0.01
[preload]
force_n = 6.0
[run]
duration_s = 3e-4
"#;

/// A CSV file's header and rows.
fn csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn displacement_drive_runs_and_writes_contact_energies() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "lat.toml", DRIVE);
    common::simulate_ok(dir.path(), "lat.toml");
    let out = dir.path().join("out");
    let run = common::json(&out.join("run.json"));
    let contacts = run["contacts"].as_array().unwrap();
    // 6 tips + 3 × 2 crossings + 2 supports.
    assert_eq!(contacts.len(), 14);
    for (k, c) in contacts[..6].iter().enumerate() {
        assert_eq!(c["layer_above"], 0);
        assert_eq!(c["rod_above"].as_u64().unwrap(), k as u64 + 1);
        assert_eq!(c["layer_below"], 1);
        assert_eq!(c["x_mm"], contacts[6 + k]["x_mm"]);
    }
    let summary = common::json(&out.join("summary.json"));
    let statics = numbers(&summary["static_contact_forces_n"]);
    let sum: f64 = statics[..6].iter().sum();
    assert!((sum - 6.0).abs() < 1e-9, "the tips carry {sum} N at rest");
    shares_are_mirror_symmetric(&contacts[..6], &statics[..6]);
    let error = summary["energy"]["max_relative_error"].as_f64().unwrap();
    assert!(error < 1e-6, "{error}");
    assert!(summary["energy"]["input_work_j"].as_f64().unwrap().abs() > 0.0);

    let (forces_header, forces) = csv(&out.join("forces.csv"));
    assert_eq!(forces_header.len(), 15);
    for (f, f0) in forces[0][1..7].iter().zip(&statics) {
        assert!(
            (f - f0).abs() < 1e-9,
            "a tip carries {f} N at t = 0, {f0} N at rest"
        );
    }
    let (energy_header, energy) = csv(&out.join("energy.csv"));
    assert_eq!(energy_header[1], "total_j");
    let (bodies_header, bodies) = csv(&out.join("rod_energies.csv"));
    assert_eq!(bodies_header[1], "actuator_j");
    let (contact_header, potentials) = csv(&out.join("contact_energies.csv"));
    assert_eq!(contact_header.len(), 15);
    assert_eq!(contact_header[14], "contact_13_j");
    let (_, dissipated) = csv(&out.join("contact_dissipated.csv"));
    assert_eq!(potentials.len(), energy.len());
    assert_eq!(dissipated.len(), energy.len());
    for f in ["contact_energy_j.npy", "contact_dissipated_j.npy"] {
        assert!(out.join(f).is_file(), "{f}");
    }

    bodies_and_contacts_add_up_to_the_total(&run, [&energy, &bodies, &potentials]);
    let totals = numbers(&summary["contact_dissipated_j"]);
    let sum: f64 = totals.iter().sum();
    assert!(sum > 0.0);
    for (a, b) in dissipated.last().unwrap()[1..].iter().zip(&totals) {
        assert!((a - b).abs() <= 1e-12 * sum, "{a} against {b}");
    }
}

#[test]
fn bad_displacement_drive_input_exits_2_naming_the_key() {
    let drive = |old: &str, new: &str| DRIVE.replace(old, new);
    common::refused_scenario(
        "free tip",
        &drive(
            "tip = { kind = \"cap\", material = \"steel\", cap_radius_mm = 5.0 }",
            "tip = { kind = \"free\" }",
        ),
        &["excitation.tip.kind", "\"free\"", "cap"],
    );
    common::refused_scenario(
        "tip under a force drive",
        &drive("drive = \"displacement\"", "drive = \"force\""),
        &["excitation.tip", "drive = \"force\""],
    );
    common::refused_scenario(
        "negative ramp",
        &drive("ramp_s = 5e-5", "ramp_s = -5e-5"),
        &["excitation.ramp_s", "-0.00005"],
    );
    common::refused_scenario(
        "flat tip on a rod (a line contact)",
        &drive(
            "tip = { kind = \"cap\", material = \"steel\", cap_radius_mm = 5.0 }",
            "tip = { kind = \"flat\", material = \"steel\" }",
        ),
        &["excitation.tip", "not a point contact"],
    );
    common::refused_scenario(
        "cap of zero radius",
        &drive("cap_radius_mm = 5.0", "cap_radius_mm = 0.0"),
        &["excitation.tip.cap_radius_mm", "0"],
    );
}

/// The rigid actuator's static shares at the tips (`contacts`, `statics`): equal at mirror images
/// (x → −x, y → −y).
fn shares_are_mirror_symmetric(contacts: &[serde_json::Value], statics: &[f64]) {
    let at = |c: &serde_json::Value| [c["x_mm"].as_f64().unwrap(), c["y_mm"].as_f64().unwrap()];
    for (k, contact) in contacts.iter().enumerate() {
        let p = at(contact);
        for mirror in [[-p[0], p[1]], [p[0], -p[1]]] {
            let j = contacts
                .iter()
                .position(|c| {
                    let q = at(c);
                    (q[0] - mirror[0]).abs() < 1e-6 && (q[1] - mirror[1]).abs() < 1e-6
                })
                .expect("a mirror image");
            assert!((statics[k] - statics[j]).abs() < 1e-9, "{statics:?}");
        }
    }
}

/// Every sample: each body's modes (its `rod_energies.csv` column less half of each of its
/// contacts' potentials) are not negative, the actuator has none, and modes plus contact
/// potentials make `total_j` (1e-12 of the largest total: rounding).
fn bodies_and_contacts_add_up_to_the_total(
    run: &serde_json::Value,
    [energy, bodies, potentials]: [&[Vec<f64>]; 3],
) {
    let contacts = run["contacts"].as_array().unwrap();
    // Body index in rod_energies.csv (after time_s): the actuator 0, then the rods layer by
    // layer; None for a support.
    let rods_per_layer: Vec<u64> = run["rods_per_layer"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    let body = |layer: u64, rod: u64| -> Option<usize> {
        if layer == 0 {
            return Some(0);
        }
        let before: u64 = rods_per_layer.iter().take(layer as usize - 1).sum();
        (layer as usize <= rods_per_layer.len()).then_some(1 + (before + rod - 1) as usize)
    };
    let scale = energy.iter().map(|r| r[1].abs()).fold(0.0_f64, f64::max);
    let (mut lowest, mut worst) = (f64::MAX, 0.0_f64);
    for (k, row) in bodies.iter().enumerate() {
        let mut modes: Vec<f64> = row[1..row.len() - 1].to_vec();
        let u = &potentials[k][1..];
        for (c, contact) in contacts.iter().enumerate() {
            let side =
                |l: &str, r: &str| body(contact[l].as_u64().unwrap(), contact[r].as_u64().unwrap());
            for b in [
                side("layer_above", "rod_above"),
                side("layer_below", "rod_below"),
            ]
            .into_iter()
            .flatten()
            {
                modes[b] -= 0.5 * u[c];
            }
        }
        // The actuator has no modes: its column is its halves alone.
        lowest = lowest.min(modes[1..].iter().fold(f64::MAX, |a, &b| a.min(b)));
        worst = worst.max(modes[0].abs() / scale);
        let total = modes[1..].iter().sum::<f64>() + u.iter().sum::<f64>();
        worst = worst.max((total - energy[k][1]).abs() / scale);
    }
    eprintln!("modes + contacts against total_j: {worst:e}; lowest modes' energy {lowest:e} J");
    assert!(worst < 1e-12, "{worst:e}");
    assert!(lowest > -1e-12 * scale, "{lowest:e}");
}
