//! A request to stop, for the whole process: set by a front end when the user asks to stop
//! (the command line's Ctrl-C or SIGTERM handler, Python's `KeyboardInterrupt`), polled by every
//! long loop of the library.
//!
//! A signal is addressed to the process, not to one call, so the request is too: one flag that
//! [`simulate`](crate::simulate()) checks after every step and the lanes after every step of
//! every lane and before starting a queued run. A run that sees it ends with
//! [`Error::Interrupted`](crate::Error::Interrupted); runs not yet started end so at once. The
//! GA ([`BreederGa::run`](crate::BreederGa::run)) then returns its state at the last complete
//! generation with `StopReason::Interrupted`, so a checkpoint of it resumes exactly.
//!
//! The front end that requested the stop [`clear`]s it once the interrupted call has returned.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Asks every running simulation of the process to stop at its next step.
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Whether a stop has been requested (and not cleared).
#[inline]
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// Withdraws the request, so that later calls run normally.
pub fn clear() {
    REQUESTED.store(false, Ordering::SeqCst);
}
