//! Who owns the loop: runs a chain under an excitation, samples on a uniform grid for recorders,
//! and computes the figures of merit of docs/physics.md §8 over every integration step.

use crate::defaults;
use crate::error::{require_positive, Error, Result};
use crate::excitation::{BlastProfile, Excitation};
use crate::integrate::{Integrator, IntegratorStats, Method, OdeSystem};
use crate::math::Libm;
use crate::model::Chain;
use crate::ode::ChainOde;
use crate::record::{Layout, Recorder, Sample};

mod lattice;
mod modal;

pub use lattice::{
    lattice_method, simulate_lattice, LatticeRun, LATTICE_EXACT_MODES_RTOL_OF_TOLERANCE,
};

/// How long, how and how often to sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSettings {
    /// Simulated time T \[s\].
    pub duration_s: f64,
    /// Integration method.
    pub method: Method,
    /// Spacing of the uniform sample grid Δs \[s\].
    pub sample_interval_s: f64,
}

impl RunSettings {
    /// The method a run of `chain` under `excitation` steps with: `method` resolved for its
    /// system ([`Method::resolve`]; a stated peak tolerance becomes RKN 6(4) or event-aware
    /// DOPRI5).
    pub fn method_for(&self, chain: &Chain, excitation: &Excitation) -> Result<Method> {
        let ode = ChainOde::new(chain, excitation)?;
        Ok(resolve_method(&ode, self.method))
    }

    /// Checks these settings ([`RunSettings::validate`]) and the excitation against them (a drive
    /// above the fixed step's Nyquist frequency, a blast that decays within one step): what both
    /// [`simulate`] and the lanes check before a run.
    pub fn check_run_of(&self, excitation: &Excitation) -> Result<()> {
        self.validate()?;
        let fixed_step_s = match self.method {
            Method::Rk4 { time_step_s } => Some(time_step_s),
            _ => None,
        };
        excitation.check_against_run(fixed_step_s)
    }

    /// docs/physics.md §8 for an impact: 2 ms, RK4 at 0.1 µs, samples every 1 µs.
    pub fn paper_impact() -> Self {
        RunSettings {
            duration_s: defaults::IMPACT_DURATION_S,
            method: Method::paper(),
            sample_interval_s: defaults::SAMPLE_INTERVAL_S,
        }
    }

    /// docs/physics.md §8 for a blast: 3 ms, RK4 at 0.1 µs, samples every 1 µs.
    pub fn paper_blast() -> Self {
        RunSettings {
            duration_s: defaults::BLAST_RUN_DURATION_S,
            ..Self::paper_impact()
        }
    }

    /// The defaults for an excitation: an impact's 2 ms, a blast's 3 ms; a drive or a column at
    /// rest also 3 ms, or a chirp's sweep plus 1 ms when that is longer.
    pub fn paper_for(excitation: &Excitation) -> Self {
        match excitation {
            Excitation::Impact(_) => Self::paper_impact(),
            Excitation::Blast(_) | Excitation::Rest => Self::paper_blast(),
            Excitation::Drive(d) => {
                let sweep = match d.signal {
                    crate::excitation::Signal::Chirp { duration_s, .. } => duration_s + 1e-3,
                    _ => 0.0,
                };
                RunSettings {
                    duration_s: sweep.max(defaults::BLAST_RUN_DURATION_S),
                    ..Self::paper_impact()
                }
            }
        }
    }

    /// Validates every field (names as in a scenario file's `[run]` table).
    pub fn validate(&self) -> Result<()> {
        require_positive("run.duration_s", self.duration_s)?;
        require_positive("run.sample_interval_s", self.sample_interval_s)?;
        if self.sample_interval_s > self.duration_s {
            return Err(Error::invalid(
                "run.sample_interval_s",
                self.sample_interval_s,
                format!("must not exceed run.duration_s = {}", self.duration_s),
            ));
        }
        let samples = self.duration_s / self.sample_interval_s;
        if samples > 1e8 {
            // Both keys make the count: the message names both, the field the run's length.
            return Err(Error::invalid(
                "run.duration_s",
                self.duration_s,
                format!(
                    "with run.sample_interval_s = {} gives {samples:.1e} samples, more than 1e8: choose a shorter run.duration_s or a larger run.sample_interval_s",
                    self.sample_interval_s
                ),
            ));
        }
        self.method.validate(self.duration_s)
    }

    /// Integration steps the run will take: T/Δt rounded up for a fixed step; `None` for the
    /// adaptive method (its steps follow the dynamics; [`defaults::MAX_STEPS`] bounds them).
    pub fn estimated_steps(&self) -> Option<u64> {
        match self.method {
            Method::Rk4 { time_step_s } => {
                // A ratio within rounding of an integer is that integer (the step snaps to T).
                let ratio = self.duration_s / time_step_s;
                let n = if (ratio - ratio.round()).abs() <= 1e-9 * ratio {
                    ratio.round()
                } else {
                    ratio.ceil()
                };
                Some(n.max(1.0) as u64)
            }
            Method::Dopri5 { .. }
            | Method::Dopri5Events { .. }
            | Method::Rkn64 { .. }
            | Method::ExactModes { .. }
            | Method::PeakTolerance { .. } => None,
        }
    }

    /// Number of samples t_k = k Δs ≤ T, k = 0, 1, …
    pub fn n_samples(&self) -> usize {
        (self.duration_s / self.sample_interval_s * (1.0 + 1e-12)).floor() as usize + 1
    }
}

/// The striker's rebound.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Restitution {
    /// e = −v_s(end)/v0. Without gravity the striker's velocity is constant once it has left.
    pub coefficient: f64,
    /// True when, at the end, the striker is out of contact and moving away from element 1
    /// (slower than it toward the wall); false means the run ended too early for a final value.
    pub separated: bool,
}

