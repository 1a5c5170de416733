//! Line plots: force histories, spectra, effective-mass curves, GA convergence, peaks per layer.

use crate::format_number;
use crate::{
    finite_range, padded, render, series_color, DrawResult, Figure, PlotError, Result, FONT,
};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};
use woodpile::{EffectiveMassCurve, Spectrum};

/// A named series of values.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry.
    pub label: String,
    /// Values, one per point of the shared x axis.
    pub values: Vec<f64>,
}

impl Series {
    /// A series.
    pub fn new(label: impl Into<String>, values: Vec<f64>) -> Self {
        Series {
            label: label.into(),
            values,
        }
    }
}

/// One generation of a genetic algorithm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvergencePoint {
    /// Generation number.
    pub generation: usize,
    /// Best objective value of the generation.
    pub best: f64,
    /// Mean objective value of the generation.
    pub mean: f64,
}

impl From<&woodpile::optimize::GenerationStats> for ConvergencePoint {
    /// A generation of a GA run in memory.
    fn from(g: &woodpile::optimize::GenerationStats) -> Self {
        ConvergencePoint {
            generation: g.generation,
            best: g.best,
            mean: g.mean,
        }
    }
}

impl From<&woodpile_io::optimize::HistoryPoint> for ConvergencePoint {
    /// A generation read back from an optimisation's `history.csv`.
    fn from(h: &woodpile_io::optimize::HistoryPoint) -> Self {
        ConvergencePoint {
            generation: h.generation,
            best: h.best,
            mean: h.mean,
        }
    }
}

const LEGEND_FONT: u32 = 15;

/// Drawing units per layout unit of the line plots: they lay out as 1100 × 600 (or 1000 × 600)
/// with 15–22-unit text, on a canvas 4 times finer, every length multiplied by 4. plotters
/// rounds coordinates to whole units of the canvas; on the layout grid (1/1100 of the width)
/// a nearly flat curve drawn 2100 px wide (7 in at 300 dpi) climbs in visible 2-px steps, on
/// the fine grid in sub-pixel ones.
pub(crate) const FINE: u32 = 4;

/// A polyline broken into segments (a new segment where the line must not be joined).
pub(crate) type Segments = Vec<Vec<(f64, f64)>>;

/// x/y points of several series, drawn as lines on linear or log-y axes.
pub(crate) struct LinePlot {
    /// Caption; empty: none (a panel under another).
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// Per series: label, (x, y) points split into segments (a new segment where the line must
    /// break, e.g. at a pole).
    pub series: Vec<(String, Segments)>,
    /// Shaded x intervals: (lo, hi, colour index or None for grey, legend label).
    pub bands: Vec<(f64, f64, Option<usize>, Option<String>)>,
    pub x_range: (f64, f64),
    pub y_range: (f64, f64),
    pub log_y: bool,
    pub markers: bool,
    /// x takes whole numbers only (generations, interfaces): ticks only at whole numbers.
    pub integer_x: bool,
    pub zero_line: bool,
    /// Layout size (before [`FINE`]).
    pub size: (u32, u32),
    /// Index of the first series' colour (a panel continuing another's colours).
    pub first_colour: usize,
}

impl LinePlot {
    pub(crate) fn write(self, stem: &Path) -> Result<Vec<PathBuf>> {
        render(&self, stem)
    }

