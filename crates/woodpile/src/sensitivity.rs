//! Global sensitivity: Sobol' indices by Saltelli sampling, with SALib's estimators.
//!
//! **Sampling** ([`saltelli_unit_cube`]): N base points of a scrambled Sobol' sequence of
//! dimension 2D ([`crate::uncertainty::unit_cube`]: D parameters, each point's first D
//! coordinates are matrix A, its last D matrix B) give N·(G + 2) rows, G the number of groups of
//! parameters (one group per parameter when none are grouped), in the row order of SALib's
//! `sobol.sample` with `calc_second_order=False`: for each base point, A, then AB₁ … AB_G (A with
//! the columns of group g taken from B), then B. A front end maps the rows to parameters by their
//! inverse CDFs.
//!
//! **Estimators** ([`indices`]): those of SALib's `sobol.analyze` (`calc_second_order=False`),
//! after the same normalisation of the outputs to zero mean and unit variance (population
//! moments of all N·(G + 2) outputs): first order (Saltelli et al. 2010)
//! S1 = mean(f_B·(f_ABg − f_A)) / V, total (Jansen 1999) ST = ½·mean((f_A − f_ABg)²) / V, with
//! V the population variance of the 2N values [f_A, f_B]. Confidence intervals as SALib's:
//! z·sd (n − 1) of the estimator over bootstrap resamples of the N base points, z the standard
//! normal quantile of ½ + level/2; the resamples are drawn from ChaCha8 seeded with `seed`.
//!
//! ```
//! use woodpile::sensitivity::{indices, saltelli_unit_cube, Bootstrap};
//!
//! // y = x₁ + 2·x₂ on the unit square: S1 = ST = 1/5 and 4/5.
//! let rows = saltelli_unit_cube(256, &[0, 1], 0)?;
//! let y: Vec<f64> = rows.iter().map(|x| x[0] + 2.0 * x[1]).collect();
//! let s = indices(&y, 256, 2, &Bootstrap::default())?;
//! assert!((s[0].first_order - 0.2).abs() < 0.02 && (s[1].total - 0.8).abs() < 0.02);
//! # Ok::<(), woodpile::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::math::Libm;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// How the confidence intervals are bootstrapped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bootstrap {
    /// Number of resamples (SALib's `num_resamples`).
    pub resamples: usize,
    /// Confidence level of the intervals, 0 < level < 1 (SALib's `conf_level`).
    pub level: f64,
    /// Seed of the resampling.
    pub seed: u64,
}

impl Default for Bootstrap {
    /// [`crate::defaults::SENSITIVITY_RESAMPLES`] resamples at level
    /// [`crate::defaults::SENSITIVITY_CONFIDENCE`], seed 0.
    fn default() -> Self {
        Bootstrap {
            resamples: crate::defaults::SENSITIVITY_RESAMPLES,
            level: crate::defaults::SENSITIVITY_CONFIDENCE,
            seed: 0,
        }
    }
}

/// Number of rows of a Saltelli design of `base_samples` points and `groups` groups.
pub fn saltelli_rows(base_samples: usize, groups: usize) -> usize {
    base_samples * (groups + 2)
}

/// The Saltelli design in the unit cube: `group_of[j]` is the group of parameter j (groups
/// numbered 0..G, every one used; `[0, 1, …, D − 1]` for one group per parameter). Row order as
/// SALib's (module docs); every coordinate strictly inside (0, 1).
pub fn saltelli_unit_cube(
    base_samples: usize,
    group_of: &[usize],
    seed: u32,
) -> Result<Vec<Vec<f64>>> {
    let d = group_of.len();
    let groups = group_count(group_of)?;
    if base_samples == 0 {
        return Err(Error::invalid(
            "sensitivity.base_samples",
            base_samples,
            "at least 1 base sample",
        ));
    }
    let base = crate::uncertainty::unit_cube(base_samples, 2 * d, seed)?;
    let mut rows = Vec::with_capacity(saltelli_rows(base_samples, groups));
    for point in &base {
        let (a, b) = point.split_at(d);
        rows.push(a.to_vec());
        for g in 0..groups {
            rows.push(
                (0..d)
                    .map(|j| if group_of[j] == g { b[j] } else { a[j] })
                    .collect(),
            );
        }
        rows.push(b.to_vec());
    }
    Ok(rows)
}

