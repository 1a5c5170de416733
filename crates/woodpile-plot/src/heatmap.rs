//! Heat maps of a [`Map2`]: rows (contact or layer, index 0 at the top, as in the chain) against
//! columns (time or frequency), with a colour bar that carries the value's unit.
//!
//! Large maps are reduced before drawing, to at most [`MAX_DRAWN_ROWS`] × [`MAX_DRAWN_COLUMNS`]
//! cells: each drawn cell holds the value of largest magnitude of its group of rows and
//! columns, so a narrow peak survives. The PNG is drawn cell by cell; the SVG carries the cells
//! as one embedded PNG `<image>` (each cell a block of whole pixels, at least the plotting
//! area's resolution, marked to scale without smoothing), so its size is bounded by the figure,
//! not the chain's length: as rectangles the cells of a 10,001 × 2,000 map take 15.5 MB
//! (measured), as an image 85 KB.

use crate::colorbar::{ColorBar, ColorScale};
use crate::typeset::Line;
use crate::{
    finite_range, format_number, render, ColorMap, DrawResult, Figure, PlotError, Result, FONT,
};
use base64::Engine as _;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use woodpile::Map2;

/// Most columns drawn: wider maps are reduced by taking the value of largest magnitude of each
/// group of columns, so narrow peaks survive (and the files stay small).
const MAX_DRAWN_COLUMNS: usize = 600;

/// Most rows drawn: maps of longer chains are reduced like the columns (value of largest
/// magnitude of each group of rows); the y axis still names the real rows.
const MAX_DRAWN_ROWS: usize = 300;

/// Fill of the rectangle that stands for the cells in the SVG until [`Heatmap::write`] replaces
/// it by the cells' image.
const SVG_CELLS_PLACEHOLDER: RGBColor = RGBColor(1, 2, 3);
const SVG_CELLS_PLACEHOLDER_FILL: &str = "fill=\"#010203\"";

/// Tick-label font size of the map's axes \[px\].
const AXIS_TICK_FONT_PX: f64 = 15.0;
/// Axis-label font size of the map's axes \[px\].
const AXIS_LABEL_FONT_PX: f64 = 17.0;

/// A heat map and how to draw it.
///
/// Colour limits come from the data: from the smallest value (linear) or `log_decades` below the
/// top (log) up to the largest value, or up to the `saturate_quantile` quantile of the non-zero
/// drawn cells. Whatever lies beyond a limit is drawn in the limit's colour and the colour bar
/// says so: "≥" / "≤" on the limit's label and a triangular cap on that end of the bar. Both
/// limits are always labelled.
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
    /// Colour by log10 of the value, over `log_decades` decades below the top limit (smaller
    /// values and zeros take the bottom colour, marked "≤" on the bar); None: linear colours.
    pub log_decades: Option<f64>,
    /// Top colour limit at this quantile of the non-zero drawn cells (e.g. 0.99), so that a few
    /// large values (the striker at t = 0) do not flatten the rest; larger values saturate,
    /// marked "≥" on the bar. None: the top limit is the largest value.
    pub saturate_quantile: Option<f64>,
}

impl<'a> Heatmap<'a> {
    /// A map with its own axis names and units, linear colours (viridis) up to the largest value,
    /// no rescaling.
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
        render(&Cells::of(self), stem)
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
        groups(n, MAX_DRAWN_COLUMNS)
            .into_iter()
            .map(|(c0, c1)| {
                let x0 = xs[c0] * self.x_scale - 0.5 * dx;
                let x1 = xs[c1 - 1] * self.x_scale + 0.5 * dx;
                (x0, x1, c0, c1)
            })
            .collect()
    }
}

/// `n` items in at most `most` consecutive groups of near-equal size: (first, end) per group.
fn groups(n: usize, most: usize) -> Vec<(usize, usize)> {
    let k = n.min(most).max(1);
    (0..k).map(|g| (g * n / k, (g + 1) * n / k)).collect()
}

/// A heat map reduced to the cells drawn, with its colour scale.
struct Cells<'h, 'a> {
    heatmap: &'h Heatmap<'a>,
    /// Column bins: (x0, x1, first col, end col), scaled x units.
    bins: Vec<(f64, f64, usize, usize)>,
    /// Row groups: (first row, end row).
    row_groups: Vec<(usize, usize)>,
    /// Colour of each drawn cell, row group-major.
    colours: Vec<RGBColor>,
    scale: ColorScale,
}

