//! One worker's lanes: L runs of one group in structure-of-arrays form, advanced by the scalar
//! path's own kernels ([`crate::integrate`]'s stage loop, error terms and crossing prediction, the
//! equations of [`crate::ode::Equations`] and the step control of [`StepControl`]), each lane
//! refilled from its group's queue when its run ends.

// Lane loops index several arrays by the lane number l: the plain form that LLVM vectorizes.
#![allow(clippy::needless_range_loop)]

use crate::error::Result;
use crate::integrate::{
    self, fixed_step_end, IntegratorStats, LandingRule, Method, OdeSystem, StepControl, Tableau,
    Verdict,
};
use crate::ode::{ChainOde, Equations, Load};
use crate::real::{Lane, Mask, Real, MAX_LANES};
use crate::simulate::{
    start_integrator, too_many_steps, PeakWatch, RunSettings, RunSummary, Watch,
};

use super::{on_scalar_path, Group, Job};

/// Lane l's contact forces and overlaps into its run's force cache.
fn contacts_into<const L: usize>(
    ode: &mut ChainOde,
    force: &[Lane<L>],
    overlap: &[Lane<L>],
    l: usize,
) {
    for (s, (f, d)) in force.iter().zip(overlap).enumerate() {
        ode.force_n[s] = f.0[l];
        ode.overlap_m[s] = d.0[l];
    }
}

/// The scalar run that occupies a lane: its compiled chain (for the per-step work and the
/// summary), its watch and its step control.
struct LaneRun<'a> {
    job: usize,
    ode: ChainOde,
    settings: &'a RunSettings,
    watch: Watch<'a>,
    t: f64,
    /// Start of the last accepted step (event-aware stepping).
    t_prev: f64,
    /// Step control (a fixed step's size in `step.h`).
    step: StepControl,
    rtol: f64,
    stats: IntegratorStats,
    /// The run's own state vector (its layout, not the lanes'): filled where needed.
    y: Vec<f64>,
    /// Lane index of each component of `y`.
    place: Vec<usize>,
}

/// L runs of one group in structure-of-arrays form, and the queue of runs waiting for a lane.
pub(super) struct Lanes<'a, const L: usize> {
    jobs: &'a [Job<'a>],
    peak_watch: PeakWatch,
    /// Runs stop at the end of the first step whose transmitted peak exceeds this \[N\].
    stop_above_n: f64,
    tableau: Tableau,
    adaptive: bool,
    events: bool,
    nystrom: bool,
    landing_rule: LandingRule,
    order: f64,
    /// Whether slot 0 carries a prescribed load (no striker).
    loaded: bool,
    dim: usize,
    /// Lane index of each primary's first resonator slot (each primary has as many slots as the
    /// most resonators any run of the group has on it).
    slot_start: Vec<usize>,
    /// The equations of motion, one run per lane.
    eq: Equations<Lane<L>>,
    atol: Vec<Lane<L>>,
    y: Vec<Lane<L>>,
    stage: Vec<Lane<L>>,
    f_now: Vec<Lane<L>>,
    k: Vec<Vec<Lane<L>>>,
    err: Vec<Lane<L>>,
    force: Vec<Lane<L>>,
    overlap: Vec<Lane<L>>,
    /// Overlap limit per slot (infinite where there is none, and in empty lanes).
    limit: Vec<Lane<L>>,
    runs: Vec<Option<LaneRun<'a>>>,
    group: &'a Group,
    /// Whether the group's queue was found empty (lanes then stop asking).
    drained: bool,
    done: Vec<(usize, Result<RunSummary>)>,
}