    fn draw_on<'a, DB: DrawingBackend + 'a, Y>(
        &self,
        chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>,
        y_lo: f64,
        y_hi: f64,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
        Y: Ranged<ValueType = f64>,
    {
        let mut legend: Vec<(&str, Swatch)> = Vec::new();
        for (lo, hi, colour, label) in &self.bands {
            let c = match colour {
                Some(i) => series_color(*i).mix(0.15),
                None => RGBColor(120, 120, 120).mix(0.2),
            };
            let (lo, hi) = (lo.max(self.x_range.0), hi.min(self.x_range.1));
            if hi <= lo {
                continue;
            }
            chart.draw_series(std::iter::once(Rectangle::new(
                [(lo, y_lo), (hi, y_hi)],
                c.filled(),
            )))?;
            if let Some(label) = label {
                legend.push((label.as_str(), Swatch::Band(c)));
            }
        }
        if self.zero_line {
            chart.draw_series(LineSeries::new(
                [(self.x_range.0, 0.0), (self.x_range.1, 0.0)],
                BLACK.mix(0.5).stroke_width(FINE),
            ))?;
        }
        for (i, (label, segments)) in self.series.iter().enumerate() {
            let colour = series_color(self.first_colour + i);
            // Dense series (spectra) 1 px wide: the miter joins of their sharp peaks would
            // overshoot the frame by far at 2 px.
            let points: usize = segments.iter().map(Vec::len).sum();
            let style = colour.stroke_width(FINE * if points > 1000 { 1 } else { 2 });
            legend.push((label.as_str(), Swatch::Line(colour)));
            for seg in segments {
                chart.draw_series(LineSeries::new(seg.iter().copied(), style))?;
                if self.markers {
                    chart.draw_series(
                        seg.iter()
                            .map(|&(x, y)| Circle::new((x, y), 4 * FINE, colour.filled())),
                    )?;
                }
            }
        }
        draw_legend(&chart.plotting_area().strip_coord_spec(), &legend)
    }
}

/// What a legend entry shows left of its label.
#[derive(Clone, Copy)]
enum Swatch {
    /// A line in the series' colour.
    Line(RGBColor),
    /// A filled box in the band's colour.
    Band(RGBAColor),
}

/// A legend in the upper right corner of `area` (the plotting area). Drawn here rather than by
/// plotters' series labels, which size their box from the font at the figure's logical size:
/// the labels' sizes are measured through the backend, so the box fits text that the output
/// enlarges (see [`crate::output`]).
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(&str, Swatch)],
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    if entries.is_empty() {
        return Ok(());
    }
    let style = TextStyle::from((FONT, LEGEND_FONT * FINE).into_font())
        .pos(Pos::new(HPos::Left, VPos::Center));
    let mut sizes = Vec::with_capacity(entries.len());
    for (label, _) in entries {
        sizes.push(area.estimate_text_size(label, &style)?);
    }
    let text_w = sizes.iter().map(|s| s.0).max().unwrap_or(0) as i32;
    let f = FINE as i32;
    let row = sizes.iter().map(|s| s.1).max().unwrap_or(0) as i32 + 6 * f;
    let (pad, swatch, gap) = (8 * f, 22 * f, 8 * f);
    let (w, _) = area.dim_in_pixel();
    let box_w = pad + swatch + gap + text_w + pad;
    let box_h = pad + row * entries.len() as i32 + pad - 6 * f;
    let (x0, y0) = (w as i32 - 10 * f - box_w, 10 * f);
    area.draw(&Rectangle::new(
        [(x0, y0), (x0 + box_w, y0 + box_h)],
        WHITE.mix(0.85).filled(),
    ))?;
    area.draw(&Rectangle::new(
        [(x0, y0), (x0 + box_w, y0 + box_h)],
        BLACK.mix(0.4).stroke_width(FINE),
    ))?;
    for (k, (label, sw)) in entries.iter().enumerate() {
        let y = y0 + pad + row * k as i32 + (row - 6 * f) / 2;
        let x = x0 + pad;
        match *sw {
            Swatch::Line(c) => area.draw(&PathElement::new(
                [(x, y), (x + swatch, y)],
                c.stroke_width(3 * FINE),
            ))?,
            Swatch::Band(c) => area.draw(&Rectangle::new(
                [(x, y - row / 3), (x + swatch, y + row / 3)],
                c.filled(),
            ))?,
        }
        area.draw(&Text::new(
            label.to_string(),
            (x + swatch + gap, y),
            style.clone(),
        ))?;
    }
    Ok(())
}

impl Figure for LinePlot {
    fn size(&self) -> (u32, u32) {
        (self.size.0 * FINE, self.size.1 * FINE)
    }

