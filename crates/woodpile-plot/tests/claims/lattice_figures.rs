//! Claims on the lattice figures (`interface_forces`, `lattice_view`): each contact's colour is
//! drawn at its own (x, y) — one scale for x and y, every panel of a row and of a column
//! aligned, to 1.5 layout units (plotters rounds coordinates to whole units) — the colour of the
//! largest value is the top of the colour map and the bar's top label is that value, and the
//! files exist and decode. No physics: the forces are made up so that every (contact, window)
//! value differs, which lets the SVG's discs be matched to contacts by colour alone.

use super::{check, out_dir, png_pixels, svg_texts};
use plot::{ContactPoint, LatticeLayout, RodLine};
use std::collections::HashMap;
use woodpile_plot as plot;

/// Two layers of two rods, 40 mm long and 5 mm across: layer 1 along x at y = ∓10 mm, layer 2
/// along y at x = ∓10 mm; the striker at (5, −10) mm on rod 1 of layer 1, the four crossings,
/// two supports under the bottom rods at y = 0.
fn two_by_two() -> LatticeLayout {
    let rod = |layer: usize, number: usize, centre_mm: [f64; 2], axis: [f64; 2]| RodLine {
        layer,
        number,
        centre_mm,
        axis,
        length_mm: 40.0,
        diameter_mm: 5.0,
    };
    let at = |layer_above: usize, x_mm: f64, y_mm: f64| ContactPoint {
        layer_above,
        layer_below: layer_above + 1,
        x_mm,
        y_mm,
    };
    LatticeLayout {
        rods: vec![
            rod(1, 1, [0.0, -10.0], [1.0, 0.0]),
            rod(1, 2, [0.0, 10.0], [1.0, 0.0]),
            rod(2, 1, [-10.0, 0.0], [0.0, 1.0]),
            rod(2, 2, [10.0, 0.0], [0.0, 1.0]),
        ],
        contacts: vec![
            at(0, 5.0, -10.0),
            at(1, -10.0, -10.0),
            at(1, 10.0, -10.0),
            at(1, -10.0, 10.0),
            at(1, 10.0, 10.0),
            at(2, -10.0, 0.0),
            at(2, 10.0, 0.0),
        ],
        layers: 2,
    }
}

/// The largest value of contact c in window w: 10 + 20 (c + 7 w) N, 10 … 270 N, all distinct.
fn window_peak(c: usize, w: usize) -> f64 {
    10.0 + 20.0 * (c + 7 * w) as f64
}

/// 10 samples 0.1 ms apart; window 0 holds samples 0–4, window 1 samples 5–9; each contact
/// reaches its window's peak at one sample and half of it at the others.
fn samples(n: usize) -> (Vec<f64>, Vec<f64>, Vec<(f64, f64)>) {
    let times: Vec<f64> = (0..10).map(|s| s as f64 * 1e-4).collect();
    let forces = (0..10)
        .flat_map(|s| {
            (0..n).map(move |c| {
                let (w, k) = (s / 5, s % 5);
                window_peak(c, w) * if k == (c % 5) { 1.0 } else { 0.5 }
            })
        })
        .collect();
    (times, forces, vec![(0.0, 4.5e-4), (4.5e-4, 1e-3)])
}

/// The filled discs of an SVG: (cx, cy, fill) of every `<circle … fill="#rrggbb" …>`.
fn discs(svg: &str) -> Vec<(f64, f64, String)> {
    let attr = |tag: &str, name: &str| -> Option<String> {
        let key = format!(" {name}=\"");
        let start = tag.find(&key)? + key.len();
        Some(tag[start..start + tag[start..].find('"')?].to_string())
    };
    svg.split("<circle")
        .skip(1)
        .filter_map(|t| {
            let tag = &t[..t.find('>')?];
            let fill = attr(tag, "fill")?;
            (fill != "none").then(|| {
                let num = |n: &str| attr(tag, n).unwrap().parse::<f64>().unwrap();
                (num("cx"), num("cy"), fill.to_uppercase())
            })
        })
        .collect()
}

