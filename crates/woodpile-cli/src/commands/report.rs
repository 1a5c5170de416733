//! `woodpile report --out DIR [--quick] [--seed S] [--threads T]`: the paper's study
//! ([`woodpile_report`]: every run, figure and number the paper's figures need, compared with
//! the paper), written as `DIR/report.md` and a self-contained `DIR/report.html` with the figures
//! in `DIR/figures/` and the GA results cached in `DIR/cache/`. This module owns the arguments,
//! the output directory's policy and the progress bar.

use crate::commands::Context;
use crate::progress::Progress;
use crate::CliError;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use woodpile_io::atomic::{io_err, write_atomic};
use woodpile_report::Setup;

/// Arguments of `woodpile report`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// Output directory: report.md, report.html, figures/, cache/ (created; a directory that
    /// holds anything else than an earlier report is refused).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// A smaller version for CI: GAs of population 10 × 5 generations, a 2 × 2 blast sweep (the
    /// figures keep their meaning; the optima are not converged).
    #[arg(long)]
    pub quick: bool,
    /// Seed of both GAs.
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "S",
        default_value_t = 1
    )]
    pub seed: u64,
    /// Worker threads (`--threads`, `--allow-many-threads`).
    #[command(flatten)]
    pub workers: super::Workers,
}

/// Runs `woodpile report`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let started = Instant::now();
    args.workers.checked()?;
    prepare_dir(&args.out)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.workers.threads)
        .build()
        .map_err(|e| CliError::invalid("--threads", args.workers.threads, e.to_string()))?;
    let bar = Progress::new("report", woodpile_report::STEPS, ctx.quiet);
    let s = Setup::new(
        args.out.clone(),
        args.quick,
        args.seed,
        args.workers.threads,
        &bar,
    );
    let result = pool.install(|| woodpile_report::build(&s));
    bar.finish();
    let (doc, summary) = result?;
    let md = doc.markdown(woodpile_report::TITLE);
    let html = doc.html(woodpile_report::TITLE)?;
    write_atomic(&args.out, "report.md", md.as_bytes())?;
    write_atomic(&args.out, "report.html", html.as_bytes())?;
    if !ctx.quiet {
        crate::out::println(summary)?;
        crate::out::println(format_args!(
            "wrote {} figures, {} and {} in {:.1} s",
            doc.figures,
            args.out.join("report.md").display(),
            args.out.join("report.html").display(),
            started.elapsed().as_secs_f64()
        ))?;
    }
    Ok(())
}

/// The output policy: `out` is created if absent; an existing directory must be empty or hold an
/// earlier report (report.md, report.html, figures/, cache/), which is then updated in place;
/// `figures/` and `cache/` are created and the directory is proved writable before any work.
fn prepare_dir(out: &Path) -> Result<(), CliError> {
    if out.exists() && !out.is_dir() {
        return Err(CliError::invalid(
            "--out",
            out.display(),
            "is a file, not a directory; choose a directory",
        ));
    }
    if out.is_dir() {
        let mut entries = fs::read_dir(out).map_err(io_err(out))?;
        let known = ["report.md", "report.html", "figures", "cache"];
        let earlier = known.iter().any(|k| out.join(k).exists());
        if entries.next().is_some() && !earlier {
            return Err(CliError::invalid(
                "--out",
                out.display(),
                "exists, is not empty and holds no earlier report: refusing to write into it; choose another --out",
            ));
        }
    }
    for d in [out.to_path_buf(), out.join("figures"), out.join("cache")] {
        fs::create_dir_all(&d).map_err(io_err(&d))?;
    }
    write_atomic(out, ".write-test", b"")?;
    let _ = fs::remove_file(out.join(".write-test"));
    Ok(())
}

impl woodpile_report::Progress for Progress {
    fn stage(&self, stage: &str) {
        Progress::stage(self, stage);
    }
    fn detail(&self, detail: &str) {
        Progress::detail(self, detail);
    }
    fn inc(&self, n: u64) {
        Progress::inc(self, n);
    }
    fn elapsed(&self) -> Duration {
        Progress::elapsed(self)
    }
}