/// Energy bookkeeping of a run (docs/physics.md §7).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EnergyBalance {
    /// Total energy at t = 0 \[J\].
    pub initial_j: f64,
    /// Total energy at the end \[J\].
    pub final_j: f64,
    /// Work done by the external forces over the run \[J\] (0 for an impact without a static
    /// load): the load, an actuator, a preload, gravity.
    pub input_work_j: f64,
    /// Energy dissipated over the run \[J\] (0 without damping; docs/physics.md §14).
    #[cfg_attr(feature = "serde", serde(default))]
    pub dissipated_j: f64,
    /// Largest |E(t) + D(t) − E(0) − W(t)| over the samples, relative to the larger of E(0) and
    /// the largest |W| (E(0) for the paper's impact, |W| for its blast).
    pub max_relative_error: f64,
}

impl RunSummary {
    /// The striker's restitution coefficient, only when it means something: an impact whose
    /// striker has left for good by the end of the run (`None` for a blast, or when the run
    /// ended with the striker still in contact or still moving with the chain).
    pub fn restitution_coefficient(&self) -> Option<f64> {
        self.restitution
            .filter(|r| r.separated)
            .map(|r| r.coefficient)
    }
}

/// Figures of merit of one run (docs/physics.md §8).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RunSummary {
    /// Peak force of every contact 0..=N over the whole run \[N\].
    pub contact_peak_forces_n: Vec<f64>,
    /// Time of each peak \[s\].
    pub contact_peak_times_s: Vec<f64>,
    /// Incident force: the peak of contact 1 \[N\].
    pub incident_peak_force_n: f64,
    /// Transmitted force: the peak of contact N (the wall) \[N\].
    pub transmitted_peak_force_n: f64,
    /// Transmitted / incident; `None` when it means nothing: a zero incident force, or a wave
    /// that never reached the wall within the run (see [`RunSummary::wave_arrived`]). Under a
    /// static load, of the dynamic parts (peak minus static force).
    pub transmission_ratio: Option<f64>,
    /// Static force of every contact 0..=N \[N\] under a preload or gravity (empty without one):
    /// a peak's dynamic part is the peak minus this.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Vec::is_empty")
    )]
    pub static_contact_forces_n: Vec<f64>,
    /// A displacement drive's tip at rest: its static position u* \[m\] (downward; None without
    /// a displacement actuator; [`ChainOde::actuator_rest_m`]).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub actuator_rest_m: Option<f64>,
    /// Whether the wave reached the wall: the transmitted peak is at least
    /// [`defaults::WAVE_ARRIVAL_FRACTION`] of the incident peak. False means the run is too short
    /// (or the chain too long) for the transmitted force to mean anything: increase the duration.
    pub wave_arrived: bool,
    /// The striker's rebound (impact only).
    pub restitution: Option<Restitution>,
    /// Energy balance.
    pub energy: EnergyBalance,
    /// Integrator work.
    pub stats: IntegratorStats,
    /// Number of samples delivered.
    pub n_samples: usize,
    /// Wall-clock time of the run \[s\].
    pub wall_time_s: f64,
    /// The time \[s\] at which the run was stopped early, at the end of the first step whose
    /// transmitted peak exceeded a design study's cutoff (`ga.stop_early`, docs/physics.md §11);
    /// None for a run over the whole `duration_s`. The peaks of a stopped run are those of
    /// [0, stopped_at_s], lower bounds of the whole run's.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub stopped_at_s: Option<f64>,
}

/// Tracks the peak of each contact force over every step, refining a maximum that falls between
/// two steps with the quintic Hermite interpolant of F and dF/dt at the last three step ends
/// (error O(h⁶)) when the contact was closed at all three, and with the cubic of the last two
/// (error O(h⁴)) otherwise.
#[derive(Debug, Clone)]
pub(crate) struct PeakTracker {
    pub(crate) peak: Vec<f64>,
    pub(crate) time: Vec<f64>,
    prev_force: Vec<f64>,
    prev_rate: Vec<f64>,
    /// F, dF/dt and the time one step further back (time NaN: none yet).
    prev2_force: Vec<f64>,
    prev2_rate: Vec<f64>,
    prev2_time: Vec<f64>,
    /// dF/dt at the end of the current step, filled by the caller before `update`.
    pub(crate) rate: Vec<f64>,
}

impl PeakTracker {
    pub(crate) fn new(n: usize) -> Self {
        PeakTracker {
            peak: vec![0.0; n],
            time: vec![0.0; n],
            prev_force: vec![0.0; n],
            prev_rate: vec![0.0; n],
            prev2_force: vec![0.0; n],
            prev2_rate: vec![0.0; n],
            prev2_time: vec![f64::NAN; n],
            rate: vec![0.0; n],
        }
    }

    /// Starts from the forces (and `self.rate`) at t = 0.
    pub(crate) fn start(&mut self, force: &[f64]) {
        self.peak.copy_from_slice(force);
        self.prev_force.copy_from_slice(force);
        self.prev_rate.copy_from_slice(&self.rate);
    }

    /// Updates with the forces and rates at the end of a step [t0, t1].
    pub(crate) fn update(&mut self, t0: f64, t1: f64, force: &[f64]) {
        for (c, &f1) in force.iter().enumerate() {
            self.update_contact(c, t0, t1, f1);
        }
    }

