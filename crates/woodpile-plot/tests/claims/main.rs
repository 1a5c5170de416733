//! Claim: every plot function writes a non-empty, valid PNG (signature and IHDR of the requested
//! size) and an SVG document for small data, without system fonts (the font is bundled).
//! No tolerance: file checks are exact.
//! Claims on the bitmaps' text (woodpile_plot::typeset) are at the end; the lattice figures'
//! claims are in `lattice_figures`.

use std::path::{Path, PathBuf};
use woodpile::analysis::{
    contact_spectrum_map, energy_map, force_map, layer_by_layer, linspace, Spectrum,
    SpectrumSettings,
};
use woodpile::{
    simulate, CellModel, ChainBuilder, EffectiveMassCurve, Excitation, RunSettings, Striker,
    Trajectory, UnitCell,
};
use woodpile_plot as plot;

mod lattice_figures;

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("woodpile-plot-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn check(paths: &[PathBuf]) {
    assert_eq!(paths.len(), 2);
    let png = std::fs::read(&paths[0]).unwrap();
    assert!(
        png.len() > 1000,
        "{} is {} bytes",
        paths[0].display(),
        png.len()
    );
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{}", paths[0].display());
    assert_eq!(&png[12..16], b"IHDR");
    let (w, h) = (
        u32::from_be_bytes(png[16..20].try_into().unwrap()),
        u32::from_be_bytes(png[20..24].try_into().unwrap()),
    );
    assert!(w >= 300 && h >= 300, "{w} × {h}");
    let svg = std::fs::read_to_string(&paths[1]).unwrap();
    assert!(
        svg.contains("<svg") && svg.contains("</svg>"),
        "{}",
        paths[1].display()
    );
    assert!(svg.contains("<text"), "the SVG has text");
}

