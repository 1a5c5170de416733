//! `woodpile sensitivity SCENARIO --out DIR`: Sobol' indices of the figures of merit over the
//! scenario's `[uncertainty]` (Saltelli design, SALib's estimators), the runs in SIMD lanes.

use super::simulate::{load, Source};
use super::Context;
use crate::progress::Progress;
use crate::CliError;
use std::path::{Path, PathBuf};
use woodpile::sensitivity::Bootstrap;
use woodpile::{simulate_many, Job, LaneWidth};
use woodpile_io::sensitivity::{accuracy_targeted, design, figure_indices, FILES, MARKER};

/// Arguments of `woodpile sensitivity`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// The scenario; it needs an `[uncertainty]` table (docs/sensitivity.md).
    #[command(flatten)]
    pub source: Source,
    /// Output directory (default: ./runs/NAME-sensitivity); an existing one is refused.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Base samples N, a power of two: N·(G + 2) runs for G scattered parameters.
    #[arg(long, allow_negative_numbers = true, value_name = "N", default_value_t = woodpile::defaults::SENSITIVITY_BASE_SAMPLES)]
    pub base_samples: usize,
    /// Seed of the Sobol' points (default: the scenario's `[uncertainty] seed`); also seeds the
    /// bootstrap.
    #[arg(long, allow_negative_numbers = true, value_name = "S")]
    pub seed: Option<u32>,
    /// Run with the scenario's own run settings (the paper's RK4 at 0.1 µs when it states none)
    /// instead of the design studies' default, every contact peak within 1e-5.
    #[arg(long)]
    pub paper_settings: bool,
    /// Keep runs whose energy balance is off by more than 1e-2 (docs/physics.md §8).
    #[arg(long)]
    pub allow_inaccurate: bool,
    /// Allow runs of more than 1e9 integration steps.
    #[arg(long)]
    pub allow_long: bool,
    /// Allow a study of more than 1e6 elements in all (runs × chain elements).
    #[arg(long)]
    pub allow_large: bool,
}

/// Runs of one progress step: the lanes are refilled from one queue within a chunk.
const CHUNK: usize = 256;

/// Runs `woodpile sensitivity`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let mut loaded = load(&args.source, "sensitivity")?;
    let Some(spec) = &loaded.scenario.uncertainty else {
        return Err(CliError::invalid(
            "uncertainty",
            "(none)",
            "woodpile sensitivity needs the scenario's [uncertainty] table: the parameters to scatter and their distributions (docs/sensitivity.md)",
        ));
    };
    let mut u = spec.check()?;
    if let Some(seed) = args.seed {
        u.seed = seed;
    }
    let (mut accuracy, fast) = accuracy_targeted(&mut loaded.scenario, args.paper_settings);
    if fast {
        accuracy.push_str(" (--paper-settings: the scenario's own run settings)");
    }
    let samples = ("--base-samples", args.base_samples);
    let d = design(&loaded.scenario, &u, samples, args.allow_large)?;
    let resolved = woodpile_io::uncertainty::resolve_samples(&d.samples, &loaded.base_dir)?;
    let staging = super::samples::stage_study(
        &resolved,
        (args.allow_long, false),
        args.out.clone(),
        Path::new("runs").join(format!("{}-sensitivity", loaded.name)),
        MARKER,
    )?;
    let rows = resolved.len();
    if !ctx.quiet {
        crate::out::println(format_args!(
            "{} parameters ({}), N = {}: {rows} runs; accuracy: {accuracy}",
            d.parameters.len(),
            d.parameters.join(", "),
            d.base_samples
        ))?;
    }
    let started = std::time::Instant::now();
    let runs = run_rows(&resolved, args.allow_inaccurate, ctx.quiet)?;
    let elapsed = started.elapsed().as_secs_f64();
    let bootstrap = Bootstrap {
        seed: u64::from(u.seed),
        ..Bootstrap::default()
    };
    let per_figure = figure_indices(&d, &runs, &bootstrap);
    woodpile_io::sensitivity::write(
        staging.path(),
        &d,
        &runs,
        &bootstrap,
        &per_figure,
        &accuracy,
    )?;
    let dir = staging.commit_study(FILES, MARKER)?;
    let figure_dir = dir.join("plots");
    let plotted = woodpile_plot::dirs::sensitivity(&dir, &figure_dir);
    if !ctx.quiet {
        crate::out::print(woodpile_io::text::sensitivity_summary(
            &d.parameters,
            &per_figure,
            rows,
            elapsed,
            &dir,
        ))?;
        match plotted {
            Ok(files) => crate::out::println(format_args!(
                "figures      {}",
                files
                    .iter()
                    .map(|f| f.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ))?,
            Err(e) => crate::out::eprintln(format_args!("warning: no bar chart: {e}")),
        }
    }
    Ok(())
}

/// Every row's run, in lanes `CHUNK` at a time (a progress step each), each checked for
/// accuracy; a failed run names its row.
fn run_rows(
    resolved: &[woodpile_io::scenario::Resolved],
    allow_inaccurate: bool,
    quiet: bool,
) -> Result<Vec<woodpile::RunSummary>, CliError> {
    let rows = resolved.len();
    let progress = Progress::new("runs", rows as u64, quiet);
    let mut runs = Vec::with_capacity(rows);
    for (c, chunk) in resolved.chunks(CHUNK).enumerate() {
        let jobs: Vec<Job<'_>> = chunk
            .iter()
            .map(|r| Job {
                chain: &r.chain,
                excitation: &r.excitation,
                settings: &r.settings,
            })
            .collect();
        for (i, run) in simulate_many(&jobs, LaneWidth::detect())
            .into_iter()
            .enumerate()
        {
            let row = c * CHUNK + i + 1;
            let run = run.inspect_err(|_| {
                crate::out::eprintln(format_args!("run {row} of {rows} failed:"));
            })?;
            woodpile_io::limits::check_accuracy(&run.energy, allow_inaccurate)?;
            runs.push(run);
        }
        progress.inc(chunk.len() as u64);
    }
    progress.finish();
    Ok(runs)
}
