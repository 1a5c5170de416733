//! The adaptive stepper of [`Method::ExactModes`](super::Method::ExactModes): exponential Lobatto
//! collocation ([`super::exponential`]) on a chain in modal form, with an embedded error estimate
//! on the primaries, steps from a geometric ladder (so that the weights of a step size are
//! computed once), and steps retaken to end where a contact opens or closes.
//!
//! Besides the contacts, the loads of docs/physics.md §14 ([`Loads`]): a prescribed force on the
//! top element (a blast, a force drive, a preload) or a displacement actuator's tip contact,
//! both in slot 0 and interpolated through the nodes with the contacts; a constant force on a
//! primary (a preload beside a striker), in its node forces; and gravity, which pulls every mass
//! of an element alike and so moves only its rigid mode (the flexible modes carry no momentum),
//! exactly, through the rigid mode's own kernel (½ g t² undamped). The cells' damping is in
//! their modes (`ode::ModalChain`: on-site damping decays each mode at 1/τ, resonator dashpots
//! make them complex). The work W of those forces is carried with the state: the constant ones'
//! exactly (force times displacement), slot 0's as the integral of its force's cubic against
//! the cubic through the top primary's (or the tip's) node positions; the dissipated energy D by
//! each element's balance. A cell with resonator dashpots has an energy that is not a sum over
//! its modes: it is computed only where read (the samples), and D's balance is carried without
//! its change, subtracted there (the change telescopes over the steps).

use super::exponential::{lagrange, nodes, work_of_cubics, StepWeights};
use super::{IntegratorStats, StepControl, Verdict, EVENT_LANDING_FRACTION, NYSTROM_LANDING_END};
use crate::error::{Error, Result};
use crate::math::Libm;
use crate::model::ContactLaw;
use crate::ode::{load_slot, ChainOde, ModalChain};

/// The order that sets the step control: that of the embedded estimate's leading term (the
/// cubic's σ³ part times h², h⁵), as for RKN 6(4).
const CONTROL_ORDER: f64 = 5.0;
/// Steps are taken from the ladder h_k = LADDER_BASE_S · 2^{k/LADDER_PER_OCTAVE} (rounded down):
/// the weights of each rung are computed once per run.
const LADDER_PER_OCTAVE: f64 = 8.0;
const LADDER_BASE_S: f64 = 1e-12;
/// The fixed-point iteration of the node forces stops when no node force changes by more than
/// this fraction of rtol times the largest contact force (at least 1e-13 of it), or after
/// [`MAX_ITERATIONS`] (a rejection): its error then stays a thousandth of the step's.
pub(super) const FIXED_POINT_TOLERANCE: f64 = 1e-3;
pub(super) const MAX_ITERATIONS: usize = 30;
/// The longest step, as a fraction of the run's shortest Hertz contact time (`contact_time_s`
/// of `ChainOde` and `LatticeOde`: the striker's, or under a load every contact's). The exact
/// flow would let a step grow without bound while the contacts are open; a contact that closes
/// and opens again between two of a step's nodes would then go unseen.
pub(super) const MAX_STEP_OF_CONTACT_TIME: f64 = 0.25;
/// Under a blast or a drive (no striker), the speed \[m/s\] at which the contacts' Hertz
/// contact times are taken: the time grows as the speed falls (∝ v^{−1/5}), so slower contacts
/// are only longer than the step limit assumes.
pub(super) const LOAD_CONTACT_SPEED_M_S: f64 = 1.0;
/// Velocity units of the error norm, as [`ChainOde::tolerance_units`]: 1/τ with τ = 1 µs.
pub(super) const VELOCITY_UNIT: f64 = 1e6;

/// One run's stepper state.
#[derive(Debug, Clone)]
pub(crate) struct ModalIntegrator {
    modal: ModalChain,
    /// β per contact slot 0..=P (slot 0 unused: nothing above a striker).
    beta: Vec<f64>,
    rtol: f64,
    atol: f64,
    t: f64,
    t_prev: f64,
    c: Vec<f64>,
    cdot: Vec<f64>,
    c_prev: Vec<f64>,
    cdot_prev: Vec<f64>,
    /// Per primary: the net force's cubic over the last step (monomials in σ) \[N\].
    coef: Vec<[f64; 4]>,
    h_last: f64,
    /// Per primary: the net force at the current point \[N\].
    force_net: Vec<f64>,
    /// Per slot: the overlap at the current point \[m\].
    overlap: Vec<f64>,
    control: StepControl,
    ladder: Ladder<StepWeights>,
    lagrange: [[f64; 4]; 4],
    stats: IntegratorStats,
    scratch: Scratch,
    /// Each primary at the start and the end of the last step.
    ends: [Vec<PrimaryEnd>; 2],
    /// Per primary: a constant force through it besides its weight (a preload beside a
    /// striker) \[N\].
    constant_n: Vec<f64>,
    /// The loads besides the contacts (None: the paper's model under an impact).
    loads: Option<Box<Loads>>,
    /// The longest step \[s\] ([`MAX_STEP_OF_CONTACT_TIME`]).
    max_step_s: f64,
    /// Whether some cell has resonator dashpots, and whether the energies of those cells (their
    /// damping's power, D) are at hand at the start and the end of the last step
    /// ([`ModalIntegrator::settle`]).
    lazy: bool,
    settled: [bool; 2],
}