    fn subdivision(&self) -> u32 {
        FINE
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (x0, x1) = self.x_range;
        let (y0, y1) = self.y_range;
        // plotters picks round steps (1, 2, 5 × 10^k) for at most this many labels: at most one
        // per whole number keeps the steps whole.
        let x_labels = if self.integer_x {
            ((x1 - x0).floor() as usize + 1).clamp(2, 11)
        } else {
            10
        };
        let mut builder = ChartBuilder::on(root);
        if !self.title.is_empty() {
            builder.caption(&self.title, (FONT, 22 * FINE));
        }
        builder
            .margin(15 * FINE)
            .x_label_area_size(50 * FINE)
            .y_label_area_size(85 * FINE);
        // The same axes on a log or a linear y coordinate: two chart types, one mesh.
        macro_rules! axes_and_series {
            ($y:expr) => {{
                let mut chart = builder.build_cartesian_2d(x0..x1, $y)?;
                chart
                    .configure_mesh()
                    .x_desc(&self.x_label)
                    .x_labels(x_labels)
                    .x_label_formatter(&|v| format_number(*v))
                    .y_desc(&self.y_label)
                    .y_label_formatter(&|v| format_number(*v))
                    .label_style((FONT, 15 * FINE))
                    .axis_desc_style((FONT, 17 * FINE))
                    .set_all_tick_mark_size(5 * FINE)
                    .axis_style(BLACK.stroke_width(FINE))
                    .bold_line_style(BLACK.mix(0.2).stroke_width(FINE))
                    .light_line_style(WHITE.mix(0.0))
                    .draw()?;
                self.draw_on(&mut chart, y0, y1)
            }};
        }
        if self.log_y {
            axes_and_series!((y0..y1).log_scale())
        } else {
            axes_and_series!(y0..y1)
        }
    }
}

pub(crate) fn bad(what: &str, reason: impl Into<String>) -> PlotError {
    PlotError::BadData {
        what: what.to_string(),
        reason: reason.into(),
    }
}

/// Force histories at chosen contacts (e.g. the striker contact, contact 1 and the wall): time
/// in ms, force in N, over the whole record. Writes `stem.png` and `stem.svg` (the formats of
/// the [`crate::Output`] in effect).
pub fn force_histories(
    times_s: &[f64],
    series: &[Series],
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    if times_s.len() < 2 || series.is_empty() {
        return Err(bad(title, "needs at least 2 samples and 1 series"));
    }
    let (t0, t1) = (times_s[0], times_s[times_s.len() - 1]);
    force_histories_between(times_s, series, title, (t0, t1), stem)
}

/// [`force_histories`] over the samples with `window_s.0 <= t <= window_s.1` only (the axis
/// spans the first to the last of them). An error when fewer than 2 samples are inside, saying
/// which times the record covers. Writes `stem.png` and `stem.svg`.
pub fn force_histories_between(
    times_s: &[f64],
    series: &[Series],
    title: &str,
    window_s: (f64, f64),
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    if times_s.len() < 2 || series.is_empty() {
        return Err(bad(title, "needs at least 2 samples and 1 series"));
    }
    if let Some(s) = series.iter().find(|s| s.values.len() != times_s.len()) {
        return Err(bad(
            title,
            format!(
                "series `{}` has {} values for {} times",
                s.label,
                s.values.len(),
                times_s.len()
            ),
        ));
    }
    let inside: Vec<usize> = (0..times_s.len())
        .filter(|&i| window_s.0 <= times_s[i] && times_s[i] <= window_s.1)
        .collect();
    if inside.len() < 2 {
        return Err(bad(
            title,
            format!(
                "fewer than 2 samples between {} and {} ms; the record covers {} to {} ms",
                window_s.0 * 1e3,
                window_s.1 * 1e3,
                times_s[0] * 1e3,
                times_s[times_s.len() - 1] * 1e3
            ),
        ));
    }
    let values = || {
        series
            .iter()
            .flat_map(|s| inside.iter().map(|&i| s.values[i]))
    };
    let (lo, hi) = finite_range(title, values())?;
    let (y0, y1) = padded(lo.min(0.0), hi * 1.08);
    let (first, last) = (inside[0], inside[inside.len() - 1]);
    LinePlot {
        title: title.to_string(),
        x_label: "time [ms]".into(),
        y_label: "contact force [N]".into(),
        series: series
            .iter()
            .map(|s| {
                let pts = inside
                    .iter()
                    .map(|&i| (times_s[i] * 1e3, s.values[i]))
                    .filter(|p| p.1.is_finite());
                (s.label.clone(), vec![pts.collect()])
            })
            .collect(),
        bands: Vec::new(),
        x_range: (times_s[first] * 1e3, times_s[last] * 1e3),
        y_range: (y0, y1),
        log_y: false,
        markers: false,
        integer_x: false,
        zero_line: false,
        size: (1100, 600),
        first_colour: 0,
    }
    .write(stem)
}

