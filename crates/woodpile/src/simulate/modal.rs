//! The run loop of [`Method::ExactModes`]: the stepper of `integrate::modal_step` keeps the
//! chain in modal form; the chain's own state is rebuilt from it where the run watches — the
//! primaries after every step (contact forces, peaks, checks), the whole state at the samples
//! (energy balance, recorder) — so that peaks, samples and the energy audit are `simulate`'s own.

use super::{PeakWatch, RunSettings, RunSummary, Watch};
use crate::error::Result;
use crate::excitation::Excitation;
use crate::integrate::modal_step::{check_fits, ModalIntegrator};
use crate::integrate::{Method, OdeSystem};
use crate::ode::ChainOde;
use crate::record::{Layout, Recorder};

/// The first step tried \[s\]: a hundredth of the sample interval (the controller grows it by up
/// to five times a step).
const FIRST_STEP_OF_SAMPLE: f64 = 0.01;

/// The exact modal method's stepper for `ode` at `method`'s tolerances (errors: the run does not
/// fit the method, or a cell's damped modes cannot be followed).
pub(super) fn stepper(
    ode: &ChainOde,
    method: Method,
    settings: &RunSettings,
) -> Result<ModalIntegrator> {
    let Method::ExactModes { rtol, atol } = method else {
        unreachable!("called for the exact modal method")
    };
    check_fits(ode)?;
    let h0 = FIRST_STEP_OF_SAMPLE * settings.sample_interval_s.min(settings.duration_s);
    ModalIntegrator::new(ode, &ode.initial_state(), rtol, atol, h0)
}

/// [`super::simulate_watching`] for [`Method::ExactModes`] with its `stepper`; `watching`: the
/// peaks watched, the transmitted peak that stops the run, the start of the run's clock.
pub(super) fn simulate_modal(
    mut ode: ChainOde,
    mut stepper: ModalIntegrator,
    excitation: &Excitation,
    settings: &RunSettings,
    recorder: &mut dyn Recorder,
    (peak_watch, stop_above_n, started): (PeakWatch, f64, crate::clock::Stopwatch),
) -> Result<RunSummary> {
    let dim = ode.dimension();
    let mut y = ode.initial_state();
    let mut scratch = vec![0.0; dim];
    ode.rhs(0.0, &y, &mut scratch);
    recorder.start(&Layout {
        n_elements: ode.n_elements(),
        has_striker: ode.has_striker(),
        n_samples: settings.n_samples(),
    });
    let mut watch = Watch::start(
        &mut ode, excitation, settings, &y, recorder, started, peak_watch,
    )
    .stop_above(stop_above_n);
    let mut y_sample = vec![0.0; dim];
    let mut internal = vec![0.0; ode.eq.p];
    let t_end = settings.duration_s;
    while stepper.t() < t_end * (1.0 - 1e-14) {
        stepper.step(t_end)?;
        let (t0, t1) = (stepper.t_prev(), stepper.t());
        // The force cache at the new primaries (the resonators' part of y, W and D are not
        // read: they are the samples', `observe_at`).
        stepper.primaries_into(&mut y);
        ode.set_contacts_at(t1, &y);
        ode.check_contacts(t1)?;
        if stepper.stats().steps > crate::defaults::MAX_STEPS {
            return Err(super::too_many_steps(t1, settings));
        }
        if crate::interrupt::requested() {
            return Err(crate::Error::Interrupted { time_s: t1 });
        }
        watch.after_step(&ode, t0, t1, &y);
        while let Some((ts, at_step)) = watch.sample_due(t1) {
            let at = if at_step { t1 } else { ts };
            stepper.observe_at(at, &mut y_sample, &mut internal);
            ode.set_contacts_at(at, &y_sample);
            watch.record_with(&mut ode, ts, &y_sample, true, Some(&internal), recorder)?;
        }
        if watch.stop_due() && t1 < t_end * (1.0 - 1e-14) {
            ode.set_contacts_at(t1, &y);
            let mut summary = watch.finish(&ode, &y, stepper.stats());
            summary.stopped_at_s = Some(t1);
            return Ok(summary);
        }
    }
    // The summary reads the primaries (the striker's rebound) and the force cache at the end.
    ode.set_contacts_at(stepper.t(), &y);
    Ok(watch.finish(&ode, &y, stepper.stats()))
}
