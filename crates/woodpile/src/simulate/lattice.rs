//! The runner of a lattice (docs/physics.md §16): steps a [`LatticeOde`] with the chain's
//! integrators, checks every contact after every step, tracks each contact's peak, samples the
//! contact forces and the energy on the uniform grid, and audits the energy (with lab physics:
//! E(t) + D(t) − E(0) − W(t) = 0).

use super::{EnergyBalance, PeakTracker, RunSettings};
use crate::error::{Error, Result};
use crate::integrate::modal_graph::GraphModalIntegrator;
use crate::integrate::{Integrator, IntegratorStats, Method, OdeSystem};
use crate::ode::LatticeOde;

/// What a lattice run gives: per-contact peaks, the supports' sum, the energy balance, and the
/// samples.
#[derive(Debug, Clone, PartialEq)]
pub struct LatticeRun {
    /// Peak force per contact over every step \[N\] (striker first, then crossings, supports).
    pub contact_peak_forces_n: Vec<f64>,
    /// When each peak occurred \[s\].
    pub contact_peak_times_s: Vec<f64>,
    /// Peak over the steps of the incident force: the striker's contact force, or the sum of
    /// the load points' forces \[N\].
    pub incident_peak_force_n: f64,
    /// Peak over the steps of the transmitted force, the sum of the support forces \[N\].
    pub transmitted_peak_force_n: f64,
    /// Whether the wave reached the supports: the transmitted peak's dynamic part (less the
    /// supports' static forces) is at least [`crate::defaults::WAVE_ARRIVAL_FRACTION`] of the
    /// incident one's (as a chain's `RunSummary::wave_arrived`). False: the run was too short
    /// for the transmitted force to mean anything, or nothing struck or loaded the lattice.
    pub wave_arrived: bool,
    /// The static parts of the incident and transmitted forces \[N\] (the load points' and the
    /// supports' sums of [`LatticeRun::contact_static_forces_n`]; 0 without a static load):
    /// the peaks less these are the dynamic parts the ratio and the wave's arrival compare.
    pub static_incident_force_n: f64,
    /// See [`LatticeRun::static_incident_force_n`].
    pub static_transmitted_force_n: f64,
    /// Transmitted / incident of the dynamic parts, as a chain's
    /// (`RunSummary::transmission_ratio`); None when the incident force is zero or the wave
    /// never reached the supports.
    pub transmission_ratio: Option<f64>,
    /// Wall-clock time of the run \[s\].
    pub wall_time_s: f64,
    /// Energy balance over the samples (lossless: E(t) = E(0); with lab physics
    /// E(t) + D(t) − E(0) − W(t) = 0).
    pub energy: EnergyBalance,
    /// Sample times \[s\].
    pub times_s: Vec<f64>,
    /// Contact forces, sample by sample (`contacts` per sample) \[N\].
    pub contact_forces_n: Vec<f64>,
    /// Total energy per sample \[J\].
    pub energy_j: Vec<f64>,
    /// Work of the external forces W per sample \[J\] (empty without lab physics).
    pub work_j: Vec<f64>,
    /// Energy dissipated D per sample \[J\] (empty without lab physics).
    pub dissipated_j: Vec<f64>,
    /// Energy dissipated at each contact over the run \[J\], in output order (empty without lab
    /// physics; the rest of D is the rods' modal damping, [`LatticeRun::modal_dissipated_j`]).
    pub contact_dissipated_j: Vec<f64>,
    /// Each contact's Hertz potential, sample by sample (`contacts` per sample, output order;
    /// 0 at a load point of a prescribed force) \[J\] ([`LatticeOde::contact_energies_j`]).
    pub contact_energies_j: Vec<f64>,
    /// Energy dissipated at each contact from the start to each sample (`contacts` per sample,
    /// output order; empty without lab physics) \[J\]: its last row is
    /// [`LatticeRun::contact_dissipated_j`] at the last sample.
    pub contact_dissipated_samples_j: Vec<f64>,
    /// Energy dissipated by the damping of the rods' modes over the run \[J\].
    pub modal_dissipated_j: f64,
    /// Each contact's force in the static equilibrium the run started from \[N\] (empty
    /// without lab physics).
    pub contact_static_forces_n: Vec<f64>,
    /// The static solve's relative residual |∇Π| / |f| (0 without a static load).
    pub static_residual: f64,
    /// Momentum audit per sample: (P, H, J, J's moment), see [`LatticeOde::momentum_audit`].
    pub momentum: Vec<(f64, [f64; 2], f64, [f64; 2])>,
    /// Number of contacts per sample.
    pub contacts: usize,
    /// Indices of the support contacts.
    pub supports: Vec<usize>,
    /// Each body's energy, sample by sample (`bodies` per sample: the striker or a
    /// displacement actuator first, if any, then the rods; [`LatticeOde::body_energies_j`])
    /// \[J\].
    pub body_energies_j: Vec<f64>,
    /// The supports' halves of their contacts' potential, per sample \[J\].
    pub support_energy_j: Vec<f64>,
    /// Number of bodies per sample ([`LatticeOde::energy_bodies`]).
    pub bodies: usize,
    /// Integrator counters.
    pub stats: IntegratorStats,
    /// The method the run took ([`lattice_method`]).
    pub method: Method,
    /// A displacement actuator's static position u* \[m\] (downward; None without one): every
    /// tip's overlap is δ_i = u* + u(t) − w_i ([`LatticeOde::actuator_rest_m`]).
    pub actuator_rest_m: Option<f64>,
}