    /// Updates contact c with its force f1 (and `self.rate[c]`) at the end of a step [t0, t1].
    #[inline(always)]
    pub(crate) fn update_contact(&mut self, c: usize, t0: f64, t1: f64, f1: f64) {
        let h = t1 - t0;
        let d1 = self.rate[c];
        let (f0, d0) = (self.prev_force[c], self.prev_rate[c]);
        if f1 > self.peak[c] {
            self.peak[c] = f1;
            self.time[c] = t1;
        }
        if d0 > 0.0 && d1 <= 0.0 {
            let cubic = hermite_max(f0, d0 * h, f1, d1 * h);
            // Three step ends inside one contact (closed at all three: no kink between them).
            let t_back = self.prev2_time[c];
            let quintic = (self.prev2_force[c] > 0.0 && f1 > 0.0 && t_back < t0)
                .then(|| {
                    let back = [
                        (t_back - t0) / h,
                        self.prev2_force[c],
                        self.prev2_rate[c] * h,
                    ];
                    hermite3_max(
                        back,
                        [f0, d0 * h],
                        [f1, d1 * h],
                        cubic.map(|(theta, _)| theta),
                    )
                })
                .flatten();
            if let Some((theta, f)) = quintic.or(cubic) {
                if f > self.peak[c] {
                    self.peak[c] = f;
                    self.time[c] = t0 + theta * h;
                }
            }
        }
        self.prev2_force[c] = f0;
        self.prev2_rate[c] = d0;
        self.prev2_time[c] = t0;
        self.prev_force[c] = f1;
        self.prev_rate[c] = d1;
    }
}

/// Which contact peaks a run tracks over every step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PeakWatch {
    /// Every contact 0..=N: what [`simulate`] reports.
    #[default]
    Every,
    /// Only the contacts of the figures of merit, the incident (contact 1) and the transmitted
    /// (contact N) peak: a design study's objectives, for a fraction of the per-step work. Those
    /// two peaks, the ratio, `wave_arrived`, the restitution and the energy balance are bit for bit
    /// those of [`PeakWatch::Every`]; the other entries of `contact_peak_forces_n` and
    /// `contact_peak_times_s` are NaN (not tracked).
    FiguresOfMerit,
}

impl PeakWatch {
    /// The contacts tracked in a chain of `n_layers` layers (contacts 0..n_layers); None = all.
    pub(crate) fn contacts(self, n_layers: usize) -> Option<Vec<usize>> {
        match self {
            PeakWatch::Every => None,
            PeakWatch::FiguresOfMerit => {
                let n = n_layers - 1;
                let mut c = vec![1.min(n), n];
                c.dedup();
                Some(c)
            }
        }
    }
}

/// Maximum on (0, 1) of the cubic Hermite interpolant with values f0, f1 and scaled slopes
/// s0 = h f'(t0), s1 = h f'(t1): returns (θ, value).
fn hermite_max(f0: f64, s0: f64, f1: f64, s1: f64) -> Option<(f64, f64)> {
    let p = |t: f64| {
        let u = 1.0 - t;
        (1.0 + 2.0 * t) * u * u * f0 + t * u * u * s0 + t * t * (3.0 - 2.0 * t) * f1
            - t * t * u * s1
    };
    // p'(θ) = a θ² + b θ + c
    let a = 6.0 * f0 + 3.0 * s0 - 6.0 * f1 + 3.0 * s1;
    let b = -6.0 * f0 - 4.0 * s0 + 6.0 * f1 - 2.0 * s1;
    let c = s0;
    let mut best: Option<(f64, f64)> = None;
    let mut consider = |t: f64| {
        if t > 0.0 && t < 1.0 {
            let v = p(t);
            if best.is_none_or(|(_, bv)| v > bv) {
                best = Some((t, v));
            }
        }
    };
    if a.abs() < 1e-300 {
        if b != 0.0 {
            consider(-c / b);
        }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            consider(q / a);
            if q != 0.0 {
                consider(c / q);
            }
        }
    }
    best
}

/// The maximum inside (0, 1) of the quintic p(s) that matches value and slope at s = a < 0
/// (`back` = [a, p(a), p'(a)]), at s = 0 (`start` = [p, p']) and at s = 1 (`end`): Newton's method
/// on p' from `guess` (the cubic's maximum) or 1/2. None when it does not converge to a maximum
/// inside the step (the caller keeps the cubic's).
fn hermite3_max(
    back: [f64; 3],
    start: [f64; 2],
    end: [f64; 2],
    guess: Option<f64>,
) -> Option<(f64, f64)> {
    let [a, fa, ga] = back;
    let z = [a, a, 0.0, 0.0, 1.0, 1.0];
    let (f, g) = ([fa, start[0], end[0]], [ga, start[1], end[1]]);
    // Divided differences on the doubled nodes: coef[k] = [z0..zk].
    let mut table = [0.0; 6];
    for (i, t) in table.iter_mut().enumerate() {
        *t = f[i / 2];
    }
    let mut coef = [0.0; 6];
    coef[0] = table[0];
    for order in 1..6 {
        for i in (order..6).rev() {
            table[i] = if z[i] == z[i - order] {
                g[i / 2]
            } else {
                (table[i] - table[i - 1]) / (z[i] - z[i - order])
            };
        }
        coef[order] = table[order];
    }
    // p, p', p'' at s (Horner on the Newton form).
    let eval = |s: f64| {
        let (mut p, mut d1, mut d2) = (coef[5], 0.0, 0.0);
        for k in (0..5).rev() {
            let w = s - z[k];
            d2 = d2 * w + 2.0 * d1;
            d1 = d1 * w + p;
            p = p * w + coef[k];
        }
        (p, d1, d2)
    };
    let mut s = guess.unwrap_or(0.5);
    for _ in 0..20 {
        let (_, d1, d2) = eval(s);
        if d2 >= 0.0 {
            return None;
        }
        let step = d1 / d2;
        s -= step;
        if !(0.0..=1.0).contains(&s) {
            return None;
        }
        if step.abs() <= 1e-14 {
            let (p, _, _) = eval(s);
            return (s > 0.0 && s < 1.0).then_some((s, p));
        }
    }
    None
}

