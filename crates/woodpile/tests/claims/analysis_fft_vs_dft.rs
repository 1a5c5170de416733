//! Claim: the spectrum's bins are the discrete Fourier transform X_k = Σ_n x_n e^{−2πikn/L} of the
//! (windowed, zero-padded) signal, checked against a naive O(L²) DFT of a fixed-seed random signal,
//! and its amplitudes are c_k |X_k| / Σ w_n.
//!
//! Tolerance: the naive DFT accumulates L terms of size ~|x| with phases from `sin_cos`; its own
//! error is ~L·ε·max|x| ≈ 1e-12 for L ~ 10³, so bins must agree to 1e-9 absolute on signals of
//! order 1 (sums of order 30).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use woodpile::analysis::{Padding, Spectrum, SpectrumSettings, Window};

fn naive_dft(x: &[f64], l: usize) -> Vec<(f64, f64)> {
    (0..=l / 2)
        .map(|k| {
            x.iter().enumerate().fold((0.0, 0.0), |(re, im), (n, v)| {
                // Reduce kn mod L first so the phase stays accurate.
                let phase = -2.0 * PI * ((k * n) % l) as f64 / l as f64;
                let (s, c) = phase.sin_cos();
                (re + v * c, im + v * s)
            })
        })
        .collect()
}

#[test]
fn fft_bins_match_a_naive_dft() {
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    for (n, padding) in [
        (256, Padding::None),
        (301, Padding::None),
        (300, Padding::Length(512)),
    ] {
        let x: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        for window in [Window::Rectangular, Window::Hamming] {
            let settings = SpectrumSettings {
                window,
                padding,
                remove_mean: false,
                scaling: Default::default(),
            };
            let s = Spectrum::of(&x, 2e-6, &settings).unwrap();
            let w = window.coefficients(n);
            let xw: Vec<f64> = x.iter().zip(&w).map(|(a, b)| a * b).collect();
            let reference = naive_dft(&xw, s.n_fft);
            assert_eq!(s.bins.len(), reference.len());
            let wsum: f64 = w.iter().sum();
            for (k, (bin, (re, im))) in s.bins.iter().zip(&reference).enumerate() {
                assert!(
                    (bin.re - re).abs() < 1e-9 && (bin.im - im).abs() < 1e-9,
                    "n = {n}, {window:?}, bin {k}: {bin} vs {re} + {im}i"
                );
                let single = k == 0 || (s.n_fft.is_multiple_of(2) && k == s.n_fft / 2);
                let c = if single { 1.0 } else { 2.0 };
                let a = c * re.hypot(*im) / wsum;
                assert!((s.amplitudes[k] - a).abs() < 1e-9);
                let f = k as f64 / (s.n_fft as f64 * 2e-6);
                assert!((s.frequencies_hz[k] - f).abs() < 1e-6);
            }
        }
    }
}
