//! The figure sets of woodpile's output directories, read back from their files: what
//! `woodpile plot DIR` and `woodpile cells --plot DIR` draw.
//!
//! - [`plot_run`]: a `woodpile simulate` run (it holds `run.json`): force, energy and spectrum
//!   maps, force histories at chosen contacts (and the same zoomed on the first arrivals), their
//!   spectra, and a picture of the chain, with the time and frequency windows and the output
//!   of a [`RunPlot`].
//! - [`plot_lattice_run`]: a `woodpile simulate` run of a lattice (its `run.json` has the
//!   lattice format): the supports' forces and their sum against time, a map of every
//!   contact's force over time (striker, crossings layer by layer, supports), each interface's
//!   contact forces on the crossing grid window by window, and a three-dimensional view of
//!   the lattice coloured by peak contact force.
//! - [`plot_optimization`]: a `woodpile optimize` output (it holds `history.csv`): the GA's
//!   convergence and, once it has finished, the best chain to scale (paper Fig. 5 d, e, right).
//! - [`plot_pareto`]: an NSGA-II output (its `history.csv` has a hypervolume): the front with
//!   reference designs marked, the front's designs as rods, the hypervolume per generation.
//! - [`sensitivity`]: a `woodpile sensitivity` output (it holds `indices.csv`): a bar chart of
//!   S1 and ST with their confidence intervals per figure of merit.
//! - [`cells_figures`]: the catalogue's effective-mass curves with the negative-mass bands
//!   shaded (paper Fig. 3).
//!
//! Errors are [`woodpile_io::Error`], the type every front end reports.

use crate::{with_output, ConvergencePoint, Output, PlotError, Series};
use std::fs;
use std::path::{Path, PathBuf};
use woodpile::analysis::{
    contact_spectrum_map, energy_map, force_map, linspace, Axis, Scaling, Spectrum,
    SpectrumSettings, Window,
};
use woodpile::model::TABLE1_LENGTHS_MM;
use woodpile::{EffectiveMassCurve, UnitCell};
use woodpile::{Map2, Trajectory};
use woodpile_io::optimize::read_output;
use woodpile_io::rundir::{read_error, read_run_info, read_trajectory};
use woodpile_io::scenario::resolve;
use woodpile_io::Error;