/// The time window of the first arrivals, chosen from the data: from the record's start to the
/// latest *first strong peak* among the series plus two *first pulses* of the first series (the
/// driven contact), at most the record's end. A series' first strong peak is the first sample
/// where |F| is at least half its largest |F| and not below the next sample's; the first pulse
/// lasts from the first series' arrival (the first sample where |F| reaches 10 % of its largest
/// |F|) to the first later sample where |F| is below that level again. With the paper's striker
/// on 20 rods of 80 mm this shows the incident pulses and the wall's first large peak (0–0.59 ms
/// of a 2 ms record). None when a series never rises above zero or the window would cover more
/// than `max_fraction` of the record (zooming would not help).
pub fn onset_window_s(times_s: &[f64], series: &[Series], max_fraction: f64) -> Option<(f64, f64)> {
    let (t0, t1) = (*times_s.first()?, *times_s.last()?);
    let peak = |s: &Series| {
        s.values
            .iter()
            .map(|v| v.abs())
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    };
    let first_at_least = |s: &Series, fraction: f64| {
        let level = fraction * peak(s);
        (level > 0.0)
            .then(|| s.values.iter().position(|v| v.abs() >= level))
            .flatten()
    };
    let first_strong_peak = |s: &Series| {
        let from = first_at_least(s, 0.5)?;
        let v = &s.values;
        Some(
            (from..v.len())
                .find(|&i| i + 1 == v.len() || v[i].abs() >= v[i + 1].abs())
                .unwrap_or(v.len() - 1),
        )
    };
    let mut latest = 0;
    for s in series {
        latest = latest.max(first_strong_peak(s)?);
    }
    let first = series.first()?;
    let start = first_at_least(first, 0.1)?;
    let level = 0.1 * peak(first);
    let end = first.values[start..]
        .iter()
        .position(|v| v.abs() < level)
        .map_or(first.values.len() - 1, |k| start + k);
    let pulse = times_s[end.min(times_s.len() - 1)] - times_s[start];
    let stop = (times_s[latest.min(times_s.len() - 1)] + 2.0 * pulse).min(t1);
    (stop > t0 && stop - t0 <= max_fraction * (t1 - t0)).then_some((t0, stop))
}

/// Spectra (log scale, labelled by their [`woodpile::analysis::Scaling`]: amplitude \[N\] or
/// |F̂(f)| \[N/Hz\]; frequency in kHz up to `max_frequency_hz`) with the negative-effective-mass
/// bands `bands_hz` shaded (paper Fig. 9). Writes `stem.png` and `stem.svg`.
pub fn spectra(
    spectra: &[(String, &Spectrum)],
    bands_hz: &[(f64, f64)],
    title: &str,
    max_frequency_hz: f64,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    spectra_between(spectra, bands_hz, title, (0.0, max_frequency_hz), stem)
}