/// What acts on the chain besides its contacts (docs/physics.md §14), as the exact method takes
/// it.
#[derive(Debug, Clone)]
struct Loads {
    /// The compiled chain, for its prescribed load at any time ([`ChainOde::load_at`]).
    ode: ChainOde,
    /// A displacement actuator's tip rest position \[m\] (None: slot 0 is a prescribed force,
    /// zero beside a striker).
    actuator_rest_m: Option<f64>,
    /// Gravity \[m/s²\] and each primary's total mass μ_0 (its rigid mode's) \[kg\].
    gravity_m_s2: f64,
    total_mass_kg: Vec<f64>,
    /// Slot 0 at the attempt's four nodes: the prescribed force \[N\] or the tip's position \[m\].
    top: [f64; 4],
    /// The work W of the loads \[J\] and its rate \[W\] at the start and the end of the last step.
    work: [(f64, f64); 2],
    /// The energy D the on-site damping dissipated \[J\] and its rate \[W\], likewise.
    dissipated: [(f64, f64); 2],
    /// D plus the change of the energy of the cells with resonator dashpots since the start
    /// \[J\], at the start and the end of the last step (D itself without such cells), and
    /// those cells' energy at the start \[J\].
    balance: [f64; 2],
    resonator_energy_0_j: f64,
    /// Where W sits in the chain's state, whether D follows it, and whether any mode is damped.
    work_index: usize,
    dissipation: bool,
    damped: bool,
}

impl Loads {
    /// Slot 0's force and overlap at node `node` of the attempt, the top primary at `x0` \[m\].
    #[inline(always)]
    fn top_force(&self, node: usize, x0: f64) -> (f64, f64) {
        load_slot(
            self.ode.eq.beta[0],
            self.actuator_rest_m,
            self.top[node],
            x0,
        )
    }

    /// Slot 0 at the nodes of a step of size h from t ([`Loads::top`]).
    fn at_nodes(&mut self, t: f64, h: f64) {
        for (top, c) in self.top.iter_mut().zip(nodes()) {
            let load = self.ode.load_at(t + c * h);
            *top = match self.actuator_rest_m {
                Some(_) => load.tip_m,
                None => load.force_n,
            };
        }
    }

    /// The rate of W at time t \[W\]: slot 0's power (its force times the top primary's
    /// velocity, or times the tip's), the constant forces' and gravity's.
    fn power_w(&self, t: f64, top_force: f64, ends: &[PrimaryEnd], constant_n: &[f64]) -> f64 {
        let load = self.ode.load_at(t);
        let top = match self.actuator_rest_m {
            Some(_) => top_force * load.tip_rate_m_s,
            None if self.ode.has_striker() => 0.0,
            None => top_force * ends[0].v,
        };
        let constant: f64 = constant_n.iter().zip(ends).map(|(f, e)| f * e.v).sum();
        let gravity: f64 = (self.total_mass_kg.iter().zip(ends))
            .map(|(m, e)| m * e.rigid_v)
            .sum();
        top + constant + self.gravity_m_s2 * gravity
    }
}

/// Buffers of an attempt.
#[derive(Debug, Clone)]
struct Scratch {
    /// Per primary: the free (force-less) positions at nodes 1..3.
    free: Vec<[f64; 3]>,
    /// Per primary: net force at nodes 0..3.
    node_force: Vec<[f64; 4]>,
    /// Per primary: positions at nodes 1..3.
    node_x: Vec<[f64; 3]>,
    /// Per slot: overlap at nodes 0..3.
    node_overlap: Vec<[f64; 4]>,
    coef: Vec<[f64; 4]>,
}

/// An attempt's outcome: its error norm (infinite when the collocation conditions were not
/// solved) and the first crossing it missed inside (\[s\] from its start).
pub(super) struct Attempt {
    pub err: f64,
    pub missed: Option<f64>,
}

/// A stepper of [`super::Method::ExactModes`] (a chain's or a contact graph's): what
/// [`adaptive_step`] needs of it.
pub(super) trait ExactStepper {
    /// Its controller and counters.
    fn control(&mut self) -> (&mut StepControl, &mut IntegratorStats);
    /// The current time \[s\].
    fn now(&self) -> f64;
    /// The longest step allowed \[s\].
    fn max_step(&self) -> f64 {
        f64::INFINITY
    }

    /// Tries a step of size h (weights from the ladder's rung, or off the ladder).
    fn attempt(&mut self, h: f64, rung: Option<i64>) -> Attempt;
    /// Advances over the attempt just made.
    fn commit(&mut self, h: f64, rung: Option<i64>);
}

/// One accepted step toward t_end; returns its size. Steps come from the ladder (the weights
/// of a rung are computed once), except a step that ends the run or lands on a crossing.
#[inline(always)]
pub(super) fn adaptive_step<S: ExactStepper>(s: &mut S, t_end: f64) -> Result<f64> {
    loop {
        let t = s.now();
        let remaining = t_end - t;
        let h_try = s.control().0.propose(t, t_end)?.min(s.max_step());
        // A rung of the ladder below the proposal, unless the step ends the run.
        let (h_try, rung) = if h_try < remaining {
            ladder_floor(h_try)
        } else {
            (h_try, None)
        };
        let h = s.control().0.land(h_try, None);
        // A retake ends exactly on the crossing, with weights of its own (ending it on the
        // rung below instead, the kink then early in the next step, was measured worse:
        // energy errors up to 2.6e-3 on Table 1 cells, bench/README.md).
        let landing = s.control().0.landing;
        let rung = if landing { None } else { rung };
        let attempt = s.attempt(h, rung);
        let missed = if landing { None } else { attempt.missed };
        let s_max = s.max_step();
        let (control, stats) = s.control();
        match control.judge(h, attempt.err, missed, CONTROL_ORDER, stats) {
            Verdict::Retry => continue,
            Verdict::Accept => {
                control.accepted(h, attempt.err, CONTROL_ORDER);
                control.h = control.h.min(s_max);
                stats.steps += 1;
                s.commit(h, rung);
                return Ok(h);
            }
        }
    }
}

