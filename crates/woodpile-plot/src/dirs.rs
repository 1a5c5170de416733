//! The figure sets of woodpile's output directories, read back from their files: what
//! `woodpile plot DIR` and `woodpile cells --plot DIR` draw.
//!
//! - [`plot_run`]: a `woodpile simulate` run (it holds `run.json`): force, energy and spectrum
//!   maps, force histories at chosen contacts, their spectra, and a picture of the chain.
//! - [`plot_optimization`]: a `woodpile optimize` output (it holds `history.csv`): the GA's
//!   convergence and, once it has finished, the best chain to scale (paper Fig. 5 d, e, right).
//! - [`cells_figures`]: the catalogue's effective-mass curves with the negative-mass bands
//!   shaded (paper Fig. 3).
//!
//! Errors are [`woodpile_io::Error`], the type every front end reports.

use crate::{ConvergencePoint, PlotError, Series};
use std::fs;
use std::path::{Path, PathBuf};
use woodpile::analysis::{
    contact_spectrum_map, energy_map, force_map, linspace, Scaling, Spectrum, SpectrumSettings,
    Window,
};
use woodpile::model::TABLE1_LENGTHS_MM;
use woodpile::{EffectiveMassCurve, UnitCell};
use woodpile_io::optimize::read_output;
use woodpile_io::rundir::{read_error, read_run_info, read_trajectory};
use woodpile_io::scenario::resolve;
use woodpile_io::Error;

/// A drawing failure as an output error naming the figure's path.
impl From<PlotError> for Error {
    fn from(e: PlotError) -> Self {
        let path = match &e {
            PlotError::Draw { path, .. } => path.clone(),
            PlotError::BadData { .. } => PathBuf::from("figure"),
        };
        Error::Output {
            path,
            source: std::io::Error::other(e.to_string()),
        }
    }
}

/// Creates `dir` (and its parents).
fn create_dir(dir: &Path) -> Result<(), Error> {
    fs::create_dir_all(dir).map_err(|e| Error::Output {
        path: dir.to_path_buf(),
        source: e,
    })
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

/// Draws every figure of a run directory into `out`; returns the files written.
pub fn plot_run(
    dir: &Path,
    out: &Path,
    max_frequency_hz: f64,
    window: Window,
    signals: &[String],
) -> Result<Vec<PathBuf>, Error> {
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
    create_dir(out)?;
    let title = format!(
        "{}: {}, {}",
        info.name,
        describe_chain(&info.labels),
        info.excitation
    );
    let stem = |s: &str| out.join(s);
    let mut files = Vec::new();
    files.extend(crate::force_map(
        &force_map(&t)?,
        &title,
        &stem("force_map"),
    )?);
    files.extend(crate::energy_map(
        &energy_map(&t)?,
        &title,
        &stem("energy_map"),
    )?);
    let settings = SpectrumSettings {
        window,
        scaling: Scaling::FourierMagnitude,
        ..SpectrumSettings::default()
    };
    files.extend(crate::spectrum_map(
        &contact_spectrum_map(&t, &settings)?,
        &title,
        max_frequency_hz,
        &stem("spectrum_map"),
    )?);
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
    let series: Vec<Series> = picks
        .iter()
        .map(|(c, l)| Series::new(l.clone(), t.contact_force_n(*c)))
        .collect();
    files.extend(crate::force_histories(
        &t.times_s,
        &series,
        &title,
        &stem("force_histories"),
    )?);
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
    files.extend(crate::spectra(
        &refs,
        &woodpile::analysis::chain_bands_hz(&info.cells),
        &title,
        max_frequency_hz,
        &stem("spectra"),
    )?);
    if let Some(chain) = &info.chain {
        let chain_title = format!("{} ({} elements, top to bottom)", info.name, n);
        files.extend(crate::chain_picture(chain, &chain_title, &stem("chain"))?);
    }
    Ok(files)
}

/// The contact a `--signal` name designates, with its legend label.
pub fn signal_contact(name: &str, n: usize) -> Result<(usize, String), Error> {
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
            Error::invalid(
                "--signal",
                name,
                format!("unknown signal; valid: contact_0 .. contact_{n}, striker, load, incident, wall"),
            )
        })
}

