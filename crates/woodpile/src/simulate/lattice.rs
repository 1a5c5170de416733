//! The runner of a lattice (docs/physics.md §16): steps a [`LatticeOde`] with the chain's
//! integrators, checks every contact after every step, tracks each contact's peak, samples the
//! contact forces and the energy on the uniform grid, and audits the energy (with lab physics:
//! E(t) + D(t) − E(0) − W(t) = 0).

use super::{EnergyBalance, RunSettings};
use crate::error::{Error, Result};
use crate::integrate::{Integrator, IntegratorStats, Method};
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
    /// Integrator counters.
    pub stats: IntegratorStats,
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

/// Runs a lattice: `settings.method` may be RK4, DOPRI5 (with or without events), RKN 6(4) or a
/// peak tolerance (RKN 6(4) at its rtol); the exact modal method is for chains.
pub fn simulate_lattice(ode: &mut LatticeOde, settings: &RunSettings) -> Result<LatticeRun> {
    settings.validate()?;
    if matches!(settings.method, Method::ExactModes { .. }) {
        return Err(Error::invalid(
            "run.integrator",
            "exact-modes",
            "lattices run with rk4, dopri5 or a peak tolerance (RKN 6(4))",
        ));
    }
    let y0 = ode.initial_state();
    let units = ode.tolerance_units();
    let mut integrator = Integrator::new(
        settings.method,
        ode,
        0.0,
        y0.clone(),
        &units,
        settings.duration_s,
    );
    let nc = ode.contacts();
    let q = ode.coordinates();
    let supports: Vec<usize> = (0..nc).filter(|&c| ode.is_support(c)).collect();
    let mut run = LatticeRun {
        contact_peak_forces_n: vec![0.0; nc],
        contact_peak_times_s: vec![0.0; nc],
        incident_peak_force_n: 0.0,
        transmitted_peak_force_n: 0.0,
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
        modal_dissipated_j: 0.0,
        contact_static_forces_n: ode.static_forces_n().0.to_vec(),
        static_residual: ode.static_forces_n().1,
        momentum: Vec::new(),
        contacts: nc,
        supports,
        stats: IntegratorStats::default(),
    };
    let e0 = ode.energy_j(&y0);
    let mut sample = y0;
    record(ode, &mut run, 0.0, &sample);
    // The forces at t = 0 (a blast's F0, the static forces under a static load) count.
    track_peaks(ode, &mut run, 0.0);
    let interval = settings.sample_interval_s;
    let mut next = 1usize;
    while integrator.t() < settings.duration_s {
        if crate::interrupt::requested() {
            return Err(Error::Interrupted {
                time_s: integrator.t(),
            });
        }
        let h = integrator.step(ode, settings.duration_s)?;
        let t = integrator.t();
        let y = integrator.y();
        ode.contact_forces_at(t, y);
        check(ode, t, y)?;
        track_peaks(ode, &mut run, t);
        while let Some(ts) = sample_time(next, interval, settings.duration_s) {
            if ts > t + 1e-9 * h {
                break;
            }
            integrator.interpolate(ts, &mut sample);
            record(ode, &mut run, ts, &sample);
            next += 1;
        }
    }
    run.energy = energy_balance(&run, e0);
    if ode.has_lab() {
        let y = integrator.y();
        run.contact_dissipated_j = ode.contact_dissipated_j(y).to_vec();
        run.modal_dissipated_j = y[2 * (q + 3) + 1];
    }
    run.stats = integrator.stats();
    Ok(run)
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

/// Each contact's peak, the incident and the transmitted peak, from the forces in `force_n`.
fn track_peaks(ode: &LatticeOde, run: &mut LatticeRun, t: f64) {
    for c in 0..run.contacts {
        if ode.force_n[c] > run.contact_peak_forces_n[c] {
            run.contact_peak_forces_n[c] = ode.force_n[c];
            run.contact_peak_times_s[c] = t;
        }
    }
    let incident: f64 = ode.force_n[ode.incident_contacts()].iter().sum();
    run.incident_peak_force_n = run.incident_peak_force_n.max(incident);
    let transmitted: f64 = run.supports.iter().map(|&s| ode.force_n[s]).sum();
    run.transmitted_peak_force_n = run.transmitted_peak_force_n.max(transmitted);
}

/// Sample k's time, if within the run.
fn sample_time(k: usize, interval: f64, duration: f64) -> Option<f64> {
    let t = k as f64 * interval;
    (t <= duration * (1.0 + 1e-12)).then_some(t.min(duration))
}

fn record(ode: &mut LatticeOde, run: &mut LatticeRun, t: f64, y: &[f64]) {
    ode.contact_forces_at(t, y);
    run.times_s.push(t);
    run.contact_forces_n.extend_from_slice(&ode.force_n);
    run.energy_j.push(ode.energy_j(y));
    if ode.has_lab() {
        let (w, d) = ode.work_and_dissipation_j(y);
        run.work_j.push(w);
        run.dissipated_j.push(d);
    }
    run.momentum.push(ode.momentum_audit(y));
}

/// A non-finite state or an overlap beyond the Hertz law's range ends the run with the contact
/// named (its index in output order).
fn check(ode: &LatticeOde, t: f64, y: &[f64]) -> Result<()> {
    for (c, (&d, &limit)) in ode.overlap_m.iter().zip(&ode.overlap_limit_m).enumerate() {
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
    if y.iter().any(|v| !v.is_finite()) {
        return Err(Error::NonFiniteState {
            time_s: t,
            contact: 0,
        });
    }
    Ok(())
}