fn small_run() -> (woodpile::Chain, Trajectory) {
    let chain = ChainBuilder::table1_rods(&[80, 40, 20], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let settings = RunSettings {
        duration_s: 3e-4,
        ..RunSettings::paper_impact()
    };
    let mut t = Trajectory::default();
    simulate(
        &chain,
        &Excitation::Impact(Striker::paper()),
        &settings,
        &mut t,
    )
    .unwrap();
    (chain, t)
}

#[test]
fn every_plot_writes_png_and_svg() {
    let dir = out_dir("all");
    let stem = |n: &str| dir.join(n);
    let (chain, t) = small_run();
    let title = "3 rods, impact";
    check(
        &plot::force_map(
            &force_map(&t).unwrap(),
            title,
            Some("striker"),
            &stem("force_map"),
        )
        .unwrap(),
    );
    check(
        &plot::energy_map(
            &energy_map(&t).unwrap(),
            title,
            Some("striker"),
            &stem("energy_map"),
        )
        .unwrap(),
    );
    let smap = contact_spectrum_map(&t, &SpectrumSettings::default()).unwrap();
    check(&plot::spectrum_map(&smap, title, 100e3, None, &stem("spectrum_map")).unwrap());
    let series = vec![
        plot::Series::new("contact 0", t.contact_force_n(0)),
        plot::Series::new("wall", t.contact_force_n(3)),
    ];
    check(&plot::force_histories(&t.times_s, &series, title, &stem("histories")).unwrap());
    let s = Spectrum::of(&t.contact_force_n(3), 1e-6, &SpectrumSettings::default()).unwrap();
    let bands = UnitCell::table1(80).unwrap().negative_mass_bands_hz();
    check(
        &plot::spectra(
            &[("wall".into(), &s)],
            &bands,
            title,
            60e3,
            &stem("spectra"),
        )
        .unwrap(),
    );
    let f = linspace(0.0, 60e3, 200);
    let curves = vec![
        (
            "20 mm".to_string(),
            EffectiveMassCurve::of(&UnitCell::table1(20).unwrap(), &f),
        ),
        (
            "80 mm".to_string(),
            EffectiveMassCurve::of(&UnitCell::table1(80).unwrap(), &f),
        ),
    ];
    check(&plot::effective_mass(&curves, "cells", 5.0, &stem("meff")).unwrap());
    let points: Vec<_> = (0..5)
        .map(|g| plot::ConvergencePoint {
            generation: g,
            best: 10.0 - g as f64,
            mean: 12.0 - g as f64,
        })
        .collect();
    check(&plot::convergence(&points, "wall force [N]", "GA", &stem("convergence")).unwrap());
    check(&plot::chain_picture(&chain, "chain", Some("striker"), &stem("chain")).unwrap());
    let settings = RunSettings {
        duration_s: 2e-4,
        ..RunSettings::paper_impact()
    };
    let p = layer_by_layer(&chain, &Excitation::Impact(Striker::paper()), &settings).unwrap();
    check(&plot::protocol_map(&p.wall_force_map, title, &stem("protocol")).unwrap());
    let peaks = [plot::Series::new("protocol", p.peak_wall_force_n)];
    check(&plot::peaks_per_layer(&peaks, title, "peak force [N]", &stem("peaks")).unwrap());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unplottable_data_is_an_error_not_a_panic() {
    let dir = out_dir("bad");
    let stem = dir.join("x");
    assert!(plot::force_histories(&[0.0], &[], "t", &stem).is_err());
    let nan = vec![f64::NAN; 3];
    let s = [plot::Series::new("nan", nan)];
    assert!(plot::force_histories(&[0.0, 1.0, 2.0], &s, "t", &stem).is_err());
    assert!(plot::convergence(&[], "y", "t", &stem).is_err());
    let missing_dir = Path::new("/nonexistent-dir-for-woodpile/x");
    let (chain, _) = small_run();
    assert!(plot::chain_picture(&chain, "t", None, missing_dir).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

// ---- Text on bitmaps -------------------------------------------------------------------------

/// Column groups of ink (coverage > `ink`) separated by blank columns: (first, last) column.
fn ink_groups(w: usize, h: usize, raster: &[f32], ink: f32) -> Vec<(usize, usize)> {
    let inked = |x: usize| (0..h).any(|y| raster[y * w + x] > ink);
    let mut groups: Vec<(usize, usize)> = Vec::new();
    for x in 0..w {
        if inked(x) {
            match groups.last_mut() {
                Some(g) if g.1 + 1 == x => g.1 = x,
                _ => groups.push((x, x)),
            }
        }
    }
    groups
}

/// Lowest row with ink (coverage > 0.5) in columns a..=b.
fn lowest_ink_row(w: usize, h: usize, raster: &[f32], (a, b): (usize, usize)) -> usize {
    (0..h)
        .rev()
        .find(|&y| (a..=b).any(|x| raster[y * w + x] > 0.5))
        .expect("the group has ink")
}

#[test]
fn a_decimal_point_sits_on_the_baseline_with_the_digits() {
    // "0·2" was the symptom: plotters placed each glyph by its own box. The period's ink must
    // end on the digits' last row; 1 px allows for anti-aliasing of the round digits' overshoot.
    for size in [12.0, 16.0, 22.0] {
        let (w, h, raster) = plot::typeset::Line::new("0.2", size, false).coverage();
        let groups = ink_groups(w, h, &raster, 0.5);
        assert_eq!(groups.len(), 3, "0, . and 2 at {size} px: {groups:?}");
        let bottoms: Vec<usize> = groups
            .iter()
            .map(|&g| lowest_ink_row(w, h, &raster, g))
            .collect();
        let (lo, hi) = (bottoms.iter().min().unwrap(), bottoms.iter().max().unwrap());
        assert!(hi - lo <= 1, "bottom rows {bottoms:?} at {size} px");
    }
}

#[test]
fn repeated_letters_are_evenly_spaced() {
    // "tim e" was the symptom: pen positions rounded down per glyph and bearings dropped (up to
    // 1 px of error per glyph). Outlines placed at their exact pen positions put the coverage
    // centroids of equal glyphs one advance apart, to 0.25 px: the rasteriser's coverage is not
    // exactly translation-invariant (deviations of up to 0.13 px measured), and a glyph placed a
    // pixel off, as before, fails by 4x.
    for size in [14.0, 18.0, 24.0] {
        let line = plot::typeset::Line::new("llllll", size, false);
        let (w, h, raster) = line.coverage();
        let groups = ink_groups(w, h, &raster, 0.02);
        assert_eq!(groups.len(), 6, "six separate l's at {size} px: {groups:?}");
        // Each glyph's centroid over its own columns and the blank ones up to its neighbours
        // (where the faintest edge coverage lies).
        let centroid = |i: usize| {
            let a = if i == 0 { 0 } else { groups[i - 1].1 + 1 };
            let b = groups.get(i + 1).map_or(w - 1, |g| g.0 - 1);
            let (mut m0, mut m1) = (0.0, 0.0);
            for y in 0..h {
                for x in a..=b {
                    let c = f64::from(raster[y * w + x]);
                    m0 += c;
                    m1 += c * x as f64;
                }
            }
            m1 / m0
        };
        let spacing: Vec<f64> = (1..6).map(|i| centroid(i) - centroid(i - 1)).collect();
        let advance = f64::from(line.size().0) / 6.0;
        for s in &spacing {
            assert!(
                (s - advance).abs() <= 0.25,
                "centroid spacings {spacing:?} px, advance {advance} px at {size} px"
            );
        }
    }
}

// --- heat maps and chain pictures ---

/// The texts of an SVG's `<text>` elements.
fn svg_texts(path: &Path) -> Vec<String> {
    let svg = std::fs::read_to_string(path).unwrap();
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..];
            Some(body[..body.find("</text>")?].trim().to_string())
        })
        .collect()
}

/// The figures' own layout, one pixel per layout unit (the default printed widths at
/// 1100 px / 7 in, text as laid out): the pixel claims below are stated in it, whatever the
/// default resolution.
fn layout_pixels() -> plot::Output {
    plot::Output {
        dpi: f64::from(plot::output::REFERENCE_WIDTH) / plot::output::DEFAULT_WIDTH_IN,
        text_scale: 1.0,
        ..Default::default()
    }
}

/// A map `rows` × `cols` (index rows, time columns 1 µs apart) with values `f(row, col)`.
fn map_of(
    rows: woodpile::analysis::Axis,
    cols: usize,
    f: impl Fn(usize, usize) -> f64,
) -> woodpile::analysis::Map2 {
    let n = rows.len();
    let data = (0..n * cols).map(|i| f(i / cols, i % cols)).collect();
    let times = (0..cols).map(|c| c as f64 * 1e-6).collect();
    woodpile::analysis::Map2::new(
        rows,
        woodpile::analysis::Axis::new("time", "s", times),
        "contact force",
        "N",
        data,
    )
    .unwrap()
}

/// A force pulse travelling down a chain of `n` contacts over `cols` samples, 300 N at the top
/// decaying to 150 N at the bottom.
fn travelling_pulse(n: usize, cols: usize) -> woodpile::analysis::Map2 {
    map_of(
        woodpile::analysis::Axis::index("contact", n),
        cols,
        |r, c| {
            let (t, front) = (c as f64 / cols as f64, r as f64 / n as f64);
            300.0 * (-((t - front) * 40.0).powi(2)).exp() * (1.0 - 0.5 * front)
        },
    )
}

/// Width, height and 8-bit RGB pixels of a PNG written by this crate.
fn png_pixels(path: &Path) -> (usize, usize, Vec<u8>) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, buf)
}

