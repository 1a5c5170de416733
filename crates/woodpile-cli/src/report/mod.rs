//! `woodpile report --out DIR [--quick] [--seed S] [--threads T]`: runs everything the paper's
//! figures and numbers need, draws every figure into `DIR/figures/` (PNG and SVG), and writes
//! `DIR/report.md` and a self-contained `DIR/report.html` (figures embedded as SVG data URIs) with a
//! comparison table: each number the paper reports (docs/physics.md §9) beside ours.
//!
//! What runs (docs/physics.md defaults throughout):
//! - homogeneous 20-rod chains of 20, 40, 80 mm rods (resonant) and 20 mm (rigid) under the
//!   impact: force and energy maps, force histories, spectra, the separated pulses at the wall
//!   (paper Figs. 5 a–c, 6);
//! - the breeder GA for the least wall force under the impact, resonant and rigid (paper Fig. 5
//!   d, e): convergence, best chain, incident and transmitted force, restitution;
//! - the layer-by-layer protocol on the resonant optimum (paper Fig. 7 a, b);
//! - the Friedlander blast on 20, 40, 80 mm chains and the paper's blast-optimised chain: peak
//!   energy of the last layer, spectra against the negative-mass bands (paper Figs. 8, 9);
//! - the effective-mass curves of the catalogue (paper Fig. 3).
//!
//! The GA results, the only expensive part, are kept in `DIR/cache/` under a stable FNV-1a hash
//! of the tool version and the complete problem (config, GA settings, seed); a rerun reuses
//! them. Everything else is re-simulated (well under a second per run). `report.md` and
//! `report.html` are written under a temporary name and renamed, so a failed run never leaves a
//! half-written report.

mod doc;
mod runs;
mod text;

use crate::commands::Context;
use crate::progress::Progress;
use crate::CliError;
use doc::Doc;
use runs::{Results, Setup};
use std::path::PathBuf;
use std::time::Instant;
use woodpile_io::atomic::write_atomic;
use woodpile_plot::dirs::cells_figures;

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
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Worker threads (default: one per core). Does not change results.
    #[arg(long, value_name = "T", default_value_t = 0)]
    pub threads: usize,
    /// Allow more than 4 worker threads per core.
    #[arg(long)]
    pub allow_many_threads: bool,
}

/// Runs `woodpile report`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let started = Instant::now();
    woodpile_io::limits::check_threads("--threads", args.threads, args.allow_many_threads)?;
    woodpile_io::study::prepare_report_dir(&args.out)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()
        .map_err(|e| CliError::invalid("--threads", args.threads, e.to_string()))?;
    let bar = Progress::new("report", STEPS, ctx.quiet);
    let result = pool.install(|| build(args, &bar));
    bar.finish();
    let (doc, summary) = result?;
    let title = "woodpile: reproduction of Kim, Yang et al. 2017 (impact and blast mitigation with locally resonant woodpiles)";
    let md = doc.markdown(title);
    let html = doc.html(title, &args.out)?;
    write_atomic(&args.out, "report.md", md.as_bytes())?;
    write_atomic(&args.out, "report.html", html.as_bytes())?;
    if !ctx.quiet {
        println!("{summary}");
        println!(
            "wrote {} figures, {} and {} in {:.1} s",
            doc.figures,
            args.out.join("report.md").display(),
            args.out.join("report.html").display(),
            started.elapsed().as_secs_f64()
        );
    }
    Ok(())
}

/// Progress steps: 4 impact chains, 2 GAs, optimum figures, protocol, 4 blast chains, 2 GAs
/// over derived cells, cells.
const STEPS: u64 = 15;

/// Runs everything and assembles the document; returns it and a short text summary.
fn build(args: &Args, bar: &Progress) -> Result<(Doc, String), CliError> {
    let s = Setup::new(args, bar);
    bar.stage("homogeneous chains under impact");
    let (impact_cases, wall_compare, waves) = runs::impact_homogeneous(&s)?;
    let (ga_res, ga_rig, optima) = runs::optima(&s)?;
    bar.stage("layer-by-layer protocol");
    let (protocol, protocol_damped, protocol_map_files, protocol_peak_files) =
        runs::protocol(&s, &optima[0].0)?;
    bar.inc(1);
    bar.stage("blast cases");
    let blast = runs::blast(&s)?;
    let fine = runs::fine(&s)?;
    bar.stage("transmission spectrum");
    let transmission = runs::transmission(&s)?;
    bar.stage("effective-mass curves");
    let cells_files = cells_figures(&s.figs, 0.0)?;
    bar.inc(1);
    bar.stage("writing the report");
    let r = Results {
        impact_cases,
        wall_compare,
        waves,
        ga_res,
        ga_rig,
        optima,
        protocol,
        protocol_damped,
        protocol_map_files,
        protocol_peak_files,
        blast,
        fine,
        transmission,
        cells_files,
        elapsed: bar.elapsed().as_secs_f64(),
    };
    let mut doc = Doc::default();
    text::write(&mut doc, &s, &r);
    bar.inc(1);
    Ok((doc, text::summary(&r)))
}
