//! `woodpile transmission`: the transmission spectrum of a scenario's chain under its preload,
//! with the Bloch prediction for a homogeneous chain (docs/physics.md §15).

use super::simulate::load_scenario;
use super::Context;
use crate::CliError;
use std::path::{Path, PathBuf};
use woodpile::analysis::{transmission, TransmissionSettings};
use woodpile::defaults;
use woodpile_io::atomic::Staging;
use woodpile_io::scenario::resolve;
use woodpile_io::transmission::{
    write_transmission, TransmissionJson, TRANSMISSION_FILES, TRANSMISSION_MARKER,
};

/// Arguments of `woodpile transmission`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// Scenario file (TOML): its chain, wall, damping, preload and [run] integrator are used;
    /// its excitation is replaced by the chirp.
    #[arg(value_name = "SCENARIO.toml", conflicts_with = "scenario")]
    pub file: Option<PathBuf>,
    /// A built-in scenario instead (e.g. `transmission-80mm`).
    #[arg(long, value_name = "NAME")]
    pub scenario: Option<String>,
    /// Output directory (default: ./runs/NAME-transmission).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Replace the files of an earlier transmission run in --out.
    #[arg(long)]
    pub overwrite: bool,
    /// Lowest frequency (Hz).
    #[arg(long, default_value_t = defaults::TRANSMISSION_START_HZ)]
    pub start_hz: f64,
    /// Highest frequency (Hz).
    #[arg(long, default_value_t = defaults::TRANSMISSION_END_HZ)]
    pub end_hz: f64,
    /// Frequency resolution (Hz); the driven run lasts its inverse.
    #[arg(long, default_value_t = defaults::TRANSMISSION_RESOLUTION_HZ)]
    pub resolution_hz: f64,
    /// Chirp amplitude as a fraction of the preload force.
    #[arg(long, default_value_t = defaults::TRANSMISSION_RELATIVE_AMPLITUDE)]
    pub relative_amplitude: f64,
    /// Level (dB) below which a frequency counts as in a measured stop band.
    #[arg(long, default_value_t = defaults::TRANSMISSION_STOP_DB, allow_negative_numbers = true)]
    pub threshold_db: f64,
}

/// Runs `woodpile transmission`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let loaded = load_scenario(args.file.as_ref(), args.scenario.as_deref())?;
    let resolved = resolve(&loaded.scenario, &loaded.base_dir)?;
    for warning in &resolved.warnings {
        eprintln!("warning: {warning}");
    }
    if resolved.chain.damping().is_lossless() {
        eprintln!("warning: the chain has no damping: its response rings past the end of the record and leaks into the gaps; add e.g. [damping] on_site_time_s = 0.02 (docs/physics.md §15)");
    }
    let settings = TransmissionSettings {
        start_hz: args.start_hz,
        end_hz: args.end_hz,
        resolution_hz: args.resolution_hz,
        relative_amplitude: args.relative_amplitude,
        method: resolved.settings.method,
        ..TransmissionSettings::standard()
    };
    settings.validate()?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new("runs").join(format!("{}-transmission", loaded.name)));
    let staging = Staging::prepare(&out, args.overwrite)?;
    let spectrum = transmission(&resolved.chain, &settings)?;
    let record = TransmissionJson::new(&loaded.name, &spectrum, &settings, args.threshold_db);
    write_transmission(staging.path(), &record, &spectrum)?;
    let title = format!(
        "{}: transmission, F_p = {} N",
        loaded.name, spectrum.preload_n
    );
    woodpile_plot::transmission(
        &spectrum,
        args.threshold_db,
        &title,
        &staging.path().join("transmission"),
    )
    .map_err(woodpile_io::Error::from)?;
    let dir = staging.commit(TRANSMISSION_FILES, TRANSMISSION_MARKER)?;
    if !ctx.quiet {
        print!("{}", summary_text(&record, &dir));
    }
    Ok(())
}

fn hz_band(lo: f64, hi: Option<f64>) -> String {
    match hi {
        Some(hi) => format!("{:.3}–{:.3} kHz", lo * 1e-3, hi * 1e-3),
        None => format!("above {:.3} kHz", lo * 1e-3),
    }
}

/// What the terminal shows.
fn summary_text(r: &TransmissionJson, dir: &Path) -> String {
    let mut o = format!(
        "transmission {}: F_p = {} N, chirp {:.3e} N, {}–{} Hz at {} Hz resolution\n",
        r.scenario, r.preload_n, r.amplitude_n, r.start_hz, r.end_hz, r.resolution_hz
    );
    let measured: Vec<String> = r
        .measured_stop_bands
        .iter()
        .map(|b| hz_band(b.lower_hz, b.upper_hz))
        .collect();
    o.push_str(&format!(
        "measured     stop bands (T < {} dB): {}\n",
        r.stop_band_threshold_db,
        if measured.is_empty() {
            "none".into()
        } else {
            measured.join(", ")
        }
    ));
    match &r.predicted_gaps {
        Some(gaps) => {
            let g: Vec<String> = gaps
                .iter()
                .map(|b| hz_band(b.lower_hz, b.upper_hz))
                .collect();
            o.push_str(&format!("predicted    gaps (Bloch): {}\n", g.join(", ")));
            for e in &r.edges {
                match (e.measured_hz, e.relative_error) {
                    (Some(m), Some(err)) => o.push_str(&format!(
                        "edge         predicted {:.1} Hz, measured {m:.1} Hz ({:+.2} %)\n",
                        e.predicted_hz,
                        100.0 * err
                    )),
                    _ => o.push_str(&format!(
                        "edge         predicted {:.1} Hz, no measured stop band\n",
                        e.predicted_hz
                    )),
                }
            }
        }
        None => o.push_str(
            "predicted    none: the chain is not homogeneous (one cell, one beta, no gravity)\n",
        ),
    }
    o.push_str(&format!(
        "energy       max relative error {:.2e}; {:.2} s wall time\noutput       {}\n",
        r.energy_max_relative_error,
        r.wall_time_s,
        dir.display()
    ));
    o
}
