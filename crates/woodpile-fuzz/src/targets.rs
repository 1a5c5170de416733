// The fuzz targets, shared by the AFL binaries (crates/woodpile-fuzz/src/bin) and the replay
// claim (crates/woodpile-io/tests/claims/fuzz_corpus.rs). Plain functions of bytes.

/// A fuzz target: its name (the folder of its corpus) and the function of bytes it runs.
pub type Target = (&'static str, fn(&[u8]));

/// The readers under test; the corpus of each lives in `crates/woodpile-fuzz/corpus/<name>/`.
pub const TARGETS: [Target; 8] = [
    ("scenario", fuzz_scenario),
    ("lattice", fuzz_lattice),
    ("optimize_config", fuzz_optimize_config),
    ("npy", fuzz_npy),
    ("table", fuzz_table),
    ("checkpoint", fuzz_checkpoint),
    ("fit", fuzz_fit),
    ("uncertainty", fuzz_uncertainty),
];

/// A scratch directory of this process for the readers that take files.
fn scratch() -> &'static std::path::Path {
    static DIR: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("woodpile-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a scratch directory");
        // The blast table that scenarios of the corpus name.
        std::fs::write(
            dir.join("table.csv"),
            "time_s, force_n\n0, 0\n1e-5, 10\n2e-5, 0\n",
        )
        .expect("a scratch table");
        dir
    })
}

/// A scenario file: parse, resolve (every check and the chain's construction), and the
/// completed scenario written out must read back as the same scenario.
pub fn fuzz_scenario(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scenario) = woodpile_io::scenario::Scenario::parse(text) else {
        return;
    };
    let complete = scenario.complete();
    let again = woodpile_io::scenario::Scenario::parse(&complete.to_toml())
        .expect("a completed scenario's TOML reads back");
    assert_eq!(again, complete, "completion round-trips");
    let _ = woodpile_io::scenario::resolve(&scenario, scratch());
}

/// A lattice scenario (`[lattice]`): parse, resolve (the size limits, every geometry check,
/// the rods' modes and crossings), then compile its equations under the striker.
pub fn fuzz_lattice(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scenario) = woodpile_io::lattice::LatticeScenario::parse(text, "fuzz") else {
        return;
    };
    let Ok(resolved) = scenario.resolve() else {
        return;
    };
    let _ =
        woodpile::ode::LatticeOde::build(&resolved.lattice, &resolved.excitation, &resolved.lab);
}

/// An optimisation config: parse, then build the problem (design space, constraints, limits).
pub fn fuzz_optimize_config(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(config) = woodpile_io::optimize::OptimizeConfig::parse(text, "fuzz") else {
        return;
    };
    let _ = woodpile_io::optimize::Problem::new(&config, scratch(), 1);
}

/// A `.npy` array.
pub fn fuzz_npy(data: &[u8]) {
    let _ = woodpile_io::npy::read(data);
}

/// A blast table (CSV `time_s, force_n`), as the scenario's `excitation.file` is read.
pub fn fuzz_table(data: &[u8]) {
    let _ = woodpile_io::table::read_blast_table(data, std::path::Path::new("fuzzed.csv"));
}

/// An optimisation checkpoint. The bytes are the JSON; a checkpoint that parses gets this
/// version and a matching checksum, so that the fuzzer reaches the checks behind them (the
/// state against its problem) rather than stopping at the checksum.
pub fn fuzz_checkpoint(data: &[u8]) {
    use woodpile_io::optimize::{read_checkpoint, Checkpoint, CHECKPOINT_FILE, CHECKPOINT_FORMAT};
    let Ok(mut checkpoint) = serde_json::from_slice::<Checkpoint>(data) else {
        return;
    };
    checkpoint.format = CHECKPOINT_FORMAT.to_string();
    checkpoint.tool_version = woodpile_io::VERSION.to_string();
    checkpoint.checksum = checkpoint.content_checksum();
    let dir = scratch().join("checkpoint");
    if std::fs::create_dir_all(&dir).is_err() {
        return;
    }
    let Ok(json) = serde_json::to_string(&checkpoint) else {
        return;
    };
    if std::fs::write(dir.join(CHECKPOINT_FILE), json).is_err() {
        return;
    }
    let config = checkpoint.config.clone();
    let Ok(state) = read_checkpoint(&dir, &config) else {
        return;
    };
    let Ok(problem) = woodpile_io::optimize::Problem::new(&config, scratch(), 1) else {
        return;
    };
    let ga = woodpile::BreederGa::new(
        problem.space.clone(),
        Box::new(problem.objective),
        problem.settings,
    );
    if let Ok(ga) = ga {
        let _ = ga.check_state(&state);
    }
}

/// The line that splits a `fit` input into its fit file (before) and its measured CSV (after).
pub const FIT_CSV_SEPARATOR: &str = "\n%% measured.csv\n";

/// A fit file and its measured CSV (split at [`FIT_CSV_SEPARATOR`]; without it, the whole input
/// is the fit file and the CSV a fixed one), over a fixed two-rod model: the file read and every
/// key, column and row checked (`fit::load`), then the fit's size limit. No model is run (a
/// fitted `run.duration_s` could make one run take minutes).
pub fn fuzz_fit(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (fit, csv) = text
        .split_once(FIT_CSV_SEPARATOR)
        .unwrap_or((text, "time_s,sensor_n\n0,0\n1e-6,0.5\n2e-6,1.0\n"));
    // One folder per thread: the replay claim runs its tests in parallel threads.
    let dir = scratch().join(format!("fit-{:?}", std::thread::current().id()));
    let written = std::fs::create_dir_all(&dir)
        .and_then(|()| {
            std::fs::write(
                dir.join("model.toml"),
                "[chain]\nrods_mm = [80, 40]\n[run]\nduration_s = 1e-4\n",
            )
        })
        .and_then(|()| std::fs::write(dir.join("measured.csv"), csv))
        .and_then(|()| std::fs::write(dir.join("fit.toml"), fit));
    if written.is_err() {
        return;
    }
    let Ok(setup) = woodpile_io::fit::load(&dir.join("fit.toml")) else {
        return;
    };
    let _ = woodpile_io::limits::check_fit(setup.starts, setup.max_evaluations, false);
}

/// A scenario with an `[uncertainty]` table: checked, then (within the study limit) up to 16
/// samples drawn and resolved, and a sensitivity design of 8 base samples built — the paths of
/// `simulate --samples` and `sensitivity` up to the runs.
pub fn fuzz_uncertainty(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scenario) = woodpile_io::scenario::Scenario::parse(text) else {
        return;
    };
    let Some(Ok(mut u)) = scenario.uncertainty.as_ref().map(|spec| spec.check()) else {
        return;
    };
    u.samples = u.samples.min(16);
    if woodpile_io::uncertainty::check_size(&scenario, u.samples, "samples", false).is_err() {
        return;
    }
    if let Ok(drawn) = woodpile_io::uncertainty::samples(&scenario, &u) {
        let _ = woodpile_io::uncertainty::resolve_samples(&drawn, scratch());
    }
    let _ = woodpile_io::sensitivity::design(&scenario, &u, ("base_samples", 8), false);
}
