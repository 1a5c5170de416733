//! Many runs advanced together in SIMD lanes: the design studies' engine.
//!
//! A design study simulates thousands of chains of one problem. [`simulate_many`] advances `L`
//! of them at once, in structure-of-arrays form: every state component is an `[f64; L]`, one
//! value per run, so each arithmetic operation of the equations of motion and of the Runge–Kutta
//! stages is one vector instruction over L runs (AVX2: 4 doubles, SSE2: 2; the instruction set
//! is chosen at run time, the width by [`LaneWidth`]). There is no AVX-512 build: on the AVX-512
//! development machine it was slower than the AVX2 build at every width, 8 lanes 2.3× slower
//! (LLVM vectorised the loops over state components with gathers; bench/README.md).
//!
//! Each lane keeps its own time, step size and step-size controller, so lanes never wait for
//! each other: a lane whose run has ended takes the next run of the queue. The work spreads over
//! the threads of the current rayon pool: each thread advances its own lanes, and all of them
//! take runs from one queue per group, so lanes idle only while the last runs finish. Runs of
//! one lane group share the number of bodies, the kind of load and the terms of their lab
//! physics (`crate::ode::LabShape`); chains whose cells carry different numbers of resonators are
//! padded with resonators that exert exactly zero force (k = c = m = 0) and the error norm skips
//! the padding.
//!
//! **The lanes compute bit for bit what [`simulate`](crate::simulate()) computes** for the same run: every lane
//! performs the scalar path's operations in the same order (IEEE arithmetic, no fused
//! multiply–add, square roots correctly rounded in both), the error norm sums in the scalar
//! order, and the per-step work (peaks, checks, the final summary) is the scalar code itself.
//! Results therefore do not depend on the lane width, the grouping or the thread count (claim
//! `lanes_bit_identical`). A run that fails (blow-up, step too small) is re-run on the scalar
//! path, which reproduces the failure and diagnoses it.
//!
//! The lanes are a scheduler: the equations of motion (`crate::ode::Equations`), the stage loop,
//! the error terms and the crossing prediction (`crate::integrate`'s kernels) are the scalar
//! path's own code, written once over the number type (`crate::real::Real`) and run here on one
//! value per lane. Lanes take the runs whose figures of merit need no samples
//! (`sample_interval_s` equal to `duration_s`, as the GA's force objectives run), with any physics
//! a scenario states (damping, preload, gravity, drives: docs/physics.md §14; the runs of a group
//! share their contact laws); runs that record samples go to [`simulate`](crate::simulate()).

// Lane loops index several arrays by the lane number l: the plain form that LLVM vectorizes.
#![allow(clippy::needless_range_loop)]

mod worker;

use std::collections::BTreeMap;
use std::sync::Mutex;
use worker::Lanes;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::integrate::{Method, OdeSystem};
use crate::model::Chain;
use crate::ode::{ChainOde, Equations, LabShape};
use crate::simulate::{check_method_fits, simulate_watching, PeakWatch, RunSettings, RunSummary};

/// How many runs advance together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LaneWidth {
    /// One run at a time (the lane engine without vectors; for tests and comparisons).
    One,
    /// Two runs (one SSE2 register).
    Two,
    /// Four runs (one AVX2 register).
    Four,
    /// Eight runs (two AVX2 registers).
    Eight,
}

impl LaneWidth {
    /// Every width.
    pub const ALL: [LaneWidth; 4] = [
        LaneWidth::One,
        LaneWidth::Two,
        LaneWidth::Four,
        LaneWidth::Eight,
    ];

    /// The width for this CPU: four with AVX2 (also on CPUs with AVX-512, whose build was slower
    /// at every width: bench/README.md), two otherwise.
    pub fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                return LaneWidth::Four;
            }
        }
        LaneWidth::Two
    }

    /// The number of lanes.
    pub fn lanes(self) -> usize {
        match self {
            LaneWidth::One => 1,
            LaneWidth::Two => 2,
            LaneWidth::Four => 4,
            LaneWidth::Eight => 8,
        }
    }

    /// The width with this many lanes (1, 2, 4 or 8).
    pub fn from_lanes(lanes: usize) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|w| w.lanes() == lanes)
            .ok_or_else(|| Error::invalid("lanes", lanes, "must be 1, 2, 4 or 8"))
    }
}

/// One run for [`simulate_many`].
#[derive(Debug, Clone, Copy)]
pub struct Job<'a> {
    /// The chain.
    pub chain: &'a Chain,
    /// Its excitation.
    pub excitation: &'a Excitation,
    /// How long and how.
    pub settings: &'a RunSettings,
}

impl<'a> Job<'a> {
    /// One job per chain, all under the same excitation and settings (a design study's runs).
    pub fn for_each_chain(
        chains: &'a [Chain],
        excitation: &'a Excitation,
        settings: &'a RunSettings,
    ) -> Vec<Job<'a>> {
        chains
            .iter()
            .map(|chain| Job {
                chain,
                excitation,
                settings,
            })
            .collect()
    }

    /// Whether [`simulate_many`] advances this job in SIMD lanes (any physics, when it records no
    /// samples: `sample_interval_s` equal to `duration_s`), rather than on its own with
    /// [`simulate`](crate::simulate()). Errors as [`simulate`](crate::simulate()) would.
    pub fn in_lanes(&self) -> Result<bool> {
        Ok(lane_ready(self)?.is_some())
    }
}

