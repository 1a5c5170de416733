//! Claim: `woodpile simulate` runs a lattice scenario (`[lattice]`, docs/physics.md §16) into a
//! run directory whose `run.json` lists the contacts in output order — the striker's (layer 0),
//! the crossings layer by layer, the supports (layer L + 1, their number as the rod) — in the
//! order of `summary.json`'s `contact_peak_forces_n` and of the force columns, and whose
//! `supports.csv` ends in their sum, `transmitted_n`, whose peak is the summary's transmitted
//! peak (sampled every step there, every µs here: within 2 % on this run); `woodpile plot`
//! draws its `support_forces`, `contact_force_map`, `interface_forces` and `lattice_view` as
//! PNG and SVG (exit 0; the last two with a disc per contact of `run.json`, in each of four time
//! windows and once) and refuses the run once its `summary.json` lists too few peaks or its
//! `forces_n.npy` is cut short, naming the file (exit 2). Bad lattices —
//! layers that do not touch, a support under no bottom rod, an impact point on no top rod, a
//! negative drop height, more rods or crossings than the limits, an output of hundreds of GB,
//! an impact point of three coordinates, two supports at one point, rods over 1e4 diameters —
//! exit with code 2 naming the key, and leave no output directory (each refused at once: the
//! oversized lattices before their rods' modes or crossings are computed).

use crate::common;

/// A 3 × 3-rod, 2-layer quartz lattice struck off centre (shared with `one_run_layout`).
pub(crate) const LATTICE: &str = r#"
[lattice]
layers = [
  { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 2 },
]
rod = { fe_elements = 2 }
[excitation]
kind = "impact"
at_mm = [10.0, 0.0]
[wall]
supports = "centres"
[run]
duration_s = 3e-4
"#;

#[test]
fn lattice_run_directory_lists_its_contacts() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "lat.toml", LATTICE);
    common::simulate_ok(dir.path(), "lat.toml");
    let run = common::json(&dir.path().join("out/run.json"));
    let contacts = run["contacts"].as_array().unwrap();
    // 1 striker + 3 × 2 crossings + 2 supports.
    assert_eq!(contacts.len(), 9);
    let key = |c: &serde_json::Value| {
        [
            c["layer_above"].as_u64().unwrap(),
            c["rod_above"].as_u64().unwrap(),
            c["layer_below"].as_u64().unwrap(),
            c["rod_below"].as_u64().unwrap(),
        ]
    };
    assert_eq!(key(&contacts[0]), [0, 1, 1, 2]);
    assert_eq!(contacts[0]["x_mm"].as_f64().unwrap(), 10.0);
    assert_eq!(key(&contacts[1]), [1, 1, 2, 1]);
    assert_eq!(key(&contacts[6]), [1, 3, 2, 2]);
    assert_eq!(key(&contacts[7]), [2, 1, 3, 1]);
    assert_eq!(key(&contacts[8]), [2, 2, 3, 2]);
    // Layer 2 runs along y at x = ∓10 mm (rods numbered toward +x); rod 1 of layer 1 lies at y = −20 mm.
    assert!((contacts[1]["x_mm"].as_f64().unwrap() + 10.0).abs() < 1e-9);
    assert!((contacts[1]["y_mm"].as_f64().unwrap() + 20.0).abs() < 1e-9);
    let summary = common::json(&dir.path().join("out/summary.json"));
    let peaks = summary["contact_peak_forces_n"].as_array().unwrap();
    assert_eq!(peaks.len(), 9);
    let text = std::fs::read_to_string(dir.path().join("out/supports.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time_s,support_1_n,support_2_n,transmitted_n"
    );
    let mut sampled_peak = 0.0_f64;
    for line in lines {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!((v[1] + v[2] - v[3]).abs() <= 1e-12 * v[3].abs().max(1.0));
        sampled_peak = sampled_peak.max(v[3]);
    }
    let transmitted = summary["transmitted_peak_force_n"].as_f64().unwrap();
    assert!(transmitted > 1.0, "the wave reached the supports");
    assert!(sampled_peak <= transmitted * (1.0 + 1e-12));
    assert!(
        sampled_peak > 0.98 * transmitted,
        "{sampled_peak} vs {transmitted}"
    );
    let forces = std::fs::read_to_string(dir.path().join("out/forces.csv")).unwrap();
    assert_eq!(forces.lines().next().unwrap().split(',').count(), 10);
    // `woodpile plot` draws the lattice's four figures, each as PNG and SVG.
    let plot = common::run_in(dir.path(), &["plot", "out", "--quiet"]);
    let stderr = String::from_utf8_lossy(&plot.stderr);
    assert_eq!(plot.status.code(), Some(0), "{stderr}");
    for stem in [
        "support_forces",
        "contact_force_map",
        "interface_forces",
        "lattice_view",
    ] {
        let png = std::fs::read(dir.path().join(format!("out/plots/{stem}.png"))).unwrap();
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "{stem}.png is a PNG");
        let svg =
            std::fs::read_to_string(dir.path().join(format!("out/plots/{stem}.svg"))).unwrap();
        assert!(svg.contains("<svg"), "{stem}.svg is an SVG");
        // The lattice's figures draw run.json's 9 contacts as discs: in each of the four time
        // windows (300 samples) and once in the 3-D view.
        let discs = svg
            .split("<circle")
            .skip(1)
            .filter(|t| !t[..t.find('>').unwrap()].contains("fill=\"none\""))
            .count();
        match stem {
            "interface_forces" => assert_eq!(discs, 4 * 9, "{stem}"),
            "lattice_view" => assert_eq!(discs, 9, "{stem}"),
            _ => {}
        }
    }
    // A summary.json whose peaks do not match run.json's contacts is refused naming it, exit 2
    // (the 3-D view colours each contact by its peak there).
    let summary_path = dir.path().join("out/summary.json");
    let summary_text = std::fs::read_to_string(&summary_path).unwrap();
    let mut short: serde_json::Value = serde_json::from_str(&summary_text).unwrap();
    short["contact_peak_forces_n"]
        .as_array_mut()
        .unwrap()
        .truncate(8);
    std::fs::write(&summary_path, short.to_string()).unwrap();
    let plot = common::run_in(dir.path(), &["plot", "out"]);
    let stderr = String::from_utf8_lossy(&plot.stderr);
    assert_eq!(plot.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("summary.json"), "{stderr}");
    std::fs::write(&summary_path, summary_text).unwrap();
    // A damaged run (its force file cut short) is refused naming the file, exit 2.
    let npy = dir.path().join("out/forces_n.npy");
    let bytes = std::fs::read(&npy).unwrap();
    std::fs::write(&npy, &bytes[..bytes.len() / 2]).unwrap();
    let plot = common::run_in(dir.path(), &["plot", "out"]);
    let stderr = String::from_utf8_lossy(&plot.stderr);
    assert_eq!(plot.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("forces_n.npy"), "{stderr}");
}

