//! `woodpile plot DIR`: the figures of an output directory, written to `DIR/plots/` as PNG and
//! SVG (or the formats of `--format`), sized for a journal page. What is drawn for a run, a
//! lattice run and an optimisation is [`woodpile_plot::dirs`]; how the figures are sized is
//! [`woodpile_plot::output`].

use crate::commands::Context;
use crate::CliError;
use std::path::PathBuf;
use woodpile::analysis::Window;
use woodpile_io::rundir::{detect_dir, DirKind};
use woodpile_plot::dirs::{plot_lattice_run, plot_optimization, plot_run, RunPlot};
use woodpile_plot::{Format, Output, PlotError};

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
    /// Time window of the force histories and the force and energy maps, in ms, e.g.
    /// `--time-ms 0,0.4`. Default: the whole record, plus `force_histories_onset`, the
    /// histories zoomed on the first arrivals (chosen from the data).
    #[arg(long, value_name = "START,END", allow_hyphen_values = true)]
    pub time_ms: Option<String>,
    /// Frequency window of the spectra and the spectrum map, in kHz, e.g.
    /// `--frequency-khz 5,40` [default: 0,80].
    #[arg(
        long,
        value_name = "LO,HI",
        allow_hyphen_values = true,
        conflicts_with = "max_frequency_khz"
    )]
    pub frequency_khz: Option<String>,
    /// Highest frequency drawn in the spectra, in kHz (same as `--frequency-khz 0,KHZ`).
    #[arg(long, value_name = "KHZ")]
    pub max_frequency_khz: Option<f64>,
    /// A contact force to draw as a history and a spectrum (repeatable): `contact_K` (K = 0..N),
    /// `striker`, `load` or `actuator` (contact 0, labelled by what drives the run), `incident`
    /// (contact 1), `wall` (contact N). Default: contact 0, the incident contact and the wall.
    #[arg(long = "signal", value_name = "NAME")]
    pub signals: Vec<String>,
    /// Colours of the force and energy maps: auto (force linear from 0 to the largest force,
    /// energy log over 3 decades), robust (linear up to the 99.5 % quantile of the non-zero
    /// cells; larger values saturate, marked on the bar) or log (3 decades below the largest).
    #[arg(long, value_name = "SCALE", default_value = "auto")]
    pub colours: String,
    /// Window of the spectra: rectangular, hann, hamming, blackman-harris, flat-top.
    #[arg(long, value_name = "NAME", default_value = "rectangular")]
    pub window: String,
    /// Files written per figure, comma-separated: png, svg. No PDF (plotters has none):
    /// convert the SVG, e.g. `rsvg-convert -f pdf -o fig.pdf fig.svg`.
    #[arg(long, value_name = "LIST", default_value = "png,svg")]
    pub format: String,
    /// Resolution of the PNG files, in dots per inch (30 to 2400).
    #[arg(
        long,
        value_name = "DPI",
        default_value_t = 300.0,
        allow_hyphen_values = true
    )]
    pub dpi: f64,
    /// Printed width of every figure, in inches (0.5 to 50). Default: 7 in (178 mm, a
    /// double-column figure) for the maps, histories and spectra, narrower figures in
    /// proportion. Text prints at 7.2 to 8.7 pt (titles 11.3 pt) at any width: the figure lays
    /// itself out on a canvas of that width (3.5 in: a single column).
    #[arg(long, value_name = "IN", allow_hyphen_values = true)]
    pub width_in: Option<f64>,
    /// Printed height of every figure, in inches (0.5 to 50). Default: from the width and the
    /// figure's own aspect ratio.
    #[arg(long, value_name = "IN", allow_hyphen_values = true)]
    pub height_in: Option<f64>,
}

/// `START,END` with START < END, both finite, as a pair.
fn parse_range(flag: &str, text: &str, unit: &str) -> Result<(f64, f64), CliError> {
    let bad = |reason: &str| CliError::invalid(flag, text, reason.to_string());
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let [a, b] = parts[..] else {
        return Err(bad(&format!(
            "must be START,END in {unit} (two numbers separated by a comma)"
        )));
    };
    let (a, b) = match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(a), Ok(b)) if a.is_finite() && b.is_finite() => (a, b),
        _ => {
            return Err(bad(&format!(
                "must be START,END in {unit}, two finite numbers"
            )))
        }
    };
    if a < 0.0 || b <= a {
        return Err(bad(&format!("must have 0 <= START < END (in {unit})")));
    }
    Ok((a, b))
}

