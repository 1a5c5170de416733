//! What is minimised: a figure of merit of one full run of a candidate chain.
//!
//! An objective's value is that of the whole window `settings.duration_s`: no cheap bound
//! proves that a later peak cannot exceed the current one. A design study may still stop a run
//! whose transmitted peak, a running maximum, already exceeds what could matter to it
//! ([`Objective::evaluate_many_stopping`]): its value is then only known to be larger.

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::lanes::{simulate_many_stopping, Job, LaneWidth};
use crate::model::Chain;
use crate::record::{Layout, Recorder, Sample};
use crate::simulate::{simulate, simulate_watching, PeakWatch, RunSettings, RunSummary};

/// A figure of merit to minimise. Implement it to optimise for your own quantity; it must be a
/// deterministic function of its arguments (the GA caches and compares values bit for bit).
pub trait Objective: Send + Sync {
    /// Short name for tables and file headers, e.g. `transmitted-force`.
    fn name(&self) -> &str;

    /// Unit of the value, e.g. `N`.
    fn unit(&self) -> &str;

    /// The value for one chain (smaller is better). Must not be NaN.
    fn evaluate(
        &self,
        chain: &Chain,
        excitation: &Excitation,
        settings: &RunSettings,
    ) -> Result<f64>;

    /// Values for many chains under one excitation, in order, on the threads of the current
    /// rayon pool. The default evaluates them one by one; the standard force objectives advance
    /// them together in SIMD lanes `lanes` wide ([`crate::lanes`]), with the same values bit
    /// for bit.
    fn evaluate_many(
        &self,
        chains: &[Chain],
        excitation: &Excitation,
        settings: &RunSettings,
        lanes: LaneWidth,
    ) -> Vec<Result<f64>> {
        let _ = lanes;
        one_by_one(self, chains, excitation, settings)
    }

    /// A bound on the relative error of the value when every contact peak is within
    /// `peak_tolerance` relative of its converged value, or None when the value is not a
    /// function of contact peaks. Screening ([`crate::optimize::GaSettings`]) needs it.
    fn relative_error(&self, peak_tolerance: f64) -> Option<f64> {
        let _ = peak_tolerance;
        None
    }

    /// Whether the value is the transmitted peak, a running maximum that the rest of a run can
    /// only raise, so that a run may stop once it exceeds a cutoff (`ga.stop_early`).
    fn is_transmitted_peak(&self) -> bool {
        false
    }

    /// [`Objective::evaluate_many`], each run of an objective with
    /// [`Objective::is_transmitted_peak`] stopped at the end of the first step whose transmitted
    /// peak exceeds `stop_above_n` \[N\]: its value is then [`Valued::AtLeast`] that peak. The
    /// default runs every design whole.
    fn evaluate_many_stopping(
        &self,
        chains: &[Chain],
        excitation: &Excitation,
        settings: &RunSettings,
        lanes: LaneWidth,
        stop_above_n: f64,
    ) -> Vec<Result<Valued>> {
        let _ = stop_above_n;
        whole_runs(self, chains, excitation, settings, lanes)
    }
}

/// [`Objective::evaluate_many`], every value exact.
fn whole_runs(
    objective: &(impl Objective + ?Sized),
    chains: &[Chain],
    excitation: &Excitation,
    settings: &RunSettings,
    lanes: LaneWidth,
) -> Vec<Result<Valued>> {
    objective
        .evaluate_many(chains, excitation, settings, lanes)
        .into_iter()
        .map(|r| r.map(Valued::Exact))
        .collect()
}

/// An objective value, or a lower bound of it from a run stopped early.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Valued {
    /// The value of the whole run.
    Exact(f64),
    /// The run stopped once its transmitted peak exceeded a cutoff: the whole run's value is at
    /// least this.
    AtLeast(f64),
}

impl Valued {
    /// The number: the value, or the lower bound.
    pub fn value_or_bound(self) -> f64 {
        match self {
            Valued::Exact(x) | Valued::AtLeast(x) => x,
        }
    }
}

/// [`Objective::evaluate`] of each chain, in order, in parallel on the current rayon pool.
fn one_by_one(
    objective: &(impl Objective + ?Sized),
    chains: &[Chain],
    excitation: &Excitation,
    settings: &RunSettings,
) -> Vec<Result<f64>> {
    chains
        .par_iter()
        .map(|c| objective.evaluate(c, excitation, settings))
        .collect()
}