#[test]
fn bad_lattices_exit_2_naming_the_key() {
    common::refused_scenario(
        "layers apart",
        &LATTICE.replace("{ rods = 2 }", "{ rods = 2, pitch_mm = 100.0 }"),
        &["lattice.layers[1]", "do not touch"],
    );
    common::refused_scenario(
        "support",
        &LATTICE.replace(
            "supports = \"centres\"",
            "supports = [{ x_mm = -10.0, y_mm = 0.0 }, { x_mm = 0.0, y_mm = 50.0 }]",
        ),
        &["wall.supports[1]", "y_mm = 50"],
    );
    common::refused_scenario(
        "impact",
        &LATTICE.replace("at_mm = [10.0, 0.0]", "at_mm = [10.0, 10.0]"),
        &["excitation.at_mm", "[10, 10]"],
    );
    common::refused_scenario(
        "drop height",
        &LATTICE.replace(
            "kind = \"impact\"",
            "kind = \"impact\"\ndrop_height_m = -0.2",
        ),
        &["excitation.drop_height_m", "-0.2"],
    );
    common::refused_scenario(
        "too many rods",
        &LATTICE.replace("{ rods = 2 }", "{ rods = 100000 }"),
        &["lattice.layers", "100003 rods in all", "at most 10000"],
    );
    common::refused_scenario(
        "too many crossings",
        &LATTICE
            .replace("rods = 3, pitch_mm = 20.0", "rods = 4000, pitch_mm = 20.0")
            .replace("{ rods = 2 }", "{ rods = 4000 }"),
        &["lattice.layers", "16000000 crossings", "at most 100000"],
    );
    common::refused_scenario(
        "output size",
        &LATTICE.replace(
            "duration_s = 3e-4",
            "duration_s = 0.1\nsample_interval_s = 1e-9",
        ),
        &["run.sample_interval_s", "GB of output", "--allow-large"],
    );
    common::refused_scenario(
        "no support",
        &LATTICE.replace("supports = \"centres\"", "supports = []"),
        &["wall.supports", "at least one support"],
    );
    // The value is shown in the unit the user wrote it in (mm), not in SI.
    common::refused_scenario(
        "negative length",
        &LATTICE.replace("length_mm = 80.0", "length_mm = -80.0"),
        &["lattice.layers[0].length_mm", "= -80:", "mm > 0"],
    );
    // Each of these was accepted silently: a z dropped, one contact reported twice, a rod whose
    // bending modes lie below a hertz (chains refuse rods over 1e4 diameters).
    common::refused_scenario(
        "a third coordinate",
        &LATTICE.replace("at_mm = [10.0, 0.0]", "at_mm = [10.0, 0.0, 5.0]"),
        &["at_mm", "invalid length 3", "[x, y]"],
    );
    common::refused_scenario(
        "two supports at one point",
        &LATTICE.replace(
            "supports = \"centres\"",
            "supports = [{ x_mm = 0.0, y_mm = 0.0 }, { x_mm = 0.0, y_mm = 0.0 }]",
        ),
        &[
            "wall.supports[1]",
            "wall.supports[0] is at this point already",
        ],
    );
    common::refused_scenario(
        "rods 1e9 mm long",
        &LATTICE.replace("length_mm = 80.0", "length_mm = 1e9"),
        &["lattice.layers[0].length_mm", "1e4 diameters"],
    );
    common::refused_scenario(
        "unknown key",
        &LATTICE.replace("{ rods = 2 }", "{ rods = 2, colour = \"red\" }"),
        &["unknown field `colour`"],
    );
}

