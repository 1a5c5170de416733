//! # woodpile-plot
//!
//! Figures of woodpile runs and analyses, each written as PNG and SVG from in-memory data (the
//! [`woodpile::analysis`] results and trajectories), never from files. Text uses DejaVu Sans,
//! bundled in the binary, so figures render the same on machines without system fonts.
//!
//! | function | figure | paper |
//! | --- | --- | --- |
//! | [`force_map`] | contact force, contact × time | Figs. 5, 9 a, c, e, g |
//! | [`energy_map`] | layer energy / injected energy [%], layer × time | Fig. 6 |
//! | [`spectrum_map`] | force spectrum (log), contact × frequency | Fig. 9 b, d, f, h |
//! | [`protocol_map`], [`peaks_per_layer`] | layer-by-layer protocol | Fig. 7 a, b |
//! | [`force_histories`], [`force_histories_between`] | force at chosen contacts vs time | Fig. 7 c |
//! | [`spectra`], [`spectra_between`] | amplitude spectra (log) with negative-mass bands shaded | Fig. 9 |
//! | [`effective_mass`] | M_eff/M_total vs frequency with bands shaded | Fig. 3 |
//! | [`transmission`] | transmission spectrum (dB) with the predicted gaps shaded | – |
//! | [`convergence`] | best and mean objective per GA generation | – |
//! | [`fit_signal`] | a fitted signal: measured and model vs time, the residual below | – |
//! | [`correlation_matrix`] | a fit's correlation matrix, cells coloured −1 … +1 with values | – |
//! | [`chain_picture`] | rods to scale, top to bottom | Fig. 5 d, e (right) |
//! | [`interface_forces`] | a lattice's contact forces on the crossing grid, interface × time window | – |
//! | [`lattice_view`] | a lattice in three dimensions, every contact coloured by its peak force | – |
//! | [`pareto_front`], [`front_designs`], [`hypervolume_history`] | a Pareto front (scatter or pairwise panels), its designs as rods, its hypervolume per generation | – |
//!
//! Every function takes a file *stem* (`dir/force_map`) and writes `stem.png` and `stem.svg`
//! (the formats, printed size and resolution of the [`Output`] in effect: by default PNG at
//! 300 dpi and SVG, full-width figures 7 in wide; see [`output`] and [`with_output`]),
//! returning the paths written.
//!
//! Heat maps of long chains are reduced to at most 300 rows × 600 columns of cells (each the
//! largest magnitude of its group, so peaks survive) and their SVG embeds the cells as one
//! image; colour bars label both limits and mark what saturates ("≥", "≤", a cap). Chain
//! pictures of more than 40 elements show the first and last 10 to scale and a strip of every
//! length.
//!
//! [`typeset`] lays out and rasterises the bitmaps' text (plotters' own drops glyph bearings).
//!
//! [`dirs`] draws the figure set of a whole output directory (a `woodpile simulate` run or a
//! `woodpile optimize` output), read back through [`woodpile_io`].
//!
//! Errors are [`PlotError`]: data that cannot be drawn, an [`Output`] option out of range (its
//! field, value and range), or a file that could not be written.

mod bars;
mod chain;
mod colorbar;
mod colormap;
pub mod dirs;
mod fit;
mod heatmap;
mod lattice;
mod lines;
pub mod output;
mod pareto;
pub mod typeset;

pub use bars::{sobol_indices, IndexBars};
pub use chain::chain_picture;
pub use colormap::ColorMap;
pub use fit::{correlation_matrix, fit_signal};
pub use heatmap::{
    contact0_name, energy_heatmap, energy_map, force_heatmap, force_map, protocol_map,
    spectrum_map, Heatmap, MapColours,
};
pub use lattice::{
    interface_forces, lattice_view, ContactPoint, LatticeLayout, RodLine, INTERFACES_PER_PAGE,
};
pub use lines::{
    convergence, effective_mass, force_histories, force_histories_between, hypervolume_history,
    onset_window_s, peaks_per_layer, spectra, spectra_between, transmission, ConvergencePoint,
    Series,
};
pub use output::{with_output, Format, Output};
pub use pareto::{front_designs, pareto_front, FrontDesign, MarkedDesign, ObjectiveAxis};

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// What can go wrong while drawing.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The data cannot be drawn (empty, wrong shape, non-finite).
    #[error("cannot plot {what}: {reason}")]
    BadData {
        /// Which figure or input.
        what: String,
        /// Why.
        reason: String,
    },
    /// An output option ([`Output`]) outside its range.
    #[error("output {field} = {value}: {reason}")]
    InvalidOutput {
        /// The field of [`Output`].
        field: &'static str,
        /// Its value.
        value: f64,
        /// What is valid.
        reason: String,
    },
    /// The drawing backend failed (e.g. the file could not be written).
    #[error("drawing {path} failed: {reason}")]
    Draw {
        /// The output file.
        path: PathBuf,
        /// The backend's message.
        reason: String,
    },
}

