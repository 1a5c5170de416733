//! [`Method::ExactModes`](super::Method::ExactModes) on a contact graph (a lattice,
//! docs/physics.md §16 and §8 "Exact linear vibrations"): every body moves in mass-normalised
//! modal coordinates, q̈_m = −ω_m² q_m + Σ_c r_cm F_c, so the linear part is diagonal. Over a
//! step each contact force F_c is replaced by its cubic through the four Lobatto nodes, every
//! mode is advanced against the cubic its contacts exert (Σ_c ∓r_cm a_c, [`super::exponential`])
//! exactly, and the node forces are found by fixed-point iteration on the contacts' overlaps.
//!
//! The embedded error estimate is that of the chain's stepper (the cubic's σ³ part against the
//! quadratic through 0, ½, 1), mapped from the modes to the two points of every loaded contact
//! and to its force; its norm is the largest over those, not their mean, so that one active
//! contact among hundreds at rest is held to the tolerance. A step in which a contact opens or closes is
//! retaken to end there; samples inside a step are the exact flow at their time.

use super::exponential::{
    damped_kernel, kernel, lagrange, nodes, DampedKernel, Kernel, ERROR_POLY,
};
use super::modal_step::{
    adaptive_step, first_crossing, Attempt, ExactStepper, Ladder, FIXED_POINT_TOLERANCE,
    MAX_ITERATIONS, VELOCITY_UNIT,
};
use super::{IntegratorStats, StepControl};
use crate::error::Result;
use crate::model::ContactLaw;
use crate::ode::LatticeOde;

/// The longest step, as a fraction of the striker's Hertz contact time
/// ([`LatticeOde::striker_contact_time_s`]). The exact flow would let a step grow without bound
/// while the contacts are open; a contact that closes and opens again between two of a step's
/// nodes would then go unseen.
const MAX_STEP_OF_CONTACT_TIME: f64 = 0.25;
/// Under a blast or a drive (no striker), the speed \[m/s\] at which the shortest Hertz contact
/// time of the lattice's contacts is taken ([`LatticeOde::contact_time_s`]): the time grows as
/// the speed falls (∝ v^{−1/5}), so slower contacts are only longer than the step limit assumes.
const LOAD_CONTACT_SPEED_M_S: f64 = 1.0;

/// What a step of size h needs of one frequency ω (z = hω): per node σ = c₁, c₂, 1 the free
/// motion cos(σz), h sin(σz)/z and the response h² S_n(σ, z) to σⁿ; at the end the velocity's
/// −(z/h) sin z and h C_n(1, z); the error weights h² Σ E_n S_n(1, z), h Σ E_n C_n(1, z). A
/// damped mode (damping rate 2γ > 0) has the damped kernels' ([`damped_kernel`]) in their
/// places: `cos` the position's response to the position, `vel_of_vel` the velocity's to the
/// velocity (cos z undamped).
#[derive(Debug, Clone, Copy, Default)]
struct FrequencyWeights {
    cos: [f64; 3],
    hsinc: [f64; 3],
    pos: [[f64; 4]; 3],
    vel_of_pos: f64,
    vel_of_vel: f64,
    vel: [f64; 4],
    err_pos: f64,
    err_vel: f64,
}

impl FrequencyWeights {
    fn new(h: f64, omega: f64, rate: f64) -> Self {
        let c = nodes();
        if rate > 0.0 {
            let (a, z) = (0.5 * rate * h, h * omega);
            let k: [DampedKernel; 3] = [
                damped_kernel(c[1], a, z),
                damped_kernel(c[2], a, z),
                damped_kernel(1.0, a, z),
            ];
            let end = &k[2];
            return FrequencyWeights {
                cos: k.map(|k| k.pos_of_pos),
                hsinc: k.map(|k| h * k.pos_of_rate),
                pos: k.map(|k| k.s.map(|s| h * h * s)),
                vel_of_pos: end.rate_of_pos / h,
                vel_of_vel: end.rate_of_rate,
                vel: end.c.map(|c| h * c),
                err_pos: h * h * (0..4).map(|n| ERROR_POLY[n] * end.s[n]).sum::<f64>(),
                err_vel: h * (0..4).map(|n| ERROR_POLY[n] * end.c[n]).sum::<f64>(),
            };
        }
        let k: [Kernel; 3] = [
            kernel(c[1], h * omega),
            kernel(c[2], h * omega),
            kernel(1.0, h * omega),
        ];
        let end = &k[2];
        FrequencyWeights {
            cos: k.map(|k| k.cos),
            hsinc: k.map(|k| h * k.sinc),
            pos: k.map(|k| k.s.map(|s| h * h * s)),
            vel_of_pos: -end.zsin / h,
            vel_of_vel: end.cos,
            vel: end.c.map(|c| h * c),
            err_pos: h * h * (0..4).map(|n| ERROR_POLY[n] * end.s[n]).sum::<f64>(),
            err_vel: h * (0..4).map(|n| ERROR_POLY[n] * end.c[n]).sum::<f64>(),
        }
    }
}

