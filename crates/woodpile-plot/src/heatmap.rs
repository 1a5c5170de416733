//! Heat maps of a [`Map2`]: rows (contact or layer, index 0 at the top, as in the chain) against
//! columns (time or frequency), with a colour bar that carries the value's unit.

use crate::{finite_range, padded, render, ColorMap, DrawResult, Figure, PlotError, Result, FONT};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use woodpile::Map2;

/// Most columns drawn: wider maps are reduced by taking the largest value of each group of
/// columns, so narrow peaks survive (and the SVG stays small).
const MAX_DRAWN_COLUMNS: usize = 600;

/// A heat map and how to draw it.
#[derive(Debug, Clone)]
pub struct Heatmap<'a> {
    /// The data.
    pub map: &'a Map2,
    /// Title (name the chain and the excitation).
    pub title: String,
    /// Colour map.
    pub color_map: ColorMap,
    /// Factor applied to the column coordinates (1e3: s → ms, 1e-3: Hz → kHz).
    pub x_scale: f64,
    /// x-axis label with unit.
    pub x_label: String,
    /// Largest x drawn (scaled units), or None for all columns.
    pub x_max: Option<f64>,
    /// y-axis label.
    pub y_label: String,
    /// Factor applied to the values (100: ratio → %).
    pub value_scale: f64,
    /// Colour bar label with unit.
    pub value_label: String,
    /// Colour by log10 of the value, over `log_decades` decades below the maximum.
    pub log_decades: Option<f64>,
    /// Saturate the colours above this quantile of the drawn cells (e.g. 0.99), so that a few
    /// large values (the striker at t = 0) do not flatten the rest; None: up to the maximum.
    pub saturate_quantile: Option<f64>,
}

impl<'a> Heatmap<'a> {
    /// A map with its own axis names and units, linear colours (viridis), no rescaling.
    pub fn new(map: &'a Map2, title: impl Into<String>) -> Self {
        Heatmap {
            map,
            title: title.into(),
            color_map: ColorMap::Viridis,
            x_scale: 1.0,
            x_label: map.cols.label(),
            x_max: None,
            y_label: map.rows.label(),
            value_scale: 1.0,
            value_label: map.value_label(),
            log_decades: None,
            saturate_quantile: None,
        }
    }

    /// Writes `stem.png` and `stem.svg`.
    pub fn write(&self, stem: &Path) -> Result<Vec<PathBuf>> {
        let m = self.map;
        if m.n_rows() == 0 || m.n_cols() < 2 {
            return Err(PlotError::BadData {
                what: self.title.clone(),
                reason: format!(
                    "a heat map needs at least 1 row and 2 columns, got {} × {}",
                    m.n_rows(),
                    m.n_cols()
                ),
            });
        }
        finite_range(&self.title, m.data.iter().copied())?;
        render(self, stem)
    }

    /// Columns kept (those up to `x_max`), grouped into at most [`MAX_DRAWN_COLUMNS`] bins:
    /// returns (x0, x1, first col, end col) per bin, in scaled units.
    fn bins(&self) -> Vec<(f64, f64, usize, usize)> {
        let xs = &self.map.cols.values;
        let dx = (xs[1] - xs[0]) * self.x_scale;
        let n = match self.x_max {
            Some(max) => xs.iter().take_while(|x| **x * self.x_scale <= max).count(),
            None => xs.len(),
        }
        .max(2);
        let nb = n.min(MAX_DRAWN_COLUMNS);
        (0..nb)
            .map(|b| {
                let (c0, c1) = (b * n / nb, (b + 1) * n / nb);
                let x0 = xs[c0] * self.x_scale - 0.5 * dx;
                let x1 = xs[c1 - 1] * self.x_scale + 0.5 * dx;
                (x0, x1, c0, c1)
            })
            .collect()
    }

    /// Value → colour-bar coordinate (scaled, or log10 of it).
    fn transform(&self, v: f64, vmax: f64) -> f64 {
        let v = v * self.value_scale;
        match self.log_decades {
            Some(d) => v.max(vmax * 10f64.powf(-d)).log10(),
            None => v,
        }
    }
}

