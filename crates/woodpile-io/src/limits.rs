//! Up-front limits on what a command may start, each with a clear message and an override, so
//! that a typo (`--threads 100000`, `duration_s = 1e6`) is an error at once rather than a hang.

use crate::error::Error;

/// Most worker threads allowed per available core without an override.
pub const THREADS_PER_CORE: usize = 4;

/// The cores this process may use (1 when unknown).
pub fn available_cores() -> usize {
    std::thread::available_parallelism().map_or(1, usize::from)
}

/// Checks a worker-thread count (0 = one per core). More than [`THREADS_PER_CORE`] per
/// available core is refused unless `allow` is set; `field` names the option (`--threads`).
pub fn check_threads(field: &str, threads: usize, allow: bool) -> Result<usize, Error> {
    let cores = available_cores();
    let most = THREADS_PER_CORE * cores;
    if threads > most && !allow {
        return Err(Error::invalid(
            field,
            threads,
            format!(
                "at most {most} ({THREADS_PER_CORE} per core, {cores} cores here); 0 = one per core; \
                 pass --allow-many-threads to use more anyway"
            ),
        ));
    }
    Ok(threads)
}
