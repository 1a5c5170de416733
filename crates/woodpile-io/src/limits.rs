//! Up-front limits on what a command may start, each with a clear message and an override, so
//! that a typo (`--threads 100000`, `duration_s = 1e6`) is an error at once rather than a hang;
//! and the accuracy check after a run ([`check_accuracy`]).

use crate::error::{Error, Limit};

/// Most worker threads allowed per available core without an override.
pub const THREADS_PER_CORE: usize = 4;

/// The cores this process may use (1 when unknown).
pub fn available_cores() -> usize {
    std::thread::available_parallelism().map_or(1, usize::from)
}

/// Checks a worker-thread count (0 = one per core). More than [`THREADS_PER_CORE`] per
/// available core is refused unless `allow` is set; `field` names the option as the front end
/// spells it.
pub fn check_threads(field: &str, threads: usize, allow: bool) -> Result<usize, Error> {
    let cores = available_cores();
    let most = THREADS_PER_CORE * cores;
    if threads > most && !allow {
        return Err(Error::OverLimit {
            limit: Limit::Threads,
            field: field.to_string(),
            value: threads.to_string(),
            reason: format!(
                "at most {most} ({THREADS_PER_CORE} per core, {cores} cores here); 0 = one per core"
            ),
        });
    }
    Ok(threads)
}

/// Most integration steps a run may take without an override (the core's backstop).
pub const MAX_STEPS: u64 = woodpile::defaults::MAX_STEPS;

/// Largest output a run may write without an override \[bytes\].
pub const MAX_OUTPUT_BYTES: f64 = 2e9;

/// Bytes per value in the outputs: a CSV field in `{:e}` form (~22 characters with its
/// separator) plus its 8-byte `.npy` copy.
const BYTES_PER_VALUE: f64 = 30.0;

/// What a run will cost, estimated before it starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSize {
    /// Integration steps (None for the adaptive method).
    pub steps: Option<u64>,
    /// Samples on the output grid.
    pub samples: usize,
    /// Size of the run directory \[bytes\].
    pub output_bytes: f64,
}

impl RunSize {
    /// The estimate for `settings` on a chain of `n_elements` elements.
    pub fn estimate(settings: &woodpile::RunSettings, n_elements: usize) -> Self {
        // forces (N+2 columns with time), energy (N+5), displacements and velocities (N+1 each),
        // striker (3).
        Self::with_columns(settings, 4 * n_elements + 12)
    }

    /// The estimate for `settings` of a run writing `columns` values per sample.
    pub fn with_columns(settings: &woodpile::RunSettings, columns: usize) -> Self {
        let samples = settings.n_samples();
        RunSize {
            steps: settings.estimated_steps(),
            samples,
            output_bytes: samples as f64 * columns as f64 * BYTES_PER_VALUE,
        }
    }

    /// Refuses a run of more than [`MAX_STEPS`] steps unless `allow_long`, and an output above
    /// [`MAX_OUTPUT_BYTES`] unless `allow_large` (`write_output` false: no samples are written).
    pub fn check(
        &self,
        allow_long: bool,
        allow_large: bool,
        write_output: bool,
    ) -> Result<(), Error> {
        if let Some(steps) = self.steps {
            if steps > MAX_STEPS && !allow_long {
                return Err(Error::OverLimit {
                    limit: Limit::Steps,
                    field: "run.duration_s / run.time_step_s".into(),
                    value: format!("{steps:.3e} steps"),
                    reason: format!(
                        "more than {MAX_STEPS:.0e} integration steps (the run would not end in reasonable time); \
                         shorten run.duration_s or enlarge run.time_step_s"
                    ),
                });
            }
        }
        if write_output && self.output_bytes > MAX_OUTPUT_BYTES && !allow_large {
            return Err(Error::OverLimit {
                limit: Limit::OutputSize,
                field: "run.sample_interval_s".into(),
                value: format!(
                    "{} samples, about {:.1} GB of output",
                    self.samples,
                    self.output_bytes / 1e9
                ),
                reason: format!(
                    "the run directory would exceed {:.0} GB; enlarge run.sample_interval_s or shorten run.duration_s",
                    MAX_OUTPUT_BYTES / 1e9
                ),
            });
        }
        Ok(())
    }
}

/// Most elements one generation of a design study may simulate without an override
/// (population × positions): about the work of one run at the step limit, so that a typo
/// (`positions = 100000`, `population = 100000000`) is refused at once rather than hanging.
pub const MAX_GENERATION_ELEMENTS: usize = 1_000_000;

