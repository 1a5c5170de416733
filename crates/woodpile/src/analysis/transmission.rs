//! Transmission spectra (docs/physics.md §15): a preloaded chain driven on its top element by a
//! small force chirp, the wall force compared with the drive force in frequency,
//!
//! ```text
//! T(f) = |F̂_wall(f)| / |F̂_drive(f)|,      T_dB = 20 log10 T,
//! ```
//!
//! with F̂ the Fourier transforms of the dynamic parts (total minus static) over the whole record.
//! For a linear(ised) chain starting from rest this is the magnitude of its frequency response
//! from the drive to the sensor. The chirp sweeps linearly over the first half of the record and
//! the second half lets the response ring down; its amplitude is a small fraction of the preload,
//! so no contact opens and the linearisation about the static equilibrium holds.
//!
//! For a homogeneous chain (one cell, one β, no gravity) the spectrum comes with the prediction of
//! the linearised Bloch relation 4 K_c sin²(qa/2) = ω² M_eff(ω) ([`BandStructure`]).

use super::bands::BandStructure;
use super::linear::LinearChain;
use super::spectrum::{SpectrumPlan, SpectrumSettings};
use crate::defaults;
use crate::error::{require_positive, Error, Result};
use crate::excitation::{Drive, DriveQuantity, Excitation, Signal, Sweep};
use crate::integrate::Method;
use crate::math::Libm;
use crate::model::{Chain, Damping};
use crate::record::EndForces;
use crate::simulate::{simulate, RunSettings, RunSummary};

/// What to measure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransmissionSettings {
    /// Lowest frequency of the chirp and the spectrum \[Hz\].
    pub start_hz: f64,
    /// Highest frequency \[Hz\].
    pub end_hz: f64,
    /// Frequency resolution Δf \[Hz\]: the record lasts 1/Δf.
    pub resolution_hz: f64,
    /// Chirp amplitude as a fraction of the static force on the top element.
    pub relative_amplitude: f64,
    /// Integration method.
    pub method: Method,
    /// Sample interval of the recorded forces \[s\].
    pub sample_interval_s: f64,
    /// On-site damping time τ \[s\] given for the measurement to a chain that has no damping
    /// (docs/physics.md §15: a lossless response rings past the record and fills the gaps);
    /// `None` measures such a chain as it is. A chain with any damping keeps its own.
    pub measurement_damping_time_s: Option<f64>,
}

impl TransmissionSettings {
    /// The on-site damping time added for the measurement (`measurement_damping_time_s`) when
    /// the user asked for `requested` (None: the default τ; 0: none, the lossless chain): a
    /// damping time is for a chain without damping of its own, and must be ≥ 0.
    pub fn measurement_damping_for(chain: &Chain, requested: Option<f64>) -> Result<Option<f64>> {
        let field = "transmission.damping_time_s";
        match requested {
            None => Ok(Some(defaults::TRANSMISSION_DAMPING_TIME_S)),
            Some(tau) if !(tau.is_finite() && tau >= 0.0) => Err(Error::invalid(
                field,
                tau,
                "must be a damping time in seconds > 0 (e.g. 0.02), or 0 to measure the lossless chain",
            )),
            Some(tau) if !chain.damping().is_lossless() => Err(Error::invalid(
                field,
                tau,
                "applies to a chain without damping; this scenario's chain has its own [damping] (change damping.on_site_time_s there)",
            )),
            Some(tau) => Ok((tau > 0.0).then_some(tau)),
        }
    }

    /// Defaults (docs/physics.md §15): 0.1–30 kHz at 10 Hz resolution (a 100 ms record), a chirp of
    /// 1 % of the preload, the paper's RK4 step, samples every 5 µs (Nyquist 100 kHz),
    /// on-site damping τ = 20 ms for a chain without damping.
    pub fn standard() -> Self {
        TransmissionSettings {
            start_hz: defaults::TRANSMISSION_START_HZ,
            end_hz: defaults::TRANSMISSION_END_HZ,
            resolution_hz: defaults::TRANSMISSION_RESOLUTION_HZ,
            relative_amplitude: defaults::TRANSMISSION_RELATIVE_AMPLITUDE,
            method: Method::paper(),
            sample_interval_s: defaults::TRANSMISSION_SAMPLE_INTERVAL_S,
            measurement_damping_time_s: Some(defaults::TRANSMISSION_DAMPING_TIME_S),
        }
    }

