//! `woodpile optimize`: drives the breeder GA of `woodpile_io::optimize` with a progress bar, a
//! checkpoint after every generation, exact resume and a clean stop on Ctrl-C.

use crate::commands::Context;
use crate::progress::Progress;
use crate::CliError;
use std::fs;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use woodpile::optimize::{BreederGa, GaState, Nsga2, Nsga2State, Objective, StopReason};
use woodpile_io::atomic::io_err;
use woodpile_io::optimize::*;
use woodpile_io::scenario::ModelSpec;

/// Arguments of `woodpile optimize`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// Config file (TOML): a scenario's excitation, wall and run tables plus design and ga tables
    /// (with a lattice table: a lattice study over rod lengths per layer and the pitch).
    #[arg(value_name = "CONFIG.toml", conflicts_with = "scenario")]
    pub file: Option<PathBuf>,
    /// A built-in problem: paper-impact or paper-blast (20 rods, Table 1 catalogue).
    #[arg(long, value_name = "NAME", required_unless_present = "file")]
    pub scenario: Option<String>,
    /// Cell model of the catalogue rods (overrides design.model): resonant or rigid.
    #[arg(long, value_name = "MODEL")]
    pub model: Option<String>,
    /// Output directory (must be absent or empty, unless --resume).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Seed of the GA (overrides ga.seed).
    #[arg(long, allow_negative_numbers = true, value_name = "S")]
    pub seed: Option<u64>,
    /// Worker threads (`--threads`, `--allow-many-threads`).
    #[command(flatten)]
    pub workers: super::Workers,
    /// Continue the run saved in DIR/checkpoint.json (same config and seed).
    #[arg(long)]
    pub resume: bool,
    /// Go ahead with a generation above the up-front limit of elements simulated per
    /// generation (sets ga.allow_large).
    #[arg(long)]
    pub allow_large: bool,
    /// The paper's integration (RK4 at 0.1 µs, every design simulated whole) instead of the
    /// accuracy-targeted default (every contact peak within 1e-5, screening, early stopping);
    /// the same as `[ga] paper_settings = true`.
    #[arg(long)]
    pub paper_settings: bool,
}

/// Loads the config the arguments name, with the command line's overrides.
pub fn load_config(args: &Args) -> Result<(OptimizeConfig, String, PathBuf), CliError> {
    let (mut cfg, name, base) = match (&args.file, &args.scenario) {
        (Some(file), _) => {
            let text = fs::read_to_string(file).map_err(|e| CliError::Read {
                path: file.clone(),
                source: e,
            })?;
            let cfg = OptimizeConfig::parse(&text, &file.display().to_string())?;
            let (name, base) = super::name_and_base(file, "optimize");
            (cfg, name, base)
        }
        (None, Some(name)) => (
            OptimizeConfig::builtin(name)?,
            name.clone(),
            PathBuf::from("."),
        ),
        (None, None) => {
            return Err(CliError::invalid(
                "CONFIG.toml",
                "(none)",
                format!(
                    "give a config file or --scenario {}",
                    BUILTIN_PROBLEMS.join("|")
                ),
            ))
        }
    };
    if let Some(m) = &args.model {
        cfg.design.model = Some(match m.as_str() {
            "resonant" => ModelSpec::Resonant,
            "rigid" => ModelSpec::Rigid,
            other => {
                return Err(CliError::invalid(
                    "--model",
                    other,
                    "must be resonant or rigid",
                ))
            }
        });
    }
    if let Some(seed) = args.seed {
        cfg.ga.seed = Some(seed);
    }
    if args.allow_large {
        cfg.ga.allow_large = Some(true);
    }
    if args.paper_settings {
        cfg.ga.paper_settings = Some(true);
    }
    Ok((cfg.accuracy_targeted(), name, base))
}

