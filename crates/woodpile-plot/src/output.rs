//! How figures are written: the file formats, the printed size and the bitmap resolution.
//!
//! Every figure lays itself out in *logical units*: a canvas of its own size (1100 × 620 for the
//! maps, 1100 × 600 for the line plots, 1000 × 600 for the GA convergence, 620 wide for the chain
//! picture), text 14–22 units high; the line plots subdivide each unit in 4 (a 4400 × 2400
//! canvas, every length × 4) so that their curves are not rounded to the layout grid. Writing
//! maps logical units to paper:
//!
//! - a logical unit has one printed length, [`DEFAULT_WIDTH_IN`] / [`REFERENCE_WIDTH`] (the
//!   1100-unit-wide figures print 7 in, 178 mm, a double-column journal figure; narrower
//!   figures print narrower in proportion), so text has one printed size in every figure at
//!   every size; with [`Output::width_in`] or [`Output::height_in`] each figure prints at exactly
//!   that width or height and lays itself out on a canvas of that many units (a 3.5 in single
//!   column: half as wide, same text), keeping its aspect ratio unless both are given;
//! - the PNG is drawn at [`Output::dpi`] through a scaling backend (every coordinate, stroke
//!   width and font size multiplied by the pixels per unit), so it is sharp at its resolution
//!   rather than an enlarged small bitmap, and it carries that resolution in its `pHYs` chunk;
//! - the SVG keeps logical units in its `viewBox` and declares the printed size in inches in its
//!   `width` and `height`, so it prints at the stated size;
//! - text is enlarged by [`Output::text_scale`] relative to the canvas (the figures' layouts
//!   were made for screens, where 15-unit text on a 1100-unit canvas reads well; printed 7 in
//!   wide it would be 5.9 pt). With the defaults (7 in, text scale 1.3) the em size of the text
//!   prints at 7.2 pt (colour-bar ticks, 14 units), 7.7 pt (tick labels and legends, 15), 8.7 pt
//!   (axis titles, 17) and 11.3 pt (figure titles, 22); the figures' font sizes are the
//!   ascent-to-descent height of DejaVu Sans, 1.164 em (typeset::em_per_size). A line of text
//!   that would run off the canvas at that size (a long title) is set smaller to fit.
//!
//! PDF: plotters has no PDF backend, and a PDF stack would outweigh the rest of the crate;
//! convert the SVG (`rsvg-convert -f pdf -o fig.pdf fig.svg`, Inkscape, or a browser's print).
//!
//! The plain figure functions ([`crate::force_map`], …) write with the output in effect on the
//! calling thread: [`Output::default`], or the one given to [`with_output`] around the call.

use crate::typeset::{Line, Typeset};
use crate::{DrawFailure, Figure, PlotError, Result};
use plotters::prelude::*;
use plotters_backend::{
    text_anchor::{HPos, Pos},
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontFamily,
    FontStyle, FontTransform,
};
use std::cell::RefCell;
use std::path::{Path, PathBuf};

/// Logical width of the full-width figures (maps, histories, spectra).
pub const REFERENCE_WIDTH: u32 = 1100;
/// Printed width of a [`REFERENCE_WIDTH`]-wide figure by default \[in\]: 7 in (178 mm), the
/// width of a double-column journal figure.
pub const DEFAULT_WIDTH_IN: f64 = 7.0;
/// Default bitmap resolution \[dots per inch\]: the usual minimum for journal bitmaps.
pub const DEFAULT_DPI: f64 = 300.0;
/// Default text enlargement (see the module's documentation for the printed sizes it gives).
pub const DEFAULT_TEXT_SCALE: f64 = 1.3;
/// Largest bitmap side accepted \[px\] (a 16384 × 16384 RGB buffer is 805 MB).
pub const MAX_PIXELS_PER_SIDE: f64 = 16384.0;

/// A file format figures are written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// PNG bitmap at [`Output::dpi`].
    Png,
    /// SVG vector drawing with its printed size declared.
    Svg,
}

impl Format {
    /// The names accepted by [`Format::parse_list`].
    pub const NAMES: &'static str = "png, svg";

