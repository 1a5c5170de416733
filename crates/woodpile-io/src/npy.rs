//! NumPy `.npy` files of little-endian float64 arrays in C order: the only kind woodpile writes
//! and reads (`numpy.load` and pandas open them as they are).
//!
//! The format (NPY version 1.0): the magic `\x93NUMPY`, the version bytes 1 and 0, the header
//! length as a little-endian u16, then an ASCII Python dict
//! `{'descr': '<f8', 'fortran_order': False, 'shape': (rows, cols), }` padded with spaces and a
//! final newline so that the data starts at a multiple of 64 bytes, then the values.
//!
//! Written by hand rather than with the `npyz` crate: npyz parses headers with a general Python
//! literal parser whose dependencies (pest, num-bigint, a C build of psm) were a seventh of the
//! whole test build from a fresh clone (47 s of 375 s CPU, measured with `cargo test --timings`),
//! for a format this narrow. Reading accepts versions 1.0, 2.0 and 3.0 of the header.

use std::io::Write;

const MAGIC: &[u8] = b"\x93NUMPY";

/// The header of a float64 C-order array of `shape`, padded to a multiple of 64 bytes.
fn header(shape: &[u64]) -> Vec<u8> {
    let dims = match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(u64::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let mut dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {dims}, }}");
    // magic (6) + version (2) + length (2) + dict + newline ≡ 0 (mod 64)
    let unpadded = MAGIC.len() + 4 + dict.len() + 1;
    dict.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    dict.push('\n');
    let mut out = Vec::with_capacity(10 + dict.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&[1, 0]);
    out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out
}

/// Writes `data` (C order, `shape.iter().product()` values) as a float64 `.npy` array.
pub fn write(out: &mut impl Write, shape: &[u64], data: &[f64]) -> std::io::Result<()> {
    let expected: u64 = shape.iter().product();
    if expected != data.len() as u64 {
        return Err(std::io::Error::other(format!(
            "shape {shape:?} holds {expected} values, {} given",
            data.len()
        )));
    }
    out.write_all(&header(shape))?;
    for v in data {
        out.write_all(&v.to_le_bytes())?;
    }
    Ok(())
}

/// Reads a float64 C-order `.npy` array: its shape and its values. The error says what is
/// wrong (not an NPY file, another dtype, Fortran order, a short file).
pub fn read(bytes: &[u8]) -> Result<(Vec<u64>, Vec<f64>), String> {
    if bytes.len() < 10 || &bytes[..6] != MAGIC {
        return Err("not a NumPy .npy file (no \\x93NUMPY magic)".into());
    }
    let (len, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        v => return Err(format!("unsupported .npy version {v}")),
    };
    let dict = bytes
        .get(start..start + len)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or("truncated or non-text .npy header")?;
    let value_of = |key: &str| {
        let k = format!("'{key}':");
        dict.find(&k).map(|i| dict[i + k.len()..].trim_start())
    };
    let descr = value_of("descr").ok_or("the header has no 'descr'")?;
    if !(descr.starts_with("'<f8'") || descr.starts_with("'float64'")) {
        return Err(format!(
            "dtype {} is not little-endian float64 ('<f8')",
            descr.split(',').next().unwrap_or(descr)
        ));
    }
    if !value_of("fortran_order").is_some_and(|v| v.starts_with("False")) {
        return Err("Fortran-ordered arrays are not supported".into());
    }
    let shape_text = value_of("shape").ok_or("the header has no 'shape'")?;
    let inner = shape_text
        .strip_prefix('(')
        .and_then(|s| s.split(')').next())
        .ok_or("malformed 'shape' in the header")?;
    let shape = inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<u64>().map_err(|_| format!("bad dimension `{s}`")))
        .collect::<Result<Vec<u64>, String>>()?;
    // The bytes the shape needs, unless that overflows (a shape no file can hold).
    let needed = shape
        .iter()
        .try_fold(8u64, |bytes, &d| bytes.checked_mul(d))
        .ok_or_else(|| format!("shape {shape:?} is larger than any file"))?;
    let data = &bytes[start + len..];
    if data.len() as u64 != needed {
        return Err(format!(
            "shape {shape:?} needs {needed} bytes of data, the file has {}",
            data.len()
        ));
    }
    let values = data
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8-byte chunk")))
        .collect();
    Ok((shape, values))
}