impl<'h, 'a> Cells<'h, 'a> {
    fn of(heatmap: &'h Heatmap<'a>) -> Self {
        let m = heatmap.map;
        let bins = heatmap.bins();
        let row_groups = groups(m.n_rows(), MAX_DRAWN_ROWS);
        // The value of largest magnitude in each group of rows × columns, scaled.
        let mut values = Vec::with_capacity(row_groups.len() * bins.len());
        for &(r0, r1) in &row_groups {
            let mut peak = vec![f64::NAN; bins.len()];
            for r in r0..r1 {
                let row = m.row(r);
                for (p, &(_, _, c0, c1)) in peak.iter_mut().zip(&bins) {
                    for &v in &row[c0..c1] {
                        if v.is_finite() && (p.is_nan() || v.abs() > p.abs()) {
                            *p = v;
                        }
                    }
                }
            }
            values.extend(peak.into_iter().map(|v| v * heatmap.value_scale));
        }
        let scale = ColorScale::of(
            &values,
            heatmap.color_map,
            heatmap.log_decades,
            heatmap.saturate_quantile,
        );
        let colours = values.iter().map(|&v| scale.rgb(v)).collect();
        Cells {
            heatmap,
            bins,
            row_groups,
            colours,
            scale,
        }
    }

    /// Label of the row at y coordinate `y` (−row index), or "" between rows.
    fn row_label(&self, y: f64) -> String {
        let i = -y;
        let rows = &self.heatmap.map.rows.values;
        if (i - i.round()).abs() > 1e-6 || i.round() < 0.0 || i.round() as usize >= rows.len() {
            return String::new();
        }
        format_number(rows[i.round() as usize])
    }

    /// The cells as a PNG, top row group first, each cell repeated over `k.0` × `k.1` pixels.
    fn png(&self, k: (usize, usize)) -> std::result::Result<Vec<u8>, png::EncodingError> {
        let (nb, ng) = (self.bins.len(), self.row_groups.len());
        let (w, h) = (nb * k.0, ng * k.1);
        let mut rgb = Vec::with_capacity(3 * w * h);
        for row in self.colours.chunks(nb) {
            let line: Vec<u8> = row
                .iter()
                .flat_map(|c| std::iter::repeat_n([c.0, c.1, c.2], k.0).flatten())
                .collect();
            for _ in 0..k.1 {
                rgb.extend_from_slice(&line);
            }
        }
        let mut bytes = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut bytes, w as u32, h as u32);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            encoder.set_compression(png::Compression::Best);
            let mut writer = encoder.write_header()?;
            writer.write_image_data(&rgb)?;
        }
        Ok(bytes)
    }

    /// Replaces the placeholder rectangle of the SVG text by the cells' image (an SVG drawn
    /// without the placeholder is returned as it is). Each cell is repeated over a whole number of
    /// image pixels so that the image has at least the rectangle's pixels: viewers that smooth
    /// scaled images (some ignore `image-rendering`) then blur only a cell's outermost pixel, and
    /// those that honour it show sharp cells at any zoom.
    fn embed_in_svg(&self, svg: String) -> std::result::Result<String, String> {
        let Some(at) = svg.find(SVG_CELLS_PLACEHOLDER_FILL) else {
            return Ok(svg);
        };
        let start = svg[..at].rfind("<rect").ok_or("no <rect")?;
        let end = at + svg[at..].find("/>").ok_or("no />")? + 2;
        let rect = &svg[start..end];
        let attribute = |name: &str| -> std::result::Result<String, String> {
            let key = format!(" {name}=\"");
            let i = rect.find(&key).ok_or(format!("no {name}"))? + key.len();
            Ok(rect[i..i + rect[i..].find('"').unwrap_or(0)].to_string())
        };
        let (width, height) = (attribute("width")?, attribute("height")?);
        let pixels = |s: &str, cells: usize| {
            let px: f64 = s.parse().unwrap_or(0.0);
            ((px / cells as f64).ceil() as usize).clamp(1, 64)
        };
        let k = (
            pixels(&width, self.bins.len()),
            pixels(&height, self.row_groups.len()),
        );
        let png = self.png(k).map_err(|e| e.to_string())?;
        let image = format!(
            "<image x=\"{}\" y=\"{}\" width=\"{width}\" height=\"{height}\" \
             preserveAspectRatio=\"none\" image-rendering=\"optimizeSpeed\" \
             style=\"image-rendering:crisp-edges;image-rendering:pixelated\" \
             href=\"data:image/png;base64,{}\"/>",
            attribute("x")?,
            attribute("y")?,
            base64::engine::general_purpose::STANDARD.encode(png)
        );
        Ok(format!("{}{}{}", &svg[..start], image, &svg[end..]))
    }
}

