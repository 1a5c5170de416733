//! The outputs of a fit: `fit.json` (estimates, errors, correlations, cost, residual RMS, starts,
//! warnings), `fitted.toml` (the scenario with the estimates), `residuals.csv` (measured, model
//! and residual of every row).

use super::FitSetup;
use crate::atomic::{io_err, write_atomic};
use crate::error::Error;
use serde_json::{json, Map, Value};
use std::fmt::Write as _;
use std::path::Path;
use woodpile::fit::{FitResult, Prediction};

/// The file that marks a directory as the output of a fit (written last).
pub const FIT_MARKER: &str = "fit.json";

/// The files a fit writes.
const FILES: [&str; 3] = ["fitted.toml", "residuals.csv", FIT_MARKER];

/// Checks that `dir` may take a fit's outputs: absent or empty, or an earlier fit's with
/// `overwrite`; anything else is refused (nothing woodpile did not write is touched).
pub fn check_output(dir: &Path, overwrite: bool) -> Result<(), Error> {
    match std::fs::read_dir(dir) {
        Ok(mut entries) => {
            if entries.next().is_none() {
                Ok(())
            } else if dir.join(FIT_MARKER).is_file() {
                if overwrite {
                    Ok(())
                } else {
                    Err(Error::OutputExists {
                        path: dir.to_path_buf(),
                    })
                }
            } else {
                Err(Error::OutputNotEmpty {
                    path: dir.to_path_buf(),
                    marker: FIT_MARKER,
                })
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(io_err(dir)(e)),
    }
}

/// Writes the three files into `dir` (created if missing), each atomically, `fit.json` last.
/// `prediction` is the model at the estimates.
pub fn write_outputs(
    dir: &Path,
    overwrite: bool,
    setup: &FitSetup,
    result: &FitResult,
    prediction: &Prediction,
) -> Result<(), Error> {
    check_output(dir, overwrite)?;
    std::fs::create_dir_all(dir).map_err(io_err(dir))?;
    let n = setup.parameters.len();
    let scenario = setup.scenario_at(&result.estimates[..n])?;
    let shift = result.estimates.get(n).copied().unwrap_or(0.0);
    let header = format!(
        "# The scenario of {} with the fitted values (woodpile fit). The measured signals are this\n# model's at t - time_shift_s, time_shift_s = {shift:e} s.\n",
        setup.path.display()
    );
    write_atomic(dir, FILES[0], (header + &scenario.to_toml()).as_bytes())?;
    write_atomic(dir, FILES[1], residuals_csv(setup, prediction).as_bytes())?;
    let text = serde_json::to_string_pretty(&fit_json(setup, result))
        .map_err(|e| Error::invalid("fit.json", "", e.to_string()))?;
    write_atomic(dir, FILES[2], text.as_bytes())
}

/// A number, or null where it is not finite (JSON has no infinity or NaN).
fn number(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// The contents of `fit.json`.
pub fn fit_json(setup: &FitSetup, result: &FitResult) -> Value {
    let u = result.uncertainty.as_ref();
    let parameters: Vec<Value> = result
        .names
        .iter()
        .enumerate()
        .map(|(k, name)| {
            json!({
                "key": name,
                "estimate": result.estimates[k],
                "std_error": u.and_then(|u| u.std_errors[k]).map_or(Value::Null, number),
                "ci95": u.and_then(|u| u.ci95[k]).map_or(Value::Null, |c| json!([number(c[0]), number(c[1])])),
                "at_bound": result.at_bound[k],
            })
        })
        .collect();
    let correlation: Value = u.map_or(Value::Null, |u| {
        Value::Array(
            u.correlation
                .iter()
                .map(|row| Value::Array(row.iter().map(|&c| number(c)).collect()))
                .collect(),
        )
    });
    let residual_rms: Vec<Value> = setup
        .measurements
        .iter()
        .zip(&setup.sources)
        .zip(&result.residual_rms)
        .map(|((m, (file, column)), rms)| {
            json!({"file": file, "signal": column, "output": m.output.name(), "unit": m.output.unit(), "rms": number(*rms)})
        })
        .collect();
    let named = |values: &[f64]| -> Value {
        let mut map = Map::new();
        for (name, v) in result.names.iter().zip(values) {
            map.insert(name.clone(), number(*v));
        }
        Value::Object(map)
    };
    let starts: Vec<Value> = result
        .starts
        .iter()
        .map(|s| {
            json!({"initial": named(&s.initial), "estimate": named(&s.estimate), "cost": number(s.cost), "evaluations": s.evaluations, "termination": s.termination})
        })
        .collect();
    json!({
        "parameters": parameters,
        "correlation": correlation,
        "condition_number": u.map_or(Value::Null, |u| number(u.condition_number)),
        "residual_rms": residual_rms,
        "cost": number(result.cost),
        "sigma": u.map_or(Value::Null, |u| number(u.sigma)),
        "degrees_of_freedom": u.map(|u| u.degrees_of_freedom),
        "evaluations": result.evaluations,
        "starts": starts,
        "warnings": result.warnings,
        "interrupted": result.interrupted,
    })
}

/// `residuals.csv`: one row per measured row: file, signal, time_s, measured, model,
/// residual = model − measured (the signal's unit), in_window (1 or 0).
pub fn residuals_csv(setup: &FitSetup, prediction: &Prediction) -> String {
    let (t0, t1) = setup.window_s.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    let mut out = String::from("file,signal,time_s,measured,model,residual,in_window\n");
    for ((m, (file, column)), model) in setup
        .measurements
        .iter()
        .zip(&setup.sources)
        .zip(&prediction.values)
    {
        for ((t, measured), model) in m.times_s.iter().zip(&m.values).zip(model) {
            let inside = u8::from((t0..=t1).contains(t));
            let _ = writeln!(
                out,
                "{file},{column},{t:e},{measured:e},{model:e},{:e},{inside}",
                model - measured
            );
        }
    }
    out
}
