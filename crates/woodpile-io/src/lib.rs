//! # woodpile-io
//!
//! Everything between the physics core ([`woodpile`]) and a front end (the `woodpile` command
//! line, the Python package): the file formats, shared so that every front end reads and writes
//! the same files with the same checks, and says what is wrong in the words of the files.
//!
//! ## Map, in the order a front end works
//!
//! 1. **Read a scenario** — [`scenario`]: the TOML format ([`scenario::Scenario`]), the built-in
//!    scenarios, and [`scenario::keys()`], the one table of its keys (type, unit, default, choices,
//!    alternatives). [`scenario::Scenario::complete`] writes every default once;
//!    [`scenario::Scenario::to_toml`] writes the completed file with a comment per key;
//!    [`scenario::resolve`] checks it and builds the core's [`woodpile::Chain`],
//!    [`woodpile::Excitation`] and [`woodpile::RunSettings`]. Inputs it names: [`table`] (blast
//!    force tables from CSV), [`cells`] (a rod's unit cell derived by beam theory).
//! 2. **Check before running** — [`limits`]: threads, steps and output size, each with its
//!    override; after the run, the energy balance ([`limits::check_accuracy`]).
//! 3. **Write and read back** — [`atomic`] (atomic files, staged run directories with one
//!    overwrite policy), [`rundir`] (`summary.json`, `run.json`, CSV and [`npy`] arrays),
//!    [`transmission`] (a transmission spectrum's directory).
//! 4. **Optimise** — [`optimize`]: the optimisation config, the problem it defines, its
//!    checksummed checkpoint and outputs; [`pareto`]: NSGA-II's checkpoint and its Pareto
//!    outputs (`pareto.csv`, `pareto/NNN.toml`, hypervolume history); [`lattice_study`]: a
//!    `[lattice]` config's design study (rod lengths and pitch) and its files; [`uncertainty`]: a
//!    scenario's `[uncertainty]` (manufacturing scatter as per-parameter distributions);
//!    [`robust`]: `ga.robust`, the GA's objective as a statistic over that scatter.
//!    [`sensitivity`]: a Saltelli design of that scatter and the Sobol' indices' files.
//! 5. **Calibrate** — [`fit`]: the fit file (a scenario, measured CSV files mapped to model
//!    outputs, the fitted parameters) and the outputs of a fit.
//! 6. **Say what went wrong** — [`Error`]: typed, naming the field, the value and what is valid
//!    ([`Error::field`], [`Error::value`], [`Error::reason`]); [`Error::kind`] sorts it for a
//!    front end, which words its own options (no exit codes or flag names here).
//!
//! ```
//! use woodpile_io::error::ErrorKind;
//! use woodpile_io::scenario::{key, resolve, Scenario};
//!
//! let text = "[chain]\nrods_mm = [80, 40, 20]\n[run]\nduration_s = 1e-4\n";
//! let resolved = resolve(&Scenario::parse(text)?, std::path::Path::new("."))?;
//! assert_eq!(resolved.chain.len(), 3);
//!
//! // The keys table gives each key's default and unit ...
//! let step = key("run.time_step_s").expect("a key of the file");
//! assert_eq!(step.unit, "s");
//! // ... and errors name the key, the value and what is valid.
//! let bad = Scenario::parse("[chain]\nrods_mm = [45]\n")?;
//! let e = resolve(&bad, std::path::Path::new(".")).unwrap_err();
//! assert_eq!((e.kind(), e.field()), (ErrorKind::Scenario, Some("chain.rods_mm[0]")));
//! # Ok::<(), woodpile_io::Error>(())
//! ```

/// This version of woodpile, as written into every file it writes (run directories, checkpoints,
/// summaries) and checked where a file must come from the same version (a checkpoint to resume).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

pub mod atomic;
pub mod cells;
pub mod error;
pub mod fit;
pub mod lattice;
pub mod lattice_study;
pub mod limits;
pub mod npy;
pub mod optimize;
mod optimize_config;
pub mod pareto;
pub mod robust;
pub mod rundir;
pub mod scenario;
pub mod sensitivity;
pub mod table;
pub mod text;
pub mod transmission;
pub mod uncertainty;

pub use error::Error;