impl Figure for Cells<'_, '_> {
    fn size(&self) -> (u32, u32) {
        (1100, 620)
    }

    fn finish_svg(&self, svg: String) -> std::result::Result<String, String> {
        self.embed_in_svg(svg)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let h = self.heatmap;
        let m = h.map;
        let bar = ColorBar {
            scale: &self.scale,
            label: &h.value_label,
        };
        let (w, _) = root.dim_in_pixel();
        let (main, _) = root.split_horizontally(w - bar.width());
        let n = m.n_rows();
        let (y_top, y_bottom) = (0.5, -(n as f64) + 0.5);
        let (x0, x1) = (self.bins[0].0, self.bins[self.bins.len() - 1].1);
        // The y-label area holds the widest row label, the tick marks and the axis label, all
        // measured at their printed size (the output's text scale).
        let ts = crate::output::text_scale();
        let widest_row_label = groups(n, 200)
            .into_iter()
            .map(|(r, _)| r)
            .chain([n - 1])
            .map(|r| {
                let s = self.row_label(-(r as f64));
                Line::new(&s, AXIS_TICK_FONT_PX * ts, false).size().0.ceil() as u32
            })
            .max()
            .unwrap_or(0);
        // A y label longer than the plotting height (a small figure) drops its parenthesis.
        let (_, root_h) = root.dim_in_pixel();
        let plot_height = f64::from(root_h) - 2.0 * 12.0 - 50.0 - 1.5 * 22.0 * ts;
        let y_label = match h.y_label.split_once(" (") {
            Some((short, _))
                if f64::from(
                    Line::new(&h.y_label, AXIS_LABEL_FONT_PX * ts, false)
                        .size()
                        .0,
                ) > plot_height =>
            {
                short.to_string()
            }
            _ => h.y_label.clone(),
        };
        let axis_label_height = Line::new(&y_label, AXIS_LABEL_FONT_PX * ts, false)
            .size()
            .1
            .ceil() as u32;
        let mut chart = ChartBuilder::on(&main)
            .caption(&h.title, (FONT, 22))
            .margin(12)
            .x_label_area_size(50)
            .y_label_area_size(widest_row_label + axis_label_height + 22)
            .build_cartesian_2d(x0..x1, y_bottom..y_top)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&h.x_label)
            .x_label_formatter(&|v| format_number(*v))
            .y_desc(&y_label)
            .y_labels(n.min(12))
            .y_label_formatter(&|y| self.row_label(*y))
            .label_style((FONT, AXIS_TICK_FONT_PX))
            .axis_desc_style((FONT, AXIS_LABEL_FONT_PX))
            .draw()?;
        // The SVG gets one placeholder rectangle, replaced by the cells' image after drawing
        // (plotters' SVG backend can embed a bitmap only through the `image` crate).
        if std::any::type_name::<DB>().contains("SVGBackend") {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(x0, y_bottom), (x1, y_top)],
                SVG_CELLS_PLACEHOLDER.filled(),
            )))?;
        } else {
            let nb = self.bins.len();
            chart.draw_series(
                self.row_groups
                    .iter()
                    .enumerate()
                    .flat_map(|(g, &(r0, r1))| {
                        self.bins
                            .iter()
                            .enumerate()
                            .map(move |(b, &(bx0, bx1, _, _))| {
                                Rectangle::new(
                                    [(bx0, -(r1 as f64) + 0.5), (bx1, -(r0 as f64) + 0.5)],
                                    self.colours[g * nb + b].filled(),
                                )
                            })
                    }),
            )?;
        }
        let (px, py) = chart.plotting_area().get_pixel_range();
        bar.draw(root, px.end, py)?;
        Ok(())
    }
}

/// What drives contact 0, for axis labels: the given name, or "striker, load or actuator".
pub fn contact0_name(contact0: Option<&str>) -> &str {
    contact0.unwrap_or("striker, load or actuator")
}

/// How the colours of the force and energy maps follow their values (`woodpile plot --colours`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MapColours {
    /// Each map's own default: force linear from 0 to the largest force (the peak is what the map
    /// is read for), energy log over 3 decades (see [`energy_map`]).
    #[default]
    Auto,
    /// Linear, the top limit at the 99.5 % quantile of the non-zero cells (robust: a few extreme
    /// cells, such as the striker's at t = 0, saturate, marked "≥" on the bar).
    Robust,
    /// Log over 3 decades below the largest value (weak echoes and tails become visible).
    Log,
}