/// Buffers for observing a state at a sample time.
pub(crate) struct Observer {
    energies: Vec<f64>,
    scratch: Vec<f64>,
}

/// Everything a run watches besides the state: peaks over every step, the samples handed to the
/// recorder, the energy balance. Shared by [`simulate`] and the lanes of [`crate::lanes`], so
/// that both report the same numbers from the same states.
pub(crate) struct Watch<'a> {
    peaks: PeakTracker,
    /// The contacts tracked over every step (None = all; [`PeakWatch`]).
    watched: Option<Vec<usize>>,
    obs: Observer,
    initial_energy: Energies,
    reference_energy: f64,
    last: Energies,
    max_abs_error: f64,
    max_abs_work: f64,
    next_sample: usize,
    n_samples: usize,
    sample_interval_s: f64,
    duration_s: f64,
    /// A tabulated load is piecewise linear: its peak over a step lies at an end of the step or
    /// at a breakpoint inside it, which the step grid may miss.
    load_table: Option<(&'a [f64], &'a [f64])>,
    next_breakpoint: usize,
    started: crate::clock::Stopwatch,
    /// The run stops at the end of the first step whose transmitted peak exceeds this \[N\]
    /// (infinite: never).
    stop_above_n: f64,
}

impl<'a> Watch<'a> {
    /// Starts watching at t = 0; the force cache of `ode` must be at `y0` (the integrator's
    /// last evaluation). Hands the first sample to `recorder`.
    pub(crate) fn start(
        ode: &mut ChainOde,
        excitation: &'a Excitation,
        settings: &RunSettings,
        y0: &[f64],
        recorder: &mut dyn Recorder,
        started: crate::clock::Stopwatch,
        peak_watch: PeakWatch,
    ) -> Self {
        let n_contacts = ode.n_layers();
        let mut peaks = PeakTracker::new(n_contacts);
        let mut obs = Observer {
            energies: vec![0.0; n_contacts],
            scratch: vec![0.0; ode.dimension()],
        };
        ode.contact_force_rates(0.0, y0, &mut peaks.rate);
        peaks.start(ode.contact_forces_n());
        let initial_energy = observe(ode, (0.0, y0), true, None, &mut obs, recorder);
        let reference_energy = if ode.has_striker() || ode.has_lab_physics() {
            initial_energy.total
        } else {
            0.0
        };
        let load_table = match excitation {
            Excitation::Blast(BlastProfile::Table { times_s, forces_n }) => {
                Some((times_s.as_slice(), forces_n.as_slice()))
            }
            _ => None,
        };
        Watch {
            peaks,
            watched: peak_watch.contacts(n_contacts),
            obs,
            initial_energy,
            reference_energy,
            last: initial_energy,
            max_abs_error: 0.0,
            max_abs_work: 0.0,
            next_sample: 1,
            n_samples: settings.n_samples(),
            sample_interval_s: settings.sample_interval_s,
            duration_s: settings.duration_s,
            load_table,
            next_breakpoint: 0,
            started,
            stop_above_n: f64::INFINITY,
        }
    }

    /// Stops the run at the end of the first step whose transmitted peak exceeds `force_n`.
    pub(crate) fn stop_above(mut self, force_n: f64) -> Self {
        self.stop_above_n = force_n;
        self
    }

    /// Whether the run stops after this step: its transmitted peak (a running maximum, which
    /// the rest of the run can only raise) exceeds the stopping force.
    pub(crate) fn stop_due(&self) -> bool {
        self.peaks.peak[self.peaks.peak.len() - 1] > self.stop_above_n
    }

    /// The contacts tracked over every step; None = all.
    pub(crate) fn watched(&self) -> Option<&[usize]> {
        self.watched.as_deref()
    }

    /// Peaks over the step [t0, t1] that ended at `y1`; the force cache of `ode` must be at `y1`
    /// (for [`PeakWatch::FiguresOfMerit`], only at the watched contacts, with the velocities of
    /// their primaries).
    pub(crate) fn after_step(&mut self, ode: &ChainOde, t0: f64, t1: f64, y1: &[f64]) {
        let peaks = &mut self.peaks;
        if let Some(watched) = &self.watched {
            let v = &y1[ode.n_dof()..2 * ode.n_dof()];
            let forces = ode.contact_forces_n();
            for &c in watched {
                peaks.rate[c] = ode.contact_force_rate(t1, c, v);
                peaks.update_contact(c, t0, t1, forces[c]);
            }
            // A table's breakpoints matter only to the load's peak (contact 0), not tracked here.
            return;
        }
        ode.contact_force_rates(t1, y1, &mut peaks.rate);
        peaks.update(t0, t1, ode.contact_forces_n());
        if let Some((times, forces)) = self.load_table {
            while self.next_breakpoint < times.len() && times[self.next_breakpoint] <= t1 {
                let (tb, fb) = (times[self.next_breakpoint], forces[self.next_breakpoint]);
                if tb > t0 && fb > peaks.peak[0] {
                    peaks.peak[0] = fb;
                    peaks.time[0] = tb;
                }
                self.next_breakpoint += 1;
            }
        }
    }

    /// The next sample time if it is due by the end of a step at t1: (t_k, whether it is t1
    /// itself, so that the state of the step is the sample).
    pub(crate) fn sample_due(&self, t1: f64) -> Option<(f64, bool)> {
        let ts = (self.next_sample as f64 * self.sample_interval_s).min(self.duration_s);
        (self.next_sample < self.n_samples && ts <= t1 * (1.0 + 1e-12))
            .then(|| (ts, (ts - t1).abs() <= 1e-9 * self.sample_interval_s))
    }

