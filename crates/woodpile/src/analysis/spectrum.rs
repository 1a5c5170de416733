//! One-sided amplitude spectra of uniformly sampled real signals (paper Fig. 9 b, d, f, h).
//!
//! The discrete Fourier transform X_k = Σ_n w_n x_n e^{−2πi kn/L} of the windowed signal, zero
//! padded to L ≥ N samples, is scaled so that a sine of amplitude A at a bin frequency reads A:
//!
//! ```text
//! A_k = c_k |X_k| / Σ_n w_n,      c_0 = c_{L/2} = 1, c_k = 2 otherwise,      f_k = k / (L Δt)
//! ```
//!
//! Dividing by Σ w_n = N · (coherent gain) is the coherent-gain correction of a window.
//!
//! The transform is RustFFT's complex FFT of the real signal. A real-to-complex FFT (the
//! `realfft` crate) would halve the work, but our signals are a few thousand samples and the
//! complex transform keeps the dependency list to one well-kept crate; a [`SpectrumPlan`] reuses
//! the FFT plan and buffers across the contacts of a chain.
//!
//! ## References
//! - F. J. Harris, "On the use of windows for harmonic analysis with the discrete Fourier
//!   transform", Proc. IEEE 66 (1978) 51–83 (window definitions, coherent gain).

use super::map::{Axis, Map2};
use crate::error::{require_positive, Error, Result};
use crate::math::Libm;
use crate::record::{sample_interval_s, Trajectory};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::f64::consts::PI;
use std::sync::Arc;

/// Window applied to a signal before its transform (Harris 1978).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Window {
    /// w_n = 1: best amplitude for transients that fit the record (our force pulses).
    #[default]
    Rectangular,
    /// w_n = sin²(π n/N): low leakage, coherent gain 1/2.
    Hann,
    /// w_n = 0.54 − 0.46 cos(2π n/N): coherent gain 0.54.
    Hamming,
    /// Blackman–Harris (4 terms, −92 dB side lobes): coherent gain 0.35875.
    BlackmanHarris,
    /// Flat top (5 terms, as MATLAB's `flattopwin`): amplitude accurate to ~0.01 dB anywhere in a
    /// bin, at the price of wide peaks.
    FlatTop,
}

impl Window {
    /// Every window, for user interfaces.
    pub const ALL: [Window; 5] = [
        Window::Rectangular,
        Window::Hann,
        Window::Hamming,
        Window::BlackmanHarris,
        Window::FlatTop,
    ];

    /// Short lowercase name (`rectangular`, `hann`, `hamming`, `blackman-harris`, `flat-top`).
    pub fn name(self) -> &'static str {
        match self {
            Window::Rectangular => "rectangular",
            Window::Hann => "hann",
            Window::Hamming => "hamming",
            Window::BlackmanHarris => "blackman-harris",
            Window::FlatTop => "flat-top",
        }
    }

    /// Parses [`Window::name`].
    pub fn from_name(name: &str) -> Result<Self> {
        Window::ALL
            .into_iter()
            .find(|w| w.name() == name)
            .ok_or_else(|| Error::Unknown {
                what: "spectral window",
                name: name.to_string(),
                valid: Window::ALL.map(Window::name).join(", "),
            })
    }

    /// Cosine-sum coefficients a_m of w_n = Σ_m (−1)^m a_m cos(2π m n/N) (periodic form).
    fn cosine_terms(self) -> &'static [f64] {
        match self {
            Window::Rectangular => &[1.0],
            Window::Hann => &[0.5, 0.5],
            Window::Hamming => &[0.54, 0.46],
            Window::BlackmanHarris => &[0.35875, 0.48829, 0.14128, 0.01168],
            Window::FlatTop => &[
                0.215_578_95,
                0.416_631_58,
                0.277_263_158,
                0.083_578_947,
                0.006_947_368,
            ],
        }
    }

    /// The n samples w_0..w_{n−1} (periodic: the DFT-even form, exact coherent gain a_0).
    pub fn coefficients(self, n: usize) -> Vec<f64> {
        let terms = self.cosine_terms();
        (0..n)
            .map(|i| {
                let x = 2.0 * PI * i as f64 / n as f64;
                terms
                    .iter()
                    .enumerate()
                    .map(|(m, a)| {
                        let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
                        sign * a * (m as f64 * x).libm_cos()
                    })
                    .sum()
            })
            .collect()
    }
}

/// How far to zero-pad a signal before its transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Padding {
    /// Transform the N samples as they are.
    #[default]
    None,
    /// Pad to the next power of two ≥ N.
    NextPowerOfTwo,
    /// Pad to L samples (L ≥ N; a shorter L is an error).
    Length(usize),
}

