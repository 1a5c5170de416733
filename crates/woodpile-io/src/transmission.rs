//! The output directory of `woodpile transmission` (docs/physics.md §15): the spectrum as CSV and
//! `.npy` beside the finite chain's linear response, and `transmission.json` with the settings,
//! any damping added for the measurement, the Bloch prediction, the measured and linear stop bands
//! and the edge table. Written into a staged directory; `transmission.json` last.

use crate::atomic::io_err;
use crate::error::Error;
use crate::rundir::write_npy;
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::path::Path;
use woodpile::analysis::{TransmissionSettings, TransmissionSpectrum};

/// Files a transmission directory holds (for the staged directory's overwrite policy).
pub const TRANSMISSION_FILES: &[&str] = &[
    "transmission.json",
    "transmission.csv",
    "frequency_hz.npy",
    "transmission.npy",
    "transmission_db.npy",
    "linear_transmission_db.npy",
    "transmission.png",
    "transmission.svg",
];

/// The file whose presence marks a complete transmission directory.
pub const TRANSMISSION_MARKER: &str = "transmission.json";

/// A frequency band; `upper_hz` is null for a gap that never closes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BandJson {
    /// Lower edge \[Hz\].
    pub lower_hz: f64,
    /// Upper edge \[Hz\] (null: unbounded).
    pub upper_hz: Option<f64>,
}

/// A predicted edge and the nearest measured one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EdgeJson {
    /// Bloch prediction \[Hz\].
    pub predicted_hz: f64,
    /// Nearest measured stop-band edge \[Hz\].
    pub measured_hz: Option<f64>,
    /// measured / predicted − 1.
    pub relative_error: Option<f64>,
}

/// One edge of the finite chain's linear stop bands against the measured and the Bloch edges.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EdgeRowJson {
    /// Edge of a stop band of the linear prediction (the finite preloaded chain, the same
    /// damping, bins and level) \[Hz\].
    pub linear_hz: f64,
    /// Nearest measured stop-band edge \[Hz\].
    pub measured_hz: Option<f64>,
    /// Nearest Bloch gap edge of the infinite lattice \[Hz\] (homogeneous chains only).
    pub bloch_hz: Option<f64>,
    /// measured / linear − 1.
    pub error_vs_linear: Option<f64>,
    /// measured / Bloch − 1.
    pub error_vs_bloch: Option<f64>,
}

/// `transmission.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TransmissionJson {
    /// `woodpile`.
    pub tool: String,
    /// Version of woodpile that wrote it.
    pub version: String,
    /// Scenario name.
    pub scenario: String,
    /// Static force on the top element F_p \[N\].
    pub preload_n: f64,
    /// Chirp amplitude \[N\].
    pub amplitude_n: f64,
    /// Chirp and spectrum range \[Hz\].
    pub start_hz: f64,
    /// Chirp and spectrum range \[Hz\].
    pub end_hz: f64,
    /// Frequency resolution \[Hz\].
    pub resolution_hz: f64,
    /// Level below which a frequency is in a measured stop band \[dB\].
    pub stop_band_threshold_db: f64,
    /// Measured stop bands \[Hz\].
    pub measured_stop_bands: Vec<BandJson>,
    /// Predicted pass bands (homogeneous chains only).
    pub predicted_pass_bands: Option<Vec<BandJson>>,
    /// Predicted gaps (homogeneous chains only).
    pub predicted_gaps: Option<Vec<BandJson>>,
    /// Predicted edges in range against the measured ones.
    pub edges: Vec<EdgeJson>,
    /// On-site damping time τ added for the measurement to a chain without damping \[s\] (null:
    /// the chain's own damping, or none).
    pub added_damping_time_s: Option<f64>,
    /// Stop bands of the finite chain's linear prediction \[Hz\].
    pub linear_stop_bands: Vec<BandJson>,
    /// Every edge of the linear prediction against the measured and the Bloch edges.
    pub edge_table: Vec<EdgeRowJson>,
    /// Energy balance of the driven run (relative).
    pub energy_max_relative_error: f64,
    /// Wall-clock time of the run \[s\].
    pub wall_time_s: f64,
}