    /// Hands the sample (ts, y) to `recorder` and updates the energy balance; `cached` as for
    /// [`observe`].
    pub(crate) fn record(
        &mut self,
        ode: &mut ChainOde,
        ts: f64,
        y: &[f64],
        cached: bool,
        recorder: &mut dyn Recorder,
    ) -> Result<()> {
        self.record_with(ode, ts, y, cached, None, recorder)
    }

    /// [`Watch::record`] with each primary's internal energy given (`internal`, the exact modal
    /// method's: its state holds only the primaries).
    pub(crate) fn record_with(
        &mut self,
        ode: &mut ChainOde,
        ts: f64,
        y: &[f64],
        cached: bool,
        internal: Option<&[f64]>,
        recorder: &mut dyn Recorder,
    ) -> Result<()> {
        let last = observe(ode, (ts, y), cached, internal, &mut self.obs, recorder);
        if !last.total.is_finite() {
            return Err(Error::NonFiniteState {
                time_s: ts,
                contact: 0,
            });
        }
        self.max_abs_error = self
            .max_abs_error
            .max((last.total + last.dissipated - self.initial_energy.total - last.work).abs());
        self.max_abs_work = self.max_abs_work.max(last.work.abs());
        self.last = last;
        self.next_sample += 1;
        Ok(())
    }

    /// The figures of merit at the end of the run; the force cache of `ode` must be at `y_end`.
    pub(crate) fn finish(
        self,
        ode: &ChainOde,
        y_end: &[f64],
        stats: IntegratorStats,
    ) -> RunSummary {
        let mut peaks = self.peaks;
        if let Some(watched) = &self.watched {
            for c in 0..peaks.peak.len() {
                if !watched.contains(&c) {
                    peaks.peak[c] = f64::NAN;
                    peaks.time[c] = f64::NAN;
                }
            }
        }
        let forces_end = ode.contact_forces_n();
        let restitution = ode.striker_state(y_end).map(|(_, vs)| {
            let v0 = ode.striker_velocity_m_s();
            let v1 = ode.top_element_velocity(y_end);
            Restitution {
                coefficient: -vs / v0,
                separated: forces_end[0] == 0.0 && vs < v1,
            }
        });
        let static_forces = ode.static_contact_forces_n();
        let preloaded = static_forces.iter().any(|&f| f != 0.0);
        let dynamic = |c: usize| peaks.peak[c] - static_forces[c];
        let n = ode.n_layers() - 1;
        let incident = dynamic(1.min(n));
        let transmitted = dynamic(n);
        let wave_arrived =
            incident > 0.0 && transmitted >= defaults::WAVE_ARRIVAL_FRACTION * incident;
        // E(0) for an impact, the largest |W| for a load from rest; under a static load both count.
        let scale = self.reference_energy.abs().max(self.max_abs_work);
        RunSummary {
            incident_peak_force_n: peaks.peak[1.min(n)],
            transmitted_peak_force_n: peaks.peak[n],
            contact_peak_forces_n: peaks.peak,
            contact_peak_times_s: peaks.time,
            transmission_ratio: (incident > 0.0 && wave_arrived).then(|| transmitted / incident),
            wave_arrived,
            static_contact_forces_n: if preloaded { static_forces } else { Vec::new() },
            actuator_rest_m: ode.actuator_rest_m(),
            restitution,
            energy: EnergyBalance {
                initial_j: self.initial_energy.total,
                final_j: self.last.total,
                input_work_j: self.last.work,
                dissipated_j: self.last.dissipated,
                max_relative_error: if scale > 0.0 {
                    self.max_abs_error / scale
                } else {
                    0.0
                },
            },
            stats,
            n_samples: self.next_sample,
            wall_time_s: self.started.elapsed_s(),
            stopped_at_s: None,
        }
    }
}