    /// Validates the fields (named as the command line's options).
    pub fn validate(&self) -> Result<()> {
        require_positive("transmission.start_hz", self.start_hz)?;
        require_positive("transmission.end_hz", self.end_hz)?;
        require_positive("transmission.resolution_hz", self.resolution_hz)?;
        require_positive("transmission.relative_amplitude", self.relative_amplitude)?;
        require_positive("transmission.sample_interval_s", self.sample_interval_s)?;
        if let Some(tau) = self.measurement_damping_time_s {
            require_positive("transmission.damping_time_s", tau)?;
        }
        if self.end_hz <= self.start_hz {
            return Err(Error::invalid(
                "transmission.end_hz",
                self.end_hz,
                format!("must exceed start_hz = {}", self.start_hz),
            ));
        }
        let nyquist = 0.5 / self.sample_interval_s;
        if self.end_hz > 0.5 * nyquist {
            return Err(Error::invalid(
                "transmission.sample_interval_s",
                self.sample_interval_s,
                format!(
                    "samples too sparse for end_hz = {} (need at most {:.3e} s: four samples per period)",
                    self.end_hz,
                    0.25 / self.end_hz
                ),
            ));
        }
        if self.relative_amplitude > 0.5 {
            return Err(Error::invalid(
                "transmission.relative_amplitude",
                self.relative_amplitude,
                "at most 0.5: the drive must not open the preloaded contacts",
            ));
        }
        Ok(())
    }

    /// Record length 1/Δf \[s\].
    pub fn duration_s(&self) -> f64 {
        1.0 / self.resolution_hz
    }
}

/// A measured transmission spectrum.
#[derive(Debug, Clone, PartialEq)]
pub struct TransmissionSpectrum {
    /// Frequencies f in [start, end] \[Hz\].
    pub frequencies_hz: Vec<f64>,
    /// |F̂_drive(f)| (one-sided amplitude spectrum of the drive force's dynamic part) \[N\].
    pub drive_amplitude_n: Vec<f64>,
    /// |F̂_wall(f)| \[N\].
    pub wall_amplitude_n: Vec<f64>,
    /// T(f) = |F̂_wall| / |F̂_drive|.
    pub transmission: Vec<f64>,
    /// 20 log10 T \[dB\].
    pub transmission_db: Vec<f64>,
    /// Static force on the top element F_p \[N\] and the chirp's amplitude \[N\].
    pub preload_n: f64,
    /// Chirp amplitude \[N\].
    pub amplitude_n: f64,
    /// The Bloch prediction for a homogeneous chain (None otherwise).
    pub prediction: Option<BandStructure>,
    /// |F̂_wall/F̂_drive| of the finite chain linearised about its preload, with the damping of
    /// the measurement, at `frequencies_hz` ([`LinearChain`]).
    pub linear_transmission: Vec<f64>,
    /// 20 log10 of `linear_transmission` \[dB\].
    pub linear_transmission_db: Vec<f64>,
    /// The on-site damping time τ \[s\] added for the measurement (None: the chain's own damping,
    /// or none).
    pub added_damping_time_s: Option<f64>,
    /// The run's figures of merit (energy balance included).
    pub run: RunSummary,
}

impl TransmissionSpectrum {
    /// Stop bands measured on the spectrum: runs where T_dB is below `threshold_db`, as (lower,
    /// upper) edges \[Hz\] linearly interpolated at the threshold. A run touching an end of the
    /// range ends there. Two runs apart by less than 1 % of their frequency are one band: such
    /// narrow peaks inside a gap are the record's finite length, not transmission.
    pub fn stop_bands_hz(&self, threshold_db: f64) -> Vec<(f64, f64)> {
        stop_bands_hz(&self.frequencies_hz, &self.transmission_db, threshold_db)
    }

    /// The stop bands of the linear prediction, found as [`TransmissionSpectrum::stop_bands_hz`]
    /// finds the measured ones (the same bins, level and merging).
    pub fn linear_stop_bands_hz(&self, threshold_db: f64) -> Vec<(f64, f64)> {
        stop_bands_hz(
            &self.frequencies_hz,
            &self.linear_transmission_db,
            threshold_db,
        )
    }
}

/// Runs of `t_db` below `threshold_db` over `f`, merged when closer than 1 % of their frequency.
fn stop_bands_hz(f: &[f64], t: &[f64], threshold_db: f64) -> Vec<(f64, f64)> {
    let mut merged: Vec<(f64, f64)> = Vec::new();
    for (lo, hi) in raw_stop_bands_hz(f, t, threshold_db) {
        match merged.last_mut() {
            Some(last) if lo - last.1 < 0.01 * lo => last.1 = hi,
            _ => merged.push((lo, hi)),
        }
    }
    merged
}

