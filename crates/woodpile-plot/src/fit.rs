//! Figures of a calibration: each fitted signal above its residual, and the correlation matrix
//! of the estimates.

use crate::lines::{bad, LinePlot, FINE};
use crate::{finite_range, padded, render, DrawResult, Figure, Result, FONT};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};

/// Line plots stacked top to bottom on one canvas, sharing its width.
struct Stacked(Vec<LinePlot>);

impl Figure for Stacked {
    fn size(&self) -> (u32, u32) {
        let w = self.0.iter().map(|p| p.size.0).max().unwrap_or(0);
        let h: u32 = self.0.iter().map(|p| p.size.1).sum();
        (w * FINE, h * FINE)
    }

    fn subdivision(&self) -> u32 {
        FINE
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        // The output may ask for another height: every panel keeps its share.
        let total: u32 = self.0.iter().map(|p| p.size.1).sum();
        let (_, height) = root.dim_in_pixel();
        let mut rest = root.clone();
        for (k, panel) in self.0.iter().enumerate() {
            if k + 1 == self.0.len() {
                panel.draw(&rest)?;
            } else {
                let h = (f64::from(panel.size.1) / f64::from(total) * f64::from(height)) as u32;
                let (top, below) = rest.split_vertically(h);
                panel.draw(&top)?;
                rest = below;
            }
        }
        Ok(())
    }
}

/// A fitted signal against time in ms: the measurement and the fitted model in the signal's
/// unit (`y_label`) above, the residual (model − measured) on its own axis below, over the rows
/// of `times_s`. Writes `stem.png` and `stem.svg`.
pub fn fit_signal(
    times_s: &[f64],
    measured: &[f64],
    model: &[f64],
    title: &str,
    y_label: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    if times_s.len() < 2 || measured.len() != times_s.len() || model.len() != times_s.len() {
        return Err(bad(
            title,
            "needs at least 2 times and one value of each curve per time",
        ));
    }
    let residual: Vec<f64> = model.iter().zip(measured).map(|(a, b)| a - b).collect();
    let x_range = (times_s[0] * 1e3, times_s[times_s.len() - 1] * 1e3);
    let points = |values: &[f64]| -> Vec<Vec<(f64, f64)>> {
        vec![times_s
            .iter()
            .zip(values)
            .map(|(t, v)| (t * 1e3, *v))
            .filter(|p| p.1.is_finite())
            .collect()]
    };
    let panel = |curves: &[(&str, &[f64])], title: &str, y_label: String, height, colour| {
        let (lo, hi) = finite_range(title, curves.iter().flat_map(|c| c.1.iter().copied()))?;
        let (y0, y1) = padded(lo, hi);
        let pad = 0.05 * (y1 - y0);
        Ok(LinePlot {
            title: title.to_string(),
            x_label: "time [ms]".into(),
            y_label,
            series: curves
                .iter()
                .map(|(label, v)| (label.to_string(), points(v)))
                .collect(),
            bands: Vec::new(),
            x_range,
            y_range: (y0 - pad, y1 + pad),
            log_y: false,
            markers: false,
            integer_x: false,
            zero_line: true,
            size: (1100, height),
            first_colour: colour,
        })
    };
    let signal = panel(
        &[("measured", measured), ("model", model)],
        title,
        y_label.to_string(),
        480,
        0,
    )?;
    // The unit of `y_label` ("contact_3_n [N]" → "residual [N]").
    let unit = y_label.rfind('[').map_or("", |i| &y_label[i..]);
    let residuals = panel(
        &[("residual (model − measured)", &residual)],
        "",
        format!("residual {unit}").trim_end().to_string(),
        260,
        2,
    )?;
    render(&Stacked(vec![signal, residuals]), stem)
}

/// The correlation matrix of a fit's estimates, one cell per pair coloured from −1 (blue)
/// through 0 (white) to +1 (red) with its value written in it; `names` in the matrix's order.
struct CorrelationMatrix<'a> {
    names: &'a [String],
    values: &'a [Vec<f64>],
    title: &'a str,
}

/// Blue → white → red for −1 → 0 → +1 (ColorBrewer RdBu's ends).
fn diverging(v: f64) -> RGBColor {
    let (end, t) = if v < 0.0 {
        ((33.0, 102.0, 172.0), -v)
    } else {
        ((178.0, 24.0, 43.0), v)
    };
    let t = if t.is_finite() { t.min(1.0) } else { 0.0 };
    let mix = |e: f64| (255.0 + t * (e - 255.0)).round() as u8;
    RGBColor(mix(end.0), mix(end.1), mix(end.2))
}

const CELL: u32 = 110;
const NAME_AREA: u32 = 300;

impl Figure for CorrelationMatrix<'_> {
    fn size(&self) -> (u32, u32) {
        let n = self.names.len() as u32;
        (NAME_AREA + 40 + n * CELL, 110 + n * CELL)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let n = self.names.len();
        let mut chart = ChartBuilder::on(root)
            .caption(self.title, (FONT, 22))
            .margin(15)
            .x_label_area_size(35)
            .y_label_area_size(NAME_AREA)
            .build_cartesian_2d(0.0..n as f64, n as f64..0.0)?;
        let label = |v: &f64| {
            let k = v.floor() as usize;
            if (v - v.floor() - 0.5).abs() < 1e-9 && k < n {
                format!("({}) {}", k + 1, self.names[k])
            } else {
                String::new()
            }
        };
        let number = |v: &f64| {
            let k = v.floor() as usize;
            if (v - v.floor() - 0.5).abs() < 1e-9 && k < n {
                format!("({})", k + 1)
            } else {
                String::new()
            }
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(2 * n + 1)
            .y_labels(2 * n + 1)
            .x_label_formatter(&number)
            .y_label_formatter(&label)
            .label_style((FONT, 15))
            .draw()?;
        let text =
            TextStyle::from((FONT, 20).into_font()).pos(Pos::new(HPos::Center, VPos::Center));
        for (i, row) in self.values.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                let (x, y) = (j as f64, i as f64);
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(x, y), (x + 1.0, y + 1.0)],
                    diverging(v).filled(),
                )))?;
                let shown = if v.is_finite() {
                    format!("{v:+.2}")
                } else {
                    "–".into()
                };
                chart.draw_series(std::iter::once(Text::new(
                    shown,
                    (x + 0.5, y + 0.5),
                    text.clone(),
                )))?;
            }
        }
        Ok(())
    }
}

/// The correlation matrix of a fit's estimates (`values[i][j]`, `names` in the same order) as a
/// grid of cells coloured blue (−1) through white (0) to red (+1), each with its value. Writes
/// `stem.png` and `stem.svg`.
pub fn correlation_matrix(
    names: &[String],
    values: &[Vec<f64>],
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
    let n = names.len();
    if n == 0 || values.len() != n || values.iter().any(|r| r.len() != n) {
        return Err(bad(title, "needs a square matrix with one name per row"));
    }
    render(
        &CorrelationMatrix {
            names,
            values,
            title,
        },
        stem,
    )
}
