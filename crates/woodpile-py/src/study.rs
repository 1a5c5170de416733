//! Design studies (`woodpile.study`): many scenarios at once, their figures of merit.

use crate::errors::Failure;
use pyo3::prelude::*;
use rayon::prelude::*;
use std::path::PathBuf;
use woodpile_io::limits::RunSize;
use woodpile_io::scenario::{resolve, Resolved, Scenario};

/// One scenario's result: its `RunSummary` as JSON, or the message of its error.
type Outcome = (Option<String>, Option<String>);

/// Runs many scenarios in parallel on `threads` threads (default: one per core), GIL released;
/// one (JSON `RunSummary`, None) or (None, error message) per scenario, in order. Scenarios
/// that only need figures of merit (`run.sample_interval_s` = `run.duration_s`) advance together
/// in SIMD lanes (`woodpile::lanes`), with the same results as one by one.
#[pyfunction]
#[pyo3(signature = (texts, base_dir, threads=None))]
fn evaluate(
    py: Python<'_>,
    texts: Vec<String>,
    base_dir: PathBuf,
    threads: Option<usize>,
) -> PyResult<Vec<Outcome>> {
    crate::interrupt::detach_interruptibly(py, || {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.unwrap_or(0))
            .build()
            .map_err(|e| Failure::invalid("threads", threads.unwrap_or(0), e.to_string()))?;
        Ok(pool.install(|| {
            let resolved: Vec<Result<Resolved, woodpile_io::Error>> = texts
                .par_iter()
                .map(|t| {
                    let resolved = Scenario::parse(t).and_then(|s| resolve(&s, &base_dir))?;
                    // The step limit of a single run holds for each (no samples are kept).
                    RunSize::estimate(&resolved.settings, resolved.chain.len())
                        .check(false, false, false)?;
                    Ok(resolved)
                })
                .collect();
            // One call: the lanes of every thread share one queue of runs.
            let jobs: Vec<woodpile::Job<'_>> = resolved
                .iter()
                .filter_map(|r| r.as_ref().ok())
                .map(|r| woodpile::Job {
                    chain: &r.chain,
                    excitation: &r.excitation,
                    settings: &r.settings,
                })
                .collect();
            let mut runs =
                woodpile::simulate_many(&jobs, woodpile::LaneWidth::detect()).into_iter();
            resolved
                .iter()
                .map(|r| match r {
                    Err(e) => (None, Some(e.to_string())),
                    Ok(_) => match runs.next().expect("one result per job") {
                        Ok(summary) => match serde_json::to_string(&summary) {
                            Ok(json) => (Some(json), None),
                            Err(e) => (None, Some(format!("cannot serialise the summary: {e}"))),
                        },
                        Err(e) => (None, Some(woodpile_io::Error::from(e).to_string())),
                    },
                })
                .collect()
        }))
    })
}

/// Adds this module's functions to the extension.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(evaluate, m)?)?;
    Ok(())
}
