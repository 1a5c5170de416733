//! Colour scales chosen from a map's values, and the colour bar drawn beside the map: tick labels
//! right of the bar, the bar's two limits always labelled (log bars: every decade in between),
//! the label right beside the widest tick label, and any saturation stated on the bar (a "≥" or
//! "≤" on the limit's label and a triangular cap in the limit's colour).

use crate::typeset::Line;
use crate::{format_number, padded, ColorMap, DrawResult, FONT};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::ops::Range;

/// Tick-label font size \[px\].
const TICK_FONT_PX: f64 = 14.0;
/// Bar-label font size \[px\].
const LABEL_FONT_PX: f64 = 16.0;
/// Width of the coloured bar \[px\].
const BAR_WIDTH_PX: i32 = 22;
/// Length of a tick mark \[px\].
const TICK_LENGTH_PX: i32 = 5;
/// Gap between a tick mark and its label, and between the labels and the bar's label \[px\].
const GAP_PX: i32 = 4;
/// Height of a saturation cap (triangle beyond the bar's end) \[px\].
const CAP_PX: i32 = 14;
/// Space left of the bar (between the map and the bar) and right of the bar's label \[px\].
const MARGIN_PX: i32 = 18;

/// How values map to colours: limits in bar units (the value, or log10 of it on log scales) and
/// whether some values lie beyond them (drawn in the limit's colour, and said so on the bar).
#[derive(Debug, Clone)]
pub(crate) struct ColorScale {
    color_map: ColorMap,
    /// Lower limit, bar units.
    lo: f64,
    /// Upper limit, bar units.
    hi: f64,
    /// Log10 colours.
    log: bool,
    /// Some value lies above `hi` (saturated at the top).
    pub(crate) over: bool,
    /// Some value lies below `lo` (log scales: zeros and values more than the decades below).
    pub(crate) under: bool,
}

impl ColorScale {
    /// The scale of `values` (NaN allowed, ignored): up to the largest finite value, or up to the
    /// `saturate_quantile` quantile of the non-zero ones when given (robust to a few large
    /// values); linear from the smallest value, or log10 over `log_decades` decades below the top.
    pub(crate) fn of(
        values: &[f64],
        color_map: ColorMap,
        log_decades: Option<f64>,
        saturate_quantile: Option<f64>,
    ) -> ColorScale {
        let finite = values.iter().copied().filter(|v| v.is_finite());
        let (vmin, vmax) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
        let (vmin, vmax) = if vmin <= vmax {
            (vmin, vmax)
        } else {
            (0.0, 0.0)
        };
        let top = match saturate_quantile {
            Some(q) => {
                let mut nonzero: Vec<f64> = values
                    .iter()
                    .copied()
                    .filter(|v| v.is_finite() && *v != 0.0)
                    .collect();
                if nonzero.is_empty() {
                    vmax
                } else {
                    let k = ((nonzero.len() - 1) as f64 * q.clamp(0.0, 1.0)).round() as usize;
                    let (_, kth, _) = nonzero.select_nth_unstable_by(k, f64::total_cmp);
                    kth.min(vmax)
                }
            }
            None => vmax,
        };
        match log_decades {
            Some(decades) => {
                let top = if top > 0.0 { top } else { 1.0 };
                let floor = top * 10f64.powf(-decades.max(0.1));
                ColorScale {
                    color_map,
                    lo: floor.log10(),
                    hi: top.log10(),
                    log: true,
                    over: vmax > top,
                    under: values.iter().any(|v| v.is_finite() && *v < floor),
                }
            }
            None => {
                let (lo, hi) = padded(vmin, top);
                ColorScale {
                    color_map,
                    lo,
                    hi,
                    log: false,
                    over: vmax > hi,
                    under: false,
                }
            }
        }
    }

    /// Position of a value on the bar, 0 (bottom) to 1 (top), clamped; NaN stays NaN.
    fn position(&self, v: f64) -> f64 {
        let u = if self.log {
            if v > 0.0 {
                v.log10()
            } else {
                self.lo
            }
        } else {
            v
        };
        ((u - self.lo) / (self.hi - self.lo)).clamp(0.0, 1.0)
    }

    /// Colour of a value (NaN: the lowest colour).
    pub(crate) fn rgb(&self, v: f64) -> RGBColor {
        self.color_map.rgb(self.position(v))
    }

    /// The value at a bar limit (bar units → value).
    fn value(&self, u: f64) -> f64 {
        if self.log {
            10f64.powf(u)
        } else {
            u
        }
    }

    /// Candidate ticks (position 0..1, label): both limits, then the round values in between
    /// (linear: steps of 1, 2, 2.5 or 5 × 10^k, about six; log: decades, at most eight).
    fn candidate_ticks(&self) -> Vec<(f64, String)> {
        let span = self.hi - self.lo;
        let mut top = format_number(self.value(self.hi));
        if self.over {
            top = format!("≥ {top}");
        }
        let mut bottom = format_number(self.value(self.lo));
        if self.under {
            bottom = format!("≤ {bottom}");
        }
        let mut ticks = vec![(0.0, bottom), (1.0, top)];
        let inner: Vec<f64> = if self.log {
            let (first, last) = (self.lo.ceil() as i64, self.hi.floor() as i64);
            let stride = ((last - first + 1) as f64 / 8.0).ceil().max(1.0) as i64;
            (first..=last)
                .filter(|k| (k - first) % stride == 0)
                .map(|k| k as f64)
                .collect()
        } else {
            let raw = span / 6.0;
            let magnitude = 10f64.powf(raw.log10().floor());
            let step = [1.0, 2.0, 2.5, 5.0, 10.0]
                .iter()
                .map(|m| m * magnitude)
                .find(|s| *s >= raw)
                .unwrap_or(10.0 * magnitude);
            let (first, last) = (
                (self.lo / step).ceil() as i64,
                (self.hi / step).floor() as i64,
            );
            (first..=last).map(|k| k as f64 * step).collect()
        };
        ticks.extend(
            inner
                .into_iter()
                .map(|u| ((u - self.lo) / span, format_number(self.value(u)))),
        );
        ticks
    }