/// Runs `chain` under `excitation` and hands every sample to `recorder`.
///
/// Errors: invalid settings or excitation ([`Error::InvalidParameter`]), a blow-up
/// ([`Error::NonFiniteState`], [`Error::RunawayOverlap`]) or, for the adaptive method,
/// [`Error::StepSizeTooSmall`].
pub fn simulate(
    chain: &Chain,
    excitation: &Excitation,
    settings: &RunSettings,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary> {
    simulate_watching(
        chain,
        excitation,
        settings,
        recorder,
        PeakWatch::Every,
        f64::INFINITY,
    )
}

/// [`simulate`], tracking the contact peaks that `peak_watch` names, and stopped at the end of
/// the first step whose transmitted peak exceeds `stop_above_n` (infinite: never).
pub(crate) fn simulate_watching(
    chain: &Chain,
    excitation: &Excitation,
    settings: &RunSettings,
    recorder: &mut dyn Recorder,
    peak_watch: PeakWatch,
    stop_above_n: f64,
) -> Result<RunSummary> {
    settings.check_run_of(excitation)?;
    let started = crate::clock::Stopwatch::start();
    let mut ode = ChainOde::new(chain, excitation)?;
    check_method_fits(&ode, settings.method)?;
    let method = resolve_method(&ode, settings.method);
    if let Method::ExactModes { .. } = method {
        match modal::stepper(&ode, method, settings) {
            Ok(stepper) => {
                let watching = (peak_watch, stop_above_n, started);
                return modal::simulate_modal(
                    ode, stepper, excitation, settings, recorder, watching,
                );
            }
            // A stated peak tolerance falls back to the integrator it resolves to without the
            // exact method (DOPRI5 with events here) where a cell's damped modes cannot be
            // followed (overdamped, or two roots meeting).
            Err(_) if matches!(settings.method, Method::PeakTolerance { .. }) => {}
            Err(e) => return Err(e),
        }
    }
    let dim = ode.dimension();
    let (mut integrator, _) = start_integrator(&mut ode, settings);
    recorder.start(&Layout {
        n_elements: ode.n_elements(),
        has_striker: ode.has_striker(),
        n_samples: settings.n_samples(),
    });
    // The integrator's last evaluation was at t = 0: the force cache holds the initial forces.
    let mut watch = Watch::start(
        &mut ode,
        excitation,
        settings,
        integrator.y(),
        recorder,
        started,
        peak_watch,
    )
    .stop_above(stop_above_n);
    let mut y_sample = vec![0.0; dim];
    let t_end = settings.duration_s;
    let mut recent = RecentStates::new(dim);
    while integrator.t() < t_end * (1.0 - 1e-14) {
        integrator.step(&mut ode, t_end)?;
        let (t0, t1) = (integrator.t_prev(), integrator.t());
        if let Err(coarse) = ode.check_contacts(t1) {
            recent.push(t0, integrator.y_prev());
            let culprit = ode.stiffest_contact().map(|c| c.0);
            return Err(diagnose_blow_up(
                chain, excitation, &recent, t1, culprit, coarse,
            ));
        }
        if integrator.stats().steps > defaults::MAX_STEPS {
            return Err(too_many_steps(t1, settings));
        }
        if crate::interrupt::requested() {
            return Err(Error::Interrupted { time_s: t1 });
        }
        watch.after_step(&ode, t0, t1, integrator.y());
        while let Some((ts, at_step)) = watch.sample_due(t1) {
            let y = if at_step {
                integrator.y()
            } else {
                integrator.interpolate(ts, &mut y_sample);
                &y_sample
            };
            watch.record(&mut ode, ts, y, at_step, recorder)?;
        }
        if watch.stop_due() && t1 < t_end * (1.0 - 1e-14) {
            let mut summary = watch.finish(&ode, integrator.y(), integrator.stats());
            summary.stopped_at_s = Some(t1);
            return Ok(summary);
        }
        // Dense output is done with this step: keep its start state without a copy.
        recent.keep(t0, &mut integrator);
    }
    Ok(watch.finish(&ode, integrator.y(), integrator.stats()))
}

/// The method a run of `ode` steps with: `method` resolved for its system and its stiffest
/// internal frequency ([`Method::resolve_for_modes`]).
pub(crate) fn resolve_method(ode: &ChainOde, method: Method) -> Method {
    let stiffest = ode.stiffest_resonator().map_or(0.0, |s| s.2);
    let exact = match (ode.fits_exact_modes(), ode.second_order().is_some()) {
        (false, _) => crate::integrate::ExactModesFit::No,
        (true, true) => crate::integrate::ExactModesFit::Impact,
        (true, false) => crate::integrate::ExactModesFit::Loaded,
    };
    method.resolve_for_modes(ode.second_order().is_some(), exact, stiffest)
}

/// The error of a run that took more than [`defaults::MAX_STEPS`] steps, ending at t1.
pub(crate) fn too_many_steps(t1: f64, settings: &RunSettings) -> Error {
    Error::TooManySteps {
        steps: defaults::MAX_STEPS,
        time_s: t1,
        duration_s: settings.duration_s,
    }
}

/// Finds the contact that blew up and why, from the start states of the last few steps
/// (`recent`) up to the failed end time `t1`:
/// - the load is beyond a contact's physical range when those steps re-integrated 256 times finer
///   also push its overlap past the limit and the energy in the system could compress it so far
///   ((2/5) β δ^{5/2} ≤ E): that contact is named;
/// - otherwise the step was too large, and the culprit is the contact that was stiffest at any
///   stage evaluation of the original steps (the one whose stability limit a step crossed; the
///   bodies it flings overrun their neighbours' limits a step or two later), falling back to
///   `culprit`, the stiffest contact of the failed state.
fn diagnose_blow_up(
    chain: &Chain,
    excitation: &Excitation,
    recent: &RecentStates,
    t1: f64,
    culprit: Option<usize>,
    coarse: Error,
) -> Error {
    let Ok(mut ode) = ChainOde::new(chain, excitation) else {
        return coarse;
    };
    let states = recent.oldest_first();
    let Some(&(t0, y0)) = states.first() else {
        return coarse;
    };
    let mut scratch = vec![0.0; y0.len()];
    ode.rhs(t0, y0, &mut scratch);
    let mut layers = vec![0.0; ode.n_layers()];
    let energy_j = layers_total(&ode, y0, &mut layers);
    let h = (t1 - t0) / (256.0 * states.len() as f64);
    let mut fine = Integrator::new(
        Method::Rk4 { time_step_s: h },
        &mut ode,
        t0,
        y0.to_vec(),
        &[],
        h,
    );
    let mut fine_failure = None;
    while fine.t() < t1 * (1.0 - 1e-14) {
        if fine.step(&mut ode, t1).is_err() {
            break;
        }
        if let Err(e) = ode.check_contacts(fine.t()) {
            fine_failure = Some(e);
            break;
        }
    }
    if let Some(Error::RunawayOverlap {
        time_s,
        contact,
        overlap_m,
        limit_m,
    }) = fine_failure
    {
        let beta = ode.contact_betas()[contact];
        let reachable_m = (2.5 * energy_j / beta).libm_powf(0.4);
        if energy_j.is_finite() && reachable_m >= limit_m {
            return Error::LoadBeyondContact {
                time_s,
                contact,
                overlap_m,
                limit_m,
                energy_j,
                reachable_m,
            };
        }
    }
    let time_s = match coarse {
        Error::RunawayOverlap { time_s, .. } | Error::NonFiniteState { time_s, .. } => time_s,
        _ => t1,
    };
    if let Some(e) = load_beyond_reach(chain, &ode, excitation, time_s) {
        return e;
    }
    let coarse_contact = match coarse {
        Error::RunawayOverlap { contact, .. } | Error::NonFiniteState { contact, .. } => contact,
        _ => 0,
    };
    let contact = stiffest_during_steps(chain, excitation, &states, t1)
        .or(culprit)
        .unwrap_or(coarse_contact);
    match coarse {
        Error::RunawayOverlap {
            time_s,
            overlap_m,
            limit_m,
            contact: c,
        } if c == contact => Error::RunawayOverlap {
            time_s,
            contact,
            overlap_m,
            limit_m,
        },
        Error::RunawayOverlap { time_s, .. } | Error::NonFiniteState { time_s, .. } => {
            Error::NonFiniteState { time_s, contact }
        }
        other => other,
    }
}

/// Whether the load asks more of a contact than its physical range, from statics and energy alone
/// (no integration, so no number from a failed state): the preload and gravity alone compress
/// contact i by (F_i/β_i)^{2/3} (F_i its static force); a blast's peak force, or a force drive's
/// amplitude, held statically on top of them compresses it by ((F + F_i)/β_i)^{2/3}; a striker's
/// kinetic energy of relative motion ½ μ v² (μ the reduced mass of striker and top primary) stored
/// in its contact compresses it by (5 E / 2β)^{2/5}.
fn load_beyond_reach(
    chain: &Chain,
    ode: &ChainOde,
    excitation: &Excitation,
    time_s: f64,
) -> Option<Error> {
    let (betas, limits) = (ode.contact_betas(), ode.overlap_limits_m());
    let words = |m: f64| {
        if m.is_finite() {
            format!("{m:.3e} m")
        } else {
            "more than any finite overlap".to_string()
        }
    };
    let exceeds = |need: f64, limit: f64| need.is_nan() || need > limit;
    let statics = chain.static_contact_forces_n();
    // A force held on element 1 (on top of the statics): the first contact it takes too far.
    let held = |force_n: f64, load: &dyn Fn() -> String| {
        (1..betas.len()).find_map(|c| {
            let need = ((force_n + statics[c - 1]) / betas[c]).libm_powf(2.0 / 3.0);
            exceeds(need, limits[c]).then(|| Error::LoadExceedsContact {
                time_s,
                contact: c,
                load: load(),
                needed: words(need),
                limit_m: limits[c],
            })
        })
    };
    let preload = chain.preload();
    if !preload.is_none() {
        let statics_words = || {
            format!(
                "the static load (preload.force_n = {:.3e} N, gravity_m_s2 = {:.3e} m/s²)",
                preload.force_n, preload.gravity_m_s2
            )
        };
        if let Some(e) = held(0.0, &statics_words) {
            return Some(e);
        }
    }
    match excitation {
        Excitation::Impact(striker) => {
            let m_s = ode.striker_mass_kg()?;
            let m_1 = chain.elements().first()?.cell.primary_mass_kg;
            let (mu, v) = (m_s * m_1 / (m_s + m_1), striker.velocity_m_s);
            let energy_j = 0.5 * mu * v * v;
            let need = (2.5 * energy_j / betas[0]).libm_powf(0.4);
            let energy = if energy_j.is_finite() {
                format!("{energy_j:.3e} J")
            } else {
                "more energy than a number holds".to_string()
            };
            exceeds(need, limits[0]).then(|| Error::LoadExceedsContact {
                time_s,
                contact: 0,
                load: format!("the striker at {v:.3e} m/s (excitation.velocity_m_s, or drop_height_m), with {energy} of relative motion,"),
                needed: words(need),
                limit_m: limits[0],
            })
        }
        Excitation::Blast(blast) => {
            let peak_n = blast.peak_force_n();
            held(peak_n, &|| {
                format!("the blast's peak force {peak_n:.3e} N (excitation.peak_force_n, or the table's largest force), held statically,")
            })
        }
        Excitation::Drive(drive) if drive.quantity == crate::excitation::DriveQuantity::Force => {
            let peak_n = drive.signal.largest_abs();
            held(peak_n, &|| {
                format!("the drive's largest force {peak_n:.3e} N (excitation.amplitude, or the table's largest value), held statically,")
            })
        }
        _ => None,
    }
}

/// Re-takes the last steps, each from its saved start state, as RK4 steps and returns the contact
/// that was the stiffest at any stage evaluation: the one whose stability limit a step crossed
/// (its own force may stay moderate while the bodies it flings overrun their neighbours, which is
/// where the overlap check then fails, a step or two later).
fn stiffest_during_steps(
    chain: &Chain,
    excitation: &Excitation,
    states: &[(f64, &[f64])],
    t1: f64,
) -> Option<usize> {
    /// Watches every evaluation of the system for its stiffest contact.
    struct Watch {
        ode: ChainOde,
        stiffest: Option<(usize, f64)>,
    }
    impl OdeSystem for Watch {
        fn dimension(&self) -> usize {
            self.ode.dimension()
        }
        fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
            self.ode.rhs(t, y, dydt);
            if let Some((c, w2)) = self.ode.stiffest_contact() {
                if self.stiffest.is_none_or(|(_, best)| w2 > best) {
                    self.stiffest = Some((c, w2));
                }
            }
        }
    }
    let mut watch = Watch {
        ode: ChainOde::new(chain, excitation).ok()?,
        stiffest: None,
    };
    for (k, &(t0, y0)) in states.iter().enumerate() {
        let t_next = states.get(k + 1).map_or(t1, |s| s.0);
        let h = t_next - t0;
        let mut step = Integrator::new(
            Method::Rk4 { time_step_s: h },
            &mut watch,
            t0,
            y0.to_vec(),
            &[],
            h,
        );
        let _ = step.step(&mut watch, t_next);
    }
    watch.stiffest.map(|(c, _)| c)
}