/// The weights of the step sizes a run has used: each rung of the ladder's, computed once, and
/// the last off-ladder step's.
#[derive(Debug, Clone)]
pub(super) struct Ladder<W> {
    rungs: Vec<(i64, W)>,
    off: Option<(f64, W)>,
}

impl<W> Default for Ladder<W> {
    fn default() -> Self {
        Ladder {
            rungs: Vec::new(),
            off: None,
        }
    }
}

impl<W> Ladder<W> {
    /// Makes sure the weights of step h (rung `rung`, or off the ladder) are at hand.
    pub fn ensure(&mut self, h: f64, rung: Option<i64>, make: impl FnOnce() -> W) {
        match rung {
            Some(k) => {
                if !self.rungs.iter().any(|(r, _)| *r == k) {
                    self.rungs.push((k, make()));
                }
            }
            None => {
                if self.off.as_ref().is_none_or(|(step, _)| *step != h) {
                    self.off = Some((h, make()));
                }
            }
        }
    }

    /// The weights of a rung, or the off-ladder ones ([`Ladder::ensure`] first).
    pub fn get(&self, rung: Option<i64>) -> &W {
        match rung {
            Some(k) => {
                &self
                    .rungs
                    .iter()
                    .find(|(r, _)| *r == k)
                    .expect("computed")
                    .1
            }
            None => &self.off.as_ref().expect("computed").1,
        }
    }
}

impl ModalIntegrator {
    /// A stepper for the run `ode` ([`ChainOde::fits_exact_modes`]) from state `y0`, with
    /// tolerances rtol and atol \[m\] and a first step `h0`.
    pub fn new(ode: &ChainOde, y0: &[f64], rtol: f64, atol: f64, h0: f64) -> Result<Self> {
        let modal = ModalChain::new(ode)?;
        let (p, n) = (ode.eq.p, modal.n_modes());
        let (gravity_m_s2, constant_n) = ode.constant_loads();
        let work_index = 2 * ode.n_dof();
        let loads = (ode.has_lab_physics() || ode.is_blast()).then(|| {
            Box::new(Loads {
                ode: ode.clone(),
                actuator_rest_m: ode.actuator_rest_m(),
                gravity_m_s2,
                total_mass_kg: ode.primary_total_mass_kg(),
                top: [0.0; 4],
                work: [(y0[work_index], 0.0); 2],
                dissipated: [(0.0, 0.0); 2],
                balance: [0.0; 2],
                resonator_energy_0_j: 0.0,
                work_index,
                dissipation: ode.has_lab_physics(),
                damped: modal.kind_rate.iter().any(|&r| r > 0.0)
                    || modal.damped.iter().any(Option::is_some),
            })
        });
        let (mut c, mut cdot) = (vec![0.0; n], vec![0.0; n]);
        modal.project_state(y0, &mut c, &mut cdot);
        let lazy = modal.damped.iter().any(Option::is_some);
        let mut me = ModalIntegrator {
            beta: ode.eq.beta.clone(),
            rtol,
            atol,
            t: 0.0,
            t_prev: 0.0,
            c_prev: c.clone(),
            cdot_prev: cdot.clone(),
            c,
            cdot,
            coef: vec![[0.0; 4]; p],
            h_last: 0.0,
            force_net: vec![0.0; p],
            overlap: vec![0.0; p + 1],
            control: StepControl::new(h0),
            ladder: Ladder::default(),
            lagrange: lagrange(),
            stats: IntegratorStats::default(),
            scratch: Scratch {
                free: vec![[0.0; 3]; p],
                node_force: vec![[0.0; 4]; p],
                node_x: vec![[0.0; 3]; p],
                node_overlap: vec![[0.0; 4]; p + 1],
                coef: vec![[0.0; 4]; p],
            },
            ends: [
                vec![PrimaryEnd::default(); p],
                vec![PrimaryEnd::default(); p],
            ],
            modal,
            constant_n,
            loads,
            max_step_s: MAX_STEP_OF_CONTACT_TIME * ode.contact_time_s(LOAD_CONTACT_SPEED_M_S),
            lazy,
            settled: [true; 2],
        };
        let x: Vec<f64> = me
            .modal
            .ranges
            .iter()
            .map(|r| me.c[r.clone()].iter().sum())
            .collect();
        let (mut f, mut d) = (vec![0.0; p + 1], vec![0.0; p + 1]);
        me.contacts(&x, &mut f, &mut d);
        for i in 0..p {
            me.force_net[i] = f[i] - f[i + 1] + me.constant_n[i];
        }
        me.overlap = d;
        me.stats.rhs_evaluations = 1;
        let mut ends = std::mem::take(&mut me.ends[1]);
        me.primary_ends(&mut ends);
        if let Some(loads) = &mut me.loads {
            let power = loads.power_w(0.0, f[0], &ends, &me.constant_n);
            loads.work = [(loads.work[0].0, power); 2];
            if loads.dissipation {
                let rate = ends.iter().map(|e| e.dissipation).sum();
                loads.dissipated = [(y0[work_index + 1], rate); 2];
                loads.balance = [y0[work_index + 1]; 2];
            }
            loads.resonator_energy_0_j = (ends.iter().zip(&me.modal.kind))
                .filter(|(_, &k)| me.modal.damped[k].is_some())
                .map(|(e, _)| e.energy)
                .sum();
        }
        me.ends = [ends.clone(), ends];
        Ok(me)
    }

