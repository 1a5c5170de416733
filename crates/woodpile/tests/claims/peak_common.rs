//! Comparing the contact peaks of two runs.

/// The worst relative error of the peaks `a` against `reference`, over the reference's peaks
/// above 1 % of its largest (smaller ones are the tails of a wave, not what a study reads).
pub fn worst_peak_error(a: &[f64], reference: &[f64]) -> f64 {
    let largest = reference.iter().fold(0.0_f64, |m, &f| m.max(f));
    a.iter()
        .zip(reference)
        .filter(|(_, &r)| r > 0.01 * largest)
        .map(|(x, r)| (x / r - 1.0).abs())
        .fold(0.0, f64::max)
}