impl Figure for Heatmap<'_> {
    fn size(&self) -> (u32, u32) {
        (1100, 620)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let m = self.map;
        let bins = self.bins();
        let (_, raw_max) =
            finite_range("", m.data.iter().copied()).expect("checked before drawing");
        let vmax_scaled = raw_max * self.value_scale;
        // Cell values: the largest of each bin, transformed to colour-bar units.
        let mut cells = Vec::with_capacity(m.n_rows() * bins.len());
        for r in 0..m.n_rows() {
            let row = m.row(r);
            for &(_, _, c0, c1) in &bins {
                let v = row[c0..c1]
                    .iter()
                    .copied()
                    .filter(|v| v.is_finite())
                    .fold(f64::NEG_INFINITY, f64::max);
                cells.push(self.transform(v, vmax_scaled));
            }
        }
        let mut finite: Vec<f64> = cells.iter().copied().filter(|v| v.is_finite()).collect();
        finite.sort_by(f64::total_cmp);
        let top = match self.saturate_quantile {
            Some(q) => finite[((finite.len() - 1) as f64 * q.clamp(0.0, 1.0)).round() as usize],
            None => finite[finite.len() - 1],
        };
        let (lo, hi) = padded(finite[0], top);
        let colour = |v: f64| self.color_map.rgb((v - lo) / (hi - lo));

        let (w, _) = self.size();
        let (main, bar) = root.split_horizontally(w - 150);
        let rows = &m.rows.values;
        let y_top = -rows[0] + 0.5;
        let y_bottom = -rows[rows.len() - 1] - 0.5;
        let (x0, x1) = (bins[0].0, bins[bins.len() - 1].1);
        let mut chart = ChartBuilder::on(&main)
            .caption(&self.title, (FONT, 22))
            .margin(12)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y_bottom..y_top)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&self.x_label)
            .x_label_formatter(&|v| format_number(*v))
            .y_desc(&self.y_label)
            .y_labels(rows.len().min(12))
            .y_label_formatter(&|y| format!("{}", (-y).round().abs() as i64))
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17))
            .draw()?;
        let nb = bins.len();
        chart.draw_series(
            bins.iter()
                .enumerate()
                .flat_map(|(b, &(bx0, bx1, _, _))| {
                    rows.iter()
                        .enumerate()
                        .map(move |(r, &row)| (b, r, bx0, bx1, -row))
                })
                .map(|(b, r, bx0, bx1, y)| {
                    Rectangle::new(
                        [(bx0, y - 0.5), (bx1, y + 0.5)],
                        colour(cells[r * nb + b]).filled(),
                    )
                }),
        )?;

        // Colour bar.
        let mut cb = ChartBuilder::on(&bar)
            .margin_top(45)
            .margin_bottom(62)
            .margin_right(8)
            .y_label_area_size(90)
            .build_cartesian_2d(0.0..1.0, lo..hi)?;
        let log = self.log_decades.is_some();
        cb.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(&self.value_label)
            .y_labels(if log {
                (hi - lo).round() as usize + 1
            } else {
                8
            })
            .y_label_formatter(&|v| {
                if log {
                    format_number(10f64.powf(*v))
                } else {
                    format_number(*v)
                }
            })
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 16))
            .draw()?;
        let steps = 128;
        cb.draw_series((0..steps).map(|i| {
            let a = lo + (hi - lo) * i as f64 / steps as f64;
            let b = lo + (hi - lo) * (i + 1) as f64 / steps as f64;
            Rectangle::new([(0.0, a), (1.0, b)], colour(0.5 * (a + b)).filled())
        }))?;
        Ok(())
    }
}

/// Short number for axis labels: up to 3 significant digits without trailing zeros, scientific
/// outside [1e-3, 1e5).
pub(crate) fn format_number(v: f64) -> String {
    let a = v.abs();
    if a < 1e-12 {
        "0".to_string()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.0e}")
    } else {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    }
}

/// Contact force map (contact × time): time in ms, force in N, viridis (paper Figs. 5, 9).
pub fn force_map(map: &Map2, title: &str, stem: &Path) -> Result<Vec<PathBuf>> {
    Heatmap {
        x_scale: 1e3,
        x_label: "time [ms]".into(),
        y_label: "contact (0 = striker, load or actuator; N = wall)".into(),
        value_label: "contact force [N]".into(),
        ..Heatmap::new(map, title)
    }
    .write(stem)
}

/// Energy map (layer × time): time in ms, energy in % of the injected energy, inferno
/// (paper Fig. 6).
pub fn energy_map(map: &Map2, title: &str, stem: &Path) -> Result<Vec<PathBuf>> {
    Heatmap {
        color_map: ColorMap::Inferno,
        x_scale: 1e3,
        x_label: "time [ms]".into(),
        y_label: "layer (0 = striker, load or actuator)".into(),
        value_scale: 100.0,
        value_label: "energy / injected energy [%] (colours saturate at the top)".into(),
        saturate_quantile: Some(0.995),
        ..Heatmap::new(map, title)
    }
    .write(stem)
}

/// Spectrum map (contact × frequency): frequency in kHz up to `max_frequency_hz`, amplitude in
/// N on a log colour scale over 4 decades (paper Fig. 9 b, d, f, h).
pub fn spectrum_map(
    map: &Map2,
    title: &str,
    max_frequency_hz: f64,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    Heatmap {
        x_scale: 1e-3,
        x_label: "frequency [kHz]".into(),
        x_max: Some(max_frequency_hz * 1e-3),
        y_label: "contact (0 = striker, load or actuator; N = wall)".into(),
        value_label: format!("{} [{}] (log)", map.value_name, map.value_unit),
        log_decades: Some(4.0),
        ..Heatmap::new(map, title)
    }
    .write(stem)
}

/// The layer-by-layer protocol's map (sub-chain k × time): wall force of the first k rods on
/// the sensor, i.e. the incident force at interface k (paper Fig. 7 a).
pub fn protocol_map(map: &Map2, title: &str, stem: &Path) -> Result<Vec<PathBuf>> {
    Heatmap {
        x_scale: 1e3,
        x_label: "time [ms]".into(),
        y_label: "interface k (first k rods on the sensor)".into(),
        value_label: "wall force [N]".into(),
        ..Heatmap::new(map, title)
    }
    .write(stem)
}
