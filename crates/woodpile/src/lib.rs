//! # woodpile
//!
//! Discrete element model of locally resonant woodpile metamaterials under impact and blast
//! (Kim, Yang et al., Int. J. Impact Eng. 2017; the project's specification is `docs/physics.md`).
//!
//! ## Map of the crate, in the order a user works
//!
//! 1. **Build a chain** — [`model`]: [`Material`] presets, exact Hertz contact coefficients
//!    ([`model::hertz_beta`]), unit cells with internal resonators ([`UnitCell`], the paper's
//!    Table 1 catalogue, effective mass and band edges), cells of any rod from Timoshenko beam
//!    theory ([`Rod`], [`UnitCell::from_rod`]), and the [`Chain`] of elements on a [`Wall`],
//!    built by [`ChainBuilder`].
//!    Lattices of several rods per layer ([`model::LatticeBuilder`], docs/physics.md §16): every
//!    crossing a contact, every rod a free–free finite-element beam ([`model::FreeRodModes`])
//!    or its analytic Timoshenko bending modes ([`model::free_rod`]),
//!    run by [`simulate::simulate_lattice`] over the contact graph [`ode::LatticeOde`], struck,
//!    blasted or driven on load points, damped and preloaded ([`model::LatticeExcitation`],
//!    [`model::LatticeLab`]); any chain runs there too, with its load and lab physics
//!    ([`ode::LatticeOde::from_chain`]).
//!    Lab physics (docs/physics.md §14): contact, resonator and on-site [`Damping`]; a static
//!    [`Preload`] and gravity, from whose exact equilibrium a run starts.
//! 2. **Excite it** — [`excitation`]: a [`Striker`] sphere, a [`BlastProfile`] force, or an
//!    actuator [`Drive`] (force or displacement; harmonic, chirp or table [`Signal`]).
//! 3. **Integrate** — [`ode`] compiles the chain into y' = f(t, y) (each contact's force from its
//!    [`ContactLaw`](model::ContactLaw));
//!    [`integrate`] advances it with a Butcher [`Tableau`] (RK4, Dormand–Prince 5(4), or the
//!    Runge–Kutta–Nyström pair RKN6(4) for x'' = a(x); the adaptive ones optionally landing
//!    steps on contacts' predicted openings and closings); a stated peak tolerance
//!    ([`Method::PeakTolerance`]) picks the method per run; with finite-element rods
//!    [`Method::ExactModes`] integrates the cells' vibrations exactly in modal form (damped
//!    cells in their complex modes; under an impact, a blast, a drive, a preload and gravity),
//!    so that the contacts, not the stiffest mode, set the step. The equations, the stage loop, the
//!    error norm, the crossing prediction and the step control are written once over the number
//!    type, so [`simulate_many`] runs many designs in SIMD lanes ([`lanes`]) with any physics,
//!    bit for bit as [`simulate()`] runs each (docs/extending.md: adding a law or a method).
//! 4. **Run and record** — [`simulate()`] owns the loop, samples on a uniform grid for a
//!    [`Recorder`] (e.g. [`Trajectory`]) and returns the figures of merit ([`RunSummary`]).
//! 5. **Analyse** — [`analysis`]: spectra ([`Spectrum`]), spatio-temporal force and energy maps
//!    ([`Map2`]), effective-mass curves and band gaps ([`BandStructure`]), and the paper's
//!    layer-by-layer experimental protocol ([`LayerByLayer`]).
//! 6. **Optimise** — [`optimize`]: the breeder genetic algorithm ([`BreederGa`]) over a
//!    [`DesignSpace`] of catalogue elements, with a user-extensible [`Objective`]; NSGA-II
//!    ([`optimize::Nsga2`]) for the Pareto front of several [`optimize::DesignFigure`]s, over
//!    any [`optimize::GenomeSpace`]: chains' catalogues or a lattice's rod lengths and pitch
//!    ([`optimize::LatticeDesigns`]).
//!    Scatter: [`uncertainty`] draws scrambled Sobol' points, maps them through inverse CDFs and
//!    sums up the figures of a design's samples (mean, sd, quantiles, CVaR); [`sensitivity`]
//!    apportions a figure's variance to the scattered parameters (Sobol' indices, Saltelli
//!    sampling, SALib's estimators).
//! 7. **Calibrate** — [`fit`]: the parameters that best explain measured signals (bounded
//!    least squares from several starts), with standard errors, correlations and warnings for
//!    what the data cannot determine.
//!
//! Every long loop polls one process-wide stop request ([`interrupt`]), which front ends set on
//! Ctrl-C, SIGTERM or Python's `KeyboardInterrupt`; times are read from one [`clock`], which a
//! front end without an operating system (a browser page) supplies. Nothing else touches the
//! platform: no files, no threads but rayon's in the design studies, and no transcendental
//! function of the platform's C library (they come from `libm`, so that a run gives the same
//! numbers bit for bit everywhere, in a browser too: `crates/woodpile-wasm`).
//!
//! ```
//! use woodpile::{simulate, CellModel, ChainBuilder, Excitation, RunSettings, Striker, Trajectory};
//!
//! // The paper's 20-rod impact problem with a short chain: 80, 40 and 20 mm rods on the sensor.
//! let chain = ChainBuilder::table1_rods(&[80, 40, 20], CellModel::Resonant)?.build()?;
//! let impact = Excitation::Impact(Striker::paper());
//! let settings = RunSettings { duration_s: 5e-4, ..RunSettings::paper_impact() };
//! let mut trajectory = Trajectory::default();
//! let summary = simulate(&chain, &impact, &settings, &mut trajectory)?;
//! assert!(summary.transmitted_peak_force_n > 0.0);
//! assert!(summary.energy.max_relative_error < 1e-6);
//! assert_eq!(trajectory.len(), 501);
//! # Ok::<(), woodpile::Error>(())
//! ```
//!
//! ## Units and numbering
//! SI throughout. Displacements are positive from the striker toward the wall. Layer 0 is the
//! striker (or the load), layers 1..N the elements top to bottom; contact 0 is striker–element 1
//! (or the load), contact i is element i – element i+1, contact N is element N – wall.

pub mod analysis;
pub mod clock;
pub mod defaults;
pub mod error;
pub mod excitation;
pub mod fit;
pub mod integrate;
pub mod interrupt;
pub mod lanes;
mod math;
pub mod model;
pub mod ode;
pub mod optimize;
mod real;
pub mod record;
mod root;
pub mod sensitivity;
pub mod simulate;
pub mod uncertainty;

pub use analysis::{BandStructure, EffectiveMassCurve, LayerByLayer, Map2, Spectrum};
pub use error::{Error, Result};
pub use excitation::{
    velocity_from_drop_height, BlastProfile, Drive, DriveQuantity, Excitation, Signal, Striker,
    Sweep,
};
pub use integrate::{Integrator, IntegratorStats, Method, OdeSystem, Tableau};
pub use lanes::{simulate_many, simulate_many_stopping, simulate_many_watching, Job, LaneWidth};
pub use model::{
    BeamTheory, Body, CellModel, Chain, ChainBuilder, ContactDamping, Damping, Element, Material,
    Preload, Reduction, Resonator, ResonatorDamping, Rod, Surface, UnitCell, Wall,
    PAPER_OPTIMIZED_CHAIN_MM, TABLE1_LENGTHS_MM,
};
pub use optimize::{BreederGa, DesignSpace, GaSettings, Objective, StandardObjective};
pub use record::{EndForces, Layout, Recorder, Sample, Trajectory};
pub use simulate::{simulate, EnergyBalance, PeakWatch, Restitution, RunSettings, RunSummary};
