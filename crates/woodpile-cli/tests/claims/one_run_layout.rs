//! Claim: a lattice's run directory is a chain's run directory with its geometry added
//! (docs/reference/outputs.md). Both `run.json` carry the format `woodpile-run/1` and say their
//! `structure` (`chain`, `lattice`); both `summary.json` hold the same figures under the same keys
//! — `energy` (`initial_j`, `final_j`, `input_work_j`, `dissipated_j`, `max_relative_error`) and
//! `integrator` (`method`, `steps`, `rhs_evaluations`, `rejected_steps`) nested, the peaks, the
//! ratio, `wave_arrived`, `energy_balance_ok`, `wall_time_s` — so one script reads either. For
//! both, the ratio is the transmitted peak over the incident one (no static load here: to 1e-12,
//! rounding of one division) and `energy.final_j` is the last row of `energy.csv`'s `total_j`
//! (to 1e-9 relative: the CSV's printed digits). One accuracy rule refuses an inaccurate run of
//! either structure with the same words: DOPRI5 at rtol 3e-3, atol 1e-3 on `lattice_run`'s
//! lattice leaves its energy balance off by 2.4e3 of E(0) (measured; far above the 1e-2 limit),
//! so the run exits 1 with nothing written, and the message names the reference energy and the
//! fix as the chain's does.

use crate::common;
use crate::lattice_run::LATTICE;

const CHAIN: &str = "[chain]\nrods_mm = [80, 40, 20]\n[run]\nduration_s = 3e-4\n";

/// The keys both structures' summaries must hold, nested ones as `outer.inner`.
const SHARED_KEYS: &[&str] = &[
    "scenario",
    "structure",
    "excitation",
    "n_samples",
    "incident_peak_force_n",
    "transmitted_peak_force_n",
    "transmission_ratio",
    "wave_arrived",
    "energy_balance_ok",
    "contact_peak_forces_n",
    "contact_peak_times_s",
    "energy.initial_j",
    "energy.final_j",
    "energy.input_work_j",
    "energy.dissipated_j",
    "energy.max_relative_error",
    "integrator.method",
    "integrator.steps",
    "integrator.rhs_evaluations",
    "integrator.rejected_steps",
    "wall_time_s",
];

fn at<'a>(v: &'a serde_json::Value, dotted: &str) -> &'a serde_json::Value {
    dotted.split('.').fold(v, |v, k| &v[k])
}

/// The last `total_j` of `energy.csv`.
fn last_total_j(dir: &std::path::Path) -> f64 {
    let text = std::fs::read_to_string(dir.join("energy.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header
        .iter()
        .position(|&h| h == "total_j")
        .expect("total_j");
    let last = lines.last().unwrap();
    last.split(',').nth(column).unwrap().parse().unwrap()
}

#[test]
fn chains_and_lattices_write_one_layout() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "lat.toml", LATTICE);
    common::write(dir.path(), "chain.toml", CHAIN);
    for (file, structure) in [("chain.toml", "chain"), ("lat.toml", "lattice")] {
        let out = common::run_in(dir.path(), &["simulate", file, "--out", structure, "-q"]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let run_dir = dir.path().join(structure);
        let run = common::json(&run_dir.join("run.json"));
        assert_eq!(run["format"], "woodpile-run/1");
        assert_eq!(run["structure"], structure);
        let s = common::json(&run_dir.join("summary.json"));
        for key in SHARED_KEYS {
            assert!(
                !at(&s, key).is_null(),
                "{structure}: summary.json lacks {key}: {s}"
            );
        }
        assert_eq!(s["structure"], structure);
        assert_eq!(s["excitation"], "impact");
        let (incident, transmitted) = (
            s["incident_peak_force_n"].as_f64().unwrap(),
            s["transmitted_peak_force_n"].as_f64().unwrap(),
        );
        let ratio = s["transmission_ratio"].as_f64().unwrap();
        assert!(
            (ratio - transmitted / incident).abs() <= 1e-12 * ratio,
            "{structure}: ratio {ratio}, peaks {transmitted} / {incident}"
        );
        let final_j = at(&s, "energy.final_j").as_f64().unwrap();
        let csv = last_total_j(&run_dir);
        assert!(
            (final_j - csv).abs() <= 1e-9 * final_j.abs(),
            "{structure}: energy.final_j {final_j}, energy.csv {csv}"
        );
    }
}

#[test]
fn one_accuracy_rule_refuses_an_inaccurate_lattice_as_a_chain() {
    let dir = tempfile::tempdir().unwrap();
    let coarse = LATTICE.replace(
        "[run]\n",
        "[run]\nintegrator = \"dopri5\"\nrtol = 3e-3\natol = 1e-3\n",
    );
    common::write(dir.path(), "lat.toml", &coarse);
    let out = common::run_in(dir.path(), &["simulate", "lat.toml", "--out", "o"]);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("inaccurate run")
            && stderr.contains("of the larger of the initial energy and the largest work done")
            && stderr.contains("run.time_step_s")
            && stderr.contains("--allow-inaccurate"),
        "{stderr}"
    );
    assert!(!dir.path().join("o").exists(), "nothing written");
}
