//! woodpile in a browser page (`docs/playground/`): the library built for
//! `wasm32-unknown-unknown`, one call from a scenario's TOML to its run.
//!
//! [`run_toml`] reads the scenario as `woodpile simulate` reads a file (woodpile-io: the same
//! checks, defaults and messages), runs it with the same library call and returns one JSON
//! object, `{"ok": true, "summary": …, "series": …, "warnings": […]}` where `summary` is
//! `summary.json`'s object key for key and `series` names the contacts and counts the samples,
//! or `{"ok": false, "error": "…"}` with the message the command line prints after `error: `;
//! and the samples themselves as numbers (the times, then every sample's contact forces), which
//! the page reads as one `Float64Array`, not as text. A chain's or a lattice's scenario alike.
//!
//! The page talks to the module through five exports over its linear memory ([`page`]): it
//! writes the TOML's bytes into a buffer the module lends, calls the run, and reads the JSON and
//! the samples back. The module imports one function, the page's clock (`performance.now()`), which becomes
//! the library's ([`woodpile::clock`]) so that `wall_time_s` is measured in the page too.

use serde::Serialize;
use serde_json::{json, Value};
use std::path::Path;
use woodpile::{simulate, Trajectory};
use woodpile_io::lattice::{LatticeScenario, LatticeSummaryJson};
use woodpile_io::rundir::{RunRecord, SummaryJson};
use woodpile_io::scenario::{resolve, Scenario};

pub mod page;

/// The scenario's name in `summary.json` (the command line names a run after its file).
pub const SCENARIO_NAME: &str = "playground";

/// The most steps a page runs (a fixed-step run's estimate): a page cannot be interrupted while
/// it runs, and 10⁷ RK4 steps of the paper's 20-rod chain take about a minute there (2 × 10⁵
/// took 1.4 s in Node.js on the benchmark machine).
pub const PAGE_MAX_STEPS: u64 = 10_000_000;

/// Refuses a run the page should not start: the command line's limits, then [`PAGE_MAX_STEPS`].
fn check_size(size: woodpile_io::limits::RunSize) -> Result<(), String> {
    size.check(false, false, true).map_err(|e| e.to_string())?;
    match size.steps {
        Some(steps) if steps > PAGE_MAX_STEPS => Err(format!(
            "run.duration_s / run.time_step_s: {steps} steps, more than the {PAGE_MAX_STEPS} a page \
             runs; shorten the run, state run.peak_tolerance (adaptive steps), or run it with \
             `woodpile simulate`"
        )),
        _ => Ok(()),
    }
}

/// What the page needs to read the samples ([`Answer::samples`]).
#[derive(Debug, Serialize)]
pub struct Series {
    /// Number of samples.
    pub n_samples: usize,
    /// Contacts per sample.
    pub n_contacts: usize,
    /// Each contact's name: `striker-1` (or `load-1`), `1-2` …, `N-wall` for a chain; `c0` …
    /// for a lattice (the command line's `run.json` lists what each joins).
    pub contact_names: Vec<String>,
}

/// A run's answer to the page.
#[derive(Debug)]
pub struct Answer {
    /// The JSON object (see the crate's documentation).
    pub json: String,
    /// The sample times \[s\], then each sample's contact forces \[N\] (empty on a refusal).
    pub samples: Vec<f64>,
}

/// Runs the scenario `toml` (see the crate's documentation).
pub fn run_toml(toml: &str) -> Answer {
    let result = if woodpile_io::lattice::is_lattice(toml) {
        run_lattice(toml)
    } else {
        run_chain(toml)
    };
    match result {
        Ok((value, samples)) => Answer {
            json: value.to_string(),
            samples,
        },
        Err(message) => Answer {
            json: json!({ "ok": false, "error": message }).to_string(),
            samples: Vec::new(),
        },
    }
}

/// The times, then the forces.
fn samples(times_s: &[f64], contact_forces_n: &[f64]) -> Vec<f64> {
    [times_s, contact_forces_n].concat()
}

/// A chain's run, as `woodpile simulate` makes it (without files).
fn run_chain(toml: &str) -> Result<(Value, Vec<f64>), String> {
    let text = |e: woodpile_io::Error| e.to_string();
    let scenario = Scenario::parse(toml).map_err(text)?;
    let resolved = resolve(&scenario, Path::new(".")).map_err(text)?;
    check_size(woodpile_io::limits::RunSize::estimate(
        &resolved.settings,
        resolved.chain.len(),
    ))?;
    let mut trajectory = Trajectory::default();
    let summary = simulate(
        &resolved.chain,
        &resolved.excitation,
        &resolved.settings,
        &mut trajectory,
    )
    .map_err(|e| text(e.into()))?;
    let mut warnings = resolved.warnings.clone();
    if let Some(w) = woodpile_io::limits::check_accuracy(&summary.energy, false).map_err(text)? {
        warnings.push(w);
    }
    let record = RunRecord {
        name: SCENARIO_NAME,
        file: None,
        scenario: &scenario,
        resolved: &resolved,
        summary: &summary,
        trajectory: &trajectory,
    };
    warnings.extend(woodpile_io::text::run_warnings(&record));
    let n = resolved.chain.len();
    let top = if matches!(resolved.excitation, woodpile::Excitation::Impact(_)) {
        "striker-1".to_string()
    } else {
        "load-1".to_string()
    };
    let mut names = vec![top];
    names.extend((1..n).map(|i| format!("{i}-{}", i + 1)));
    names.push(format!("{n}-wall"));
    let series = Series {
        n_samples: trajectory.len(),
        n_contacts: trajectory.n_contacts(),
        contact_names: names,
    };
    Ok((
        done(&SummaryJson::new(&record), &series, &warnings),
        samples(&trajectory.times_s, &trajectory.contact_forces_n),
    ))
}

/// A lattice's run, as `woodpile simulate` makes it (without files).
fn run_lattice(toml: &str) -> Result<(Value, Vec<f64>), String> {
    let text = |e: woodpile_io::Error| e.to_string();
    let scenario = LatticeScenario::parse(toml, SCENARIO_NAME).map_err(text)?;
    let resolved = scenario.resolve().map_err(text)?;
    check_size(woodpile_io::lattice::run_size(&resolved))?;
    let mut ode =
        woodpile::ode::LatticeOde::build(&resolved.lattice, &resolved.excitation, &resolved.lab)
            .map_err(|e| text(e.into()))?;
    let run = woodpile::simulate::simulate_lattice(&mut ode, &resolved.settings)
        .map_err(|e| text(e.into()))?;
    let mut warnings = Vec::new();
    if let Some(w) = woodpile_io::limits::check_accuracy(&run.energy, false).map_err(text)? {
        warnings.push(w);
    }
    warnings.extend(woodpile_io::text::lattice_warnings(&resolved, &run));
    let series = Series {
        n_samples: run.times_s.len(),
        n_contacts: run.contacts,
        contact_names: (0..run.contacts).map(|c| format!("c{c}")).collect(),
    };
    let summary = LatticeSummaryJson::of(SCENARIO_NAME, &resolved.excitation, &run);
    Ok((
        done(&summary, &series, &warnings),
        samples(&run.times_s, &run.contact_forces_n),
    ))
}

/// The page's JSON of a finished run.
fn done(summary: &impl Serialize, series: &Series, warnings: &[String]) -> Value {
    json!({ "ok": true, "summary": summary, "series": series, "warnings": warnings })
}
