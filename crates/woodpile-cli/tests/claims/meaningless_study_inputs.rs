//! Claim: inputs that would make a study or a fit print numbers that mean nothing are refused
//! (exit 2) or warned about, naming the option or key as written:
//!
//! - a distribution that draws values the scenario refuses (`rod_length_mm = { sd = 1e6 }`: rods
//!   of negative length; a negative speed range) names the `[uncertainty]` key, the column and row
//!   of `samples.csv` and the value, not the scenario key the value was written into.
//! - negative `--samples`, `--base-samples`, `--seed`: refused naming the flag.
//! - `sensitivity --base-samples 1`: a bootstrap over one point gives intervals of ±1e-15; the
//!   fewest is 8, and the refusal says why.
//! - an empty `[uncertainty]` given to `simulate --samples`: every sample would be the nominal
//!   scenario.
//! - a fit whose signal is rounding noise (peaks of 1e-12 N against a model that peaks at about
//!   200 N), refused as an all-zero signal is; and `fit.max_evaluations = 0`.
//! - NSGA-II with `reference_point = [-1, -1]` (below every positive objective): a hypervolume
//!   of 0 at every generation, so it warns.
//! - `plot` of a lattice study draws its front, and refuses a `pareto.csv` with a NaN objective
//!   naming the line and the column.

use crate::common;

fn run(files: &[(&str, &str)], args: &[&str]) -> (Option<i32>, String, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        common::write(dir.path(), name, text);
    }
    let out = common::run_in(dir.path(), args);
    let text = String::from_utf8_lossy(&out.stderr).into_owned();
    (out.status.code(), text, dir)
}

fn refused(files: &[(&str, &str)], args: &[&str], needles: &[&str]) {
    let (code, stderr, dir) = run(files, args);
    assert_eq!(code, Some(2), "{args:?}: {stderr}");
    for n in needles {
        assert!(stderr.contains(n), "expected `{n}` in: {stderr}");
    }
    assert!(!dir.path().join("o").exists(), "{args:?}: output written");
}

const SCATTERED: &str = "[chain]\nrods_mm = [40, 30, 20]\n[run]\nduration_s = 2e-4\n[uncertainty]\nimpact_velocity_m_s = { uniform = [1.8, 2.2] }\n";

#[test]
fn a_draw_the_scenario_refuses_names_the_uncertainty_key() {
    let chain = "[chain]\nelements = [{ kind = \"rod\", length_mm = 40 }, { kind = \"rod\", length_mm = 30 }]\n[run]\nduration_s = 2e-4\n[uncertainty]\n";
    for (scatter, key, column) in [
        (
            "rod_length_mm = { sd = 1e6 }",
            "uncertainty.rod_length_mm",
            "rod_length_mm[1] = -",
        ),
        (
            "impact_velocity_m_s = { uniform = [-2.0, -1.0] }",
            "uncertainty.impact_velocity_m_s",
            "impact_velocity_m_s = -",
        ),
    ] {
        refused(
            &[("s.toml", &format!("{chain}{scatter}\n"))],
            &["simulate", "s.toml", "--samples", "16", "--out", "o"],
            &[key, column, "row 1 of samples.csv", "must be narrowed"],
        );
    }
}

#[test]
fn negative_counts_name_their_flag() {
    // clap's own refusal, naming the flag, rather than "unexpected argument '-3'" and a tip to
    // pass it after `--`.
    for args in [
        &["simulate", "s.toml", "--samples", "-3", "--out", "o"][..],
        &[
            "sensitivity",
            "s.toml",
            "--base-samples",
            "-4",
            "--out",
            "o",
        ][..],
        &["sensitivity", "s.toml", "--seed", "-1", "--out", "o"][..],
    ] {
        let flag = args[2];
        refused(&[("s.toml", SCATTERED)], args, &[flag]);
        let (_, stderr, _dir) = run(&[("s.toml", SCATTERED)], args);
        assert!(!stderr.contains("unexpected argument"), "{stderr}");
    }
}