    /// The file extension (and the format's name).
    pub fn ext(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Svg => "svg",
        }
    }

    /// Parses a comma-separated list (`png,svg`, `svg`); duplicates are dropped. The error
    /// says what is valid (and, for `pdf`, how to get one).
    pub fn parse_list(list: &str) -> std::result::Result<Vec<Format>, String> {
        let mut formats = Vec::new();
        for name in list.split(',').map(str::trim) {
            let f = match name.to_ascii_lowercase().as_str() {
                "png" => Format::Png,
                "svg" => Format::Svg,
                "pdf" | "eps" | "ps" => {
                    return Err(format!(
                        "{name} is not written (plotters has no {name} backend); valid: {}. \
                         Convert the SVG, e.g. `rsvg-convert -f pdf -o fig.pdf fig.svg` or Inkscape",
                        Format::NAMES
                    ))
                }
                _ => {
                    return Err(format!(
                        "unknown format `{name}`; valid: {} (comma-separated)",
                        Format::NAMES
                    ))
                }
            };
            if !formats.contains(&f) {
                formats.push(f);
            }
        }
        Ok(formats)
    }
}

/// Formats, printed size and resolution of the figures written.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// Files written per figure, in this order: `stem.png`, `stem.svg`.
    pub formats: Vec<Format>,
    /// Printed width of every figure \[in\]; None: [`DEFAULT_WIDTH_IN`] for a
    /// [`REFERENCE_WIDTH`]-wide figure, narrower figures in proportion (or from `height_in`).
    pub width_in: Option<f64>,
    /// Printed height of every figure \[in\]; None: from the width and the figure's own aspect.
    pub height_in: Option<f64>,
    /// PNG resolution \[dots per inch\].
    pub dpi: f64,
    /// Text size relative to the figure's layout (1: as laid out for screens).
    pub text_scale: f64,
}

impl Default for Output {
    /// PNG and SVG, 7 in wide (full-width figures), 300 dpi, text scale 1.3.
    fn default() -> Self {
        Output {
            formats: vec![Format::Png, Format::Svg],
            width_in: None,
            height_in: None,
            dpi: DEFAULT_DPI,
            text_scale: DEFAULT_TEXT_SCALE,
        }
    }
}

/// Where a figure of a given logical size goes on paper and in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Logical canvas the figure lays itself out on (its own size, or its width with the
    /// requested aspect ratio).
    pub logical: (u32, u32),
    /// Printed size \[in\].
    pub inches: (f64, f64),
    /// PNG size \[px\]: the printed size times the resolution, rounded.
    pub pixels: (u32, u32),
}

impl Output {
    /// Checks the values; the error ([`PlotError::InvalidOutput`]) names the field, the value
    /// and what is valid.
    pub fn check(&self) -> Result<()> {
        let bad = |field: &'static str, value: f64, reason: &str| {
            Err(PlotError::InvalidOutput {
                field,
                value,
                reason: reason.to_string(),
            })
        };
        if self.formats.is_empty() {
            return Err(PlotError::BadData {
                what: "output formats".into(),
                reason: format!("none given; valid: {}", Format::NAMES),
            });
        }
        if !(self.dpi.is_finite() && (30.0..=2400.0).contains(&self.dpi)) {
            return bad(
                "dpi",
                self.dpi,
                "must be a number from 30 to 2400 (dots per inch)",
            );
        }
        for (field, v) in [("width_in", self.width_in), ("height_in", self.height_in)] {
            if let Some(v) = v {
                if !(v.is_finite() && (0.5..=50.0).contains(&v)) {
                    return bad(field, v, "must be a number of inches from 0.5 to 50");
                }
            }
        }
        if !(self.text_scale.is_finite() && (0.5..=3.0).contains(&self.text_scale)) {
            return bad(
                "text_scale",
                self.text_scale,
                "must be a number from 0.5 to 3",
            );
        }
        Ok(())
    }

    /// Where a figure drawn on a `logical` canvas, `subdivision` units per layout unit (1 for
    /// most figures, 4 for the line plots), is printed and drawn.
    ///
    /// The length of a logical unit on paper is fixed ([`DEFAULT_WIDTH_IN`] per
    /// [`REFERENCE_WIDTH`] layout units), so text prints at one size whatever the figure's size:
    /// a width or height asked for changes the canvas the figure lays itself out on (a 3.5 in
    /// single-column figure gets a canvas half as wide, its plotting area shrinking around
    /// text of the same printed size), keeping the figure's aspect ratio unless both are given.
    pub fn place(&self, logical: (u32, u32), subdivision: u32) -> Placement {
        let (lw, lh) = (f64::from(logical.0), f64::from(logical.1));
        // Inches per logical unit.
        let unit = DEFAULT_WIDTH_IN / f64::from(REFERENCE_WIDTH) / f64::from(subdivision.max(1));
        let (cw, ch) = match (self.width_in, self.height_in) {
            (Some(w), Some(h)) => (w / unit, h / unit),
            (Some(w), None) => (w / unit, lh * w / unit / lw),
            (None, Some(h)) => (lw * h / unit / lh, h / unit),
            (None, None) => (lw, lh),
        };
        let (cw, ch) = (cw.round().max(1.0), ch.round().max(1.0));
        let (w_in, h_in) = (
            self.width_in.unwrap_or(cw * unit),
            self.height_in.unwrap_or(ch * unit),
        );
        Placement {
            logical: (cw as u32, ch as u32),
            inches: (w_in, h_in),
            pixels: (
                (w_in * self.dpi).round().max(1.0) as u32,
                (h_in * self.dpi).round().max(1.0) as u32,
            ),
        }
    }
}

