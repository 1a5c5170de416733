//! # woodpile-io
//!
//! Everything between the physics core ([`woodpile`]) and a front end (the `woodpile` command
//! line, the Python package): the file formats, shared so that every front end reads and writes
//! the same files with the same checks.
//!
//! - [`scenario`]: the TOML scenario format ([`scenario::Scenario`]), completion of its
//!   defaults, the built-in scenarios, TOML emission and [`scenario::resolve`] into a
//!   [`woodpile::Chain`], [`woodpile::Excitation`] and [`woodpile::RunSettings`].
//! - [`table`]: blast force tables from CSV.
//! - [`cells`]: a rod's unit cell derived by beam theory, as one typed record.
//! - [`rundir`]: the run directory (`summary.json`, `run.json`, CSV and `.npy`), written and
//!   read back.
//! - [`npy`]: NumPy `.npy` float64 arrays, written and read.
//! - [`atomic`]: atomic file replacement and staged run directories.
//! - [`limits`]: up-front limits (threads, steps, output size) with overrides.
//! - [`optimize`]: the optimisation config, the problem it defines and its checkpoint.
//! - [`transmission`]: the output directory of a transmission spectrum.
//! - [`Error`]: every failure, typed, naming the field, the value and what would be valid.

pub mod atomic;
pub mod cells;
pub mod error;
pub mod limits;
pub mod npy;
pub mod optimize;
pub mod rundir;
pub mod scenario;
pub mod table;
pub mod transmission;

pub use error::Error;
