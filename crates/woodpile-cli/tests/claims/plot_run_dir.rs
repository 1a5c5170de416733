//! Claim: `woodpile plot RUN_DIR` turns a `simulate` output directory into PNG and SVG figures in
//! RUN_DIR/plots (from the .npy files, or from the CSV files when those are gone), and refuses
//! with exit code 2 and a message naming the problem: a directory that is not a run, a run of
//! another format version, a missing data file, a signal name that does not exist.
//! `woodpile cells --plot DIR` draws Fig. 3.
//! No tolerance: file existence and exit codes are exact.

use std::path::Path;
use std::process::{Command, Output};

fn woodpile(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_woodpile"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const SCENARIO: &str = r#"
[chain]
rods_mm = [80, 40, 20]
[run]
duration_s = 3e-4
"#;

fn simulate(dir: &Path) -> std::path::PathBuf {
    let file = dir.join("short.toml");
    std::fs::write(&file, SCENARIO).unwrap();
    let run = dir.join("run");
    let o = woodpile(&[
        "simulate",
        file.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    run
}

fn assert_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        bytes.len() > 1000 && bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
        "{}",
        path.display()
    );
}

#[test]
fn plot_writes_every_figure_of_a_run() {
    let tmp = tempfile::tempdir().unwrap();
    let run = simulate(tmp.path());
    let o = woodpile(&["plot", run.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for name in [
        "force_map",
        "energy_map",
        "spectrum_map",
        "force_histories",
        "spectra",
        "chain",
    ] {
        assert_png(&run.join("plots").join(format!("{name}.png")));
        assert!(run.join("plots").join(format!("{name}.svg")).is_file());
    }
    // Without the .npy files the CSV files are read.
    for f in std::fs::read_dir(&run).unwrap() {
        let p = f.unwrap().path();
        if p.extension().is_some_and(|e| e == "npy") {
            std::fs::remove_file(p).unwrap();
        }
    }
    let out = tmp.path().join("from_csv");
    let o = woodpile(&[
        "plot",
        run.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_png(&out.join("force_map.png"));
}

#[test]
fn bad_run_directories_are_clear_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let o = woodpile(&["plot", tmp.path().to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no run.json"), "{}", stderr(&o));

    let run = simulate(tmp.path());
    let json = std::fs::read_to_string(run.join("run.json")).unwrap();
    // Another run format is refused, naming it.
    let other = json.replacen("\"woodpile-run/1\"", "\"woodpile-run/0\"", 1);
    assert_ne!(other, json, "run.json carries its format");
    std::fs::write(run.join("run.json"), &other).unwrap();
    let o = woodpile(&["plot", run.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("woodpile-run/0"), "{}", stderr(&o));
    // A run.json without a format tag (older files) is judged by its version.
    let old = json
        .replacen("\"format\": \"woodpile-run/1\",", "", 1)
        .replacen(
            &format!("\"version\": \"{}\"", env!("CARGO_PKG_VERSION")),
            "\"version\": \"0.0.1\"",
            1,
        );
    std::fs::write(run.join("run.json"), &old).unwrap();
    let o = woodpile(&["plot", run.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("0.0.1"), "{}", stderr(&o));

    std::fs::write(run.join("run.json"), &json).unwrap();
    std::fs::remove_file(run.join("forces_n.npy")).unwrap();
    std::fs::remove_file(run.join("forces.csv")).unwrap();
    let o = woodpile(&["plot", run.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("forces.csv"), "{}", stderr(&o));

    let o = woodpile(&["plot", run.to_str().unwrap(), "--signal", "contact_99"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("contact_99") && stderr(&o).contains("wall"),
        "names the signal and the valid ones: {}",
        stderr(&o)
    );

    let o = woodpile(&["plot", run.to_str().unwrap(), "--window", "kaiser"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("hann"),
        "lists the valid windows: {}",
        stderr(&o)
    );
}

#[test]
fn cells_plot_draws_the_effective_mass_curves() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("cells");
    let o = woodpile(&["cells", "--plot", dir.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_png(&dir.join("effective_mass_20_40mm.png"));
    assert_png(&dir.join("effective_mass_50_80mm.png"));
}