/// Claim: the maps of a 10,001-contact chain over 2,000 samples (20 M values) stay small: SVG
/// under 5 MB (the stated target; 85 KB and 113 KB measured for the force and energy maps, as
/// the cells travel as one PNG image of at most 300 × 600 cells, each a block of whole pixels;
/// drawn as rectangles they take 15.5 MB), PNG at the fixed 1100 × 620 px of the layout and under 1 MB (122 KB
/// and 144 KB measured). And the y axis
/// names real contacts (5000 and 10000 among its labels), not drawn-row numbers.
#[test]
fn maps_of_a_10000_element_chain_stay_small() {
    let dir = out_dir("long-maps");
    let map = travelling_pulse(10_001, 2_000);
    let mut energy = map.clone();
    energy.data.iter_mut().for_each(|v| *v /= 3000.0);
    let (force, energy) = plot::with_output(&layout_pixels(), || {
        (
            plot::force_map(&map, "10,000 rods", None, &dir.join("force")).unwrap(),
            plot::energy_map(&energy, "10,000 rods", None, &dir.join("energy")).unwrap(),
        )
    });
    for paths in [&force, &energy] {
        check(paths);
        let png = std::fs::metadata(&paths[0]).unwrap().len();
        let svg = std::fs::metadata(&paths[1]).unwrap().len();
        assert!(png < 1_000_000, "{}: {png} bytes", paths[0].display());
        assert!(svg < 5_000_000, "{}: {svg} bytes", paths[1].display());
        let (w, h, _) = png_pixels(&paths[0]);
        assert_eq!((w, h), (1100, 620));
        let texts = svg_texts(&paths[1]);
        for row in ["5000", "10000"] {
            assert!(texts.iter().any(|t| t == row), "row {row} in {texts:?}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: a single spike (7.31 N, the rest ≤ 0.2 N) in one of 10,000 rows survives the row
/// reduction (each drawn row holds the largest magnitude of its group of ~33 rows): the colour
/// bar's top is labelled 7.31, and the map shows the top colour (viridis' last, compared exactly:
/// a cell is filled with one colour) left of the colour bar on 1 to 100 pixels, one cell (17 ×
/// ~2 px) and not the background. Averaging the group would draw the spike at 1/33 of its
/// height, keeping the group's first row would drop it.
#[test]
fn row_reduction_keeps_a_spike_in_one_row_of_10000() {
    let dir = out_dir("spike");
    let map = map_of(
        woodpile::analysis::Axis::index("contact", 10_000),
        50,
        |r, c| {
            if (r, c) == (6_789, 20) {
                7.31
            } else {
                0.1 * ((r + c) % 3) as f64
            }
        },
    );
    let paths = plot::with_output(&layout_pixels(), || {
        plot::force_map(&map, "one spike", None, &dir.join("spike")).unwrap()
    });
    let (w, h, rgb) = png_pixels(&paths[0]);
    let top = plot::ColorMap::Viridis.rgb(1.0);
    // The map ends left of x = 900 px (the colour bar starts right of it).
    let spike_pixels = (0..h)
        .flat_map(|y| (0..900.min(w)).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let p = &rgb[3 * (y * w + x)..3 * (y * w + x) + 3];
            (p[0], p[1], p[2]) == (top.0, top.1, top.2)
        })
        .count();
    assert!(
        (1..=100).contains(&spike_pixels),
        "{spike_pixels} pixels of the top colour in the map"
    );
    let texts = svg_texts(&paths[1]);
    assert!(texts.iter().any(|t| t == "7.31"), "top label in {texts:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: both ends of every colour bar are labelled with the scale's limits, and saturation is
/// said on the bar. Linear (force map, largest value 7.31 N): "0" and "7.31". Log (spectrum map,
/// 4 decades below 23.6): "23.6" at the top, "0.00236" at the bottom, the decades 0.01 to 10
/// between, and "≤ 0.00236" since zeros lie below. Saturated at a quantile: the top label starts
/// with "≥". Labels are compared as exact strings (3 significant digits).
#[test]
fn colour_bars_label_both_limits_and_say_what_saturates() {
    let dir = out_dir("bars");
    let rows = || woodpile::analysis::Axis::index("contact", 8);
    let linear = map_of(rows(), 40, |r, c| 7.31 * ((r * 40 + c) as f64 / 319.0));
    let paths = plot::force_map(&linear, "linear", None, &dir.join("linear")).unwrap();
    let texts = svg_texts(&paths[1]);
    for label in ["0", "7.31"] {
        assert!(texts.iter().any(|t| t == label), "{label} in {texts:?}");
    }
    assert!(!texts
        .iter()
        .any(|t| t.starts_with('≥') || t.starts_with('≤')));

    let log = map_of(rows(), 40, |r, c| {
        if c % 5 == 0 {
            0.0
        } else {
            23.6 * 0.3f64.powi(r as i32)
        }
    });
    let paths = plot::spectrum_map(&log, "log", 1e9, None, &dir.join("log")).unwrap();
    let texts = svg_texts(&paths[1]);
    for label in ["23.6", "10", "1", "0.1", "0.01", "≤ 0.00236"] {
        assert!(texts.iter().any(|t| t == label), "{label} in {texts:?}");
    }

    let paths = plot::Heatmap {
        saturate_quantile: Some(0.5),
        ..plot::Heatmap::new(&linear, "saturated")
    }
    .write(&dir.join("saturated"))
    .unwrap();
    let texts = svg_texts(&paths[1]);
    assert!(texts.iter().any(|t| t.starts_with("≥ ")), "≥ in {texts:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: the y ticks of a map name its rows' coordinates, not their indices: a map over four
/// peak forces F0 = 50, 100, 200, 400 N labels 400 (the last row), and no row index 3.
#[test]
fn map_rows_are_labelled_with_their_coordinates() {
    let dir = out_dir("row-labels");
    let rows = woodpile::analysis::Axis::new("peak force F0", "N", vec![50.0, 100.0, 200.0, 400.0]);
    let map = map_of(rows, 10, |r, c| (r + c) as f64);
    let paths = plot::Heatmap::new(&map, "sweep")
        .write(&dir.join("sweep"))
        .unwrap();
    let texts = svg_texts(&paths[1]);
    for label in ["50", "100", "200", "400"] {
        assert!(texts.iter().any(|t| t == label), "{label} in {texts:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: the chain picture of a 10,000-rod chain has a bounded size (at most 1000 × 900 px;
/// 950 × 840 measured, against 620 × 300,210 px when every rod was drawn), its SVG is under
/// 200 KB (61 KB measured), and its title says it is a summary.
#[test]
fn the_picture_of_a_10000_rod_chain_is_bounded() {
    let dir = out_dir("long-chain");
    let rods: Vec<_> = (0..10_000).map(|i| [20, 40, 80][i % 3]).collect();
    let chain = ChainBuilder::table1_rods(&rods, CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let paths = plot::with_output(&layout_pixels(), || {
        plot::chain_picture(&chain, "10,000 rods", None, &dir.join("chain")).unwrap()
    });
    check(&paths);
    let (w, h, _) = png_pixels(&paths[0]);
    assert!(w <= 1000 && h <= 900, "{w} × {h}");
    let svg = std::fs::metadata(&paths[1]).unwrap().len();
    assert!(svg < 200_000, "{svg} bytes");
    let texts = svg_texts(&paths[1]);
    assert!(
        texts
            .iter()
            .any(|t| t.contains("first and last 10 of 10000")),
        "{texts:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

// --- output options and histories ---

/// Width and height of a PNG file from its IHDR chunk, and its pHYs pixels per metre (None
/// without a pHYs chunk).
fn png_info(path: &Path) -> ((u32, u32), Option<(u32, u32)>) {
    let png = std::fs::read(path).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{}", path.display());
    let be = |i: usize| u32::from_be_bytes(png[i..i + 4].try_into().unwrap());
    let size = (be(16), be(20));
    // Walk the chunks: length, type, data, CRC.
    let mut i = 8;
    let mut phys = None;
    while i + 8 <= png.len() {
        let len = be(i) as usize;
        if &png[i + 4..i + 8] == b"pHYs" {
            assert_eq!(png[i + 16], 1, "pHYs unit is the metre");
            phys = Some((be(i + 8), be(i + 12)));
        }
        i += 12 + len;
    }
    (size, phys)
}

/// The x-axis tick labels of an SVG written by plotters: centred texts hanging below their
/// anchor (`text-anchor="middle"`, `dy="0.76em"`) that are numbers.
fn svg_x_ticks(svg: &str) -> Vec<f64> {
    svg.split("<text ")
        .skip(1)
        .filter(|t| t.contains("text-anchor=\"middle\"") && t.contains("dy=\"0.76em\""))
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..t.find("</text>")?];
            body.trim().parse::<f64>().ok()
        })
        .collect()
}

fn histories(t: &Trajectory) -> Vec<plot::Series> {
    vec![
        plot::Series::new("contact 0", t.contact_force_n(0)),
        plot::Series::new("wall", t.contact_force_n(3)),
    ]
}

/// Claim: a PNG is exactly the printed size times the resolution, in pixels, and declares that
/// resolution: 3.5 in at 600 dpi is 2100 px wide and 23622 px/m (600 / 0.0254, rounded), its
/// height the figure's aspect (1100 × 600 units: 3.5 × 600 / 1100 in, 1145.45 → 1145 px); with
/// both sizes given, 3 × 2.5 in at 200 dpi is 600 × 500 px; the defaults give 7 in at 300 dpi,
/// 2100 px. Exact: the only rounding is to whole pixels, stated here.
#[test]
fn png_pixels_follow_printed_size_times_dpi() {
    let dir = out_dir("dpi");
    let (_, t) = small_run();
    let series = histories(&t);
    let draw = |output: &plot::Output, name: &str| {
        plot::with_output(output, || {
            plot::force_histories(&t.times_s, &series, "3 rods", &dir.join(name)).unwrap()
        })
    };
    let column = plot::Output {
        width_in: Some(3.5),
        dpi: 600.0,
        ..plot::Output::default()
    };
    let files = draw(&column, "column");
    assert_eq!(
        png_info(&files[0]),
        ((2100, 1145), Some((23622, 23622))),
        "3.5 in at 600 dpi"
    );
    let boxed = plot::Output {
        width_in: Some(3.0),
        height_in: Some(2.5),
        dpi: 200.0,
        ..plot::Output::default()
    };
    let files = draw(&boxed, "boxed");
    assert_eq!(png_info(&files[0]).0, (600, 500), "3 × 2.5 in at 200 dpi");
    let files = plot::force_histories(&t.times_s, &series, "3 rods", &dir.join("default")).unwrap();
    assert_eq!(
        png_info(&files[0]),
        ((2100, 1145), Some((11811, 11811))),
        "the default: 7 in at 300 dpi"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: an SVG declares its printed size in inches in its root element and keeps the
/// figure's logical units in its viewBox, so it prints at the stated size: `width="3.5000in"`,
/// `height="1.9091in"` (3.5 × 600 / 1100, 4 decimals) and `viewBox="0 0 2200 1200"`: a unit
/// prints at one length (7 in per 1100 layout units, the line plots 4 units per layout unit),
/// so a 3.5 in figure lays out on a canvas half as wide as the 7 in default (4400 × 2400) and
/// its text prints at the default's size. Exact text.
#[test]
fn svg_declares_its_printed_size() {
    let dir = out_dir("svgsize");
    let (_, t) = small_run();
    let series = histories(&t);
    let output = plot::Output {
        width_in: Some(3.5),
        ..plot::Output::default()
    };
    let files = plot::with_output(&output, || {
        plot::force_histories(&t.times_s, &series, "3 rods", &dir.join("h")).unwrap()
    });
    let svg = std::fs::read_to_string(&files[1]).unwrap();
    let root = &svg[svg.find("<svg").unwrap()..];
    let root = &root[..root.find('>').unwrap()];
    assert!(
        root.contains("width=\"3.5000in\"")
            && root.contains("height=\"1.9091in\"")
            && root.contains("viewBox=\"0 0 2200 1200\""),
        "{root}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: only the requested formats are written, in the requested order: `svg` alone writes
/// no PNG; outside `with_output` the default (PNG and SVG) is back. Exact.
#[test]
fn only_the_requested_formats_are_written() {
    let dir = out_dir("formats");
    let (chain, t) = small_run();
    let svg_only = plot::Output {
        formats: plot::Format::parse_list("svg").unwrap(),
        ..plot::Output::default()
    };
    let files = plot::with_output(&svg_only, || {
        plot::chain_picture(&chain, "chain", None, &dir.join("chain")).unwrap()
    });
    assert_eq!(files, vec![dir.join("chain.svg")]);
    assert!(!dir.join("chain.png").exists());
    let files = plot::force_map(&force_map(&t).unwrap(), "map", None, &dir.join("map")).unwrap();
    assert_eq!(files, vec![dir.join("map.png"), dir.join("map.svg")]);
    let err = plot::Format::parse_list("png,pdf").unwrap_err();
    assert!(
        err.contains("pdf") && err.contains("svg") && err.contains("rsvg-convert"),
        "says PDF is not written and how to get one: {err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: histories drawn over a time window span only that window: every x tick label of the
/// SVG lies in [0.1, 0.2] ms (there are at least 3), where the whole record's reach 0.3 ms; a
/// window without 2 samples is an error that says which times the record covers. Exact (the
/// tick labels are rounded to 3 significant digits, which a window ending on 0.2 cannot exceed).
#[test]
fn a_time_window_limits_the_histories() {
    let dir = out_dir("window");
    let (_, t) = small_run();
    let series = histories(&t);
    let files = plot::force_histories_between(
        &t.times_s,
        &series,
        "3 rods",
        (0.1e-3, 0.2e-3),
        &dir.join("w"),
    )
    .unwrap();
    let ticks = svg_x_ticks(&std::fs::read_to_string(&files[1]).unwrap());
    assert!(ticks.len() >= 3, "{ticks:?}");
    assert!(
        ticks.iter().all(|&x| (0.1..=0.2).contains(&x)),
        "ticks {ticks:?} outside 0.1–0.2 ms"
    );
    let files = plot::force_histories(&t.times_s, &series, "3 rods", &dir.join("all")).unwrap();
    let all = svg_x_ticks(&std::fs::read_to_string(&files[1]).unwrap());
    assert!(all.iter().any(|&x| x >= 0.25), "whole record: {all:?}");
    let err = plot::force_histories_between(
        &t.times_s,
        &series,
        "3 rods",
        (1e-3, 2e-3),
        &dir.join("empty"),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("covers 0 to 0.3 ms"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: the first-arrivals window is chosen from the data as documented. Synthetic record,
/// 0.01 ms steps over 10 ms (levels placed between samples, so no sample sits on a threshold):
/// series 0 a triangle pulse of peak 1 at 0.105 ms, 0.105 ms half-width, at or above 10 % of its
/// peak from 0.0105 to 0.1995 ms, i.e. from the sample at 0.02 ms to the first sample below,
/// 0.20 ms: a 0.18 ms first pulse; series 1 a ramp from 3.005 ms to its peak 1 at 4.005 ms, then
/// flat: its first strong peak (at least half the peak, not below the next sample) is the sample
/// 4.01 ms. The window is 0 to 4.01 + 2 × 0.18 = 4.37 ms, to 1e-9 ms (sample times are exact
/// multiples of 0.01 ms up to rounding); with a series that never rises there is none, nor when
/// the window would cover more than the allowed fraction of the record (4.37 of 10 ms > 0.3).
#[test]
fn the_first_arrivals_window_follows_the_data() {
    let times: Vec<f64> = (0..=1000).map(|i| i as f64 * 1e-5).collect();
    let pulse: Vec<f64> = times
        .iter()
        .map(|&t| (1.0 - (t - 1.05e-4).abs() / 1.05e-4).max(0.0))
        .collect();
    let ramp: Vec<f64> = times
        .iter()
        .map(|&t| ((t - 3.005e-3) / 1e-3).clamp(0.0, 1.0))
        .collect();
    let series = vec![
        plot::Series::new("driven", pulse.clone()),
        plot::Series::new("far", ramp),
    ];
    let (a, b) = plot::onset_window_s(&times, &series, 0.5).expect("a window");
    assert_eq!(a, 0.0);
    assert!((b - 4.37e-3).abs() <= 1e-12, "window ends at {b} s");
    let silent = vec![
        plot::Series::new("driven", pulse),
        plot::Series::new("nothing", vec![0.0; times.len()]),
    ];
    assert_eq!(plot::onset_window_s(&times, &silent, 0.5), None);
    assert_eq!(plot::onset_window_s(&times, &series, 0.3), None);
}

/// Printed em sizes [pt] of an SVG's texts: `font-size` (user units) × printed width
/// (`width="…in"` × 72 pt) / viewBox width.
fn svg_text_pt(svg: &str) -> Vec<f64> {
    let attr = |s: &str, name: &str| -> Option<String> {
        let i = s.find(&format!("{name}=\""))? + name.len() + 2;
        Some(s[i..i + s[i..].find('"')?].to_string())
    };
    let root = &svg[svg.find("<svg").unwrap()..];
    let width_in: f64 = attr(root, "width")
        .unwrap()
        .trim_end_matches("in")
        .parse()
        .unwrap();
    let view: Vec<f64> = attr(root, "viewBox")
        .unwrap()
        .split(' ')
        .map(|v| v.parse().unwrap())
        .collect();
    svg.split("<text ")
        .skip(1)
        .map(|t| attr(t, "font-size").unwrap().parse::<f64>().unwrap() * width_in * 72.0 / view[2])
        .collect()
}

/// Claim: text prints at journal sizes, in the default double-column width (7 in) and in a
/// single column (3.5 in): every text of the force map's and the force histories' SVG (ticks,
/// legends, axis and colour-bar titles) has an em of 7.0 to 9.0 pt at the declared size, except
/// the figure title (the largest), at most 12 pt. Computed from the SVG's own numbers; the
/// bitmap uses the same em (typeset::em_per_size).
#[test]
fn default_text_prints_at_7_to_9_pt() {
    let dir = out_dir("textpt");
    let (_, t) = small_run();
    let draw = |name: &str| {
        [
            plot::force_map(&force_map(&t).unwrap(), "3 rods", None, &dir.join(name)).unwrap(),
            plot::force_histories(
                &t.times_s,
                &histories(&t),
                "3 rods",
                &dir.join(name.to_owned() + "_h"),
            )
            .unwrap(),
        ]
    };
    let single = plot::Output {
        width_in: Some(3.5),
        ..plot::Output::default()
    };
    let mut files = draw("double").to_vec();
    files.extend(plot::with_output(&single, || draw("single")));
    for f in &files {
        let mut pt = svg_text_pt(&std::fs::read_to_string(&f[1]).unwrap());
        pt.sort_by(f64::total_cmp);
        pt.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        eprintln!("{}: {pt:.2?} pt", f[1].display());
        let (title, body) = pt.split_last().unwrap();
        assert!(*title <= 12.0, "title {title} pt");
        assert!(
            body.iter().all(|p| (7.0..=9.0).contains(p)),
            "text sizes {pt:?} pt"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Claim: a line of text too long for the figure (here a 140-character title) is set smaller
/// so that it stays on the canvas: in the SVG, the title's width at its font size (measured
/// with the bitmap's typesetter, the same font) fits both ways from its centred anchor, where at
/// the default size it would not. Exact arithmetic on the SVG's numbers.
#[test]
fn a_too_long_title_is_set_smaller_to_fit() {
    let dir = out_dir("fit");
    let (_, t) = small_run();
    let title = "A title far too long for any figure: ".repeat(4);
    let title = title.trim_end();
    let files =
        plot::force_histories(&t.times_s, &histories(&t), title, &dir.join("long")).unwrap();
    let svg = std::fs::read_to_string(&files[1]).unwrap();
    let root = &svg[svg.find("viewBox=\"").unwrap() + 9..];
    let view_w: f64 = root.split(' ').nth(2).unwrap().parse().unwrap();
    let text = svg
        .split("<text ")
        .find(|t| t.contains(title))
        .expect("the title is drawn");
    let num = |name: &str| -> f64 {
        let i = text.find(&format!("{name}=\"")).unwrap() + name.len() + 2;
        text[i..i + text[i..].find('"').unwrap()].parse().unwrap()
    };
    // The SVG's font-size is the em; the typesetter takes the ascent-to-descent size.
    let size = num("font-size") / plot::typeset::em_per_size();
    let width = f64::from(plot::typeset::Line::new(title, size, false).size().0);
    let x = num("x");
    assert!(
        width <= 2.0 * x.min(view_w - x),
        "title {width} units wide at x = {x} on a {view_w}-unit canvas"
    );
    let default_size = 22.0 * 4.0 * plot::output::DEFAULT_TEXT_SCALE;
    let default_width = f64::from(
        plot::typeset::Line::new(title, default_size, false)
            .size()
            .0,
    );
    assert!(default_width > view_w, "the test title must be too long");
    std::fs::remove_dir_all(&dir).ok();
}
