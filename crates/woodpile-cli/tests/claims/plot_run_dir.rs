//! Claim: `woodpile plot RUN_DIR` turns a `simulate` output directory into PNG and SVG figures in
//! RUN_DIR/plots (from the .npy files, or from the CSV files when those are gone), and refuses
//! with exit code 2 and a message naming the problem: a directory that is not a run, a run of
//! another format version, a missing data file, a signal name that does not exist.
//! `woodpile cells --plot DIR` draws Fig. 3. The count it prints is that of the figures it lists
//! (it said "wrote 14 files" and listed 7).
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
    // What it says it wrote is what it lists: a line per figure, its PNG (and an SVG beside it).
    let stdout = String::from_utf8_lossy(&o.stdout);
    let listed = stdout.lines().filter(|l| l.starts_with("  ")).count();
    let first = stdout.lines().next().unwrap_or_default();
    assert!(
        first.starts_with(&format!("wrote {listed} figures ({} files)", 2 * listed)),
        "{stdout}"
    );
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
    refused(&["plot", run.to_str().unwrap()], &["woodpile-run/0"]);
    // A run.json without a format tag (older files) is judged by its version.
    let old = json
        .replacen("\"format\": \"woodpile-run/1\",", "", 1)
        .replacen(
            &format!("\"version\": \"{}\"", env!("CARGO_PKG_VERSION")),
            "\"version\": \"0.0.1\"",
            1,
        );
    std::fs::write(run.join("run.json"), &old).unwrap();
    refused(&["plot", run.to_str().unwrap()], &["0.0.1"]);

    std::fs::write(run.join("run.json"), &json).unwrap();
    std::fs::remove_file(run.join("forces_n.npy")).unwrap();
    std::fs::remove_file(run.join("forces.csv")).unwrap();
    let run = run.to_str().unwrap();
    refused(&["plot", run], &["forces.csv"]);
    // Names the signal and the valid ones.
    refused(
        &["plot", run, "--signal", "contact_99"],
        &["contact_99", "wall"],
    );
    // Lists the valid windows.
    refused(&["plot", run, "--window", "kaiser"], &["hann"]);
}

/// Asserts that `woodpile args` exits with code 2 and that its standard error contains every
/// one of `expected`.
fn refused(args: &[&str], expected: &[&str]) {
    let o = woodpile(args);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    for e in expected {
        assert!(
            stderr(&o).contains(e),
            "{args:?}: `{e}` missing from {}",
            stderr(&o)
        );
    }
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

/// Width of a PNG file from its IHDR chunk.
fn png_width(path: &Path) -> u32 {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    u32::from_be_bytes(bytes[16..20].try_into().unwrap())
}

/// The x-axis tick labels of a plotters SVG: centred texts hanging below their anchor that are
/// numbers.
fn svg_x_ticks(path: &Path) -> Vec<f64> {
    let svg = std::fs::read_to_string(path).unwrap();
    svg.split("<text ")
        .skip(1)
        .filter(|t| t.contains("text-anchor=\"middle\"") && t.contains("dy=\"0.76em\""))
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..t.find("</text>")?];
            body.trim().parse::<f64>().ok()
        })
        .collect()
}