/// One mode's flow at θ of a step (from [`kernel`] or [`damped_kernel`]): position from
/// position and from h × velocity, h × velocity from position and from h × velocity, and the
/// responses S_n, C_n.
struct FlowAt {
    pp: f64,
    pv: f64,
    vp: f64,
    vv: f64,
    s: [f64; 4],
    c: [f64; 4],
}

impl FlowAt {
    fn new(theta: f64, h: f64, omega: f64, rate: f64) -> Self {
        if rate > 0.0 {
            let k = damped_kernel(theta, 0.5 * rate * h, h * omega);
            FlowAt {
                pp: k.pos_of_pos,
                pv: k.pos_of_rate,
                vp: k.rate_of_pos,
                vv: k.rate_of_rate,
                s: k.s,
                c: k.c,
            }
        } else {
            let k = kernel(theta, h * omega);
            FlowAt {
                pp: k.cos,
                pv: k.sinc,
                vp: -k.zsin,
                vv: k.cos,
                s: k.s,
                c: k.c,
            }
        }
    }
}

/// An attempt's error at one point of a contact.
#[derive(Debug, Clone, Copy, Default)]
struct PointError {
    position: f64,
    velocity: f64,
    x: f64,
    v: f64,
}

impl PointError {
    /// The squared errors of position and velocity against their scales, summed.
    fn norm2(&self, rtol: f64, atol: f64) -> f64 {
        let sx = atol + rtol * self.x.abs();
        let sv = atol * VELOCITY_UNIT + rtol * self.v.abs();
        (self.position / sx).powi(2) + (self.velocity / sv).powi(2)
    }
}

/// The stepper of a lattice's run.
#[derive(Debug, Clone)]
pub(crate) struct GraphModalIntegrator {
    ode: LatticeOde,
    /// The distinct (frequency \[rad/s\], damping rate 2γ \[1/s\]) pairs and each coordinate's
    /// index into them.
    frequencies: Vec<(f64, f64)>,
    frequency_index: Vec<usize>,
    rtol: f64,
    atol: f64,
    t: f64,
    t_prev: f64,
    h_last: f64,
    /// The state in [`LatticeOde`]'s layout, now and at the last step's start.
    y: Vec<f64>,
    y_prev: Vec<f64>,
    /// Per contact: its force's cubic over the last step (monomials in σ) \[N\].
    coef: Vec<[f64; 4]>,
    /// Per coordinate: the cubic of its modal force over the last step.
    modal_force: Vec<[f64; 4]>,
    /// Per contact: its overlap's cubic through the nodes of the last step (monomials in σ) \[m\].
    overlap_coef: Vec<[f64; 4]>,
    /// Where W and D_modes sit in the state (lab physics), and whether any mode is damped.
    lab: Option<usize>,
    damped: bool,
    /// The load's kinks \[s\], ascending: steps end on them, so that no step's cubic straddles one.
    kinks: Vec<f64>,
    /// Per coordinate: the constant modal force of gravity and a striker's preload \[N/√kg\]
    /// (zeros without).
    static_force: Vec<f64>,
    /// Per contact: force and overlap now, and the largest overlap at any node so far \[m\].
    force: Vec<f64>,
    largest_overlap: Vec<f64>,
    overlap: Vec<f64>,
    control: StepControl,
    /// The longest step \[s\]: a quarter of the striker's Hertz contact time.
    max_step_s: f64,
    ladder: Ladder<Vec<FrequencyWeights>>,
    lagrange: [[f64; 4]; 4],
    stats: IntegratorStats,
    sc: Scratch,
}

