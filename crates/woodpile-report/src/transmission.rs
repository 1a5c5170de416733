//! Beyond the paper: the transmission spectrum of twenty preloaded 80 mm rods against the gaps
//! the Bloch relation predicts (docs/physics.md §15).

use super::doc::Doc;
use super::study::Setup;
use crate::Error;
use std::path::PathBuf;
use woodpile::analysis::{transmission, TransmissionSettings, TransmissionSpectrum};
use woodpile::defaults::TRANSMISSION_STOP_DB;
use woodpile::{CellModel, ChainBuilder, Damping, Method, Preload};

/// Static force on the top rod \[N\].
const PRELOAD_N: f64 = 10.0;
/// On-site damping time \[s\].
const ON_SITE_S: f64 = 0.02;

/// The spectrum and its figure.
pub struct Transmission {
    /// The measured spectrum.
    pub spectrum: TransmissionSpectrum,
    /// Its figure.
    pub files: Vec<PathBuf>,
}

/// Twenty 80 mm rods on the sensor under [`PRELOAD_N`] on the top rod with on-site damping
/// [`ON_SITE_S`], measured with the default spectrum settings (RK4 at 0.2 µs), and drawn.
pub fn run(s: &Setup) -> Result<Transmission, Error> {
    let chain = ChainBuilder::table1_rods(&[80; 20], CellModel::Resonant)?
        .preload(Preload {
            force_n: PRELOAD_N,
            gravity_m_s2: 0.0,
        })
        .damping(Damping {
            on_site_time_s: Some(ON_SITE_S),
            ..Damping::default()
        })
        .build()?;
    // 20 Hz bins: the figures docs/physics.md §15 quotes for this case.
    let settings = TransmissionSettings {
        method: Method::Rk4 { time_step_s: 2e-7 },
        resolution_hz: 20.0,
        ..TransmissionSettings::standard()
    };
    let spectrum = transmission(&chain, &settings)?;
    let files = woodpile_plot::transmission(
        &spectrum,
        TRANSMISSION_STOP_DB,
        &format!("Twenty 80 mm rods on the sensor, F_p = {PRELOAD_N} N, on-site τ = {ON_SITE_S} s"),
        &s.fig("transmission_80mm"),
    )?;
    Ok(Transmission { spectrum, files })
}

impl Transmission {
    /// The subsection: the measured band edges against the predicted ones.
    pub fn write(&self, doc: &mut Doc) {
        let t = &self.spectrum;
        let threshold = TRANSMISSION_STOP_DB;
        doc.h3("Transmission spectrum of the 80 mm chain");
        doc.p(format!(
            "Beyond the paper: twenty 80 mm rods on the sensor under a static force of {} N on the top rod, with light on-site damping (τ = {ON_SITE_S} s), driven by a force chirp of {:.2} N sweeping {:.1}–{:.0} kHz; T = |F̂_wall|/|F̂_drive| (docs/physics.md §15, `woodpile transmission`). Shaded: the gaps the linearised Bloch relation predicts for an infinite chain of this cell; a measured stop band is where T < {threshold} dB. Energy balance of the driven run: {:.1e}.",
            t.preload_n,
            t.amplitude_n,
            t.frequencies_hz.first().copied().unwrap_or(0.0) * 1e-3,
            t.frequencies_hz.last().copied().unwrap_or(0.0) * 1e-3,
            t.run.energy.max_relative_error,
        ));
        let rows = t.compare_edges(threshold).into_iter().map(|e| {
            vec![
                format!("{:.0}", e.predicted_hz),
                e.measured_hz.map_or("none".into(), |m| format!("{m:.0}")),
                e.relative_error()
                    .map_or("–".into(), |x| format!("{:+.2} %", 100.0 * x)),
            ]
        });
        doc.table(
            &[
                "predicted edge [Hz]",
                "nearest measured edge [Hz]",
                "difference",
            ],
            rows.collect(),
        );
        doc.figure(&self.files, "Transmission of twenty preloaded 80 mm rods: measured spectrum, the −20 dB stop-band level, and the predicted Bloch gaps shaded.");
    }
}