    /// Contact forces and overlaps per slot for primary positions `x` at the start (slot 0:
    /// the load, or nothing above a striker).
    fn contacts(&mut self, x: &[f64], force: &mut [f64], overlap: &mut [f64]) {
        let p = x.len();
        (force[0], overlap[0]) = match &mut self.loads {
            Some(loads) => {
                loads.at_nodes(self.t, 0.0);
                loads.top_force(0, x[0])
            }
            None => (0.0, 0.0),
        };
        for s in 1..=p {
            let d = if s < p { x[s - 1] - x[s] } else { x[p - 1] };
            overlap[s] = d;
            force[s] = ContactLaw::elastic_force(self.beta[s], d);
        }
    }

    pub fn t(&self) -> f64 {
        self.t
    }

    pub fn t_prev(&self) -> f64 {
        self.t_prev
    }

    pub fn stats(&self) -> IntegratorStats {
        self.stats
    }

    /// Makes sure the weights of step h are at hand (a rung's, or the off-ladder ones).
    fn weights(&mut self, h: f64, rung: Option<i64>) {
        let m = &self.modal;
        self.ladder.ensure(h, rung, || StepWeights::new(h, m));
    }

    super::exact_step_in_simd_build!();

    /// The same step without run-time SIMD dispatch: the reference the AVX2 build is checked
    /// against.
    #[inline(always)]
    pub fn step_portable(&mut self, t_end: f64) -> Result<f64> {
        adaptive_step(self, t_end)
    }

    /// Tries a step of size h: solves the collocation conditions, returns the error norm
    /// (infinite when the iteration does not converge) and the first crossing inside.
    #[inline(always)]
    fn attempt(&mut self, h: f64, rung: Option<i64>) -> Attempt {
        let p = self.force_net.len();
        let c_nodes = nodes();
        // The free motion of each primary at the nodes, and the first guess of the node forces:
        // the last step's cubic continued (constant at the start).
        let mut sc = std::mem::replace(&mut self.scratch, Scratch::empty());
        self.weights(h, rung);
        if let Some(loads) = &mut self.loads {
            loads.at_nodes(self.t, h);
        }
        let (m, weights) = (&self.modal, self.ladder_or_off(rung));
        for (i, range) in m.ranges.iter().enumerate() {
            let (c, cdot) = (&self.c[range.clone()], &self.cdot[range.clone()]);
            sc.free[i] = weights.free_positions(m.groups(i), groups(c), groups(cdot));
            let f = &mut sc.node_force[i];
            f[0] = self.force_net[i];
            for j in 1..4 {
                f[j] = if self.h_last > 0.0 {
                    let s = 1.0 + c_nodes[j] * h / self.h_last;
                    let a = &self.coef[i];
                    ((a[3] * s + a[2]) * s + a[1]) * s + a[0]
                } else {
                    self.force_net[i]
                };
            }
        }
        let g = self.loads.as_ref().map_or(0.0, |l| l.gravity_m_s2);
        if g != 0.0 {
            // Gravity moves every rigid mode (½ g t² undamped), so every primary.
            let (m, weights) = (&self.modal, self.ladder_or_off(rung));
            for (free, &kind) in sc.free.iter_mut().zip(&m.kind) {
                for (x, r) in free.iter_mut().zip(weights.rigid[kind].nodes) {
                    *x += g * r;
                }
            }
        }
        let converged = self.solve_nodes(h, rung, &mut sc);
        let (m, weights) = (&self.modal, self.ladder_or_off(rung));
        let mut sum = 0.0;
        for i in 0..p {
            let a3 = sc.coef[i][3];
            let (ex, ev) = weights.error[m.kind[i]];
            let x = sc.node_x[i][2];
            let v = self.ends[1][i].v;
            let sx = self.atol + self.rtol * x.abs();
            let sv = self.atol * VELOCITY_UNIT + self.rtol * v.abs();
            sum += (h * h * a3 * ex / sx).powi(2) + (h * a3 * ev / sv).powi(2);
        }
        let err = if converged {
            (sum / (2 * p) as f64).sqrt()
        } else {
            f64::INFINITY
        };
        let missed = if err <= 1.0 {
            first_crossing(&sc.node_overlap, &self.beta).map(|theta| theta * h)
        } else {
            None
        };
        self.scratch = sc;
        Attempt { err, missed }
    }

    fn ladder_or_off(&self, rung: Option<i64>) -> &StepWeights {
        self.ladder.get(rung)
    }

