//! `woodpile plot DIR`: the figures of an output directory, written to `DIR/plots/` as PNG and
//! SVG. What is drawn for a run and for an optimisation is [`woodpile_plot::dirs`].

use crate::commands::Context;
use crate::CliError;
use std::path::PathBuf;
use woodpile::analysis::Window;
use woodpile_io::rundir::{detect_dir, DirKind};
use woodpile_plot::dirs::{plot_optimization, plot_run};

/// Arguments of `woodpile plot`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// A directory written by `woodpile simulate` (it holds run.json) or by `woodpile optimize`
    /// (it holds history.csv).
    #[arg(value_name = "DIR")]
    pub dir: PathBuf,
    /// Where to write the figures (default: DIR/plots).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Highest frequency drawn in the spectra, in kHz.
    #[arg(long, value_name = "KHZ", default_value_t = 80.0)]
    pub max_frequency_khz: f64,
    /// A contact force to draw as a history and a spectrum (repeatable): `contact_K` (K = 0..N),
    /// `striker` or `load` (contact 0), `incident` (contact 1), `wall` (contact N).
    /// Default: the striker or load, the incident contact and the wall.
    #[arg(long = "signal", value_name = "NAME")]
    pub signals: Vec<String>,
    /// Window of the spectra: rectangular, hann, hamming, blackman-harris, flat-top.
    #[arg(long, value_name = "NAME", default_value = "rectangular")]
    pub window: String,
}

/// Runs `woodpile plot`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let window = Window::from_name(&args.window).map_err(CliError::at("--window"))?;
    if !(args.max_frequency_khz.is_finite() && args.max_frequency_khz > 0.0) {
        return Err(CliError::invalid(
            "--max-frequency-khz",
            args.max_frequency_khz,
            "must be a finite number > 0",
        ));
    }
    let out = args.out.clone().unwrap_or_else(|| args.dir.join("plots"));
    let files = match detect_dir(&args.dir)? {
        DirKind::Run => plot_run(
            &args.dir,
            &out,
            args.max_frequency_khz * 1e3,
            window,
            &args.signals,
        )?,
        DirKind::Optimization => {
            let (files, note) = plot_optimization(&args.dir, &out)?;
            if let (Some(note), false) = (note, ctx.quiet) {
                eprintln!("note: {note}");
            }
            files
        }
    };
    if !ctx.quiet {
        println!("wrote {} files to {}", files.len(), out.display());
        for f in files
            .iter()
            .filter(|f| f.extension().is_some_and(|e| e == "png"))
        {
            println!("  {}", f.display());
        }
    }
    Ok(())
}
