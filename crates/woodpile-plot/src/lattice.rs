//! Figures of a lattice (docs/physics.md §16): the contact forces of each interface on the
//! crossing grid, window by window ([`interface_forces`]), and a three-dimensional view of the
//! rods with every contact coloured by its peak force ([`lattice_view`]).
//!
//! An *interface* k joins layer k to layer k + 1: interface 0 is the striker's contact with the
//! top layer (layer 0 is the striker), interface L the bottom layer's supports (layer L + 1),
//! as in `run.json`'s `contacts` (`layer_above` is the interface's number).

use crate::colorbar::{ColorBar, ColorScale};
use crate::typeset::Line;
use crate::FONT;
use crate::{format_number, render, ColorMap, DrawResult, Figure, MapColours, PlotError, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};

/// One rod as seen from above: its layer, number, centre, axis, length and diameter.
#[derive(Debug, Clone, PartialEq)]
pub struct RodLine {
    /// Layer, 1..=L from the top.
    pub layer: usize,
    /// Rod number in its layer, 1..
    pub number: usize,
    /// Centre (x, y) \[mm\].
    pub centre_mm: [f64; 2],
    /// Unit vector along the axis.
    pub axis: [f64; 2],
    /// Length \[mm\].
    pub length_mm: f64,
    /// Diameter \[mm\].
    pub diameter_mm: f64,
}

impl RodLine {
    /// The rod's two ends (x, y) \[mm\].
    fn ends(&self) -> [[f64; 2]; 2] {
        let h = 0.5 * self.length_mm;
        let [cx, cy] = self.centre_mm;
        let [ax, ay] = self.axis;
        [[cx - h * ax, cy - h * ay], [cx + h * ax, cy + h * ay]]
    }

    /// Its outline seen from above: a rectangle of its length and diameter \[mm\].
    fn outline(&self) -> Vec<(f64, f64)> {
        let [a, b] = self.ends();
        let r = 0.5 * self.diameter_mm;
        let n = [-self.axis[1] * r, self.axis[0] * r];
        vec![
            (a[0] + n[0], a[1] + n[1]),
            (b[0] + n[0], b[1] + n[1]),
            (b[0] - n[0], b[1] - n[1]),
            (a[0] - n[0], a[1] - n[1]),
        ]
    }
}

/// One contact: the layers it joins (0: the striker; L + 1: a support) and where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// Layer of the body above (0: the striker); the contact's interface.
    pub layer_above: usize,
    /// Layer of the body below (L + 1: a support).
    pub layer_below: usize,
    /// Where the contact is (x, y) \[mm\].
    pub x_mm: f64,
    /// Where the contact is \[mm\].
    pub y_mm: f64,
}

/// A lattice as drawn: its rods, its contacts in output order and its number of layers L.
#[derive(Debug, Clone, PartialEq)]
pub struct LatticeLayout {
    /// Every rod.
    pub rods: Vec<RodLine>,
    /// The contacts, in the order of the force columns.
    pub contacts: Vec<ContactPoint>,
    /// Number of layers L.
    pub layers: usize,
}

fn bad(what: &str, reason: impl Into<String>) -> PlotError {
    PlotError::BadData {
        what: what.to_string(),
        reason: reason.into(),
    }
}

