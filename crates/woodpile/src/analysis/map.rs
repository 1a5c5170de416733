//! Spatio-temporal maps: a value over (contact or layer) × (time or frequency), as in the paper's
//! Figs. 5, 6, 7 a and 9.

use crate::error::{Error, Result};
use crate::record::{sample_interval_s, Trajectory};

/// One axis of a map: a name, a unit and the coordinate of every row or column.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// What the axis is (`contact`, `layer`, `time`, `frequency`, …).
    pub name: String,
    /// Unit of the values (`s`, `Hz`, or `""` for an index).
    pub unit: String,
    /// Coordinate of each row or column.
    pub values: Vec<f64>,
}

impl Axis {
    /// An axis with explicit coordinates.
    pub fn new(name: impl Into<String>, unit: impl Into<String>, values: Vec<f64>) -> Self {
        Axis {
            name: name.into(),
            unit: unit.into(),
            values,
        }
    }

    /// An index axis 0, 1, …, n−1 (no unit).
    pub fn index(name: impl Into<String>, n: usize) -> Self {
        Axis::new(name, "", (0..n).map(|i| i as f64).collect())
    }

    /// Number of coordinates.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Whether the axis has no coordinate.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// `name [unit]`, or the name alone for an index.
    pub fn label(&self) -> String {
        if self.unit.is_empty() {
            self.name.clone()
        } else {
            format!("{} [{}]", self.name, self.unit)
        }
    }
}

/// A value over rows × columns, stored row-major (`data[r * n_cols + c]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Map2 {
    /// Row axis (e.g. contact index).
    pub rows: Axis,
    /// Column axis (e.g. time \[s\]).
    pub cols: Axis,
    /// What the values are (`contact force`, …).
    pub value_name: String,
    /// Unit of the values (`N`, `1` for a ratio).
    pub value_unit: String,
    /// Values, row-major.
    pub data: Vec<f64>,
}

impl Map2 {
    /// A map, checked for a consistent size.
    pub fn new(
        rows: Axis,
        cols: Axis,
        value_name: impl Into<String>,
        value_unit: impl Into<String>,
        data: Vec<f64>,
    ) -> Result<Self> {
        if data.len() != rows.len() * cols.len() {
            return Err(Error::invalid(
                "map data length",
                data.len(),
                format!("expected {} rows × {} columns", rows.len(), cols.len()),
            ));
        }
        Ok(Map2 {
            rows,
            cols,
            value_name: value_name.into(),
            value_unit: value_unit.into(),
            data,
        })
    }

    /// Number of rows.
    pub fn n_rows(&self) -> usize {
        self.rows.len()
    }

    /// Number of columns.
    pub fn n_cols(&self) -> usize {
        self.cols.len()
    }

    /// Value at (row, column).
    pub fn at(&self, row: usize, col: usize) -> f64 {
        self.data[row * self.n_cols() + col]
    }

    /// One row.
    pub fn row(&self, row: usize) -> &[f64] {
        let n = self.n_cols();
        &self.data[row * n..(row + 1) * n]
    }

    /// Sum over the rows of each column.
    pub fn column_sums(&self) -> Vec<f64> {
        let mut sums = vec![0.0; self.n_cols()];
        for row in self.data.chunks(self.n_cols().max(1)) {
            for (s, v) in sums.iter_mut().zip(row) {
                *s += v;
            }
        }
        sums
    }

    /// (min, max) of the finite values, or None if there is none.
    pub fn range(&self) -> Option<(f64, f64)> {
        self.data
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .fold(None, |acc, v| match acc {
                None => Some((v, v)),
                Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
            })
    }

    /// `value_name [value_unit]`.
    pub fn value_label(&self) -> String {
        if self.value_unit.is_empty() {
            self.value_name.clone()
        } else {
            format!("{} [{}]", self.value_name, self.value_unit)
        }
    }
}

/// Transposes sample-major rows of `width` into a row-major (quantity × time) block.
fn transpose(samples: &[f64], width: usize, n_samples: usize) -> Vec<f64> {
    let mut out = vec![0.0; samples.len()];
    for (s, row) in samples.chunks(width).enumerate() {
        for (q, v) in row.iter().enumerate() {
            out[q * n_samples + s] = *v;
        }
    }
    out
}

fn check_recorded(trajectory: &Trajectory) -> Result<()> {
    if trajectory.is_empty() {
        return Err(Error::invalid(
            "trajectory",
            "empty",
            "record a run with a Trajectory recorder first",
        ));
    }
    sample_interval_s(trajectory).map(|_| ())
}

/// Contact force over contacts 0..=N (rows) × time \[s\] (columns) \[N\] (paper Figs. 5, 9).
pub fn force_map(trajectory: &Trajectory) -> Result<Map2> {
    check_recorded(trajectory)?;
    let c = trajectory.n_contacts();
    Map2::new(
        Axis::index("contact", c),
        Axis::new("time", "s", trajectory.times_s.clone()),
        "contact force",
        "N",
        transpose(&trajectory.contact_forces_n, c, trajectory.len()),
    )
}

/// The energy put into the system \[J\]: the striker's initial energy for an impact (the total at
/// t = 0), the largest work done by the load so far for a blast.
pub fn injected_energy_j(trajectory: &Trajectory) -> f64 {
    let work = trajectory
        .input_work_j
        .iter()
        .copied()
        .fold(0.0_f64, f64::max);
    if work > 0.0 {
        work
    } else {
        trajectory.total_energy_j().first().copied().unwrap_or(0.0)
    }
}

/// Layer energy over layers 0..=N (rows) × time \[s\] (columns), divided by the injected energy
/// ([`injected_energy_j`]) — dimensionless (paper Fig. 6 shows it in %). The wall's half of the
/// last contact is not a layer: for an impact the columns sum to 1 − E_wall(t)/E_in.
pub fn energy_map(trajectory: &Trajectory) -> Result<Map2> {
    check_recorded(trajectory)?;
    let injected = injected_energy_j(trajectory);
    if !(injected > 0.0 && injected.is_finite()) {
        return Err(Error::invalid(
            "injected energy",
            injected,
            "the run put no energy into the chain (zero striker velocity or load?)",
        ));
    }
    let c = trajectory.n_contacts();
    let mut data = transpose(&trajectory.layer_energies_j, c, trajectory.len());
    for v in &mut data {
        *v /= injected;
    }
    Map2::new(
        Axis::index("layer", c),
        Axis::new("time", "s", trajectory.times_s.clone()),
        "energy / injected energy",
        "1",
        data,
    )
}
