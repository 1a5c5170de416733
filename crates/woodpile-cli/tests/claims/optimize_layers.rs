//! Claim: with `positions = { min, max }` and `layers` among the objectives, every design
//! `woodpile optimize` reports (each `pareto.csv` row, each line of the breeder's
//! `population.csv`) has min to max layers, its fixed top layer, and a mass and height within
//! `max_total_mass_g` and `max_stack_height_mm`, recomputed here from Table 1's cells; a row
//! shorter than the longest has empty cells after its last layer only, and its `layers` value
//! is its number of layers. Bad ranges — min > max, min = 0, a max whose generation is over the
//! size limit or above 1,024 layers, a fixed layer below min, a mass or a height no design of min layers meets, a
//! robust objective over designs of several lengths, a malformed range — exit with code 2
//! before any simulation, naming the key (and the numbers), and create no output directory.
//!
//! Tolerance: the limits are compared with a relative slack of 1e-12 (the library's, for sums
//! of the same masses in another order); the rest is exact.

use crate::common;
use woodpile::{CellModel, Element};

const MAX_MASS_G: f64 = 30.0;
const MAX_HEIGHT_MM: f64 = 35.0;
/// Every Table 1 rod is 5 mm across (paper §2).
const ROD_DIAMETER_MM: f64 = 5.0;

const CONFIG: &str = "[design]\npositions = { min = 3, max = 8 }\ncatalogue_mm = [20, 40, 60, 80]\n[design.constraints]\nmax_total_mass_g = 30.0\nmax_stack_height_mm = 35.0\nfixed = [{ layer = 1, rod_mm = 80 }]\n[run]\nduration_s = 4e-4\npeak_tolerance = 1e-4\n[ga]\npopulation = 16\ngenerations = 5\nseed = 2\n";

/// The layers of a row (cells from `first`), checked to be a run of lengths then empty cells.
fn layers_of(row: &[&str], first: usize) -> Vec<f64> {
    let cells = &row[first..];
    let n = cells
        .iter()
        .position(|c| c.is_empty())
        .unwrap_or(cells.len());
    assert!(
        cells[n..].iter().all(|c| c.is_empty()),
        "a gap inside {row:?}"
    );
    cells[..n]
        .iter()
        .map(|c| c.trim_end_matches("mm").parse().unwrap())
        .collect()
}

fn check_design(layers: &[f64]) {
    assert!((3..=8).contains(&layers.len()), "{layers:?}");
    assert_eq!(layers[0], 80.0, "fixed top layer: {layers:?}");
    let mass_g: f64 = layers
        .iter()
        .map(|&mm| {
            Element::table1_rod(mm as u32, CellModel::Resonant)
                .unwrap()
                .cell
                .total_mass_kg()
                * 1e3
        })
        .sum();
    assert!(
        mass_g <= MAX_MASS_G * (1.0 + 1e-12),
        "{layers:?}: {mass_g} g"
    );
    let height_mm = layers.len() as f64 * ROD_DIAMETER_MM;
    assert!(
        height_mm <= MAX_HEIGHT_MM * (1.0 + 1e-12),
        "{layers:?}: {height_mm} mm"
    );
}

fn run(config: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "c.toml", config);
    let out = common::run_in(dir.path(), &["optimize", "c.toml", "--out", "o"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let o = dir.path().join("o");
    (dir, o)
}

#[test]
fn every_reported_design_keeps_its_range_and_limits() {
    let (_dir, o) = run(&format!(
        "{CONFIG}objectives = [\"transmitted-force\", \"layers\"]\n"
    ));
    let csv = std::fs::read_to_string(o.join("pareto.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[..3], ["transmitted-force", "layers", "layer_1"]);
    let mut lengths = std::collections::BTreeSet::new();
    for line in lines {
        let row: Vec<&str> = line.split(',').collect();
        let layers = layers_of(&row, 2);
        check_design(&layers);
        assert_eq!(row[1].parse::<f64>().unwrap(), layers.len() as f64);
        lengths.insert(layers.len());
    }
    // A front of force against layers spans several lengths (fewer layers, more force).
    assert!(lengths.len() > 1, "{lengths:?}");

    let (_dir2, o) = run(&format!("{CONFIG}objective = \"transmitted-force\"\n"));
    let csv = std::fs::read_to_string(o.join("population.csv")).unwrap();
    for line in csv.lines().skip(1) {
        let row: Vec<&str> = line.split(',').collect();
        check_design(&layers_of(&row, 4));
    }
}

fn refused(config: &str, expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "c.toml", config);
    let out = common::run_in(dir.path(), &["optimize", "c.toml", "--out", "out"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    for e in expected {
        assert!(stderr.contains(e), "expected `{e}` in: {stderr}");
    }
    assert!(
        !dir.path().join("out").exists(),
        "{config}: output dir created"
    );
}

#[test]
fn bad_ranges_are_refused_naming_the_key() {
    let with = |positions: &str, more: &str| {
        format!("[design]\npositions = {positions}\ncatalogue_mm = [20, 80]\n{more}[run]\nduration_s = 1e-4\n[ga]\npopulation = 4\ngenerations = 1\n")
    };
    refused(
        &with("{ min = 5, max = 3 }", ""),
        &["design.positions.max", "3", "min = 5"],
    );
    refused(
        &with("{ min = 0, max = 3 }", ""),
        &["design.positions.min", "0", "at least 1"],
    );
    refused(
        &with("{ min = 2, max = 300000 }", ""),
        &[
            "ga.population × design.positions.max",
            "4 × 300000",
            "1000000",
        ],
    );
    refused(
        &with(
            "{ min = 3, max = 9 }",
            "[design.constraints]\nfixed = [{ layer = 4, rod_mm = 20 }]\n",
        ),
        &[
            "design.constraints.fixed[0].layer",
            "4",
            "design.positions.min = 3",
        ],
    );
    // 8 rods of 20 mm, the lightest design of 8 layers, weigh 6.928 g; they stand 40 mm.
    refused(
        &with(
            "{ min = 8, max = 12 }",
            "[design.constraints]\nmax_total_mass_g = 5.0\n",
        ),
        &[
            "design.constraints.max_total_mass_g",
            "5",
            "6.928 g",
            "8 layers",
        ],
    );
    refused(
        &with(
            "{ min = 8, max = 12 }",
            "[design.constraints]\nmax_stack_height_mm = 30.0\n",
        ),
        &[
            "design.constraints.max_stack_height_mm",
            "30",
            "40 mm",
            "8 layers",
        ],
    );
    refused(
        &format!(
            "{}robust = \"mean\"\n[uncertainty]\nsamples = 4\nimpact_velocity_m_s = {{ uniform = [1.8, 2.2] }}\n",
            with("{ min = 3, max = 5 }", "")
        ),
        &["ga.robust", "fixed number of layers"],
    );
    refused(
        &with("{ min = 3 }", ""),
        &["positions", "missing field `max`"],
    );
    refused(
        &with("{ min = 3, max = 5, step = 1 }", ""),
        &["unknown field `step`"],
    );
    refused(&with("-3", ""), &["positions", "{ min = 8, max = 24 }"]);
}
