//! Claim: spectra scaled as Fourier-transform magnitudes (docs/physics.md §8, `Scaling::
//! FourierMagnitude`) mean the same at any record length and sample interval. A half-sine force
//! pulse A sin(πt/T) (A = 100 N, T = 50 µs, the width of an impact's contact force):
//! - recorded for 2 ms and for 4 ms at Δt = 1 µs, gives the same |F̂(f)| at every common
//!   frequency (multiples of 500 Hz) to 1e-12 relative (the extra samples are zeros: only
//!   rounding differs), while the sine-amplitude scaling halves — the reason for the change;
//! - matches the closed form |F̂(f)| = 2 A π T |cos(π f T)| / |π² − (2π f T)²| to 2e-3 relative
//!   (A T/2 at f = 1/2T) below 20 kHz at Δt = 1 µs and 0.5 µs (the Riemann sum's O(Δt²) error of a pulse sampled 50
//!   times per width, and the pulse's kink at its ends);
//! - at Δt = 1 µs and 0.5 µs agrees with itself to 2e-3 over the same band.

use woodpile::analysis::{Scaling, Spectrum, SpectrumSettings};

const A: f64 = 100.0;
const T: f64 = 50e-6;

fn pulse(duration_s: f64, dt: f64) -> Vec<f64> {
    let n = (duration_s / dt).round() as usize + 1;
    (0..n)
        .map(|k| {
            let t = k as f64 * dt;
            if t <= T {
                A * (std::f64::consts::PI * t / T).sin()
            } else {
                0.0
            }
        })
        .collect()
}

fn spectrum(duration_s: f64, dt: f64, scaling: Scaling) -> Spectrum {
    let settings = SpectrumSettings {
        scaling,
        ..SpectrumSettings::default()
    };
    Spectrum::of(&pulse(duration_s, dt), dt, &settings).unwrap()
}

fn closed_form(f: f64) -> f64 {
    use std::f64::consts::PI;
    if (2.0 * f * T - 1.0).abs() < 1e-9 {
        return 0.5 * A * T; // the removable 0/0 at f = 1/(2T)
    }
    2.0 * A * PI * T * (PI * f * T).cos().abs() / (PI * PI - (2.0 * PI * f * T).powi(2)).abs()
}

#[test]
fn fourier_magnitude_does_not_depend_on_the_record_length() {
    // 2 ms + 1 sample and 4 ms + 1 sample: use 2000 and 4000 samples so the bins line up.
    let dt = 1e-6;
    let settings = SpectrumSettings {
        scaling: Scaling::FourierMagnitude,
        ..SpectrumSettings::default()
    };
    let short = Spectrum::of(&pulse(2e-3 - dt, dt), dt, &settings).unwrap();
    let long = Spectrum::of(&pulse(4e-3 - dt, dt), dt, &settings).unwrap();
    assert_eq!((short.n_samples, long.n_samples), (2000, 4000));
    // Relative to the spectrum's top: at the zeros of the transform both are rounding.
    let top = short.amplitudes[0];
    for (k, &a) in short.amplitudes.iter().enumerate().take(100) {
        let b = long.amplitudes[2 * k];
        assert!((short.frequencies_hz[k] - long.frequencies_hz[2 * k]).abs() < 1e-9);
        let f = short.frequencies_hz[k];
        assert!((a - b).abs() <= 1e-12 * top, "f = {f}: {a} vs {b}");
    }
    // The sine-amplitude scaling of the same pulse halves when the record doubles.
    let amp = |d: f64| spectrum(d - dt, dt, Scaling::Amplitude).amplitudes[1];
    let (a2, a4) = (amp(2e-3), amp(4e-3));
    assert!((a2 / spectrum(4e-3 - dt, dt, Scaling::Amplitude).amplitudes[2] - 2.0).abs() < 1e-9);
    assert!(a4 < a2);
}

#[test]
fn fourier_magnitude_matches_the_closed_form_at_two_sample_intervals() {
    // 2 ms records: 2000 samples at 1 µs, 4000 at 0.5 µs, so bin k is the same frequency.
    let coarse = spectrum(2e-3 - 1e-6, 1e-6, Scaling::FourierMagnitude);
    let fine = spectrum(2e-3 - 0.5e-6, 0.5e-6, Scaling::FourierMagnitude);
    for (k, &f) in coarse.frequencies_hz.iter().enumerate() {
        // Skip the zeros of cos(π f T) (every 20 kHz from 30 kHz) and stay below 20 kHz.
        if f > 20e3 {
            break;
        }
        let exact = closed_form(f);
        let kf = fine
            .frequencies_hz
            .iter()
            .position(|&g| (g - f).abs() < 1e-6)
            .unwrap();
        for (got, label) in [
            (coarse.amplitudes[k], "Δt = 1 µs"),
            (fine.amplitudes[kf], "Δt = 0.5 µs"),
        ] {
            assert!(
                (got / exact - 1.0).abs() < 2e-3,
                "{label}, f = {f}: {got} vs {exact}"
            );
        }
        assert!((coarse.amplitudes[k] / fine.amplitudes[kf] - 1.0).abs() < 2e-3);
    }
}
