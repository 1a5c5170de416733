//! Bar charts of Sobol' indices: first-order and total index of each parameter side by side,
//! each with its confidence interval as a whisker.

use crate::{format_number, render, series_color, DrawResult, Figure, PlotError, Result, FONT};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Drawing units per layout unit (as the line plots).
const FINE: u32 = 4;

/// One parameter's bars: its name, (S1, S1 half-width), (ST, ST half-width).
#[derive(Debug, Clone, PartialEq)]
pub struct IndexBars {
    /// Parameter name.
    pub parameter: String,
    /// First-order index and the half-width of its interval.
    pub first_order: (f64, f64),
    /// Total index and the half-width of its interval.
    pub total: (f64, f64),
}

struct Bars {
    title: String,
    bars: Vec<IndexBars>,
    y_range: (f64, f64),
}

/// The S1 and ST bars of each parameter with their confidence intervals.
/// Writes `stem.png` and `stem.svg`.
pub fn sobol_indices(bars: &[IndexBars], title: &str, stem: &Path) -> Result<Vec<PathBuf>> {
    if bars.is_empty() {
        return Err(PlotError::BadData {
            what: title.to_string(),
            reason: "no parameter".into(),
        });
    }
    let values = bars.iter().flat_map(|b| {
        [
            b.first_order.0 - b.first_order.1,
            b.first_order.0 + b.first_order.1,
            b.total.0 - b.total.1,
            b.total.0 + b.total.1,
        ]
    });
    let (lo, hi) = crate::finite_range(title, values)?;
    render(
        &Bars {
            title: title.to_string(),
            bars: bars.to_vec(),
            // Headroom above for the legend.
            y_range: (lo.min(0.0) - 0.02, hi.max(1.0) * 1.2),
        },
        stem,
    )
}

impl Figure for Bars {
    fn size(&self) -> (u32, u32) {
        (1000 * FINE, 600 * FINE)
    }

    fn subdivision(&self) -> u32 {
        FINE
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let n = self.bars.len();
        let names: Vec<&str> = self.bars.iter().map(|b| b.parameter.as_str()).collect();
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 22 * FINE))
            .margin(15 * FINE)
            .x_label_area_size(50 * FINE)
            .y_label_area_size(85 * FINE)
            .build_cartesian_2d(-0.5..n as f64 - 0.5, self.y_range.0..self.y_range.1)?;
        chart
            .configure_mesh()
            .x_labels(n)
            .x_label_formatter(&|v| {
                let i = v.round();
                if (v - i).abs() < 1e-6 && i >= 0.0 {
                    names
                        .get(i as usize)
                        .map_or(String::new(), |s| s.to_string())
                } else {
                    String::new()
                }
            })
            .y_desc("Sobol' index (S1 first order, ST total)")
            .y_label_formatter(&|v| format_number(*v))
            .label_style((FONT, 15 * FINE))
            .axis_desc_style((FONT, 17 * FINE))
            .set_all_tick_mark_size(5 * FINE)
            .axis_style(BLACK.stroke_width(FINE))
            .bold_line_style(BLACK.mix(0.2).stroke_width(FINE))
            .light_line_style(WHITE.mix(0.0))
            .disable_x_mesh()
            .draw()?;
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(-0.5, 0.0), (n as f64 - 0.5, 0.0)],
            BLACK.stroke_width(FINE),
        )))?;
        for (k, label) in ["S1", "ST"].into_iter().enumerate() {
            let colour = series_color(k);
            let offset = if k == 0 { -0.2 } else { 0.2 };
            let pick = |b: &IndexBars| if k == 0 { b.first_order } else { b.total };
            chart
                .draw_series(self.bars.iter().enumerate().map(|(i, b)| {
                    let x = i as f64 + offset;
                    Rectangle::new([(x - 0.17, 0.0), (x + 0.17, pick(b).0)], colour.filled())
                }))?
                .label(label)
                .legend(move |(x, y)| {
                    Rectangle::new(
                        [
                            (x, y - 6 * FINE as i32),
                            (x + 18 * FINE as i32, y + 6 * FINE as i32),
                        ],
                        colour.filled(),
                    )
                });
            // Whiskers: the interval v ± w, capped.
            for (i, b) in self.bars.iter().enumerate() {
                let (v, w) = pick(b);
                let x = i as f64 + offset;
                let style = BLACK.stroke_width(FINE);
                chart.draw_series([
                    PathElement::new(vec![(x, v - w), (x, v + w)], style),
                    PathElement::new(vec![(x - 0.06, v - w), (x + 0.06, v - w)], style),
                    PathElement::new(vec![(x - 0.06, v + w), (x + 0.06, v + w)], style),
                ])?;
            }
        }
        chart
            .configure_series_labels()
            .label_font((FONT, 15 * FINE))
            .legend_area_size(26 * FINE)
            .margin(8 * FINE)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK.mix(0.4))
            .position(SeriesLabelPosition::UpperRight)
            .draw()?;
        Ok(())
    }
}
