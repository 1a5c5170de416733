//! Bisection: the one root finder the model needs (monotonic functions on a known bracket).

/// Finds where `below` switches from true (at `lo`) to false (at `hi`) by bisection, halving the
/// bracket until it cannot shrink in floating point; returns the midpoint of the last bracket.
pub(crate) fn bisect(mut lo: f64, mut hi: f64, below: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..2100 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