    /// The fixed-point iteration of the collocation conditions: node forces → node positions
    /// (the response to the forces' interpolating cubic) → node forces. Leaves the cubic in
    /// `sc.coef`, the positions in `sc.node_x` and the overlaps in `sc.node_overlap`. False when
    /// it did not converge.
    #[inline(always)]
    fn solve_nodes(&mut self, h: f64, rung: Option<i64>, sc: &mut Scratch) -> bool {
        let p = self.force_net.len();
        for (s, d) in sc.node_overlap.iter_mut().enumerate() {
            *d = [self.overlap[s], 0.0, 0.0, 0.0];
        }
        let h2 = h * h;
        let tolerance = (FIXED_POINT_TOLERANCE * self.rtol).max(1e-13);
        let weights = self.ladder.get(rung);
        let kind = &self.modal.kind;
        let beta = &self.beta[..=p];
        for _ in 0..MAX_ITERATIONS {
            for ((x, free), (f, &k)) in sc.node_x[..p]
                .iter_mut()
                .zip(&sc.free[..p])
                .zip(sc.node_force[..p].iter().zip(&kind[..p]))
            {
                let g = &weights.node_response[k];
                for j in 0..3 {
                    let g = &g[j];
                    x[j] =
                        free[j] + h2 * ((g[0] * f[0] + g[1] * f[1]) + (g[2] * f[2] + g[3] * f[3]));
                }
            }
            let (mut change, mut scale) = (0.0_f64, 0.0_f64);
            for j in 0..3 {
                // The force of the slot above primary i, then below it (slot 0: the load, or
                // nothing above a striker).
                let mut above = 0.0;
                if let Some(loads) = &self.loads {
                    let (f, d) = loads.top_force(j + 1, sc.node_x[0][j]);
                    sc.node_overlap[0][j + 1] = d;
                    scale = scale.max(f.abs());
                    above = f;
                }
                for i in 0..p {
                    let d = if i + 1 < p {
                        sc.node_x[i][j] - sc.node_x[i + 1][j]
                    } else {
                        sc.node_x[i][j]
                    };
                    sc.node_overlap[i + 1][j + 1] = d;
                    let below = ContactLaw::elastic_force(beta[i + 1], d);
                    let f = above - below + self.constant_n[i];
                    change = change.max((f - sc.node_force[i][j + 1]).abs());
                    scale = scale.max(below.abs());
                    sc.node_force[i][j + 1] = f;
                    above = below;
                }
            }
            self.stats.rhs_evaluations += 3;
            if change <= tolerance * scale || scale == 0.0 {
                for (coef, f) in sc.coef[..p].iter_mut().zip(&sc.node_force[..p]) {
                    *coef = [0, 1, 2, 3].map(|n| (0..4).map(|k| self.lagrange[n][k] * f[k]).sum());
                }
                return true;
            }
        }
        false
    }

    /// Advances the state over the attempt just made (step h).
    #[inline(always)]
    fn commit(&mut self, h: f64, rung: Option<i64>) {
        std::mem::swap(&mut self.c, &mut self.c_prev);
        std::mem::swap(&mut self.cdot, &mut self.cdot_prev);
        let sc = std::mem::replace(&mut self.scratch, Scratch::empty());
        let weights = self.ladder.get(rung);
        let m = &self.modal;
        let g = self.loads.as_ref().map_or(0.0, |l| l.gravity_m_s2);
        self.ends.swap(0, 1);
        for (i, (range, a)) in m.ranges.iter().zip(&sc.coef).enumerate() {
            let [mut x, mut v, w2c, mut energy] = weights.advance(
                m.groups(i),
                a,
                (
                    groups(&self.c_prev[range.clone()]),
                    groups(&self.cdot_prev[range.clone()]),
                ),
                (
                    self.c[range.clone()].as_chunks_mut::<4>().0,
                    self.cdot[range.clone()].as_chunks_mut::<4>().0,
                ),
            );
            let (rigid, kind) = (range.start, m.kind[i]);
            let mu0 = 1.0 / m.inv_modal_mass[m.kind_ranges[kind].start];
            if g != 0.0 {
                // Gravity moves the rigid mode alone (½ g h² and g h undamped).
                let response = weights.rigid[kind];
                let (dx, dv) = (g * response.nodes[2], g * response.end_velocity);
                let v0 = self.cdot[rigid];
                self.c[rigid] += dx;
                self.cdot[rigid] = v0 + dv;
                x += dx;
                v += dv;
                energy += 0.5 * mu0 * (self.cdot[rigid] * self.cdot[rigid] - v0 * v0);
            }
            let f = sc.node_force[i][3];
            self.force_net[i] = f;
            let rigid_v = self.cdot[rigid];
            let (energy, dissipation, damping) =
                element_energy(m, i, &self.cdot[range.clone()], energy, v);
            let power_in = f * v + g * mu0 * rigid_v;
            self.ends[1][i] = PrimaryEnd {
                x,
                v,
                a: f * m.accel_per_newton[kind] - w2c + g - damping,
                energy,
                power: power_in - dissipation,
                power_in,
                rigid_x: self.c[rigid],
                rigid_v,
                dissipation,
            };
        }
        self.coef.copy_from_slice(&sc.coef);
        for (s, d) in sc.node_overlap.iter().enumerate() {
            self.overlap[s] = d[3];
        }
        self.h_last = h;
        self.t_prev = self.t;
        self.t += h;
        self.settled = [self.settled[1], !self.lazy];
        if self.loads.is_some() {
            self.add_work(&sc);
        }
        self.scratch = sc;
    }

    /// Adds the loads' work over the step just taken (from `t_prev` to `t`, its collocation in
    /// `sc`) to W, and sets W's rate at the new end.
    fn add_work(&mut self, sc: &Scratch) {
        let loads = self.loads.as_mut().expect("called with loads");
        let [before, after] = &self.ends;
        let mut w = loads.work[1].0;
        for (i, (a, b)) in before.iter().zip(after).enumerate() {
            w += self.constant_n[i] * (b.x - a.x)
                + loads.gravity_m_s2 * loads.total_mass_kg[i] * (b.rigid_x - a.rigid_x);
        }
        // Slot 0: ∫ F dX over the cubics through the nodes, X the top primary's position (a
        // force) or the tip's (an actuator).
        let force: [f64; 4] = match loads.actuator_rest_m {
            Some(_) => {
                sc.node_overlap[0].map(|d| ContactLaw::elastic_force(loads.ode.eq.beta[0], d))
            }
            None => loads.top,
        };
        let position = match loads.actuator_rest_m {
            Some(_) => loads.top,
            None => {
                let x = &sc.node_x[0];
                [before[0].x, x[0], x[1], x[2]]
            }
        };
        let monomials = |v: &[f64; 4]| {
            [0, 1, 2, 3].map(|n| (0..4).map(|k| self.lagrange[n][k] * v[k]).sum::<f64>())
        };
        if !loads.ode.has_striker() {
            w += work_of_cubics(&monomials(&force), &monomials(&position), 1.0);
        }
        let power = loads.power_w(self.t, force[3], after, &self.constant_n);
        loads.work = [loads.work[1], (w, power)];
        if loads.damped {
            // D by the balance of each element: the work of its net force (∫ F dx over the
            // cubics through the nodes) and of gravity, less the change of its modes' energy
            // (a cell with resonator dashpots: at the samples, `settle`).
            let mut d = loads.balance[1];
            for (i, (a, b)) in before.iter().zip(after).enumerate() {
                let x = &sc.node_x[i];
                let position = monomials(&[a.x, x[0], x[1], x[2]]);
                let change = match self.modal.damped[self.modal.kind[i]] {
                    Some(_) => 0.0,
                    None => b.energy - a.energy,
                };
                d += work_of_cubics(&sc.coef[i], &position, 1.0)
                    + loads.gravity_m_s2 * loads.total_mass_kg[i] * (b.rigid_x - a.rigid_x)
                    - change;
            }
            let rate = after.iter().map(|e| e.dissipation).sum();
            loads.balance = [loads.balance[1], d];
            loads.dissipated = [loads.dissipated[1], (d, rate)];
        }
    }

