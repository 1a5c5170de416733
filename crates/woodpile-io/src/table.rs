//! Load tables: CSV files with a header row `time_s, force_n` (a blast) or `time_s, value` (a
//! drive signal) and one (t, value) row per line.

use crate::error::Error;
use std::path::Path;
use woodpile::BlastProfile;

/// Reads a blast table (header `time_s, force_n`); errors as [`load_table`].
pub fn load_blast_table(path: &Path) -> Result<BlastProfile, Error> {
    let (times, forces) = load_table(path, "force_n")?;
    Ok(BlastProfile::table(times, forces)?)
}

/// [`load_blast_table`] of a reader's bytes; errors name `path` as the table's file.
pub fn read_blast_table(bytes: impl std::io::Read, path: &Path) -> Result<BlastProfile, Error> {
    let (times, forces) = read_table(bytes, path, "force_n")?;
    Ok(BlastProfile::table(times, forces)?)
}

/// Reads a table of (time_s, `column`) rows: (times, values). Errors name the file and the line:
/// a missing file, a header that is not `time_s, COLUMN`, a row that is not two finite numbers,
/// times that do not increase strictly, fewer than two rows.
pub fn load_table(path: &Path, column: &str) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let file = std::fs::File::open(path).map_err(|e| Error::Read {
        path: path.to_path_buf(),
        source: e,
    })?;
    read_table(file, path, column)
}

/// [`load_table`] of a reader's bytes; errors name `path` as the table's file.
pub fn read_table(
    bytes: impl std::io::Read,
    path: &Path,
    column: &str,
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let table_err = |line: u64, message: String| Error::Table {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut reader = csv_reader(bytes);
    let headers = reader
        .headers()
        .map_err(|e| table_err(1, format!("cannot read the header row: {e}")))?
        .clone();
    let names: Vec<&str> = headers.iter().collect();
    if names != ["time_s", column] {
        return Err(table_err(
            1,
            format!(
                "header is `{}`; expected `time_s,{column}`",
                names.join(",")
            ),
        ));
    }
    let mut times = Vec::new();
    let mut values: Vec<f64> = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line());
            table_err(line, format!("cannot read the row: {e}"))
        })?;
        let line = record.position().map_or(0, |p| p.line());
        if record.len() != 2 {
            return Err(table_err(
                line,
                format!("has {} fields; expected 2 (time_s, {column})", record.len()),
            ));
        }
        let parse = |k: usize, name: &str| -> Result<f64, Error> {
            let text = &record[k];
            match text.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(table_err(
                    line,
                    format!("{name} `{text}` is not a finite number"),
                )),
            }
        };
        let t = parse(0, "time_s")?;
        let f = parse(1, column)?;
        if let Some(&prev) = times.last() {
            if t <= prev {
                return Err(table_err(
                    line,
                    format!("time_s {t} does not increase (previous row: {prev}); times must increase strictly"),
                ));
            }
        }
        times.push(t);
        values.push(f);
    }
    if times.len() < 2 {
        return Err(table_err(
            1,
            format!("has {} data rows; a table needs at least two", times.len()),
        ));
    }
    Ok((times, values))
}

/// The CSV reader of every table woodpile reads (blast and drive tables, measured signals): a
/// header row, fields trimmed, `#` comments, rows of any length (checked by the caller, which
/// names the line).
pub(crate) fn csv_reader<R: std::io::Read>(bytes: R) -> csv::Reader<R> {
    csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .flexible(true)
        .from_reader(bytes)
}