fn bands(list: &[(f64, f64)]) -> Vec<BandJson> {
    list.iter()
        .map(|&(lower_hz, hi)| BandJson {
            lower_hz,
            upper_hz: hi.is_finite().then_some(hi),
        })
        .collect()
}

impl TransmissionJson {
    /// The record of a measured spectrum.
    pub fn new(
        scenario: &str,
        t: &TransmissionSpectrum,
        settings: &TransmissionSettings,
        threshold_db: f64,
    ) -> Self {
        TransmissionJson {
            tool: "woodpile".into(),
            version: crate::VERSION.into(),
            scenario: scenario.into(),
            preload_n: t.preload_n,
            amplitude_n: t.amplitude_n,
            start_hz: settings.start_hz,
            end_hz: settings.end_hz,
            resolution_hz: settings.resolution_hz,
            stop_band_threshold_db: threshold_db,
            measured_stop_bands: bands(&t.stop_bands_hz(threshold_db)),
            predicted_pass_bands: t.prediction.as_ref().map(|p| bands(&p.pass_bands_hz)),
            predicted_gaps: t.prediction.as_ref().map(|p| bands(&p.gaps_hz)),
            edges: t
                .compare_edges(threshold_db)
                .iter()
                .map(|e| EdgeJson {
                    predicted_hz: e.predicted_hz,
                    measured_hz: e.measured_hz,
                    relative_error: e.relative_error(),
                })
                .collect(),
            added_damping_time_s: t.added_damping_time_s,
            linear_stop_bands: bands(&t.linear_stop_bands_hz(threshold_db)),
            edge_table: t
                .edge_table(threshold_db)
                .iter()
                .map(|e| EdgeRowJson {
                    linear_hz: e.linear_hz,
                    measured_hz: e.measured_hz,
                    bloch_hz: e.bloch_hz,
                    error_vs_linear: e.error_vs_linear(),
                    error_vs_bloch: e.error_vs_bloch(),
                })
                .collect(),
            energy_max_relative_error: t.run.energy.max_relative_error,
            wall_time_s: t.run.wall_time_s,
        }
    }
}

fn hz_band(lo: f64, hi: Option<f64>) -> String {
    match hi {
        Some(hi) => format!("{:.3}–{:.3} kHz", lo * 1e-3, hi * 1e-3),
        None => format!("above {:.3} kHz", lo * 1e-3),
    }
}

impl TransmissionJson {
    /// What a terminal shows: settings, measured stop bands, predicted gaps, each edge
    /// compared, the energy balance and the output directory `dir`.
    pub fn summary_text(&self, dir: &Path) -> String {
        let mut o = format!(
            "transmission {}: F_p = {} N, chirp {:.3e} N, {}–{} Hz at {} Hz resolution\n",
            self.scenario,
            self.preload_n,
            self.amplitude_n,
            self.start_hz,
            self.end_hz,
            self.resolution_hz
        );
        let measured: Vec<String> = self
            .measured_stop_bands
            .iter()
            .map(|b| hz_band(b.lower_hz, b.upper_hz))
            .collect();
        o.push_str(&format!(
            "measured     stop bands (T < {} dB): {}\n",
            self.stop_band_threshold_db,
            if measured.is_empty() {
                "none".into()
            } else {
                measured.join(", ")
            }
        ));
        if let Some(tau) = self.added_damping_time_s {
            o.push_str(&format!("damping      the chain has none: on-site τ = {tau} s added for the measurement and the prediction (--damping-time-s; 0 measures it lossless)\n"));
        }
        let linear: Vec<String> = self
            .linear_stop_bands
            .iter()
            .map(|b| hz_band(b.lower_hz, b.upper_hz))
            .collect();
        o.push_str(&format!(
            "linear       stop bands of the finite chain: {}\n",
            if linear.is_empty() {
                "none".into()
            } else {
                linear.join(", ")
            }
        ));
        match &self.predicted_gaps {
            Some(gaps) => {
                let g: Vec<String> = gaps.iter().map(|b| hz_band(b.lower_hz, b.upper_hz)).collect();
                o.push_str(&format!("predicted    gaps (Bloch, infinite chain): {}\n", g.join(", ")));
            }
            None => o.push_str("predicted    no Bloch gaps: the chain is not homogeneous (one cell, one beta, no gravity)\n"),
        }
        o.push_str(&self.edge_table_text());
        o.push_str(&format!(
            "energy       max relative error {:.2e}; {:.2} s wall time\noutput       {}\n",
            self.energy_max_relative_error,
            self.wall_time_s,
            dir.display()
        ));
        o
    }
}

