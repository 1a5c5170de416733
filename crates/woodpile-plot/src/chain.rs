//! A picture of a chain: rods to scale, top to bottom (paper Fig. 5 d, e, right panels).

use crate::{render, ColorMap, DrawResult, Figure, PlotError, Result, FONT};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};
use woodpile::{Body, Chain, Wall};

struct ChainPicture<'a> {
    chain: &'a Chain,
    title: String,
    /// What drives the top (`striker`, `load`, `actuator`), for the label above the chain.
    contact0: String,
    /// Extent of every element along the picture's x axis [mm] (rod length, sphere diameter).
    widths_mm: Vec<f64>,
}

/// Draws the elements of `chain` top to bottom as bars whose width is the rod length (spheres as
/// their diameter), coloured by length, labelled with the length and the layer index; the wall
/// at the bottom.
///
/// Chains of more than 40 elements are summarised, so the picture's size is bounded whatever
/// their length (950 × 840 px): the first and last 10 elements to scale with an ellipsis
/// between, and beside them a strip of every element's length (top to bottom, groups of
/// elements drawn as the range of their lengths beyond 350), as the title states. `contact0`
/// names what drives the top, as in [`crate::force_map`].
pub fn chain_picture(
    chain: &Chain,
    title: &str,
    contact0: Option<&str>,
    stem: &Path,
) -> Result<Vec<PathBuf>> {
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
            contact0: crate::heatmap::contact0_name(contact0)
                .replace(", ", " / ")
                .replace(" or ", " / "),
            widths_mm,
        },
        stem,
    )
}

/// Chains longer than this are summarised: the first and last [`SHOWN_AT_EACH_END`] elements
/// to scale, and a strip of every element's length beside them.
const SUMMARISED_ABOVE: usize = 40;

/// Elements drawn to scale at each end of a summarised chain.
const SHOWN_AT_EACH_END: usize = 10;

/// Height of one element's row \[px\].
const ROW_PX: u32 = 30;

/// Width of the rods' panel \[px\].
const RODS_PANEL_PX: u32 = 620;

/// Width of the strip's panel of a summarised chain \[px\].
const STRIP_PANEL_PX: u32 = 330;

/// Most rows of the strip (at least 2 px each): longer chains are grouped, each group drawn as
/// the range of its elements' lengths.
const STRIP_MAX_ROWS: usize = 350;