impl<'a, const L: usize> Lanes<'a, L> {
    pub(super) fn new(
        jobs: &'a [Job<'a>],
        group: &'a Group,
        peak_watch: PeakWatch,
        stop_above_n: f64,
    ) -> Self {
        let key = &group.key;
        let p = key.n_primary;
        let slots_per_element = &group.slots_per_element;
        let res_owner: Vec<usize> = slots_per_element
            .iter()
            .enumerate()
            .flat_map(|(o, &n)| std::iter::repeat_n(o, n))
            .collect();
        let slot_start: Vec<usize> = slots_per_element
            .iter()
            .scan(p, |start, &n| {
                let s = *start;
                *start += n;
                Some(s)
            })
            .collect();
        let eq = Equations::empty_like(&group.like, res_owner);
        let dim = eq.dimension();
        let tableau = if key.nystrom {
            Tableau::rkn64()
        } else {
            jobs[group.first_job]
                .settings
                .method
                .resolve(false)
                .tableau()
        };
        let zeros = |n: usize| vec![Lane::<L>::ZERO; n];
        Lanes {
            jobs,
            peak_watch,
            stop_above_n,
            order: f64::from(tableau.order),
            k: (0..tableau.stages()).map(|_| zeros(dim)).collect(),
            landing_rule: LandingRule::of(&tableau),
            tableau,
            adaptive: key.adaptive,
            events: key.events,
            nystrom: key.nystrom,
            loaded: key.shift == 1,
            dim,
            slot_start,
            eq,
            atol: vec![Lane::splat(1.0); dim],
            y: zeros(dim),
            stage: zeros(dim),
            f_now: zeros(dim),
            err: zeros(dim),
            force: zeros(p + 1),
            overlap: zeros(p + 1),
            limit: vec![Lane::splat(f64::INFINITY); p + 1],
            runs: (0..L).map(|_| None).collect(),
            group,
            drained: false,
            done: Vec::new(),
        }
    }

    #[inline(always)]
    pub(super) fn run(mut self) -> Vec<(usize, Result<RunSummary>)> {
        loop {
            for l in 0..L {
                if self.runs[l].is_none() {
                    self.fill(l);
                }
            }
            if self.runs.iter().all(Option::is_none) {
                return self.done;
            }
            self.iterate();
        }
    }

    /// Starts the next queued run in lane l, as [`simulate`](crate::simulate()) starts it.
    fn fill(&mut self, l: usize) {
        if self.drained {
            return;
        }
        let Some((job, mut ode)) = self.group.next_run() else {
            self.drained = true;
            return;
        };
        if crate::interrupt::requested() {
            // No queued run starts: each ends interrupted, and the lanes stop asking.
            let interrupted = || Err(crate::Error::Interrupted { time_s: 0.0 });
            self.done.push((job, interrupted()));
            while let Some((job, _)) = self.group.next_run() {
                self.done.push((job, interrupted()));
            }
            self.drained = true;
            return;
        }
        let jobs = self.jobs;
        let Job {
            excitation,
            settings,
            ..
        } = jobs[job];
        let started = crate::clock::Stopwatch::start();
        let (integrator, units) = start_integrator(&mut ode, settings);
        let watch = Watch::start(
            &mut ode,
            excitation,
            settings,
            integrator.y(),
            &mut (),
            started,
            self.peak_watch,
        )
        .stop_above(self.stop_above_n);
        let (step, rtol, atol) = match settings.method.resolve(self.nystrom) {
            Method::Dopri5 { rtol, atol }
            | Method::Dopri5Events { rtol, atol }
            | Method::Rkn64 { rtol, atol } => {
                let step = integrator.adaptive_control().expect("adaptive");
                (step, rtol, atol)
            }
            Method::Rk4 { time_step_s } => (StepControl::new(time_step_s), 0.0, 0.0),
            Method::PeakTolerance { .. } | Method::ExactModes { .. } => {
                unreachable!("resolved; the exact modal method runs on the scalar path")
            }
        };
        // Where each of the run's components sits in the lanes.
        let (p, nd) = (self.eq.p, self.eq.nd);
        let mut place = Vec::with_capacity(ode.dimension());
        let mut res_place = Vec::with_capacity(ode.eq.res_owner.len());
        let mut next_slot = vec![0usize; p];
        for &o in &ode.eq.res_owner {
            res_place.push(self.slot_start[o] + next_slot[o]);
            next_slot[o] += 1;
        }
        place.extend(0..p);
        place.extend(res_place.iter().copied());
        place.extend(nd..nd + p);
        place.extend(res_place.iter().map(|&i| nd + i));
        place.extend(2 * nd..self.dim);
        debug_assert_eq!(place.len(), ode.dimension());
        // Parameters and state into lane l; padding stays inert.
        for c in 0..self.dim {
            self.y[c].0[l] = 0.0;
            self.f_now[c].0[l] = 0.0;
            self.atol[c].0[l] = 1.0;
        }
        let n = place.len();
        for (i, &c) in place.iter().enumerate() {
            self.y[c].0[l] = integrator.y()[i];
            self.f_now[c].0[l] = integrator.f_now()[i];
            self.atol[c].0[l] = atol * units[i];
        }
        let res_slot: Vec<usize> = res_place.iter().map(|&c| c - p).collect();
        self.eq.set_lane(l, &ode.eq, &res_slot);
        for s in 0..=p {
            self.limit[s].0[l] = ode.overlap_limits_by_slot()[s];
        }
        let stats = integrator.stats();
        self.runs[l] = Some(LaneRun {
            job,
            y: vec![0.0; n],
            place,
            ode,
            settings,
            watch,
            t: 0.0,
            t_prev: 0.0,
            step,
            rtol,
            stats,
        });
    }

    /// One attempted step in every occupied lane, then each lane's own bookkeeping.
    #[inline(always)]
    fn iterate(&mut self) {
        let (t, h, t_fixed) = self.propose_steps();
        self.attempt(&t, &h);
        let mut err = [0.0; L];
        if self.adaptive {
            self.error_norms(&h, &mut err);
        }
        let missed = if self.nystrom {
            self.missed_crossings(&h, &err)
        } else {
            [None; MAX_LANES]
        };
        let accepted = self.judge(&h, &err, &missed);
        self.commit(accepted, &t, &h);
        let blown_up = self.check_contacts();
        for l in 0..L {
            if accepted[l] && self.runs[l].is_some() {
                let t1 = if self.adaptive {
                    t[l] + h[l]
                } else {
                    t_fixed[l]
                };
                self.after_accept(l, t[l], t1, h[l], err[l], blown_up[l]);
            }
        }
    }

    /// Each occupied lane's time and step to try, as [`Integrator`] chooses it: its controller's
    /// proposal ([`StepControl`], shortened to land on a predicted crossing), or the fixed step
    /// (also: where it ends). A lane whose step fell below the smallest allowed goes to the
    /// scalar path, which reports it.
    #[allow(clippy::type_complexity)]
    #[inline(always)]
    fn propose_steps(&mut self) -> ([f64; L], [f64; L], [f64; L]) {
        let (mut t, mut h, mut t_fixed) = ([0.0; L], [0.0; L], [0.0; L]);
        // Lanes whose step event-aware stepping may shorten.
        let mut want = [false; MAX_LANES];
        for l in 0..L {
            let Some(run) = &self.runs[l] else { continue };
            let t_end = run.settings.duration_s;
            t[l] = run.t;
            if !self.adaptive {
                t_fixed[l] = fixed_step_end(0.0, run.stats.steps, run.step.h, t_end);
                h[l] = t_fixed[l] - run.t;
                continue;
            }
            want[l] = self.events && run.step.predicts() && run.stats.steps > 0;
            match run.step.propose(run.t, t_end) {
                Ok(h_try) => h[l] = h_try,
                Err(_) => {
                    want[l] = false;
                    self.rerun(l);
                }
            }
        }
        if self.adaptive {
            let predicted = if self.events {
                self.predict_crossings(&h, want)
            } else {
                [None; MAX_LANES]
            };
            for l in 0..L {
                if let Some(run) = self.runs[l].as_mut() {
                    h[l] = run.step.land(h[l], predicted[l]);
                }
            }
        }
        (t, h, t_fixed)
    }

    /// Each lane's verdict on its attempt ([`StepControl::judge`]; fixed steps are accepted).
    /// Empty lanes count as accepted (their values are never read).
    #[inline(always)]
    fn judge(&mut self, h: &[f64; L], err: &[f64; L], missed: &[Option<f64>]) -> Mask {
        let stages = self.tableau.stages();
        let mut accepted = [true; MAX_LANES];
        for l in 0..L {
            let Some(run) = &mut self.runs[l] else {
                continue;
            };
            run.stats.rhs_evaluations += (stages - 1) as u64;
            if self.adaptive {
                let verdict = run
                    .step
                    .judge(h[l], err[l], missed[l], self.order, &mut run.stats);
                accepted[l] = verdict == Verdict::Accept;
            }
        }
        accepted
    }

    /// Accepted lanes take the new state; f at the current point is the FSAL stage for accepted
    /// lanes and the old one (moved to k\[0\] by `attempt`) for rejected ones; a tableau that is
    /// not FSAL (fixed steps: every lane accepted) evaluates f at the new point, at t + h as the
    /// integrator does.
    #[inline(always)]
    fn commit(&mut self, accepted: Mask, t: &[f64; L], h: &[f64; L]) {
        let last = self.tableau.stages() - 1;
        if accepted[..L].iter().all(|&a| a) {
            std::mem::swap(&mut self.y, &mut self.stage);
            if self.tableau.fsal {
                std::mem::swap(&mut self.f_now, &mut self.k[last]);
            }
        } else {
            for c in 0..self.dim {
                self.y[c] = Lane::select(accepted, self.stage[c], self.y[c]);
                let fsal = if self.tableau.fsal {
                    self.k[last][c]
                } else {
                    self.f_now[c]
                };
                self.f_now[c] = Lane::select(accepted, fsal, self.k[0][c]);
            }
        }
        if !self.tableau.fsal {
            let mut t_new = [0.0; L];
            for l in 0..L {
                t_new[l] = t[l] + h[l];
            }
            let load = self.loads(&t_new, 0.0, &[0.0; L]);
            let (force, overlap) = (&mut self.force, &mut self.overlap);
            self.eq
                .rhs(load, &self.y, &mut self.f_now, force, overlap, true);
        }
    }

    /// Event-aware stepping in every lane at once: for each lane in `want` (adaptive, after an
    /// accepted step), the step that lands on a predicted crossing of a contact's overlap within
    /// its next step of size h\[l\], as [`Integrator`] predicts it (the same kernel,
    /// [`integrate::predict_crossings`], on the same switching functions).
    #[inline(always)]
    fn predict_crossings(&self, h: &[f64; L], mut want: Mask) -> [Option<f64>; MAX_LANES] {
        let mut dt = [1.0; L];
        for l in 0..L {
            if let Some(run) = self.runs[l].as_ref().filter(|_| want[l]) {
                dt[l] = run.t - run.t_prev;
                want[l] = dt[l] > 0.0;
            }
        }
        if !want.iter().any(|&w| w) {
            return [None; MAX_LANES];
        }
        // After a step, k[0] holds f at its start and f_now f at its end; the switching
        // functions are evaluated where the kernel reads them.
        let (eq, y, f, k0) = (&self.eq, &self.y, &self.f_now, &self.k[0]);
        integrate::predict_crossings(
            eq.p,
            #[inline(always)]
            |s| eq.switch(y, s + 1),
            #[inline(always)]
            |s| eq.switch(f, s + 1),
            #[inline(always)]
            |s| eq.switch(k0, s + 1),
            Lane(dt),
            Lane(*h),
            want,
            self.landing_rule,
        )
    }

    /// [`Method::Rkn64`]'s check in every lane whose attempt passed its error test without a
    /// landing: the first crossing inside the step that no landing caught, as the integrator
    /// finds it (the same kernel, [`integrate::missed_crossings`]).
    fn missed_crossings(&self, h: &[f64; L], err: &[f64; L]) -> [Option<f64>; MAX_LANES] {
        let mut check = [false; MAX_LANES];
        for l in 0..L {
            check[l] = self.runs[l]
                .as_ref()
                .is_some_and(|run| !run.step.landing && err[l] <= 1.0);
        }
        if !check.iter().any(|&c| c) {
            return [None; MAX_LANES];
        }
        let last = self.k.len() - 1;
        let (eq, y0, y1) = (&self.eq, &self.y, &self.stage);
        let (f0, f1) = (&self.k[0], &self.k[last]);
        let g = (
            #[inline(always)]
            |s| eq.switch(y0, s + 1),
            #[inline(always)]
            |s| eq.switch(y1, s + 1),
        );
        let d = (
            #[inline(always)]
            |s| eq.switch(f0, s + 1),
            #[inline(always)]
            |s| eq.switch(f1, s + 1),
        );
        integrate::missed_crossings(eq.p, g, d, Lane(*h), check)
    }

    /// [`ChainOde::check_contacts`] of the force cache in every lane at once: whether it would
    /// fail (a non-finite force or overlap, or an overlap beyond its contact's limit). A lane that
    /// fails goes to the scalar path, which names the contact and the cause.
    #[inline(always)]
    fn check_contacts(&self) -> [bool; L] {
        let mut bad = [false; L];
        let first = usize::from(!self.loaded);
        for s in first..=self.eq.p {
            let (f, d, limit) = (self.force[s], self.overlap[s], self.limit[s]);
            for l in 0..L {
                bad[l] |=
                    !f.0[l].is_finite() || (s > 0 && !d.0[l].is_finite()) || d.0[l] > limit.0[l];
            }
        }
        bad
    }

    /// Bookkeeping of an accepted step [t0, t1] of size h in lane l: time, step control, checks,
    /// peaks, the end.
    fn after_accept(&mut self, l: usize, t0: f64, t1: f64, h: f64, err: f64, blown_up: bool) {
        let adaptive = self.adaptive;
        let order = self.order;
        let (p, nd) = (self.eq.p, self.eq.nd);
        let run = self.runs[l].as_mut().expect("occupied");
        run.stats.steps += 1;
        run.t = t1;
        if adaptive {
            run.step.accepted(h, err, order);
            run.t_prev = t0;
        } else {
            run.stats.rhs_evaluations += 1;
        }
        if blown_up {
            self.rerun(l);
            return;
        }
        let finished = t1 >= run.settings.duration_s * (1.0 - 1e-14);
        let sample = run.watch.sample_due(t1);
        // The lane's contact cache becomes the run's, with the velocities the rates need: every
        // slot, or only those of the watched contacts until a step that samples or ends the run.
        let n_dof = run.ode.n_dof();
        match run.watch.watched() {
            Some(watched) if !finished && sample.is_none() => {
                let first = 1 - run.ode.shift;
                for &c in watched {
                    let s = c + first;
                    run.ode.force_n[s] = self.force[s].0[l];
                    run.ode.overlap_m[s] = self.overlap[s].0[l];
                    for i in [s.saturating_sub(1), s.min(p - 1)] {
                        run.y[n_dof + i] = self.y[nd + i].0[l];
                    }
                }
            }
            _ => {
                contacts_into(&mut run.ode, &self.force, &self.overlap, l);
                for i in 0..p {
                    run.y[n_dof + i] = self.y[nd + i].0[l];
                }
            }
        }
        if crate::interrupt::requested() {
            let job = run.job;
            self.vacate(l);
            self.done
                .push((job, Err(crate::Error::Interrupted { time_s: t1 })));
            return;
        }
        if run.stats.steps > crate::defaults::MAX_STEPS {
            let e = too_many_steps(t1, run.settings);
            let job = run.job;
            self.vacate(l);
            self.done.push((job, Err(e)));
            return;
        }
        run.watch.after_step(&run.ode, t0, t1, &run.y);
        let stopped = !finished && run.watch.stop_due();
        if stopped {
            // The summary reads the whole force cache (and the state, copied below).
            contacts_into(&mut run.ode, &self.force, &self.overlap, l);
        }
        if sample.is_none() && !finished && !stopped {
            return;
        }
        for (i, &c) in run.place.iter().enumerate() {
            run.y[i] = self.y[c].0[l];
        }
        if let Some((ts, at_step)) = sample {
            if !at_step {
                // Not a lane run after all (a sample between steps): the scalar path decides.
                self.rerun(l);
                return;
            }
            if let Err(e) = run.watch.record(&mut run.ode, ts, &run.y, true, &mut ()) {
                let job = run.job;
                self.vacate(l);
                self.done.push((job, Err(e)));
                return;
            }
        }
        if finished || stopped {
            let run = self.vacate(l);
            let mut summary = run.watch.finish(&run.ode, &run.y, run.stats);
            summary.stopped_at_s = stopped.then_some(t1);
            self.done.push((run.job, Ok(summary)));
        }
    }

    /// Empties lane l (its run has left), leaving a state that stays finite under zero steps.
    fn vacate(&mut self, l: usize) -> LaneRun<'a> {
        for c in 0..self.dim {
            self.y[c].0[l] = 0.0;
            self.f_now[c].0[l] = 0.0;
        }
        self.runs[l].take().expect("occupied")
    }

    /// Gives lane l's run to the scalar path (which reproduces and diagnoses its failure).
    fn rerun(&mut self, l: usize) {
        let run = self.vacate(l);
        let result = on_scalar_path(&self.jobs[run.job], self.peak_watch, self.stop_above_n);
        self.done.push((run.job, result));
    }

    /// The prescribed load of every lane at times t\[l\] + c h\[l\] (none beside a striker or in
    /// an empty lane), from each run's own [`ChainOde::load_at`].
    #[inline(always)]
    fn loads(&self, t: &[f64; L], c: f64, h: &[f64; L]) -> Load<Lane<L>> {
        loads(&self.runs, self.loaded, t, c, h)
    }

    /// The stages of a step of size h[l] from (t[l], y) in every lane ([`integrate::attempt`], the
    /// scalar path's stage loop): k, and the new state in `stage`. Moves f at the current point
    /// into k[0].
    #[inline(always)]
    fn attempt(&mut self, t: &[f64; L], h: &[f64; L]) {
        std::mem::swap(&mut self.k[0], &mut self.f_now);
        let (eq, runs, loaded) = (&self.eq, &self.runs, self.loaded);
        let (force, overlap) = (&mut self.force, &mut self.overlap);
        // A Nyström stage reads only accelerations; its step's end writes the new velocities
        // into the last stage (`nystrom_finish`), the only one whose dx/dt is read.
        let velocities = !self.nystrom;
        integrate::attempt(
            &self.tableau,
            &self.y,
            &mut self.k,
            &mut self.stage,
            &mut self.err,
            Lane(*h),
            #[inline(always)]
            |c, stage, out| {
                let load = loads(runs, loaded, t, c, h);
                eq.rhs(load, stage, out, force, overlap, velocities);
            },
        );
    }

    /// Each lane's weighted RMS error norm, by the scalar path's kernels: the weighted squares
    /// of every component at once ([`integrate::weighted_squares`]), then, lane by lane, their
    /// norm in the run's own component order (`place`, [`integrate::rms`]).
    #[inline(always)]
    fn error_norms(&mut self, h: &[f64; L], out: &mut [f64; L]) {
        let mut rtol = [0.0; L];
        for (l, r) in rtol.iter_mut().enumerate() {
            *r = self.runs[l].as_ref().map_or(0.0, |run| run.rtol);
        }
        let (tableau, k, y, y1) = (&self.tableau, &self.k, &self.y, &self.stage);
        let (h, rtol) = (Lane(*h), Lane(rtol));
        integrate::weighted_squares(tableau, &mut self.err, k, h, y, y1, &self.atol, rtol);
        for l in 0..L {
            out[l] = match &self.runs[l] {
                Some(run) => {
                    // Lane l's squares in its run's own component order.
                    let err = &self.err;
                    integrate::rms(
                        &run.place,
                        #[inline(always)]
                        |c| err[c].0[l],
                    )
                }
                None => 0.0,
            };
        }
    }
}

/// The prescribed load of every occupied lane at times t\[l\] + c h\[l\] (see
/// [`Lanes::loads`]); a function of the fields it reads, so that a stage's closure can call it
/// beside the mutable force cache.
#[inline(always)]
fn loads<const L: usize>(
    runs: &[Option<LaneRun<'_>>],
    loaded: bool,
    t: &[f64; L],
    c: f64,
    h: &[f64; L],
) -> Load<Lane<L>> {
    let mut load = Load::<Lane<L>>::NONE;
    if loaded {
        for l in 0..L {
            if let Some(run) = &runs[l] {
                let one = run.ode.load_at(t[l] + c * h[l]);
                load.force_n.0[l] = one.force_n;
                load.tip_m.0[l] = one.tip_m;
                load.tip_rate_m_s.0[l] = one.tip_rate_m_s;
            }
        }
    }
    load
}
