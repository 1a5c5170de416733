//! Measured CSV files: `time_s` plus one column per signal; every problem named by file, line
//! and column.

use super::DataSpec;
use crate::error::Error;
use crate::scenario::Resolved;
use std::collections::BTreeMap;
use std::path::Path;
use woodpile::fit::{Measurement, Output};

/// Reads the columns `columns` of a measured CSV file: (times, one vector per column). Errors
/// name the file and the line: a header without `time_s` first or naming a column twice, a named
/// column that is missing, a row with more or fewer fields than the header, a value that is not
/// a number, a NaN or an empty field (a gap), times that do not increase strictly, fewer than
/// two rows.
pub fn read_signals(path: &Path, columns: &[&str]) -> Result<(Vec<f64>, Vec<Vec<f64>>), Error> {
    let file = std::fs::File::open(path).map_err(|e| Error::Read {
        path: path.to_path_buf(),
        source: e,
    })?;
    let err = |line: u64, message: String| Error::Table {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut reader = crate::table::csv_reader(file);
    let headers = reader
        .headers()
        .map_err(|e| err(1, format!("cannot read the header row: {e}")))?
        .clone();
    let names: Vec<&str> = headers.iter().collect();
    if names.first() != Some(&"time_s") {
        return Err(err(
            1,
            format!(
                "header is `{}`; its first column must be time_s",
                names.join(",")
            ),
        ));
    }
    // A column named twice would be read from its first copy, the other silently ignored.
    if let Some((j, dup)) = (1..names.len()).find_map(|j| {
        let first = names[..j].iter().position(|n| *n == names[j])?;
        Some((first, names[j]))
    }) {
        return Err(err(
            1,
            format!("names column `{dup}` twice (the {} and a later column): which one is measured is ambiguous; rename one", ordinal(j + 1)),
        ));
    }
    let mut index = Vec::new();
    for c in columns {
        match names.iter().position(|n| n == c) {
            Some(k) => index.push(k),
            None => {
                return Err(err(
                    1,
                    format!("has no column `{c}` (columns: {})", names.join(", ")),
                ))
            }
        }
    }
    let mut times = Vec::new();
    let mut values = vec![Vec::new(); columns.len()];
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line());
            err(line, format!("cannot read the row: {e}"))
        })?;
        let line = record.position().map_or(0, |p| p.line());
        if record.len() != names.len() {
            return Err(err(
                line,
                format!(
                    "has {} fields and the header {}: a row of another length means a field was lost or added; every row needs one value per column",
                    record.len(),
                    names.len()
                ),
            ));
        }
        let value = |k: usize, name: &str| -> Result<f64, Error> {
            let text = record.get(k).unwrap_or("");
            if text.is_empty() {
                return Err(err(line, format!("{name} is empty: a gap in the record; a fit needs every row, so cut the record before the gap or fill it")));
            }
            match text.parse::<f64>() {
                Ok(v) if v.is_nan() => Err(err(line, format!("{name} is NaN: a gap in the record; a fit needs every row, so cut the record before the gap or fill it"))),
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(err(line, format!("{name} `{text}` is not a finite number"))),
            }
        };
        let t = value(0, "time_s")?;
        if let Some(&prev) = times.last() {
            if t <= prev {
                return Err(err(
                    line,
                    format!("time_s {t} does not increase (previous row: {prev}); times must increase strictly"),
                ));
            }
        }
        times.push(t);
        for ((k, c), v) in index.iter().zip(columns).zip(&mut values) {
            v.push(value(*k, c)?);
        }
    }
    if times.len() < 2 {
        return Err(err(
            1,
            format!("has {} data rows; a fit needs at least two", times.len()),
        ));
    }
    Ok((times, values))
}

/// `1st`, `2nd`, `3rd`, `4th`, ….
fn ordinal(n: usize) -> String {
    let suffix = match (n % 10, n % 100) {
        (1, x) if x != 11 => "st",
        (2, x) if x != 12 => "nd",
        (3, x) if x != 13 => "rd",
        _ => "th",
    };
    format!("{n}{suffix}")
}