impl LatticeRun {
    /// Contact c's force at every sample \[N\].
    pub fn contact_force_n(&self, c: usize) -> Vec<f64> {
        self.contact_forces_n
            .chunks(self.contacts)
            .map(|row| row[c])
            .collect()
    }

    /// The transmitted force (sum of the supports) at every sample \[N\].
    pub fn transmitted_force_n(&self) -> Vec<f64> {
        self.contact_forces_n
            .chunks(self.contacts)
            .map(|row| self.supports.iter().map(|&s| row[s]).sum())
            .collect()
    }
}

/// What steps a lattice: the chain's integrators, or the exact modal stepper.
enum Stepper {
    Explicit(Box<Integrator>),
    ExactModes(Box<GraphModalIntegrator>),
}

impl Stepper {
    fn new(ode: &mut LatticeOde, method: Method, settings: &RunSettings) -> Self {
        match method {
            Method::ExactModes { rtol, atol } => Stepper::ExactModes(Box::new(
                GraphModalIntegrator::new(ode, rtol, atol, settings.duration_s),
            )),
            _ => {
                let (y0, units) = (ode.initial_state(), ode.tolerance_units());
                Stepper::Explicit(Box::new(Integrator::new(
                    method,
                    ode,
                    0.0,
                    y0,
                    &units,
                    settings.duration_s,
                )))
            }
        }
    }

    fn step(&mut self, ode: &mut LatticeOde, t_end: f64) -> Result<f64> {
        match self {
            Stepper::Explicit(i) => i.step(ode, t_end),
            Stepper::ExactModes(m) => m.step(t_end),
        }
    }

    fn t(&self) -> f64 {
        match self {
            Stepper::Explicit(i) => i.t(),
            Stepper::ExactModes(m) => m.t(),
        }
    }

    fn y(&mut self) -> &[f64] {
        match self {
            Stepper::Explicit(i) => i.y(),
            Stepper::ExactModes(m) => m.y(),
        }
    }

    fn interpolate(&mut self, ts: f64, out: &mut [f64]) {
        match self {
            Stepper::Explicit(i) => i.interpolate(ts, out),
            Stepper::ExactModes(m) => m.observe_at(ts, out),
        }
    }

    /// Every contact's overlap and force at the last step's end into `ode`'s `overlap_m` and
    /// `force_n`, its force rate into `rate` (as [`LatticeOde::contact_forces_and_rates_at`]).
    fn contact_forces_and_rates(&mut self, ode: &mut LatticeOde, elastic: bool, rate: &mut [f64]) {
        match self {
            Stepper::Explicit(i) => ode.contact_forces_and_rates_at(i.t(), i.y(), elastic, rate),
            // (Every contact of a run the exact method takes is elastic.)
            Stepper::ExactModes(m) => m.contact_forces_and_rates(ode, rate),
        }
    }

    /// Every contact's overlap and force at the sample `y` just interpolated at ts into `ode`.
    fn sample_contact_forces(&self, ode: &mut LatticeOde, ts: f64, y: &[f64]) {
        match self {
            Stepper::Explicit(_) => ode.contact_forces_at(ts, y),
            Stepper::ExactModes(m) => m.sample_contact_forces(ode, ts),
        }
    }

    /// Whether the state now is finite.
    fn state_finite(&self) -> bool {
        match self {
            Stepper::Explicit(i) => all_finite(i.y()),
            Stepper::ExactModes(m) => m.state_finite(),
        }
    }

    fn stats(&self) -> IntegratorStats {
        match self {
            Stepper::Explicit(i) => i.stats(),
            Stepper::ExactModes(m) => m.stats(),
        }
    }
}