/// The output options of the flags, each checked and named in its error.
fn output(args: &Args) -> Result<Output, CliError> {
    let formats = Format::parse_list(&args.format)
        .map_err(|reason| CliError::invalid("--format", &args.format, reason))?;
    let out = Output {
        formats,
        width_in: args.width_in,
        height_in: args.height_in,
        dpi: args.dpi,
        ..Output::default()
    };
    out.check().map_err(|e| match e {
        PlotError::InvalidOutput {
            field,
            value,
            reason,
        } => CliError::invalid(format!("--{}", field.replace('_', "-")), value, reason),
        other => CliError::from(other),
    })?;
    let place = out.place((woodpile_plot::output::REFERENCE_WIDTH, 620), 1);
    let side = place.pixels.0.max(place.pixels.1);
    let png = out.formats.contains(&Format::Png);
    if f64::from(side) > woodpile_plot::output::MAX_PIXELS_PER_SIDE && png {
        return Err(CliError::invalid(
            "--dpi",
            args.dpi,
            format!(
                "gives PNG files {side} px wide or high at this size; at most {} px: lower --dpi or the size",
                woodpile_plot::output::MAX_PIXELS_PER_SIDE
            ),
        ));
    }
    Ok(out)
}

/// Runs `woodpile plot`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let window = Window::from_name(&args.window).map_err(CliError::at("--window"))?;
    let map_colours = woodpile_plot::MapColours::from_name(&args.colours).map_err(|_| {
        CliError::invalid(
            "--colours",
            &args.colours,
            format!("valid: {}", woodpile_plot::MapColours::NAMES),
        )
    })?;
    let frequency_khz = match (&args.frequency_khz, args.max_frequency_khz) {
        (Some(text), _) => parse_range("--frequency-khz", text, "kHz")?,
        (None, Some(max)) => {
            if !(max.is_finite() && max > 0.0) {
                return Err(CliError::invalid(
                    "--max-frequency-khz",
                    max,
                    "must be a finite number > 0",
                ));
            }
            (0.0, max)
        }
        (None, None) => (0.0, 80.0),
    };
    let time_ms = args
        .time_ms
        .as_deref()
        .map(|text| parse_range("--time-ms", text, "ms"))
        .transpose()?;
    let output = output(args)?;
    let out = args.out.clone().unwrap_or_else(|| args.dir.join("plots"));
    let files = match detect_dir(&args.dir)? {
        DirKind::Optimization if woodpile_io::pareto::is_pareto_dir(&args.dir) => {
            let (files, note) = woodpile_plot::dirs::plot_pareto(&args.dir, &out, &output)?;
            if let (Some(note), false) = (note, ctx.quiet) {
                crate::out::eprintln(format_args!("note: {note}"));
            }
            files
        }
        DirKind::Run => {
            let plot = RunPlot {
                time_s: time_ms.map(|(a, b)| (a * 1e-3, b * 1e-3)),
                frequency_hz: (frequency_khz.0 * 1e3, frequency_khz.1 * 1e3),
                window,
                signals: args.signals.clone(),
                map_colours,
                output,
            };
            if woodpile_io::lattice::is_lattice_run(&args.dir) {
                plot_lattice_run(&args.dir, &out, &plot)?
            } else {
                plot_run(&args.dir, &out, &plot)?
            }
        }
        DirKind::Optimization => {
            let (files, note) = plot_optimization(&args.dir, &out, &output)?;
            if let (Some(note), false) = (note, ctx.quiet) {
                crate::out::eprintln(format_args!("note: {note}"));
            }
            files
        }
        DirKind::Sensitivity => woodpile_plot::dirs::sensitivity(&args.dir, &out)?,
    };
    if !ctx.quiet {
        // One line per figure: its PNG, or its first file when no PNG is written.
        let first = output_first_ext(&files);
        let listed: Vec<&PathBuf> = files
            .iter()
            .filter(|f| f.extension().is_some_and(|e| e == first.as_str()))
            .collect();
        crate::out::println(format_args!(
            "wrote {} figures ({} files) to {}",
            listed.len(),
            files.len(),
            out.display()
        ))?;
        for f in listed {
            crate::out::println(format_args!("  {}", f.display()))?;
        }
    }
    Ok(())
}

/// The extension listed per figure: png when written, else the first file's.
fn output_first_ext(files: &[PathBuf]) -> String {
    if files
        .iter()
        .any(|f| f.extension().is_some_and(|e| e == "png"))
    {
        "png".to_string()
    } else {
        files
            .first()
            .and_then(|f| f.extension())
            .map(|e| e.to_string_lossy().into_owned())
            .unwrap_or_default()
    }
}