/// Runs `woodpile optimize`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    if let Some(file) = &args.file {
        let text = fs::read_to_string(file).map_err(|e| CliError::Read {
            path: file.clone(),
            source: e,
        })?;
        if woodpile_io::lattice_study::is_lattice_study(&text) {
            return run_lattice(args, ctx, file, &text);
        }
    }
    let (cfg, name, base_dir) = load_config(args)?;
    let threads = args.workers.checked()?;
    let problem = Problem::new(&cfg, &base_dir, threads)?;
    if problem.algorithm == Algorithm::Nsga2 {
        return run_nsga2(args, ctx, &problem, &name);
    }
    let out = &args.out;
    let initial = prepare_output(out, args.resume, &problem.config)?;
    let objective: Box<dyn Objective> = match problem.robust_objective() {
        Some(robust) => Box::new(robust),
        None => Box::new(problem.objective),
    };
    let ga = BreederGa::new(problem.space.clone(), objective, problem.settings)
        .map_err(optimize_error)?;
    if let Some(state) = &initial {
        ga.check_state(state).map_err(optimize_error)?;
    }
    fs::create_dir_all(out).map_err(io_err(out))?;

    crate::interrupt::cooperative(true);
    let stop = crate::interrupt::stop_flag();
    let bar = generations_progress(
        problem.settings.generations,
        initial.as_ref().map(|s| s.generation),
        ctx.quiet,
    );
    let unit = problem.objective.unit().to_string();
    let mut write_error: Option<CliError> = None;
    let mut last_elapsed = initial.as_ref().map_or(0.0, |s| s.elapsed_s);
    let simulations = |s: &GaState| s.ledger.evaluations + s.ledger.screenings;
    let mut last_evals = initial.as_ref().map_or(0, simulations);
    let mut observer = |s: &GaState| {
        let written = write_generation(out, &problem.config, s);
        if let Err(e) = written {
            write_error = Some(e);
            return ControlFlow::Break(());
        }
        let dt = s.elapsed_s - last_elapsed;
        let rate = if dt > 0.0 {
            (simulations(s) - last_evals) as f64 / dt
        } else {
            0.0
        };
        (last_elapsed, last_evals) = (s.elapsed_s, simulations(s));
        generation_done(&bar, s.generation);
        bar.detail(format!(
            "generation {}: best {:.6e} {unit} | {rate:.0} sim/s | {} evaluations, {}{} cache hits",
            s.generation,
            s.best().objective,
            s.ledger.evaluations,
            screened_text(&s.ledger),
            s.ledger.cache_hits
        ));
        ControlFlow::Continue(())
    };
    let outcome = ga.run(initial, stop, &mut observer);
    bar.finish();
    // The best design is simulated once more for the outputs: the request that stopped the GA
    // is withdrawn (a second Ctrl-C still ends the command at once).
    woodpile::interrupt::clear();
    if let Some(e) = write_error {
        return Err(e);
    }
    let outcome = match outcome {
        Err(e) if e.is_interrupted() => return Err(interrupted_in_generation_zero()),
        other => other.map_err(optimize_error)?,
    };
    let state = &outcome.state;
    let interrupted = outcome.reason == StopReason::Interrupted;
    let figures = write_final_outputs(&problem, &name, &outcome, out)?;
    if !ctx.quiet {
        crate::out::print(format_args!(
            "{}",
            terminal_summary(&problem, &name, &outcome, &figures, out)
        ))?;
    }
    if interrupted {
        return Err(interrupted_at(state.generation, out));
    }
    Ok(())
}

/// The progress of a GA over `generations` generations, resumed after `resumed_at` if given.
/// The GA stops sooner when it stalls, so its ETA is an upper bound, and it is measured from
/// the generations run here after generation 0 (which simulates the whole population).
fn generations_progress(generations: usize, resumed_at: Option<usize>, quiet: bool) -> Progress {
    let bar = Progress::new("optimize", generations as u64, quiet).ending_early();
    if let Some(generation) = resumed_at {
        bar.set_position(generation as u64);
        bar.rate_from_here();
    }
    bar
}