/// The run-based objectives of a design study, each over the whole run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StandardObjective {
    /// Peak force of contact N (the wall) \[N\]: the paper's objective. Peaks are tracked over
    /// every integration step with Hermite refinement ([`crate::RunSummary`]).
    #[default]
    TransmittedForce,
    /// Transmitted / incident peak force (contact N over contact 1).
    TransmissionRatio,
    /// Peak energy of the last layer N \[J\] (docs/physics.md §7), the maximum over the sample grid.
    TransmittedEnergy,
    /// Impulse ∫ F_N dt delivered to the wall over the run \[N s\], by the trapezoid rule on the
    /// sample grid (the runner hands recorders samples, not steps).
    TransmittedImpulse,
}

impl StandardObjective {
    /// Every standard objective.
    pub const ALL: [StandardObjective; 4] = [
        StandardObjective::TransmittedForce,
        StandardObjective::TransmissionRatio,
        StandardObjective::TransmittedEnergy,
        StandardObjective::TransmittedImpulse,
    ];

    /// The objective with this name (as in [`Objective::name`]).
    pub fn from_name(name: &str) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|o| o.as_str() == name)
            .ok_or_else(|| Error::Unknown {
                what: "objective",
                name: name.to_string(),
                valid: Self::ALL.map(StandardObjective::as_str).join(", "),
            })
    }

    /// The name used in config files and tables.
    pub fn as_str(self) -> &'static str {
        match self {
            StandardObjective::TransmittedForce => "transmitted-force",
            StandardObjective::TransmissionRatio => "transmission-ratio",
            StandardObjective::TransmittedEnergy => "transmitted-energy",
            StandardObjective::TransmittedImpulse => "transmitted-impulse",
        }
    }
}

impl Objective for StandardObjective {
    fn name(&self) -> &str {
        self.as_str()
    }

    fn unit(&self) -> &str {
        match self {
            StandardObjective::TransmittedForce => "N",
            StandardObjective::TransmissionRatio => "1",
            StandardObjective::TransmittedEnergy => "J",
            StandardObjective::TransmittedImpulse => "N s",
        }
    }

    fn evaluate(
        &self,
        chain: &Chain,
        excitation: &Excitation,
        settings: &RunSettings,
    ) -> Result<f64> {
        match self {
            StandardObjective::TransmittedForce | StandardObjective::TransmissionRatio => {
                let summary = simulate_watching(
                    chain,
                    excitation,
                    &peaks_only(settings),
                    &mut (),
                    PeakWatch::FiguresOfMerit,
                    f64::INFINITY,
                )?;
                self.force_value(summary, settings)
            }
            StandardObjective::TransmittedEnergy => {
                let mut peak = LayerEnergyPeak::last_layer();
                arrived(simulate(chain, excitation, settings, &mut peak)?, settings)?;
                Ok(peak.peak_j)
            }
            StandardObjective::TransmittedImpulse => {
                let mut impulse = ContactImpulse::wall();
                arrived(
                    simulate(chain, excitation, settings, &mut impulse)?,
                    settings,
                )?;
                Ok(impulse.impulse_n_s)
            }
        }
    }

    fn evaluate_many(
        &self,
        chains: &[Chain],
        excitation: &Excitation,
        settings: &RunSettings,
        lanes: LaneWidth,
    ) -> Vec<Result<f64>> {
        if !matches!(
            self,
            StandardObjective::TransmittedForce | StandardObjective::TransmissionRatio
        ) {
            return one_by_one(self, chains, excitation, settings);
        }
        self.force_values(chains, excitation, settings, lanes, f64::INFINITY)
            .into_iter()
            .map(|v| v.map(Valued::value_or_bound))
            .collect()
    }

    fn is_transmitted_peak(&self) -> bool {
        matches!(self, StandardObjective::TransmittedForce)
    }

    fn evaluate_many_stopping(
        &self,
        chains: &[Chain],
        excitation: &Excitation,
        settings: &RunSettings,
        lanes: LaneWidth,
        stop_above_n: f64,
    ) -> Vec<Result<Valued>> {
        if !self.is_transmitted_peak() {
            return whole_runs(self, chains, excitation, settings, lanes);
        }
        self.force_values(chains, excitation, settings, lanes, stop_above_n)
    }

    /// The transmitted peak is a contact peak (e); the ratio of two is within
    /// (1 + e)/(1 − e) − 1 = 2e/(1 − e). The energy and the impulse are read on the sample grid
    /// and have no such bound.
    fn relative_error(&self, peak_tolerance: f64) -> Option<f64> {
        let e = peak_tolerance;
        match self {
            StandardObjective::TransmittedForce => Some(e),
            StandardObjective::TransmissionRatio => Some(2.0 * e / (1.0 - e)),
            StandardObjective::TransmittedEnergy | StandardObjective::TransmittedImpulse => None,
        }
    }
}