/// The number of groups of `group_of`, checking they are numbered 0..G with none unused.
fn group_count(group_of: &[usize]) -> Result<usize> {
    let groups = group_of.iter().max().map_or(0, |g| g + 1);
    if group_of.is_empty() {
        return Err(Error::invalid(
            "sensitivity.parameters",
            0,
            "at least one scattered parameter",
        ));
    }
    if let Some(g) = (0..groups).find(|g| !group_of.contains(g)) {
        return Err(Error::invalid(
            "sensitivity.groups",
            format!("{group_of:?}"),
            format!("groups numbered 0..{groups} with none left out (group {g} has no parameter)"),
        ));
    }
    Ok(groups)
}

/// One group's indices for one output.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Indices {
    /// First-order index S1 (Saltelli 2010).
    pub first_order: f64,
    /// Half-width of S1's confidence interval.
    pub first_order_conf: f64,
    /// Total index ST (Jansen 1999).
    pub total: f64,
    /// Half-width of ST's confidence interval.
    pub total_conf: f64,
}

/// The outputs split into A, AB_g and B by the row order of [`saltelli_unit_cube`].
struct Blocks {
    a: Vec<f64>,
    b: Vec<f64>,
    ab: Vec<Vec<f64>>,
}

fn blocks(y: &[f64], base_samples: usize, groups: usize) -> Blocks {
    let step = groups + 2;
    let at = |i: usize, k: usize| y[i * step + k];
    Blocks {
        a: (0..base_samples).map(|i| at(i, 0)).collect(),
        b: (0..base_samples).map(|i| at(i, groups + 1)).collect(),
        ab: (0..groups)
            .map(|g| (0..base_samples).map(|i| at(i, g + 1)).collect())
            .collect(),
    }
}

fn mean(values: impl ExactSizeIterator<Item = f64>) -> f64 {
    let n = values.len() as f64;
    values.sum::<f64>() / n
}

/// Population variance (numpy's `np.var`).
fn variance(values: &[f64]) -> f64 {
    let m = mean(values.iter().copied());
    mean(values.iter().map(|v| (v - m) * (v - m)))
}

/// S1 and ST over the base points `rows` (indices into A, B and AB_g, repeats allowed).
fn estimate(blocks: &Blocks, g: usize, rows: &[usize]) -> (f64, f64) {
    let (a, b, ab) = (&blocks.a, &blocks.b, &blocks.ab[g]);
    let both: Vec<f64> = rows
        .iter()
        .map(|&i| a[i])
        .chain(rows.iter().map(|&i| b[i]))
        .collect();
    // SALib's guard: outputs that do not vary give indices of 0 (only a bootstrap resample can
    // be constant here; [`indices`] refuses constant outputs).
    let (lo, hi) = both
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    if hi - lo <= f64::EPSILON {
        return (0.0, 0.0);
    }
    let v = variance(&both);
    let s1 = mean(rows.iter().map(|&i| b[i] * (ab[i] - a[i]))) / v;
    let st = 0.5 * mean(rows.iter().map(|&i| (a[i] - ab[i]).powi(2))) / v;
    (s1, st)
}

