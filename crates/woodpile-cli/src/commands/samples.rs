//! `woodpile simulate SCENARIO --samples K`: the scenario under its `[uncertainty]`, K samples
//! run together in SIMD lanes, written as samples.csv, samples/NNN.toml and summary.json.

use super::simulate::{load, Args};
use super::Context;
use crate::CliError;
use std::path::Path;
use woodpile::{simulate_many, Job, LaneWidth};
use woodpile_io::atomic::Staging;
use woodpile_io::uncertainty::{resolve_samples, samples, write_samples};

/// The files a samples directory is made of; summary.json, written last, marks it complete.
const SAMPLES_FILES: &[&str] = &["samples.csv", "summary.json"];
const SAMPLES_MARKER: &str = "summary.json";

/// Runs `woodpile simulate --samples K`.
pub fn run(args: &Args, k: usize, ctx: &Context) -> Result<(), CliError> {
    let loaded = load(&args.source, "simulate --samples")?;
    let Some(spec) = &loaded.scenario.uncertainty else {
        return Err(CliError::invalid(
            "--samples",
            k,
            "needs the scenario's [uncertainty] table (docs/optimization.md, \"Scatter\")",
        ));
    };
    if k == 0 {
        return Err(CliError::invalid("--samples", k, "at least 1 sample"));
    }
    if args.overwrite {
        return Err(CliError::invalid(
            "--overwrite",
            "true",
            "not with --samples: a samples study is never overwritten; choose another --out",
        ));
    }
    let mut u = spec.check()?;
    u.samples = k;
    woodpile_io::uncertainty::check_size(&loaded.scenario, k, "--samples", args.allow_large)?;
    let drawn = samples(&loaded.scenario, &u)?;
    let resolved = resolve_samples(&drawn, &loaded.base_dir)?;
    let staging = stage_study(
        &resolved,
        (args.allow_long, args.allow_large),
        args.out.clone(),
        Path::new("runs").join(format!("{}-samples", loaded.name)),
        SAMPLES_MARKER,
    )?;
    let jobs: Vec<Job<'_>> = resolved
        .iter()
        .map(|r| Job {
            chain: &r.chain,
            excitation: &r.excitation,
            settings: &r.settings,
        })
        .collect();
    let started = std::time::Instant::now();
    let mut runs = Vec::with_capacity(k);
    for (i, run) in simulate_many(&jobs, LaneWidth::detect())
        .into_iter()
        .enumerate()
    {
        let run = run.inspect_err(|_| {
            crate::out::eprintln(format_args!("sample {} of {k} failed:", i + 1));
        })?;
        woodpile_io::limits::check_accuracy(&run.energy, args.allow_inaccurate)?;
        runs.push(run);
    }
    let elapsed = started.elapsed().as_secs_f64();
    write_samples(staging.path(), &u, &drawn, &runs)?;
    let dir = staging.commit_study(SAMPLES_FILES, SAMPLES_MARKER)?;
    if !ctx.quiet {
        crate::out::print(woodpile_io::text::samples_summary(&dir, k, elapsed, &runs))?;
    }
    Ok(())
}

/// The run-size check of a study's runs (the first stands for all: one chain, one run setting)
/// and its staged output directory: `out`, or `default`. `--overwrite` does not apply: a
/// directory holding `marker` is refused (`Staging::prepare_study`).
pub(crate) fn stage_study(
    resolved: &[woodpile_io::scenario::Resolved],
    (allow_long, allow_large): (bool, bool),
    out: Option<std::path::PathBuf>,
    default: std::path::PathBuf,
    marker: &'static str,
) -> Result<Staging, CliError> {
    woodpile_io::limits::RunSize::estimate(&resolved[0].settings, resolved[0].chain.len()).check(
        allow_long,
        allow_large,
        true,
    )?;
    let out = out.unwrap_or(default);
    Staging::prepare_study(&out, marker)
}
