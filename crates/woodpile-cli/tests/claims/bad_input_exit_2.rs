//! Claim: bad input — a TOML syntax error, an unknown key, an unknown rod length, material or
//! scenario name, a negative, zero or non-finite value, a time step not smaller than the duration,
//! mutually exclusive keys, a missing table file — exits with code 2 and one message on stderr
//! that starts with `error:` and names the offending key (or the line of a syntax error), and
//! leaves no output directory (complete-looking or partial) behind.

use crate::common;

fn case(name: &str, scenario: &str, expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "s.toml", scenario);
    let out = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
    assert!(stderr.starts_with("error: "), "{name}: {stderr}");
    for e in expected {
        assert!(stderr.contains(e), "{name}: expected `{e}` in: {stderr}");
    }
    assert!(!dir.path().join("out").exists(), "{name}: output dir left");
    assert!(
        common::leftovers(dir.path()).is_empty(),
        "{name}: staging left"
    );
}

#[test]
fn syntax_error_gives_line_and_column() {
    case(
        "syntax",
        "[chain]\nrods_mm = [20, 30\n",
        &["line 2", "column"],
    );
}

#[test]
fn unknown_keys_are_refused() {
    case(
        "top",
        "[chain]\nrods_mm = [20]\n[runn]\n",
        &["unknown field `runn`"],
    );
    case(
        "chain",
        "[chain]\nrods_mm = [20]\nrods = 1\n",
        &["line 3", "unknown field `rods`"],
    );
    case(
        "element",
        "[chain]\nelements = [{ rod_mm = 20, colour = \"red\" }]\n",
        &["unknown field `colour`"],
    );
    case(
        "run",
        "[chain]\nrods_mm = [20]\n[run]\ndt = 1e-7\n",
        &["unknown field `dt`", "time_step_s"],
    );
}

#[test]
fn unknown_names_list_the_valid_ones() {
    case(
        "rod",
        "[chain]\nrods_mm = [20, 30, 40, 45]\n",
        &["chain.rods_mm[3]", "45", "20, 30, 40, 50, 60, 70, 80"],
    );
    case(
        "material",
        "[chain]\nrods_mm = [20]\n[wall]\nmaterial = \"unobtainium\"\n",
        &["wall.material", "unobtainium", "stainless-steel"],
    );
    case(
        "element kind",
        "[chain]\nelements = [{ kind = \"cube\" }]\n",
        &["unknown variant `cube`", "sphere"],
    );
    let dir = tempfile::tempdir().unwrap();
    let out = common::run_in(dir.path(), &["simulate", "--scenario", "paper-impact-9mm"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("paper-impact-9mm") && stderr.contains("paper-impact-20mm"));
    assert!(!dir.path().join("runs").exists());
    let out = common::run_in(dir.path(), &["scenario", "nope"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn bad_numbers_name_the_field() {
    let base = "[chain]\nrods_mm = [20, 40]\n";
    case(
        "negative height",
        &format!("{base}[excitation]\ndrop_height_m = -0.2\n"),
        &["excitation.drop_height_m", "-0.2", "> 0"],
    );
    case(
        "zero duration",
        &format!("{base}[run]\nduration_s = 0.0\n"),
        &["run.duration_s", "> 0"],
    );
    case(
        "nan",
        &format!("{base}[run]\nsample_interval_s = nan\n"),
        &["run.sample_interval_s", "nan"],
    );
    case(
        "inf",
        &format!("{base}[wall]\ncap_radius_mm = inf\n"),
        &["wall.cap_radius_mm", "inf"],
    );
    case(
        "time step",
        &format!("{base}[run]\nduration_s = 1e-6\nsample_interval_s = 1e-6\ntime_step_s = 1e-6\n"),
        &["run.time_step_s", "smaller than run.duration_s"],
    );
    case(
        "cell mass",
        "[chain]\nelements = [{ kind = \"rod\", length_mm = 45.0, cell = { primary_mass_g = -1.0 } }]\n",
        &["chain.elements[0].cell.primary_mass_g"],
    );
    case(
        "poisson",
        "[chain]\nrods_mm = [20]\n[excitation]\nstriker = { material = { name = \"x\", youngs_modulus_pa = 1e9, poisson_ratio = 0.7, density_kg_m3 = 1000.0 } }\n",
        &["excitation.striker.material.poisson_ratio", "0.7"],
    );
    case(
        "contact index",
        &format!("{base}contact_beta = [{{ contact = 5, beta = 1e9 }}]\n"),
        &["chain.contact_beta[0].contact", "1..=2"],
    );
    case(
        "rod length type",
        "[chain]\nrods_mm = [20, -40]\n",
        &["line 2", "-40"],
    );
}

#[test]
fn conflicting_keys_are_refused() {
    case(
        "rods and elements",
        "[chain]\nrods_mm = [20]\nelements = [{ rod_mm = 20 }]\n",
        &["rods_mm", "elements", "not both"],
    );
    case(
        "height and velocity",
        "[chain]\nrods_mm = [20]\n[excitation]\ndrop_height_m = 0.2\nvelocity_m_s = 2.0\n",
        &["excitation.velocity_m_s", "drop_height_m"],
    );
    case(
        "blast key on impact",
        "[chain]\nrods_mm = [20]\n[excitation]\npeak_force_n = 100.0\n",
        &["excitation.peak_force_n", "impact"],
    );
    case(
        "rtol with rk4",
        "[chain]\nrods_mm = [20]\n[run]\nrtol = 1e-8\n",
        &["run.rtol", "rk4"],
    );
    case(
        "rod on a flat",
        "[chain]\nrods_mm = [20]\n[wall]\nkind = \"flat\"\n",
        &["wall.kind", "line contact", "cap_radius_mm"],
    );
    case("no rods", "[chain]\n", &["chain", "rods_mm"]);
    case(
        "empty chain",
        "[chain]\nrods_mm = []\n",
        &["chain.rods_mm", "at least one"],
    );
}

#[test]
fn missing_table_file_names_the_key_and_path() {
    case(
        "missing table",
        "[chain]\nrods_mm = [20]\n[excitation]\nkind = \"blast\"\nprofile = \"table\"\nfile = \"load.csv\"\n",
        &["excitation.file", "load.csv"],
    );
}

#[test]
fn missing_scenario_file_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let out = common::run_in(dir.path(), &["simulate", "nowhere.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("nowhere.toml"));
}