/// A drawing failure as an output error naming the figure's path; an output option out of
/// range as invalid input naming the option.
impl From<PlotError> for Error {
    fn from(e: PlotError) -> Self {
        let path = match e {
            PlotError::InvalidOutput {
                field,
                value,
                reason,
            } => return Error::invalid(field, value, reason),
            PlotError::Draw { ref path, .. } => path.clone(),
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

/// What [`plot_run`] draws of a run, and how it writes it.
#[derive(Debug, Clone, PartialEq)]
pub struct RunPlot {
    /// Time window \[s\] of the force histories and the force and energy maps; None: the whole
    /// record, plus `force_histories_onset`, the histories zoomed on the first arrivals
    /// ([`crate::onset_window_s`]). The spectra are always those of the whole record.
    pub time_s: Option<(f64, f64)>,
    /// Frequency window \[Hz\] of the spectra and the spectrum map.
    pub frequency_hz: (f64, f64),
    /// Window function of the spectra.
    pub window: Window,
    /// Contacts drawn as histories and spectra (names as for [`signal_contact`]); empty: the
    /// driven contact, contact 1 and the wall.
    pub signals: Vec<String>,
    /// Colours of the force and energy maps.
    pub map_colours: crate::MapColours,
    /// Formats, printed size and resolution.
    pub output: Output,
}

impl Default for RunPlot {
    /// The whole record, 0–80 kHz, rectangular window, default contacts and output.
    fn default() -> Self {
        RunPlot {
            time_s: None,
            frequency_hz: (0.0, 80e3),
            window: Window::Rectangular,
            signals: Vec::new(),
            map_colours: crate::MapColours::Auto,
            output: Output::default(),
        }
    }
}

/// What drives contact 0 of a run, from its excitation (`impact …`, `blast …`, `drive …`):
/// the name its legends and titles give it.
pub fn contact0_role(excitation: &str) -> Option<&'static str> {
    match excitation.split_whitespace().next() {
        Some("impact") => Some("striker"),
        Some("blast") => Some("load"),
        Some("drive") => Some("actuator"),
        _ => None,
    }
}

/// The columns of `map` with `lo <= x <= hi`; None when fewer than 2 are inside.
fn columns_between(map: &Map2, lo: f64, hi: f64) -> Result<Option<Map2>, Error> {
    let keep: Vec<usize> = (0..map.n_cols())
        .filter(|&c| lo <= map.cols.values[c] && map.cols.values[c] <= hi)
        .collect();
    if keep.len() < 2 {
        return Ok(None);
    }
    let cols = Axis::new(
        map.cols.name.clone(),
        map.cols.unit.clone(),
        keep.iter().map(|&c| map.cols.values[c]).collect(),
    );
    let data = (0..map.n_rows())
        .flat_map(|r| {
            let row = map.row(r);
            keep.iter().map(move |&c| row[c])
        })
        .collect();
    Ok(Some(Map2::new(
        map.rows.clone(),
        cols,
        map.value_name.clone(),
        map.value_unit.clone(),
        data,
    )?))
}

/// Draws every figure of a run directory into `out`: `force_map`, `energy_map`,
/// `spectrum_map`, `force_histories`, `force_histories_onset` (without a time window, when the
/// first arrivals take less than half the record), `spectra` and `chain` (when the scenario
/// still resolves), each in the formats of `plot.output` (by default `.png` and `.svg`).
/// Returns the files written. A time or frequency window with fewer than 2 samples inside is an
/// error naming the flag (`--time-ms`, `--frequency-khz`) and the range the run covers.
pub fn plot_run(dir: &Path, out: &Path, plot: &RunPlot) -> Result<Vec<PathBuf>, Error> {
    plot.output.check()?;
    with_output(&plot.output, || draw_run(dir, out, plot))
}

/// A run read back for its figures, its windows checked against the record.
struct RunFigures<'a> {
    /// What is drawn, and how.
    plot: &'a RunPlot,
    /// `run.json`.
    info: woodpile_io::rundir::RunInfo,
    /// The samples.
    t: Trajectory,
    /// What drives contact 0 (`striker`, `load`, `actuator`).
    role: Option<&'static str>,
    /// The contacts drawn as histories and spectra, with their labels.
    picks: Vec<(usize, String)>,
    /// The time window of the histories \[s\].
    window_s: (f64, f64),
    /// The spectrum settings (the window function of `plot`).
    settings: SpectrumSettings,
    /// The title of every figure but the chain's.
    title: String,
}

fn draw_run(dir: &Path, out: &Path, plot: &RunPlot) -> Result<Vec<PathBuf>, Error> {
    let run = RunFigures::read(dir, plot)?;
    let spectrum_map = run.spectrum_map()?;
    create_dir(out)?;
    let mut files = run.maps(out)?;
    files.extend(crate::spectrum_map(
        &spectrum_map,
        &run.title,
        plot.frequency_hz.1,
        run.role,
        &out.join("spectrum_map"),
    )?);
    files.extend(run.histories(out)?);
    files.extend(run.spectra(out)?);
    if let Some(chain) = &run.info.chain {
        let chain_title = format!("{}, {} elements", run.info.name, run.info.labels.len());
        files.extend(crate::chain_picture(
            chain,
            &chain_title,
            run.role,
            &out.join("chain"),
        )?);
    }
    Ok(files)
}

impl<'a> RunFigures<'a> {
    /// Reads the run in `dir`; the signals and the time window are checked, errors naming the
    /// flags (`--signal`, `--time-ms`).
    fn read(dir: &Path, plot: &'a RunPlot) -> Result<Self, Error> {
        let info = read_run_info(dir)?;
        let n = info.labels.len();
        let role = contact0_role(&info.excitation);
        let signal_picks = plot
            .signals
            .iter()
            .map(|name| signal_contact_of(name, n, role))
            .collect::<Result<Vec<_>, _>>()?;
        let t = read_trajectory(dir, n)?;
        if t.len() < 2 {
            return Err(read_error(
                &dir.join("time_s.npy"),
                "fewer than 2 samples: nothing to plot",
            ));
        }
        let (t0, t1) = (t.times_s[0], t.times_s[t.len() - 1]);
        let ms = |v: f64| format!("{}", (v * 1e6).round() / 1e3);
        let (w0, w1) = plot.time_s.unwrap_or((t0, t1));
        let inside = t.times_s.iter().filter(|&&x| w0 <= x && x <= w1).count();
        if inside < 2 {
            return Err(Error::invalid(
                "--time-ms",
                format!("{},{}", ms(w0), ms(w1)),
                format!(
                    "holds {inside} sample(s), at least 2 are needed; the run covers {} to {} ms",
                    ms(t0),
                    ms(t1)
                ),
            ));
        }
        let chain = describe_chain(&info.labels);
        // Short enough for the maps' width at the default text size: a long chain is described
        // by the chain picture, not the titles.
        let title = if chain.chars().count() <= 24 {
            format!("{}: {chain}, {}", info.name, info.excitation)
        } else {
            format!("{}, {}", info.name, info.excitation)
        };
        let picks = if signal_picks.is_empty() {
            default_picks(n, role)
        } else {
            signal_picks
        };
        Ok(RunFigures {
            plot,
            info,
            t,
            role,
            picks,
            window_s: (w0, w1),
            settings: SpectrumSettings {
                window: plot.window,
                scaling: Scaling::FourierMagnitude,
                ..SpectrumSettings::default()
            },
            title,
        })
    }

