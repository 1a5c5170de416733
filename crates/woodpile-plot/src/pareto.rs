//! Figures of a Pareto front (NSGA-II): the front as a scatter (two objectives) or pairwise
//! panels (three or more) with reference designs marked, and the front's designs as rods to
//! scale, side by side.

use crate::{
    finite_range, format_number, render, ColorMap, DrawResult, Figure, PlotError, Result, FONT,
};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};

/// An objective's axis: its label (with the unit shown) and the factor from its SI values to
/// the values drawn (kg → g, m → mm, Pa → MPa).
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectiveAxis {
    /// Axis label.
    pub label: String,
    /// Drawn value = SI value × scale.
    pub scale: f64,
}

impl ObjectiveAxis {
    /// The axis of an objective from its name and SI unit.
    pub fn new(name: &str, unit: &str) -> Self {
        let (shown, scale) = match unit {
            "kg" => ("g", 1e3),
            "m" => ("mm", 1e3),
            "Pa" => ("MPa", 1e-6),
            other => (other, 1.0),
        };
        ObjectiveAxis {
            label: crate::dirs::objective_label(name, shown),
            scale,
        }
    }
}

/// A design marked on the front's figure: its name, its objective values (SI), whether it
/// meets the constraints (an infeasible one is drawn hollow) and whether it is the design the
/// front is compared with (a red triangle; others are grey crosses).
#[derive(Debug, Clone, PartialEq)]
pub struct MarkedDesign {
    /// Name written beside it.
    pub name: String,
    /// One value per objective, SI units.
    pub values: Vec<f64>,
    /// Drawn filled when true.
    pub feasible: bool,
    /// Drawn as a red triangle when true.
    pub highlight: bool,
}

struct FrontFigure<'a> {
    axes: &'a [ObjectiveAxis],
    front: &'a [Vec<f64>],
    marked: &'a [MarkedDesign],
    title: String,
    pairs: Vec<(usize, usize)>,
}

/// Layout size of one panel.
const PANEL: (u32, u32) = (900, 620);

impl FrontFigure<'_> {
    fn columns(&self) -> usize {
        self.pairs.len().min(2)
    }

    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        (i, j): (usize, usize),
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let (ax, ay) = (&self.axes[i], &self.axes[j]);
        let all = || {
            self.front
                .iter()
                .chain(self.marked.iter().map(|m| &m.values))
        };
        let range = |k: usize, scale: f64| {
            let (lo, hi) = finite_range("front", all().map(|v| v[k] * scale)).unwrap_or((0.0, 1.0));
            let pad = if hi > lo {
                0.06 * (hi - lo)
            } else {
                0.5 * lo.abs().max(1.0)
            };
            (lo - pad, hi + pad)
        };
        let (x0, x1) = range(i, ax.scale);
        let (y0, y1) = range(j, ay.scale);
        let mut chart = ChartBuilder::on(area)
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(85)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc(&ax.label)
            .y_desc(&ay.label)
            .x_label_formatter(&|v| format_number(*v))
            .y_label_formatter(&|v| format_number(*v))
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17))
            .bold_line_style(BLACK.mix(0.2))
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        let blue = crate::series_color(0);
        let mut points: Vec<(f64, f64)> = self
            .front
            .iter()
            .map(|v| (v[i] * ax.scale, v[j] * ay.scale))
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        if self.axes.len() == 2 {
            chart.draw_series(LineSeries::new(points.iter().copied(), blue.mix(0.5)))?;
        }
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 5, blue.filled())))?;
        let label = TextStyle::from((FONT, 14).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
        for (k, m) in self.marked.iter().enumerate() {
            let paper = m.highlight;
            let colour = if paper {
                crate::series_color(3)
            } else {
                RGBColor(80, 80, 80)
            };
            let p = (m.values[i] * ax.scale, m.values[j] * ay.scale);
            if !(p.0.is_finite() && p.1.is_finite()) {
                continue;
            }
            let style = if m.feasible {
                colour.filled()
            } else {
                colour.stroke_width(2)
            };
            if paper {
                chart.draw_series(std::iter::once(TriangleMarker::new(p, 9, style)))?;
            } else {
                chart.draw_series(std::iter::once(Cross::new(p, 6, colour.stroke_width(2))))?;
            }
            // Alternate the side of the label a little so that neighbours stay legible; names
            // of points in the right third of the panel go to their left, inside the frame.
            let dy = if k % 2 == 0 { -10 } else { 10 };
            let (dx, dy, style) = if paper {
                // Above the point: a highlighted design usually sits next to the front.
                (
                    0,
                    -14,
                    label.clone().pos(Pos::new(HPos::Left, VPos::Bottom)),
                )
            } else if p.0 > x0 + 0.66 * (x1 - x0) {
                (
                    -10,
                    dy,
                    label.clone().pos(Pos::new(HPos::Right, VPos::Center)),
                )
            } else {
                (10, dy, label.clone())
            };
            chart.draw_series(std::iter::once(
                EmptyElement::at(p) + Text::new(m.name.clone(), (dx, dy), style),
            ))?;
        }
        Ok(())
    }
}

impl Figure for FrontFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let cols = self.columns() as u32;
        let rows = self.pairs.len().div_ceil(self.columns()) as u32;
        (PANEL.0 * cols, PANEL.1 * rows + 50)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let body = root.titled(&self.title, (FONT, 22))?;
        let cols = self.columns();
        let rows = self.pairs.len().div_ceil(cols);
        let panels = body.split_evenly((rows, cols));
        for (pair, area) in self.pairs.iter().zip(&panels) {
            self.panel(area, *pair)?;
        }
        Ok(())
    }
}

