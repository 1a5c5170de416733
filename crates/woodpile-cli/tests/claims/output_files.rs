//! Claim: a run writes every promised output with the documented layout: summary.json with the
//! figures of merit under unit-suffixed keys, run.json with the tool version, the completed
//! scenario and the contact coefficients, CSV files whose headers name time and every contact /
//! layer, and .npy arrays of shape samples × (N+1) (forces, energies), samples × N (displacements,
//! velocities) and samples × 2 (striker), all consistent with the sample grid (0.2 ms at 1 µs:
//! 201 samples).

use crate::common;

use std::path::Path;

/// Shape and values of a `.npy` file, read by the letter of the NPY 1.0 specification (magic,
/// version 1.0, u16 header length, a dict with '<f8' C-order data starting at a multiple of 64
/// bytes), independently of woodpile's own reader.
fn npy_shape_and_data(path: &Path) -> (Vec<u64>, Vec<f64>) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00", "{}", path.display());
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!(
        (10 + len) % 64,
        0,
        "data of {} not 64-byte aligned",
        path.display()
    );
    let header = std::str::from_utf8(&bytes[10..10 + len]).unwrap();
    assert!(header.starts_with("{'descr': '<f8', 'fortran_order': False, 'shape': ("));
    assert!(header.ends_with('\n'));
    let dims = header
        .split("'shape': (")
        .nth(1)
        .unwrap()
        .split(')')
        .next()
        .unwrap();
    let shape: Vec<u64> = dims
        .split(',')
        .filter(|d| !d.trim().is_empty())
        .map(|d| d.trim().parse().unwrap())
        .collect();
    let data = bytes[10 + len..]
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    (shape, data)
}

#[test]
fn impact_run_writes_every_file() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", common::SHORT);
    let out = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    for key in [
        "transmitted",
        "incident",
        "restitution",
        "energy",
        "steps",
        "out",
    ] {
        assert!(
            stdout.contains(key),
            "terminal summary lacks {key}: {stdout}"
        );
    }
    let d = dir.path().join("out");
    let (n, samples) = (5u64, 201u64);

    let s = summary_has_every_key(&d, samples);
    let r = common::json(&d.join("run.json"));
    assert_eq!(r["version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(
        r["scenario"]["run"]["time_step_s"], 1e-7,
        "defaults filled in"
    );
    assert_eq!(r["scenario"]["wall"]["cap_radius_mm"], 5.0);
    assert_eq!(
        r["contact_betas_n_per_m1_5"]["inner"]
            .as_array()
            .unwrap()
            .len(),
        4
    );
    let striker_beta = r["contact_betas_n_per_m1_5"]["striker"].as_f64().unwrap();
    assert!(
        (striker_beta / 2.5683e9 - 1.0).abs() < 1e-4,
        "{striker_beta}"
    );
    let wall_beta = r["contact_betas_n_per_m1_5"]["wall"].as_f64().unwrap();
    assert!((wall_beta / 4.0644e9 - 1.0).abs() < 1e-4, "{wall_beta}");

    let forces = std::fs::read_to_string(d.join("forces.csv")).unwrap();
    let mut lines = forces.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time_s,contact_0_n,contact_1_n,contact_2_n,contact_3_n,contact_4_n,contact_5_n"
    );
    assert_eq!(lines.count() as u64, samples);
    let energy = std::fs::read_to_string(d.join("energy.csv")).unwrap();
    assert_eq!(
        energy.lines().next().unwrap(),
        "time_s,layer_0_j,layer_1_j,layer_2_j,layer_3_j,layer_4_j,layer_5_j,wall_j,total_j,input_work_j,dissipated_j"
    );
    for f in ["displacements.csv", "velocities.csv", "striker.csv"] {
        assert!(d.join(f).is_file(), "{f}");
    }

    let (shape, t) = npy_shape_and_data(&d.join("time_s.npy"));
    assert_eq!(shape, vec![samples]);
    assert_eq!(t[0], 0.0);
    assert!((t[200] - 2e-4).abs() < 1e-15);
    let (shape, f) = npy_shape_and_data(&d.join("forces_n.npy"));
    assert_eq!(shape, vec![samples, n + 1]);
    assert!(f.iter().all(|x| x.is_finite() && *x >= 0.0));
    let peak1 = f.chunks(6).map(|row| row[1]).fold(0.0, f64::max);
    let incident = s["incident_peak_force_n"].as_f64().unwrap();
    assert!(peak1 <= incident * (1.0 + 1e-12) && peak1 > 0.9 * incident);
    assert_eq!(
        npy_shape_and_data(&d.join("energy_j.npy")).0,
        vec![samples, n + 1]
    );
    assert_eq!(
        npy_shape_and_data(&d.join("displacements_m.npy")).0,
        vec![samples, n]
    );
    assert_eq!(
        npy_shape_and_data(&d.join("velocities_m_s.npy")).0,
        vec![samples, n]
    );
    assert_eq!(
        npy_shape_and_data(&d.join("striker.npy")).0,
        vec![samples, 2]
    );
}

#[test]
fn blast_run_has_no_striker_outputs() {
    let dir = tempfile::tempdir().unwrap();
    common::write(
        dir.path(),
        "s.toml",
        "[chain]\nrods_mm = [20, 40]\n[excitation]\nkind = \"blast\"\n[run]\nduration_s = 2e-4\n",
    );
    let out = common::run_in(
        dir.path(),
        &["simulate", "s.toml", "--out", "out", "--quiet"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.stdout.is_empty(), "--quiet prints nothing");
    let d = dir.path().join("out");
    let s = common::json(&d.join("summary.json"));
    assert!(s["restitution_coefficient"].is_null());
    assert!(s["energy"]["input_work_j"].as_f64().unwrap() > 0.0);
    assert!(!d.join("striker.npy").exists() && !d.join("striker.csv").exists());
    assert_eq!(npy_shape_and_data(&d.join("forces_n.npy")).0, vec![201, 3]);
}

/// The impact run's `summary.json` (`samples` samples, 6 contacts): every key it documents.
fn summary_has_every_key(d: &std::path::Path, samples: u64) -> serde_json::Value {
    let s = common::json(&d.join("summary.json"));
    for key in [
        "incident_peak_force_n",
        "transmitted_peak_force_n",
        "transmission_ratio",
        "striker_separated",
        "wall_time_s",
    ] {
        assert!(!s[key].is_null(), "summary.json lacks {key}");
    }
    assert_eq!(s["contact_peak_forces_n"].as_array().unwrap().len(), 6);
    assert_eq!(s["contact_peak_times_s"].as_array().unwrap().len(), 6);
    assert_eq!(s["chain_labels"][0], "80mm");
    assert_eq!(s["n_samples"], samples);
    for key in [
        "initial_j",
        "final_j",
        "input_work_j",
        "dissipated_j",
        "max_relative_error",
    ] {
        assert!(s["energy"][key].is_number(), "energy.{key}");
    }
    for key in ["steps", "rhs_evaluations", "rejected_steps"] {
        assert!(s["integrator"][key].is_number(), "integrator.{key}");
    }
    assert_eq!(s["integrator"]["steps"], 2000);

    s
}