#[test]
fn one_base_sample_is_refused_with_the_minimum_and_why() {
    refused(
        &[("s.toml", SCATTERED)],
        &["sensitivity", "s.toml", "--base-samples", "1", "--out", "o"],
        &["--base-samples = 1", "at least 8", "bootstrap"],
    );
}

#[test]
fn an_empty_uncertainty_table_is_refused_for_samples() {
    let empty = "[chain]\nrods_mm = [40, 30, 20]\n[run]\nduration_s = 2e-4\n[uncertainty]\n";
    refused(
        &[("s.toml", empty)],
        &["simulate", "s.toml", "--samples", "4", "--out", "o"],
        &["uncertainty", "at least one scattered parameter"],
    );
}

const MODEL: &str = "[chain]\nrods_mm = [80, 40]\n[run]\nduration_s = 1e-4\n";

fn fit_file(extra: &str) -> String {
    format!(
        "scenario = \"model.toml\"\n[[data]]\nfile = \"m.csv\"\nsignals = {{ sensor_n = \"contact_2_n\" }}\n[fit]\nparameters = [{{ key = \"excitation.velocity_m_s\", bounds = [1.5, 2.5] }}]\nstarts = 1\n{extra}"
    )
}

#[test]
fn a_fit_to_rounding_noise_is_refused_naming_the_signal() {
    let noise = "time_s,sensor_n\n0,1e-12\n1e-6,-2e-12\n";
    refused(
        &[
            ("model.toml", MODEL),
            ("m.csv", noise),
            ("f.toml", &fit_file("")),
        ],
        &["fit", "f.toml", "--out", "o"],
        &["data[0].signals.sensor_n", "m.csv", "rounding noise"],
    );
    let csv = "time_s,sensor_n\n0,0\n1e-6,0.5\n2e-6,1.0\n";
    refused(
        &[
            ("model.toml", MODEL),
            ("m.csv", csv),
            ("f.toml", &fit_file("max_evaluations = 0\n")),
        ],
        &["fit", "f.toml", "--out", "o"],
        &["fit.max_evaluations = 0", "at least 1"],
    );
}

#[test]
fn a_reference_point_below_the_front_warns_that_the_hypervolume_means_nothing() {
    let config = "[design]\npositions = 4\ncatalogue_mm = [20, 40, 60]\n[run]\nduration_s = 3e-4\npeak_tolerance = 1e-4\n[ga]\nobjectives = [\"transmitted-force\", \"total-mass\"]\npopulation = 8\ngenerations = 2\nreference_point = [-1.0, -1.0]\n";
    let (code, stderr, _dir) = run(
        &[("mo.toml", config)],
        &["optimize", "mo.toml", "--out", "o", "--quiet"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("warning: the hypervolume is 0"), "{stderr}");
    assert!(stderr.contains("ga.reference_point"), "{stderr}");
}

const LATTICE_STUDY: &str = r#"[lattice]
layers = [
  { rods = 3, pitch_mm = 16.0, length_mm = 60.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 3 },
]
rod = { fe_elements = 2 }
[run]
duration_s = 1e-4
peak_tolerance = 1e-4
[design]
length_mm = [50.0, 60.0, 70.0]
[ga]
population = 6
generations = 2
seed = 5
"#;

#[test]
fn plot_draws_a_lattice_study_and_refuses_a_nan_objective() {
    let (code, stderr, dir) = run(
        &[("ls.toml", LATTICE_STUDY)],
        &["optimize", "ls.toml", "--out", "lo", "--quiet"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    let out = common::run_in(dir.path(), &["plot", "lo", "--quiet"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.path().join("lo/plots/pareto_front.png").is_file());
    assert!(dir.path().join("lo/plots/hypervolume.png").is_file());
    let csv = dir.path().join("lo/pareto.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let rest = lines[1].split_once(',').unwrap().1.to_string();
    lines[1] = format!("NaN,{rest}");
    std::fs::write(&csv, lines.join("\n") + "\n").unwrap();
    let out = common::run_in(dir.path(), &["plot", "lo"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    for n in ["pareto.csv, line 2", "transmitted-force", "NaN"] {
        assert!(stderr.contains(n), "expected `{n}` in: {stderr}");
    }
}
