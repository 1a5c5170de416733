//! Claim: a screened GA run's checkpoint holds everything the run needs: written after
//! generation 2 and read back, it is the state that was saved (population with each screened
//! value's bound, both value caches, every counter), and the run resumed from it ends where the
//! uninterrupted run ends. The same holds with early stopping (`ga.stop_early`), whose lower
//! bounds of stopped designs the checkpoint keeps too.
//!
//! Tolerance: none (JSON keeps f64 bit for bit), except the wall-clock times.

use std::ops::ControlFlow;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{BreederGa, GaState};
use woodpile_io::optimize::{read_checkpoint, write_generation, OptimizeConfig, Problem};

const CONFIG: &str = "[design]\npositions = 5\n[run]\nduration_s = 4e-4\npeak_tolerance = 1e-4\n[ga]\npopulation = 12\ngenerations = 5\nstall_generations = 0\nseed = 4\nscreen_peak_tolerance = 1e-2\n";

fn without_times(mut s: GaState) -> GaState {
    s.elapsed_s = 0.0;
    for h in &mut s.history {
        h.elapsed_s = 0.0;
    }
    s
}

#[test]
fn screened_run_resumes_from_its_checkpoint_exactly() {
    resumes_exactly(CONFIG, |saved| {
        assert!(saved.ledger.screenings > 0 && !saved.ledger.screened.is_empty());
        assert!(saved.population.iter().any(|i| i.bound > 0.0));
    });
}

#[test]
fn a_run_that_stops_early_resumes_from_its_checkpoint_exactly() {
    let config = format!("{CONFIG}stop_early = true\n");
    resumes_exactly(&config, |saved| {
        assert!(!saved.ledger.stopped.is_empty());
        assert!(saved.population.iter().any(|i| i.stopped));
    });
}

fn resumes_exactly(text: &str, check_saved: impl Fn(&GaState)) {
    let config = OptimizeConfig::parse(text, "c.toml").unwrap();
    let problem = Problem::new(&config, Path::new("."), 2).unwrap();
    let ga = BreederGa::new(
        problem.space.clone(),
        Box::new(problem.objective),
        problem.settings,
    )
    .unwrap();
    let straight = ga
        .run(None, &AtomicBool::new(false), &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap()
        .state;
    let dir = tempfile::tempdir().unwrap();
    let mut saved = None;
    ga.run(None, &AtomicBool::new(false), &mut |s| {
        if s.generation < 2 {
            return ControlFlow::Continue(());
        }
        write_generation(dir.path(), &problem.config, s).unwrap();
        saved = Some(s.clone());
        ControlFlow::Break(())
    })
    .unwrap();
    let saved = saved.unwrap();
    check_saved(&saved);

    let back = read_checkpoint(dir.path(), &problem.config).unwrap();
    assert_eq!(back, saved);
    let resumed = ga
        .run(Some(back), &AtomicBool::new(false), &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap()
        .state;
    assert_eq!(without_times(resumed), without_times(straight));
}