/// The front: two objectives as a scatter joined in order of the first (blue), three or more
/// as one panel per pair; `marked` designs drawn as crosses (highlighted ones as red triangles),
/// hollow where they break a constraint, named beside them. Writes `stem.png` and `stem.svg`.
pub fn pareto_front(
    axes: &[ObjectiveAxis],
    front: &[Vec<f64>],
    marked: &[MarkedDesign],
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    let m = axes.len();
    let bad = |reason: String| PlotError::BadData {
        what: title.to_string(),
        reason,
    };
    if m < 2 {
        return Err(bad(format!("{m} objective: a front needs two or more")));
    }
    if front.is_empty() {
        return Err(bad("no design on the front".into()));
    }
    if let Some(v) = front
        .iter()
        .chain(marked.iter().map(|d| &d.values))
        .find(|v| v.len() != m)
    {
        return Err(bad(format!(
            "a design has {} values for {m} objectives",
            v.len()
        )));
    }
    // A value that is not finite would be drawn nowhere, or stretch the axes to nothing.
    for (k, v) in front.iter().enumerate() {
        if let Some(j) = v.iter().position(|x| !x.is_finite()) {
            return Err(bad(format!(
                "design {} of the front has {} = {}: every value must be a finite number",
                k + 1,
                axes[j].label,
                v[j]
            )));
        }
    }
    let pairs = (0..m)
        .flat_map(|i| (i + 1..m).map(move |j| (i, j)))
        .collect();
    render(
        &FrontFigure {
            axes,
            front,
            marked,
            title: title.to_string(),
            pairs,
        },
        stem,
    )
}

/// A design of the front drawn as rods: its caption (e.g. its objective values) and the length
/// of each layer's rod, top to bottom \[mm\].
#[derive(Debug, Clone, PartialEq)]
pub struct FrontDesign {
    /// Lines written under the column.
    pub caption: Vec<String>,
    /// Rod lengths (a sphere's diameter) top to bottom \[mm\].
    pub widths_mm: Vec<f64>,
}

struct DesignsFigure<'a> {
    designs: &'a [FrontDesign],
    title: String,
}

/// Layout width of one design's column and height of the rods' panel.
const COLUMN: u32 = 110;
const RODS_HEIGHT: u32 = 640;

impl Figure for DesignsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (COLUMN * self.designs.len() as u32 + 80, RODS_HEIGHT + 170)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let body = root.titled(&self.title, (FONT, 20))?;
        let layers = self
            .designs
            .iter()
            .map(|d| d.widths_mm.len())
            .max()
            .unwrap_or(1);
        let all = self
            .designs
            .iter()
            .flat_map(|d| d.widths_mm.iter().copied());
        let (lo, hi) = all.fold((f64::INFINITY, 0.0_f64), |(a, b), w| (a.min(w), b.max(w)));
        let row = (RODS_HEIGHT - 20) as f64 / layers as f64;
        let gap = (row * 0.15).clamp(1.0, 4.0);
        let caption =
            TextStyle::from((FONT, 13).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
        let small =
            TextStyle::from((FONT, 11).into_font()).pos(Pos::new(HPos::Center, VPos::Center));
        for (k, d) in self.designs.iter().enumerate() {
            let cx = 40 + COLUMN as i32 * k as i32 + COLUMN as i32 / 2;
            for (l, &w) in d.widths_mm.iter().enumerate() {
                let half = ((w / hi) * (COLUMN as f64 - 14.0) / 2.0).max(1.0) as i32;
                let y0 = 10 + (l as f64 * row) as i32;
                let y1 = 10 + ((l + 1) as f64 * row - gap) as i32;
                let t = if hi > lo { (w - lo) / (hi - lo) } else { 0.5 };
                let colour = ColorMap::Viridis.rgb(0.15 + 0.7 * t);
                body.draw(&Rectangle::new(
                    [(cx - half, y0), (cx + half, y1)],
                    colour.filled(),
                ))?;
                if row >= 14.0 {
                    let text = format_number(w);
                    body.draw(&Text::new(
                        text,
                        (cx, (y0 + y1) / 2),
                        small.clone().color(&WHITE),
                    ))?;
                }
            }
            let wall = 10 + RODS_HEIGHT as i32 - 14;
            body.draw(&Rectangle::new(
                [
                    (cx - COLUMN as i32 / 2 + 6, wall),
                    (cx + COLUMN as i32 / 2 - 6, wall + 6),
                ],
                BLACK.mix(0.6).filled(),
            ))?;
            for (n, line) in d.caption.iter().enumerate() {
                body.draw(&Text::new(
                    line.clone(),
                    (cx, wall + 14 + 18 * n as i32),
                    caption.clone(),
                ))?;
            }
        }
        Ok(())
    }
}

/// The front's designs side by side, each a column of rods to scale (width ∝ length, coloured
/// by length, the length written where a row is tall enough), top to bottom, over the wall,
/// with its caption under it. Writes `stem.png` and `stem.svg`.
pub fn front_designs(designs: &[FrontDesign], title: &str, stem: &Path) -> Result<Vec<PathBuf>> {
    let bad = |reason: &str| PlotError::BadData {
        what: title.to_string(),
        reason: reason.to_string(),
    };
    if designs.is_empty() {
        return Err(bad("no design"));
    }
    if designs
        .iter()
        .flat_map(|d| &d.widths_mm)
        .any(|w| !w.is_finite() || *w <= 0.0)
    {
        return Err(bad("an element has no positive size"));
    }
    render(
        &DesignsFigure {
            designs,
            title: title.to_string(),
        },
        stem,
    )
}
