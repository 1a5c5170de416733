//! Breeder genetic algorithm for the element arrangement that transmits the least force
//! (docs/physics.md §11; paper §4).
//!
//! - [`DesignSpace`]: N positions (or any N in a range: the number of layers as part of the
//!   design) filled from a catalogue of [`crate::Element`]s, how the chain
//!   is held and loaded, the run settings and the designer's [`Constraints`]; [`FeasibleSet`]
//!   proves the constraints can be met and repairs genomes into them.
//! - [`Objective`]: what is minimised; [`StandardObjective`] holds the transmitted peak force
//!   (the paper's), the transmission ratio, the peak energy of the last layer and the impulse
//!   delivered to the wall. Every evaluation runs the full window (no early stopping).
//! - [`DesignFigure`]: objectives as data (the run's figures, total mass, stack height, layers,
//!   the worst contact's Hertz peak pressure), evaluated together by [`figures_many`] (no run
//!   for the figures that need none; [`run_figures_many`] for runs of any chains and
//!   excitations); [`Nsga2`]: NSGA-II over the same genomes, operators and repair, with
//!   [`pareto`]'s sorting, crowding distance and hypervolume, its figures from a
//!   [`FigureEvaluator`] (default [`NominalFigures`]; a front end may supply robust ones).
//!   NSGA-II is written over a [`GenomeSpace`] (genes with their choice counts, variation and
//!   repair, a batch evaluator): the chains' [`ChainDesigns`] and the lattices'
//!   [`LatticeDesigns`] (rod length per layer and the pitch, docs/physics.md §16).
//! - [`operators`]: truncation selection, discrete recombination, BGA mutation, as plain
//!   functions of (population, rng).
//! - [`BreederGa`]: one generation at a time ([`BreederGa::next_generation`]) on a detachable
//!   [`GaState`], and the driver [`BreederGa::run`] with a stop flag and an observer for
//!   progress and checkpoints. Results are bit-identical for a seed whatever the thread count.
//!   With [`GaSettings::screen_peak_tolerance`] new designs are simulated first at a looser
//!   accuracy, and again at the run's only where their rank could decide a selection
//!   ([`BreederGa::settle`]): the same choices for less work.
//!
//! ```
//! use std::sync::atomic::AtomicBool;
//! use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, StandardObjective};
//! use woodpile::{CellModel, RunSettings};
//!
//! // 3 positions, Table 1 rods, a short impact: a quick search.
//! let mut space = DesignSpace::paper_impact(CellModel::Resonant);
//! space.positions = 3;
//! space.settings = RunSettings { duration_s: 1e-4, ..space.settings };
//! let settings = GaSettings { population: 6, generations: 2, threads: 1, ..GaSettings::default() };
//! let ga = BreederGa::new(space, Box::new(StandardObjective::TransmittedForce), settings)?;
//! let outcome = ga.run(None, &AtomicBool::new(false), &mut |_| std::ops::ControlFlow::Continue(()))?;
//! assert_eq!(outcome.state.history.len(), 3);
//! assert!(outcome.state.best().objective > 0.0);
//! # Ok::<(), woodpile::optimize::OptimizeError>(())
//! ```
//!
//! ## References
//! - H. Mühlenbein, D. Schlierkamp-Voosen, "Predictive models for the breeder genetic algorithm
//!   I. Continuous parameter optimization", Evolutionary Computation 1 (1993) 25–49.
//! - Kim, Yang et al., Int. J. Impact Eng. 2017, §4.

mod error;
mod figures;
mod ga;
mod lattice;
mod nsga2;
mod objective;
pub mod operators;
pub mod pareto;
mod space;

pub use error::OptimizeError;
pub use figures::{
    contact_peak_pressures_pa, figures_many, run_figures_many, DesignFigure, FigureEvaluator,
    NominalFigures,
};
pub use ga::{
    BreederGa, GaSettings, GaState, GenerationStats, Individual, Ledger, Outcome, StopReason,
    STOP_EARLY_MARGIN,
};
pub use lattice::{LatticeDesignSpace, LatticeDesigns, LATTICE_FIGURES, MAX_LATTICE_CHOICES};
pub use nsga2::{
    ChainDesigns, GenomeSpace, MoIndividual, Nsga2, Nsga2Settings, Nsga2State, Nsga2Stats,
};
pub use objective::{ContactImpulse, LayerEnergyPeak, Objective, StandardObjective, Valued};
pub use space::{
    element_height_m, Constraints, DesignSpace, FeasibleSet, Genome, MAX_CATALOGUE_LEN,
    MAX_VARIABLE_POSITIONS,
};
