//! A picture of a chain: rods to scale, top to bottom (paper Fig. 5 d, e, right panels).

use crate::{render, ColorMap, DrawResult, Figure, PlotError, Result, FONT};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};
use woodpile::{Body, Chain, Wall};

struct ChainPicture<'a> {
    chain: &'a Chain,
    title: String,
    /// Extent of every element along the picture's x axis [mm] (rod length, sphere diameter).
    widths_mm: Vec<f64>,
}

/// Draws the elements of `chain` top to bottom as bars whose width is the rod length (spheres as
/// their diameter), coloured by length, labelled with the length and the layer index; the wall
/// at the bottom.
pub fn chain_picture(chain: &Chain, title: &str, stem: &Path) -> Result<Vec<PathBuf>> {
    let widths_mm: Vec<f64> = chain
        .elements()
        .iter()
        .map(|e| match e.body {
            Body::Rod { length_m, .. } => length_m * 1e3,
            Body::Sphere { diameter_m } => diameter_m * 1e3,
        })
        .collect();
    if widths_mm.iter().any(|w| !w.is_finite() || *w <= 0.0) {
        return Err(PlotError::BadData {
            what: title.to_string(),
            reason: "an element has no positive size".to_string(),
        });
    }
    render(
        &ChainPicture {
            chain,
            title: title.to_string(),
            widths_mm,
        },
        stem,
    )
}

impl Figure for ChainPicture<'_> {
    fn size(&self) -> (u32, u32) {
        let n = self.widths_mm.len() as u32;
        (620, 150 + 30 * (n + 2))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let n = self.widths_mm.len();
        let widest = self.widths_mm.iter().copied().fold(0.0, f64::max);
        let half = 0.5 * widest.max(20.0) + 30.0;
        let (min_w, max_w) = self
            .widths_mm
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(a, b), w| (a.min(*w), b.max(*w)));
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 20))
            .margin(15)
            .x_label_area_size(55)
            .build_cartesian_2d(-half..half, -(n as f64) - 1.2..0.8)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_y_axis()
            .x_desc("rod length, to scale [mm]")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 15))
            .draw()?;
        let text = |s: String, x: f64, y: f64, anchor: (HPos, VPos)| {
            Text::new(
                s,
                (x, y),
                TextStyle::from((FONT, 15).into_font()).pos(Pos::new(anchor.0, anchor.1)),
            )
        };
        chart.draw_series(std::iter::once(text(
            "layer".to_string(),
            -half + 2.0,
            0.1,
            (HPos::Left, VPos::Center),
        )))?;
        chart.draw_series(std::iter::once(text(
            "striker / load ↓".to_string(),
            0.0,
            0.1,
            (HPos::Center, VPos::Center),
        )))?;
        for (i, (&w, e)) in self.widths_mm.iter().zip(self.chain.elements()).enumerate() {
            let y = -(i as f64) - 1.0;
            let t = if max_w > min_w {
                (w - min_w) / (max_w - min_w)
            } else {
                0.5
            };
            let colour = ColorMap::Viridis.rgb(0.15 + 0.7 * t);
            chart.draw_series(std::iter::once(Rectangle::new(
                [(-0.5 * w, y - 0.32), (0.5 * w, y + 0.32)],
                colour.filled(),
            )))?;
            chart.draw_series(std::iter::once(Rectangle::new(
                [(-0.5 * w, y - 0.32), (0.5 * w, y + 0.32)],
                BLACK.mix(0.6).stroke_width(1),
            )))?;
            let label = match e.body {
                Body::Rod { .. } => format!("{w:.0} mm"),
                Body::Sphere { .. } => format!("sphere {w:.0} mm"),
            };
            chart.draw_series([
                text(label, 0.5 * w + 2.0, y, (HPos::Left, VPos::Center)),
                text(
                    format!("{}", i + 1),
                    -half + 2.0,
                    y,
                    (HPos::Left, VPos::Center),
                ),
            ])?;
        }
        let wall_y = -(n as f64) - 0.85;
        if !matches!(self.chain.wall(), Wall::Free) {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(-half * 0.8, wall_y - 0.35), (half * 0.8, wall_y + 0.21)],
                RGBColor(90, 90, 90).filled(),
            )))?;
            chart.draw_series(std::iter::once(Text::new(
                "wall / force sensor",
                (0.0, wall_y - 0.07),
                TextStyle::from((FONT, 14).into_font())
                    .color(&WHITE)
                    .pos(Pos::new(HPos::Center, VPos::Center)),
            )))?;
        }
        Ok(())
    }
}
