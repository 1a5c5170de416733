//! Claim: every plot function writes a non-empty, valid PNG (signature and IHDR of the requested
//! size) and an SVG document for small data, without system fonts (the font is bundled).
//! No tolerance: file checks are exact.

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