    /// The spectrum map in the frequency window; an error naming `--frequency-khz` when fewer
    /// than 2 frequencies are inside.
    fn spectrum_map(&self) -> Result<Map2, Error> {
        let map = contact_spectrum_map(&self.t, &self.settings)?;
        let (f0, f1) = self.plot.frequency_hz;
        let khz = |v: f64| format!("{}", v.round() / 1e3);
        let nyquist = map.cols.values.last().copied().unwrap_or(0.0);
        columns_between(&map, f0, f1)?.ok_or_else(|| {
            Error::invalid(
                "--frequency-khz",
                format!("{},{}", khz(f0), khz(f1)),
                format!(
                    "holds fewer than 2 frequencies of the spectra, which cover 0 to {} kHz",
                    khz(nyquist)
                ),
            )
        })
    }

    /// `force_map` and `energy_map`, in the time window and the colours of the plot.
    fn maps(&self, out: &Path) -> Result<Vec<PathBuf>, Error> {
        let windowed = |map: Map2| -> Result<Map2, Error> {
            Ok(match self.plot.time_s {
                Some((a, b)) => columns_between(&map, a, b)?.unwrap_or(map),
                None => map,
            })
        };
        let colours = self.plot.map_colours;
        let (title, role) = (&self.title, self.role);
        let (force, energy) = (
            windowed(force_map(&self.t)?)?,
            windowed(energy_map(&self.t)?)?,
        );
        let mut files = (colours.apply(crate::force_heatmap(&force, title, role)))
            .write(&out.join("force_map"))?;
        files.extend(
            colours
                .apply(crate::energy_heatmap(&energy, title, role))
                .write(&out.join("energy_map"))?,
        );
        Ok(files)
    }

    /// `force_histories` in the time window and, without one, `force_histories_onset`.
    fn histories(&self, out: &Path) -> Result<Vec<PathBuf>, Error> {
        let t = &self.t;
        let series: Vec<Series> = self
            .picks
            .iter()
            .map(|(c, l)| Series::new(l.clone(), t.contact_force_n(*c)))
            .collect();
        let mut files = crate::force_histories_between(
            &t.times_s,
            &series,
            &self.title,
            self.window_s,
            &out.join("force_histories"),
        )?;
        if self.plot.time_s.is_none() {
            if let Some(onset) = crate::onset_window_s(&t.times_s, &series, 0.5) {
                files.extend(crate::force_histories_between(
                    &t.times_s,
                    &series,
                    &format!("{}: first arrivals", self.title),
                    onset,
                    &out.join("force_histories_onset"),
                )?);
            }
        }
        Ok(files)
    }