impl TransmissionJson {
    /// The edge table: each linear edge, the measured one against it and the Bloch one, and a
    /// warning with the fix when a measured edge is more than 1 % off its linear prediction.
    fn edge_table_text(&self) -> String {
        let pct = |e: Option<f64>| e.map_or("–".to_string(), |e| format!("{:+.2} %", 100.0 * e));
        let hz = |f: Option<f64>| f.map_or("–".to_string(), |f| format!("{f:.1}"));
        let mut o = String::new();
        if !self.edge_table.is_empty() {
            o.push_str("edges [Hz]   linear     measured   vs linear  Bloch      vs Bloch\n");
        }
        for e in &self.edge_table {
            o.push_str(&format!(
                "             {:<10.1} {:<10} {:<10} {:<10} {}\n",
                e.linear_hz,
                hz(e.measured_hz),
                pct(e.error_vs_linear),
                hz(e.bloch_hz),
                pct(e.error_vs_bloch)
            ));
        }
        let off = self
            .edge_table
            .iter()
            .filter(|e| e.error_vs_linear.is_none_or(|x| x.abs() > 0.01))
            .count();
        if off > 0 {
            o.push_str(&format!("warning      {off} measured edge(s) missing or more than 1 % off the linear prediction: the record (1/Δf = {:.3} s) is too short for the damping to end the response, or the bins too coarse; halve --resolution-hz, or damp a lossless chain (docs/physics.md §15)\n", 1.0 / self.resolution_hz));
        }
        o
    }
}

/// Writes every file of a transmission directory into `dir` (`transmission.json` last).
pub fn write_transmission(
    dir: &Path,
    record: &TransmissionJson,
    t: &TransmissionSpectrum,
) -> Result<(), Error> {
    let csv_path = dir.join("transmission.csv");
    let csv_err = |e: csv::Error| io_err(&csv_path)(std::io::Error::other(e));
    let mut w = csv::Writer::from_path(&csv_path).map_err(csv_err)?;
    w.write_record([
        "frequency_hz",
        "drive_amplitude_n",
        "wall_amplitude_n",
        "transmission",
        "transmission_db",
        "linear_transmission_db",
    ])
    .map_err(csv_err)?;
    for k in 0..t.frequencies_hz.len() {
        let row = [
            t.frequencies_hz[k],
            t.drive_amplitude_n[k],
            t.wall_amplitude_n[k],
            t.transmission[k],
            t.transmission_db[k],
            t.linear_transmission_db[k],
        ];
        w.write_record(row.iter().map(|v| format!("{v:e}")))
            .map_err(csv_err)?;
    }
    w.flush().map_err(io_err(&csv_path))?;
    let n = t.frequencies_hz.len() as u64;
    write_npy(&dir.join("frequency_hz.npy"), &[n], &t.frequencies_hz)?;
    write_npy(&dir.join("transmission.npy"), &[n], &t.transmission)?;
    write_npy(&dir.join("transmission_db.npy"), &[n], &t.transmission_db)?;
    write_npy(
        &dir.join("linear_transmission_db.npy"),
        &[n],
        &t.linear_transmission_db,
    )?;
    let path = dir.join(TRANSMISSION_MARKER);
    let mut file = std::io::BufWriter::new(std::fs::File::create(&path).map_err(io_err(&path))?);
    serde_json::to_writer_pretty(&mut file, record)
        .map_err(|e| io_err(&path)(std::io::Error::other(e)))?;
    writeln!(file)
        .and_then(|_| file.flush())
        .map_err(io_err(&path))
}