impl MapColours {
    /// The names `woodpile plot --colours` takes.
    pub const NAMES: &'static str = "auto, robust, log";

    /// Parses a name of [`MapColours::NAMES`].
    pub fn from_name(name: &str) -> std::result::Result<Self, String> {
        match name {
            "auto" => Ok(MapColours::Auto),
            "robust" => Ok(MapColours::Robust),
            "log" => Ok(MapColours::Log),
            other => Err(format!(
                "unknown colour scale `{other}`; valid: {}",
                Self::NAMES
            )),
        }
    }

    /// Applies the choice to a map's style (Auto keeps it).
    pub fn apply(self, heatmap: Heatmap<'_>) -> Heatmap<'_> {
        match self {
            MapColours::Auto => heatmap,
            MapColours::Robust => Heatmap {
                log_decades: None,
                saturate_quantile: Some(0.995),
                ..heatmap
            },
            MapColours::Log => Heatmap {
                log_decades: Some(3.0),
                saturate_quantile: None,
                ..heatmap
            },
        }
    }
}

/// The style of [`force_map`]: contact × time, time in ms, force in N, viridis, linear colours
/// from 0 to the largest force.
pub fn force_heatmap<'a>(map: &'a Map2, title: &str, contact0: Option<&str>) -> Heatmap<'a> {
    Heatmap {
        x_scale: 1e3,
        x_label: "time [ms]".into(),
        y_label: format!("contact (0 = {}; N = wall)", contact0_name(contact0)),
        value_label: "contact force [N]".into(),
        ..Heatmap::new(map, title)
    }
}

/// Contact force map (contact × time): time in ms, force in N, viridis (paper Figs. 5, 9),
/// linear colours from 0 up to the largest force (the peak of the pulse is the quantity read off
/// this map, so it is not saturated; [`MapColours`] gives robust or log colours).
///
/// `contact0` names what drives contact 0 (`striker`, `load`, `actuator`, see [`contact0_name`]),
/// so the axis says it; None: "striker, load or actuator".
pub fn force_map(
    map: &Map2,
    title: &str,
    contact0: Option<&str>,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    force_heatmap(map, title, contact0).write(stem)
}

/// The style of [`energy_map`]: layer × time, % of the injected energy, inferno, log colours
/// over 3 decades.
pub fn energy_heatmap<'a>(map: &'a Map2, title: &str, contact0: Option<&str>) -> Heatmap<'a> {
    Heatmap {
        color_map: ColorMap::Inferno,
        x_scale: 1e3,
        x_label: "time [ms]".into(),
        y_label: format!("layer (0 = {})", contact0_name(contact0)),
        value_scale: 100.0,
        value_label: "layer energy / injected energy [%]".into(),
        log_decades: Some(3.0),
        ..Heatmap::new(map, title)
    }
}

/// Energy map (layer × time): time in ms, energy in % of the injected energy, inferno
/// (paper Fig. 6), log colours over 3 decades below the largest value.
///
/// Why log: under an impact the striker's row holds 100 % at t = 0 while the travelling wave
/// carries a few % per layer and its tail a fraction of a %. Linear colours up to 100 % leave the
/// wave in the darkest tenth of the range; linear colours saturated at a high quantile (the
/// former default, ~25 %) paint the striker and the first layers one flat colour. Over
/// 0.1 %…100 % every decade of the wave takes a third of the range and nothing saturates at the
/// top; energies below 0.1 % (the chain ahead of the wave) take the bottom colour, marked "≤".
///
/// `contact0` as in [`force_map`] (layer 0 is what drives contact 0).
pub fn energy_map(
    map: &Map2,
    title: &str,
    contact0: Option<&str>,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    energy_heatmap(map, title, contact0).write(stem)
}

/// Spectrum map (contact × frequency): frequency in kHz up to `max_frequency_hz`, amplitude in
/// N on a log colour scale over 4 decades (paper Fig. 9 b, d, f, h); `contact0` as in
/// [`force_map`].
pub fn spectrum_map(
    map: &Map2,
    title: &str,
    max_frequency_hz: f64,
    contact0: Option<&str>,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    Heatmap {
        x_scale: 1e-3,
        x_label: "frequency [kHz]".into(),
        x_max: Some(max_frequency_hz * 1e-3),
        y_label: format!("contact (0 = {}; N = wall)", contact0_name(contact0)),
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