    /// The primaries' positions and velocities now into y (the rest of y, W and D included, is
    /// left: [`ModalIntegrator::observe_at`] gives them).
    pub fn primaries_into(&self, y: &mut [f64]) {
        let nd = self.dof(y);
        for (i, e) in self.ends[1].iter().enumerate() {
            y[i] = e.x;
            y[nd + i] = e.v;
        }
    }

    /// The number of point masses of the chain's state `y`.
    fn dof(&self, y: &[f64]) -> usize {
        self.loads.as_ref().map_or(y.len(), |l| l.work_index) / 2
    }

    /// W (and D) at the fraction s of the last step into y: cubic Hermite interpolation from
    /// the ends' values and rates.
    fn integrals_into(&self, s: f64, y: &mut [f64]) {
        let Some(loads) = &self.loads else { return };
        let [(w0, p0), (w1, p1)] = loads.work;
        y[loads.work_index] = if s >= 1.0 {
            w1
        } else {
            hermite(s, self.h_last, [w0, p0, w1, p1])
        };
        if loads.dissipation {
            let [(d0, r0), (d1, r1)] = loads.dissipated;
            y[loads.work_index + 1] = if s >= 1.0 {
                d1
            } else {
                hermite(s, self.h_last, [d0, r0, d1, r1])
            };
        }
    }

    /// The primaries' positions and velocities at ts within the last step into y (the rest of
    /// y is left) and each primary's internal energy Σ_k ½ μ_k (ċ_k² + Ω_k² c_k²) \[J\] into
    /// `internal`. At the step's end: the state itself. Inside: cubic Hermite interpolation of
    /// each primary's position (from its velocity), velocity (from its acceleration) and internal
    /// energy (from its rate, the net contact force's power F_net·v), as RKN 6(4)'s samples; the
    /// exact formula at θ would cost a kernel per frequency and a pass over every mode per sample.
    pub fn observe_at(&mut self, ts: f64, y: &mut [f64], internal: &mut [f64]) {
        let nd = self.dof(y);
        let h = self.h_last;
        let at_end = ts >= self.t || h == 0.0;
        self.settle(1);
        if !at_end {
            self.settle(0);
        }
        let (now, before) = (&self.ends[1], &self.ends[0]);
        if at_end {
            for (i, e) in now.iter().enumerate() {
                y[i] = e.x;
                y[nd + i] = e.v;
                internal[i] = e.energy;
            }
            self.integrals_into(1.0, y);
            return;
        }
        let s = ((ts - self.t_prev) / h).clamp(0.0, 1.0);
        for (i, (a, b)) in before.iter().zip(now).enumerate() {
            y[i] = hermite(s, h, [a.x, a.v, b.x, b.v]);
            y[nd + i] = hermite(s, h, [a.v, a.a, b.v, b.a]);
            internal[i] = hermite(s, h, [a.energy, a.power, b.energy, b.power]);
        }
        self.integrals_into(s, y);
    }

    /// Computes what a step leaves out at the start (`end` 0) or the end (1) of the last step,
    /// unless done: the energy of each cell with resonator dashpots, the power its damping
    /// dissipates, and so the rate of its energy, D and D's rate. D is the balance carried by
    /// the steps less the change of those cells' energy since the start: the same sum over the
    /// steps as each step's balance, its energy terms telescoped.
    fn settle(&mut self, end: usize) {
        if self.settled[end] {
            return;
        }
        self.settled[end] = true;
        let (c, cdot) = match end {
            0 => (&self.c_prev, &self.cdot_prev),
            _ => (&self.c, &self.cdot),
        };
        let m = &self.modal;
        let mut energy = 0.0;
        for (i, (range, e)) in m.ranges.iter().zip(&mut self.ends[end]).enumerate() {
            if let Some(cell) = &m.damped[m.kind[i]] {
                (e.energy, e.dissipation, _) = cell.energy(&c[range.clone()], &cdot[range.clone()]);
                e.power = e.power_in - e.dissipation;
                energy += e.energy;
            }
        }
        if let Some(loads) = self.loads.as_mut().filter(|l| l.damped) {
            let rate = self.ends[end].iter().map(|e| e.dissipation).sum();
            let change = energy - loads.resonator_energy_0_j;
            loads.dissipated[end] = (loads.balance[end] - change, rate);
        }
    }

