//! Cells and analysis (`woodpile.analysis`): unit cells, effective mass, band gaps, spectra and
//! transmission spectra.

use crate::errors::{core_err, py_err, Failure, Kind};
use numpy::PyArray1;
use pyo3::prelude::*;
use std::path::PathBuf;
use woodpile::analysis::{BandStructure, EffectiveMassCurve};
use woodpile_io::scenario::{resolve, Scenario};

/// Two NumPy vectors of the same length.
type ArrayPair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The paper's Table 1 cell of a rod length, or a rod's cell from beam theory: (primary mass
/// [kg], resonator masses [kg], resonator stiffnesses [N/m]).
#[pyfunction]
#[pyo3(signature = (length_mm, diameter_mm=None, material=None, modes=None))]
fn cell(
    length_mm: f64,
    diameter_mm: Option<f64>,
    material: Option<String>,
    modes: Option<usize>,
) -> PyResult<(f64, Vec<f64>, Vec<f64>)> {
    let table1 = length_mm.fract() == 0.0
        && diameter_mm.is_none()
        && material.is_none()
        && modes.is_none()
        && woodpile::TABLE1_LENGTHS_MM.contains(&(length_mm as u32));
    let cell = if table1 {
        woodpile::UnitCell::table1(length_mm as u32).map_err(core_err)?
    } else {
        let request = woodpile_io::cells::RodRequest {
            length_mm,
            diameter_mm: diameter_mm.unwrap_or(woodpile::defaults::ROD_DIAMETER_MM),
            inner_diameter_mm: None,
            material: material.unwrap_or_else(|| woodpile::defaults::ELEMENT_MATERIAL.into()),
            modes,
            reduction: woodpile_io::scenario::ReductionSpec::PoleZero,
        };
        let d = woodpile_io::cells::derive(&request, &|k: &str| k.to_string()).map_err(py_err)?;
        return Ok((
            d.primary_mass_g * 1e-3,
            d.resonators.iter().map(|r| r.mass_g * 1e-3).collect(),
            d.resonators
                .iter()
                .map(|r| r.stiffness_kn_per_mm * 1e6)
                .collect(),
        ));
    };
    Ok((
        cell.primary_mass_kg,
        cell.resonators.iter().map(|r| r.mass_kg).collect(),
        cell.resonators
            .iter()
            .map(|r| r.stiffness_n_per_m)
            .collect(),
    ))
}

fn unit_cell(
    primary_kg: f64,
    masses_kg: &[f64],
    stiffnesses: &[f64],
) -> PyResult<woodpile::UnitCell> {
    let resonators = masses_kg
        .iter()
        .zip(stiffnesses)
        .map(|(&mass_kg, &stiffness_n_per_m)| woodpile::Resonator {
            mass_kg,
            stiffness_n_per_m,
        })
        .collect();
    woodpile::UnitCell::new(primary_kg, resonators).map_err(core_err)
}

/// M_eff(2πf)/M_total of a cell at `frequencies_hz` (real and imaginary parts; the resonators
/// damped at `ratio`, by default the scenario's default `damping.resonator_ratio`).
#[pyfunction]
#[pyo3(signature = (primary_kg, masses_kg, stiffnesses, frequencies_hz, ratio=None))]
fn effective_mass<'py>(
    py: Python<'py>,
    primary_kg: f64,
    masses_kg: Vec<f64>,
    stiffnesses: Vec<f64>,
    frequencies_hz: Vec<f64>,
    ratio: Option<f64>,
) -> PyResult<ArrayPair<'py>> {
    let cell = unit_cell(primary_kg, &masses_kg, &stiffnesses)?;
    let ratio = ratio.unwrap_or(woodpile::Damping::default().resonator_ratio);
    let c = EffectiveMassCurve::damped(&cell, &frequencies_hz, ratio).map_err(core_err)?;
    Ok((
        PyArray1::from_vec(py, c.normalised_mass),
        PyArray1::from_vec(py, c.normalised_loss),
    ))
}

/// Pass bands and gaps [Hz] of a homogeneous chain of a cell with contact coefficient β under a
/// static force F_p: (pass bands, gaps), each a list of (lower, upper); an open gap's upper edge
/// is infinite.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn band_gaps(
    primary_kg: f64,
    masses_kg: Vec<f64>,
    stiffnesses: Vec<f64>,
    beta: f64,
    precompression_n: f64,
) -> PyResult<(Vec<(f64, f64)>, Vec<(f64, f64)>)> {
    let cell = unit_cell(primary_kg, &masses_kg, &stiffnesses)?;
    let b = BandStructure::homogeneous(&cell, beta, precompression_n).map_err(core_err)?;
    Ok((b.pass_bands_hz, b.gaps_hz))
}