/// Buffers of an attempt.
#[derive(Debug, Clone, Default)]
struct Scratch {
    /// Per node σ = c₁, c₂, 1 and coordinate: the free (force-less) motion.
    free: [Vec<f64>; 3],
    /// Per node and coordinate: the response to the modal forces' cubics.
    forced: [Vec<f64>; 3],
    /// Per coordinate: the cubic of its modal force.
    modal_force: Vec<[f64; 4]>,
    /// Per contact and node 1..3: the free overlap.
    free_overlap: Vec<[f64; 3]>,
    /// Per contact and node 0..3: force and overlap.
    node_force: Vec<[f64; 4]>,
    node_overlap: Vec<[f64; 4]>,
    coef: Vec<[f64; 4]>,
}

impl GraphModalIntegrator {
    /// A stepper for the lattice `ode` from its initial state over `duration_s`, with
    /// tolerances rtol and atol \[m\] on the contacts' points. The first step tried is a
    /// hundredth of the longest (of the run, if shorter): the steps do not depend on how the
    /// run is sampled, so a design study's runs, which take one sample, give `simulate`'s bits.
    pub fn new(ode: &LatticeOde, rtol: f64, atol: f64, duration_s: f64) -> Self {
        let max_step_s = MAX_STEP_OF_CONTACT_TIME * ode.contact_time_s(LOAD_CONTACT_SPEED_M_S);
        let h0 = 0.01 * max_step_s.min(duration_s);
        let q = ode.coordinates();
        let rates = ode
            .damping_rates()
            .map_or_else(|| vec![0.0; q], |r| r.to_vec());
        let (mut frequencies, mut frequency_index) = (Vec::new(), Vec::with_capacity(q));
        for (&w2, &rate) in ode.omega2.iter().zip(&rates) {
            let key = (w2.sqrt(), rate);
            let index = frequencies
                .iter()
                .position(|&f| f == key)
                .unwrap_or_else(|| {
                    frequencies.push(key);
                    frequencies.len() - 1
                });
            frequency_index.push(index);
        }
        let n = ode.contacts();
        let y = ode.initial_state();
        let mut ode = ode.clone();
        ode.contact_forces(&y[..q]);
        for c in 0..ode.load_contacts() {
            ode.force_n[c] = ode.load_per_point_n(0.0);
        }
        let per_node = || [vec![0.0; q], vec![0.0; q], vec![0.0; q]];
        GraphModalIntegrator {
            frequencies,
            frequency_index,
            rtol,
            atol,
            t: 0.0,
            t_prev: 0.0,
            h_last: 0.0,
            y_prev: y.clone(),
            y,
            coef: vec![[0.0; 4]; n],
            modal_force: vec![[0.0; 4]; q],
            overlap_coef: vec![[0.0; 4]; n],
            lab: ode.has_lab().then_some(2 * (q + 3)),
            damped: rates.iter().any(|&r| r > 0.0),
            kinks: ode.load_kinks_s(),
            static_force: ode
                .static_modal_forces()
                .map_or_else(|| vec![0.0; q], |f| f.to_vec()),
            force: ode.force_n.clone(),
            largest_overlap: ode.overlap_m.iter().map(|d| d.max(0.0)).collect(),
            overlap: ode.overlap_m.clone(),
            control: StepControl::new(h0),
            max_step_s,
            ladder: Ladder::default(),
            lagrange: lagrange(),
            stats: IntegratorStats {
                rhs_evaluations: 1,
                ..IntegratorStats::default()
            },
            sc: Scratch {
                free: per_node(),
                forced: per_node(),
                modal_force: vec![[0.0; 4]; q],
                free_overlap: vec![[0.0; 3]; n],
                node_force: vec![[0.0; 4]; n],
                node_overlap: vec![[0.0; 4]; n],
                coef: vec![[0.0; 4]; n],
            },
            ode,
        }
    }

    pub fn t(&self) -> f64 {
        self.t
    }