    /// Each primary's position, velocity, acceleration, internal energy and its rate now.
    fn primary_ends(&self, out: &mut [PrimaryEnd]) {
        let m = &self.modal;
        for (i, range) in m.ranges.iter().enumerate() {
            let f = self.force_net[i];
            let kind = m.kind_ranges[m.kind[i]].clone();
            let (c, cd) = (&self.c[range.clone()], &self.cdot[range.clone()]);
            let (w2, mu) = (&m.omega2[kind.clone()], &m.modal_mass[kind]);
            let mut e = PrimaryEnd::default();
            let mut w2c = 0.0;
            for k in 0..c.len() {
                e.x += c[k];
                e.v += cd[k];
                w2c += w2[k] * c[k];
                e.energy += 0.5 * mu[k] * (cd[k] * cd[k] + w2[k] * c[k] * c[k]);
            }
            let g = self.loads.as_ref().map_or(0.0, |l| l.gravity_m_s2);
            (e.rigid_x, e.rigid_v) = (c[0], cd[0]);
            let damping;
            (e.energy, e.dissipation, damping) = match &m.damped[m.kind[i]] {
                Some(cell) => cell.energy(c, cd),
                None => element_energy(m, i, cd, e.energy, e.v),
            };
            let mu0 = 1.0 / m.inv_modal_mass[m.kind_ranges[m.kind[i]].start];
            e.a = f * m.accel_per_newton[m.kind[i]] - w2c + g - damping;
            e.power_in = f * e.v + g * mu0 * e.rigid_v;
            e.power = e.power_in - e.dissipation;
            out[i] = e;
        }
    }
}

impl ExactStepper for ModalIntegrator {
    fn control(&mut self) -> (&mut StepControl, &mut IntegratorStats) {
        (&mut self.control, &mut self.stats)
    }

    fn now(&self) -> f64 {
        self.t
    }

    fn max_step(&self) -> f64 {
        self.max_step_s
    }

    #[inline(always)]
    fn attempt(&mut self, h: f64, rung: Option<i64>) -> Attempt {
        self.attempt(h, rung)
    }

    #[inline(always)]
    fn commit(&mut self, h: f64, rung: Option<i64>) {
        self.commit(h, rung)
    }
}

/// A primary at a step's end: what the samples inside the step are interpolated from (for a
/// cell with resonator dashpots, `energy`, `power` and `dissipation` are NaN until
/// [`ModalIntegrator::settle`]).
#[derive(Debug, Clone, Copy, Default)]
struct PrimaryEnd {
    x: f64,
    v: f64,
    a: f64,
    energy: f64,
    power: f64,
    /// The power of its net force and of gravity on it (`power` less its damping's) \[W\].
    power_in: f64,
    /// Its rigid mode's amplitude and rate (what gravity works on).
    rigid_x: f64,
    rigid_v: f64,
    /// The power its on-site damping dissipates, 1/τ Σ_k μ_k ċ_k² \[W\].
    dissipation: f64,
}

/// Σ_k μ_k ċ_k² over one element's modes (twice their kinetic energy).
fn dissipation_sum(cdot: &[f64], modal_mass: &[f64]) -> f64 {
    cdot.iter().zip(modal_mass).map(|(v, m)| m * v * v).sum()
}

/// Primary i's element at the end of a step, from its modes' rates ċ: its energy (`energy`, the
/// sum over its modes), the power its damping dissipates, and the damping's part of the
/// primary's acceleration (1/τ v under on-site damping, `v` the primary's velocity). A cell
/// whose resonators have dashpots gets NaN for the first two: they are rebuilt from every
/// resonator (`ode::damped_modes`) where read ([`ModalIntegrator::settle`]).
#[inline(always)]
fn element_energy(m: &ModalChain, i: usize, cdot: &[f64], energy: f64, v: f64) -> (f64, f64, f64) {
    let kind = m.kind[i];
    if let Some(cell) = &m.damped[kind] {
        return (f64::NAN, f64::NAN, cell.damping_accel(cdot));
    }
    let rate = m.kind_rate[kind];
    if rate == 0.0 {
        return (energy, 0.0, 0.0);
    }
    let mu = &m.modal_mass[m.kind_ranges[kind].clone()];
    (energy, rate * dissipation_sum(cdot, mu), rate * v)
}

/// The cubic Hermite interpolant at the fraction s of a step of size h through the values and
/// rates `[f0, d0, f1, d1]` at its ends.
fn hermite(s: f64, h: f64, [f0, d0, f1, d1]: [f64; 4]) -> f64 {
    let (h00, h10, h01, h11) = (
        (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s),
        s * (1.0 - s) * (1.0 - s),
        s * s * (3.0 - 2.0 * s),
        s * s * (s - 1.0),
    );
    h00 * f0 + h10 * h * d0 + h01 * f1 + h11 * h * d1
}

impl Scratch {
    fn empty() -> Self {
        Scratch {
            free: Vec::new(),
            node_force: Vec::new(),
            node_x: Vec::new(),
            node_overlap: Vec::new(),
            coef: Vec::new(),
        }
    }
}

/// A primary's modes in their groups of four (its range is padded to whole groups).
fn groups(modes: &[f64]) -> &[[f64; 4]] {
    modes.as_chunks::<4>().0
}

/// The rung of the step ladder at or below h, and its index.
pub(super) fn ladder_floor(h: f64) -> (f64, Option<i64>) {
    let k = (LADDER_PER_OCTAVE * (h / LADDER_BASE_S).libm_log2()).floor();
    (
        LADDER_BASE_S * (k / LADDER_PER_OCTAVE).exp2(),
        Some(k as i64),
    )
}