    /// `spectra` of the picked contacts in the frequency window, the chain's bands shaded.
    fn spectra(&self, out: &Path) -> Result<Vec<PathBuf>, Error> {
        let dt = woodpile::analysis::sample_interval_s(&self.t)?;
        let spectra = self
            .picks
            .iter()
            .map(|(c, l)| {
                let s = Spectrum::of(&self.t.contact_force_n(*c), dt, &self.settings)?;
                Ok((l.clone(), s))
            })
            .collect::<Result<Vec<_>, woodpile::Error>>()?;
        let refs: Vec<(String, &Spectrum)> = spectra.iter().map(|(l, s)| (l.clone(), s)).collect();
        Ok(crate::spectra_between(
            &refs,
            &woodpile::analysis::chain_bands_hz(&self.info.cells),
            &self.title,
            self.plot.frequency_hz,
            &out.join("spectra"),
        )?)
    }
}

/// The contacts drawn without `--signal`: contact 0, the incident contact and the wall.
fn default_picks(n: usize, role: Option<&str>) -> Vec<(usize, String)> {
    let contact0 = match role {
        Some(r) => format!("contact 0 ({r})"),
        None => "contact 0".to_string(),
    };
    let mut picks = vec![(0, contact0)];
    if n >= 2 {
        picks.push((1, "contact 1 (incident)".to_string()));
    }
    picks.push((n, format!("contact {n} (wall)")));
    picks
}

/// The contact a `--signal` name designates, with its legend label: `contact_K` (K = 0..n),
/// `striker`, `load` or `actuator` (contact 0), `incident` (contact 1), `wall` (contact n).
pub fn signal_contact(name: &str, n: usize) -> Result<(usize, String), Error> {
    let role = match name {
        "striker" | "load" | "actuator" => Some(name),
        _ => None,
    };
    signal_contact_of(name, n, role)
}

/// [`signal_contact`] in a run whose contact 0 is driven by `role` (see [`contact0_role`]):
/// contact 0 is labelled by the run's role whatever name selected it, so a blast run's contact
/// 0 is never called the striker.
pub fn signal_contact_of(
    name: &str,
    n: usize,
    role: Option<&str>,
) -> Result<(usize, String), Error> {
    let contact = match name {
        "striker" | "load" | "actuator" => Some(0),
        "incident" if n >= 2 => Some(1),
        "wall" => Some(n),
        _ => name
            .strip_prefix("contact_")
            .and_then(|k| k.parse::<usize>().ok())
            .filter(|&k| k <= n),
    };
    contact
        .map(|c| {
            let label = match (c, role) {
                (0, Some(r)) => format!("contact 0 ({r})"),
                _ if name.starts_with("contact_") || c == 0 => format!("contact {c}"),
                _ => format!("contact {c} ({name})"),
            };
            (c, label)
        })
        .ok_or_else(|| {
            Error::invalid(
                "--signal",
                name,
                format!("unknown signal; valid: contact_0 .. contact_{n}, striker, load, actuator (contact 0), incident, wall"),
            )
        })
}

/// The catalogue's effective-mass curves (paper Fig. 3 a: 20–40 mm, b: 50–80 mm) into `dir`:
/// `effective_mass_20_40mm` and `effective_mass_50_80mm`, in the formats of the
/// [`Output`] in effect (by default `.png` and `.svg`).
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
    // Titles short enough for the figure's width at the default text size (see
    // crate::output); the axis says what is drawn.
    let (one, two, shaded) = if resonator_ratio > 0.0 {
        let z = format!("ζ = {resonator_ratio} (real part)");
        (
            format!("20, 30, 40 mm rods, {z}"),
            format!("50–80 mm rods, {z}"),
            "undamped bands shaded",
        )
    } else {
        (
            "20, 30, 40 mm rods (one resonator)".to_string(),
            "50–80 mm rods (two resonators)".to_string(),
            "negative-mass bands shaded",
        )
    };
    let mut files = Vec::new();
    for (curves, title, name) in [
        (
            &curves[..3],
            format!("{one}; {shaded}"),
            "effective_mass_20_40mm",
        ),
        (
            &curves[3..],
            format!("{two}; {shaded}"),
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
/// scale, top to bottom), each in the formats of `output` (by default `.png` and `.svg`).
/// Returns the files written and a note when the chain could not be drawn.
pub fn plot_optimization(
    dir: &Path,
    out: &Path,
    output: &Output,
) -> Result<(Vec<PathBuf>, Option<String>), Error> {
    output.check()?;
    with_output(output, || draw_optimization(dir, out))
}

fn draw_optimization(dir: &Path, out: &Path) -> Result<(Vec<PathBuf>, Option<String>), Error> {
    let output = read_output(dir)?;
    let points: Vec<ConvergencePoint> = output.history.iter().map(Into::into).collect();
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
        contact0_role(excitation),
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

/// Most designs [`plot_pareto`] draws as rods: a longer front is thinned evenly along its first
/// objective (both ends kept), as the figure's title states.
pub const MOST_FRONT_DESIGNS_DRAWN: usize = 16;

/// The rows `0..n` drawn when at most `most` fit: all, or `most` spread evenly, both ends kept.
fn thinned(n: usize, most: usize) -> Vec<usize> {
    if n <= most {
        return (0..n).collect();
    }
    let mut rows: Vec<usize> = (0..most)
        .map(|k| (k as f64 * (n - 1) as f64 / (most - 1) as f64).round() as usize)
        .collect();
    rows.dedup();
    rows
}

/// Draws the figures of an NSGA-II output (`ga.algorithm = "nsga2"`, it holds `pareto.csv`)
/// into `out`: `pareto_front` (two objectives: a scatter; three or more: one panel per pair;
/// the designs of `references.csv` marked: the catalogue's homogeneous chains and, for the
/// paper's catalogue, the paper's blast-optimised chain), `pareto_designs` (the front's designs as
/// rods to scale, at most [`MOST_FRONT_DESIGNS_DRAWN`]) and `hypervolume` (per generation).
/// A lattice study's directory (`woodpile optimize` of a `[lattice]` config) is drawn as its
/// `hypervolume` and `pareto_front`. Returns the files written and a
/// note when the front is empty.
pub fn plot_pareto(
    dir: &Path,
    out: &Path,
    output: &Output,
) -> Result<(Vec<PathBuf>, Option<String>), Error> {
    output.check()?;
    with_output(
        output,
        || match woodpile_io::lattice_study::read_study_output(dir)? {
            Some(study) => draw_lattice_study(&study, out),
            None => draw_pareto(dir, out),
        },
    )
}

fn draw_pareto(dir: &Path, out: &Path) -> Result<(Vec<PathBuf>, Option<String>), Error> {
    let read = woodpile_io::pareto::read_pareto_output(dir)?;
    let s = &read.summary;
    let config = &s.config;
    let model = config.design.model.unwrap_or_default().name();
    let excitation = config.excitation.kind.name();
    create_dir(out)?;
    let title = format!(
        "NSGA-II, {} ({model} model, {excitation}, seed {})",
        s.problem, s.seed
    );
    let reference = s
        .reference_point
        .iter()
        .zip(&s.objectives)
        .map(|(v, o)| {
            format!("{} {}", format_value(*v), o.unit)
                .trim_end()
                .to_string()
        })
        .collect::<Vec<_>>()
        .join(", ");
    let mut files = crate::hypervolume_history(
        &read.hypervolume,
        &format!("{title}: hypervolume (reference point {reference})"),
        &out.join("hypervolume"),
    )?;
    if s.front.is_empty() {
        return Ok((
            files,
            Some("no feasible design on the front: the front is not drawn".into()),
        ));
    }
    let axes: Vec<crate::ObjectiveAxis> = s
        .objectives
        .iter()
        .map(|o| crate::ObjectiveAxis::new(&o.name, &o.unit))
        .collect();
    let front: Vec<Vec<f64>> = s.front.iter().map(|d| d.objectives.clone()).collect();
    let marked: Vec<crate::MarkedDesign> = read
        .references
        .unwrap_or_default()
        .into_iter()
        .map(|r| crate::MarkedDesign {
            highlight: r.name.starts_with("paper"),
            name: r.name,
            values: r.objectives,
            feasible: r.feasible,
        })
        .collect();
    files.extend(crate::pareto_front(
        &axes,
        &front,
        &marked,
        &format!("{title}: front of {} designs", front.len()),
        &out.join("pareto_front"),
    )?);
    let rows = thinned(s.front.len(), MOST_FRONT_DESIGNS_DRAWN);
    let mut designs = Vec::with_capacity(rows.len());
    for &k in &rows {
        let d = &s.front[k];
        let path = dir.join(&d.file);
        let scenario = woodpile_io::scenario::Scenario::load(&path)?;
        let chain = resolve(&scenario, path.parent().unwrap_or(dir))?.chain;
        let widths_mm = chain
            .elements()
            .iter()
            .map(|e| match e.body {
                woodpile::Body::Rod { length_m, .. } => length_m * 1e3,
                woodpile::Body::Sphere { diameter_m } => diameter_m * 1e3,
            })
            .collect();
        let mut caption = vec![format!("#{}", k + 1)];
        caption.extend(d.objectives.iter().zip(&axes).map(|(v, a)| {
            let unit = a
                .label
                .rsplit_once('[')
                .map_or("", |(_, u)| u.trim_end_matches(']'));
            let unit = if unit == "-" { "" } else { unit };
            format!("{} {unit}", format_value(v * a.scale))
                .trim_end()
                .to_string()
        }));
        designs.push(crate::FrontDesign { caption, widths_mm });
    }
    let shown = if rows.len() < s.front.len() {
        format!(
            "{} of the {} designs, evenly along the front",
            rows.len(),
            s.front.len()
        )
    } else {
        format!("its {} designs", rows.len())
    };
    files.extend(crate::front_designs(
        &designs,
        &format!("Pareto front ({model}, {excitation}): {shown}, top to bottom, to scale"),
        &out.join("pareto_designs"),
    )?);
    Ok((files, None))
}

/// The figures of a lattice study (`woodpile optimize` of a `[lattice]` config): `hypervolume`
/// (per generation) and `pareto_front` (the rows of `pareto.csv`).
fn draw_lattice_study(
    study: &woodpile_io::lattice_study::LatticeStudyOutput,
    out: &Path,
) -> Result<(Vec<PathBuf>, Option<String>), Error> {
    let s = &study.summary;
    create_dir(out)?;
    let title = format!("NSGA-II, lattice study (seed {})", s.seed);
    let mut files = crate::hypervolume_history(
        &study.hypervolume,
        &format!("{title}: hypervolume"),
        &out.join("hypervolume"),
    )?;
    if study.front.is_empty() {
        let note = "no feasible design on the front: the front is not drawn";
        return Ok((files, Some(note.into())));
    }
    let axes: Vec<crate::ObjectiveAxis> = (s.objectives.iter().zip(&s.units))
        .map(|(name, unit)| crate::ObjectiveAxis::new(name, unit))
        .collect();
    files.extend(crate::pareto_front(
        &axes,
        &study.front,
        &[],
        &format!("{title}: front of {} designs", study.front.len()),
        &out.join("pareto_front"),
    )?);
    Ok((files, None))
}

/// The bar charts of a `woodpile sensitivity` directory, one per figure of merit with indices
/// (`indices.csv`), into `out` as `indices_FIGURE.png` and `.svg`.
pub fn sensitivity(dir: &Path, out: &Path) -> Result<Vec<PathBuf>, Error> {
    let rows = woodpile_io::sensitivity::read_indices(dir)?;
    create_dir(out)?;
    let mut figures: Vec<&str> = Vec::new();
    for r in &rows {
        if !figures.contains(&r.figure.as_str()) {
            figures.push(&r.figure);
        }
    }
    let mut files = Vec::new();
    for figure in figures {
        let bars: Vec<crate::IndexBars> = rows
            .iter()
            .filter(|r| r.figure == figure)
            .map(|r| crate::IndexBars {
                parameter: r.parameter.clone(),
                first_order: (r.s1, r.s1_conf),
                total: (r.st, r.st_conf),
            })
            .collect();
        let title = format!("Sobol' indices of {figure} (95 % intervals)");
        files.extend(crate::sobol_indices(
            &bars,
            &title,
            &out.join(format!("indices_{figure}")),
        )?);
    }
    Ok(files)
}

/// Draws the figures of a lattice run directory (`woodpile simulate` of a `[lattice]`
/// scenario, docs/physics.md §16) into `out`: `support_forces` (each support's force and their
/// sum, the transmitted force, against time), `contact_force_map` (every contact's force
/// over time, contacts in output order: the striker's, the crossings layer by layer, the
/// supports), `interface_forces` (each interface's contacts on the crossing grid, coloured by
/// their largest force in four windows of the time window; `interface_forces_1`, `_2`, … when
/// more than [`crate::INTERFACES_PER_PAGE`] interfaces) and `lattice_view` (the lattice in
/// three dimensions, each contact coloured by its peak force from `summary.json`), in the time
/// window and map colours of `plot` and its output formats. Chain-only
/// options (`signals`) are refused naming `--signal`; the frequency window and the spectrum
/// window are not used (no spectra are drawn of a lattice). Returns the files written.
pub fn plot_lattice_run(dir: &Path, out: &Path, plot: &RunPlot) -> Result<Vec<PathBuf>, Error> {
    plot.output.check()?;
    if let Some(name) = plot.signals.first() {
        return Err(Error::invalid(
            "--signal",
            name,
            "picks a contact of a chain run; a lattice run draws every contact (contact_force_map) and the supports (support_forces)",
        ));
    }
    with_output(&plot.output, || draw_lattice_run(dir, out, plot))
}

fn draw_lattice_run(dir: &Path, out: &Path, plot: &RunPlot) -> Result<Vec<PathBuf>, Error> {
    let read = woodpile_io::lattice::read_lattice_run(dir)?;
    let times = &read.times_s;
    if times.len() < 2 {
        return Err(read_error(
            &dir.join("time_s.npy"),
            "fewer than 2 samples: nothing to plot",
        ));
    }
    let (t0, t1) = (times[0], times[times.len() - 1]);
    let window_s = plot.time_s.unwrap_or((t0, t1));
    let ms = |v: f64| format!("{}", (v * 1e6).round() / 1e3);
    if times
        .iter()
        .filter(|&&t| window_s.0 <= t && t <= window_s.1)
        .count()
        < 2
    {
        return Err(Error::invalid(
            "--time-ms",
            format!("{},{}", ms(window_s.0), ms(window_s.1)),
            format!(
                "holds fewer than 2 samples; the run covers {} to {} ms",
                ms(t0),
                ms(t1)
            ),
        ));
    }
    let run = &read.run;
    let layers = run.rods_per_layer.len();
    let title = format!(
        "{}, {layers} layers × {} rods",
        run.scenario_name,
        describe_rods(&run.rods_per_layer)
    );
    let supports = read.supports();
    let mut series: Vec<Series> = supports
        .iter()
        .map(|&c| {
            let p = &run.contacts[c];
            // To 0.1 mm, −0 written as 0 (the points come from rod geometry, ~1e-15 off).
            let mm = |v: f64| format!("{:.1}", if v.abs() < 0.05 { 0.0 } else { v });
            let label = format!(
                "support {} at ({}, {}) mm",
                p.rod_below,
                mm(p.x_mm),
                mm(p.y_mm)
            );
            Series::new(label, read.contact_force_n(c))
        })
        .collect();
    series.push(Series::new("transmitted (sum)", read.transmitted_force_n()));
    create_dir(out)?;
    let mut files = crate::force_histories_between(
        times,
        &series,
        &format!(
            "{title}, impact {:.2} m/s: support forces",
            run.striker_velocity_m_s
        ),
        window_s,
        &out.join("support_forces"),
    )?;
    files.extend(lattice_force_map(&read, &title, plot, out)?);
    let layout = lattice_layout(dir, &read)?;
    let summary = woodpile_io::lattice::read_lattice_summary(dir, read.n_contacts())?;
    files.extend(crate::interface_forces(
        &layout,
        times,
        &read.forces_n,
        &interface_windows(times, window_s),
        plot.map_colours,
        &format!("{title}: largest contact force per time window"),
        &out.join("interface_forces"),
    )?);
    files.extend(crate::lattice_view(
        &layout,
        &summary.contact_peak_forces_n,
        &format!("{title}: peak contact forces"),
        &out.join("lattice_view"),
    )?);
    Ok(files)
}

/// The rods of a lattice run (its scenario in `run.json` resolved again) and its contacts.
fn lattice_layout(
    dir: &Path,
    read: &woodpile_io::lattice::LatticeRunRead,
) -> Result<crate::LatticeLayout, Error> {
    let resolved = read.run.scenario.resolve().map_err(|e| {
        read_error(
            &dir.join("run.json"),
            format!("its scenario does not resolve ({e}); re-run `woodpile simulate`"),
        )
    })?;
    Ok(layout_of(&resolved.lattice, &read.run.contacts))
}

/// The figures' view of a lattice: its rods (in mm) and the contacts of `run.json`.
pub fn layout_of(
    lattice: &woodpile::model::Lattice,
    contacts: &[woodpile_io::lattice::ContactJson],
) -> crate::LatticeLayout {
    let rods = lattice
        .rods
        .iter()
        .map(|r| crate::RodLine {
            layer: r.layer,
            number: r.number,
            centre_mm: [r.centre_m[0] * 1e3, r.centre_m[1] * 1e3],
            axis: r.axis,
            length_mm: r.rod.length_m * 1e3,
            diameter_mm: r.rod.outer_diameter_m * 1e3,
        })
        .collect();
    let contacts = contacts
        .iter()
        .map(|c| crate::ContactPoint {
            layer_above: c.layer_above,
            layer_below: c.layer_below,
            x_mm: c.x_mm,
            y_mm: c.y_mm,
        })
        .collect();
    crate::LatticeLayout {
        rods,
        contacts,
        layers: lattice.layers,
    }
}

/// The time windows of [`crate::interface_forces`] in `woodpile plot`: the plotted window in four equal parts (each then
/// holds at least one sample), or whole when it holds fewer than 8 samples.
pub fn interface_windows(times_s: &[f64], (a, b): (f64, f64)) -> Vec<(f64, f64)> {
    let samples = times_s.iter().filter(|&&t| a <= t && t <= b).count();
    let parts = if samples >= 8 { 4 } else { 1 };
    let span = (b - a) / parts as f64;
    (0..parts)
        .map(|j| {
            let end = if j + 1 == parts {
                b
            } else {
                a + (j + 1) as f64 * span
            };
            (a + j as f64 * span, end)
        })
        .collect()
}

/// `contact_force_map` of a lattice run: contacts in output order (rows) × time.
fn lattice_force_map(
    read: &woodpile_io::lattice::LatticeRunRead,
    title: &str,
    plot: &RunPlot,
    out: &Path,
) -> Result<Vec<PathBuf>, Error> {
    let n = read.n_contacts();
    let ns = read.times_s.len();
    let data = (0..n)
        .flat_map(|c| (0..ns).map(move |s| read.forces_n[s * n + c]))
        .collect();
    let map = Map2::new(
        Axis::index("contact", n),
        Axis::new("time", "s", read.times_s.clone()),
        "contact force",
        "N",
        data,
    )?;
    let map = match plot.time_s {
        Some((a, b)) => columns_between(&map, a, b)?.unwrap_or(map),
        None => map,
    };
    let supports = read.supports();
    let first_support = supports.first().copied().unwrap_or(n);
    let span = |a: usize, b: usize| match b - a {
        0 => format!("{a}"),
        _ => format!("{a}–{b}"),
    };
    let mut order = vec!["0 striker".to_string()];
    if first_support > 1 {
        order.push(format!(
            "{} crossings layer by layer",
            span(1, first_support - 1)
        ));
    }
    if !supports.is_empty() {
        order.push(format!("{} supports", span(first_support, n - 1)));
    }
    // The order is the title (a long axis label loses its parenthesis when it does not fit).
    let heatmap = crate::Heatmap {
        y_label: "contact (output order)".into(),
        ..crate::force_heatmap(
            &map,
            &format!("{title}: contacts {}", order.join(", ")),
            Some("striker"),
        )
    };
    Ok(plot
        .map_colours
        .apply(heatmap)
        .write(&out.join("contact_force_map"))?)
}

/// Rods per layer: `3` when every layer has as many, else `3/2/3`.
fn describe_rods(rods_per_layer: &[usize]) -> String {
    match rods_per_layer {
        [first, rest @ ..] if rest.iter().all(|r| r == first) => first.to_string(),
        _ => rods_per_layer
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join("/"),
    }
}