impl LatticeLayout {
    /// Checks that every rod and contact can be drawn.
    fn check(&self, what: &str) -> Result<()> {
        if self.contacts.is_empty() {
            return Err(bad(what, "the lattice has no contact"));
        }
        for r in &self.rods {
            let finite = r.centre_mm.iter().chain(&r.axis).all(|v| v.is_finite());
            let sized = r.length_mm > 0.0 && r.diameter_mm > 0.0;
            if !finite || !sized || r.layer == 0 {
                return Err(bad(
                    what,
                    format!(
                        "rod {} of layer {} has no finite position, length or diameter",
                        r.number, r.layer
                    ),
                ));
            }
        }
        for (c, p) in self.contacts.iter().enumerate() {
            if !(p.x_mm.is_finite() && p.y_mm.is_finite())
                || p.layer_below != p.layer_above + 1
                || p.layer_below > self.layers + 1
            {
                return Err(bad(
                    what,
                    format!(
                        "contact {c} joins layers {} and {} at ({}, {}) mm: not adjacent layers of a {}-layer lattice",
                        p.layer_above, p.layer_below, p.x_mm, p.y_mm, self.layers
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The rods' and contacts' extent seen from above: (x0, x1, y0, y1) \[mm\].
    fn extent_mm(&self) -> (f64, f64, f64, f64) {
        let points = self
            .rods
            .iter()
            .flat_map(|r| r.outline())
            .chain(self.contacts.iter().map(|p| (p.x_mm, p.y_mm)));
        points.fold(
            (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ),
            |(a, b, c, d), (x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
        )
    }

    /// The contacts of interface k, by index.
    fn interface(&self, k: usize) -> Vec<usize> {
        (0..self.contacts.len())
            .filter(|&c| self.contacts[c].layer_above == k)
            .collect()
    }

    /// The name of interface k.
    fn interface_name(&self, k: usize) -> String {
        match k {
            0 => "striker on layer 1".to_string(),
            k if k == self.layers => format!("layer {k} on supports"),
            k => format!("layers {k} on {}", k + 1),
        }
    }
}

/// Most interfaces (rows) in one figure of [`interface_forces`]: more are drawn on further
/// pages, so that a page prints at most about 8 in tall at the default width.
pub const INTERFACES_PER_PAGE: usize = 5;

/// The colour scale of the forces drawn, in the map colours' style (forces from 0: auto and
/// robust are linear from 0, log spans 3 decades below the top).
fn force_scale(values: &[f64], colours: MapColours) -> ColorScale {
    let mut with_zero = values.to_vec();
    with_zero.push(0.0);
    let (log, quantile) = match colours {
        MapColours::Auto => (None, None),
        MapColours::Robust => (None, Some(0.995)),
        MapColours::Log => (Some(3.0), None),
    };
    ColorScale::of(&with_zero, ColorMap::Viridis, log, quantile)
}

/// Each interface's contact forces on the crossing grid, window by window: a grid of panels,
/// one row per interface (the striker's contact, the crossings of layers k and k + 1, the
/// supports) and one column per time window, each contact a disc at its (x, y) coloured by its
/// largest force in the window (of the samples at `times_s` with a ≤ t ≤ b), the rods of the
/// two layers as grey outlines to scale (the upper darker), x and y to the same scale. One
/// colour bar in N for every panel and page: linear from 0 to the largest force drawn (the
/// `colours` choice as for the maps: robust saturates above the 99.5 % quantile, log spans 3
/// decades).
///
/// `forces_n` holds the samples × the layout's contacts (row-major). Up to
/// [`INTERFACES_PER_PAGE`] interfaces are drawn per figure: `stem` when they fit, else
/// `stem_1`, `stem_2`, … with the interfaces split evenly, every page on the same scale.
/// Returns the files written.
pub fn interface_forces(
    layout: &LatticeLayout,
    times_s: &[f64],
    forces_n: &[f64],
    windows_s: &[(f64, f64)],
    colours: MapColours,
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    layout.check(title)?;
    let n = layout.contacts.len();
    if times_s.is_empty() || forces_n.len() != times_s.len() * n {
        return Err(bad(
            title,
            format!(
                "{} forces for {} samples × {n} contacts",
                forces_n.len(),
                times_s.len()
            ),
        ));
    }
    if windows_s.is_empty() {
        return Err(bad(title, "no time window"));
    }
    let values = window_maxima(times_s, forces_n, n, windows_s, title)?;
    crate::finite_range(title, values.iter().copied())?;
    let scale = force_scale(&values, colours);
    let interfaces: Vec<usize> = (0..=layout.layers)
        .filter(|&k| !layout.interface(k).is_empty())
        .collect();
    let pages = interfaces.len().div_ceil(INTERFACES_PER_PAGE);
    let per_page = interfaces.len().div_ceil(pages);
    let mut files = Vec::new();
    for (p, rows) in interfaces.chunks(per_page).enumerate() {
        let page_title = if pages > 1 {
            format!(
                "{title} (interfaces {}–{} of 0–{})",
                rows[0],
                rows[rows.len() - 1],
                layout.layers
            )
        } else {
            title.to_string()
        };
        let page_stem = if pages > 1 {
            let mut s = stem.as_os_str().to_owned();
            s.push(format!("_{}", p + 1));
            PathBuf::from(s)
        } else {
            stem.to_path_buf()
        };
        files.extend(render(
            &InterfaceGrid {
                layout,
                interfaces: rows,
                windows_s,
                values: &values,
                scale: &scale,
                title: page_title,
            },
            &page_stem,
        )?);
    }
    Ok(files)
}

/// Each contact's largest force in each window (windows × contacts), of the samples with
/// a ≤ t ≤ b; a window without a sample is an error.
fn window_maxima(
    times_s: &[f64],
    forces_n: &[f64],
    n: usize,
    windows_s: &[(f64, f64)],
    title: &str,
) -> Result<Vec<f64>> {
    let mut values = vec![0.0; windows_s.len() * n];
    for (w, &(a, b)) in windows_s.iter().enumerate() {
        let rows: Vec<&[f64]> = times_s
            .iter()
            .zip(forces_n.chunks(n))
            .filter(|(t, _)| a <= **t && **t <= b)
            .map(|(_, row)| row)
            .collect();
        if rows.is_empty() {
            return Err(bad(title, format!("no sample in the window {a} to {b} s")));
        }
        for c in 0..n {
            values[w * n + c] = rows
                .iter()
                .map(|row| row[c])
                .fold(f64::NEG_INFINITY, f64::max);
        }
    }
    Ok(values)
}

struct InterfaceGrid<'a> {
    layout: &'a LatticeLayout,
    /// The interfaces of this page, top to bottom.
    interfaces: &'a [usize],
    windows_s: &'a [(f64, f64)],
    /// Windows × contacts.
    values: &'a [f64],
    scale: &'a ColorScale,
    title: String,
}

/// Logical sizes of the interface grid.
const TITLE_PX: u32 = 50;
const HEADER_PX: u32 = 32;
const ROW_LABEL_PX: u32 = 34;
const Y_TICKS_PX: u32 = 62;
const X_TICKS_PX: u32 = 58;
const GAP_PX: u32 = 10;
const MARGIN_PX: u32 = 12;
const DISC_PX: u32 = 6;
const TICK_FONT: f64 = 14.0;
const LABEL_FONT: f64 = 15.0;

/// A label area of `units` at the text's printed size (the output's text scale).
fn scaled(units: u32) -> u32 {
    (f64::from(units) * crate::output::text_scale()).round() as u32
}

/// Tick labels for a panel side of `px` units: at most one per 30 units of printed text, 2 to 7.
fn ticks(px: u32) -> usize {
    (f64::from(px) / (30.0 * crate::output::text_scale())).clamp(2.0, 7.0) as usize
}

impl InterfaceGrid<'_> {
    /// The panels' data ranges (x0..x1, y0..y1) \[mm\] with the aspect `h / w` (equal scales).
    fn ranges(&self, w: f64, h: f64) -> ((f64, f64), (f64, f64)) {
        let (x0, x1, y0, y1) = self.layout.extent_mm();
        let pad = 0.05 * (x1 - x0).max(y1 - y0).max(1.0);
        let (mut sx, mut sy) = (x1 - x0 + 2.0 * pad, y1 - y0 + 2.0 * pad);
        if sy / sx < h / w {
            sy = sx * h / w;
        } else {
            sx = sy * w / h;
        }
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        (
            (cx - 0.5 * sx, cx + 0.5 * sx),
            (cy - 0.5 * sy, cy + 0.5 * sy),
        )
    }

    /// The panels' plotting size (w, h) in units for a canvas `width` wide beside a bar
    /// `bar_px` wide: the data's aspect, between 0.5 and 1.
    fn panel_size(&self, width: u32, bar_px: u32) -> (u32, u32) {
        let cols = self.windows_s.len() as u32;
        let free = width
            .saturating_sub(scaled(ROW_LABEL_PX) + scaled(Y_TICKS_PX) + bar_px + 2 * MARGIN_PX);
        let w = (free.saturating_sub(GAP_PX * (cols - 1)) / cols).max(40);
        let (x0, x1, y0, y1) = self.layout.extent_mm();
        let aspect = ((y1 - y0) / (x1 - x0).max(1e-9)).clamp(0.5, 1.0);
        (w, (f64::from(w) * aspect).round() as u32)
    }

    fn bar(&self) -> ColorBar<'_> {
        ColorBar {
            scale: self.scale,
            label: "largest contact force in the window [N]",
        }
    }

    /// Draws the panel of interface `k` in window `w` on `area` (its label areas included).
    #[allow(clippy::too_many_arguments)]
    fn draw_panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        k: usize,
        w: usize,
        ranges: ((f64, f64), (f64, f64)),
        y_ticks: bool,
        x_ticks: bool,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let ((x0, x1), (y0, y1)) = ranges;
        let (w_all, h_all) = area.dim_in_pixel();
        let w_px = w_all - if y_ticks { scaled(Y_TICKS_PX) } else { 0 };
        let h_px = h_all - if x_ticks { scaled(X_TICKS_PX) } else { 0 };
        let mut chart = ChartBuilder::on(area)
            .y_label_area_size(if y_ticks { scaled(Y_TICKS_PX) } else { 0 })
            .x_label_area_size(if x_ticks { scaled(X_TICKS_PX) } else { 0 })
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(ticks(w_px))
            .y_labels(ticks(h_px))
            .x_desc(if x_ticks { "x [mm]" } else { "" })
            // A row too short for the axis title goes without (its neighbours' would overlap).
            .y_desc(
                if y_ticks && f64::from(h_px) > 70.0 * crate::output::text_scale() {
                    "y [mm]"
                } else {
                    ""
                },
            )
            .x_label_formatter(&|v| {
                if x_ticks {
                    format_number(*v)
                } else {
                    String::new()
                }
            })
            .y_label_formatter(&|v| {
                if y_ticks {
                    format_number(*v)
                } else {
                    String::new()
                }
            })
            .label_style((FONT, TICK_FONT))
            .axis_desc_style((FONT, LABEL_FONT))
            .draw()?;
        let frame = RGBColor(200, 200, 200).stroke_width(1);
        chart.draw_series([Rectangle::new([(x0, y0), (x1, y1)], frame)])?;
        // The two layers' rods, the upper darker and drawn last.
        for (layer, grey) in [(k + 1, 225u8), (k, 175u8)] {
            let shade = RGBColor(grey, grey, grey);
            chart.draw_series(
                self.layout
                    .rods
                    .iter()
                    .filter(|r| r.layer == layer)
                    .map(|r| Polygon::new(r.outline(), shade.filled())),
            )?;
        }
        let n = self.layout.contacts.len();
        for c in self.layout.interface(k) {
            let p = self.layout.contacts[c];
            let colour = self.scale.rgb(self.values[w * n + c]);
            chart.draw_series([
                Circle::new((p.x_mm, p.y_mm), DISC_PX, colour.filled()),
                Circle::new((p.x_mm, p.y_mm), DISC_PX, BLACK.stroke_width(1)),
            ])?;
        }
        Ok(())
    }
}

impl Figure for InterfaceGrid<'_> {
    fn size(&self) -> (u32, u32) {
        let width = crate::output::REFERENCE_WIDTH;
        let (_, h) = self.panel_size(width, self.bar().width());
        let rows = self.interfaces.len() as u32;
        let height = scaled(TITLE_PX)
            + scaled(HEADER_PX)
            + rows * h
            + (rows - 1) * GAP_PX
            + scaled(X_TICKS_PX);
        (width, height + 2 * MARGIN_PX)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (width, height) = root.dim_in_pixel();
        let bar = self.bar();
        let rows = self.interfaces.len() as u32;
        let cols = self.windows_s.len() as u32;
        let (w, natural_h) = self.panel_size(width, bar.width());
        // Another height than the natural one (an output's aspect): the rows share it.
        let free = height.saturating_sub(
            scaled(TITLE_PX)
                + scaled(HEADER_PX)
                + scaled(X_TICKS_PX)
                + 2 * MARGIN_PX
                + (rows - 1) * GAP_PX,
        );
        let h = (free / rows).clamp(20, natural_h.max(20) * 2);
        let ranges = self.ranges(f64::from(w), f64::from(h));
        root.draw(&Text::new(
            self.title.clone(),
            (
                (width / 2) as i32,
                (MARGIN_PX + scaled(TITLE_PX) / 2) as i32,
            ),
            TextStyle::from((FONT, 22).into_font()).pos(Pos::new(HPos::Center, VPos::Center)),
        ))?;
        let left = MARGIN_PX + scaled(ROW_LABEL_PX) + scaled(Y_TICKS_PX);
        let top = MARGIN_PX + scaled(TITLE_PX) + scaled(HEADER_PX);
        let ms = |t: f64| format_number(t * 1e3);
        let label_style = TextStyle::from((FONT, LABEL_FONT).into_font());
        for (j, &(a, b)) in self.windows_s.iter().enumerate() {
            let x = left + j as u32 * (w + GAP_PX) + w / 2;
            root.draw(&Text::new(
                format!("{}–{} ms", ms(a), ms(b)),
                (x as i32, (top - scaled(HEADER_PX) / 2) as i32),
                label_style.pos(Pos::new(HPos::Center, VPos::Center)),
            ))?;
        }
        for (i, &k) in self.interfaces.iter().enumerate() {
            let y = top + i as u32 * (h + GAP_PX);
            let name = self.layout.interface_name(k);
            let fit = (f64::from(h)
                / f64::from(
                    Line::new(&name, LABEL_FONT * crate::output::text_scale(), false)
                        .size()
                        .0,
                ))
            .min(1.0);
            root.draw(&Text::new(
                name,
                (
                    (MARGIN_PX + scaled(ROW_LABEL_PX) / 2) as i32,
                    (y + h / 2) as i32,
                ),
                TextStyle::from((FONT, LABEL_FONT * fit).into_font())
                    .transform(FontTransform::Rotate270)
                    .pos(Pos::new(HPos::Center, VPos::Center)),
            ))?;
            for j in 0..cols {
                let x = left + j * (w + GAP_PX);
                let (y_ticks, x_ticks) = (j == 0, i as u32 == rows - 1);
                let x_from = if y_ticks { x - scaled(Y_TICKS_PX) } else { x };
                let w_all = w + if y_ticks { scaled(Y_TICKS_PX) } else { 0 };
                let h_all = h + if x_ticks { scaled(X_TICKS_PX) } else { 0 };
                let area = root.clone().shrink((x_from, y), (w_all, h_all));
                self.draw_panel(&area, k, j as usize, ranges, y_ticks, x_ticks)?;
            }
        }
        let bar_x = left + cols * w + (cols - 1) * GAP_PX;
        bar.draw(
            root,
            bar_x as i32,
            top as i32..(top + rows * h + (rows - 1) * GAP_PX) as i32,
        )?;
        Ok(())
    }
}

/// A three-dimensional view of the lattice: every rod as a grey line in its layer (layers
/// stacked top to bottom, the vertical axis numbering them: 0 the striker, L + 1 the
/// supports), every contact a disc between the two bodies it joins at its (x, y), coloured by
/// its peak force `peaks_n` (in the layout's contact order), with a colour bar in N linear from
/// 0 to the largest peak. x and y are to scale; the vertical axis counts layers. Returns the
/// files written.
pub fn lattice_view(
    layout: &LatticeLayout,
    peaks_n: &[f64],
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    layout.check(title)?;
    if peaks_n.len() != layout.contacts.len() {
        return Err(bad(
            title,
            format!(
                "{} peaks for {} contacts",
                peaks_n.len(),
                layout.contacts.len()
            ),
        ));
    }
    crate::finite_range(title, peaks_n.iter().copied())?;
    let scale = force_scale(peaks_n, MapColours::Auto);
    render(
        &LatticeView {
            layout,
            peaks_n,
            scale,
            title: title.to_string(),
        },
        stem,
    )
}

struct LatticeView<'a> {
    layout: &'a LatticeLayout,
    peaks_n: &'a [f64],
    scale: ColorScale,
    title: String,
}

impl Figure for LatticeView<'_> {
    fn size(&self) -> (u32, u32) {
        (crate::output::REFERENCE_WIDTH, 820)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let bar = ColorBar {
            scale: &self.scale,
            label: "peak contact force [N]",
        };
        let (w, _) = root.dim_in_pixel();
        let (main, _) = root.split_horizontally(w - bar.width());
        let (x0, x1, y0, y1) = self.layout.extent_mm();
        // The same span on x and y: the plane is to scale.
        let half = 0.5 * (x1 - x0).max(y1 - y0) * 1.05;
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let bottom = -(self.layout.layers as f64) - 1.0;
        let mut chart = ChartBuilder::on(&main)
            .caption(&self.title, (FONT, 22))
            .margin(MARGIN_PX)
            .build_cartesian_3d(cx - half..cx + half, bottom..0.0, -cy - half..-cy + half)?;
        chart.with_projection(|mut p| {
            p.pitch = 0.45;
            p.yaw = 0.6;
            p.scale = 0.85;
            p.into_matrix()
        });
        let layer_label = |v: &f64| {
            let l = (-v).round();
            if (v + l).abs() > 1e-6 {
                String::new()
            } else if l == 0.0 {
                "striker".to_string()
            } else if l as usize == self.layout.layers + 1 {
                "supports".to_string()
            } else {
                format!("layer {l}")
            }
        };
        chart
            .configure_axes()
            .x_labels(5)
            .z_labels(5)
            .y_labels(self.layout.layers + 2)
            .x_formatter(&|v| format!("x {} mm", format_number(*v)))
            .z_formatter(&|v| format!("y {} mm", format_number(-*v)))
            .y_formatter(&layer_label)
            .label_style((FONT, TICK_FONT))
            .axis_panel_style(RGBColor(248, 248, 248))
            .light_grid_style(TRANSPARENT)
            .bold_grid_style(RGBColor(215, 215, 215))
            .draw()?;
        // Painter's order, bottom up: the supports, the bottom rods, the crossings above them…
        let height = |a: usize, b: usize| -0.5 * (a + b) as f64;
        let n = self.layout.contacts.len();
        for level in (0..=self.layout.layers + 1).rev() {
            let rods = self.layout.rods.iter().filter(|r| r.layer == level);
            chart.draw_series(rods.map(|r| {
                let [a, b] = r.ends();
                let y = -(level as f64);
                PathElement::new(
                    vec![(a[0], y, -a[1]), (b[0], y, -b[1])],
                    RGBColor(120, 120, 120).stroke_width(4),
                )
            }))?;
            for c in (0..n).filter(|&c| self.layout.contacts[c].layer_below == level) {
                let p = self.layout.contacts[c];
                let at = (p.x_mm, height(p.layer_above, p.layer_below), -p.y_mm);
                chart.draw_series([
                    Circle::new(at, DISC_PX, self.scale.rgb(self.peaks_n[c]).filled()),
                    Circle::new(at, DISC_PX, BLACK.stroke_width(1)),
                ])?;
            }
        }
        let (px, py) = chart.plotting_area().get_pixel_range();
        main.draw(&Text::new(
            "x, y to scale; layers in order, not to scale",
            (px.start, py.end - 4),
            TextStyle::from((FONT, TICK_FONT).into_font()).pos(Pos::new(HPos::Left, VPos::Bottom)),
        ))?;
        bar.draw(root, px.end, py)?;
        Ok(())
    }
}