/// Shows `generation` as done on `bar` (see [`generations_progress`]).
fn generation_done(bar: &Progress, generation: usize) {
    bar.set_position(generation as u64);
    if generation == 0 {
        bar.rate_from_here();
    }
}

/// An interrupt after `generation` was saved in `out`'s checkpoint.
fn interrupted_at(generation: usize, out: &Path) -> CliError {
    CliError::Interrupted {
        saved: format!(
            "generation {generation} is saved in {}; continue with the same command and --resume",
            out.join(CHECKPOINT_FILE).display()
        ),
    }
}

/// An interrupt before generation 0 was complete: no checkpoint exists yet.
fn interrupted_in_generation_zero() -> CliError {
    CliError::Interrupted {
        saved: "during generation 0, before its checkpoint: nothing to resume; run the same command again to start over".into(),
    }
}

/// What `woodpile optimize` prints when it stops.
fn terminal_summary(
    problem: &Problem,
    name: &str,
    outcome: &woodpile::optimize::Outcome,
    figures: &woodpile::RunSummary,
    out: &std::path::Path,
) -> String {
    let state = &outcome.state;
    let best = state.best();
    // Robust: the statistic over the samples (robust/001.csv); the forces are the nominal run's.
    let robust = problem.config.ga.robust.as_ref().map(|r| {
        let k = problem.robust.as_ref().map_or(0, |(_, u)| u.samples);
        (format!("{r} over {k} samples of "), "nominal: ".to_string())
    });
    let ratio = figures
        .transmission_ratio
        .map_or("none".to_string(), |r| format!("{r:.4}"));
    format!(
        "problem      {name} ({}, {} catalogue entries, seed {})\n\
         stopped      {} after generation {}: {} evaluations, {}{} cache hits, {:.1} s\n\
         best         {}\n\
         accuracy     {}\n\
         objective    {}{} = {:.6e} {}\n\
         forces       {}incident {:.4} N, transmitted {:.4} N, ratio {ratio}\n\
         output       {}\n",
        problem.positions_text(),
        problem.space.catalogue.len(),
        problem.settings.seed,
        stop_text(outcome.reason),
        state.generation,
        state.ledger.evaluations,
        screened_text(&state.ledger),
        state.ledger.cache_hits,
        state.elapsed_s,
        problem.space.labels(&best.genome).join(" "),
        problem.config.accuracy_text(),
        robust.as_ref().map_or("", |(r, _)| r.as_str()),
        problem.objective.as_str(),
        best.objective,
        problem.objective.unit(),
        robust.as_ref().map_or("", |(_, nominal)| nominal.as_str()),
        figures.incident_peak_force_n,
        figures.transmitted_peak_force_n,
        out.display()
    )
}

/// The screening runs and the designs whose run stopped early, where there are any.
fn screened_text(ledger: &woodpile::optimize::Ledger) -> String {
    let mut text = String::new();
    if ledger.screenings > 0 {
        text.push_str(&format!("{} screenings, ", ledger.screenings));
    }
    if !ledger.stopped.is_empty() {
        text.push_str(&format!("{} stopped early, ", ledger.stopped.len()));
    }
    text
}

/// Evaluates the designs a front is compared with (the catalogue's homogeneous chains, the
/// paper's optimised chain for the paper's catalogue) and writes `references.csv`.
fn write_references(ga: &Nsga2, problem: &Problem, out: &Path) -> Result<(), CliError> {
    let designs = woodpile_io::pareto::reference_designs(problem);
    let genomes: Vec<&[u8]> = designs.iter().map(|(_, g)| g.as_slice()).collect();
    let set = woodpile::optimize::FeasibleSet::new(&problem.space).map_err(optimize_error)?;
    let values = ga.evaluate_designs(&genomes).map_err(optimize_error)?;
    let rows: Vec<(String, Vec<f64>, bool)> = designs
        .iter()
        .zip(values)
        .map(|((name, g), ind)| {
            (
                name.clone(),
                ind.objectives,
                set.contains(g) && ind.violation == 0.0,
            )
        })
        .collect();
    let csv = woodpile_io::pareto::references_csv(problem, &rows);
    woodpile_io::atomic::write_atomic(out, "references.csv", csv.as_bytes())?;
    Ok(())
}