/// Refuses a generation of `population` designs of `positions` elements (the most a design may
/// have, named by `positions_key` as the config writes it) above [`MAX_GENERATION_ELEMENTS`]
/// unless `allow`.
pub fn check_generation(
    population: usize,
    positions: usize,
    positions_key: &str,
    allow: bool,
) -> Result<(), Error> {
    let elements = population.saturating_mul(positions);
    if elements > MAX_GENERATION_ELEMENTS && !allow {
        return Err(Error::OverLimit {
            limit: Limit::Generation,
            field: format!("ga.population × {positions_key}"),
            value: format!("{population} × {positions} = {elements} elements per generation"),
            reason: format!(
                "more than {MAX_GENERATION_ELEMENTS} elements simulated per generation (a generation would not end in reasonable time, \
                 and its designs would fill memory); reduce ga.population or {positions_key}"
            ),
        });
    }
    Ok(())
}

/// Refuses a study of `runs` runs of `elements` elements each (the samples of a scenario, a
/// sensitivity design: every run's scenario is built before the runs) above
/// [`MAX_GENERATION_ELEMENTS`] elements in all unless `allow`; `field` names the number of runs
/// as the user gave it, `runs_text` how many runs follow from it (`512`, or `64 × (2 + 2) = 256`).
pub fn check_study(
    field: &str,
    runs_text: &str,
    runs: usize,
    elements: usize,
    allow: bool,
) -> Result<(), Error> {
    let total = runs.saturating_mul(elements.max(1));
    if total > MAX_GENERATION_ELEMENTS && !allow {
        return Err(Error::OverLimit {
            limit: Limit::Study,
            field: field.to_string(),
            value: format!(
                "{runs_text} runs × {} elements = {} elements",
                elements.max(1),
                count(total)
            ),
            reason: format!(
                "more than {MAX_GENERATION_ELEMENTS} elements simulated in one study (its runs would not end in reasonable time, \
                 and their scenarios would fill memory); reduce {field}"
            ),
        });
    }
    Ok(())
}

/// `n` in words, where a product that overflowed (saturated at `usize::MAX`) is "more than
/// 1.8e19" rather than a wrong exact number.
pub(crate) fn count(n: usize) -> String {
    if n == usize::MAX {
        format!("more than {:.1e}", usize::MAX as f64)
    } else {
        n.to_string()
    }
}

/// Most model runs a fit may plan (starts × most runs per start) without an override: each
/// start's points and results are kept, and a fit of more would not end in reasonable time
/// (the default fit plans 8 × 200 = 1600).
pub const MAX_FIT_RUNS: usize = 1_000_000;

/// Refuses a fit of `starts` starts of at most `max_evaluations` model runs each above
/// [`MAX_FIT_RUNS`] unless `allow` (keys as the fit file writes them).
pub fn check_fit(starts: usize, max_evaluations: usize, allow: bool) -> Result<(), Error> {
    let runs = starts.saturating_mul(max_evaluations);
    if runs > MAX_FIT_RUNS && !allow {
        return Err(Error::OverLimit {
            limit: Limit::Study,
            field: "fit.starts × fit.max_evaluations".into(),
            value: format!(
                "{starts} × {max_evaluations} = {} model runs",
                count(runs)
            ),
            reason: format!(
                "more than {MAX_FIT_RUNS} model runs planned (the fit would not end in reasonable time, and its \
                 starts would fill memory); reduce fit.starts or fit.max_evaluations"
            ),
        });
    }
    Ok(())
}

/// What a run's energy error is relative to: the larger of E(0) and the largest |W|, which is
/// E(0) for an unloaded impact and |W| for a blast (`woodpile::EnergyBalance`).
pub const ENERGY_REFERENCE: &str = "the larger of the initial energy and the largest work done";

/// The one accuracy rule of every run, chain or lattice, in the CLI and in Python
/// (docs/physics.md §8): above [`ENERGY_ERROR_FAIL`](woodpile::defaults::ENERGY_ERROR_FAIL) the
/// run is refused (unless `allow`); above
/// [`ENERGY_ERROR_WARN`](woodpile::defaults::ENERGY_ERROR_WARN) (or when allowed) the warning
/// to print is returned. A NaN error is a failure.
pub fn check_accuracy(
    energy: &woodpile::EnergyBalance,
    allow: bool,
) -> Result<Option<String>, Error> {
    let err = energy.max_relative_error;
    // A NaN error counts as a failure: `is_some_and(Le)` is false for it.
    let within = |limit: f64| err.partial_cmp(&limit).is_some_and(|o| o.is_le());
    if !within(woodpile::defaults::ENERGY_ERROR_FAIL) && !allow {
        return Err(Error::Inaccurate {
            relative_error: err,
            reference: ENERGY_REFERENCE,
            limit: woodpile::defaults::ENERGY_ERROR_FAIL,
        });
    }
    Ok((!within(woodpile::defaults::ENERGY_ERROR_WARN)).then(|| {
        format!(
            "the energy balance is off by {err:.2e} of {ENERGY_REFERENCE} (above {:.0e}): the results may be inaccurate; use a smaller run.peak_tolerance (or run.time_step_s under rk4, rtol/atol under dopri5)",
            woodpile::defaults::ENERGY_ERROR_WARN
        )
    }))
}
