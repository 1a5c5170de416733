//! Claim: an NSGA-II run's checkpoint holds everything the run needs: written after generation
//! 2 and read back it is the saved state (population, cache, reference point, history,
//! counters), the run resumed from it ends where the uninterrupted run ends, and a checkpoint
//! edited after it was written is refused naming both checksums.
//!
//! Tolerance: none (JSON keeps f64 bit for bit), except the wall-clock times.

use std::ops::ControlFlow;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{Nsga2, Nsga2State};
use woodpile_io::optimize::{OptimizeConfig, Problem};
use woodpile_io::pareto::{prepare_output, write_generation};

const CONFIG: &str = "[design]\npositions = 5\ncatalogue_mm = [20, 40, 60, 80]\n[run]\nduration_s = 4e-4\npeak_tolerance = 1e-4\n[ga]\nobjectives = [\"transmitted-force\", \"total-mass\"]\npopulation = 12\ngenerations = 5\nstall_generations = 0\nseed = 4\n";

fn without_times(mut s: Nsga2State) -> Nsga2State {
    s.elapsed_s = 0.0;
    for h in &mut s.history {
        h.elapsed_s = 0.0;
    }
    s
}

#[test]
fn nsga2_resumes_from_its_checkpoint_exactly() {
    let config = OptimizeConfig::parse(CONFIG, "c.toml").unwrap();
    let problem = Problem::new(&config, Path::new("."), 2).unwrap();
    let ga = Nsga2::new(
        problem.space.clone(),
        problem.objectives.clone(),
        problem.nsga2.clone(),
    )
    .unwrap();
    let never = AtomicBool::new(false);
    let (whole, _) = ga
        .run(None, &never, &mut |_| ControlFlow::Continue(()))
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (saved, _) = ga
        .run(None, &never, &mut |s| {
            if s.generation == 2 {
                write_generation(dir.path(), &problem.config, s).unwrap();
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })
        .unwrap();
    let read = prepare_output(dir.path(), true, &problem.config)
        .unwrap()
        .unwrap();
    assert_eq!(read, saved, "the checkpoint is the state");
    assert!(!read.cache.is_empty());
    let (resumed, _) = ga
        .run(Some(read), &never, &mut |_| ControlFlow::Continue(()))
        .unwrap();
    assert_eq!(without_times(resumed), without_times(whole));

    let path = dir.path().join("checkpoint.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let edited = text.replacen("\"generation\":2", "\"generation\":1", 1);
    assert_ne!(edited, text);
    std::fs::write(&path, edited).unwrap();
    let e = prepare_output(dir.path(), true, &problem.config)
        .unwrap_err()
        .to_string();
    assert!(e.contains("checksum") && e.contains("modified"), "{e}");
}