/// What a spectrum's values are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scaling {
    /// One-sided sine amplitude, A_k = c_k |X_k| / Σ w_n [unit of the signal]: a steady sine of
    /// amplitude A at a bin reads A. For a transient it falls as the record grows (the same pulse
    /// in a record twice as long reads half): use it for steady signals.
    #[default]
    Amplitude,
    /// Magnitude of the Fourier transform, |F̂(f_k)| = Δt |X_k| / (Σ w_n / N) [unit · s, e.g.
    /// N/Hz]: the Riemann sum of ∫ w x(t) e^{−2πift} dt. For a transient that fits the record it
    /// is independent of the record length and (to O(Δt²)) of the sample interval: spectra of
    /// two runs compare directly.
    FourierMagnitude,
}

impl Scaling {
    /// (quantity, unit) for a signal in `unit`: ("amplitude", "N") or ("|F̂(f)|", "N/Hz").
    pub fn label(self, unit: &str) -> (&'static str, String) {
        match self {
            Scaling::Amplitude => ("amplitude", unit.to_string()),
            Scaling::FourierMagnitude => ("|F̂(f)|", format!("{unit}/Hz")),
        }
    }
}

/// Options of a spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpectrumSettings {
    /// What the values are (default: the sine amplitude).
    pub scaling: Scaling,
    /// Window applied before the transform.
    pub window: Window,
    /// Zero padding (finer frequency grid; no new resolution).
    pub padding: Padding,
    /// Subtract the mean before windowing (removes the 0 Hz bin of a force offset).
    pub remove_mean: bool,
}

/// The one-sided spectrum of a real signal.
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    /// Frequencies f_k = k/(L Δt), k = 0..=L/2 \[Hz\].
    pub frequencies_hz: Vec<f64>,
    /// One-sided amplitude A_k with coherent-gain correction [unit of the signal].
    pub amplitudes: Vec<f64>,
    /// The raw DFT bins X_0..X_{L/2} of the windowed, padded signal (no scaling).
    pub bins: Vec<Complex64>,
    /// Number of signal samples N.
    pub n_samples: usize,
    /// Transform length L ≥ N.
    pub n_fft: usize,
    /// Sample interval Δt \[s\].
    pub sample_interval_s: f64,
    /// Window used.
    pub window: Window,
    /// What the values are.
    pub scaling: Scaling,
}

impl Spectrum {
    /// The spectrum of `signal` sampled every `sample_interval_s` seconds.
    pub fn of(signal: &[f64], sample_interval_s: f64, settings: &SpectrumSettings) -> Result<Self> {
        SpectrumPlan::new(signal.len(), sample_interval_s, settings)?.transform(signal)
    }

    /// Frequency resolution 1/(L Δt) \[Hz\].
    pub fn resolution_hz(&self) -> f64 {
        1.0 / (self.n_fft as f64 * self.sample_interval_s)
    }

    /// Nyquist frequency 1/(2Δt) \[Hz\].
    pub fn nyquist_hz(&self) -> f64 {
        0.5 / self.sample_interval_s
    }

    /// (f, A) of the largest amplitude, skipping the 0 Hz bin.
    pub fn peak(&self) -> (f64, f64) {
        let k = (1..self.amplitudes.len())
            .max_by(|&a, &b| self.amplitudes[a].total_cmp(&self.amplitudes[b]))
            .unwrap_or(0);
        (self.frequencies_hz[k], self.amplitudes[k])
    }

    /// Parseval's sum (1/L) Σ_{k=0}^{L−1} |X_k|² over the two-sided transform, from the
    /// one-sided bins (X_{L−k} = conj X_k). Equals Σ_n (w_n x_n)² of the windowed signal.
    pub fn parseval_sum(&self) -> f64 {
        let l = self.n_fft;
        let total: f64 = self
            .bins
            .iter()
            .enumerate()
            .map(|(k, x)| {
                let twice = k != 0 && !(l.is_multiple_of(2) && k == l / 2);
                let p = x.norm_sqr();
                if twice {
                    2.0 * p
                } else {
                    p
                }
            })
            .sum();
        total / l as f64
    }
}

/// A reusable transform for signals of one length: the FFT plan, the window and buffers.
pub struct SpectrumPlan {
    fft: Arc<dyn Fft<f64>>,
    window: Vec<f64>,
    window_sum: f64,
    settings: SpectrumSettings,
    n_samples: usize,
    n_fft: usize,
    sample_interval_s: f64,
    buffer: Vec<Complex64>,
    scratch: Vec<Complex64>,
}

impl std::fmt::Debug for SpectrumPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SpectrumPlan")
            .field("n_samples", &self.n_samples)
            .field("n_fft", &self.n_fft)
            .field("settings", &self.settings)
            .finish()
    }
}