/// Runs every job, in lanes where it can (see the module documentation) and on [`simulate`](crate::simulate())
/// otherwise, with no recorder, on the threads of the current rayon pool (the global one, or
/// the pool whose `install` calls it). The results are in the order of `jobs` and equal, bit
/// for bit except `wall_time_s`, to `simulate(chain, excitation, settings, &mut ())` of each job.
pub fn simulate_many(jobs: &[Job<'_>], width: LaneWidth) -> Vec<Result<RunSummary>> {
    simulate_many_watching(jobs, width, PeakWatch::Every)
}

/// [`simulate_many`], tracking over every step only the contact peaks that `peak_watch` names
/// (the force objectives of a design study need two of them: [`PeakWatch::FiguresOfMerit`]).
/// Each result equals, bit for bit except `wall_time_s`, what [`simulate`](crate::simulate()) gives the job, except
/// the peaks not tracked, which are NaN.
pub fn simulate_many_watching(
    jobs: &[Job<'_>],
    width: LaneWidth,
    peak_watch: PeakWatch,
) -> Vec<Result<RunSummary>> {
    simulate_many_stopping(jobs, width, peak_watch, f64::INFINITY)
}

/// [`simulate_many_watching`], each run stopped at the end of the first step whose transmitted
/// peak exceeds `stop_above_n` \[N\] (a design study's cutoff: the transmitted peak is a running
/// maximum, so a run stopped there ends above the cutoff whatever follows). A stopped run's
/// summary has `stopped_at_s` set and the peaks of the steps up to then; it is bit for bit that
/// of the same run on the scalar path, stopped at the same step.
pub fn simulate_many_stopping(
    jobs: &[Job<'_>],
    width: LaneWidth,
    peak_watch: PeakWatch,
    stop_above_n: f64,
) -> Vec<Result<RunSummary>> {
    let ready: Vec<Result<Option<(GroupKey, ChainOde)>>> =
        jobs.par_iter().map(lane_ready).collect();
    let mut results: Vec<Option<Result<RunSummary>>> = (0..jobs.len()).map(|_| None).collect();
    let mut scalar = Vec::new();
    let mut groups: BTreeMap<GroupKey, Vec<(usize, ChainOde)>> = BTreeMap::new();
    for (index, ready) in ready.into_iter().enumerate() {
        match ready {
            Ok(Some((key, ode))) => groups.entry(key).or_default().push((index, ode)),
            Ok(None) => scalar.push(index),
            Err(e) => results[index] = Some(Err(e)),
        }
    }
    let threads = rayon::current_num_threads().max(1);
    let groups: Vec<Group> = groups
        .into_iter()
        .map(|(key, members)| Group::new(key, members, width, threads))
        .collect();
    let tasks: Vec<Task<'_>> = scalar
        .into_iter()
        .map(Task::Scalar)
        .chain(
            groups
                .iter()
                .flat_map(|g| std::iter::repeat_n(Task::Lanes(g), g.workers)),
        )
        .collect();
    let done: Vec<(usize, Result<RunSummary>)> = tasks
        .into_par_iter()
        .flat_map_iter(|task| match task {
            Task::Scalar(index) => vec![(
                index,
                on_scalar_path(&jobs[index], peak_watch, stop_above_n),
            )],
            Task::Lanes(group) => group.run_worker(jobs, peak_watch, stop_above_n),
        })
        .collect();
    for (index, result) in done {
        results[index] = Some(result);
    }
    results
        .into_iter()
        .map(|r| r.expect("every job has a result"))
        .collect()
}

/// A job run by [`simulate`](crate::simulate()) itself, watching and stopping as the lanes do.
fn on_scalar_path(job: &Job<'_>, peak_watch: PeakWatch, stop_above_n: f64) -> Result<RunSummary> {
    simulate_watching(
        job.chain,
        job.excitation,
        job.settings,
        &mut (),
        peak_watch,
        stop_above_n,
    )
}

/// What the runs of one lane group share.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct GroupKey {
    n_primary: usize,
    shift: usize,
    blast: bool,
    adaptive: bool,
    /// Event-aware stepping ([`Method::Dopri5Events`], [`Method::Rkn64`]).
    events: bool,
    /// A Runge–Kutta–Nyström method ([`Method::Rkn64`]).
    nystrom: bool,
    /// The lab physics' terms (None: the paper's model).
    lab: Option<LabShape>,
}

/// Checks a job as [`simulate`](crate::simulate()) does (same errors, same order) and compiles it; `None` when it
/// is not for the lanes.
fn lane_ready(job: &Job<'_>) -> Result<Option<(GroupKey, ChainOde)>> {
    job.settings.check_run_of(job.excitation)?;
    let ode = ChainOde::new(job.chain, job.excitation)?;
    check_method_fits(&ode, job.settings.method)?;
    if job.settings.sample_interval_s != job.settings.duration_s {
        return Ok(None);
    }
    // The exact modal method has no lane kernels: its runs take the scalar path.
    if matches!(
        crate::simulate::resolve_method(&ode, job.settings.method),
        Method::ExactModes { .. }
    ) {
        return Ok(None);
    }
    let method = job.settings.method.resolve(ode.second_order().is_some());
    let lab = ode.eq.lab.as_ref();
    let key = GroupKey {
        lab: lab.map(|lab| lab.shape.clone()),
        n_primary: ode.eq.p,
        shift: ode.shift,
        blast: ode.is_blast(),
        adaptive: method.adaptive(),
        events: method.event_aware(),
        nystrom: matches!(method, Method::Rkn64 { .. }),
    };
    Ok(Some((key, ode)))
}

/// A unit of [`simulate_many_stopping`]'s parallel work: a run for the scalar path, or one
/// worker's lanes of a group.
#[derive(Clone, Copy)]
enum Task<'g> {
    Scalar(usize),
    Lanes(&'g Group),
}

/// The runs of one group key, waiting in one queue for the lanes of its workers.
///
/// Each worker (one per thread) advances its own lanes and refills a lane from the shared queue
/// as soon as the lane's run ends, so lanes idle only while the last runs finish. A group with
/// at most half as many runs per worker as lanes runs one lane wide: a lane group costs the
/// same per step however many of its lanes are busy, and on the development machine a step of
/// four lanes costs about three times a step of one (bench/README.md).
struct Group {
    key: GroupKey,
    /// The job whose method gives the tableau (every run of a group has the same method kind).
    first_job: usize,
    /// The most resonators any run of the group has on each primary: the lanes' slots.
    slots_per_element: Vec<usize>,
    /// The equations of the group's first run: the shape every run of the group shares.
    like: Equations<f64>,
    width: LaneWidth,
    workers: usize,
    queue: Mutex<std::vec::IntoIter<(usize, ChainOde)>>,
}

impl Group {
    fn new(
        key: GroupKey,
        members: Vec<(usize, ChainOde)>,
        width: LaneWidth,
        threads: usize,
    ) -> Self {
        let p = key.n_primary;
        let mut slots_per_element = vec![0usize; p];
        for (_, ode) in &members {
            let mut count = vec![0usize; p];
            for &o in &ode.eq.res_owner {
                count[o] += 1;
            }
            for (s, c) in slots_per_element.iter_mut().zip(count) {
                *s = (*s).max(c);
            }
        }
        let runs = members.len();
        let per_worker = runs.div_ceil(threads.min(runs).max(1));
        let width = if 2 * per_worker <= width.lanes() {
            LaneWidth::One
        } else {
            width
        };
        Group {
            key,
            first_job: members[0].0,
            like: members[0].1.eq.clone(),
            slots_per_element,
            width,
            workers: threads.min(runs.div_ceil(width.lanes())).max(1),
            queue: Mutex::new(members.into_iter()),
        }
    }

    /// The next run waiting for a lane, if any.
    fn next_run(&self) -> Option<(usize, ChainOde)> {
        // A worker that panicked left the queue intact: its lock is still good to take.
        let mut queue = self.queue.lock().unwrap_or_else(|e| e.into_inner());
        queue.next()
    }

    /// One worker: its lanes take runs from the queue until it is empty and every lane is done.
    fn run_worker(
        &self,
        jobs: &[Job<'_>],
        peak_watch: PeakWatch,
        stop_above_n: f64,
    ) -> Vec<(usize, Result<RunSummary>)> {
        match self.width {
            LaneWidth::One => run_lanes::<1>(jobs, self, peak_watch, stop_above_n),
            LaneWidth::Two => run_lanes::<2>(jobs, self, peak_watch, stop_above_n),
            LaneWidth::Four => run_lanes::<4>(jobs, self, peak_watch, stop_above_n),
            LaneWidth::Eight => run_lanes::<8>(jobs, self, peak_watch, stop_above_n),
        }
    }
}

/// One worker's lanes of a group, choosing the instruction set at run time.
#[allow(unsafe_code)]
fn run_lanes<const L: usize>(
    jobs: &[Job<'_>],
    group: &Group,
    peak_watch: PeakWatch,
    stop_above_n: f64,
) -> Vec<(usize, Result<RunSummary>)> {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked on the line above).
            return unsafe { run_lanes_avx2::<L>(jobs, group, peak_watch, stop_above_n) };
        }
    }
    Lanes::<L>::new(jobs, group, peak_watch, stop_above_n).run()
}

/// [`run_lanes`] compiled for AVX2 (no FMA: the results stay those of the portable build).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[allow(unsafe_code)]
unsafe fn run_lanes_avx2<const L: usize>(
    jobs: &[Job<'_>],
    group: &Group,
    peak_watch: PeakWatch,
    stop_above_n: f64,
) -> Vec<(usize, Result<RunSummary>)> {
    Lanes::<L>::new(jobs, group, peak_watch, stop_above_n).run()
}
