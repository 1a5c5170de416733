//! What can go wrong in an optimisation ([`OptimizeError`]), and the check of a saved state's
//! counts that the breeder GA and NSGA-II share.

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
