//! Claim: NSGA-II with `[ga] robust` minimises, for each figure of a run, the statistic of its
//! values over the config's `[uncertainty]` samples, and the front it reports is exactly that:
//! for every design of the final front, `pareto.csv`'s transmitted-force equals the type-7 0.95
//! quantile of its 4 samples re-simulated one by one with `woodpile simulate` (the samples
//! drawn by `woodpile simulate pareto/NNN.toml --samples 4` with the same `[uncertainty]`, each
//! `samples/NNN.toml` run on its own), computed here by hand, to 1e-12 relative (the
//! quantile's interpolation); `robust/NNN.csv` holds those forces and the drawn values bit for
//! bit; every front design has the same drawn angles and speeds (common random numbers; the
//! lengths are drawn about each design's own rods); total-mass is
//! the nominal design's (rod lengths are scattered, so a sample's mass would differ). A third
//! objective, max-contact-pressure, gets its own column in `robust/NNN.csv` (written with
//! round-trip precision), and `pareto.csv`'s value is the same quantile of that column.
//! 3 positions of rods of 20, 40 and 60 mm (`rod_range`), population 6 × 3 generations, runs of 0.2 ms at peak
//! tolerance 1e-5; lengths, angle and speed scattered.

use crate::common;
use std::path::Path;
use woodpile_io::optimize::{OptimizeConfig, Problem};

const UNCERTAINTY: &str = "[uncertainty]\nsamples = 4\nrod_length_mm = { sd = 0.2 }\n\
crossing_angle_deg = { sd = 2.0 }\nimpact_velocity_m_s = { uniform = [1.8, 2.2] }\n";

const CONFIG: &str =
    "[design]\npositions = 3\nrod_range = { from_mm = 20.0, to_mm = 60.0, step_mm = 20.0 }\n\
[run]\nduration_s = 2e-4\npeak_tolerance = 1e-5\n\
[ga]\nobjectives = [\"transmitted-force\", \"total-mass\", \"max-contact-pressure\"]\npopulation = 6\ngenerations = 3\n\
robust = \"quantile:0.95\"\n";

/// Header and rows of a CSV file.
fn table(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (header, rows)
}

/// The column `name` of a table, parsed.
fn column(table: &(Vec<String>, Vec<Vec<String>>), name: &str) -> Vec<f64> {
    let j = table.0.iter().position(|h| h == name).unwrap();
    table.1.iter().map(|r| r[j].parse().unwrap()).collect()
}

/// Type-7 quantile at 0.95 of 4 values: h = (n − 1) p = 2.85.
fn quantile_95(values: &[f64]) -> f64 {
    let mut x = values.to_vec();
    x.sort_by(f64::total_cmp);
    x[2] + 0.85 * (x[3] - x[2])
}

fn simulate(d: &Path, args: &[&str]) {
    let out = common::run_in(d, args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn front_robust_values_are_the_statistic_of_their_samples_rerun() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = format!("{CONFIG}{UNCERTAINTY}");
    common::write(d, "c.toml", &text);
    simulate(d, &["optimize", "c.toml", "--out", "o", "-q"]);
    let pareto = table(&d.join("o/pareto.csv"));
    let summary = common::json(&d.join("o/summary.json"));
    let front = summary["front"].as_array().unwrap();
    assert_eq!(front.len(), pareto.1.len());
    assert!(!front.is_empty());
    let problem = Problem::new(&OptimizeConfig::parse(&text, "c.toml").unwrap(), d, 1).unwrap();

    let mut draws: Option<Vec<Vec<u64>>> = None;
    for (k, design) in front.iter().enumerate() {
        let n = format!("{:03}", k + 1);
        // The design's scenario under the same [uncertainty], sampled by `simulate --samples`.
        let scenario = std::fs::read_to_string(d.join(format!("o/pareto/{n}.toml"))).unwrap();
        common::write(
            d,
            &format!("u{n}.toml"),
            &format!("{scenario}\n{UNCERTAINTY}"),
        );
        let samples_dir = format!("s{n}");
        simulate(
            d,
            &[
                "simulate",
                &format!("u{n}.toml"),
                "--samples",
                "4",
                "--out",
                &samples_dir,
                "-q",
            ],
        );
        let forces: Vec<f64> = (1..=4)
            .map(|j| {
                let run = format!("r{n}_{j}");
                let sample = format!("{samples_dir}/samples/{j:03}.toml");
                simulate(d, &["simulate", &sample, "--out", &run, "-q"]);
                common::json(&d.join(format!("{run}/summary.json")))["transmitted_peak_force_n"]
                    .as_f64()
                    .unwrap()
            })
            .collect();
        let expected = quantile_95(&forces);
        let reported = column(&pareto, "transmitted-force")[k];
        assert!(
            (reported - expected).abs() <= 1e-12 * expected,
            "design {n}: NSGA-II {reported} vs re-run {expected}"
        );

        let robust = table(&d.join(format!("o/robust/{n}.csv")));
        let sampled = table(&d.join(format!("{samples_dir}/samples.csv")));
        assert_eq!(
            robust.0[..sampled.0.len()],
            sampled.0,
            "robust/{n}.csv columns"
        );
        assert_eq!(robust.0.last().unwrap(), "max_contact_pressure_pa");
        let pressures = column(&robust, "max_contact_pressure_pa");
        let expected = quantile_95(&pressures);
        let reported = column(&pareto, "max-contact-pressure")[k];
        assert!(
            (reported - expected).abs() <= 1e-12 * expected,
            "design {n}: pressure {reported} vs its samples' {expected}"
        );
        let written = column(&robust, "transmitted_peak_force_n");
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&written), bits(&forces), "robust/{n}.csv forces");
        let drawn: Vec<Vec<u64>> = robust.0[1..robust.0.len() - 4]
            .iter()
            .map(|c| bits(&column(&robust, c)))
            .collect();
        let drawn_alone: Vec<Vec<u64>> = sampled.0[1..sampled.0.len() - 3]
            .iter()
            .map(|c| bits(&column(&sampled, c)))
            .collect();
        assert_eq!(drawn, drawn_alone, "robust/{n}.csv drawn values");
        // Lengths are drawn about each design's own rods; the other draws are the same numbers.
        let shared: Vec<Vec<u64>> = robust.0[1..robust.0.len() - 4]
            .iter()
            .filter(|c| !c.starts_with("rod_length_mm"))
            .map(|c| bits(&column(&robust, c)))
            .collect();
        assert_eq!(shared.len(), 3, "two angles and the speed");
        match &draws {
            None => draws = Some(shared),
            Some(first) => assert_eq!(first, &shared, "design {n} drew other values"),
        }

        let genome: Vec<u8> = serde_json::from_value(design["genome"].clone()).unwrap();
        let mass = column(&pareto, "total-mass")[k];
        assert_eq!(
            mass,
            problem.space.mass_kg(&genome),
            "design {n}: nominal mass"
        );
    }
    eprintln!("front of {} designs", front.len());
}