thread_local! {
    static CURRENT: RefCell<Option<Output>> = const { RefCell::new(None) };
}

/// Runs `f` with `output` in effect for the figures it writes on this thread (the plain figure
/// functions take no output argument); the previous output is restored afterwards, also when
/// `f` panics. Figures written on other threads are not affected.
pub fn with_output<R>(output: &Output, f: impl FnOnce() -> R) -> R {
    struct Restore(Option<Output>);
    impl Drop for Restore {
        fn drop(&mut self) {
            CURRENT.with(|c| *c.borrow_mut() = self.0.take());
        }
    }
    let _restore = Restore(CURRENT.with(|c| c.borrow_mut().replace(output.clone())));
    f()
}

/// How much larger than laid out the text prints (the output's text scale, at least 1): layouts
/// that measure text multiply by it, so labels printed larger do not overlap.
pub(crate) fn text_scale() -> f64 {
    current_output().text_scale.max(1.0)
}

/// The output in effect on this thread.
pub fn current_output() -> Output {
    CURRENT.with(|c| c.borrow().clone()).unwrap_or_default()
}

/// Writes `figure` in every format of `output` to `stem.<ext>`; returns the files in the
/// order of `output.formats`.
pub(crate) fn write(figure: &impl Figure, stem: &Path, output: &Output) -> Result<Vec<PathBuf>> {
    output.check()?;
    let place = output.place(figure.size(), figure.subdivision());
    let (pw, ph) = place.pixels;
    if f64::from(pw.max(ph)) > MAX_PIXELS_PER_SIDE {
        return Err(PlotError::BadData {
            what: format!("output {} × {} px", pw, ph),
            reason: format!("exceeds {MAX_PIXELS_PER_SIDE} px per side; lower the dpi or the size"),
        });
    }
    let fail = |path: &Path| {
        let path = path.to_path_buf();
        move |e: DrawFailure| PlotError::Draw { path, reason: e.0 }
    };
    let mut files = Vec::new();
    for format in &output.formats {
        let path = crate::with_extension(stem, format.ext());
        match format {
            Format::Png => {
                // Drawn into an RGB buffer and encoded with the `png` crate: plotters' own
                // encoder would pull in the whole `image` crate.
                let mut rgb = vec![0u8; 3 * pw as usize * ph as usize];
                {
                    let backend = Scaled::new(
                        Typeset(BitMapBackend::with_buffer(&mut rgb, (pw, ph))),
                        place.logical,
                        output.text_scale,
                    );
                    let root = backend.into_drawing_area();
                    figure.draw(&root).map_err(fail(&path))?;
                    root.present()
                        .map_err(|e| DrawFailure(e.to_string()))
                        .map_err(fail(&path))?;
                }
                let png = crate::encode_png((pw, ph), output.dpi, &rgb).map_err(fail(&path))?;
                crate::write_whole(&path, &png).map_err(fail(&path))?;
            }
            Format::Svg => {
                let mut svg = String::new();
                {
                    // plotters writes `font-size` = size / 1.24; the bitmap's em is
                    // size × em_per_size(): the SVG's text is given the bitmap's em.
                    let backend = Scaled::new(
                        SVGBackend::with_string(&mut svg, place.logical),
                        place.logical,
                        output.text_scale,
                    )
                    .with_drawn_text(1.24 * crate::typeset::em_per_size());
                    let root = backend.into_drawing_area();
                    figure.draw(&root).map_err(fail(&path))?;
                    root.present()
                        .map_err(|e| DrawFailure(e.to_string()))
                        .map_err(fail(&path))?;
                }
                let svg = figure
                    .finish_svg(physical_svg(&svg, place.logical, place.inches))
                    .map_err(DrawFailure)
                    .map_err(fail(&path))?;
                crate::write_whole(&path, svg.as_bytes()).map_err(fail(&path))?;
            }
        }
        files.push(path);
    }
    Ok(files)
}

