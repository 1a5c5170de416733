//! Claims of the pulse measurements (docs/physics.md §9: a solitary wave in 20 mm chains, pulses
//! split into groups in 40 and 80 mm chains).
//!
//! - Two Gaussian pulses of 100 N at 0.3 ms and 60 N at 0.5 ms (width 20 µs, so the force between
//!   them falls to ~0) are two separated peaks, found at their centres to the 1 µs sampling; a
//!   dip to only 90 % between two maxima makes them one peak (the larger).
//! - The arrival time at 5 % of the maximum of a linear ramp F = 1e6 t N is the first sample above
//!   5 % of its maximum (exact on the grid).

use woodpile::analysis::{arrival_s, separated_peaks};

fn grid() -> Vec<f64> {
    (0..=1000).map(|k| k as f64 * 1e-6).collect()
}

fn gauss(t: f64, t0: f64, a: f64) -> f64 {
    a * (-((t - t0) / 20e-6).powi(2)).exp()
}

#[test]
fn two_separated_pulses_are_two_peaks() {
    let t = grid();
    let f: Vec<f64> = t
        .iter()
        .map(|&t| gauss(t, 3e-4, 100.0) + gauss(t, 5e-4, 60.0))
        .collect();
    let peaks = separated_peaks(&t, &f, 0.0, 1e-3, 0.05);
    assert_eq!(peaks.len(), 2, "{peaks:?}");
    assert!((peaks[0].0 - 3e-4).abs() <= 1e-6 && (peaks[0].1 - 100.0).abs() < 1e-9);
    assert!((peaks[1].0 - 5e-4).abs() <= 1e-6 && (peaks[1].1 - 60.0).abs() < 1e-6);
}

#[test]
fn shallow_dip_makes_one_peak() {
    let t = grid();
    // Two maxima 30 µs apart with 20 µs width: the sum dips only slightly between them.
    let f: Vec<f64> = t
        .iter()
        .map(|&t| gauss(t, 3e-4, 100.0) + gauss(t, 3.3e-4, 95.0))
        .collect();
    let peaks = separated_peaks(&t, &f, 0.0, 1e-3, 0.05);
    assert_eq!(peaks.len(), 1, "{peaks:?}");
}

#[test]
fn arrival_of_a_ramp() {
    let t = grid();
    let f: Vec<f64> = t.iter().map(|&t| 1e6 * t).collect();
    // Maximum 1000 N at 1 ms: 5 % is 50 N, first exceeded at 51 µs.
    let a = arrival_s(&t, &f, 0.05).unwrap();
    assert!((a - 51e-6).abs() < 1e-12, "{a}");
}
