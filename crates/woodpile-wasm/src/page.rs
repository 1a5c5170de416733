//! The module's interface to the page: plain exports over the module's linear memory, so that
//! the page needs no generated glue (a few lines of its own JavaScript, `docs/playground/`).
//!
//! 1. `woodpile_input(len)` lends a buffer of `len` bytes and returns its address; the page
//!    writes the scenario's UTF-8 there.
//! 2. `woodpile_run()` runs it ([`crate::run_toml`]) and returns the length of the JSON answer.
//! 3. `woodpile_output()` returns the answer's address; the page decodes `len` bytes there.
//! 4. `woodpile_samples()` and `woodpile_samples_len()`: the address and the count of the
//!    samples' numbers (f64, [`crate::Answer::samples`]), which the page copies out.
//!
//! The buffers belong to the module and live until the next call; nothing is freed by the page.
//! Exported symbols are what `#[no_mangle]` is for, which the workspace's `unsafe_code` lint
//! counts: allowed here, on these items only, because the names are unique to this crate. No
//! pointer is dereferenced on this side; the page reads and writes the bytes.

use std::cell::RefCell;

thread_local! {
    static INPUT: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    static OUTPUT: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    static SAMPLES: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

/// Lends the page a buffer of `len` bytes for the scenario's TOML; returns its address.
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn woodpile_input(len: usize) -> *mut u8 {
    INPUT.with_borrow_mut(|input| {
        input.clear();
        input.resize(len, 0);
        input.as_mut_ptr()
    })
}

/// Runs the scenario the page wrote and returns the length of the JSON answer in bytes.
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn woodpile_run() -> usize {
    start_clock();
    let answer = INPUT.with_borrow(|input| match std::str::from_utf8(input) {
        Ok(toml) => crate::run_toml(toml),
        Err(e) => crate::Answer {
            json: serde_json::json!({
                "ok": false,
                "error": format!("the scenario is not UTF-8 text: {e}"),
            })
            .to_string(),
            samples: Vec::new(),
        },
    });
    SAMPLES.set(answer.samples);
    OUTPUT.with_borrow_mut(|output| {
        *output = answer.json.into_bytes();
        output.len()
    })
}

/// The address of the last answer ([`woodpile_run`] gave its length).
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn woodpile_output() -> *const u8 {
    OUTPUT.with_borrow(|output| output.as_ptr())
}

/// The address of the last run's samples ([`crate::Answer::samples`]).
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn woodpile_samples() -> *const f64 {
    SAMPLES.with_borrow(|samples| samples.as_ptr())
}

/// How many numbers the last run's samples hold.
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn woodpile_samples_len() -> usize {
    SAMPLES.with_borrow(|samples| samples.len())
}

/// Makes the page's clock the library's (in the browser; elsewhere the platform's is kept).
fn start_clock() {
    #[cfg(all(target_family = "wasm", target_os = "unknown"))]
    woodpile::clock::set_source(page_now_ms);
}

#[cfg(all(target_family = "wasm", target_os = "unknown"))]
#[allow(unsafe_code)]
mod clock_import {
    #[link(wasm_import_module = "page")]
    unsafe extern "C" {
        /// The page's `performance.now()` \[ms\].
        pub safe fn now_ms() -> f64;
    }
}

/// The page's clock \[ms\].
#[cfg(all(target_family = "wasm", target_os = "unknown"))]
fn page_now_ms() -> f64 {
    clock_import::now_ms()
}
