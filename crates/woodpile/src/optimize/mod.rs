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

mod figures;
mod ga;
mod lattice;
mod nsga2;
mod objective;
pub mod operators;
pub mod pareto;
mod space;

pub use figures::{
    contact_peak_pressures_pa, element_height_m, figures_many, run_figures_many, DesignFigure,
    FigureEvaluator, NominalFigures,
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
    Constraints, DesignSpace, FeasibleSet, Genome, MAX_CATALOGUE_LEN, MAX_VARIABLE_POSITIONS,
};

/// What can go wrong in an optimisation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OptimizeError {
    /// An invalid parameter of the design space or the GA settings.
    #[error(transparent)]
    Model(#[from] crate::Error),
    /// No design meets the constraints.
    #[error("infeasible constraints: {reason}")]
    Infeasible {
        /// Which constraints conflict, with their numbers.
        reason: String,
    },
    /// Even the lightest design that meets the other constraints is above the mass limit.
    #[error("infeasible constraints: design.constraints.max_total_mass_kg = {max_total_mass_kg} kg, but the lightest design meeting the other constraints weighs {lightest_kg} kg ({lightest})")]
    TooHeavy {
        /// The limit \[kg\].
        max_total_mass_kg: f64,
        /// The lightest design's mass \[kg\].
        lightest_kg: f64,
        /// Its element labels, top to bottom.
        lightest: String,
    },
    /// Even the lowest design that meets the other constraints is above the height limit.
    #[error("infeasible constraints: design.constraints.max_stack_height_m = {max_stack_height_m} m, but the lowest design meeting the other constraints stands {lowest_m} m high ({lowest})")]
    TooTall {
        /// The limit \[m\].
        max_stack_height_m: f64,
        /// The lowest design's height \[m\].
        lowest_m: f64,
        /// Its element labels, top to bottom.
        lowest: String,
    },
    /// Simulating a candidate failed.
    #[error("evaluating design [{design}] failed: {source}")]
    Simulation {
        /// Labels of the design, top to bottom.
        design: String,
        /// The simulation's error.
        source: crate::Error,
    },
    /// An objective returned NaN.
    #[error("objective `{objective}` returned NaN for design [{design}]")]
    NotANumber {
        /// The objective's name.
        objective: String,
        /// Labels of the design, top to bottom.
        design: String,
    },
    /// A saved state does not belong to this problem.
    #[error("the saved GA state does not match this problem: {reason}")]
    StateMismatch {
        /// What differs.
        reason: String,
    },
    /// The worker threads could not be started.
    #[error("could not start {threads} worker threads: {reason}")]
    ThreadPool {
        /// Requested thread count.
        threads: usize,
        /// The system's reason.
        reason: String,
    },
}

/// The checks every algorithm's saved state starts with: its population size against the
/// settings', and one history line per generation (0 included).
pub(crate) fn check_counts(
    population: usize,
    settings_population: usize,
    history: usize,
    generation: usize,
) -> Result<(), OptimizeError> {
    let mismatch = |reason: String| Err(OptimizeError::StateMismatch { reason });
    if population != settings_population {
        return mismatch(format!(
            "population has {population} individuals, the settings ask for {settings_population}"
        ));
    }
    if history != generation + 1 {
        return mismatch(format!(
            "history has {history} lines for generation {generation}"
        ));
    }
    Ok(())
}

impl OptimizeError {
    /// Whether a stop request ([`crate::interrupt`]) ended the evaluation.
    pub fn is_interrupted(&self) -> bool {
        matches!(
            self,
            OptimizeError::Simulation {
                source: crate::Error::Interrupted { .. },
                ..
            }
        )
    }
}