/// The exact modal method's rtol on a lattice, as a fraction of a stated peak tolerance. On the
/// chains the rule is tolerance / (3 · 1.3) (docs/physics.md §8); on lattices the error of small
/// peaks deep in the lattice (1–4 % of the largest) does not fall as rtol: on the 10-layer ×
/// 5-rod lattice of 16-element rods it was 29 and 369 rtol at rtol 2.6e-6 and 1e-8
/// (examples/lattice_exact.rs). 1e-3 keeps that lattice's worst peak 2.7 times inside the
/// tolerance.
pub const LATTICE_EXACT_MODES_RTOL_OF_TOLERANCE: f64 = 1e-3;

/// The method a lattice runs: a stated peak tolerance becomes [`Method::ExactModes`] at rtol =
/// tolerance · [`LATTICE_EXACT_MODES_RTOL_OF_TOLERANCE`] for rods whose stiffest mode is above
/// [`crate::integrate::EXACT_MODES_ABOVE_RAD_S`] (finite-element rods: RKN 6(4)'s or DOPRI5's
/// step would be set by that mode's stability) under an impact, a blast or a force drive, lossless
/// or with the rods' modes damped, gravity and a preload (every contact elastic:
/// [`LatticeOde::fits_exact_modes`]); otherwise as [`Method::resolve`] (RKN 6(4), or DOPRI5
/// with events under lab physics).
pub fn lattice_method(ode: &LatticeOde, method: Method) -> Method {
    match method {
        Method::PeakTolerance { peak_tolerance }
            if ode.fits_exact_modes()
                && ode.stiffest_mode_rad_s() > crate::integrate::EXACT_MODES_ABOVE_RAD_S =>
        {
            let rtol = (peak_tolerance * LATTICE_EXACT_MODES_RTOL_OF_TOLERANCE).max(1e-13);
            Method::ExactModes {
                rtol,
                atol: rtol * 1e-6,
            }
        }
        _ => method.resolve(ode.second_order().is_some()),
    }
}

/// Runs a lattice: `settings.method` may be RK4, DOPRI5 (with or without events), RKN 6(4), the
/// exact modal method ([`LatticeOde::fits_exact_modes`]), or a peak tolerance
/// ([`lattice_method`] chooses).
pub fn simulate_lattice(ode: &mut LatticeOde, settings: &RunSettings) -> Result<LatticeRun> {
    let started = crate::clock::Stopwatch::start();
    settings.validate()?;
    if matches!(settings.method, Method::ExactModes { .. }) && !ode.fits_exact_modes() {
        return Err(Error::invalid(
            "run.integrator",
            "exact-modes",
            "the exact modal method advances an impact, a blast or a force drive of a lattice \
             with elastic contacts, each mode damped on its own if at all (no resonator \
             dashpots), under gravity and a preload; state run.peak_tolerance instead",
        ));
    }
    if settings.method.needs_second_order() && ode.second_order().is_none() {
        return Err(Error::invalid(
            "run.integrator",
            "rkn64",
            "RKN 6(4) advances only x'' = a(x): a lossless, unloaded impact; with damping, a \
             load or a preload use dopri5, or state run.peak_tolerance",
        ));
    }
    let method = lattice_method(ode, settings.method);
    let mut stepper = Stepper::new(ode, method, settings);
    // With lab physics whose contacts are all elastic (what the exact modal method runs), the
    // peaks are refined from the contact forces' rates as a lossless run's are, whatever the
    // method.
    let elastic_rates = ode.has_lab() && ode.fits_exact_modes();
    let y0 = ode.initial_state();
    let nc = ode.contacts();
    let q = ode.coordinates();
    let mut run = LatticeRun::empty(ode, method);
    let mut sample = y0.clone();
    ode.contact_forces_at(0.0, &sample);
    record(ode, &mut run, 0.0, &sample);
    // (After the forces at t = 0: an actuator's tip overlaps depend on the time.)
    let e0 = run.energy_j[0];
    // Every contact's peak, then the incident force's (the striker's, or the load points' sum)
    // and the transmitted force's (the supports' sum) as two more; the forces at t = 0 (a
    // blast's F0, the static forces under a static load) count.
    let mut peaks = PeakTracker::new(nc + 2);
    let mut forces = vec![0.0; nc + 2];
    ode.contact_forces_and_rates_at(0.0, &y0, elastic_rates, &mut peaks.rate[..nc]);
    watch_sums(ode, &run.supports, &mut forces, &mut peaks.rate);
    peaks.start(&forces);
    let interval = settings.sample_interval_s;
    let mut next = 1usize;
    while stepper.t() < settings.duration_s {
        if crate::interrupt::requested() {
            return Err(Error::Interrupted {
                time_s: stepper.t(),
            });
        }
        let t0 = stepper.t();
        let h = stepper.step(ode, settings.duration_s)?;
        let t = stepper.t();
        stepper.contact_forces_and_rates(ode, elastic_rates, &mut peaks.rate[..nc]);
        watch_sums(ode, &run.supports, &mut forces, &mut peaks.rate);
        check(ode, t, stepper.state_finite())?;
        peaks.update(t0, t, &forces);
        while let Some(ts) = sample_time(next, interval, settings.duration_s) {
            if ts > t + 1e-9 * h {
                break;
            }
            stepper.interpolate(ts, &mut sample);
            stepper.sample_contact_forces(ode, ts, &sample);
            record(ode, &mut run, ts, &sample);
            next += 1;
        }
    }
    run.contact_peak_forces_n.copy_from_slice(&peaks.peak[..nc]);
    run.contact_peak_times_s.copy_from_slice(&peaks.time[..nc]);
    run.incident_peak_force_n = peaks.peak[nc];
    run.transmitted_peak_force_n = peaks.peak[nc + 1];
    arrival(&mut run, ode);
    run.energy = energy_balance(&run, e0);
    if ode.has_lab() {
        let y = stepper.y();
        run.contact_dissipated_j = ode.contact_dissipated_j(y).to_vec();
        run.modal_dissipated_j = y[2 * (q + 3) + 1];
    }
    run.stats = stepper.stats();
    run.wall_time_s = started.elapsed_s();
    Ok(run)
}

