//! Claim: bad input to `woodpile fit` — a measured CSV whose time does not increase, a NaN or an
//! empty field (a gap), a column mapped to no model output, a column missing from the file, a
//! contact the chain does not have, bounds with lower ≥ upper, a parameter key that is not a
//! number or not a key at all, a CSV header naming a column twice or a row of another length
//! than the header (either would be read silently as something else), no parameter at all or
//! one key fitted twice, an element's key of a chain given as `rods_mm`, a record or time-shift
//! bounds so long that every model run would exceed the 1e9-step limit (rather than "the model
//! failed to run at every start point") — exits with code 2, one message that starts with
//! `error:` and names the file and row, or the key as written in the fit file; no output is
//! written.

use crate::common;

const MODEL: &str = "[chain]\nrods_mm = [80, 40]\n[run]\nduration_s = 1e-4\n";
const CSV: &str = "time_s,sensor_n\n0,0\n1e-6,0.5\n2e-6,1.0\n3e-6,1.5\n";

fn fit_file(signals: &str, parameters: &str) -> String {
    format!(
        "scenario = \"model.toml\"\n[[data]]\nfile = \"measured.csv\"\nsignals = {signals}\n[fit]\nparameters = [{parameters}]\nstarts = 1\n"
    )
}

fn case(name: &str, csv: &str, fit: &str, expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "model.toml", MODEL);
    common::write(dir.path(), "measured.csv", csv);
    common::write(dir.path(), "fit.toml", fit);
    let out = common::run_in(dir.path(), &["fit", "fit.toml", "--out", "out"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
    assert!(stderr.starts_with("error: "), "{name}: {stderr}");
    for e in expected {
        assert!(stderr.contains(e), "{name}: expected `{e}` in: {stderr}");
    }
    assert!(!dir.path().join("out").exists(), "{name}: output written");
}

const GOOD_SIGNALS: &str = "{ sensor_n = \"contact_2_n\" }";
const GOOD_PARAMETER: &str = "{ key = \"excitation.velocity_m_s\", bounds = [1.5, 2.5] }";

#[test]
fn bad_rows_name_the_file_and_the_line() {
    let backwards = "time_s,sensor_n\n0,0\n2e-6,0.5\n1e-6,1.0\n";
    let fit = fit_file(GOOD_SIGNALS, GOOD_PARAMETER);
    case(
        "time",
        backwards,
        &fit,
        &["measured.csv, line 4", "does not increase"],
    );
    let nan = "time_s,sensor_n\n0,0\n1e-6,NaN\n2e-6,1.0\n";
    case(
        "nan",
        nan,
        &fit,
        &["measured.csv, line 3", "sensor_n is NaN", "gap"],
    );
    let gap = "time_s,sensor_n\n0,0\n1e-6,\n2e-6,1.0\n";
    case(
        "gap",
        gap,
        &fit,
        &["measured.csv, line 3", "sensor_n is empty"],
    );
    let text = "time_s,sensor_n\n0,0\n1e-6,high\n2e-6,1.0\n";
    case(
        "text",
        text,
        &fit,
        &["measured.csv, line 3", "`high` is not a finite number"],
    );
}

#[test]
fn signals_must_name_a_column_and_a_model_output() {
    let params = GOOD_PARAMETER;
    case(
        "output",
        CSV,
        &fit_file("{ sensor_n = \"wall_force\" }", params),
        &["data[0].signals.sensor_n", "wall_force", "contact_N_n"],
    );
    case(
        "contact",
        CSV,
        &fit_file("{ sensor_n = \"contact_7_n\" }", params),
        &["data[0].signals.sensor_n", "contacts 0..=2"],
    );
    case(
        "column",
        CSV,
        &fit_file("{ load_n = \"contact_2_n\" }", params),
        &["measured.csv, line 1", "no column `load_n`"],
    );
}

#[test]
fn parameters_must_be_numeric_keys_with_ordered_bounds() {
    let fit = |p: &str| fit_file(GOOD_SIGNALS, p);
    case(
        "bounds",
        CSV,
        &fit("{ key = \"excitation.velocity_m_s\", bounds = [2.5, 1.5] }"),
        &["fit.parameters[0].bounds", "[2.5, 1.5]", "lower < upper"],
    );
    case(
        "equal bounds",
        CSV,
        &fit("{ key = \"excitation.velocity_m_s\", bounds = [2.0, 2.0] }"),
        &["fit.parameters[0].bounds"],
    );
    case(
        "not numeric",
        CSV,
        &fit("{ key = \"chain.model\", bounds = [0, 1] }"),
        &["fit.parameters[0].key", "chain.model", "not a number"],
    );
    case(
        "unknown key",
        CSV,
        &fit("{ key = \"excitation.speed\", bounds = [0, 1] }"),
        &["fit.parameters[0].key", "excitation.speed", "not a key"],
    );
    case(
        "scale",
        CSV,
        &fit("{ key = \"contact_beta_scale.floor\", bounds = [0.5, 2] }"),
        &["fit.parameters[0].key", "striker, inner or wall"],
    );
}

#[test]
fn ambiguous_files_and_parameter_lists_are_refused() {
    let fit = fit_file(GOOD_SIGNALS, GOOD_PARAMETER);
    let twice = "time_s,sensor_n,sensor_n\n0,0,1\n1e-6,0.5,1\n2e-6,1.0,1\n";
    case(
        "duplicate column",
        twice,
        &fit,
        &["measured.csv, line 1", "`sensor_n` twice"],
    );
    let ragged = "time_s,sensor_n\n0,0\n1e-6,0.5,7\n2e-6,1.0\n";
    case(
        "ragged row",
        ragged,
        &fit,
        &["measured.csv, line 3", "has 3 fields and the header 2"],
    );
    case(
        "no parameter",
        CSV,
        &fit_file(GOOD_SIGNALS, ""),
        &["fit.parameters = []", "at least one parameter"],
    );
    case(
        "a key twice",
        CSV,
        &fit_file(GOOD_SIGNALS, &format!("{GOOD_PARAMETER}, {GOOD_PARAMETER}")),
        &[
            "fit.parameters[1].key",
            "fit.parameters[0] fits this key already",
        ],
    ); // The chain is `rods_mm`: there is no `elements` list to index (not "0 entries").
    case(
        "an element of a rods_mm chain",
        CSV,
        &fit_file(
            GOOD_SIGNALS,
            "{ key = \"chain.elements[99].diameter_mm\", bounds = [1.0, 2.0] }",
        ),
        &["chain.elements[99].diameter_mm", "given as rods_mm"],
    );
}

#[test]
fn records_too_long_to_model_name_the_data_or_the_shift() {
    let params = GOOD_PARAMETER;
    case(
        "a record of 1e6 s",
        "time_s,sensor_n\n0,0\n1e6,1\n",
        &fit_file(GOOD_SIGNALS, params),
        &["invalid data = measured.csv", "1.000e13 steps"],
    );
    let shifted =
        fit_file(GOOD_SIGNALS, params) + "time_shift_s = { bounds = [-1000.0, 1000.0] }\n";
    case(
        "shifts of 1000 s",
        CSV,
        &shifted,
        &["fit.time_shift_s.bounds = [-1000, 1000]", "steps"],
    );
}
