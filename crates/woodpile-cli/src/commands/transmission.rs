//! `woodpile transmission`: the transmission spectrum of a scenario's chain under its preload,
//! with the Bloch prediction for a homogeneous chain (docs/physics.md §15).

use super::simulate::load;
use super::Context;
use crate::CliError;
use std::path::{Path, PathBuf};
use woodpile::analysis::{transmission, TransmissionSettings};
use woodpile::defaults;
use woodpile_io::atomic::Staging;
use woodpile_io::transmission::{
    write_transmission, TransmissionJson, TRANSMISSION_FILES, TRANSMISSION_MARKER,
};

/// Arguments of `woodpile transmission`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// The scenario (e.g. --scenario transmission-80mm): its chain, wall, damping, preload and
    /// `[run]` integrator are used; its excitation is replaced by the chirp.
    #[command(flatten)]
    pub source: super::simulate::Source,
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
    #[arg(long, allow_negative_numbers = true, default_value_t = defaults::TRANSMISSION_RESOLUTION_HZ)]
    pub resolution_hz: f64,
    /// Chirp amplitude as a fraction of the preload force.
    #[arg(long, default_value_t = defaults::TRANSMISSION_RELATIVE_AMPLITUDE)]
    pub relative_amplitude: f64,
    /// On-site damping time τ (s) given for the measurement to a chain without damping, so that
    /// its response ends within the record [default: 0.02]; 0 measures the lossless chain. A
    /// chain with its own damping keeps it.
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub damping_time_s: Option<f64>,
    /// Level (dB) below which a frequency counts as in a measured stop band.
    #[arg(long, default_value_t = defaults::TRANSMISSION_STOP_DB, allow_negative_numbers = true)]
    pub threshold_db: f64,
}

/// Runs `woodpile transmission`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    if !(args.threshold_db.is_finite() && args.threshold_db < 0.0) {
        // A stop band is where less comes out than goes in: a threshold at or above 0 dB would
        // count pass bands (and most of the spectrum) as gaps.
        return Err(CliError::invalid(
            "--threshold-db",
            args.threshold_db,
            "must be a negative level in dB (e.g. -20): a stop band is where the transmitted amplitude falls below the driven one",
        ));
    }
    let loaded = load(&args.source, "transmission")?;
    let resolved = loaded.resolve()?;
    let lossless = resolved.chain.damping().is_lossless();
    let measurement_damping_time_s =
        TransmissionSettings::measurement_damping_for(&resolved.chain, args.damping_time_s)
            .map_err(option_error)?;
    if lossless && measurement_damping_time_s.is_none() {
        crate::out::eprintln(format_args!("warning: measuring the lossless chain (--damping-time-s 0): its response rings past the end of the record and leaks into the gaps (docs/physics.md §15)"));
    }
    let settings = TransmissionSettings {
        start_hz: args.start_hz,
        end_hz: args.end_hz,
        resolution_hz: args.resolution_hz,
        relative_amplitude: args.relative_amplitude,
        method: resolved.settings.method,
        measurement_damping_time_s,
        ..TransmissionSettings::standard()
    };
    settings.validate().map_err(option_error)?;
    // The driven run lasts 1/Δf: refused up front when it would exceed the step limit.
    let run = woodpile::RunSettings {
        duration_s: settings.duration_s(),
        method: settings.method,
        sample_interval_s: settings.sample_interval_s,
    };
    if let Some(steps) = run.estimated_steps().filter(|&n| n > defaults::MAX_STEPS) {
        return Err(CliError::invalid(
            "--resolution-hz",
            args.resolution_hz,
            format!("the record of 1/Δf = {:.3e} s would take {steps:.3e} steps (at most {:.0e}): choose a coarser resolution or a larger run.time_step_s", run.duration_s, defaults::MAX_STEPS as f64),
        ));
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new("runs").join(format!("{}-transmission", loaded.name)));
    let staging = Staging::prepare_marked(&out, args.overwrite, TRANSMISSION_MARKER)?;
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
        crate::out::print(record.summary_text(&dir))?;
    }
    Ok(())
}

/// The settings' errors in this command's words: `transmission.resolution_hz` is the option
/// `--resolution-hz`.
fn option_error(e: woodpile::Error) -> CliError {
    match e {
        woodpile::Error::InvalidParameter {
            field,
            value,
            reason,
        } => match field.strip_prefix("transmission.") {
            Some(key) => CliError::invalid(format!("--{}", key.replace('_', "-")), value, reason),
            None => CliError::invalid(field, value, reason),
        },
        other => other.into(),
    }
}
