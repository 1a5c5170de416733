//! `woodpile plot DIR`: the figures of an output directory, written to `DIR/plots/` as PNG and
//! SVG.
//!
//! - A `woodpile simulate` run (it holds `run.json`): force map, energy map, spectrum map, force
//!   histories at the striker contact, contact 1 and the wall, their spectra, and a picture of the
//!   chain ([`plot_run`]).
//! - A `woodpile optimize` output (it holds `history.csv` and `summary.json`, `best.toml` or
//!   `checkpoint.json`): the convergence of the GA (best and mean objective per generation) and
//!   the best chain as a picture of rods to scale, like the right panels of paper Fig. 5 d, e
//!   ([`plot_optimization`]).
//!
//! Also [`cells_figures`] for `woodpile cells --plot DIR`: the effective-mass curves of the
//! catalogue with the negative-mass bands shaded (paper Fig. 3).

use crate::commands::Context;
use crate::CliError;
use serde_json::Value;
use std::fs;
use std::path::{Path, PathBuf};
use woodpile::analysis::{
    contact_spectrum_map, energy_map, force_map, linspace, Spectrum, SpectrumSettings, Window,
};
use woodpile::model::TABLE1_LENGTHS_MM;
use woodpile::{EffectiveMassCurve, UnitCell};
use woodpile_io::optimize::read_history;
use woodpile_io::rundir::{detect_dir, read_error, read_run_info, read_trajectory, DirKind};
use woodpile_io::scenario::{resolve, Scenario};
use woodpile_plot as plot;

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

/// A short description of the chain: `20 × 80mm` or the labels top to bottom.
pub fn describe_chain(labels: &[String]) -> String {
    match labels {
        [] => "empty chain".to_string(),
        [first, rest @ ..] if rest.iter().all(|l| l == first) => {
            format!("{} × {first}", labels.len())
        }
        _ if labels.len() <= 8 => labels.join(" "),
        _ => format!(
            "{} elements ({} … {})",
            labels.len(),
            labels[..3].join(" "),
            labels[labels.len() - 2..].join(" ")
        ),
    }
}

/// A plotting failure as a CLI output error naming the figure's path.
pub(crate) fn plot_err(e: plot::PlotError) -> CliError {
    let path = match &e {
        plot::PlotError::Draw { path, .. } => path.clone(),
        plot::PlotError::BadData { .. } => PathBuf::from("figure"),
    };
    CliError::Output {
        path,
        source: std::io::Error::other(e.to_string()),
    }
}

/// The negative-mass bands to shade: those of the chain's cells when it has at most two
/// different cells (more would cover the whole axis; paper §5: no common band then).
fn bands_to_shade(cells: &[UnitCell]) -> Vec<(f64, f64)> {
    let mut distinct: Vec<&UnitCell> = Vec::new();
    for c in cells {
        if !distinct.contains(&c) {
            distinct.push(c);
        }
    }
    if distinct.len() > 2 {
        return Vec::new();
    }
    let mut bands: Vec<(f64, f64)> = distinct
        .iter()
        .flat_map(|c| c.negative_mass_bands_hz())
        .collect();
    bands.sort_by(|a, b| a.0.total_cmp(&b.0));
    bands
}

