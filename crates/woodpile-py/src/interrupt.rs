//! Ctrl-C while Rust runs: the work runs with the GIL released on a thread of its own while the
//! calling thread checks Python's signal handlers every [`POLL`]. A `KeyboardInterrupt` (or any
//! exception a handler raises) asks the library to stop ([`woodpile::interrupt`]): every run
//! ends at its next step, so the call returns within a fraction of a second and raises it.

use pyo3::prelude::*;
use std::sync::mpsc;
use std::time::Duration;

/// How often the signal handlers are checked while Rust works.
const POLL: Duration = Duration::from_millis(50);

/// Runs `work` with the GIL released, checking for signals meanwhile; the work's result and the
/// exception a signal handler raised, if any (the work then stopped early).
pub fn detach_polling<T, F>(py: Python<'_>, work: F) -> (T, Option<PyErr>)
where
    T: Send,
    F: FnOnce() -> T + Send,
{
    py.detach(|| {
        std::thread::scope(|scope| {
            let (done, finished) = mpsc::channel::<()>();
            let worker = scope.spawn(move || {
                let result = work();
                let _ = done.send(());
                result
            });
            let mut raised: Option<PyErr> = None;
            // Disconnected (the worker panicked) ends the wait as well.
            while let Err(mpsc::RecvTimeoutError::Timeout) = finished.recv_timeout(POLL) {
                if raised.is_none() {
                    if let Err(e) = Python::attach(|py| py.check_signals()) {
                        woodpile::interrupt::request();
                        raised = Some(e);
                    }
                }
            }
            let result = match worker.join() {
                Ok(result) => result,
                Err(panic) => std::panic::resume_unwind(panic),
            };
            if raised.is_some() {
                woodpile::interrupt::clear();
            }
            (result, raised)
        })
    })
}

/// [`detach_polling`], raising the signal handler's exception in place of the result when
/// there was one.
pub fn detach_interruptibly<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> PyResult<T> + Send,
{
    match detach_polling(py, work) {
        (_, Some(raised)) => Err(raised),
        (result, None) => result,
    }
}
