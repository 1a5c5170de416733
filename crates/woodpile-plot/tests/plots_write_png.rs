//! Claim: every plot function writes a non-empty, valid PNG (signature and IHDR of the requested
//! size) and an SVG document for small data, without system fonts (the font is bundled).
//! No tolerance: file checks are exact.
//! Claims on the bitmaps' text (woodpile_plot::typeset) are at the end.

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
    check(&plot::force_map(&force_map(&t).unwrap(), title, &stem("force_map")).unwrap());
    check(&plot::energy_map(&energy_map(&t).unwrap(), title, &stem("energy_map")).unwrap());
    let smap = contact_spectrum_map(&t, &SpectrumSettings::default()).unwrap();
    check(&plot::spectrum_map(&smap, title, 100e3, &stem("spectrum_map")).unwrap());
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
    check(&plot::chain_picture(&chain, "chain", &stem("chain")).unwrap());
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
    assert!(plot::chain_picture(&chain, "t", missing_dir).is_err());
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
