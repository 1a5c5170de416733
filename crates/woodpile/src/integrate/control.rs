//! The adaptive step-size controller of one run, shared by the [`Integrator`](super::Integrator)
//! and by each lane of `crate::lanes`: which step to try, whether it lands on a contact's
//! crossing, what an attempt's error norm decides, and the next step.

use super::{next_step_after_accept, next_step_after_reject, IntegratorStats};
use crate::error::{Error, Result};

/// What an attempted step decided.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Verdict {
    /// The step is accepted.
    Accept,
    /// Try again from the same point: a smaller step after a rejection, or a step retaken to end
    /// on a crossing the attempt missed.
    Retry,
}

/// The controller's state between steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct StepControl {
    /// The step the controller proposes \[s\].
    pub h: f64,
    /// Error norm of the last accepted step that was not a landing (for the PI controller).
    pub err_prev: f64,
    /// Whether an attempt from the current point was rejected (the step may then not grow, and
    /// no crossing is predicted).
    pub rejected_before: bool,
    /// Whether the current attempt was shortened to land on a crossing.
    pub landing: bool,
    /// A step to retake so that it ends on a crossing the last attempt missed.
    pub retake: Option<f64>,
}

impl StepControl {
    /// A controller that proposes `h` first.
    pub fn new(h: f64) -> Self {
        StepControl {
            h,
            err_prev: 1e-4,
            rejected_before: false,
            landing: false,
            retake: None,
        }
    }

    /// The step to try from t toward t_end: the proposal, cut at t_end; an error when it is
    /// below the smallest step allowed there ([`super::min_step_s`]).
    pub fn propose(&self, t: f64, t_end: f64) -> Result<f64> {
        let remaining = t_end - t;
        let h_try = self.h.min(remaining);
        if h_try < super::min_step_s(t, t_end) && h_try < remaining {
            return Err(Error::StepSizeTooSmall {
                time_s: t,
                step_s: h_try,
            });
        }
        Ok(h_try)
    }

    /// Whether this attempt may be shortened to land on a predicted crossing: not while
    /// retaking a step, nor after a rejection from the same point.
    pub fn predicts(&self) -> bool {
        self.retake.is_none() && !self.rejected_before
    }

    /// The step actually tried: a retake's, else the predicted crossing's, else `h_try`.
    pub fn land(&mut self, h_try: f64, predicted: Option<f64>) -> f64 {
        let tau = self.retake.take().or(predicted);
        self.landing = tau.is_some();
        tau.unwrap_or(h_try)
    }

    /// The verdict on an attempt of size `h_try` with error norm `err` (≤ 1 passes) and, for a
    /// passing attempt of RKN 6(4) that was no landing, the first crossing it missed. A rejection
    /// or a retake counts as a rejected step.
    pub fn judge(
        &mut self,
        h_try: f64,
        err: f64,
        missed: Option<f64>,
        order: f64,
        stats: &mut IntegratorStats,
    ) -> Verdict {
        if let Some(tau) = missed {
            stats.rejected_steps += 1;
            self.retake = Some(tau);
            return Verdict::Retry;
        }
        if err <= 1.0 {
            return Verdict::Accept;
        }
        stats.rejected_steps += 1;
        self.rejected_before = true;
        self.h = next_step_after_reject(h_try, err, order);
        Verdict::Retry
    }

    /// After an accepted step of size `h_try` with error norm `err`: the next proposal. A step
    /// shortened to land on a crossing keeps the proposal and the last error norm (its error says
    /// nothing about the step the dynamics allow).
    pub fn accepted(&mut self, h_try: f64, err: f64, order: f64) {
        if !self.landing {
            self.h = next_step_after_accept(
                self.h,
                h_try,
                err,
                self.err_prev,
                order,
                self.rejected_before,
            );
            self.err_prev = err.max(1e-4);
        }
        self.rejected_before = false;
    }
}