impl LatticeRun {
    /// A run of `ode` by `method` before its first sample: no samples, no peaks.
    fn empty(ode: &LatticeOde, method: Method) -> LatticeRun {
        let nc = ode.contacts();
        let supports: Vec<usize> = (0..nc).filter(|&c| ode.is_support(c)).collect();
        LatticeRun {
            contact_peak_forces_n: vec![0.0; nc],
            contact_peak_times_s: vec![0.0; nc],
            incident_peak_force_n: 0.0,
            transmitted_peak_force_n: 0.0,
            wave_arrived: false,
            static_incident_force_n: 0.0,
            static_transmitted_force_n: 0.0,
            transmission_ratio: None,
            wall_time_s: 0.0,
            energy: EnergyBalance {
                initial_j: 0.0,
                final_j: 0.0,
                input_work_j: 0.0,
                dissipated_j: 0.0,
                max_relative_error: 0.0,
            },
            times_s: Vec::new(),
            contact_forces_n: Vec::new(),
            energy_j: Vec::new(),
            work_j: Vec::new(),
            dissipated_j: Vec::new(),
            contact_dissipated_j: Vec::new(),
            contact_energies_j: Vec::new(),
            contact_dissipated_samples_j: Vec::new(),
            modal_dissipated_j: 0.0,
            contact_static_forces_n: ode.static_forces_n().0.to_vec(),
            static_residual: ode.static_forces_n().1,
            momentum: Vec::new(),
            contacts: nc,
            supports,
            body_energies_j: Vec::new(),
            support_energy_j: Vec::new(),
            bodies: ode.energy_bodies(),
            stats: IntegratorStats::default(),
            method,
            actuator_rest_m: ode.actuator_rest_m(),
        }
    }
}

/// The energy balance over the samples: the largest |E(t) + D(t) − E(0) − W(t)| relative to
/// the larger of E(0) and the largest |W| (E(0) for a lossless impact).
fn energy_balance(run: &LatticeRun, e0: f64) -> EnergyBalance {
    let n = run.energy_j.len();
    let work = |k: usize| run.work_j.get(k).copied().unwrap_or(0.0);
    let dissipated = |k: usize| run.dissipated_j.get(k).copied().unwrap_or(0.0);
    let reference = (0..n).map(|k| work(k).abs()).fold(e0, f64::max);
    EnergyBalance {
        initial_j: e0,
        final_j: run.energy_j[n - 1],
        input_work_j: work(n - 1),
        dissipated_j: dissipated(n - 1),
        max_relative_error: (0..n)
            .map(|k| (run.energy_j[k] + dissipated(k) - e0 - work(k)).abs() / reference)
            .fold(0.0, f64::max),
    }
}

