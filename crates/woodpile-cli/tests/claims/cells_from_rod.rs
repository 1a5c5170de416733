//! Claim: `woodpile cells --rod L --json` prints the cell derived from the rod with the promised
//! keys: the resonator masses and the primary mass sum to ρ·A·L of the rod (1e-9 relative: a sum
//! of three numbers printed with 17 digits), the zeros `free_resonances_khz` of the 80 mm quartz
//! rod's cell are its Timoshenko free–free frequencies 3.94 and 20.42 kHz (0.2 %: the references
//! are rounded to 4 digits), the default rule gives it two resonators, and out-of-range flags
//! exit 2 naming the flag. In a scenario, a `kind = "rod"` element without a cell gets the same
//! derived cell (run.json records it), so a rod's length changes the result; a given cell whose
//! mass is not the rod's is reported on stderr. A finite-element rod (`cell = { fe_elements = 16 }`)
//! runs at a step its stiffest mode allows and is refused, naming run.time_step_s, at the paper's.
//! A rod's options without `--rod` are refused naming it (they were silently ignored).

use crate::common;

#[test]
fn derived_cell_json_has_the_rods_mass_and_frequencies() {
    let dir = tempfile::tempdir().unwrap();
    let out = common::run_in(dir.path(), &["cells", "--rod", "80", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let total = v["total_mass_g"].as_f64().unwrap();
    let rho_a_l_g = 2200.0 * std::f64::consts::PI * 2.5e-3_f64.powi(2) * 0.08 * 1e3;
    assert!(
        (total - rho_a_l_g).abs() < 1e-9 * rho_a_l_g,
        "{total} vs {rho_a_l_g}"
    );
    let resonators = v["resonators"].as_array().unwrap();
    assert_eq!(resonators.len(), 2, "default rule: two modes for 80 mm");
    let sum: f64 = v["primary_mass_g"].as_f64().unwrap()
        + resonators
            .iter()
            .map(|r| r["mass_g"].as_f64().unwrap())
            .sum::<f64>();
    assert!((sum - total).abs() < 1e-9 * total, "{sum} vs {total}");
    for r in resonators {
        assert!(r["stiffness_kn_per_mm"].as_f64().unwrap() > 0.0);
        assert!(r["frequency_khz"].as_f64().unwrap() > 0.0);
    }
    let zeros: Vec<f64> = v["free_resonances_khz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|z| z.as_f64().unwrap())
        .collect();
    for (z, reference) in zeros.iter().zip([3.94, 20.42]) {
        assert!(
            (z - reference).abs() < 2e-3 * reference,
            "{z} vs {reference}"
        );
    }
    for (args, flag) in [
        (&["cells", "--rod", "80", "--modes", "9"][..], "--modes"),
        (&["cells", "--rod", "-3"][..], "--rod"),
        (
            &["cells", "--rod", "40", "--inner-diameter-mm", "6"][..],
            "--inner-diameter-mm",
        ),
        (
            &["cells", "--rod", "40", "--material", "cheese"][..],
            "--material",
        ),
    ] {
        let out = common::run_in(dir.path(), args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(flag), "{args:?}: {err}");
    }
}

#[test]
fn scenario_rods_derive_their_cells_and_length_matters() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = |length: f64| {
        format!(
            "[chain]\nelements = [{{ kind = \"rod\", length_mm = {length}, diameter_mm = 6.0, material = \"steel\" }}, {{ rod_mm = 40 }}]\n[run]\nduration_s = 2e-4\n"
        )
    };
    let mut transmitted = Vec::new();
    for (name, length) in [("short", 45.0), ("long", 90.0)] {
        common::write(dir.path(), &format!("{name}.toml"), &scenario(length));
        let file = format!("{name}.toml");
        let out = common::run_in(dir.path(), &["simulate", &file, "--out", name]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let run = common::json(&dir.path().join(name).join("run.json"));
        let summary = common::json(&dir.path().join(name).join("summary.json"));
        transmitted.push(summary["transmitted_peak_force_n"].as_f64().unwrap());
        let text = run.to_string();
        let rho_a_l_kg = 7850.0 * std::f64::consts::PI * 3e-3_f64.powi(2) * length * 1e-3;
        let recorded = run
            .pointer("/elements/0/total_mass_kg")
            .and_then(serde_json::Value::as_f64)
            .unwrap_or_else(|| panic!("run.json lacks elements[0].total_mass_kg: {text}"));
        assert!(
            (recorded - rho_a_l_kg).abs() < 1e-9 * rho_a_l_kg,
            "{recorded} vs {rho_a_l_kg}"
        );
    }
    assert!(
        (transmitted[0] - transmitted[1]).abs() > 1e-3 * transmitted[0],
        "45 mm and 90 mm rods gave the same transmitted peak {transmitted:?}"
    );
    common::write(
        dir.path(),
        "given.toml",
        "[chain]\nelements = [{ kind = \"rod\", length_mm = 45.0, cell = { primary_mass_g = 0.5, resonators = [{ mass_g = 0.7, stiffness_kn_per_mm = 5.0 }] } }]\n[run]\nduration_s = 1e-4\n",
    );
    let out = common::run_in(dir.path(), &["simulate", "given.toml", "--out", "given"]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("warning: chain.elements[0].cell") && err.contains("ρ·A·L"),
        "{err}"
    );
}

#[test]
fn finite_element_rods_need_a_small_step() {
    let dir = tempfile::tempdir().unwrap();
    let chain = "[chain]\nelements = [{ kind = \"rod\", length_mm = 20.0, cell = { fe_elements = 16 } }, { rod_mm = 40 }]\n";
    common::write(
        dir.path(),
        "paper.toml",
        &format!("{chain}[run]\nduration_s = 1e-4\n"),
    );
    let out = common::run_in(dir.path(), &["simulate", "paper.toml", "--out", "a"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("run.time_step_s") && err.contains("element 1"),
        "{err}"
    );
    common::write(
        dir.path(),
        "fine.toml",
        &format!("{chain}[run]\nduration_s = 1e-4\ntime_step_s = 1e-8\n"),
    );
    let out = common::run_in(dir.path(), &["simulate", "fine.toml", "--out", "b"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let run = common::json(&dir.path().join("b").join("run.json"));
    let resonators = run
        .pointer("/elements/0/resonator_masses_kg")
        .and_then(serde_json::Value::as_array)
        .map_or(0, Vec::len);
    assert_eq!(
        resonators, 32,
        "16 elements per half: 32 modes of the held half rod"
    );
}

/// A rod's options without `--rod` would be silently ignored (the catalogue is printed instead):
/// each is refused with exit code 2, naming `--rod`.
#[test]
fn rod_options_without_a_rod_are_refused() {
    for args in [
        ["cells", "--modes", "2"],
        ["cells", "--diameter-mm", "6"],
        ["cells", "--material", "steel"],
        ["cells", "--reduction", "pole-zero"],
        ["cells", "--inner-diameter-mm", "2"],
    ] {
        let out = common::woodpile().args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("--rod"), "{args:?}: {stderr}");
    }
}
