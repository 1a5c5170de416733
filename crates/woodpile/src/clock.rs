//! The wall clock that runs and studies report their time by (`wall_time_s`, a generation's
//! `elapsed_s`), as the one place the library reads the platform's time.
//!
//! On an operating system it is [`std::time::Instant`]. In a browser (`wasm32-unknown-unknown`)
//! the standard library has no clock (`Instant::now` panics there), so the front end that runs
//! the library there gives it one with [`set_source`] (the page's `performance.now()`); until it
//! does, elapsed times there are NaN: not measured, never a made-up zero.

use std::sync::OnceLock;

/// A clock in milliseconds from any fixed origin.
pub type Source = fn() -> f64;

static SOURCE: OnceLock<Source> = OnceLock::new();

/// Makes `source` the library's clock where the platform has none. The first call wins; later
/// ones are ignored (one clock per process). Where the platform has a clock, it is kept.
pub fn set_source(source: Source) {
    let _ = SOURCE.set(source);
}

/// A started stopwatch.
#[derive(Debug, Clone, Copy)]
pub struct Stopwatch {
    #[cfg(not(all(target_family = "wasm", target_os = "unknown")))]
    started: std::time::Instant,
    #[cfg(all(target_family = "wasm", target_os = "unknown"))]
    started_ms: f64,
}

impl Stopwatch {
    /// Starts a stopwatch now.
    pub fn start() -> Self {
        Stopwatch {
            #[cfg(not(all(target_family = "wasm", target_os = "unknown")))]
            started: std::time::Instant::now(),
            #[cfg(all(target_family = "wasm", target_os = "unknown"))]
            started_ms: now_ms(),
        }
    }

    /// Seconds since [`Stopwatch::start`] (NaN where no clock is at hand).
    pub fn elapsed_s(&self) -> f64 {
        #[cfg(not(all(target_family = "wasm", target_os = "unknown")))]
        return self.started.elapsed().as_secs_f64();
        #[cfg(all(target_family = "wasm", target_os = "unknown"))]
        return (now_ms() - self.started_ms) * 1e-3;
    }
}

/// The given clock's reading \[ms\], or NaN without one.
#[cfg(all(target_family = "wasm", target_os = "unknown"))]
fn now_ms() -> f64 {
    SOURCE.get().map_or(f64::NAN, |source| source())
}
