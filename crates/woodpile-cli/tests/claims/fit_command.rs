//! Claim: `woodpile fit` recovers, from noise-free signals that `woodpile simulate` wrote for a
//! known scenario (restitution 0.85, impact speed 1.98 m/s, the wall's β as computed), the
//! restitution, the speed and a wall-β scale of 1 to 1e-6 relative, starting from 0.8, 2.0 m/s
//! and the bounds' middle; and `woodpile simulate fitted.toml` reproduces the fitted model
//! curve of residuals.csv to 1e-9 of the signal's peak. A figure per signal and the correlation
//! matrix are drawn.
//!
//! Tolerance: the data are the model itself on the same RK4 steps, so the optimum is the truth
//! (the optimiser stops at a relative tolerance of 1e-10); fitted.toml holds the estimates with
//! every digit, and the simulated samples fall on the measured times, where the fit's
//! interpolation returns its samples exactly: only the ~1e-10 estimate error remains.

use crate::common;

const TRUTH: &str = "[chain]\nrods_mm = [80, 40, 20]\n[excitation]\nvelocity_m_s = 1.98\n[damping]\ncontact = \"restitution\"\nrestitution = 0.85\n[run]\nduration_s = 3e-4\n";
const MODEL: &str = "[chain]\nrods_mm = [80, 40, 20]\n[excitation]\nvelocity_m_s = 2.0\n[damping]\ncontact = \"restitution\"\nrestitution = 0.8\n[run]\nduration_s = 3e-4\n";
const FIT: &str = r#"scenario = "model.toml"
[[data]]
file = "truth/forces.csv"
signals = { contact_3_n = "contact_3_n" }
[[data]]
file = "truth/velocities.csv"
signals = { element_1_m_s = "element_1_m_s" }
[fit]
parameters = [
  { key = "damping.restitution", bounds = [0.6, 1.0] },
  { key = "contact_beta_scale.wall", bounds = [0.5, 2.0] },
  { key = "excitation.velocity_m_s", bounds = [1.5, 2.5] },
]
starts = 1
"#;

fn column(path: &std::path::Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let k = lines
        .next()
        .unwrap()
        .split(',')
        .position(|c| c == name)
        .unwrap();
    lines
        .map(|l| l.split(',').nth(k).unwrap().parse().unwrap())
        .collect()
}

#[test]
fn fit_recovers_a_simulated_scenario_and_fitted_toml_reproduces_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    common::write(d, "truth.toml", TRUTH);
    common::write(d, "model.toml", MODEL);
    common::write(d, "fit.toml", FIT);
    let sim = common::run_in(d, &["simulate", "truth.toml", "--out", "truth", "-q"]);
    assert!(
        sim.status.success(),
        "{}",
        String::from_utf8_lossy(&sim.stderr)
    );
    let fit = common::run_in(d, &["fit", "fit.toml", "--out", "out"]);
    assert!(
        fit.status.success(),
        "{}",
        String::from_utf8_lossy(&fit.stderr)
    );
    let json = common::json(&d.join("out/fit.json"));
    for (k, truth) in [0.85, 1.0, 1.98].iter().enumerate() {
        let p = &json["parameters"][k];
        let estimate = p["estimate"].as_f64().unwrap();
        assert!(
            ((estimate - truth) / truth).abs() < 1e-6,
            "{}: {estimate} vs {truth}",
            p["key"]
        );
        assert!(p["ci95"][0].as_f64().is_some() && p["std_error"].as_f64().is_some());
    }
    assert_eq!(json["residual_rms"].as_array().unwrap().len(), 2);
    for figure in [
        "fit_contact_3_n.png",
        "fit_contact_3_n.svg",
        "fit_element_1_m_s.png",
        "correlation.png",
        "correlation.svg",
    ] {
        assert!(
            d.join("out/plots").join(figure).is_file(),
            "no figure {figure}"
        );
    }
    assert!(
        json["warnings"].as_array().unwrap().is_empty(),
        "{}",
        json["warnings"]
    );
    // simulate fitted.toml: its wall force at the measured times is the fit's model curve.
    let rerun = common::run_in(d, &["simulate", "out/fitted.toml", "--out", "rerun", "-q"]);
    assert!(
        rerun.status.success(),
        "{}",
        String::from_utf8_lossy(&rerun.stderr)
    );
    let simulated = column(&d.join("rerun/forces.csv"), "contact_3_n");
    let text = std::fs::read_to_string(d.join("out/residuals.csv")).unwrap();
    let fitted: Vec<f64> = text
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(1) == Some("contact_3_n"))
        .map(|l| l.split(',').nth(4).unwrap().parse().unwrap())
        .collect();
    assert_eq!(simulated.len(), fitted.len());
    let peak = fitted.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let worst = simulated
        .iter()
        .zip(&fitted)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        worst < 1e-9 * peak,
        "fitted.toml differs by {worst:e} N (peak {peak:e} N)"
    );
}