    /// Ticks of a bar `bar_px` pixels high: both limits, and the round values at least a label's
    /// height away from them and from each other (labels as printed: the output's text scale
    /// enlarges them beyond the layout's font size).
    fn ticks(&self, bar_px: f64) -> Vec<(f64, String)> {
        let min_gap = 1.3 * text_scale() * TICK_FONT_PX / bar_px.max(1.0);
        let mut kept: Vec<(f64, String)> = Vec::new();
        for (t, label) in self.candidate_ticks() {
            if kept.iter().all(|(k, _)| (k - t).abs() >= min_gap) {
                kept.push((t, label));
            }
        }
        kept
    }
}

use crate::output::text_scale;

/// A colour bar: a scale and its label (quantity and unit).
pub(crate) struct ColorBar<'a> {
    /// The scale drawn.
    pub(crate) scale: &'a ColorScale,
    /// Label, drawn rotated right of the tick labels.
    pub(crate) label: &'a str,
}

impl ColorBar<'_> {
    /// Widest tick label \[px\].
    fn tick_label_width(&self) -> i32 {
        let size = TICK_FONT_PX * text_scale();
        self.scale
            .candidate_ticks()
            .iter()
            .map(|(_, s)| Line::new(s, size, false).size().0.ceil() as i32)
            .max()
            .unwrap_or(0)
    }

    /// Width the bar, its ticks, tick labels and label take \[px\].
    pub(crate) fn width(&self) -> u32 {
        let label_height = Line::new(self.label, LABEL_FONT_PX * text_scale(), false)
            .size()
            .1
            .ceil() as i32;
        (MARGIN_PX
            + BAR_WIDTH_PX
            + TICK_LENGTH_PX
            + GAP_PX
            + self.tick_label_width()
            + 2 * GAP_PX
            + label_height
            + MARGIN_PX) as u32
    }

    /// Draws the bar on `root` with its left end at pixel `x`, spanning pixel rows `y` (the
    /// map's plotting area: saturation caps are drawn inside this span).
    pub(crate) fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        x: i32,
        y: Range<i32>,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let s = self.scale;
        let x0 = x + MARGIN_PX;
        let x1 = x0 + BAR_WIDTH_PX;
        let top = y.start + if s.over { CAP_PX } else { 0 };
        let bottom = y.end - if s.under { CAP_PX } else { 0 };
        let height = (bottom - top).max(1);
        // One rectangle per pixel row: the gradient is exact at the figure's resolution.
        for py in top..bottom {
            let t = (f64::from(bottom - py) - 0.5) / f64::from(height);
            root.draw(&Rectangle::new(
                [(x0, py), (x1, py + 1)],
                s.color_map.rgb(t).filled(),
            ))?;
        }
        let outline = BLACK.stroke_width(1);
        root.draw(&Rectangle::new([(x0, top), (x1, bottom)], outline))?;
        let cap = |base: i32, tip: i32, colour: RGBColor| -> DrawResult {
            let points = vec![(x0, base), ((x0 + x1) / 2, tip), (x1, base)];
            root.draw(&Polygon::new(points.clone(), colour.filled()))?;
            root.draw(&PathElement::new(points, outline))?;
            Ok(())
        };
        if s.over {
            cap(top, y.start, s.color_map.rgb(1.0))?;
        }
        if s.under {
            cap(bottom, y.end, s.color_map.rgb(0.0))?;
        }
        let style = TextStyle::from((FONT, TICK_FONT_PX).into_font())
            .pos(Pos::new(HPos::Left, VPos::Center));
        let label_x = x1 + TICK_LENGTH_PX + GAP_PX;
        for (t, label) in s.ticks(f64::from(height)) {
            let py = bottom - (t * f64::from(height)).round() as i32;
            root.draw(&PathElement::new(
                vec![(x1, py), (x1 + TICK_LENGTH_PX, py)],
                outline,
            ))?;
            root.draw(&Text::new(label, (label_x, py), style.clone()))?;
        }
        let (label_length, label_height) =
            Line::new(self.label, LABEL_FONT_PX * text_scale(), false).size();
        // A label longer than the bar (a small figure) is set smaller to fit its height.
        let fit = (f64::from(y.end - y.start) / f64::from(label_length)).min(1.0);
        let desc_x = label_x + self.tick_label_width() + 2 * GAP_PX + (label_height / 2.0) as i32;
        root.draw(&Text::new(
            self.label.to_string(),
            (desc_x, (y.start + y.end) / 2),
            TextStyle::from((FONT, LABEL_FONT_PX * fit).into_font())
                .transform(FontTransform::Rotate270)
                .pos(Pos::new(HPos::Center, VPos::Center)),
        ))?;
        Ok(())
    }
}