/// [`spectra`] between `window_hz.0` and `window_hz.1` (the axis spans the window, or up to the
/// highest frequency computed). 0 Hz (the mean force) is never drawn. An error when no
/// frequency lies inside. Writes `stem.png` and `stem.svg`.
pub fn spectra_between(
    spectra: &[(String, &Spectrum)],
    bands_hz: &[(f64, f64)],
    title: &str,
    window_hz: (f64, f64),
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    if spectra.is_empty() {
        return Err(bad(title, "no spectrum"));
    }
    let (lo_hz, max_frequency_hz) = window_hz;
    let in_range = |s: &Spectrum| -> Vec<(f64, f64)> {
        s.frequencies_hz
            .iter()
            .zip(&s.amplitudes)
            .skip(1) // 0 Hz: the mean force, not a vibration
            .filter(|(f, _)| lo_hz <= **f && **f <= max_frequency_hz)
            .map(|(f, a)| (f * 1e-3, *a))
            .collect()
    };
    let (_, top) = finite_range(
        title,
        spectra
            .iter()
            .flat_map(|(_, s)| in_range(s).into_iter().map(|p| p.1)),
    )?;
    if top <= 0.0 {
        return Err(bad(title, "every amplitude is zero"));
    }
    // Down to the smallest amplitude drawn, but no more than 5 decades below the top.
    let smallest = spectra
        .iter()
        .flat_map(|(_, s)| in_range(s).into_iter().map(|p| p.1))
        .filter(|a| *a > 0.0)
        .fold(f64::INFINITY, f64::min);
    let floor = (0.5 * smallest).max(top * 1e-5);
    let x_max = spectra
        .iter()
        .map(|(_, s)| s.frequencies_hz.last().copied().unwrap_or(0.0))
        .fold(0.0, f64::max)
        .min(max_frequency_hz)
        * 1e-3;
    let mut bands: Vec<(f64, f64, Option<usize>, Option<String>)> = bands_hz
        .iter()
        .map(|&(lo, hi)| (lo * 1e-3, hi * 1e-3, None, None))
        .collect();
    if let Some(first) = bands.first_mut() {
        first.3 = Some("negative-mass band".to_string());
    }
    LinePlot {
        title: title.to_string(),
        x_label: "frequency [kHz]".into(),
        y_label: {
            let (what, unit) = spectra[0].1.scaling.label("N");
            format!("force {what} [{unit}]")
        },
        series: spectra
            .iter()
            .map(|(label, s)| {
                let pts = in_range(s)
                    .into_iter()
                    .map(|(f, a)| (f, a.max(floor)))
                    .collect();
                (label.clone(), vec![pts])
            })
            .collect(),
        bands,
        x_range: (lo_hz * 1e-3, x_max.max(lo_hz * 1e-3 + 1e-9)),
        y_range: (floor, top * 2.0),
        log_y: true,
        markers: false,
        integer_x: false,
        zero_line: false,
        size: (1100, 600),
        first_colour: 0,
    }
    .write(stem)
}

/// Effective-mass curves M_eff/M_total against frequency in kHz, clipped to ±`y_limit`, each
/// curve's negative-mass bands shaded in its colour (paper Fig. 3).
/// Writes `stem.png` and `stem.svg`.
pub fn effective_mass(
    curves: &[(String, EffectiveMassCurve)],
    title: &str,
    y_limit: f64,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    if curves.is_empty() || curves.iter().any(|(_, c)| c.frequencies_hz.len() < 2) {
        return Err(bad(title, "needs curves of at least 2 frequencies"));
    }
    let mut bands = Vec::new();
    let mut series = Vec::new();
    for (i, (label, c)) in curves.iter().enumerate() {
        let poles: Vec<f64> = c.negative_bands_hz.iter().map(|b| b.0).collect();
        // Points beyond ±y_limit are left out: the line runs to the frame and breaks there
        // (no flat runs along the frame), and it breaks at every pole.
        let mut segments: Segments = vec![Vec::new()];
        let mut prev: Option<(f64, f64)> = None;
        for (&f, &m) in c.frequencies_hz.iter().zip(&c.normalised_mass) {
            let x = f * 1e-3;
            if let Some((px, _)) = prev {
                if poles.iter().any(|&p| px * 1e3 < p && p <= f) {
                    segments.push(Vec::new());
                    prev = None;
                }
            }
            if !m.is_finite() {
                prev = None;
                continue;
            }
            let inside = m.abs() <= y_limit;
            let seg = segments.last_mut().expect("at least one segment");
            match (prev, inside) {
                (Some((px, pm)), true) if pm.abs() > y_limit => {
                    seg.push((px, pm.clamp(-y_limit, y_limit)));
                    seg.push((x, m));
                }
                (_, true) => seg.push((x, m)),
                (Some((_, pm)), false) if pm.abs() <= y_limit => {
                    seg.push((x, m.clamp(-y_limit, y_limit)));
                    segments.push(Vec::new());
                }
                (_, false) => {}
            }
            prev = Some((x, m));
        }
        segments.retain(|s| !s.is_empty());
        series.push((label.clone(), segments));
        for &(lo, hi) in &c.negative_bands_hz {
            bands.push((lo * 1e-3, hi * 1e-3, Some(i), None));
        }
    }
    let x_max = curves
        .iter()
        .filter_map(|(_, c)| c.frequencies_hz.last().copied())
        .fold(0.0, f64::max)
        * 1e-3;
    let x_min = curves
        .iter()
        .map(|(_, c)| c.frequencies_hz[0])
        .fold(f64::INFINITY, f64::min)
        * 1e-3;
    LinePlot {
        title: title.to_string(),
        x_label: "frequency [kHz]".into(),
        y_label: "M_eff / M_total [-]".into(),
        series,
        bands,
        x_range: (x_min, x_max),
        y_range: (-y_limit, y_limit),
        log_y: false,
        markers: false,
        integer_x: false,
        zero_line: true,
        size: (1100, 600),
        first_colour: 0,
    }
    .write(stem)
}

