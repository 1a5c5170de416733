//! `woodpile fit`: calibrate a scenario's parameters to measured signals (docs/fit.md) and write
//! `fit.json`, `fitted.toml`, `residuals.csv` and a figure per signal in `plots/`. Ctrl-C stops the fit and writes the best point
//! so far (without uncertainties), then exits 130.

use super::Context;
use crate::progress::Progress;
use crate::{interrupt, out, CliError};
use std::path::{Path, PathBuf};
use woodpile::fit::{fit, predict, FitProgress, FitResult, FitSettings, Prediction};
use woodpile_io::fit::{check_output, load, write_outputs, FitSetup};

/// Arguments of `woodpile fit`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// The fit file (docs/fit.md): the scenario, the measured CSV files and the parameters.
    #[arg(value_name = "FIT.toml")]
    pub file: PathBuf,
    /// Output directory (default: ./runs/NAME-fit).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Replace the files of an earlier fit in --out.
    #[arg(long)]
    pub overwrite: bool,
    /// Allow a fit of more than 1e6 model runs planned (fit.starts × fit.max_evaluations).
    #[arg(long)]
    pub allow_large: bool,
    /// Worker threads (`--threads`, `--allow-many-threads`): a Jacobian's runs go in parallel.
    #[command(flatten)]
    pub workers: super::Workers,
}

/// Runs `woodpile fit`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let threads = args.workers.checked()?;
    let setup = load(&args.file).map_err(super::chains_only("fit"))?;
    woodpile_io::limits::check_fit(setup.starts, setup.max_evaluations, args.allow_large)?;
    let (name, _) = super::name_and_base(&args.file, "fit");
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("runs").join(format!("{name}-fit")));
    check_output(&dir, args.overwrite)?;
    setup.check_signals()?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::invalid("--threads", threads, e.to_string()))?;
    interrupt::cooperative(false);
    let model = |v: &[f64]| setup.model(v);
    let problem = setup.problem(&model);
    let bar = Progress::new("fit", setup.starts as u64, ctx.quiet);
    let report = |p: FitProgress| {
        bar.set_position(p.start as u64);
        bar.detail(format!(
            "start {}/{}: {} runs, best cost {:.4e}",
            p.start + 1,
            p.starts,
            p.evaluations,
            p.best_cost
        ));
    };
    let settings = FitSettings {
        starts: setup.starts,
        max_evaluations: setup.max_evaluations,
        seed: setup.seed,
        stop: Some(interrupt::stop_flag()),
        progress: Some(&report),
        ..FitSettings::default()
    };
    let result = pool.install(|| fit(&problem, &settings));
    bar.finish();
    let result = result?;
    let prediction = predict(&problem, &result.estimates)?;
    write_outputs(&dir, args.overwrite, &setup, &result, &prediction)?;
    if let Err(e) = draw(&setup, &result, &prediction, &dir.join("plots")) {
        out::eprintln(format_args!("warning: the figures were not drawn: {e}"));
    }
    if !ctx.quiet {
        print_summary(&setup, &result, &dir)?;
    }
    if result.interrupted {
        return Err(CliError::Interrupted {
            saved: format!(
                "the best point so far is in {} (fit.json: \"interrupted\": true, no uncertainties)",
                dir.display()
            ),
        });
    }
    Ok(())
}

/// One figure per signal in `plots`: `fit_COLUMN.png` and `.svg` (measured and model above, the
/// residual below), and `correlation.png`/`.svg` (the estimates' correlation matrix, when the
/// fit has uncertainties).
fn draw(
    setup: &FitSetup,
    result: &FitResult,
    prediction: &Prediction,
    plots: &Path,
) -> Result<(), String> {
    std::fs::create_dir_all(plots).map_err(|e| format!("{}: {e}", plots.display()))?;
    let mut used = std::collections::BTreeSet::new();
    for (k, (m, model)) in setup
        .measurements
        .iter()
        .zip(&prediction.values)
        .enumerate()
    {
        let clean: String = m
            .label
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let mut name = format!("fit_{clean}");
        if !used.insert(name.clone()) {
            name = format!("{name}_{k}");
        }
        let (file, column) = &setup.sources[k];
        let title = format!("{file}: {column} against {}", m.output.name());
        let y_label = format!("{} [{}]", m.output.name(), m.output.unit());
        woodpile_plot::fit_signal(
            &m.times_s,
            &m.values,
            model,
            &title,
            &y_label,
            &plots.join(name),
        )
        .map_err(|e| e.to_string())?;
    }
    if let Some(u) = &result.uncertainty {
        woodpile_plot::correlation_matrix(
            &result.names,
            &u.correlation,
            "correlation of the estimates",
            &plots.join("correlation"),
        )
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// The estimates, their intervals, the residual RMS and the warnings, on standard output.
fn print_summary(setup: &FitSetup, r: &FitResult, dir: &std::path::Path) -> Result<(), CliError> {
    out::println(format_args!(
        "{:<32} {:>14} {:>12} {:>30}",
        "parameter", "estimate", "std error", "95 % interval"
    ))?;
    for (k, name) in r.names.iter().enumerate() {
        let u = r.uncertainty.as_ref();
        let se = u
            .and_then(|u| u.std_errors[k])
            .map_or("-".into(), |s| format!("{s:.4e}"));
        let ci = u
            .and_then(|u| u.ci95[k])
            .map_or("-".into(), |[a, b]| format!("[{a:.5e}, {b:.5e}]"));
        out::println(format_args!(
            "{name:<32} {:>14.7e} {se:>12} {ci:>30}",
            r.estimates[k]
        ))?;
    }
    for ((m, (file, column)), rms) in setup
        .measurements
        .iter()
        .zip(&setup.sources)
        .zip(&r.residual_rms)
    {
        out::println(format_args!(
            "residual RMS of {file}:{column} ({}): {rms:.4e} {} ({:.2} % of its peak)",
            m.output.name(),
            m.output.unit(),
            100.0 * rms / m.scale
        ))?;
    }
    if let Some(u) = &r.uncertainty {
        out::println(format_args!(
            "condition number {:.3e}; {} model runs, {} starts",
            u.condition_number,
            r.evaluations,
            r.starts.len()
        ))?;
    }
    for w in &r.warnings {
        out::eprintln(format_args!("warning: {w}"));
    }
    out::println(format_args!("wrote {}", dir.display()))
}
