//! Claim: Parseval's theorem holds for the transform behind a spectrum: the energy of the
//! windowed, zero-padded signal Σ (w_n x_n)² equals (1/L) Σ_k |X_k|² over the two-sided transform
//! reconstructed from the stored one-sided bins — for odd and even transform lengths.
//!
//! Tolerance: both sides are sums of ~10³ positive terms computed in f64; the FFT's round-off is
//! O(ε log L) relative, so 1e-12 relative is loose by two orders.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use woodpile::analysis::{Padding, Spectrum, SpectrumSettings, Window};

#[test]
fn parseval_holds_for_even_odd_and_padded_lengths() {
    let mut rng = ChaCha8Rng::seed_from_u64(20170101);
    for (n, padding) in [
        (1024, Padding::None),
        (999, Padding::None),
        (999, Padding::NextPowerOfTwo),
        (500, Padding::Length(777)),
    ] {
        let x: Vec<f64> = (0..n).map(|_| rng.random_range(-5.0..5.0)).collect();
        for window in [Window::Rectangular, Window::Hann, Window::BlackmanHarris] {
            let settings = SpectrumSettings {
                window,
                padding,
                remove_mean: false,
                scaling: Default::default(),
            };
            let s = Spectrum::of(&x, 1e-6, &settings).unwrap();
            let w = window.coefficients(n);
            let time_energy: f64 = x.iter().zip(&w).map(|(a, b)| (a * b).powi(2)).sum();
            let freq_energy = s.parseval_sum();
            assert!(
                (freq_energy / time_energy - 1.0).abs() < 1e-12,
                "n = {n}, {padding:?}, {window:?}: {freq_energy} vs {time_energy}"
            );
        }
    }
}
