//! Python bindings of woodpile: the extension module `woodpile._core`, a thin layer over the
//! scenario format and run directories of `woodpile-io` and the physics core. The Python package
//! (`python/woodpile`) builds its API on these functions; every scenario crosses the boundary as
//! TOML text, so Python and the command line read the same files with the same checks.
//!
//! One binding file per module of the Python package:
//!
//! | binding | Python module | what |
//! | --- | --- | --- |
//! | [`scenario`] | `woodpile.scenario` | built-in scenarios, completion, TOML ↔ JSON |
//! | [`run`] | `woodpile.run` | one simulation, its arrays, its run directory |
//! | [`lattice`] | `woodpile.lattice` | one lattice run, its contacts and arrays, its run directory |
//! | [`study`] | `woodpile.study` | many scenarios at once (rayon, SIMD lanes) |
//! | [`analysis`] | `woodpile.analysis` | cells, effective mass, band gaps, spectra |
//! | [`optimize`] | `woodpile.optimize` | the breeder GA as ask/tell |
//! | [`pareto`] | `woodpile.optimize`, `woodpile.pymoo` | NSGA-II's fronts; a population's objectives and constraints |
//! | [`sensitivity`] | `woodpile.sensitivity` | Sobol' indices over `[uncertainty]` (Saltelli) |
//! | [`fit`] | `woodpile.fit` | calibration to measured signals, with uncertainties |
//! | [`errors`] | `woodpile.errors` | every error as a `WoodpileError` subclass |
//!
//! The GIL is released while Rust simulates, and Ctrl-C stops it within a step ([`interrupt`]).

mod analysis;
mod errors;
mod fit;
mod interrupt;
mod lattice;
mod optimize;
mod pareto;
mod run;
mod scenario;
mod sensitivity;
mod study;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    scenario::register(m)?;
    run::register(m)?;
    lattice::register(m)?;
    study::register(m)?;
    analysis::register(m)?;
    optimize::register(m)?;
    pareto::register(m)?;
    fit::register(m)?;
    sensitivity::register(m)?;
    Ok(())
}
