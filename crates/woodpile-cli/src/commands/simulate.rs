//! `woodpile simulate`: run a scenario file or a built-in scenario and write its outputs.

use super::Context;
use crate::progress::Progress;
use crate::CliError;
use std::path::{Path, PathBuf};
use woodpile::record::{Layout, Recorder, Sample};
use woodpile::{simulate, Trajectory};
use woodpile_io::atomic::{Staging, RUN_MARKER};
use woodpile_io::limits::RunSize;
use woodpile_io::rundir::{RunRecord, RUN_FILES};
use woodpile_io::scenario::{resolve, Resolved, Scenario, DEFAULT_SCENARIO};

/// Which scenario a command runs: a file or a built-in (shared by `simulate` and
/// `transmission`).
#[derive(Debug, Clone, clap::Args)]
pub struct Source {
    /// Scenario file (TOML). Without it and without --scenario: the default job,
    /// `paper-impact-optimized`.
    #[arg(value_name = "SCENARIO.toml", conflicts_with = "scenario")]
    pub file: Option<PathBuf>,
    /// A built-in scenario (see `woodpile scenarios`).
    #[arg(long, value_name = "NAME")]
    pub scenario: Option<String>,
}

/// Arguments of `woodpile simulate`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// The scenario.
    #[command(flatten)]
    pub source: Source,
    /// Output directory (default: ./runs/NAME, NAME = scenario name or file stem). An existing
    /// run directory is written only with --overwrite.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Replace the run files of an earlier run in --out (other files and plots/ are kept).
    #[arg(long)]
    pub overwrite: bool,
    /// Keep the results of a run whose energy balance is off by more than 1e-2 (see
    /// docs/physics.md §8); they are written with a warning.
    #[arg(long)]
    pub allow_inaccurate: bool,
    /// Allow a run of more than 1e9 integration steps.
    #[arg(long)]
    pub allow_long: bool,
    /// Allow an output directory larger than 2 GB.
    #[arg(long)]
    pub allow_large: bool,
    /// Run K samples of the scenario's `[uncertainty]` (overriding its `samples`) in SIMD lanes and
    /// write DIR/samples.csv, DIR/samples/NNN.toml and DIR/summary.json (default DIR:
    /// ./runs/NAME-samples).
    #[arg(long, allow_negative_numbers = true, value_name = "K")]
    pub samples: Option<usize>,
}

/// A scenario ready to run: its name, where it came from, and the directory its files are
/// relative to.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// Built-in name or file stem.
    pub name: String,
    /// The scenario file, if any.
    pub file: Option<PathBuf>,
    /// The scenario.
    pub scenario: Scenario,
    /// Directory for relative paths in the scenario.
    pub base_dir: PathBuf,
}

impl Loaded {
    /// The scenario resolved into the core's types; its warnings are printed on stderr.
    pub fn resolve(&self) -> Result<Resolved, CliError> {
        let resolved = resolve(&self.scenario, &self.base_dir)?;
        for warning in &resolved.warnings {
            crate::out::eprintln(format_args!("warning: {warning}"));
        }
        Ok(resolved)
    }
}

/// Loads a scenario file, or a built-in scenario by name (default: the default job), for
/// `command`, which runs chains only.
pub fn load(source: &Source, command: &'static str) -> Result<Loaded, CliError> {
    if let Some(file) = &source.file {
        let scenario = Scenario::load(file).map_err(super::chains_only(command))?;
        let (name, base_dir) = super::name_and_base(file, "scenario");
        return Ok(Loaded {
            name,
            file: Some(file.clone()),
            scenario,
            base_dir,
        });
    }
    let name = source.scenario.as_deref().unwrap_or(DEFAULT_SCENARIO);
    if woodpile_io::lattice::builtin_lattice(name).is_some() {
        let source_name = format!("built-in scenario {name}");
        return Err(super::chains_only(command)(CliError::ChainsOnly {
            source_name,
        }));
    }
    Ok(Loaded {
        name: name.to_string(),
        file: None,
        scenario: super::scenarios::lookup(name)?,
        base_dir: PathBuf::from("."),
    })
}

/// Runs `woodpile simulate` of one scenario (`--samples` runs `samples::run`).
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    if let Some(file) = &args.source.file {
        let text = std::fs::read_to_string(file).map_err(|e| woodpile_io::Error::Read {
            path: file.clone(),
            source: e,
        })?;
        if woodpile_io::lattice::is_lattice(&text) {
            return run_lattice(args, file, &text, ctx);
        }
    }
    if let (None, Some(name)) = (&args.source.file, args.source.scenario.as_deref()) {
        if let Some(text) = woodpile_io::lattice::builtin_lattice(name) {
            return run_lattice(args, Path::new(name), text, ctx);
        }
    }
    let loaded = load(&args.source, "simulate")?;
    let resolved = loaded.resolve()?;
    RunSize::estimate(&resolved.settings, resolved.chain.len()).check(
        args.allow_long,
        args.allow_large,
        true,
    )?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new("runs").join(&loaded.name));
    let staging = Staging::prepare(&out, args.overwrite)?;
    let mut trajectory = Trajectory::default();
    let mut watched = Watched::new(&mut trajectory, resolved.settings.duration_s, ctx.quiet);
    let summary = simulate(
        &resolved.chain,
        &resolved.excitation,
        &resolved.settings,
        &mut watched,
    );
    watched.finish();
    let watched_progress = watched.progress.is_some();
    let summary = summary?;
    let accuracy = woodpile_io::limits::check_accuracy(&summary.energy, args.allow_inaccurate)?;
    let record = RunRecord {
        name: &loaded.name,
        file: loaded.file.as_deref(),
        scenario: &loaded.scenario,
        resolved: &resolved,
        summary: &summary,
        trajectory: &trajectory,
    };
    // Writing a long run's samples takes a while: shown as stages when the run showed progress
    // or the samples are many.
    let values = trajectory.len() * (2 * resolved.chain.len() + 4);
    let writing = (!ctx.quiet && (watched_progress || values > WRITE_QUIET_BELOW))
        .then(|| Progress::new("simulate", woodpile_io::rundir::WRITE_RUN_STAGES, ctx.quiet));
    woodpile_io::rundir::write_run_reporting(staging.path(), &record, &mut |stage| {
        if let Some(p) = &writing {
            p.inc(1);
            p.stage(format!("{stage} ({} samples)", trajectory.len()));
        }
    })?;
    if let Some(p) = &writing {
        p.finish();
    }
    let dir = staging.commit(RUN_FILES, RUN_MARKER)?;
    if let Some(warning) = accuracy {
        crate::out::eprintln(format_args!("warning: {warning}"));
    }
    for warning in woodpile_io::text::run_warnings(&record) {
        crate::out::eprintln(format_args!("warning: {warning}"));
    }
    if !ctx.quiet {
        crate::out::print(woodpile_io::text::run_summary(&record, &dir))?;
    }
    Ok(())
}