impl ChainPicture<'_> {
    /// Whether the chain is summarised (too long to draw every element).
    fn summarised(&self) -> bool {
        self.widths_mm.len() > SUMMARISED_ABOVE
    }

    /// The rows of the rods' panel, top to bottom: an element's index, or None for the ellipsis.
    fn shown(&self) -> Vec<Option<usize>> {
        let n = self.widths_mm.len();
        if self.summarised() {
            (0..SHOWN_AT_EACH_END)
                .map(Some)
                .chain(std::iter::once(None))
                .chain((n - SHOWN_AT_EACH_END..n).map(Some))
                .collect()
        } else {
            (0..n).map(Some).collect()
        }
    }

    /// Colour of an element of width `w` \[mm\]: viridis over the chain's range of widths.
    fn colour(&self, w: f64) -> RGBColor {
        let (min_w, max_w) = self.width_range();
        let t = if max_w > min_w {
            (w - min_w) / (max_w - min_w)
        } else {
            0.5
        };
        ColorMap::Viridis.rgb(0.15 + 0.7 * t)
    }

    /// Smallest and largest element width \[mm\].
    fn width_range(&self) -> (f64, f64) {
        self.widths_mm
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(a, b), w| (a.min(*w), b.max(*w)))
    }

    /// The rods (or the first and last ones and an ellipsis) to scale, the wall at the bottom.
    fn draw_rods<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        caption: Option<&str>,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let shown = self.shown();
        let n = self.widths_mm.len();
        let rows = shown.len();
        let widest = self.widths_mm.iter().copied().fold(0.0, f64::max);
        let half = 0.5 * widest.max(20.0) + 30.0;
        let mut builder = ChartBuilder::on(area);
        if let Some(caption) = caption {
            builder.caption(caption, (FONT, 20));
        }
        let mut chart = builder
            .margin(15)
            .x_label_area_size(55)
            .build_cartesian_2d(-half..half, -(rows as f64) - 1.2..0.8)?;
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
            format!("{} ↓", self.contact0),
            0.0,
            0.1,
            (HPos::Center, VPos::Center),
        )))?;
        let elements = self.chain.elements();
        for (slot, element) in shown.iter().enumerate() {
            let y = -(slot as f64) - 1.0;
            let Some(i) = *element else {
                let hidden = n - 2 * SHOWN_AT_EACH_END;
                chart.draw_series([
                    text("⋮".to_string(), -half + 8.0, y, (HPos::Left, VPos::Center)),
                    text(
                        format!("⋮  {hidden} more elements (strip, right)"),
                        0.0,
                        y,
                        (HPos::Center, VPos::Center),
                    ),
                ])?;
                continue;
            };
            let w = self.widths_mm[i];
            chart.draw_series(std::iter::once(Rectangle::new(
                [(-0.5 * w, y - 0.32), (0.5 * w, y + 0.32)],
                self.colour(w).filled(),
            )))?;
            chart.draw_series(std::iter::once(Rectangle::new(
                [(-0.5 * w, y - 0.32), (0.5 * w, y + 0.32)],
                BLACK.mix(0.6).stroke_width(1),
            )))?;
            let label = match elements[i].body {
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
        if !matches!(self.chain.wall(), Wall::Free) {
            draw_wall(&mut chart, half, -(rows as f64) - 0.85)?;
        }
        Ok(())
    }

    /// Every element's length, top to bottom: one bar per element, or per group of elements
    /// (spanning their shortest to longest, coloured by their mean) when the chain is longer
    /// than the strip has rows.
    fn draw_strip<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let n = self.widths_mm.len();
        let (_, max_w) = self.width_range();
        let k = n.min(STRIP_MAX_ROWS);
        let per_row = n.div_ceil(k);
        // The y axis is the long one: it carries what a row is.
        let y_desc = if per_row > 1 {
            format!("element, 1 = top (a row: the range of ≤ {per_row})")
        } else {
            "element, 1 = top".to_string()
        };
        // Label areas from the widest tick label and the title's height at the printed size.
        let ts = crate::output::text_scale();
        let widest = crate::typeset::Line::new(&n.to_string(), 14.0 * ts, false)
            .size()
            .0;
        let desc_height = crate::typeset::Line::new(&y_desc, 16.0 * ts, false)
            .size()
            .1;
        let mut chart = ChartBuilder::on(area)
            .margin(15)
            .margin_top(45)
            .x_label_area_size(40.0 * ts)
            .y_label_area_size((widest + desc_height) as f64 + 20.0)
            .build_cartesian_2d(0.0..1.08 * max_w, -(n as f64)..0.0)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("length [mm]")
            .x_labels(5)
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_desc(y_desc)
            .y_label_formatter(&|y| {
                let i = -y;
                if (i - i.round()).abs() > 1e-6 {
                    String::new()
                } else {
                    format!("{}", (i.round() as usize).clamp(1, n))
                }
            })
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 15))
            .draw()?;
        let bar = 0.004 * max_w;
        chart.draw_series((0..k).map(|g| {
            let (e0, e1) = (g * n / k, (g + 1) * n / k);
            let group = &self.widths_mm[e0..e1];
            let (lo, hi) = group
                .iter()
                .fold((f64::INFINITY, 0.0_f64), |(a, b), w| (a.min(*w), b.max(*w)));
            let mean = group.iter().sum::<f64>() / group.len() as f64;
            Rectangle::new(
                [(lo - bar, -(e1 as f64)), (hi + bar, -(e0 as f64))],
                self.colour(mean).filled(),
            )
        }))?;
        Ok(())
    }
}

impl Figure for ChainPicture<'_> {
    fn size(&self) -> (u32, u32) {
        let rows = self.shown().len() as u32;
        let width = if self.summarised() {
            RODS_PANEL_PX + STRIP_PANEL_PX
        } else {
            RODS_PANEL_PX
        };
        (width, 150 + ROW_PX * (rows + 2))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        if !self.summarised() {
            return self.draw_rods(root, Some(&self.title));
        }
        let n = self.widths_mm.len();
        let caption = format!(
            "{}: first and last {SHOWN_AT_EACH_END} of {n} elements to scale, strip: all lengths",
            self.title
        );
        let body = root.titled(&caption, (FONT, 17))?;
        let (rods, strip) = body.split_horizontally(RODS_PANEL_PX);
        self.draw_rods(&rods, None)?;
        self.draw_strip(&strip)
    }
}

/// The wall (the force sensor) under the rods: a bar `2 × 0.8 half` wide, centred at `wall_y`.
fn draw_wall<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    half: f64,
    wall_y: f64,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
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
    Ok(())
}
