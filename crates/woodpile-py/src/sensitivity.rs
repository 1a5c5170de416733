//! Sensitivity studies (`woodpile.sensitivity`): Sobol' indices over a scenario's
//! `[uncertainty]`, and the estimators alone on any outputs.

use crate::errors::{core_err, py_err, Failure};
use pyo3::prelude::*;
use std::path::PathBuf;
use woodpile::sensitivity::Bootstrap;
use woodpile_io::scenario::Scenario;
use woodpile_io::sensitivity::{accuracy_targeted, design, figure_indices, FigureIndices};
use woodpile_io::uncertainty::{figures, FIGURES};

/// One index row: parameter, figure, S1, S1_conf, ST, ST_conf.
type IndexRow = (String, String, f64, f64, f64, f64);

/// A study's results: the drawn values' names, the Saltelli matrix, the figures' names, the
/// outputs (None where a figure means nothing), the index rows, the figures without indices
/// (name, reason), and how the runs were integrated.
type Study = (
    Vec<String>,
    Vec<Vec<f64>>,
    Vec<String>,
    Vec<Vec<Option<f64>>>,
    Vec<IndexRow>,
    Vec<(String, String)>,
    String,
);

/// The sensitivity study of the scenario `text` (`woodpile sensitivity`), runs in SIMD lanes on
/// `threads` threads, GIL released.
// The Python keyword arguments, one parameter each.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (text, base_dir, base_samples, seed=None, paper_settings=false, threads=None, allow_large=false))]
fn sensitivity(
    py: Python<'_>,
    text: String,
    base_dir: PathBuf,
    base_samples: usize,
    seed: Option<u32>,
    paper_settings: bool,
    threads: Option<usize>,
    allow_large: bool,
) -> PyResult<Study> {
    crate::interrupt::detach_interruptibly(py, || {
        let mut scenario = Scenario::parse(&text).map_err(py_err)?;
        let Some(spec) = &scenario.uncertainty else {
            return Err(Failure::invalid(
                "uncertainty",
                "(none)",
                "a sensitivity study needs the scenario's [uncertainty] table: the parameters to scatter and their distributions",
            )
            .into());
        };
        let mut u = spec.check().map_err(py_err)?;
        if let Some(seed) = seed {
            u.seed = seed;
        }
        // A Python Scenario is always completed (RK4 at the default step written out): only a
        // stated peak tolerance counts as the user's choice of integration.
        if !paper_settings && scenario.run.peak_tolerance.is_none() {
            let r = &mut scenario.run;
            (r.integrator, r.time_step_s, r.rtol, r.atol) = (None, None, None, None);
        }
        let (mut accuracy, fast) = accuracy_targeted(&mut scenario, paper_settings);
        if fast {
            accuracy.push_str(" (paper_settings=True: the scenario's own run settings)");
        }
        let d =
            design(&scenario, &u, ("base_samples", base_samples), allow_large).map_err(py_err)?;
        // Resolving thousands of rows takes seconds: Ctrl-C ends it.
        let resolved =
            woodpile_io::uncertainty::resolve_samples(&d.samples, &base_dir).map_err(py_err)?;
        woodpile_io::limits::RunSize::estimate(&resolved[0].settings, resolved[0].chain.len())
            .check(false, false, false)
            .map_err(py_err)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.unwrap_or(0))
            .build()
            .map_err(|e| Failure::invalid("threads", threads.unwrap_or(0), e.to_string()))?;
        let jobs: Vec<woodpile::Job<'_>> = resolved
            .iter()
            .map(|r| woodpile::Job {
                chain: &r.chain,
                excitation: &r.excitation,
                settings: &r.settings,
            })
            .collect();
        let runs = pool
            .install(|| woodpile::simulate_many(&jobs, woodpile::LaneWidth::detect()))
            .into_iter()
            .map(|run| {
                let run = run.map_err(core_err)?;
                woodpile_io::limits::check_accuracy(&run.energy, false).map_err(py_err)?;
                Ok(run)
            })
            .collect::<PyResult<Vec<_>>>()?;
        let bootstrap = Bootstrap {
            seed: u64::from(u.seed),
            ..Bootstrap::default()
        };
        let (rows, meaningless) = index_rows(&d, &runs, &bootstrap);
        Ok((
            d.samples.columns.clone(),
            d.samples.samples.iter().map(|s| s.values.clone()).collect(),
            FIGURES.iter().map(|f| f.to_string()).collect(),
            runs.iter().map(|r| figures(r).to_vec()).collect(),
            rows,
            meaningless,
            accuracy,
        ))
    })
}

/// The indices of every figure as rows (parameter, figure, S1, its interval, ST, its interval),
/// and the figures without indices with the reason.
#[allow(clippy::type_complexity)]
fn index_rows(
    d: &woodpile_io::sensitivity::Design,
    runs: &[woodpile::RunSummary],
    bootstrap: &Bootstrap,
) -> (
    Vec<(String, String, f64, f64, f64, f64)>,
    Vec<(String, String)>,
) {
    let mut rows = Vec::new();
    let mut meaningless = Vec::new();
    for (figure, result) in figure_indices(d, runs, bootstrap) {
        match result {
            FigureIndices::Indices(s) => {
                for (p, i) in d.parameters.iter().zip(s) {
                    rows.push((
                        p.clone(),
                        figure.to_string(),
                        i.first_order,
                        i.first_order_conf,
                        i.total,
                        i.total_conf,
                    ));
                }
            }
            FigureIndices::Meaningless(reason) => meaningless.push((figure.into(), reason)),
        }
    }
    (rows, meaningless)
}

/// The Saltelli design in the unit cube (`woodpile::sensitivity::saltelli_unit_cube`).
#[pyfunction]
#[pyo3(signature = (base_samples, group_of, seed=0))]
fn saltelli_unit_cube(
    base_samples: usize,
    group_of: Vec<usize>,
    seed: u32,
) -> PyResult<Vec<Vec<f64>>> {
    woodpile::sensitivity::saltelli_unit_cube(base_samples, &group_of, seed).map_err(core_err)
}

/// SALib's estimators on outputs `y` of a Saltelli design: (S1, S1_conf, ST, ST_conf) per group.
#[pyfunction]
#[pyo3(signature = (y, base_samples, groups, resamples=100, level=0.95, seed=0))]
fn sobol_indices(
    y: Vec<f64>,
    base_samples: usize,
    groups: usize,
    resamples: usize,
    level: f64,
    seed: u64,
) -> PyResult<Vec<(f64, f64, f64, f64)>> {
    let bootstrap = Bootstrap {
        resamples,
        level,
        seed,
    };
    Ok(
        woodpile::sensitivity::indices(&y, base_samples, groups, &bootstrap)
            .map_err(core_err)?
            .into_iter()
            .map(|i| (i.first_order, i.first_order_conf, i.total, i.total_conf))
            .collect(),
    )
}

/// Adds this module's functions to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(sensitivity, m)?)?;
    m.add_function(wrap_pyfunction!(saltelli_unit_cube, m)?)?;
    m.add_function(wrap_pyfunction!(sobol_indices, m)?)?;
    Ok(())
}