/// The measurements of one `[[data]]` entry (`i`-th), each signal checked against the run.
pub(super) fn measurements(
    spec: &DataSpec,
    i: usize,
    base: &Path,
    window_s: Option<(f64, f64)>,
    resolved: &Resolved,
) -> Result<Vec<Measurement>, Error> {
    let field = format!("data[{i}]");
    if spec.signals.is_empty() {
        return Err(Error::invalid(
            format!("{field}.signals"),
            "{}",
            "map at least one CSV column to a model output: { column = \"contact_N_n\" }",
        ));
    }
    check_weights(&spec.weights, &spec.signals, &field)?;
    let cutoff = match spec.sensor_cutoff_hz {
        Some(f) if !(f.is_finite() && f > 0.0) => {
            return Err(Error::invalid(
                format!("{field}.sensor_cutoff_hz"),
                f,
                "must be a finite frequency > 0 [Hz]",
            ))
        }
        f => f,
    };
    let has_striker = matches!(resolved.excitation, woodpile::Excitation::Impact(_));
    let mut outputs = Vec::new();
    for (column, name) in &spec.signals {
        let key = format!("{field}.signals.{column}");
        let output = Output::parse(name).ok_or_else(|| {
            Error::invalid(
                &key,
                name,
                format!("names no model output (valid: {})", Output::FORMS),
            )
        })?;
        output.check(&key, resolved.chain.len(), has_striker)?;
        outputs.push(output);
    }
    let columns: Vec<&str> = spec.signals.keys().map(String::as_str).collect();
    let (times, values) = read_signals(&base.join(&spec.file), &columns)?;
    let window = window_s.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    let mut out = Vec::new();
    for ((column, output), values) in columns.iter().zip(outputs).zip(values) {
        let mut m = Measurement {
            label: (*column).to_string(),
            output,
            times_s: times.clone(),
            values,
            scale: 1.0,
            weight: spec.weights.get(*column).copied().unwrap_or(1.0),
            sensor_cutoff_hz: cutoff,
        };
        m.scale = m.peak_in(window);
        if m.scale <= 0.0 {
            return Err(Error::invalid(
                format!("{field}.signals.{column}"),
                format!("{} (all zero in the window)", spec.file),
                "a signal that is zero everywhere in the window carries no information to fit",
            ));
        }
        out.push(m);
    }
    Ok(out)
}

/// The smallest peak of a measured signal, relative to the model's peak of the same output:
/// a signal a billionth of the model's is rounding noise (a double's is 1e-16 of the values it
/// was computed from) or in another unit; a real measurement in kN against a model in N is 1e-3.
pub const SIGNAL_FLOOR: f64 = 1e-9;

/// Records the peak |value| of each output over a run.
struct Peaks {
    outputs: Vec<Output>,
    peaks: Vec<f64>,
}

impl woodpile::Recorder for Peaks {
    fn start(&mut self, _: &woodpile::Layout) {}

    fn record(&mut self, s: &woodpile::Sample<'_>) {
        for (o, peak) in self.outputs.iter().zip(&mut self.peaks) {
            let v = match *o {
                Output::ContactForce { contact } => s.contact_forces_n.get(contact),
                Output::ElementVelocity { element } => s.velocities_m_s.get(element - 1),
                Output::ElementDisplacement { element } => s.displacements_m.get(element - 1),
                Output::StrikerVelocity => s.striker.as_ref().map(|(_, v)| v),
            };
            // NaN (no value) never raises the peak.
            *peak = peak.max(v.map_or(0.0, |v| v.abs()));
        }
    }
}

/// The peak |value| of each of `outputs` over one run of `built` (sampled at least 4000 times),
/// or None when the run fails.
pub(super) fn model_peaks(built: &woodpile::fit::Built, outputs: &[Output]) -> Option<Vec<f64>> {
    let mut settings = built.settings;
    settings.sample_interval_s = settings.sample_interval_s.min(settings.duration_s / 4000.0);
    let mut peaks = Peaks {
        outputs: outputs.to_vec(),
        peaks: vec![0.0; outputs.len()],
    };
    woodpile::simulate(&built.chain, &built.excitation, &settings, &mut peaks).ok()?;
    Some(peaks.peaks)
}

fn check_weights(
    weights: &BTreeMap<String, f64>,
    signals: &BTreeMap<String, String>,
    field: &str,
) -> Result<(), Error> {
    for (column, &w) in weights {
        let key = format!("{field}.weights.{column}");
        if !signals.contains_key(column) {
            return Err(Error::invalid(
                key,
                w,
                "weights a column that is not among the signals",
            ));
        }
        if !(w.is_finite() && w > 0.0) {
            return Err(Error::invalid(key, w, "must be a finite number > 0"));
        }
    }
    Ok(())
}
