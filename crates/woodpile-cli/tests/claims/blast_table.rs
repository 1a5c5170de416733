//! Claim: a blast given as a CSV table (header `time_s,force_n`, path relative to the scenario
//! file) runs and matches the Friedlander profile it samples (1 µs table of the default pulse:
//! linear interpolation changes the transmitted peak by far less than 1 %); a malformed table is
//! refused with exit 2 naming the file and the line.

use crate::common;

const SCENARIO: &str = "[chain]\nrods_mm = [20, 40, 80]\n[excitation]\nkind = \"blast\"\nprofile = \"table\"\nfile = \"loads/load.csv\"\n[run]\nduration_s = 5e-4\n";

fn friedlander_csv() -> String {
    let mut s = String::from("time_s,force_n\n");
    for k in 0..=200 {
        let t = k as f64 * 1e-6;
        let x = t / 2e-4;
        s.push_str(&format!("{t:e},{:e}\n", 200.0 * (1.0 - x) * (-x).exp()));
    }
    s
}

#[test]
fn table_matches_friedlander() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("case");
    std::fs::create_dir_all(sub.join("loads")).unwrap();
    common::write(&sub.join("loads"), "load.csv", &friedlander_csv());
    common::write(&sub, "table.toml", SCENARIO);
    common::write(
        &sub,
        "fr.toml",
        &SCENARIO.replace("profile = \"table\"\nfile = \"loads/load.csv\"\n", ""),
    );
    // Run from the parent directory: the table path is relative to the scenario file.
    for (file, out) in [("case/table.toml", "t"), ("case/fr.toml", "f")] {
        let o = common::run_in(dir.path(), &["simulate", file, "--out", out, "-q"]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let t = common::json(&dir.path().join("t/summary.json"));
    let f = common::json(&dir.path().join("f/summary.json"));
    let (a, b) = (
        t["transmitted_peak_force_n"].as_f64().unwrap(),
        f["transmitted_peak_force_n"].as_f64().unwrap(),
    );
    assert!((a / b - 1.0).abs() < 1e-2, "table {a} vs friedlander {b}");
}

fn bad_table(csv: &str, expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("loads")).unwrap();
    common::write(&dir.path().join("loads"), "load.csv", csv);
    common::write(dir.path(), "s.toml", SCENARIO);
    let o = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "out"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    for e in expected {
        assert!(stderr.contains(e), "expected `{e}` in {stderr}");
    }
    assert!(!dir.path().join("out").exists());
}

#[test]
fn malformed_tables_name_the_line() {
    bad_table(
        "time_s,force_n\n0,0\n1e-5,abc\n",
        &["load.csv", "line 3", "abc"],
    );
    bad_table(
        "time_s,force_n\n0,0\n2e-5,10\n1e-5,5\n",
        &["load.csv", "line 4", "increase"],
    );
    bad_table("t,F\n0,0\n1e-5,1\n", &["line 1", "time_s,force_n"]);
    bad_table("time_s,force_n\n0,0\n1e-5\n", &["line 3", "2"]);
    bad_table("time_s,force_n\n0,0\n", &["at least two"]);
}