impl SpectrumPlan {
    /// Plans transforms of signals of `n_samples` samples.
    pub fn new(
        n_samples: usize,
        sample_interval_s: f64,
        settings: &SpectrumSettings,
    ) -> Result<Self> {
        require_positive("spectrum.sample_interval_s", sample_interval_s)?;
        if n_samples < 2 {
            return Err(Error::invalid(
                "spectrum.signal length",
                n_samples,
                "a spectrum needs at least 2 samples",
            ));
        }
        let n_fft = match settings.padding {
            Padding::None => n_samples,
            Padding::NextPowerOfTwo => n_samples.next_power_of_two(),
            Padding::Length(l) if l >= n_samples => l,
            Padding::Length(l) => {
                return Err(Error::invalid(
                    "spectrum.padding",
                    l,
                    format!("must be at least the signal length {n_samples}"),
                ))
            }
        };
        let window = settings.window.coefficients(n_samples);
        let window_sum = window.iter().sum();
        let fft = FftPlanner::new().plan_fft_forward(n_fft);
        let scratch = vec![Complex64::default(); fft.get_inplace_scratch_len()];
        Ok(SpectrumPlan {
            fft,
            window,
            window_sum,
            settings: *settings,
            n_samples,
            n_fft,
            sample_interval_s,
            buffer: vec![Complex64::default(); n_fft],
            scratch,
        })
    }

    /// Frequencies of the one-sided bins \[Hz\].
    pub fn frequencies_hz(&self) -> Vec<f64> {
        let df = 1.0 / (self.n_fft as f64 * self.sample_interval_s);
        (0..=self.n_fft / 2).map(|k| k as f64 * df).collect()
    }

    /// The spectrum of one signal of the planned length.
    pub fn transform(&mut self, signal: &[f64]) -> Result<Spectrum> {
        let (bins, amplitudes) = self.bins_and_amplitudes(signal)?;
        Ok(Spectrum {
            frequencies_hz: self.frequencies_hz(),
            amplitudes,
            bins,
            n_samples: self.n_samples,
            n_fft: self.n_fft,
            sample_interval_s: self.sample_interval_s,
            window: self.settings.window,
            scaling: self.settings.scaling,
        })
    }

    /// One-sided amplitudes only (no allocation of the frequency axis).
    pub fn amplitudes(&mut self, signal: &[f64]) -> Result<Vec<f64>> {
        Ok(self.bins_and_amplitudes(signal)?.1)
    }

    fn bins_and_amplitudes(&mut self, signal: &[f64]) -> Result<(Vec<Complex64>, Vec<f64>)> {
        if signal.len() != self.n_samples {
            return Err(Error::invalid(
                "spectrum.signal length",
                signal.len(),
                format!("the plan was made for {} samples", self.n_samples),
            ));
        }
        if let Some(i) = signal.iter().position(|x| !x.is_finite()) {
            return Err(Error::invalid(
                format!("spectrum.signal[{i}]"),
                signal[i],
                "every sample must be finite",
            ));
        }
        let mean = if self.settings.remove_mean {
            signal.iter().sum::<f64>() / signal.len() as f64
        } else {
            0.0
        };
        for (b, (x, w)) in self.buffer.iter_mut().zip(signal.iter().zip(&self.window)) {
            *b = Complex64::new((x - mean) * w, 0.0);
        }
        for b in &mut self.buffer[self.n_samples..] {
            *b = Complex64::default();
        }
        self.fft
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
        let l = self.n_fft;
        let bins: Vec<Complex64> = self.buffer[..=l / 2].to_vec();
        let amplitudes = match self.settings.scaling {
            Scaling::Amplitude => bins
                .iter()
                .enumerate()
                .map(|(k, x)| {
                    let single = k == 0 || (l.is_multiple_of(2) && k == l / 2);
                    let c = if single { 1.0 } else { 2.0 };
                    c * x.norm() / self.window_sum
                })
                .collect(),
            Scaling::FourierMagnitude => {
                let gain = self.window_sum / self.n_samples as f64;
                bins.iter()
                    .map(|x| self.sample_interval_s * x.norm() / gain)
                    .collect()
            }
        };
        Ok((bins, amplitudes))
    }
}

/// Spectra of every contact force of a trajectory: rows = contacts 0..=N, columns = frequencies
/// \[Hz\], values as `settings.scaling` says (amplitude \[N\] or |F̂(f)| \[N/Hz\]).
pub fn contact_spectrum_map(trajectory: &Trajectory, settings: &SpectrumSettings) -> Result<Map2> {
    let dt = sample_interval_s(trajectory)?;
    let mut plan = SpectrumPlan::new(trajectory.len(), dt, settings)?;
    let frequencies = plan.frequencies_hz();
    let n_contacts = trajectory.n_contacts();
    let mut data = Vec::with_capacity(n_contacts * frequencies.len());
    for c in 0..n_contacts {
        data.extend(plan.amplitudes(&trajectory.contact_force_n(c))?);
    }
    Map2::new(
        Axis::index("contact", n_contacts),
        Axis::new("frequency", "Hz", frequencies),
        format!("force {}", settings.scaling.label("N").0),
        settings.scaling.label("N").1,
        data,
    )
}
