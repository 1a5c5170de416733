//! Typed errors of the library. Every variant carries the numbers a user needs to fix the problem.

/// Everything that can go wrong while building or running a model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter is outside its valid range.
    #[error("invalid {field} = {value}: {reason}")]
    InvalidParameter {
        /// Dotted path of the field, e.g. `chain.elements[3].diameter_m`.
        field: String,
        /// The offending value as given.
        value: String,
        /// What would be valid.
        reason: String,
    },
    /// A name (material, rod length, scenario, …) that is not in its catalogue.
    #[error("unknown {what} `{name}` (valid: {valid})")]
    Unknown {
        /// What kind of name it is ("material", "rod length", …).
        what: &'static str,
        /// The name as given.
        name: String,
        /// The valid names, comma separated.
        valid: String,
    },
    /// Two bodies whose contact is not a Hertzian point contact (e.g. parallel cylinders, a
    /// cylinder on a flat): the force law is not δ^{3/2}.
    #[error("{what}: not a point contact ({reason}); give a spherical cap radius or set the contact coefficient beta directly")]
    NotPointContact {
        /// Which contact.
        what: String,
        /// Why.
        reason: String,
    },
    /// The state became NaN or infinite.
    #[error("numerical blow-up at t = {time_s:.6e} s starting at contact {contact}: the state became non-finite; the step is too large for this contact: reduce run.time_step_s (rk4) or tighten rtol/atol (dopri5)")]
    NonFiniteState {
        /// Simulation time \[s\].
        time_s: f64,
        /// Contact index in the paper's numbering (0 = striker/load, N = wall).
        contact: usize,
    },
    /// A contact overlap grew beyond the range where the Hertz law is physical.
    #[error("numerical blow-up at t = {time_s:.6e} s: overlap at contact {contact} is {overlap_m:.3e} m, beyond the physical limit {limit_m:.3e} m (10 % of the smallest radius of curvature), and a step 256 times smaller stays within it: the step is too large: reduce run.time_step_s (rk4) or tighten rtol/atol (dopri5)")]
    RunawayOverlap {
        /// Simulation time \[s\].
        time_s: f64,
        /// Contact index in the paper's numbering.
        contact: usize,
        /// Overlap δ \[m\].
        overlap_m: f64,
        /// Largest physical overlap \[m\].
        limit_m: f64,
    },
    /// The wave never reached the wall within the run, so a transmitted figure would be a
    /// meaningless number (docs/physics.md §8).
    #[error("the wave did not reach the wall within run.duration_s = {duration_s:e} s (transmitted peak {transmitted_n:.3e} N against an incident {incident_n:.3e} N): a transmitted figure would mean nothing; increase run.duration_s")]
    WaveNotArrived {
        /// Simulated time \[s\].
        duration_s: f64,
        /// Peak force at the wall \[N\].
        transmitted_n: f64,
        /// Peak force of contact 1 \[N\].
        incident_n: f64,
    },
    /// A contact was compressed beyond its physical range even when the failing step was
    /// re-integrated with much smaller steps: the load is more than the contact can take, and no
    /// time step will help.
    #[error("the load exceeds what contact {contact} can take: at t = {time_s:.6e} s its overlap reached {overlap_m:.3e} m, beyond its physical range {limit_m:.3e} m (10 % of the smallest radius of curvature), also with steps 256 times smaller; the {energy_j:.3e} J in the system could compress it by up to {reachable_m:.3e} m. Reduce the impact velocity or the load, or model a stiffer or larger contact (beta, cap radius); a smaller time step will not help")]
    LoadBeyondContact {
        /// Simulation time \[s\].
        time_s: f64,
        /// Contact index in the paper's numbering.
        contact: usize,
        /// Overlap δ reached \[m\].
        overlap_m: f64,
        /// Largest physical overlap \[m\].
        limit_m: f64,
        /// Total energy in the system at the start of the failing step \[J\].
        energy_j: f64,
        /// Overlap that energy could produce at this contact, (5 E / 2β)^{2/5} \[m\].
        reachable_m: f64,
    },
    /// The run stopped because a stop was requested ([`crate::interrupt`]: Ctrl-C, SIGTERM,
    /// Python's `KeyboardInterrupt`).
    #[error("interrupted at t = {time_s:.6e} s")]
    Interrupted {
        /// Simulation time reached \[s\] (0 for a run that never started).
        time_s: f64,
    },
    /// The load asks more of a contact than its physical range, judged from statics and energy
    /// alone: the load's peak force held statically, or the striker's whole kinetic energy of
    /// relative motion stored in the contact, would compress it beyond 10 % of its smallest radius
    /// of curvature. No time step will help.
    #[error("the load exceeds what contact {contact} can take: {load} would compress it by {needed}, beyond its physical range {limit_m:.3e} m (10 % of the smallest radius of curvature); the run blew up at t = {time_s:.6e} s. Reduce the load, or model a stiffer or larger contact (beta, cap radius); a smaller time step will not help")]
    LoadExceedsContact {
        /// Simulation time of the blow-up \[s\].
        time_s: f64,
        /// Contact index in the paper's numbering.
        contact: usize,
        /// The load, in words with its numbers (e.g. "the blast's peak force 1.000e9 N held
        /// statically").
        load: String,
        /// The overlap it needs, in words ("1.234e-3 m", or "more than any finite overlap").
        needed: String,
        /// Largest physical overlap \[m\].
        limit_m: f64,
    },
    /// The run needed more integration steps than allowed.
    #[error("the run stopped after {steps} integration steps at t = {time_s:.6e} s of run.duration_s = {duration_s:e} s (limit {steps}); shorten run.duration_s, use a larger run.time_step_s, or loosen rtol")]
    TooManySteps {
        /// Steps taken.
        steps: u64,
        /// Simulation time reached \[s\].
        time_s: f64,
        /// Requested duration \[s\].
        duration_s: f64,
    },
    /// The adaptive integrator could not meet its tolerance.
    #[error("adaptive step size fell to {step_s:.3e} s at t = {time_s:.6e} s, below 1e-10 of the run: the system is too stiff for the tolerance (a very stiff resonator or contact?); check the cell's stiffnesses, loosen rtol/atol, or use rk4 with a small fixed step")]
    StepSizeTooSmall {
        /// Simulation time \[s\].
        time_s: f64,
        /// The step it tried \[s\].
        step_s: f64,
    },
}

/// Result alias of the library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        Error::InvalidParameter {
            field: field.into(),
            value: readable_number(value.to_string()),
            reason: reason.into(),
        }
    }
}

/// A number written out in more than 16 characters (`1e300` prints as 301 digits) in its
/// shortest scientific form; any other text as it is.
fn readable_number(text: String) -> String {
    match text.parse::<f64>() {
        Ok(x) if text.len() > 16 && x.is_finite() => format!("{x:e}"),
        _ => text,
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn require_positive(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "must be a finite number > 0"))
    }
}

/// Checks that `value` is finite and not negative.
pub fn require_non_negative(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "must be a finite number >= 0"))
    }
}
