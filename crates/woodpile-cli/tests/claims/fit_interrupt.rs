//! Claim: Ctrl-C (SIGINT) during `woodpile fit` stops the fit at its next model run, writes the
//! best point so far (`fit.json` with `"interrupted": true`, estimates but no standard errors,
//! `fitted.toml`, `residuals.csv`) and exits 130.
//!
//! Tolerance: none (what is checked is present or absent).

use crate::common;
use std::io::{BufRead, BufReader};

const MODEL: &str =
    "[chain]\nrods_mm = [80, 40, 20]\n[excitation]\nvelocity_m_s = 2.0\n[run]\nduration_s = 3e-4\n";
// 500 starts: minutes of work, so the signal arrives mid-fit.
const FIT: &str = r#"scenario = "model.toml"
[[data]]
file = "truth/forces.csv"
signals = { contact_3_n = "contact_3_n" }
[fit]
parameters = [{ key = "excitation.velocity_m_s", bounds = [1.5, 2.5] }]
starts = 500
"#;

#[test]
fn ctrl_c_keeps_the_best_point_so_far() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    common::write(d, "model.toml", MODEL);
    common::write(d, "fit.toml", FIT);
    let sim = common::run_in(d, &["simulate", "model.toml", "--out", "truth", "-q"]);
    assert!(
        sim.status.success(),
        "{}",
        String::from_utf8_lossy(&sim.stderr)
    );
    let mut child = common::woodpile()
        .current_dir(d)
        .args(["fit", "fit.toml", "--out", "out", "--threads", "1"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // The first progress line comes with the first model run: the fit is under way.
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut first = String::new();
    stderr.read_line(&mut first).unwrap();
    assert!(first.contains("fit"), "{first}");
    let killed = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut rest).unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{first}{rest}");
    assert!(rest.contains("best point so far"), "{rest}");
    let json = common::json(&d.join("out/fit.json"));
    assert_eq!(json["interrupted"], true);
    let p = &json["parameters"][0];
    assert!(p["estimate"]
        .as_f64()
        .is_some_and(|v| (1.5..=2.5).contains(&v)));
    assert!(p["std_error"].is_null(), "{p}");
    assert!(json["starts"].as_array().unwrap().len() < 500);
    assert!(d.join("out/fitted.toml").is_file() && d.join("out/residuals.csv").is_file());
}