/// Convergence of a genetic algorithm: best and mean objective per generation.
/// Writes `stem.png` and `stem.svg`.
pub fn convergence(
    points: &[ConvergencePoint],
    objective_label: &str,
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    if points.is_empty() {
        return Err(bad(title, "no generation"));
    }
    let (lo, hi) = finite_range(title, points.iter().flat_map(|p| [p.best, p.mean]))?;
    let (y0, y1) = padded(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo));
    let g0 = points[0].generation as f64;
    let g1 = (points[points.len() - 1].generation as f64).max(g0 + 1.0);
    let line = |f: fn(&ConvergencePoint) -> f64| {
        vec![points
            .iter()
            .map(|p| (p.generation as f64, f(p)))
            .filter(|p| p.1.is_finite())
            .collect()]
    };
    LinePlot {
        title: title.to_string(),
        x_label: "generation".into(),
        y_label: objective_label.to_string(),
        series: vec![
            ("best".to_string(), line(|p| p.best)),
            ("population mean".to_string(), line(|p| p.mean)),
        ],
        bands: Vec::new(),
        x_range: (g0, g1),
        y_range: (y0, y1),
        log_y: false,
        markers: points.len() <= 40,
        integer_x: true,
        zero_line: false,
        size: (1000, 600),
        first_colour: 0,
    }
    .write(stem)
}

/// Hypervolume of a Pareto search's front per generation (NSGA-II's `history.csv`), with the
/// reference point stated in the title by the caller. Writes `stem.png` and `stem.svg`.
pub fn hypervolume_history(
    points: &[(usize, f64)],
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    if points.is_empty() {
        return Err(bad(title, "no generation"));
    }
    let (lo, hi) = finite_range(title, points.iter().map(|p| p.1))?;
    let (y0, y1) = padded(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo));
    let g0 = points[0].0 as f64;
    let g1 = (points[points.len() - 1].0 as f64).max(g0 + 1.0);
    LinePlot {
        title: title.to_string(),
        x_label: "generation".into(),
        y_label: "hypervolume [product of the objectives' SI units]".into(),
        series: vec![(
            "hypervolume".to_string(),
            vec![points.iter().map(|&(g, h)| (g as f64, h)).collect()],
        )],
        bands: Vec::new(),
        x_range: (g0, g1),
        y_range: (y0, y1),
        log_y: false,
        markers: points.len() <= 40,
        integer_x: true,
        zero_line: false,
        size: (1000, 600),
        first_colour: 0,
    }
    .write(stem)
}