/// `woodpile simulate` of a lattice scenario (a `[lattice]` table, docs/physics.md §16).
fn run_lattice(args: &Args, file: &Path, text: &str, ctx: &Context) -> Result<(), CliError> {
    use woodpile_io::lattice::{write_lattice_run, LatticeScenario, LATTICE_RUN_FILES};
    let scenario = LatticeScenario::parse(text, &file.display().to_string())?;
    let (name, base) = super::name_and_base(file, "lattice");
    let resolved = scenario.resolve_in(&base)?;
    woodpile_io::lattice::run_size(&resolved).check(args.allow_long, args.allow_large, true)?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new("runs").join(&name));
    let mut ode =
        woodpile::ode::LatticeOde::build(&resolved.lattice, &resolved.excitation, &resolved.lab)
            .map_err(woodpile_io::Error::from)?;
    let staging = Staging::prepare(&out, args.overwrite)?;
    let progress = (!ctx.quiet).then(|| Progress::new("simulate", 1, ctx.quiet));
    let run = woodpile::simulate::simulate_lattice(&mut ode, &resolved.settings)
        .map_err(woodpile_io::Error::from)?;
    if let Some(p) = &progress {
        p.inc(1);
        p.finish();
    }
    let accuracy = woodpile_io::limits::check_accuracy(&run.energy, args.allow_inaccurate)?;
    write_lattice_run(
        staging.path(),
        &name,
        &scenario,
        &resolved,
        ode.contact_betas(),
        &run,
    )?;
    let dir = staging.commit(LATTICE_RUN_FILES, RUN_MARKER)?;
    if let Some(warning) = accuracy {
        crate::out::eprintln(format_args!("warning: {warning}"));
    }
    for warning in woodpile_io::text::lattice_warnings(&resolved, &run) {
        crate::out::eprintln(format_args!("warning: {warning}"));
    }
    if !ctx.quiet {
        let text = woodpile_io::text::lattice_run_summary(&name, &resolved, &ode, &run, &dir);
        crate::out::print(text)?;
    }
    Ok(())
}

/// Sampled values (samples × columns) below which writing a run's files shows no progress.
const WRITE_QUIET_BELOW: usize = 2_000_000;

/// Wall time after which a run shows its progress: shorter runs stay silent.
const QUIET_FOR: std::time::Duration = std::time::Duration::from_secs(1);

/// Passes every sample on to a recorder and, once a run has taken longer than [`QUIET_FOR`],
/// shows how much of the simulated time is done (a bar on a terminal, a line at every tenth
/// otherwise). Runs that only keep peaks (`sample_interval_s = duration_s`) have no samples to
/// count and show nothing.
struct Watched<'a, R> {
    inner: &'a mut R,
    duration_s: f64,
    quiet: bool,
    started: std::time::Instant,
    progress: Option<Progress>,
}

/// Steps of a run's progress: permille of the simulated time.
const PERMILLE: u64 = 1000;

impl<'a, R: Recorder> Watched<'a, R> {
    fn new(inner: &'a mut R, duration_s: f64, quiet: bool) -> Self {
        Watched {
            inner,
            duration_s,
            quiet,
            started: std::time::Instant::now(),
            progress: None,
        }
    }

    fn finish(&self) {
        if let Some(p) = &self.progress {
            p.finish();
        }
    }
}

impl<R: Recorder> Recorder for Watched<'_, R> {
    fn start(&mut self, layout: &Layout) {
        self.inner.start(layout);
    }

    fn record(&mut self, sample: &Sample<'_>) {
        self.inner.record(sample);
        if self.quiet || self.started.elapsed() < QUIET_FOR {
            return;
        }
        let done =
            (sample.time_s / self.duration_s * PERMILLE as f64).clamp(0.0, PERMILLE as f64) as u64;
        let p = self.progress.get_or_insert_with(|| {
            let p = Progress::since("simulate", PERMILLE, false, self.started);
            p.set_position(done);
            p.stage(simulated(sample.time_s, self.duration_s));
            p
        });
        // Lines at every tenth of the simulated time; the bar at every permille.
        let before = p.position();
        if done > before {
            p.set_position(done);
            if done / 100 > before / 100 {
                p.stage(simulated(sample.time_s, self.duration_s));
            }
        }
    }
}

/// `0.5 of 2 ms simulated`.
fn simulated(time_s: f64, duration_s: f64) -> String {
    format!(
        "{:.4} of {:.4} ms simulated",
        time_s * 1e3,
        duration_s * 1e3
    )
}