/// The catalogue's effective-mass curves (paper Fig. 3 a: 20–40 mm, b: 50–80 mm) into `dir`.
pub fn cells_figures(dir: &Path, resonator_ratio: f64) -> Result<Vec<PathBuf>, Error> {
    create_dir(dir)?;
    let f = linspace(0.0, 60e3, 3001);
    let curves = TABLE1_LENGTHS_MM
        .iter()
        .map(|&l| {
            let cell = UnitCell::table1(l)?;
            let curve = if resonator_ratio > 0.0 {
                EffectiveMassCurve::damped(&cell, &f, resonator_ratio)?
            } else {
                EffectiveMassCurve::of(&cell, &f)
            };
            Ok((format!("{l} mm"), curve))
        })
        .collect::<Result<Vec<_>, woodpile::Error>>()?;
    let damped = if resonator_ratio > 0.0 {
        format!(" (real part, resonators damped at ζ = {resonator_ratio})")
    } else {
        String::new()
    };
    let mut files = Vec::new();
    for (curves, title, name) in [
        (
            &curves[..3],
            format!("Effective mass of 20, 30, 40 mm rods (one resonator){damped}, undamped negative-mass bands shaded"),
            "effective_mass_20_40mm",
        ),
        (
            &curves[3..],
            format!("Effective mass of 50–80 mm rods (two resonators){damped}, undamped negative-mass bands shaded"),
            "effective_mass_50_80mm",
        ),
    ] {
        files.extend(crate::effective_mass(curves, &title, 5.0, &dir.join(name))?);
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
pub fn plot_optimization(dir: &Path, out: &Path) -> Result<(Vec<PathBuf>, Option<String>), Error> {
    let output = read_output(dir)?;
    let points: Vec<ConvergencePoint> = output
        .history
        .iter()
        .map(|h| ConvergencePoint {
            generation: h.generation,
            best: h.best,
            mean: h.mean,
        })
        .collect();
    let summary = output.summary.as_ref();
    let config = output.config.as_ref();
    let objective = summary
        .map(|s| s.objective.clone())
        .or_else(|| config.and_then(|c| c.ga.objective.clone()))
        .unwrap_or_else(|| "objective".to_string());
    let unit = summary
        .map(|s| s.objective_unit.clone())
        .unwrap_or_default();
    let problem = summary.map(|s| s.problem.clone()).unwrap_or_else(|| {
        dir.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "optimisation".into())
    });
    let model = config
        .and_then(|c| c.design.model)
        .unwrap_or_default()
        .name();
    let excitation = config.map_or("impact", |c| c.excitation.kind.name());
    let seed = config
        .and_then(|c| c.ga.seed)
        .map(|s| format!(", seed {s}"))
        .unwrap_or_default();
    create_dir(out)?;
    let label = objective_label(&objective, &unit);
    let last = points[points.len() - 1];
    let title = format!(
        "Breeder GA, {problem} ({model} model, {excitation}{seed}): best {} after {} generations",
        format_value(last.best),
        last.generation
    );
    let mut files = crate::convergence(&points, &label, &title, &out.join("convergence"))?;
    let Some((best_path, scenario)) = &output.best else {
        return Ok((
            files,
            Some(format!(
                "{} is missing (the run has not finished): the best chain is not drawn",
                dir.join("best.toml").display()
            )),
        ));
    };
    let chain = resolve(scenario, best_path.parent().unwrap_or(dir))?.chain;
    let best_value = summary.map_or(last.best, |s| s.best_objective);
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
    files.extend(crate::chain_picture(
        &chain,
        chain_title.trim_end(),
        &out.join("best_chain"),
    )?);
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