/// Replaces the root element's pixel `width`/`height` by the printed size in inches, keeping
/// the `viewBox` in logical units.
fn physical_svg(svg: &str, logical: (u32, u32), inches: (f64, f64)) -> String {
    let from = format!("width=\"{}\" height=\"{}\"", logical.0, logical.1);
    let to = format!("width=\"{:.4}in\" height=\"{:.4}in\"", inches.0, inches.1);
    svg.replacen(&from, &to, 1)
}

/// A backend that presents a logical canvas and draws on a backend `sx`, `sy` times larger,
/// text additionally enlarged by `text`. Text sizes are measured with [`Line`] (DejaVu Sans,
/// the font both the bitmap and the SVG use), so the layout is the same in every format.
pub(crate) struct Scaled<B> {
    inner: B,
    logical: (u32, u32),
    sx: f64,
    sy: f64,
    text: f64,
    /// Factor on the size handed to the wrapped backend's text, beyond `text` (1 for the
    /// bitmap; for the SVG, what makes its `font-size` the bitmap's em).
    drawn: f64,
}

impl<B: DrawingBackend> Scaled<B> {
    pub(crate) fn new(inner: B, logical: (u32, u32), text: f64) -> Self {
        let (w, h) = inner.get_size();
        Scaled {
            sx: f64::from(w) / f64::from(logical.0),
            sy: f64::from(h) / f64::from(logical.1),
            inner,
            logical,
            text,
            drawn: 1.0,
        }
    }

    /// The same, handing the wrapped backend text `drawn` times the laid-out size.
    pub(crate) fn with_drawn_text(self, drawn: f64) -> Self {
        Scaled { drawn, ..self }
    }

    fn at(&self, (x, y): BackendCoord) -> BackendCoord {
        (
            (f64::from(x) * self.sx).round() as i32,
            (f64::from(y) * self.sy).round() as i32,
        )
    }

    /// `size`, or smaller where a long line of text set at `size` would run off the canvas (a
    /// title longer than the figure is wide): the room is measured from the anchor along the
    /// line's direction, both ways for a centred line, less 2 % of the canvas. Only lines longer
    /// than a quarter of the canvas are fitted: a tick label centred on the frame's last tick
    /// may reach the edge and keeps its size.
    fn fitted<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
        size: f64,
        pos: BackendCoord,
    ) -> f64 {
        let bold = matches!(style.style(), FontStyle::Bold);
        let width = f64::from(Line::new(text, size, bold).size().0);
        let (w, h) = (f64::from(self.logical.0), f64::from(self.logical.1));
        let (at, extent) = match style.transform() {
            FontTransform::Rotate90 | FontTransform::Rotate270 => (f64::from(pos.1), h),
            _ => (f64::from(pos.0), w),
        };
        let room = match style.anchor().h_pos {
            HPos::Left => extent - at,
            HPos::Right => at,
            HPos::Center => 2.0 * at.min(extent - at),
        } - 0.02 * extent;
        if width > room && width > 0.25 * extent && room > 0.0 {
            size * room / width
        } else {
            size
        }
    }

    fn stroke<S: BackendStyle>(&self, style: &S) -> Stroke {
        Stroke {
            color: style.color(),
            width: ((f64::from(style.stroke_width()) * self.sx).round() as u32).max(1),
        }
    }
}

/// A colour and a stroke width in the wrapped backend's pixels.
struct Stroke {
    color: BackendColor,
    width: u32,
}

impl BackendStyle for Stroke {
    fn color(&self) -> BackendColor {
        self.color
    }
    fn stroke_width(&self) -> u32 {
        self.width
    }
}

/// A text style at another size; everything else is the original's. `layout_box` and `draw`
/// are the original's (at the original size): the wrapped backends ([`Typeset`], the SVG
/// backend) use neither.
struct Resized<'a, S> {
    style: &'a S,
    size: f64,
}