/// Draws every figure of a run directory into `out`; returns the files written.
pub fn plot_run(
    dir: &Path,
    out: &Path,
    max_frequency_hz: f64,
    window: Window,
    signals: &[String],
) -> Result<Vec<PathBuf>, CliError> {
    let info = read_run_info(dir)?;
    let n = info.labels.len();
    let signal_picks = signals
        .iter()
        .map(|name| signal_contact(name, n))
        .collect::<Result<Vec<_>, _>>()?;
    let t = read_trajectory(dir, n)?;
    if t.len() < 2 {
        return Err(read_error(
            &dir.join("time_s.npy"),
            "fewer than 2 samples: nothing to plot",
        ));
    }
    fs::create_dir_all(out).map_err(|e| CliError::Output {
        path: out.to_path_buf(),
        source: e,
    })?;
    let title = format!(
        "{}: {}, {}",
        info.name,
        describe_chain(&info.labels),
        info.excitation
    );
    let stem = |s: &str| out.join(s);
    let mut files = Vec::new();
    files.extend(plot::force_map(&force_map(&t)?, &title, &stem("force_map")).map_err(plot_err)?);
    files
        .extend(plot::energy_map(&energy_map(&t)?, &title, &stem("energy_map")).map_err(plot_err)?);
    let settings = SpectrumSettings {
        window,
        ..SpectrumSettings::default()
    };
    files.extend(
        plot::spectrum_map(
            &contact_spectrum_map(&t, &settings)?,
            &title,
            max_frequency_hz,
            &stem("spectrum_map"),
        )
        .map_err(plot_err)?,
    );
    let striker_label = if info.excitation.starts_with("impact") {
        "contact 0 (striker)"
    } else {
        "contact 0 (load)"
    };
    let mut picks = vec![(0, striker_label.to_string())];
    if n >= 2 {
        picks.push((1, "contact 1 (incident)".to_string()));
    }
    picks.push((n, format!("contact {n} (wall)")));
    if !signal_picks.is_empty() {
        picks = signal_picks;
    }
    let series: Vec<plot::Series> = picks
        .iter()
        .map(|(c, l)| plot::Series::new(l.clone(), t.contact_force_n(*c)))
        .collect();
    files.extend(
        plot::force_histories(&t.times_s, &series, &title, &stem("force_histories"))
            .map_err(plot_err)?,
    );
    let dt = woodpile::analysis::sample_interval_s(&t)?;
    let spectra = picks
        .iter()
        .map(|(c, l)| {
            Ok((
                l.clone(),
                Spectrum::of(&t.contact_force_n(*c), dt, &settings)?,
            ))
        })
        .collect::<Result<Vec<_>, woodpile::Error>>()?;
    let refs: Vec<(String, &Spectrum)> = spectra.iter().map(|(l, s)| (l.clone(), s)).collect();
    files.extend(
        plot::spectra(
            &refs,
            &bands_to_shade(&info.cells),
            &title,
            max_frequency_hz,
            &stem("spectra"),
        )
        .map_err(plot_err)?,
    );
    if let Some(chain) = &info.chain {
        let chain_title = format!("{} ({} elements, top to bottom)", info.name, n);
        files.extend(plot::chain_picture(chain, &chain_title, &stem("chain")).map_err(plot_err)?);
    }
    Ok(files)
}