    /// The state now, in [`LatticeOde`]'s layout.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    pub fn stats(&self) -> IntegratorStats {
        self.stats
    }

    /// One accepted step toward t_end (or the load's next kink before it); returns its size.
    pub fn step(&mut self, t_end: f64) -> Result<f64> {
        let t = self.t;
        let kink = self.kinks.iter().find(|&&k| k - t > 1e-12 * k).copied();
        adaptive_step(self, kink.map_or(t_end, |k| k.min(t_end)))
    }

    /// The overlap of contact c for coordinates `x` \[m\].
    fn overlap_of(&self, c: usize, x: &[f64]) -> f64 {
        let o = &self.ode;
        let mut d = o.above[c].dot(&o.rows, x);
        if let Some(b) = o.below[c] {
            d -= b.dot(&o.rows, x);
        }
        d
    }

    /// The attempt's free motion at the nodes and the first guess of the node forces (the last
    /// step's cubics continued; constant at the start).
    fn start_attempt(&mut self, h: f64, weights: &[FrequencyWeights]) {
        let q = self.frequency_index.len();
        let c_nodes = nodes();
        let (x, v) = (&self.y[..q], &self.y[q + 3..2 * q + 3]);
        for j in 0..3 {
            for m in 0..q {
                let w = &weights[self.frequency_index[m]];
                self.sc.free[j][m] = w.cos[j] * x[m] + w.hsinc[j] * v[m];
            }
        }
        for c in 0..self.force.len() {
            let free = [0, 1, 2].map(|j| self.overlap_of(c, &self.sc.free[j]));
            self.sc.free_overlap[c] = free;
            self.sc.node_overlap[c][0] = self.overlap[c];
            let f = &mut self.sc.node_force[c];
            f[0] = self.force[c];
            for j in 1..4 {
                f[j] = if self.h_last > 0.0 {
                    let s = 1.0 + c_nodes[j] * h / self.h_last;
                    let a = &self.coef[c];
                    ((a[3] * s + a[2]) * s + a[1]) * s + a[0]
                } else {
                    self.force[c]
                };
            }
        }
        for c in 0..self.ode.load_contacts() {
            for (f, s) in self.sc.node_force[c].iter_mut().zip(c_nodes).skip(1) {
                *f = self.ode.load_per_point_n(self.t + s * h);
            }
        }
    }

    /// Each contact's cubic from its node forces, and each coordinate's modal force cubic.
    fn cubics(&mut self) {
        let o = &self.ode;
        let sc = &mut self.sc;
        for (b, &f) in sc.modal_force.iter_mut().zip(&self.static_force) {
            *b = [f, 0.0, 0.0, 0.0];
        }
        for (c, (a, f)) in sc.coef.iter_mut().zip(&sc.node_force).enumerate() {
            for (an, l) in a.iter_mut().zip(&self.lagrange) {
                *an = (0..4).map(|j| l[j] * f[j]).sum();
            }
            if f.iter().all(|&x| x == 0.0) {
                continue;
            }
            let mut add = |side: crate::ode::Side, sign: f64| {
                let rows = &o.rows[side.row..side.row + side.len];
                let b = &mut sc.modal_force[side.offset..side.offset + side.len];
                for (bm, r) in b.iter_mut().zip(rows) {
                    for n in 0..4 {
                        bm[n] += sign * r * a[n];
                    }
                }
            };
            add(o.above[c], -1.0);
            if let Some(below) = o.below[c] {
                add(below, 1.0);
            }
        }
    }

    /// The fixed-point iteration of the collocation conditions: node forces → cubics → node
    /// overlaps → node forces. False when it did not converge.
    fn solve_nodes(&mut self, weights: &[FrequencyWeights]) -> bool {
        let q = self.frequency_index.len();
        for _ in 0..MAX_ITERATIONS {
            self.cubics();
            for j in 0..3 {
                for m in 0..q {
                    let w = &weights[self.frequency_index[m]].pos[j];
                    let b = &self.sc.modal_force[m];
                    self.sc.forced[j][m] = w[0] * b[0] + w[1] * b[1] + w[2] * b[2] + w[3] * b[3];
                }
            }
            let (mut change, mut scale) = (0.0_f64, 0.0_f64);
            let loads = self.ode.load_contacts();
            for c in 0..self.force.len() {
                let beta = self.ode.beta[c];
                for j in 0..3 {
                    let d = self.sc.free_overlap[c][j] + self.overlap_of(c, &self.sc.forced[j]);
                    if c < loads {
                        // A load point's force is prescribed; its overlap is minus its deflection.
                        self.sc.node_overlap[c][j + 1] = d;
                        continue;
                    }
                    let f = ContactLaw::elastic_force(beta, d);
                    if !f.is_finite() {
                        return false;
                    }
                    change = change.max((f - self.sc.node_force[c][j + 1]).abs());
                    scale = scale.max(f.abs());
                    self.sc.node_force[c][j + 1] = f;
                    self.sc.node_overlap[c][j + 1] = d;
                }
            }
            self.stats.rhs_evaluations += 3;
            if change <= (FIXED_POINT_TOLERANCE * self.rtol).max(1e-13) * scale || scale == 0.0 {
                self.cubics();
                return true;
            }
        }
        false
    }

    /// The error norm of the solved attempt, the larger of two tests over the loaded contacts:
    /// at each of a contact's points, the σ³ part's effect on its position and velocity against
    /// atol + rtol |x| (the position at the step's end) and atol/τ + rtol |v| (the velocity at
    /// its start); and on the contact's overlap, against atol + rtol δ_max / 1.5 with δ_max its
    /// largest overlap so far (a point can move far more than a contact deep in the lattice is
    /// compressed, and a peak force's relative error is 1.5 times its overlap's).
    fn error_norm(&self, weights: &[FrequencyWeights]) -> f64 {
        let o = &self.ode;
        let (mut worst_point, mut worst_force) = (0.0_f64, 0.0_f64);
        for c in 0..self.force.len() {
            let f = &self.sc.node_force[c];
            if f.iter().all(|&f| f == 0.0) {
                continue;
            }
            let above = self.point_error(o.above[c], weights);
            worst_point = worst_point.max(above.norm2(self.rtol, self.atol));
            let mut overlap_error = above.position;
            if let Some(b) = o.below[c] {
                let below = self.point_error(b, weights);
                worst_point = worst_point.max(below.norm2(self.rtol, self.atol));
                overlap_error -= below.position;
            }
            if c < self.ode.load_contacts() {
                // A load point's force is prescribed: only its point's error counts.
                continue;
            }
            // F ∝ δ^{3/2}: a relative error ε of the overlap at the peak is 1.5 ε of the force.
            let largest = self.sc.node_overlap[c]
                .iter()
                .fold(self.largest_overlap[c], |m, &d| m.max(d));
            let scale = self.atol + self.rtol * largest / 1.5;
            worst_force = worst_force.max(overlap_error.abs() / scale);
        }
        (0.5 * worst_point).sqrt().max(worst_force)
    }

    /// The σ³ part's effect on a point's position and velocity, and the point's position at the
    /// step's end and velocity at its start.
    fn point_error(&self, side: crate::ode::Side, weights: &[FrequencyWeights]) -> PointError {
        let q = self.frequency_index.len();
        let v = &self.y[q + 3..2 * q + 3];
        let mut e = PointError::default();
        for k in 0..side.len {
            let (m, r) = (side.offset + k, self.ode.rows[side.row + k]);
            let w = &weights[self.frequency_index[m]];
            let b3 = self.sc.modal_force[m][3];
            e.position += r * w.err_pos * b3;
            e.velocity += r * w.err_vel * b3;
            e.x += r * (self.sc.free[2][m] + self.sc.forced[2][m]);
            e.v += r * v[m];
        }
        e
    }

    /// The weights of the step h (a rung's, or off the ladder).
    fn weights(&mut self, h: f64, rung: Option<i64>) -> Vec<FrequencyWeights> {
        let frequencies = &self.frequencies;
        self.ladder.ensure(h, rung, || {
            frequencies
                .iter()
                .map(|&(w, rate)| FrequencyWeights::new(h, w, rate))
                .collect()
        });
        self.ladder.get(rung).clone()
    }

    /// The state at ts inside the last step (the exact flow under the step's cubics) into y.
    pub fn observe_at(&self, ts: f64, out: &mut [f64]) {
        let h = self.h_last;
        if ts >= self.t || h == 0.0 {
            out.copy_from_slice(&self.y);
            return;
        }
        let theta = ((ts - self.t_prev) / h).clamp(0.0, 1.0);
        let kernels: Vec<FlowAt> = self
            .frequencies
            .iter()
            .map(|&(w, rate)| FlowAt::new(theta, h, w, rate))
            .collect();
        let q = self.frequency_index.len();
        let (x0, v0) = (&self.y_prev[..q], &self.y_prev[q + 3..2 * q + 3]);
        for m in 0..q {
            let k = &kernels[self.frequency_index[m]];
            let b = &self.modal_force[m];
            let sb: f64 = (0..4).map(|n| k.s[n] * b[n]).sum();
            let cb: f64 = (0..4).map(|n| k.c[n] * b[n]).sum();
            out[m] = k.pp * x0[m] + h * k.pv * v0[m] + h * h * sb;
            out[q + 3 + m] = k.vp / h * x0[m] + k.vv * v0[m] + h * cb;
        }
        self.supports_flow(theta, h, &self.y_prev, out);
        self.work_and_dissipation(theta, &self.coef, &self.overlap_coef, out);
    }

    /// W and D_modes at θ of the step from the last step's start into `out` (which holds the
    /// modes at θ), with lab physics. W: the load points' forces' work, −∫ a_c p_c' over their
    /// cubics (force a_c, overlap p_c: minus the point's deflection). D_modes, if any mode is
    /// damped: the modes' energy balance, D = −ΔE_modes + Σ_c −∫ a_c p_c' (every mode is
    /// advanced exactly under the cubics, so the energy the modes lost beyond the work the
    /// contacts' cubics did on them is what their damping took); docs/physics.md §8.
    fn work_and_dissipation(
        &self,
        theta: f64,
        coef: &[[f64; 4]],
        overlap_coef: &[[f64; 4]],
        out: &mut [f64],
    ) {
        let Some(i) = self.lab else { return };
        let loads = self.ode.load_contacts();
        let (mut w_loads, mut w_all) = (0.0, 0.0);
        for (c, (a, p)) in coef.iter().zip(overlap_coef).enumerate() {
            if a.iter().all(|&x| x == 0.0) {
                continue;
            }
            let w = contact_work(a, p, theta);
            w_all += w;
            if c < loads {
                w_loads += w;
            }
        }
        // Gravity's and a striker's preload's constant modal forces: their work is f Δq.
        let w_static: f64 = self
            .static_force
            .iter()
            .zip(out.iter().zip(&self.y_prev))
            .map(|(f, (q1, q0))| f * (q1 - q0))
            .sum();
        out[i] = self.y_prev[i] + w_loads + w_static;
        out[i + 1] = if self.damped {
            let e0 = modal_energy_j(&self.y_prev, &self.ode.omega2);
            let e1 = modal_energy_j(out, &self.ode.omega2);
            self.y_prev[i + 1] - (e1 - e0) + w_all + w_static
        } else {
            self.y_prev[i + 1]
        };
    }

    /// The supports' impulses J and their integrals ∫J dt at θ of a step of size h from `from`
    /// (the support forces' cubics of that step) into `out`.
    fn supports_flow(&self, theta: f64, h: f64, from: &[f64], out: &mut [f64]) {
        let q = self.frequency_index.len();
        let (mut dj, mut djint) = ([0.0; 3], [0.0; 3]);
        for &(c, dx, dy) in &self.ode.supports {
            let a = &self.coef[c];
            let (mut i1, mut i2) = (0.0, 0.0);
            let mut pw = theta;
            for (n, an) in a.iter().enumerate() {
                let n1 = (n + 1) as f64;
                i1 += an * pw / n1;
                i2 += an * pw * theta / (n1 * (n1 + 1.0));
                pw *= theta;
            }
            for (k, arm) in [1.0, dx, dy].iter().enumerate() {
                dj[k] += arm * h * i1;
                djint[k] += arm * h * h * i2;
            }
        }
        for k in 0..3 {
            let j0 = from[2 * q + 3 + k];
            out[2 * q + 3 + k] = j0 + dj[k];
            out[q + k] = from[q + k] + theta * h * j0 + djint[k];
        }
    }
}