fn raw_stop_bands_hz(f: &[f64], t: &[f64], threshold_db: f64) -> Vec<(f64, f64)> {
    let crossing = |k: usize| {
        // Between k and k+1, where t crosses the threshold.
        let (t0, t1) = (t[k], t[k + 1]);
        f[k] + (f[k + 1] - f[k]) * (threshold_db - t0) / (t1 - t0)
    };
    let mut bands = Vec::new();
    let mut start: Option<f64> = (t.first().is_some_and(|&v| v < threshold_db)).then(|| f[0]);
    for k in 0..t.len().saturating_sub(1) {
        let (below0, below1) = (t[k] < threshold_db, t[k + 1] < threshold_db);
        if !below0 && below1 {
            start = Some(crossing(k));
        } else if below0 && !below1 {
            if let Some(s) = start.take() {
                bands.push((s, crossing(k)));
            }
        }
    }
    if let (Some(s), Some(&last)) = (start, f.last()) {
        bands.push((s, last));
    }
    bands
}

/// The edges of stop bands, less the ends of the range `f` (a band touching an end is cut there,
/// not bounded by an edge).
fn inner_edges(bands: &[(f64, f64)], f: &[f64]) -> Vec<f64> {
    let (lo, hi) = match (f.first(), f.last()) {
        (Some(&a), Some(&b)) => (a, b),
        _ => return Vec::new(),
    };
    bands
        .iter()
        .flat_map(|&(a, b)| [a, b])
        .filter(|&e| e > lo && e < hi)
        .collect()
}

fn nearest(candidates: &[f64], to: f64) -> Option<f64> {
    candidates
        .iter()
        .copied()
        .min_by(|a, b| (a - to).abs().total_cmp(&(b - to).abs()))
}

/// One edge of the finite chain's linear stop bands, with the nearest measured edge (found the
/// same way on the same bins: like with like) and the nearest Bloch edge of the infinite lattice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeRow {
    /// Edge of a stop band of the linear prediction \[Hz\].
    pub linear_hz: f64,
    /// Nearest edge of a measured stop band \[Hz\] (None: no measured stop band).
    pub measured_hz: Option<f64>,
    /// Nearest Bloch gap edge \[Hz\] (None: no prediction for this chain).
    pub bloch_hz: Option<f64>,
}

impl EdgeRow {
    /// measured / linear − 1.
    pub fn error_vs_linear(&self) -> Option<f64> {
        self.measured_hz.map(|m| m / self.linear_hz - 1.0)
    }

    /// measured / Bloch − 1.
    pub fn error_vs_bloch(&self) -> Option<f64> {
        self.measured_hz
            .zip(self.bloch_hz)
            .map(|(m, b)| m / b - 1.0)
    }
}

impl TransmissionSpectrum {
    /// The edge table at `threshold_db`: every inner edge of the linear prediction's stop bands
    /// against the nearest measured and Bloch edges.
    pub fn edge_table(&self, threshold_db: f64) -> Vec<EdgeRow> {
        let f = &self.frequencies_hz;
        let measured = inner_edges(&self.stop_bands_hz(threshold_db), f);
        let linear = inner_edges(&self.linear_stop_bands_hz(threshold_db), f);
        let bloch: Vec<f64> = self
            .prediction
            .iter()
            .flat_map(|p| p.gaps_hz.iter().flat_map(|&(a, b)| [a, b]))
            .filter(|e| e.is_finite())
            .collect();
        linear
            .into_iter()
            .map(|linear_hz| EdgeRow {
                linear_hz,
                measured_hz: nearest(&measured, linear_hz),
                bloch_hz: nearest(&bloch, linear_hz),
            })
            .collect()
    }
}

/// A predicted band edge and the nearest measured one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeComparison {
    /// Predicted edge \[Hz\].
    pub predicted_hz: f64,
    /// Nearest measured stop-band edge \[Hz\] (None when no stop band was measured).
    pub measured_hz: Option<f64>,
}

impl EdgeComparison {
    /// measured / predicted − 1.
    pub fn relative_error(&self) -> Option<f64> {
        self.measured_hz.map(|m| m / self.predicted_hz - 1.0)
    }
}

impl TransmissionSpectrum {
    /// Every finite predicted gap edge inside the measured range, with the nearest edge of the
    /// stop bands measured at `threshold_db` (empty without a prediction).
    pub fn compare_edges(&self, threshold_db: f64) -> Vec<EdgeComparison> {
        let measured: Vec<f64> = self
            .stop_bands_hz(threshold_db)
            .iter()
            .flat_map(|&(lo, hi)| [lo, hi])
            .collect();
        let (lo, hi) = match (self.frequencies_hz.first(), self.frequencies_hz.last()) {
            (Some(&a), Some(&b)) => (a, b),
            _ => return Vec::new(),
        };
        self.prediction
            .iter()
            .flat_map(|p| p.gaps_hz.iter().flat_map(|&(a, b)| [a, b]))
            .filter(|e| e.is_finite() && *e > lo && *e < hi)
            .map(|predicted_hz| EdgeComparison {
                predicted_hz,
                measured_hz: measured.iter().copied().min_by(|a, b| {
                    (a - predicted_hz)
                        .abs()
                        .total_cmp(&(b - predicted_hz).abs())
                }),
            })
            .collect()
    }
}

