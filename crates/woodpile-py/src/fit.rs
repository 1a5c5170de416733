//! Calibration (`woodpile.fit`): a fit file's parameters fitted to its measured signals, with
//! uncertainties; the same file format, checks and outputs as `woodpile fit`.

use crate::errors::{core_err, py_err, Failure};
use pyo3::prelude::*;
use std::path::PathBuf;
use woodpile::fit::{fit, predict, FitSettings};
use woodpile_io::fit::{fit_json, load, residuals_csv, write_outputs};

/// Fits the fit file at `path` on `threads` threads (default: one per core), GIL released,
/// Ctrl-C raising `KeyboardInterrupt` within a run.
/// Returns (`fit.json` as text, `residuals.csv` as text); with `out`, also writes the three
/// files there (`overwrite`: replace an earlier fit's). A fit planning more than
/// `woodpile_io::limits::MAX_FIT_RUNS` model runs is refused unless `allow_large`.
#[pyfunction]
#[pyo3(signature = (path, out=None, overwrite=false, threads=None, allow_large=false))]
fn fit_file(
    py: Python<'_>,
    path: PathBuf,
    out: Option<PathBuf>,
    overwrite: bool,
    threads: Option<usize>,
    allow_large: bool,
) -> PyResult<(String, String)> {
    crate::interrupt::detach_interruptibly(py, || {
        let setup = load(&path).map_err(py_err)?;
        woodpile_io::limits::check_fit(setup.starts, setup.max_evaluations, allow_large)
            .map_err(py_err)?;
        setup.check_signals().map_err(py_err)?;
        if let Some(dir) = &out {
            woodpile_io::fit::check_output(dir, overwrite).map_err(py_err)?;
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.unwrap_or(0))
            .build()
            .map_err(|e| Failure::invalid("threads", threads.unwrap_or(0), e.to_string()))?;
        let model = |v: &[f64]| setup.model(v);
        let problem = setup.problem(&model);
        let settings = FitSettings {
            starts: setup.starts,
            max_evaluations: setup.max_evaluations,
            seed: setup.seed,
            ..FitSettings::default()
        };
        let result = pool
            .install(|| fit(&problem, &settings))
            .map_err(core_err)?;
        let prediction = predict(&problem, &result.estimates).map_err(core_err)?;
        if let Some(dir) = &out {
            write_outputs(dir, overwrite, &setup, &result, &prediction).map_err(py_err)?;
        }
        let json = serde_json::to_string(&fit_json(&setup, &result))
            .map_err(|e| Failure::invalid("fit.json", "", e.to_string()))?;
        Ok((json, residuals_csv(&setup, &prediction)))
    })
}

/// Adds the functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fit_file, m)?)?;
    Ok(())
}