fn hex(c: plotters::style::RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// Claim: in `interface_forces`, the disc of contact c in window w has the colour of its
/// largest force in that window on a 0–270 N scale, and sits at its (x, y): with one scale s
/// for x and y (y up), cx = X_{k,w} + s·x and cy = Y_{k,w} − s·y, where X depends only on the
/// window (column, left to right) and Y only on the interface (row, top to bottom), to 1.5
/// units. The largest value (270 N)
/// has viridis' top colour and the bar's labels run from 0 to 270.
#[test]
fn interface_forces_draw_each_contact_at_its_place_in_its_colour() {
    let layout = two_by_two();
    let n = layout.contacts.len();
    let (times, forces, windows) = samples(n);
    let dir = out_dir("interfaces");
    let files = plot::with_output(&super::layout_pixels(), || {
        plot::interface_forces(
            &layout,
            &times,
            &forces,
            &windows,
            plot::MapColours::Auto,
            "2 × 2 rods",
            &dir.join("interface_forces"),
        )
    })
    .unwrap();
    check(&files);
    let (w, h, _) = png_pixels(&files[0]);
    assert!(w >= 1000 && h >= 600, "{w} × {h}");
    let svg = std::fs::read_to_string(&files[1]).unwrap();
    let found = discs(&svg);
    assert_eq!(found.len(), 2 * n, "one disc per contact per window");
    let by_colour: HashMap<&str, (f64, f64)> = found
        .iter()
        .map(|(x, y, f)| (f.as_str(), (*x, *y)))
        .collect();
    assert_eq!(by_colour.len(), 2 * n, "every value has its own colour");
    let top = 270.0;
    assert_eq!(
        plot::ColorMap::Viridis.rgb(window_peak(6, 1) / top),
        plot::ColorMap::Viridis.rgb(1.0),
        "the largest value is the top colour"
    );
    let place = |c: usize, w: usize| -> (f64, f64) {
        let colour = hex(plot::ColorMap::Viridis.rgb(window_peak(c, w) / top));
        *by_colour
            .get(colour.as_str())
            .unwrap_or_else(|| panic!("no disc of contact {c} in window {w} coloured {colour}"))
    };
    // The scale from the crossings of window 0: 20 mm apart in x and in y.
    let s = (place(2, 0).0 - place(1, 0).0) / 20.0;
    let s_y = (place(1, 0).1 - place(3, 0).1) / 20.0;
    assert!(s > 1.0 && (s - s_y).abs() * 20.0 <= 1.5, "x {s}, y {s_y}");
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); 2];
    let mut rows: Vec<Vec<f64>> = vec![Vec::new(); 3];
    for (c, p) in layout.contacts.iter().enumerate() {
        for (w, column) in columns.iter_mut().enumerate() {
            let (cx, cy) = place(c, w);
            column.push(cx - s * p.x_mm);
            rows[p.layer_above].push(cy + s * p.y_mm);
        }
    }
    for (what, offsets) in columns
        .iter()
        .map(|c| ("column", c))
        .chain(rows.iter().map(|r| ("row", r)))
    {
        let (lo, hi) = offsets
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(*v), b.max(*v))
            });
        assert!(hi - lo <= 1.5, "{what} offsets {offsets:?}");
    }
    assert!(
        columns[0][0] + 10.0 * s < columns[1][0],
        "window 0 is the left column, window 1 the right: {columns:?}"
    );
    assert!(
        rows[0][0] + 10.0 * s < rows[1][0] && rows[1][0] + 10.0 * s < rows[2][0],
        "interfaces 0, 1, 2 top to bottom: {rows:?}"
    );
    let texts = svg_texts(&files[1]);
    assert!(texts.iter().any(|t| t == "270"), "bar top: {texts:?}");
    assert!(texts.iter().any(|t| t == "0"), "bar bottom: {texts:?}");
    assert!(
        texts.iter().any(|t| t.contains("0.45–1 ms")),
        "window headers: {texts:?}"
    );
}