/// Result alias of this crate.
pub type Result<T, E = PlotError> = std::result::Result<T, E>;

/// Backend error while drawing, before the file is known.
#[derive(Debug)]
pub(crate) struct DrawFailure(String);

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for DrawFailure {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        DrawFailure(e.to_string())
    }
}

pub(crate) type DrawResult = std::result::Result<(), DrawFailure>;

/// A figure that can be drawn on any plotters backend.
///
/// A figure lays itself out in logical units on a canvas of its own [`Figure::size`] (text
/// 14–22 units high); [`render`] maps the units to the printed size and the bitmap's pixels
/// (see [`output`]), so no figure knows the output's resolution.
pub(crate) trait Figure {
    /// Canvas size in logical units.
    fn size(&self) -> (u32, u32);
    /// Logical units per layout unit: a figure that lays out on a nominal canvas (e.g. 1100 ×
    /// 600) with every length and font size multiplied by this factor, so that plotters'
    /// integer coordinates are finer than the layout grid. Its printed size by default is that
    /// of the nominal canvas.
    fn subdivision(&self) -> u32 {
        1
    }
    /// The SVG text as drawn, finished before it is written (e.g. a placeholder replaced by an
    /// embedded image); by default unchanged. An error is the reason it could not be.
    fn finish_svg(&self, svg: String) -> std::result::Result<String, String> {
        Ok(svg)
    }
    /// Draws on a white canvas of the drawing area's size: [`Figure::size`], or that width
    /// with another height when the output asks for another aspect ratio.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static;
}

/// Font family name under which DejaVu Sans is registered.
pub(crate) const FONT: &str = "sans-serif";

fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bundled fonts are valid TrueType files: registration cannot fail.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold());
    });
}

/// Writes the figure in the formats of the [`Output`] in effect on this thread (by default
/// `stem.png` and `stem.svg`); returns the files written.
pub(crate) fn render(figure: &impl Figure, stem: &Path) -> Result<Vec<PathBuf>> {
    register_fonts();
    output::write(figure, stem, &output::current_output())
}

/// Encodes an 8-bit RGB buffer of `size` pixels as PNG bytes, declaring `dpi` in the `pHYs`
/// chunk (pixels per metre, rounded) so that documents place it at its printed size.
fn encode_png(size: (u32, u32), dpi: f64, rgb: &[u8]) -> std::result::Result<Vec<u8>, DrawFailure> {
    let fail = |e: &dyn std::fmt::Display| DrawFailure(e.to_string());
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, size.0, size.1);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let per_metre = (dpi / 0.0254).round() as u32;
        encoder.set_pixel_dims(Some(png::PixelDimensions {
            xppu: per_metre,
            yppu: per_metre,
            unit: png::Unit::Meter,
        }));
        let mut writer = encoder.write_header().map_err(|e| fail(&e))?;
        writer.write_image_data(rgb).map_err(|e| fail(&e))?;
        writer.finish().map_err(|e| fail(&e))?;
    }
    Ok(bytes)
}

/// Writes a figure file whole: under a temporary name beside it, then renamed, so that an
/// interrupted or failed run never leaves a half-written figure.
fn write_whole(path: &Path, bytes: &[u8]) -> std::result::Result<(), DrawFailure> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| DrawFailure(format!("{} names no file", path.display())))?;
    woodpile_io::atomic::write_atomic(dir, &name, bytes).map_err(|e| DrawFailure(e.to_string()))
}

/// `stem` + `.ext`, keeping any dots already in the file name.
fn with_extension(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

/// A qualitative palette (Tableau 10) for line series.
pub(crate) fn series_color(i: usize) -> RGBColor {
    const P: [(u8, u8, u8); 10] = [
        (31, 119, 180),
        (255, 127, 14),
        (44, 160, 44),
        (214, 39, 40),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
    ];
    let (r, g, b) = P[i % P.len()];
    RGBColor(r, g, b)
}

/// Checks that `values` has at least one finite value; returns (min, max) of the finite ones.
pub(crate) fn finite_range(
    what: &str,
    values: impl IntoIterator<Item = f64>,
) -> Result<(f64, f64)> {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold(None, |acc: Option<(f64, f64)>, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
        .ok_or_else(|| PlotError::BadData {
            what: what.to_string(),
            reason: "no finite value to draw".to_string(),
        })
}

/// Widens a degenerate range so an axis can be drawn.
pub(crate) fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if hi > lo {
        (lo, hi)
    } else if lo == 0.0 {
        (-1.0, 1.0)
    } else {
        (lo - 0.5 * lo.abs(), hi + 0.5 * hi.abs())
    }
}

/// Short number for axis labels: up to 3 significant digits without trailing zeros, scientific
/// outside [1e-3, 1e5).
pub(crate) fn format_number(v: f64) -> String {
    let a = v.abs();
    if a < 1e-12 {
        "0".to_string()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.0e}")
    } else {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    }
}