/// The root of f in the bracket (lo, hi) whose values (f_lo, f_hi) differ in sign (f_lo > 0, the
/// contact closed there, or f_hi > 0): Newton's steps on f from the chord's root, each evaluation
/// narrowing the bracket, a bisection wherever a step would leave it, until a step moves less
/// than 4 ulp or the bracket is a single point (at most 100 evaluations, then its middle).
fn newton_in_bracket(
    f: impl Fn(f64) -> f64,
    slope: impl Fn(f64) -> f64,
    (mut lo, mut hi): (f64, f64),
    (f_lo, f_hi): (f64, f64),
) -> f64 {
    let closed_lo = f_lo > 0.0;
    let mut x = lo + (hi - lo) * f_lo / (f_lo - f_hi);
    for _ in 0..100 {
        if !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
            if x == lo || x == hi {
                return x;
            }
        }
        let fx = f(x);
        if (fx > 0.0) == closed_lo {
            lo = x;
        } else {
            hi = x;
        }
        let next = x - fx / slope(x);
        if (next - x).abs() <= 4.0 * f64::EPSILON * x.abs() {
            return if next > lo && next < hi { next } else { x };
        }
        x = next;
    }
    0.5 * (lo + hi)
}

/// The first point θ ∈ (EVENT_LANDING_FRACTION, NYSTROM_LANDING_END) of a step where a contact
/// (β > 0) opens or closes, from its overlaps at the four nodes: the root of the cubic through
/// them (in monomials, by Horner's rule) in the first node interval whose ends differ in sign
/// ([`newton_in_bracket`]).
pub(super) fn first_crossing(overlaps: &[[f64; 4]], beta: &[f64]) -> Option<f64> {
    let c = super::exponential::nodes();
    let mut lagrange = None;
    let mut first: Option<f64> = None;
    for (s, d) in overlaps.iter().enumerate() {
        if beta[s] == 0.0 {
            continue;
        }
        let Some(j) = (0..3).find(|&j| (d[j] > 0.0) != (d[j + 1] > 0.0)) else {
            continue;
        };
        let l: &[[f64; 4]; 4] = lagrange.get_or_insert_with(super::exponential::lagrange);
        let a = l.map(|row| (0..4).map(|k| row[k] * d[k]).sum::<f64>());
        let cubic = |x: f64| ((a[3] * x + a[2]) * x + a[1]) * x + a[0];
        let slope = |x: f64| (3.0 * a[3] * x + 2.0 * a[2]) * x + a[1];
        let theta = newton_in_bracket(cubic, slope, (c[j], c[j + 1]), (d[j], d[j + 1]));
        if theta > EVENT_LANDING_FRACTION
            && theta < NYSTROM_LANDING_END
            && first.is_none_or(|f| theta < f)
        {
            first = Some(theta);
        }
    }
    first
}

/// Every modal amplitude and rate after `steps` accepted steps of [`super::Method::ExactModes`]
/// (rtol, atol \[m\], first step `h0`) on the impact run `ode`, stepped with the run-time SIMD
/// dispatch of [`ModalIntegrator::step`] or, with `portable`, without it: what the claim
/// `simd_step_bit_identical` compares bit for bit.
#[doc(hidden)]
pub fn exact_modes_state(
    ode: &ChainOde,
    (rtol, atol, h0): (f64, f64, f64),
    steps: usize,
    portable: bool,
) -> Result<Vec<f64>> {
    check_fits(ode)?;
    let mut stepper = ModalIntegrator::new(ode, &ode.initial_state(), rtol, atol, h0)?;
    for _ in 0..steps {
        if portable {
            stepper.step_portable(1.0)?;
        } else {
            stepper.step(1.0)?;
        }
    }
    Ok([stepper.c, stepper.cdot].concat())
}

/// Each primary's internal energy, then the chain's state as [`ModalIntegrator::observe_at`]
/// gives it (the primaries' positions and velocities, W and D; the resonators' entries as at
/// the start), at each of `times` (ascending) of a run of [`super::Method::ExactModes`] (rtol,
/// atol \[m\], first step `h0`) on `ode` stepped to the last of them; with `every_step`, the
/// energies are also read at the end of every step: what the claim `exact_modes_lazy_energy`
/// compares bit for bit.
#[doc(hidden)]
pub fn exact_modes_observations(
    ode: &ChainOde,
    (rtol, atol, h0): (f64, f64, f64),
    times: &[f64],
    every_step: bool,
) -> Result<Vec<Vec<f64>>> {
    check_fits(ode)?;
    let mut y = ode.initial_state();
    let mut stepper = ModalIntegrator::new(ode, &y, rtol, atol, h0)?;
    let mut internal = vec![0.0; ode.eq.p];
    let t_end = times.last().copied().unwrap_or(0.0);
    let mut out = Vec::with_capacity(times.len());
    while out.len() < times.len() {
        stepper.step(t_end)?;
        if every_step {
            stepper.observe_at(stepper.t(), &mut y, &mut internal);
        }
        while let Some(&ts) = times.get(out.len()).filter(|&&ts| ts <= stepper.t()) {
            stepper.observe_at(ts, &mut y, &mut internal);
            out.push([internal.as_slice(), &y].concat());
        }
    }
    Ok(out)
}

/// Refuses a chain the exact modal method cannot run ([`ChainOde::fits_exact_modes`]).
pub(crate) fn check_fits(ode: &ChainOde) -> Result<()> {
    if !ode.fits_exact_modes() {
        return Err(Error::invalid(
            "run.method",
            "exact-modes",
            "advances a chain whose contacts are elastic (under an impact, a blast, a drive, a \
             preload, gravity, resonator and on-site damping); with a damped contact law use \
             dopri5, or run.peak_tolerance (which chooses the method for the run)",
        ));
    }
    Ok(())
}