/// Every contact's force (from `ode`) into `forces`, then the incident force (the striker's, or
/// the load points' sum) and the transmitted force (the supports' sum) and their rates (from
/// the contacts' `rates`) into both.
fn watch_sums(ode: &LatticeOde, supports: &[usize], forces: &mut [f64], rates: &mut [f64]) {
    let nc = ode.contacts();
    forces[..nc].copy_from_slice(&ode.graph.force_n);
    let incident = ode.incident_contacts();
    forces[nc] = forces[incident.clone()].iter().sum();
    rates[nc] = rates[incident].iter().sum();
    forces[nc + 1] = supports.iter().map(|&s| forces[s]).sum();
    rates[nc + 1] = supports.iter().map(|&s| rates[s]).sum();
}

/// The wave's arrival and the transmission ratio, of the dynamic parts (the peaks less the
/// static forces), as a chain's: the transmitted part at least
/// [`crate::defaults::WAVE_ARRIVAL_FRACTION`] of the incident one's.
fn arrival(run: &mut LatticeRun, ode: &LatticeOde) {
    let statics = &run.contact_static_forces_n;
    let at_rest = |contacts: &mut dyn Iterator<Item = usize>| -> f64 {
        contacts
            .map(|c| statics.get(c).copied().unwrap_or(0.0))
            .sum()
    };
    run.static_incident_force_n = at_rest(&mut ode.incident_contacts());
    run.static_transmitted_force_n = at_rest(&mut run.supports.iter().copied());
    let incident = run.incident_peak_force_n - run.static_incident_force_n;
    let transmitted = run.transmitted_peak_force_n - run.static_transmitted_force_n;
    run.wave_arrived =
        incident > 0.0 && transmitted >= crate::defaults::WAVE_ARRIVAL_FRACTION * incident;
    run.transmission_ratio = run.wave_arrived.then(|| transmitted / incident);
}

/// Sample k's time, if within the run.
fn sample_time(k: usize, interval: f64, duration: f64) -> Option<f64> {
    let t = k as f64 * interval;
    (t <= duration * (1.0 + 1e-12)).then_some(t.min(duration))
}

/// Sample y at t into `run`, the contacts' forces and overlaps already in `ode`.
fn record(ode: &LatticeOde, run: &mut LatticeRun, t: f64, y: &[f64]) {
    run.times_s.push(t);
    run.contact_forces_n.extend_from_slice(&ode.graph.force_n);
    // Each contact's potential once, from the overlaps just evaluated: the total and the
    // bodies' shares read it.
    let start = run.contact_energies_j.len();
    run.contact_energies_j.resize(start + run.contacts, 0.0);
    let contact_energies = &mut run.contact_energies_j[start..];
    ode.contact_energies_j(contact_energies);
    let start = run.body_energies_j.len();
    run.body_energies_j.resize(start + run.bodies, 0.0);
    let bodies = &mut run.body_energies_j[start..];
    let supports = ode.body_energies_j(y, contact_energies, bodies);
    run.support_energy_j.push(supports);
    // ([`LatticeOde::energy_j`] in other words: the bodies' shares and the supports'.)
    run.energy_j.push(bodies.iter().sum::<f64>() + supports);
    if ode.has_lab() {
        let (w, d) = ode.work_and_dissipation_j(y);
        run.work_j.push(w);
        run.dissipated_j.push(d);
        run.contact_dissipated_samples_j
            .extend_from_slice(ode.contact_dissipated_j(y));
    }
    run.momentum.push(ode.momentum_audit(y));
}

/// A non-finite state (`finite` false) or an overlap beyond the Hertz law's range ends the run
/// with the contact named (its index in output order).
fn check(ode: &LatticeOde, t: f64, finite: bool) -> Result<()> {
    for (c, (&d, &limit)) in ode
        .graph
        .overlap_m
        .iter()
        .zip(&ode.overlap_limit_m)
        .enumerate()
    {
        if !d.is_finite() {
            return Err(Error::NonFiniteState {
                time_s: t,
                contact: c,
            });
        }
        if d > limit {
            return Err(Error::RunawayOverlap {
                time_s: t,
                contact: c,
                overlap_m: d,
                limit_m: limit,
            });
        }
    }
    if !finite {
        return Err(Error::NonFiniteState {
            time_s: t,
            contact: 0,
        });
    }
    Ok(())
}

/// Whether every value is finite: a whole block at a time, with no exit inside one, so that
/// the test runs in vectors (the state is checked after every step).
fn all_finite(values: &[f64]) -> bool {
    values
        .chunks(64)
        .all(|block| block.iter().fold(true, |all, v| all & v.is_finite()))
}