impl StandardObjective {
    /// A force objective's values in SIMD lanes, runs stopped above `stop_above_n` (infinite:
    /// never; only the transmitted peak stops, see [`Objective::evaluate_many_stopping`]).
    fn force_values(
        self,
        chains: &[Chain],
        excitation: &Excitation,
        settings: &RunSettings,
        lanes: LaneWidth,
        stop_above_n: f64,
    ) -> Vec<Result<Valued>> {
        let peaks_only = peaks_only(settings);
        let jobs = Job::for_each_chain(chains, excitation, &peaks_only);
        simulate_many_stopping(&jobs, lanes, PeakWatch::FiguresOfMerit, stop_above_n)
            .into_iter()
            .map(|summary| {
                let summary = summary?;
                if summary.stopped_at_s.is_some() {
                    // Stopped above the cutoff: the wave has arrived, and the peak can only grow.
                    return Ok(Valued::AtLeast(summary.transmitted_peak_force_n));
                }
                self.force_value(summary, settings).map(Valued::Exact)
            })
            .collect()
    }

    /// The value of a force objective from a run's summary.
    fn force_value(self, summary: RunSummary, settings: &RunSettings) -> Result<f64> {
        let s = arrived(summary, settings)?;
        Ok(match self {
            StandardObjective::TransmissionRatio => s.transmission_ratio.unwrap_or(f64::NAN),
            _ => s.transmitted_peak_force_n,
        })
    }
}

/// Peak forces are tracked over every integration step whatever the sample grid, so the force
/// objectives observe only the start and the end (no per-sample energies): the same peaks (bit
/// for bit with fixed steps), less work per evaluation, and runs that fit SIMD lanes. They track
/// only the incident and transmitted peaks ([`PeakWatch::FiguresOfMerit`]), bit for bit those
/// of a run that tracks every contact.
fn peaks_only(settings: &RunSettings) -> RunSettings {
    RunSettings {
        sample_interval_s: settings.duration_s,
        ..*settings
    }
}

/// A transmitted figure of a wave that never reached the wall is a meaningless (tiny) number
/// the GA would happily "minimise": refuse it, naming the duration to increase.
fn arrived(s: RunSummary, settings: &RunSettings) -> Result<RunSummary> {
    if s.wave_arrived {
        Ok(s)
    } else {
        Err(Error::WaveNotArrived {
            duration_s: settings.duration_s,
            transmitted_n: s.transmitted_peak_force_n,
            incident_n: s.incident_peak_force_n,
        })
    }
}

/// Records the largest energy of one layer over the sample grid.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerEnergyPeak {
    /// The layer (0 = striker, N = last element); None = the last layer N.
    pub layer: Option<usize>,
    /// Largest energy seen \[J\].
    pub peak_j: f64,
    /// Time of the peak \[s\].
    pub time_s: f64,
    resolved: usize,
}

impl LayerEnergyPeak {
    /// Watches the last layer N.
    pub fn last_layer() -> Self {
        LayerEnergyPeak {
            layer: None,
            peak_j: 0.0,
            time_s: 0.0,
            resolved: 0,
        }
    }
}

impl Recorder for LayerEnergyPeak {
    fn start(&mut self, layout: &Layout) {
        self.resolved = self.layer.unwrap_or(layout.n_elements);
        self.peak_j = f64::NEG_INFINITY;
        self.time_s = 0.0;
    }

    fn record(&mut self, s: &Sample<'_>) {
        let e = s.layer_energies_j[self.resolved];
        if e > self.peak_j {
            self.peak_j = e;
            self.time_s = s.time_s;
        }
    }
}

/// Integrates one contact force over time with the trapezoid rule on the sample grid.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactImpulse {
    /// The contact (paper numbering); None = the wall contact N.
    pub contact: Option<usize>,
    /// ∫ F dt so far \[N s\].
    pub impulse_n_s: f64,
    resolved: usize,
    last: Option<(f64, f64)>,
}

impl ContactImpulse {
    /// Integrates the wall force F_N.
    pub fn wall() -> Self {
        ContactImpulse {
            contact: None,
            impulse_n_s: 0.0,
            resolved: 0,
            last: None,
        }
    }
}

impl Recorder for ContactImpulse {
    fn start(&mut self, layout: &Layout) {
        self.resolved = self.contact.unwrap_or(layout.n_elements);
        self.impulse_n_s = 0.0;
        self.last = None;
    }

    fn record(&mut self, s: &Sample<'_>) {
        let f = s.contact_forces_n[self.resolved];
        if let Some((t0, f0)) = self.last {
            self.impulse_n_s += 0.5 * (f0 + f) * (s.time_s - t0);
        }
        self.last = Some((s.time_s, f));
    }
}
