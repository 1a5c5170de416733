//! Ctrl-C and SIGTERM, one handler for every command.
//!
//! A command that can stop cleanly by itself (`optimize`: it abandons the generation under way,
//! writes its outputs from the last complete one and exits 130; its checkpoint resumes exactly) marks itself [`cooperative`] and polls [`stop_flag`]. For every other
//! command the handler removes the staging directories of unfinished outputs (so the output
//! location is as it was) and exits at once with [`EXIT_INTERRUPTED`].

use std::sync::atomic::{AtomicBool, Ordering};

/// Exit status of an interrupted command (128 + SIGINT), so scripts can tell it from success (0),
/// a failed run (1) and bad input (2).
pub const EXIT_INTERRUPTED: u8 = 130;

static STOP: AtomicBool = AtomicBool::new(false);
static COOPERATIVE: AtomicBool = AtomicBool::new(false);
static STOP_RUNS: AtomicBool = AtomicBool::new(false);

/// Installs the handler (once per process; later calls do nothing). For a command that
/// declared [`cooperative`] with `stop_runs`, the first interrupt also asks the library to stop
/// every run at its next step ([`woodpile::interrupt`]), so it stops within a step rather than
/// at the end of its current stage; a second interrupt ends even a cooperative command at once,
/// its unfinished outputs removed.
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        let again = STOP.swap(true, Ordering::SeqCst);
        if STOP_RUNS.load(Ordering::SeqCst) {
            woodpile::interrupt::request();
        }
        if again || !COOPERATIVE.load(Ordering::SeqCst) {
            woodpile_io::atomic::remove_active_staging();
            crate::out::eprintln(if again {
                "interrupted again: stopped at once; the last checkpoint is kept"
            } else {
                "interrupted: nothing was written"
            });
            std::process::exit(i32::from(EXIT_INTERRUPTED));
        }
    });
}

/// Declares that the running command polls [`stop_flag`] and stops cleanly by itself;
/// `stop_runs`: the runs under way are stopped too (a GA abandons its generation), rather than
/// finished (a fit, whose runs are short and whose best point is simulated once more).
pub fn cooperative(stop_runs: bool) {
    STOP_RUNS.store(stop_runs, Ordering::SeqCst);
    COOPERATIVE.store(true, Ordering::SeqCst);
}

/// Set once an interrupt has arrived.
pub fn stop_flag() -> &'static AtomicBool {
    &STOP
}
