//! Text on bitmaps, typeset properly. plotters 0.3's ab_glyph text drops each glyph's left side
//! bearing and rounds every pen position down to a pixel ("tim e"), and places small glyphs by
//! their own bounding box ("0·2"). `Typeset` wraps a backend and draws text itself: pen
//! positions in floating point with kerning, each glyph's outline at its bearing on one common
//! baseline, anti-aliased coverage blended in the text colour. Everything else goes to the
//! wrapped backend unchanged.

use ab_glyph::{point, Font, FontRef, PxScale, ScaleFont};
use plotters::prelude::*;
use plotters_backend::{
    text_anchor::{HPos, VPos},
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontStyle,
};
use std::sync::OnceLock;

/// The bundled regular and bold faces.
fn faces() -> &'static (FontRef<'static>, FontRef<'static>) {
    static FACES: OnceLock<(FontRef<'static>, FontRef<'static>)> = OnceLock::new();
    FACES.get_or_init(|| {
        // The bundled DejaVu files are valid fonts.
        let regular = FontRef::try_from_slice(dejavu::sans::regular()).expect("DejaVu Sans");
        let bold = FontRef::try_from_slice(dejavu::sans::bold()).expect("DejaVu Sans Bold");
        (regular, bold)
    })
}

/// The em of DejaVu Sans per unit of the size a [`Line`] is laid out at (its ascent-to-descent
/// height): units per em / (ascent − descent) of the regular face, 2048 / 2384 = 0.859.
pub fn em_per_size() -> f64 {
    let face = &faces().0;
    f64::from(face.units_per_em().unwrap_or(2048.0)) / f64::from(face.height_unscaled())
}

/// A line of text laid out at a pixel size in DejaVu Sans: glyph pen positions from the left
/// end of the baseline (kerned, in floating point), the advance width and the ascent and
/// descent \[px\]. Every bitmap figure's text is drawn from one.
pub struct Line {
    glyphs: Vec<(ab_glyph::GlyphId, f32)>,
    width: f32,
    ascent: f32,
    descent: f32,
    bold: bool,
    scale: PxScale,
}

impl Line {
    /// Lays out `text` at `size_px` pixels (ascent − descent), regular or bold.
    pub fn new(text: &str, size_px: f64, bold: bool) -> Line {
        let (regular, heavy) = faces();
        let face = if bold { heavy } else { regular };
        let scale = PxScale::from(size_px as f32);
        let font = face.as_scaled(scale);
        let mut x = 0.0;
        let mut prev = None;
        let mut glyphs = Vec::with_capacity(text.len());
        for c in text.chars() {
            let id = font.glyph_id(c);
            if let Some(p) = prev {
                x += font.kern(p, id);
            }
            glyphs.push((id, x));
            x += font.h_advance(id);
            prev = Some(id);
        }
        Line {
            glyphs,
            width: x,
            ascent: font.ascent(),
            descent: font.descent(),
            bold,
            scale,
        }
    }

    /// Width and height of the line's box \[px\].
    pub fn size(&self) -> (f32, f32) {
        (self.width, self.ascent - self.descent)
    }

    /// The line's anti-aliased coverage (0 to 1), row by row: (width, height, values) in pixels,
    /// the baseline at row `ascent`.
    pub fn coverage(&self) -> (usize, usize, Vec<f32>) {
        let (w, h) = self.size();
        let (w, h) = (w.ceil() as usize + 2, h.ceil() as usize + 2);
        let mut raster = vec![0.0; w * h];
        self.rasterize(|x, y, c| {
            if x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h {
                let v = &mut raster[y as usize * w + x as usize];
                *v = (*v + c).min(1.0);
            }
        });
        (w, h, raster)
    }

    /// Calls `pixel(x, y, coverage)` for every covered pixel, x and y from the top left of the
    /// line's box.
    fn rasterize(&self, mut pixel: impl FnMut(i32, i32, f32)) {
        let (regular, heavy) = faces();
        let face = if self.bold { heavy } else { regular };
        for &(id, x) in &self.glyphs {
            let glyph = id.with_scale_and_position(self.scale, point(x, self.ascent));
            if let Some(outline) = face.outline_glyph(glyph) {
                let bounds = outline.px_bounds();
                outline.draw(|gx, gy, c| {
                    pixel(
                        bounds.min.x as i32 + gx as i32,
                        bounds.min.y as i32 + gy as i32,
                        c,
                    )
                });
            }
        }
    }
}

/// A backend whose text is typeset by [`Line`]; everything else is the wrapped backend's.
pub(crate) struct Typeset<B>(pub(crate) B);

impl<B: DrawingBackend> DrawingBackend for Typeset<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.present()
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_path(path, style)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.fill_polygon(vert, style)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_circle(center, radius, style, fill)
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        (iw, ih): (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.blit_bitmap(pos, (iw, ih), src)
    }

    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<B::ErrorType>> {
        let (w, h) = Line::new(text, style.size(), matches!(style.style(), FontStyle::Bold)).size();
        Ok((w.ceil() as u32, h.ceil() as u32))
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let line = Line::new(text, style.size(), matches!(style.style(), FontStyle::Bold));
        let (w, h) = line.size();
        let anchor = style.anchor();
        let dx = match anchor.h_pos {
            HPos::Left => 0.0,
            HPos::Center => -w / 2.0,
            HPos::Right => -w,
        };
        let dy = match anchor.v_pos {
            VPos::Top => 0.0,
            VPos::Center => -h / 2.0,
            VPos::Bottom => -h,
        };
        let (dx, dy) = (dx.round() as i32, dy.round() as i32);
        let transform = style.transform();
        let (width, height) = self.get_size();
        let mut result = Ok(());
        line.rasterize(|x, y, coverage| {
            if result.is_err() || coverage <= 0.0 {
                return;
            }
            let (x, y) = transform.transform(x + dx, y + dy);
            let (x, y) = (pos.0 + x, pos.1 + y);
            if x >= 0 && y >= 0 && (x as u32) < width && (y as u32) < height {
                let c = BackendColor {
                    alpha: color.alpha * f64::from(coverage.min(1.0)),
                    rgb: color.rgb,
                };
                result = self.0.draw_pixel((x, y), c);
            }
        });
        result
    }
}