/// Runs NSGA-II (`ga.algorithm = "nsga2"`): a checkpoint and `history.csv` after every
/// generation, then `pareto.csv`, `pareto/NNN.toml` and `summary.json`.
fn run_nsga2(args: &Args, ctx: &Context, problem: &Problem, name: &str) -> Result<(), CliError> {
    let out = &args.out;
    let initial = woodpile_io::pareto::prepare_output(out, args.resume, &problem.config)?;
    let mut ga = Nsga2::new(
        problem.space.clone(),
        problem.objectives.clone(),
        problem.nsga2.clone(),
    )
    .map_err(optimize_error)?;
    if let Some(robust) = problem.robust_objective() {
        ga = ga.with_evaluator(Box::new(robust));
    }
    let (state, reason) = drive_nsga2(&ga, initial, out, ctx.quiet, &mut |s| {
        woodpile_io::pareto::write_generation(out, &problem.config, s)
    })?;
    let summary = woodpile_io::pareto::write_final_outputs(problem, name, &state, reason, out)?;
    write_references(&ga, problem, out)?;
    if !ctx.quiet {
        let names: Vec<String> = summary
            .objectives
            .iter()
            .map(|o| format!("{} [{}]", o.name, o.unit))
            .collect();
        let front = if summary.front.is_empty() {
            "no feasible design in the final population: loosen design.constraints.max_contact_pressure_pa or run longer".to_string()
        } else {
            format!(
                "{} designs (pareto.csv, pareto/001.toml ...)",
                summary.front.len()
            )
        };
        crate::out::print(format_args!(
            "problem      {name} ({}, {} catalogue entries, seed {}, NSGA-II)\n\
             stopped      {} after generation {}: {} evaluations, {} cache hits, {:.1} s\n\
             accuracy     {}\n\
             objectives   {}\n\
             front        {front}\n\
             hypervolume  {:.6e} (reference point {:?})\n\
             output       {}\n",
            problem.positions_text(),
            problem.space.catalogue.len(),
            problem.nsga2.seed,
            stop_text(reason),
            state.generation,
            state.evaluations,
            state.cache_hits,
            state.elapsed_s,
            problem.config.accuracy_text(),
            names.join(", "),
            summary.hypervolume,
            summary.reference_point,
            out.display()
        ))?;
    }
    if reason == StopReason::Interrupted {
        return Err(interrupted_at(state.generation, out));
    }
    Ok(())
}