impl<S: BackendTextStyle> BackendTextStyle for Resized<'_, S> {
    type FontError = S::FontError;
    fn color(&self) -> BackendColor {
        self.style.color()
    }
    fn size(&self) -> f64 {
        self.size
    }
    fn transform(&self) -> FontTransform {
        self.style.transform()
    }
    fn style(&self) -> FontStyle {
        self.style.style()
    }
    fn anchor(&self) -> Pos {
        self.style.anchor()
    }
    fn family(&self) -> FontFamily<'_> {
        self.style.family()
    }
    fn layout_box(
        &self,
        text: &str,
    ) -> std::result::Result<((i32, i32), (i32, i32)), Self::FontError> {
        self.style.layout_box(text)
    }
    fn draw<E, DrawFunc: FnMut(i32, i32, BackendColor) -> std::result::Result<(), E>>(
        &self,
        text: &str,
        pos: BackendCoord,
        draw: DrawFunc,
    ) -> std::result::Result<std::result::Result<(), E>, Self::FontError> {
        self.style.draw(text, pos, draw)
    }
}

type Drawn<E> = std::result::Result<(), DrawingErrorKind<E>>;

impl<B: DrawingBackend> DrawingBackend for Scaled<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.logical
    }

    fn ensure_prepared(&mut self) -> Drawn<B::ErrorType> {
        self.inner.ensure_prepared()
    }

    fn present(&mut self) -> Drawn<B::ErrorType> {
        self.inner.present()
    }

    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Drawn<B::ErrorType> {
        // A logical pixel is a block of the wrapped backend's pixels.
        let (x0, y0) = self.at(point);
        let (x1, y1) = self.at((point.0 + 1, point.1 + 1));
        self.inner
            .draw_rect((x0, y0), ((x1 - 1).max(x0), (y1 - 1).max(y0)), &color, true)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Drawn<B::ErrorType> {
        let stroke = self.stroke(style);
        self.inner.draw_line(self.at(from), self.at(to), &stroke)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Drawn<B::ErrorType> {
        let stroke = self.stroke(style);
        self.inner
            .draw_rect(self.at(upper_left), self.at(bottom_right), &stroke, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Drawn<B::ErrorType> {
        let stroke = self.stroke(style);
        let points: Vec<BackendCoord> = path.into_iter().map(|p| self.at(p)).collect();
        self.inner.draw_path(points, &stroke)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Drawn<B::ErrorType> {
        let stroke = self.stroke(style);
        let points: Vec<BackendCoord> = vert.into_iter().map(|p| self.at(p)).collect();
        self.inner.fill_polygon(points, &stroke)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Drawn<B::ErrorType> {
        let stroke = self.stroke(style);
        let r = (f64::from(radius) * self.sx).round() as u32;
        self.inner.draw_circle(self.at(center), r, &stroke, fill)
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        (iw, ih): (u32, u32),
        src: &[u8],
    ) -> Drawn<B::ErrorType> {
        // Nearest-neighbour enlargement of the RGB image.
        let (x0, y0) = self.at(pos);
        let (x1, y1) = self.at((pos.0 + iw as i32, pos.1 + ih as i32));
        let (w, h) = ((x1 - x0).max(1) as u32, (y1 - y0).max(1) as u32);
        let mut big = vec![0u8; 3 * w as usize * h as usize];
        for y in 0..h {
            let sy = ((u64::from(y) * u64::from(ih)) / u64::from(h)) as usize;
            for x in 0..w {
                let sx = ((u64::from(x) * u64::from(iw)) / u64::from(w)) as usize;
                let s = 3 * (sy * iw as usize + sx);
                let d = 3 * (y as usize * w as usize + x as usize);
                if let (Some(src), Some(dst)) = (src.get(s..s + 3), big.get_mut(d..d + 3)) {
                    dst.copy_from_slice(src);
                }
            }
        }
        self.inner.blit_bitmap((x0, y0), (w, h), &big)
    }

    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> std::result::Result<(u32, u32), DrawingErrorKind<B::ErrorType>> {
        let bold = matches!(style.style(), FontStyle::Bold);
        let (w, h) = Line::new(text, style.size() * self.text, bold).size();
        Ok((w.ceil() as u32, h.ceil() as u32))
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Drawn<B::ErrorType> {
        let size = style.size() * self.text;
        let resized = Resized {
            style,
            size: self.fitted(text, style, size, pos) * self.drawn * self.sx,
        };
        self.inner.draw_text(text, &resized, self.at(pos))
    }
}