/// Measures the transmission spectrum of `chain`, which must carry a static force on its top
/// element (`Preload::force_n`) and stand on a wall.
pub fn transmission(
    chain: &Chain,
    settings: &TransmissionSettings,
) -> Result<TransmissionSpectrum> {
    settings.validate()?;
    let added_damping_time_s = settings
        .measurement_damping_time_s
        .filter(|_| chain.damping().is_lossless());
    let damped;
    let chain = match added_damping_time_s {
        Some(tau) => {
            damped = chain.clone().with_damping(Damping {
                on_site_time_s: Some(tau),
                ..Damping::default()
            })?;
            &damped
        }
        None => chain,
    };
    let preload_n = chain.preload().force_n;
    if preload_n <= 0.0 {
        return Err(Error::invalid(
            "preload.force_n",
            preload_n,
            "a transmission spectrum linearises about a precompressed chain: give the top element a static force (e.g. preload.force_n = 10)",
        ));
    }
    let duration_s = settings.duration_s();
    let amplitude_n = settings.relative_amplitude * preload_n;
    let sweep_s = 0.5 * duration_s;
    let drive = Drive {
        quantity: DriveQuantity::Force,
        signal: Signal::Chirp {
            amplitude: amplitude_n,
            start_hz: settings.start_hz,
            end_hz: settings.end_hz,
            duration_s: sweep_s,
            sweep: Sweep::Linear,
        },
        ramp_s: 0.05 * sweep_s,
    };
    let run_settings = RunSettings {
        duration_s,
        method: settings.method,
        sample_interval_s: settings.sample_interval_s,
    };
    let mut forces = EndForces::default();
    let run = simulate(chain, &Excitation::Drive(drive), &run_settings, &mut forces)?;
    let wall_static = chain
        .static_contact_forces_n()
        .last()
        .copied()
        .unwrap_or(0.0);
    let drive_dynamic: Vec<f64> = forces.load_n.iter().map(|f| f - preload_n).collect();
    let wall_dynamic: Vec<f64> = forces.wall_n.iter().map(|f| f - wall_static).collect();
    let mut plan = SpectrumPlan::new(
        drive_dynamic.len(),
        settings.sample_interval_s,
        &SpectrumSettings::default(),
    )?;
    let all_f = plan.frequencies_hz();
    let drive_all = plan.amplitudes(&drive_dynamic)?;
    let wall_all = plan.amplitudes(&wall_dynamic)?;
    let keep: Vec<usize> = (0..all_f.len())
        .filter(|&k| all_f[k] >= settings.start_hz && all_f[k] <= settings.end_hz)
        .collect();
    let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<f64>>();
    let (frequencies_hz, drive_amplitude_n, wall_amplitude_n) =
        (pick(&all_f), pick(&drive_all), pick(&wall_all));
    let transmission: Vec<f64> = wall_amplitude_n
        .iter()
        .zip(&drive_amplitude_n)
        .map(|(w, d)| w / d)
        .collect();
    let transmission_db = transmission.iter().map(|t| 20.0 * t.libm_log10()).collect();
    let linear_transmission = LinearChain::new(chain)?.transmission(&frequencies_hz);
    let linear_transmission_db = linear_transmission
        .iter()
        .map(|t| 20.0 * t.libm_log10())
        .collect();
    Ok(TransmissionSpectrum {
        frequencies_hz,
        drive_amplitude_n,
        wall_amplitude_n,
        transmission,
        transmission_db,
        preload_n,
        amplitude_n,
        prediction: homogeneous_prediction(chain)?,
        linear_transmission,
        linear_transmission_db,
        added_damping_time_s,
        run,
    })
}

/// The Bloch prediction when the chain is homogeneous: one cell, one β between elements, no
/// gravity (under gravity each contact carries a different load, so K_c varies along the chain).
pub fn homogeneous_prediction(chain: &Chain) -> Result<Option<BandStructure>> {
    let cell = &chain.elements()[0].cell;
    let betas = chain.inner_betas();
    let homogeneous = chain.elements().iter().all(|e| &e.cell == cell)
        && betas
            .windows(2)
            .all(|w| (w[0] - w[1]).abs() <= 1e-12 * w[0])
        && chain.preload().gravity_m_s2 == 0.0
        && chain.preload().force_n > 0.0;
    match (homogeneous, betas.first()) {
        (true, Some(&beta)) => Ok(Some(BandStructure::homogeneous(
            cell,
            beta,
            chain.preload().force_n,
        )?)),
        _ => Ok(None),
    }
}