/// One-sided spectrum of a uniformly sampled signal: (frequencies [Hz], values). `scaling`:
/// "fourier" (|F̂(f)| in unit·s, independent of the record length for a transient) or
/// "amplitude" (the sine amplitude, for steady signals).
#[pyfunction]
fn spectrum<'py>(
    py: Python<'py>,
    signal: Vec<f64>,
    sample_interval_s: f64,
    scaling: &str,
) -> PyResult<ArrayPair<'py>> {
    let scaling = match scaling {
        "fourier" => woodpile::analysis::Scaling::FourierMagnitude,
        "amplitude" => woodpile::analysis::Scaling::Amplitude,
        other => {
            return Err(py_err(woodpile_io::Error::invalid(
                "scaling",
                other,
                "\"fourier\" (Fourier-transform magnitude, for transients) or \"amplitude\" (sine amplitude, for steady signals)",
            )))
        }
    };
    let settings = woodpile::analysis::SpectrumSettings {
        scaling,
        ..Default::default()
    };
    let s = woodpile::Spectrum::of(&signal, sample_interval_s, &settings).map_err(core_err)?;
    Ok((
        PyArray1::from_vec(py, s.frequencies_hz),
        PyArray1::from_vec(py, s.amplitudes),
    ))
}

/// The transmission spectrum of a scenario's preloaded chain (docs/physics.md §15), GIL
/// released: ((frequencies [Hz], T), (T [dB], the finite chain's linear T [dB]),
/// `transmission.json` as JSON text). `damping_time_s`: as `woodpile transmission
/// --damping-time-s` (None: τ = 20 ms added to a chain without damping; 0: none).
/// Each setting left None takes the library's default (`TransmissionSettings::standard()`,
/// `woodpile::defaults::TRANSMISSION_STOP_DB`).
#[pyfunction]
#[pyo3(signature = (text, base_dir, name, start_hz=None, end_hz=None, resolution_hz=None, relative_amplitude=None, threshold_db=None, damping_time_s=None))]
#[allow(clippy::too_many_arguments)]
fn transmission<'py>(
    py: Python<'py>,
    text: &str,
    base_dir: PathBuf,
    name: &str,
    start_hz: Option<f64>,
    end_hz: Option<f64>,
    resolution_hz: Option<f64>,
    relative_amplitude: Option<f64>,
    threshold_db: Option<f64>,
    damping_time_s: Option<f64>,
) -> PyResult<(ArrayPair<'py>, ArrayPair<'py>, String)> {
    use woodpile::analysis::TransmissionSettings;
    let scenario = Scenario::parse(text).map_err(py_err)?;
    let resolved = resolve(&scenario, &base_dir).map_err(py_err)?;
    let standard = TransmissionSettings::standard();
    let settings = TransmissionSettings {
        start_hz: start_hz.unwrap_or(standard.start_hz),
        end_hz: end_hz.unwrap_or(standard.end_hz),
        resolution_hz: resolution_hz.unwrap_or(standard.resolution_hz),
        relative_amplitude: relative_amplitude.unwrap_or(standard.relative_amplitude),
        method: resolved.settings.method,
        measurement_damping_time_s: TransmissionSettings::measurement_damping_for(
            &resolved.chain,
            damping_time_s,
        )
        .map_err(keyword_error)?,
        ..standard
    };
    settings.validate().map_err(keyword_error)?;
    let threshold_db = threshold_db.unwrap_or(woodpile::defaults::TRANSMISSION_STOP_DB);
    let (t, record) = crate::interrupt::detach_interruptibly(py, || {
        let t = woodpile::analysis::transmission(&resolved.chain, &settings).map_err(core_err)?;
        let record =
            woodpile_io::transmission::TransmissionJson::new(name, &t, &settings, threshold_db);
        Ok::<_, PyErr>((t, record))
    })?;
    let json = serde_json::to_string(&record)
        .map_err(|e| PyErr::from(Failure::new(Kind::Run, format!("transmission.json: {e}"))))?;
    Ok((
        (
            PyArray1::from_vec(py, t.frequencies_hz),
            PyArray1::from_vec(py, t.transmission),
        ),
        (
            PyArray1::from_vec(py, t.transmission_db),
            PyArray1::from_vec(py, t.linear_transmission_db),
        ),
        json,
    ))
}

/// A transmission setting's error under its keyword (`transmission.resolution_hz` is the
/// argument `resolution_hz`).
fn keyword_error(e: woodpile::Error) -> PyErr {
    match e {
        woodpile::Error::InvalidParameter {
            field,
            value,
            reason,
        } if field.starts_with("transmission.") => {
            Failure::invalid(&field["transmission.".len()..], value, reason).into()
        }
        other => core_err(other),
    }
}

/// Adds this module's functions to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(cell, m)?)?;
    m.add_function(wrap_pyfunction!(effective_mass, m)?)?;
    m.add_function(wrap_pyfunction!(band_gaps, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(transmission, m)?)?;
    Ok(())
}