/// Claim: `woodpile plot` writes the formats, printed size and windows asked for:
/// `--format svg` writes every figure as SVG and no PNG; `--dpi 150 --width-in 3.5` gives
/// PNG files 525 px wide (3.5 × 150, exact); `--time-ms 0.1,0.2` gives force histories, force
/// and energy maps whose x tick labels all lie in [0.1, 0.2] ms (3 or more of them) and no
/// zoomed onset figure (the window is the user's); `--frequency-khz 20,60` gives spectra whose
/// ticks lie in [20, 60] kHz; `--max-frequency-khz` still works; `--colours log` and `robust`
/// change the maps' colour bars (auto force map: no saturation mark; log: a "≤" bottom; robust:
/// a saturated "≥" top). Exact: tick labels are
/// printed to 3 significant digits, which cannot leave windows ending on these values.
#[test]
fn plot_writes_the_formats_sizes_and_windows_asked_for() {
    let tmp = tempfile::tempdir().unwrap();
    let run = simulate(tmp.path());
    let out = |name: &str| tmp.path().join(name);
    let path = |p: &Path| p.to_str().unwrap().to_string();
    let plot = |extra: &[&str], dir: &Path| {
        let mut args = vec![
            "plot".to_string(),
            path(&run),
            "--out".into(),
            path(dir),
            "-q".into(),
        ];
        args.extend(extra.iter().map(|s| s.to_string()));
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = woodpile(&refs);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
    };

    plot(&["--format", "svg"], &out("svg"));
    let names: Vec<String> = std::fs::read_dir(out("svg"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(names.iter().any(|n| n == "force_map.svg"), "{names:?}");
    assert!(
        names.iter().all(|n| n.ends_with(".svg")),
        "--format svg wrote {names:?}"
    );

    plot(
        &["--dpi", "150", "--width-in", "3.5", "--format", "png"],
        &out("small"),
    );
    for name in ["force_map", "force_histories", "spectra", "chain"] {
        assert_eq!(
            png_width(&out("small").join(format!("{name}.png"))),
            525,
            "{name}"
        );
    }

    plot(&["--time-ms", "0.1,0.2"], &out("window"));
    for name in ["force_histories", "force_map", "energy_map"] {
        let ticks = svg_x_ticks(&out("window").join(format!("{name}.svg")));
        assert!(ticks.len() >= 3, "{name}: {ticks:?}");
        assert!(
            ticks.iter().all(|&x| (0.1..=0.2).contains(&x)),
            "{name}: ticks {ticks:?} outside 0.1–0.2 ms"
        );
    }
    assert!(!out("window").join("force_histories_onset.png").exists());

    plot(
        &["--frequency-khz", "20,60", "--format", "svg"],
        &out("band"),
    );
    let ticks = svg_x_ticks(&out("band").join("spectra.svg"));
    assert!(ticks.len() >= 3, "{ticks:?}");
    assert!(
        ticks.iter().all(|&f| (20.0..=60.0).contains(&f)),
        "spectra ticks {ticks:?} outside 20–60 kHz"
    );
    plot(
        &["--max-frequency-khz", "40", "--format", "svg"],
        &out("max"),
    );
    let ticks = svg_x_ticks(&out("max").join("spectra.svg"));
    assert!(
        ticks.iter().all(|&f| (0.0..=40.0).contains(&f)) && ticks.contains(&40.0),
        "{ticks:?}"
    );

    // Colour scales of the maps: by default the force map's bar is linear from 0 and nothing
    // saturates (no "≤"/"≥" mark); with --colours log its bottom is marked "≤ …" (log colours
    // saturate below); with --colours robust the energy map's top saturates, marked "≥ …".
    let bar_texts = |dir: &Path, name: &str| -> Vec<String> {
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap();
        svg.split("<text")
            .skip(1)
            .filter_map(|t| Some(t[t.find('>')? + 1..t.find("</text>")?].trim().to_string()))
            .collect()
    };
    plot(&["--format", "svg"], &out("auto"));
    let auto = bar_texts(&out("auto"), "force_map");
    assert!(
        !auto
            .iter()
            .any(|t| t.starts_with("≤ ") || t.starts_with("≥ ")),
        "{auto:?}"
    );
    plot(&["--colours", "log", "--format", "svg"], &out("log"));
    let log = bar_texts(&out("log"), "force_map");
    assert!(log.iter().any(|t| t.starts_with("≤ ")), "{log:?}");
    plot(&["--colours", "robust", "--format", "svg"], &out("robust"));
    let robust = bar_texts(&out("robust"), "energy_map");
    assert!(robust.iter().any(|t| t.starts_with("≥ ")), "{robust:?}");
}

/// Claim: a bad output or window flag exits with code 2 and a message naming the flag and what
/// is valid (and, for `pdf`, how to get one); an empty window names the range the run covers
/// (the test run: 0 to 0.3 ms). Exact.
#[test]
fn bad_plot_flags_exit_2_naming_the_flag() {
    let tmp = tempfile::tempdir().unwrap();
    let run = simulate(tmp.path());
    let dir = run.to_str().unwrap();
    for (args, expected) in [
        (
            &["--format", "pdf"][..],
            &["--format", "svg", "rsvg-convert"][..],
        ),
        (&["--format", "jpg"], &["--format", "png, svg"]),
        (&["--dpi", "0"], &["--dpi", "30 to 2400"]),
        (
            &["--colours", "rainbow"],
            &["--colours", "auto, robust, log"],
        ),
        (&["--dpi", "nan"], &["--dpi"]),
        (&["--width-in", "-2"], &["--width-in", "0.5 to 50"]),
        (&["--height-in", "100"], &["--height-in", "0.5 to 50"]),
        (&["--time-ms", "0.2,0.1"], &["--time-ms", "START < END"]),
        (&["--time-ms", "1"], &["--time-ms", "START,END"]),
        (&["--time-ms", "5,6"], &["--time-ms", "covers 0 to 0.3 ms"]),
        (
            &["--frequency-khz", "900,1000"],
            &["--frequency-khz", "cover 0 to"],
        ),
        (
            &["--frequency-khz", "1,2", "--max-frequency-khz", "3"],
            &["--frequency-khz", "--max-frequency-khz"],
        ),
        (
            &["--max-frequency-khz", "0"],
            &["--max-frequency-khz", "> 0"],
        ),
    ] {
        let mut all = vec!["plot", dir, "-q"];
        all.extend_from_slice(args);
        refused(&all, expected);
    }
}

/// Claim: the figures of a blast run call contact 0 the load, never the striker, even when it
/// is selected as `--signal striker`: the legends of the histories and spectra say
/// `contact 0 (load)`, the maps' axes `0 = load`, the chain picture `load ↓`, and no SVG text
/// says `striker`. Exact.
#[test]
fn blast_runs_are_not_labelled_striker() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("blast.toml");
    std::fs::write(
        &file,
        "[chain]\nrods_mm = [20, 40]\n[excitation]\nkind = \"blast\"\n[run]\nduration_s = 3e-4\n",
    )
    .unwrap();
    let run = tmp.path().join("run");
    let o = woodpile(&[
        "simulate",
        file.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for extra in [&[][..], &["--signal", "striker", "--signal", "wall"]] {
        let mut args = vec!["plot", run.to_str().unwrap(), "-q", "--format", "svg"];
        args.extend_from_slice(extra);
        let o = woodpile(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let svg = |name: &str| {
            std::fs::read_to_string(run.join("plots").join(format!("{name}.svg"))).unwrap()
        };
        for name in ["force_histories", "spectra"] {
            assert!(svg(name).contains("contact 0 (load)"), "{name} {extra:?}");
        }
        for name in ["force_map", "energy_map", "spectrum_map"] {
            assert!(svg(name).contains("0 = load"), "{name} {extra:?}");
        }
        assert!(svg("chain").contains("load ↓"), "chain {extra:?}");
        for name in [
            "force_histories",
            "spectra",
            "force_map",
            "energy_map",
            "spectrum_map",
            "chain",
        ] {
            assert!(
                !svg(name).contains("striker"),
                "{name} {extra:?} says striker"
            );
        }
    }
}