/// Runs NSGA-II from `initial` (a resumed state, if any) to its end, writing every generation by
/// `write` into `out` and showing its progress; Ctrl-C stops it after a complete generation.
fn drive_nsga2<S: woodpile::optimize::GenomeSpace>(
    ga: &Nsga2<S>,
    initial: Option<Nsga2State>,
    out: &Path,
    quiet: bool,
    write: &mut dyn FnMut(&Nsga2State) -> Result<(), CliError>,
) -> Result<(Nsga2State, StopReason), CliError> {
    if let Some(state) = &initial {
        ga.check_state(state).map_err(optimize_error)?;
    }
    fs::create_dir_all(out).map_err(io_err(out))?;
    crate::interrupt::cooperative(true);
    let stop = crate::interrupt::stop_flag();
    let resumed_at = initial.as_ref().map(|s| s.generation);
    let bar = generations_progress(ga.settings().generations, resumed_at, quiet);
    let mut write_error: Option<CliError> = None;
    let mut last = initial
        .as_ref()
        .map_or((0.0, 0), |s| (s.elapsed_s, s.evaluations));
    let mut observer = |s: &Nsga2State| {
        if let Err(e) = write(s) {
            write_error = Some(e);
            return ControlFlow::Break(());
        }
        let dt = s.elapsed_s - last.0;
        let rate = if dt > 0.0 {
            (s.evaluations - last.1) as f64 / dt
        } else {
            0.0
        };
        last = (s.elapsed_s, s.evaluations);
        let h = s.history.last().expect("a generation's line");
        generation_done(&bar, s.generation);
        bar.detail(format!(
            "generation {}: hypervolume {:.6e} | front {} | {rate:.0} sim/s | {} evaluations, {} cache hits",
            s.generation, h.hypervolume, h.front_size, s.evaluations, s.cache_hits
        ));
        ControlFlow::Continue(())
    };
    let outcome = ga.run(initial, stop, &mut observer);
    bar.finish();
    woodpile::interrupt::clear();
    if let Some(e) = write_error {
        return Err(e);
    }
    match outcome {
        Err(e) if e.is_interrupted() => Err(interrupted_in_generation_zero()),
        other => other.map_err(optimize_error).inspect(|(s, _)| {
            if let Some(w) = woodpile_io::pareto::hypervolume_warning(s) {
                crate::out::eprintln(format_args!("warning: {w}"));
            }
        }),
    }
}

/// Runs a lattice study (a config with a `[lattice]` table, docs/optimization.md): NSGA-II over
/// rod lengths per layer and the pitch, a checkpoint and `history.csv` after every generation,
/// then `pareto.csv`, `pareto/NNN.toml` and `summary.json`.
fn run_lattice(args: &Args, ctx: &Context, file: &Path, text: &str) -> Result<(), CliError> {
    use woodpile_io::lattice_study::{
        prepare_output, write_final_outputs, write_generation, LatticeStudyConfig,
    };
    let chain_flags = [
        ("--model", args.model.clone()),
        (
            "--allow-large",
            args.allow_large.then(|| "true".to_string()),
        ),
        (
            "--paper-settings",
            args.paper_settings.then(|| "true".to_string()),
        ),
    ];
    if let Some((flag, Some(value))) = chain_flags.into_iter().find(|(_, v)| v.is_some()) {
        return Err(CliError::invalid(
            flag,
            value,
            "is for chains' studies; a lattice study's rods are FE beams and its run is its [run] table",
        ));
    }
    let mut cfg = LatticeStudyConfig::parse(text, &file.display().to_string())?;
    if let Some(seed) = args.seed {
        cfg.ga.seed = Some(seed);
    }
    let threads = args.workers.checked()?;
    let study = cfg.resolve(threads)?;
    let (name, _) = super::name_and_base(file, "optimize");
    let out = &args.out;
    let initial = prepare_output(out, args.resume, &study.config)?;
    let (state, reason) = drive_nsga2(&study.ga, initial, out, ctx.quiet, &mut |s| {
        write_generation(out, &study.config, s)
    })?;
    let summary = write_final_outputs(out, &study, &state, reason)?;
    if !ctx.quiet {
        crate::out::print(format_args!(
            "problem      {name} (lattice: {} designs, seed {}, NSGA-II)\n\
             stopped      {} after generation {}: {} evaluations, {} cache hits, {:.1} s\n\
             objectives   {}\n\
             front        {} designs (pareto.csv, pareto/001.toml ...)\n\
             hypervolume  {:.6e} (reference point {:?})\n\
             output       {}\n",
            summary.designs_in_space,
            summary.seed,
            stop_text(reason),
            state.generation,
            state.evaluations,
            state.cache_hits,
            state.elapsed_s,
            summary.objectives.join(", "),
            summary.front.len(),
            summary.hypervolume,
            summary.reference_point,
            out.display()
        ))?;
    }
    if reason == StopReason::Interrupted {
        return Err(interrupted_at(state.generation, out));
    }
    Ok(())
}