/// Claim: `lattice_view` draws one disc per contact, each coloured by its peak on a scale from
/// 0 to the largest peak (whose disc has viridis' top colour, the bar's top label that peak),
/// and writes a PNG that decodes and an SVG.
#[test]
fn lattice_view_colours_every_contact_by_its_peak() {
    let layout = two_by_two();
    let peaks: Vec<f64> = (0..layout.contacts.len())
        .map(|c| window_peak(c, 0))
        .collect();
    let dir = out_dir("lattice-view");
    let files =
        plot::lattice_view(&layout, &peaks, "2 × 2 rods", &dir.join("lattice_view")).unwrap();
    check(&files);
    let (w, h, pixels) = png_pixels(&files[0]);
    assert_eq!(pixels.len(), 3 * w * h, "the PNG decodes whole");
    let svg = std::fs::read_to_string(&files[1]).unwrap();
    let mut fills: Vec<String> = discs(&svg).into_iter().map(|(_, _, f)| f).collect();
    fills.sort();
    let top = peaks.iter().copied().fold(0.0, f64::max);
    let mut expected: Vec<String> = peaks
        .iter()
        .map(|p| hex(plot::ColorMap::Viridis.rgb(p / top)))
        .collect();
    expected.sort();
    assert_eq!(fills, expected);
    assert!(fills.contains(&hex(plot::ColorMap::Viridis.rgb(1.0))));
    let texts = svg_texts(&files[1]);
    assert!(
        texts.iter().any(|t| t == "130"),
        "bar top = 130 N: {texts:?}"
    );
}

/// Claim: a lattice of more interfaces than a page holds is drawn on pages `stem_1`, `stem_2`
/// (7 interfaces: 4 and 3 rows), every file written; data of the wrong shape is an error, not a
/// panic.
#[test]
fn many_interfaces_go_on_pages_and_bad_shapes_are_refused() {
    let mut layout = two_by_two();
    // Six layers: the 2 × 2 block repeated, the supports under layer 6.
    let base = layout.clone();
    layout.rods.clear();
    layout.contacts = vec![base.contacts[0]];
    for l in 1..=6 {
        let along_x = l % 2 == 1;
        for r in base.rods.iter().filter(|r| (r.layer == 1) == along_x) {
            layout.rods.push(RodLine {
                layer: l,
                ..r.clone()
            });
        }
        let (x, y) = if l < 6 { (10.0, 10.0) } else { (10.0, 0.0) };
        for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
            if l == 6 && sy > 0.0 {
                continue;
            }
            layout.contacts.push(ContactPoint {
                layer_above: l,
                layer_below: l + 1,
                x_mm: sx * x,
                y_mm: sy * y,
            });
        }
    }
    layout.layers = 6;
    let n = layout.contacts.len();
    let (times, _, windows) = samples(n);
    let forces: Vec<f64> = (0..times.len() * n).map(|i| (i % 97) as f64).collect();
    let dir = out_dir("pages");
    let stem = dir.join("interface_forces");
    let files = plot::interface_forces(
        &layout,
        &times,
        &forces,
        &windows,
        plot::MapColours::Log,
        "6 layers",
        &stem,
    )
    .unwrap();
    assert_eq!(files.len(), 4, "{files:?}");
    for page in ["interface_forces_1", "interface_forces_2"] {
        check(&[
            dir.join(format!("{page}.png")),
            dir.join(format!("{page}.svg")),
        ]);
    }
    let short = plot::interface_forces(
        &layout,
        &times,
        &forces[1..],
        &windows,
        plot::MapColours::Auto,
        "6 layers",
        &stem,
    );
    assert!(matches!(short, Err(plot::PlotError::BadData { .. })));
    let view = plot::lattice_view(&layout, &[1.0], "6 layers", &stem);
    assert!(matches!(view, Err(plot::PlotError::BadData { .. })));
}