/// The contact a `--signal` name designates, with its legend label.
fn signal_contact(name: &str, n: usize) -> Result<(usize, String), CliError> {
    let contact = match name {
        "striker" | "load" => Some(0),
        "incident" if n >= 2 => Some(1),
        "wall" => Some(n),
        _ => name
            .strip_prefix("contact_")
            .and_then(|k| k.parse::<usize>().ok())
            .filter(|&k| k <= n),
    };
    contact
        .map(|c| {
            let label = if name.starts_with("contact_") {
                format!("contact {c}")
            } else {
                format!("contact {c} ({name})")
            };
            (c, label)
        })
        .ok_or_else(|| {
            CliError::invalid(
                "--signal",
                name,
                format!("unknown signal; valid: contact_0 .. contact_{n}, striker, load, incident, wall"),
            )
        })
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

/// The catalogue's effective-mass curves (paper Fig. 3 a: 20–40 mm, b: 50–80 mm) into `dir`.
pub fn cells_figures(dir: &Path) -> Result<Vec<PathBuf>, CliError> {
    fs::create_dir_all(dir).map_err(|e| CliError::Output {
        path: dir.to_path_buf(),
        source: e,
    })?;
    let f = linspace(0.0, 60e3, 3001);
    let curves = TABLE1_LENGTHS_MM
        .iter()
        .map(|&l| {
            Ok((
                format!("{l} mm"),
                EffectiveMassCurve::of(&UnitCell::table1(l)?, &f),
            ))
        })
        .collect::<Result<Vec<_>, woodpile::Error>>()?;
    let mut files = Vec::new();
    for (curves, title, name) in [
        (
            &curves[..3],
            "Effective mass of 20, 30, 40 mm rods (one resonator), negative-mass bands shaded",
            "effective_mass_20_40mm",
        ),
        (
            &curves[3..],
            "Effective mass of 50–80 mm rods (two resonators), negative-mass bands shaded",
            "effective_mass_50_80mm",
        ),
    ] {
        files.extend(plot::effective_mass(curves, title, 5.0, &dir.join(name)).map_err(plot_err)?);
    }
    Ok(files)
}

/// The objective's axis label, from its name and unit.
pub fn objective_label(name: &str, unit: &str) -> String {
    match name {
        "transmitted-force" => "transmitted peak force (wall) [N]".to_string(),
        "transmission-ratio" => "transmitted / incident peak force [-]".to_string(),
        "transmitted-energy" => "peak energy of the last layer [J]".to_string(),
        "transmitted-impulse" => "impulse delivered to the wall [N s]".to_string(),
        _ if unit.is_empty() || unit == "1" => format!("{name} [-]"),
        _ => format!("{name} [{unit}]"),
    }
}

/// Draws the figures of a `woodpile optimize` output into `out`: `convergence` (best and mean
/// objective per generation) and, once the run has written `best.toml`, `best_chain` (rods to
/// scale, top to bottom). Returns the files written and a note when the chain could not be drawn.
pub fn plot_optimization(
    dir: &Path,
    out: &Path,
) -> Result<(Vec<PathBuf>, Option<String>), CliError> {
    let points: Vec<plot::ConvergencePoint> = read_history(&dir.join("history.csv"))?
        .into_iter()
        .map(|h| plot::ConvergencePoint {
            generation: h.generation,
            best: h.best,
            mean: h.mean,
        })
        .collect();
    // What was optimised: summary.json of a finished run, else the checkpoint's config.
    let read_json = |name: &str| -> Result<Option<Value>, CliError> {
        let path = dir.join(name);
        if !path.is_file() {
            return Ok(None);
        }
        let text = fs::read_to_string(&path).map_err(|e| CliError::Read {
            path: path.clone(),
            source: e,
        })?;
        serde_json::from_str(&text)
            .map(Some)
            .map_err(|e| CliError::Parse {
                source_name: path.display().to_string(),
                message: e.to_string(),
            })
    };
    let summary = read_json("summary.json")?;
    let config = match &summary {
        Some(s) => s.get("config").cloned(),
        None => read_json(woodpile_io::optimize::CHECKPOINT_FILE)?
            .and_then(|c| c.get("config").cloned()),
    };
    let text_at = |v: Option<&Value>, pointer: &str| {
        v.and_then(|v| v.pointer(pointer))
            .and_then(Value::as_str)
            .map(str::to_string)
    };
    let objective = text_at(summary.as_ref(), "/objective")
        .or_else(|| text_at(config.as_ref(), "/ga/objective"))
        .unwrap_or_else(|| "objective".to_string());
    let unit = text_at(summary.as_ref(), "/objective_unit").unwrap_or_default();
    let problem = text_at(summary.as_ref(), "/problem").unwrap_or_else(|| {
        dir.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "optimisation".into())
    });
    let model = text_at(config.as_ref(), "/design/model").unwrap_or_else(|| "resonant".into());
    let excitation =
        text_at(config.as_ref(), "/excitation/kind").unwrap_or_else(|| "impact".into());
    let seed = config
        .as_ref()
        .and_then(|c| c.pointer("/ga/seed"))
        .and_then(Value::as_u64)
        .map(|s| format!(", seed {s}"))
        .unwrap_or_default();
    fs::create_dir_all(out).map_err(|e| CliError::Output {
        path: out.to_path_buf(),
        source: e,
    })?;
    let label = objective_label(&objective, &unit);
    let last = points[points.len() - 1];
    let title = format!(
        "Breeder GA, {problem} ({model} model, {excitation}{seed}): best {} after {} generations",
        format_value(last.best),
        last.generation
    );
    let mut files =
        plot::convergence(&points, &label, &title, &out.join("convergence")).map_err(plot_err)?;
    let best = dir.join("best.toml");
    if !best.is_file() {
        return Ok((
            files,
            Some(format!(
                "{} is missing (the run has not finished): the best chain is not drawn",
                best.display()
            )),
        ));
    }
    let scenario = Scenario::load(&best)?;
    let chain = resolve(&scenario, dir)?.chain;
    let best_value = summary
        .as_ref()
        .and_then(|s| s.get("best_objective"))
        .and_then(Value::as_f64)
        .unwrap_or(last.best);
    let short = match objective.as_str() {
        "transmitted-force" => "wall force",
        "transmission-ratio" => "ratio",
        "transmitted-energy" => "last-layer energy",
        "transmitted-impulse" => "wall impulse",
        other => other,
    };
    // Short enough for the picture's width: the chain's own labels say the rest.
    let chain_title = format!(
        "Best chain ({model}, {excitation}): {short} {} {unit}",
        format_value(best_value)
    );
    files.extend(
        plot::chain_picture(&chain, chain_title.trim_end(), &out.join("best_chain"))
            .map_err(plot_err)?,
    );
    Ok((files, None))
}

/// Four significant digits.
fn format_value(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:.3e}")
    } else {
        let decimals = (3 - v.abs().log10().floor() as i32).clamp(0, 6) as usize;
        format!("{v:.decimals$}")
    }
}