/// Sample standard deviation (n − 1).
fn sample_sd(values: &[f64]) -> f64 {
    let m = mean(values.iter().copied());
    let n = values.len() as f64;
    (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
}

/// First-order and total indices of each of `groups` groups from the outputs `y` of a Saltelli
/// design of `base_samples` points (`y[r]` the output of row r of [`saltelli_unit_cube`]), with
/// bootstrap confidence intervals. An error when the outputs have no variance (every index would
/// be 0/0), when `y` is not N·(G + 2) long or holds a non-finite value, or when the bootstrap is
/// not one (fewer than 2 resamples, a level outside (0, 1)).
pub fn indices(
    y: &[f64],
    base_samples: usize,
    groups: usize,
    bootstrap: &Bootstrap,
) -> Result<Vec<Indices>> {
    let rows = saltelli_rows(base_samples, groups);
    if base_samples == 0 || groups == 0 || y.len() != rows {
        return Err(Error::invalid(
            "sensitivity.outputs",
            y.len(),
            format!(
                "N·(G + 2) = {base_samples}·({groups} + 2) = {rows} outputs, N and G at least 1"
            ),
        ));
    }
    if let Some(r) = y.iter().position(|v| !v.is_finite()) {
        return Err(Error::invalid(
            format!("sensitivity.outputs[{r}]"),
            y[r],
            "a finite output",
        ));
    }
    if bootstrap.resamples < 2 || !(bootstrap.level > 0.0 && bootstrap.level < 1.0) {
        return Err(Error::invalid(
            "sensitivity.bootstrap",
            format!(
                "{} resamples at level {}",
                bootstrap.resamples, bootstrap.level
            ),
            "at least 2 resamples, a level strictly between 0 and 1",
        ));
    }
    let m = mean(y.iter().copied());
    let sd = variance(y).sqrt();
    if sd <= 0.0 {
        return Err(Error::invalid(
            "sensitivity.outputs",
            format!("all {rows} equal to {m:e}"),
            "outputs that vary: a constant output has no Sobol' indices (0/0)",
        ));
    }
    let normalised: Vec<f64> = y.iter().map(|v| (v - m) / sd).collect();
    let blocks = blocks(&normalised, base_samples, groups);
    let all: Vec<usize> = (0..base_samples).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(bootstrap.seed);
    let resamples: Vec<Vec<usize>> = (0..bootstrap.resamples)
        .map(|_| {
            (0..base_samples)
                .map(|_| rng.random_range(0..base_samples))
                .collect()
        })
        .collect();
    let z = crate::uncertainty::standard_normal_quantile(0.5 + bootstrap.level / 2.0);
    Ok((0..groups)
        .map(|g| {
            let (s1, st) = estimate(&blocks, g, &all);
            let (boot_s1, boot_st): (Vec<f64>, Vec<f64>) = resamples
                .iter()
                .map(|rows| estimate(&blocks, g, rows))
                .unzip();
            Indices {
                first_order: s1,
                first_order_conf: z * sample_sd(&boot_s1),
                total: st,
                total_conf: z * sample_sd(&boot_st),
            }
        })
        .collect())
}

/// The Ishigami function sin x₁ + a·sin² x₂ + b·x₃⁴·sin x₁ (Ishigami & Homma 1990), the
/// standard test of sensitivity estimators, on x ∈ [−π, π]³.
pub fn ishigami(x: [f64; 3], a: f64, b: f64) -> f64 {
    x[0].libm_sin() + a * x[1].libm_sin().powi(2) + b * x[2].powi(4) * x[0].libm_sin()
}

/// The Ishigami function's exact first-order and total indices (Sobol' & Levitan 1999) for
/// parameters `a`, `b`: `([S1₁, S1₂, S1₃], [ST₁, ST₂, ST₃])`.
pub fn ishigami_indices(a: f64, b: f64) -> ([f64; 3], [f64; 3]) {
    use std::f64::consts::PI;
    let pi4 = PI.powi(4);
    let v1 = 0.5 * (1.0 + b * pi4 / 5.0).powi(2);
    let v2 = a * a / 8.0;
    let v13 = b * b * pi4 * pi4 * (1.0 / 18.0 - 1.0 / 50.0);
    let v = v1 + v2 + v13;
    ([v1 / v, v2 / v, 0.0], [(v1 + v13) / v, v2 / v, v13 / v])
}