/// Peak force per interface k = 1..N (one or more series, e.g. protocol vs full chain; paper
/// Fig. 7 b).
/// Writes `stem.png` and `stem.svg`.
pub fn peaks_per_layer(
    series: &[Series],
    title: &str,
    y_label: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    let n = series.iter().map(|s| s.values.len()).max().unwrap_or(0);
    if n == 0 {
        return Err(bad(title, "no value"));
    }
    let (_, hi) = finite_range(title, series.iter().flat_map(|s| s.values.iter().copied()))?;
    LinePlot {
        title: title.to_string(),
        x_label: "interface k (rod k – rod k+1; N = wall)".into(),
        y_label: y_label.to_string(),
        series: series
            .iter()
            .map(|s| {
                let pts = s
                    .values
                    .iter()
                    .enumerate()
                    .map(|(k, v)| ((k + 1) as f64, *v))
                    .filter(|p| p.1.is_finite())
                    .collect();
                (s.label.clone(), vec![pts])
            })
            .collect(),
        bands: Vec::new(),
        x_range: (0.5, n as f64 + 0.5),
        y_range: padded(0.0, hi * 1.1),
        log_y: false,
        markers: true,
        integer_x: true,
        zero_line: false,
        size: (1000, 600),
        first_colour: 0,
    }
    .write(stem)
}

/// A transmission spectrum T_dB against frequency in kHz with the finite chain's exact linear
/// response beside it, the predicted (Bloch) band gaps shaded grey and the stop-band level
/// `threshold_db` drawn (docs/physics.md §15).
/// Writes `stem.png` and `stem.svg`.
pub fn transmission(
    spectrum: &woodpile::analysis::TransmissionSpectrum,
    threshold_db: f64,
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    let points: Vec<(f64, f64)> = spectrum
        .frequencies_hz
        .iter()
        .zip(&spectrum.transmission_db)
        .filter(|(_, t)| t.is_finite())
        .map(|(f, t)| (f * 1e-3, *t))
        .collect();
    let (lo, hi) = finite_range(title, points.iter().map(|p| p.1))?;
    // Resonance peaks and the deepest notches say little: show threshold − 40 dB to +40 dB at
    // most, points clamped to the frame (plotters does not clip lines).
    let (lo, hi) = padded(
        lo.max(threshold_db - 40.0).min(threshold_db - 5.0),
        hi.clamp(5.0, 40.0),
    );
    let points: Vec<(f64, f64)> = points
        .into_iter()
        .map(|(f, t)| (f, t.clamp(lo, hi)))
        .collect();
    // The linear prediction drops far below any measurement inside a gap: clamped to the frame.
    let linear: Vec<(f64, f64)> = spectrum
        .frequencies_hz
        .iter()
        .zip(&spectrum.linear_transmission_db)
        .filter(|(_, t)| !t.is_nan())
        .map(|(f, t)| (f * 1e-3, t.clamp(lo, hi)))
        .collect();
    let x_range = match (points.first(), points.last()) {
        (Some(a), Some(b)) if b.0 > a.0 => (a.0, b.0),
        _ => return Err(bad(title, "fewer than two finite frequencies")),
    };
    let mut bands: Vec<(f64, f64, Option<usize>, Option<String>)> = spectrum
        .prediction
        .iter()
        .flat_map(|p| p.gaps_hz.iter())
        .map(|&(a, b)| (a * 1e-3, b.min(1e12) * 1e-3, None, None))
        .collect();
    if let Some(first) = bands.first_mut() {
        first.3 = Some("predicted gap (Bloch)".to_string());
    }
    let threshold = vec![(x_range.0, threshold_db), (x_range.1, threshold_db)];
    LinePlot {
        title: title.to_string(),
        x_label: "frequency [kHz]".into(),
        y_label: "transmission |F_wall| / |F_drive| [dB]".into(),
        series: vec![
            ("measured".to_string(), vec![points]),
            ("linear prediction (finite chain)".to_string(), vec![linear]),
            (
                format!("{threshold_db} dB (stop-band level)"),
                vec![threshold],
            ),
        ],
        bands,
        x_range,
        y_range: (lo, hi),
        log_y: false,
        markers: false,
        integer_x: false,
        zero_line: true,
        size: (1100, 600),
        first_colour: 0,
    }
    .write(stem)
}
