//! Claim: `[run] peak_tolerance` states an accuracy instead of an integrator: it resolves to the
//! core's choice for that accuracy (`Method::for_peak_tolerance`, the single source of the
//! mapping), `to_toml()` and completion keep it (and add no integrator beside it), and a file
//! that states both an accuracy and integrator settings, or an accuracy that is not a small
//! relative error, is refused naming the key to fix. No tolerance: the file format only moves
//! the number.

use std::path::Path;
use woodpile::Method;
use woodpile_io::scenario::{resolve, Scenario};

const CHAIN: &str = "[chain]\nrods_mm = [80, 40, 20]\n";

fn method_of(run: &str) -> Result<Method, String> {
    let s = Scenario::parse(&format!("{CHAIN}[run]\n{run}")).map_err(|e| e.to_string())?;
    resolve(&s, Path::new("."))
        .map(|r| r.settings.method)
        .map_err(|e| e.to_string())
}

#[test]
fn a_stated_accuracy_resolves_to_the_cores_choice() {
    assert_eq!(
        method_of("peak_tolerance = 1e-5\n").unwrap(),
        Method::for_peak_tolerance(1e-5).unwrap()
    );
}

#[test]
fn written_out_and_completed_scenarios_keep_the_accuracy() {
    let s = Scenario::parse(&format!("{CHAIN}[run]\npeak_tolerance = 1e-4\n")).unwrap();
    let text = s.to_toml();
    assert!(text.contains("peak_tolerance = "), "{text}");
    let again = resolve(&Scenario::parse(&text).unwrap(), Path::new(".")).unwrap();
    assert_eq!(
        again.settings.method,
        Method::for_peak_tolerance(1e-4).unwrap()
    );
    let completed = s.complete();
    assert_eq!(completed.run.integrator, None);
    assert_eq!(completed.run.time_step_s, None);
    resolve(&completed, Path::new(".")).unwrap();
}

#[test]
fn conflicting_or_meaningless_accuracies_name_their_key() {
    for (run, key) in [
        (
            "peak_tolerance = 1e-5\nintegrator = \"rk4\"\n",
            "run.integrator",
        ),
        ("peak_tolerance = 1e-5\nrtol = 1e-9\n", "run.rtol"),
        (
            "peak_tolerance = 1e-5\ntime_step_s = 1e-7\n",
            "run.time_step_s",
        ),
        ("peak_tolerance = 0.5\n", "run.peak_tolerance"),
        ("peak_tolerance = -1e-5\n", "run.peak_tolerance"),
        // Below the calibrated range (it was accepted and silently clamped to rtol 1e-13).
        ("peak_tolerance = 1e-15\n", "at least 2e-7"),
    ] {
        let e = method_of(run).unwrap_err();
        assert!(e.contains(key), "{run}: {e}");
    }
}