/// Each body's energy (`rod_energies.csv`: the striker, every rod as `layer_{k}_rod_{i}_j`, the
/// supports' halves) adds up to `energy.csv`'s total at every sample (1e-12 of the largest: both
/// are sums of the same terms in another order), and `energy_j.npy` holds samples × (1 + rods).
#[test]
fn rod_energies_add_up_to_the_total() {
    let dir = tempfile::tempdir().unwrap();
    common::write(dir.path(), "lat.toml", LATTICE);
    common::simulate_ok(dir.path(), "lat.toml");
    let read = |name: &str| -> (String, Vec<Vec<f64>>) {
        let text = std::fs::read_to_string(dir.path().join("out").join(name)).unwrap();
        let mut lines = text.lines();
        let header = lines.next().unwrap().to_string();
        let rows = lines
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect();
        (header, rows)
    };
    let (header, bodies) = read("rod_energies.csv");
    assert_eq!(
        header,
        "time_s,striker_j,layer_1_rod_1_j,layer_1_rod_2_j,layer_1_rod_3_j,layer_2_rod_1_j,layer_2_rod_2_j,supports_j"
    );
    let (_, totals) = read("energy.csv");
    assert_eq!(bodies.len(), totals.len());
    let largest = totals.iter().fold(0.0_f64, |m, r| m.max(r[1]));
    for (b, t) in bodies.iter().zip(&totals) {
        let sum: f64 = b[1..].iter().sum();
        assert!(
            (sum - t[1]).abs() <= 1e-12 * largest,
            "{sum} against {}",
            t[1]
        );
    }
    let npy = std::fs::read(dir.path().join("out/energy_j.npy")).unwrap();
    let header = String::from_utf8_lossy(&npy[10..npy.len().min(128)]).to_string();
    assert!(
        header.contains(&format!("({}, 6)", bodies.len())),
        "{header}"
    );
}

/// A lattice run too short for the wave to reach the supports says so rather than print a
/// transmitted force: over 5 µs (the striker's contact lasts about 34 µs) the supports have
/// felt 7e-5 N against an incident 74 N, below `WAVE_ARRIVAL_FRACTION` (1e-3) of it — exit 0,
/// a warning naming `run.duration_s`, "transmitted  none" in the terminal summary and
/// `wave_arrived: false` in summary.json. The same lattice over 0.3 ms reports its transmitted
/// peak and `wave_arrived: true`.
#[test]
fn a_run_too_short_for_the_wave_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let short = LATTICE.replace("duration_s = 3e-4", "duration_s = 5e-6");
    common::write(dir.path(), "short.toml", &short);
    let out = common::run_in(dir.path(), &["simulate", "short.toml", "--out", "short"]);
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("the wave did not reach the supports") && stderr.contains("run.duration_s"),
        "{stderr}"
    );
    assert!(stdout.contains("transmitted  none"), "{stdout}");
    let summary = common::json(&dir.path().join("short/summary.json"));
    assert_eq!(summary["wave_arrived"], false);

    common::write(dir.path(), "lat.toml", LATTICE);
    let out = common::run_in(dir.path(), &["simulate", "lat.toml", "--out", "full"]);
    assert!(out.status.success());
    assert!(!String::from_utf8_lossy(&out.stderr).contains("did not reach"));
    let summary = common::json(&dir.path().join("full/summary.json"));
    assert_eq!(summary["wave_arrived"], true);
}