/// The start states of the last few steps (a ring allocated once, whose buffers are exchanged
/// with the integrator's: no copy per step), so that a blow-up can be traced back to the step
/// where it began.
struct RecentStates {
    times: Vec<f64>,
    states: Vec<Vec<f64>>,
    next: usize,
    len: usize,
}

impl RecentStates {
    /// Steps kept: a stiff contact flings its neighbours in one step; they overrun the next
    /// contacts' limits within a step or two.
    const DEPTH: usize = 4;

    fn new(dim: usize) -> Self {
        RecentStates {
            times: vec![0.0; Self::DEPTH],
            states: vec![vec![0.0; dim]; Self::DEPTH],
            next: 0,
            len: 0,
        }
    }

    /// Keeps a copy of the start state y of a step at t.
    fn push(&mut self, t: f64, y: &[f64]) {
        self.states[self.next].copy_from_slice(y);
        self.advance(t);
    }

    /// Keeps the integrator's start state of its last step (at t) by exchanging buffers with it
    /// (no copy); see [`Integrator::exchange_y_prev`].
    fn keep(&mut self, t: f64, integrator: &mut Integrator) {
        integrator.exchange_y_prev(&mut self.states[self.next]);
        self.advance(t);
    }

    fn advance(&mut self, t: f64) {
        self.times[self.next] = t;
        self.next = (self.next + 1) % Self::DEPTH;
        self.len = (self.len + 1).min(Self::DEPTH);
    }