impl ExactStepper for GraphModalIntegrator {
    fn control(&mut self) -> (&mut StepControl, &mut IntegratorStats) {
        (&mut self.control, &mut self.stats)
    }

    fn now(&self) -> f64 {
        self.t
    }

    fn max_step(&self) -> f64 {
        self.max_step_s
    }

    fn attempt(&mut self, h: f64, rung: Option<i64>) -> Attempt {
        let weights = self.weights(h, rung);
        self.start_attempt(h, &weights);
        let converged = self.solve_nodes(&weights);
        let err = match converged.then(|| self.error_norm(&weights)) {
            Some(e) if e.is_finite() => e,
            _ => f64::INFINITY,
        };
        let missed = if err <= 1.0 {
            first_crossing(&self.sc.node_overlap, &self.ode.beta, &nodes()).map(|theta| theta * h)
        } else {
            None
        };
        Attempt { err, missed }
    }

    fn commit(&mut self, h: f64, rung: Option<i64>) {
        std::mem::swap(&mut self.y, &mut self.y_prev);
        let q = self.frequency_index.len();
        let weights = self.ladder.get(rung);
        let (x0, v0) = (&self.y_prev[..q], &self.y_prev[q + 3..2 * q + 3]);
        let (x1, rest) = self.y.split_at_mut(q + 3);
        let v1 = &mut rest[..q];
        for m in 0..q {
            let w = &weights[self.frequency_index[m]];
            let b = &self.sc.modal_force[m];
            let p = &w.pos[2];
            x1[m] = w.cos[2] * x0[m]
                + w.hsinc[2] * v0[m]
                + (p[0] * b[0] + p[1] * b[1] + p[2] * b[2] + p[3] * b[3]);
            v1[m] = w.vel_of_pos * x0[m]
                + w.vel_of_vel * v0[m]
                + (w.vel[0] * b[0] + w.vel[1] * b[1] + w.vel[2] * b[2] + w.vel[3] * b[3]);
        }
        self.coef.copy_from_slice(&self.sc.coef);
        self.modal_force.copy_from_slice(&self.sc.modal_force);
        let mut y = std::mem::take(&mut self.y);
        self.supports_flow(1.0, h, &self.y_prev, &mut y);
        if self.lab.is_some() {
            for (p, d) in self.overlap_coef.iter_mut().zip(&self.sc.node_overlap) {
                for (pn, l) in p.iter_mut().zip(&self.lagrange) {
                    *pn = (0..4).map(|j| l[j] * d[j]).sum();
                }
            }
            self.work_and_dissipation(1.0, &self.sc.coef, &self.overlap_coef, &mut y);
        }
        self.y = y;
        for c in 0..self.force.len() {
            let d = &self.sc.node_overlap[c];
            self.force[c] = self.sc.node_force[c][3];
            self.overlap[c] = d[3];
            self.largest_overlap[c] = d.iter().fold(self.largest_overlap[c], |m, &x| m.max(x));
        }
        self.h_last = h;
        self.t_prev = self.t;
        self.t += h;
    }
}

/// −∫₀^θ a(σ) p'(σ) dσ for a force cubic a and an overlap cubic p (monomials in σ) \[J\]: the
/// work a contact's force does on the bodies over the first θ of a step.
fn contact_work(a: &[f64; 4], p: &[f64; 4], theta: f64) -> f64 {
    let mut w = 0.0;
    for (n, an) in a.iter().enumerate() {
        for (k, pk) in p.iter().enumerate().skip(1) {
            let e = (n + k) as i32;
            w += an * k as f64 * pk * theta.powi(e) / f64::from(e);
        }
    }
    -w
}

/// The modes' kinetic and strain energy Σ ½ (q̇² + ω² q²) of a state \[J\].
fn modal_energy_j(y: &[f64], omega2: &[f64]) -> f64 {
    let q = omega2.len();
    (0..q)
        .map(|j| 0.5 * (y[q + 3 + j] * y[q + 3 + j] + omega2[j] * y[j] * y[j]))
        .sum()
}
