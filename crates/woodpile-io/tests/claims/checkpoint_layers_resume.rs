//! Claim: a run whose number of layers is part of the design (`positions = { min, max }`)
//! resumes from its checkpoint exactly, for both algorithms: the checkpoint written after
//! generation 2 reads back as the saved state (designs of several lengths, their caches), and
//! the run resumed from it ends where the uninterrupted run ends. A checkpoint of the same
//! problem with a narrower range is refused (its designs lie outside the new range).
//!
//! Tolerance: none (JSON keeps f64 bit for bit), except the wall-clock times.

use std::collections::BTreeSet;
use std::ops::ControlFlow;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::{BreederGa, GaState, Nsga2, Nsga2State};
use woodpile_io::optimize::{read_checkpoint, write_generation, OptimizeConfig, Problem};

const DESIGN: &str = "[design]\npositions = { min = 3, max = 7 }\ncatalogue_mm = [20, 40, 60, 80]\n[design.constraints]\nmax_total_mass_g = 30.0\n[run]\nduration_s = 4e-4\npeak_tolerance = 1e-4\n[ga]\npopulation = 12\ngenerations = 5\nstall_generations = 0\nseed = 6\n";

fn problem_of(text: &str) -> Problem {
    let config = OptimizeConfig::parse(text, "c.toml").unwrap();
    Problem::new(&config, Path::new("."), 2).unwrap()
}

fn lengths<'a>(genomes: impl Iterator<Item = &'a Vec<u8>>) -> BTreeSet<usize> {
    genomes.map(Vec::len).collect()
}

#[test]
fn breeder_run_of_variable_length_resumes_exactly() {
    let problem = problem_of(DESIGN);
    let ga = BreederGa::new(
        problem.space.clone(),
        Box::new(problem.objective),
        problem.settings,
    )
    .unwrap();
    let never = AtomicBool::new(false);
    let untimed = |mut s: GaState| {
        s.elapsed_s = 0.0;
        s.history.iter_mut().for_each(|h| h.elapsed_s = 0.0);
        s
    };
    let straight = ga.run(None, &never, &mut |_| ControlFlow::Continue(()));
    let straight = untimed(straight.unwrap().state);
    let dir = tempfile::tempdir().unwrap();
    let mut saved = None;
    ga.run(None, &never, &mut |s| {
        if s.generation < 2 {
            return ControlFlow::Continue(());
        }
        write_generation(dir.path(), &problem.config, s).unwrap();
        saved = Some(s.clone());
        ControlFlow::Break(())
    })
    .unwrap();
    let saved = saved.unwrap();
    assert!(
        lengths(saved.ledger.cache.keys()).len() > 1,
        "one length only"
    );
    let back = read_checkpoint(dir.path(), &problem.config).unwrap();
    assert_eq!(back, saved);
    let resumed = ga.run(Some(back.clone()), &never, &mut |_| {
        ControlFlow::Continue(())
    });
    assert_eq!(untimed(resumed.unwrap().state), straight);

    // The same state under a narrower range holds designs outside it.
    let narrow = problem_of(&DESIGN.replace("max = 7", "max = 3"));
    let narrow_ga = BreederGa::new(
        narrow.space.clone(),
        Box::new(narrow.objective),
        narrow.settings,
    )
    .unwrap();
    let e = narrow_ga.run(Some(back), &never, &mut |_| ControlFlow::Continue(()));
    assert!(e.unwrap_err().to_string().contains("does not match"));
}

#[test]
fn nsga2_run_of_variable_length_resumes_exactly() {
    let text = format!("{DESIGN}objectives = [\"transmitted-force\", \"layers\"]\n");
    let problem = problem_of(&text);
    let ga = Nsga2::new(
        problem.space.clone(),
        problem.objectives.clone(),
        problem.nsga2.clone(),
    )
    .unwrap();
    let never = AtomicBool::new(false);
    let untimed = |mut s: Nsga2State| {
        s.elapsed_s = 0.0;
        s.history.iter_mut().for_each(|h| h.elapsed_s = 0.0);
        s
    };
    let (whole, _) = ga
        .run(None, &never, &mut |_| ControlFlow::Continue(()))
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (saved, _) = ga
        .run(None, &never, &mut |s| {
            if s.generation == 2 {
                woodpile_io::pareto::write_generation(dir.path(), &problem.config, s).unwrap();
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })
        .unwrap();
    assert!(
        lengths(saved.population.iter().map(|i| &i.genome)).len() > 1,
        "one length only"
    );
    let read = woodpile_io::pareto::prepare_output(dir.path(), true, &problem.config)
        .unwrap()
        .unwrap();
    assert_eq!(read, saved, "the checkpoint is the state");
    let (resumed, _) = ga
        .run(Some(read), &never, &mut |_| ControlFlow::Continue(()))
        .unwrap();
    assert_eq!(untimed(resumed), untimed(whole));
}