    fn oldest_first(&self) -> Vec<(f64, &[f64])> {
        (0..self.len)
            .map(|k| (self.next + Self::DEPTH - self.len + k) % Self::DEPTH)
            .map(|i| (self.times[i], self.states[i].as_slice()))
            .collect()
    }
}

/// Total energy of the state `y` (all layers and the wall's share) \[J\]; the force cache of
/// `ode` must be at `y`.
fn layers_total(ode: &ChainOde, y: &[f64], layers: &mut [f64]) -> f64 {
    let wall = ode.layer_energies_j(y, layers);
    layers.iter().sum::<f64>() + wall
}

#[derive(Debug, Clone, Copy)]
pub(crate) struct Energies {
    total: f64,
    work: f64,
    dissipated: f64,
}

/// Computes the observables at (t, y) and hands them to the recorder. `cached` says the ODE's
/// force cache is already at y (the state of the last step); otherwise it is evaluated here
/// (an observation, not counted in the integrator's statistics). `internal`: each primary's
/// internal energy, when y holds only the primaries ([`Watch::record_with`]).
fn observe(
    ode: &mut ChainOde,
    (t, y): (f64, &[f64]),
    cached: bool,
    internal: Option<&[f64]>,
    obs: &mut Observer,
    recorder: &mut dyn Recorder,
) -> Energies {
    if !cached {
        ode.rhs(t, y, &mut obs.scratch);
    }
    let wall = match internal {
        None => ode.layer_energies_j(y, &mut obs.energies),
        Some(internal) => ode.layer_energies_with_internal_j(y, internal, &mut obs.energies),
    };
    let work = ode.input_work_j(y);
    let dissipated = ode.dissipated_j(y);
    let sample = Sample {
        time_s: t,
        contact_forces_n: ode.contact_forces_n(),
        layer_energies_j: &obs.energies,
        wall_energy_j: wall,
        input_work_j: work,
        dissipated_j: dissipated,
        displacements_m: ode.element_displacements(y),
        velocities_m_s: ode.element_velocities(y),
        striker: ode.striker_state(y),
    };
    recorder.record(&sample);
    Energies {
        total: sample.total_energy_j(),
        work,
        dissipated,
    }
}

/// Refuses a method that cannot run this system: a Runge–Kutta–Nyström method where the
/// acceleration depends on the velocity, and a fixed step beyond RK4's stability limit on the
/// stiffest resonator (resonators are linear, so such a run would blow up for certain,
/// docs/physics.md §12; cells with many stiff modes, the finite-element rod of §13, need a
/// smaller step than the paper's).
pub(crate) fn check_method_fits(ode: &ChainOde, method: Method) -> Result<()> {
    if method.needs_second_order() && ode.second_order().is_none() {
        return Err(Error::invalid(
            "run.method",
            "rkn64",
            "advances only x'' = a(x): an impact without damping, static load or drive; use \
             dopri5, or run.peak_tolerance (which chooses the method for the run)",
        ));
    }
    let Method::Rk4 { time_step_s } = method else {
        return Ok(());
    };
    match ode.stiffest_resonator() {
        Some((element, resonator, omega))
            if time_step_s * omega > crate::integrate::RK4_STABILITY_LIMIT =>
        {
            Err(Error::invalid(
                "run.time_step_s",
                time_step_s,
                format!(
                    "RK4 is unstable on resonator {resonator} of element {element} (ω = sqrt(k (1/m + 1/M)) = {omega:.3e} rad/s, Δt ω = {:.2} > 2√2): use run.time_step_s < {:.3e} s, or integrator = \"dopri5\", or check that resonator's stiffness and mass",
                    time_step_s * omega,
                    crate::integrate::RK4_STABILITY_LIMIT / omega
                ),
            ))
        }
        _ => Ok(()),
    }
}

/// The integrator of a run at its start: the chain's initial state, the run's method with the
/// chain's tolerance units (also returned: the lanes scale their own atol by them).
pub(crate) fn start_integrator(
    ode: &mut ChainOde,
    settings: &RunSettings,
) -> (Integrator, Vec<f64>) {
    let y0 = ode.initial_state();
    let units = ode.tolerance_units();
    let integrator = Integrator::new(
        settings.method,
        ode,
        0.0,
        y0,
        &units,
        settings.sample_interval_s,
    );
    (integrator, units)
}
