//! [`Method::ExactModes`](super::Method::ExactModes) on a contact graph (a lattice,
//! docs/physics.md §16 and §8 "Exact linear vibrations"): every body moves in mass-normalised
//! modal coordinates, q̈_m = −ω_m² q_m + Σ_c r_cm F_c, so the linear part is diagonal. Over a
//! step each contact force F_c is replaced by its cubic through the four Lobatto nodes, every
//! mode is advanced against the cubic its contacts exert (Σ_c ∓r_cm a_c, [`super::exponential`])
//! exactly, and the node forces are found by fixed-point iteration on the contacts' overlaps.
//! Contacts at one point of a body share it, and a body's modes that no point moves are left
//! out ([`layout`]); on the ladder's steps the iteration runs through the points' influence on
//! each other over the step ([`influence`]), not through the modes.
//!
//! The embedded error estimate is that of the chain's stepper (the cubic's σ³ part against the
//! quadratic through 0, ½, 1), mapped from the modes to the two points of every loaded contact
//! and to its force; its norm is the largest over those, not their mean, so that one active
//! contact among hundreds at rest is held to the tolerance. A step in which a contact opens or closes is
//! retaken to end there; samples inside a step are the exact flow at their time.
//!
//! The passes over the modes run four modes per vector ([`Layout`]): each body's modes padded
//! to whole groups of four with massless modes at rest (zero weights, zero rows), the step's
//! weights stored per group of each distinct body's modes, a body at rest under no force passed
//! over, and the step compiled with AVX2 where the CPU has it (no FMA contraction: bit for bit
//! the portable build's results, claim `simd_step_bit_identical`).

use super::exponential::{lagrange, nodes, work_of_cubics, Flow, ERROR_POLY};
use super::modal_step::{
    adaptive_step, first_crossing, Attempt, ExactStepper, Ladder, FIXED_POINT_TOLERANCE,
    LOAD_CONTACT_SPEED_M_S, MAX_ITERATIONS, MAX_STEP_OF_CONTACT_TIME, VELOCITY_UNIT,
};
use super::{IntegratorStats, StepControl};
use crate::error::Result;
use crate::model::ContactLaw;
use crate::ode::LatticeOde;
use crate::real::{Lane, Real};
use influence::Influence;
use layout::Layout;

mod influence;
mod layout;

/// The weights of one step size: per group of each kind's modes, and (a rung of the ladder's)
/// the influence of every family's points on each other.
#[derive(Debug, Clone)]
struct StepWeights {
    groups: Vec<WeightGroup>,
    influence: Option<Influence>,
    /// With the influence and static forces: each point's deflection at the nodes under the
    /// static modal forces alone (else empty).
    point_static: Vec<[f64; 3]>,
}

/// Each point's deflection at the nodes of a step (weights `groups`) under the static modal
/// forces alone (`statics`: per group the forces, per body whether any acts).
fn static_deflections(
    layout: &Layout,
    (static_groups, static_loaded): (&[V], &[bool]),
    groups: &[WeightGroup],
) -> Vec<[f64; 3]> {
    let mut response = vec![[V::ZERO; 3]; layout.groups];
    for (b, _) in layout.bodies.iter().zip(static_loaded).filter(|s| *s.1) {
        let (g, k) = (b.group..b.group + b.groups, b.kind..b.kind + b.groups);
        let forces = static_groups[g.clone()].iter().zip(&groups[k]);
        for (x, (&f, w)) in response[g].iter_mut().zip(forces) {
            *x = [w.pos[0][0] * f, w.pos[1][0] * f, w.pos[2][0] * f];
        }
    }
    let mut out = vec![[0.0; 3]; layout.points.len()];
    layout.deflections3(&response, static_loaded, &mut out);
    out
}

/// Four modes at once, as [`Lane`] values (the form that runs in vectors).
type V = Lane<4>;

/// What a step of size h needs of one frequency ω (z = hω): per node σ = c₁, c₂, 1 the free
/// motion cos(σz), h sin(σz)/z and the response h² S_n(σ, z) to σⁿ; at the end the velocity's
/// −(z/h) sin z and h C_n(1, z); the error weights h² Σ E_n S_n(1, z), h Σ E_n C_n(1, z). A
/// damped mode (damping rate 2γ > 0) has the damped kernels' ([`Flow`]) in their
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
        let k = Flow::at_nodes(h, omega, rate);
        let end = &k[2];
        FrequencyWeights {
            cos: k.map(|k| k.pos_of_pos),
            hsinc: k.map(|k| h * k.pos_of_rate),
            pos: k.map(|k| k.s.map(|s| h * h * s)),
            vel_of_pos: end.rate_of_pos / h,
            vel_of_vel: end.rate_of_rate,
            vel: end.c.map(|c| h * c),
            err_pos: h * h * (0..4).map(|n| ERROR_POLY[n] * end.s[n]).sum::<f64>(),
            err_vel: h * (0..4).map(|n| ERROR_POLY[n] * end.c[n]).sum::<f64>(),
        }
    }
}

/// [`FrequencyWeights`] of a group of four modes (a padding mode's all zero), as [`Lane`]
/// values.
#[derive(Debug, Clone, Copy, Default)]
struct WeightGroup {
    cos: [V; 3],
    hsinc: [V; 3],
    pos: [[V; 4]; 3],
    vel_of_pos: V,
    vel_of_vel: V,
    vel: [V; 4],
    err_pos: V,
    err_vel: V,
}

impl WeightGroup {
    /// The weights of step h for the modes (frequency \[rad/s\], damping rate 2γ \[1/s\]) of a
    /// group; None: padding.
    fn new(h: f64, modes: &[Option<(f64, f64)>; 4]) -> Self {
        let mut g = WeightGroup::default();
        for (l, mode) in modes.iter().enumerate() {
            let Some((omega, rate)) = *mode else { continue };
            let w = FrequencyWeights::new(h, omega, rate);
            for j in 0..3 {
                g.cos[j].0[l] = w.cos[j];
                g.hsinc[j].0[l] = w.hsinc[j];
                for n in 0..4 {
                    g.pos[j][n].0[l] = w.pos[j][n];
                }
            }
            for n in 0..4 {
                g.vel[n].0[l] = w.vel[n];
            }
            g.vel_of_pos.0[l] = w.vel_of_pos;
            g.vel_of_vel.0[l] = w.vel_of_vel;
            g.err_pos.0[l] = w.err_pos;
            g.err_vel.0[l] = w.err_vel;
        }
        g
    }
}

/// The flows at θ of a group of four modes (a padding lane's all zero), from their [`Flow`]s with
/// the step's factors of h: position from velocity h × the kernel's, velocity from position the
/// kernel's / h, the responses S_n, C_n times h², h.
#[derive(Debug, Clone, Copy, Default)]
struct FlowGroup {
    pp: V,
    pv: V,
    vp: V,
    vv: V,
    s: [V; 4],
    c: [V; 4],
}

impl FlowGroup {
    /// The group whose lanes are the frequencies `lanes` (indices into `kernels`; `usize::MAX`:
    /// padding) of a step h.
    fn new(lanes: &[usize; 4], kernels: &[Flow], h: f64) -> Self {
        let mut g = FlowGroup::default();
        for (l, &f) in lanes.iter().enumerate() {
            let Some(k) = kernels.get(f) else { continue };
            (g.pp.0[l], g.pv.0[l]) = (k.pos_of_pos, h * k.pos_of_rate);
            (g.vp.0[l], g.vv.0[l]) = (k.rate_of_pos / h, k.rate_of_rate);
            for n in 0..4 {
                g.s[n].0[l] = h * h * k.s[n];
                g.c[n].0[l] = h * k.c[n];
            }
        }
        g
    }

    /// Positions and velocities at θ from (x0, v0) at the step's start under the modal force
    /// cubic b.
    #[inline(always)]
    fn flow(&self, x0: V, v0: V, b: &[V; 4]) -> (V, V) {
        let (s, c) = (&self.s, &self.c);
        (
            self.pp * x0 + self.pv * v0 + (s[0] * b[0] + s[1] * b[1] + s[2] * b[2] + s[3] * b[3]),
            self.vp * x0 + self.vv * v0 + (c[0] * b[0] + c[1] * b[1] + c[2] * b[2] + c[3] * b[3]),
        )
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
    /// The distinct (frequency \[rad/s\], damping rate 2γ \[1/s\]) pairs of the carried modes,
    /// and per group of each kind's modes each lane's index into them (`usize::MAX`: padding),
    /// for the samples inside a step.
    frequencies: Vec<(f64, f64)>,
    kind_frequencies: Vec<[usize; 4]>,
    /// The coordinates in groups of four.
    layout: Layout,
    rtol: f64,
    atol: f64,
    t: f64,
    t_prev: f64,
    h_last: f64,
    /// The state in [`LatticeOde`]'s layout, now and at the last step's start: the supports'
    /// impulses and their integrals, W and D always; the modes only where `y_fresh` (scattered
    /// from the groups when the state is asked for) — a mode left out stays at rest there.
    y: Vec<f64>,
    y_prev: Vec<f64>,
    y_fresh: bool,
    /// The modal positions and velocities now and at the last step's start, in groups.
    x: Vec<V>,
    v: Vec<V>,
    x_prev: Vec<V>,
    v_prev: Vec<V>,
    /// Per body: whether it has moved (a body at rest, under no force, stays at rest and is
    /// passed over), and whether a static force acts on it.
    moving: Vec<bool>,
    static_loaded: Vec<bool>,
    /// Per contact: its force's cubic over the last step (monomials in σ) \[N\].
    coef: Vec<[f64; 4]>,
    /// Per group: the cubic of its modal force over the last step.
    modal_force: Vec<[V; 4]>,
    /// Per contact: its overlap's cubic through the nodes of the last step (monomials in σ) \[m\].
    overlap_coef: Vec<[f64; 4]>,
    /// Where W and D_modes sit in the state (lab physics), and whether any mode is damped.
    lab: Option<usize>,
    damped: bool,
    /// With damped modes: their energy Σ ½ (q̇² + ω² q²) at the run's start \[J\], and
    /// S = D_modes + E_modes − E_modes(0), the contacts' and static forces' work on the modes
    /// summed step by step, at the last step's start and now \[J\]: D_modes is formed from S
    /// only where the state is read (the modes' energy then once, not every step).
    modal_energy_j: f64,
    work_sums_j: [f64; 2],
    /// The load's kinks \[s\], ascending: steps end on them, so that no step's cubic straddles one.
    kinks: Vec<f64>,
    /// Per group: the constant modal force of gravity and a striker's preload \[N/√kg\]
    /// (zeros without).
    static_groups: Vec<V>,
    /// Per point: its deflection and its rate now \[m, m/s\].
    point_end: Vec<[f64; 2]>,
    /// Per contact: force and overlap now, and the largest overlap at any node so far \[m\].
    force: Vec<f64>,
    largest_overlap: Vec<f64>,
    overlap: Vec<f64>,
    control: StepControl,
    /// The longest step \[s\]: a quarter of the striker's Hertz contact time.
    max_step_s: f64,
    /// Per step size: the weights of every group of the distinct bodies' modes.
    ladder: Ladder<StepWeights>,
    lagrange: [[f64; 4]; 4],
    stats: IntegratorStats,
    sc: Scratch,
    /// Buffers of a sample inside a step.
    sample: Sample,
}

/// Buffers of a sample inside a step: each frequency's flow, each kind group's, the modes'
/// positions and velocities in groups, and the points' deflections.
#[derive(Debug, Clone, Default)]
struct Sample {
    kernels: Vec<Flow>,
    flows: Vec<FlowGroup>,
    x: Vec<V>,
    v: Vec<V>,
    /// Per point: its deflection and rate at the sample.
    points: Vec<[f64; 2]>,
}

/// Buffers of an attempt.
#[derive(Debug, Clone, Default)]
struct Scratch {
    /// Per group and node σ = c₁, c₂, 1: the free (force-less) motion.
    free: Vec<[V; 3]>,
    /// Per group and node: the response to the modal forces' cubics.
    forced: Vec<[V; 3]>,
    /// Per group: the cubic of its modal force (monomials in σ).
    modal_force: Vec<[V; 4]>,
    /// Per body: whether a force acts on it (its modal force is more than the static force; all
    /// true before the first pass), and whether its forced response is all zero.
    loaded: Vec<bool>,
    unforced: Vec<bool>,
    /// Per point and node σ = c₁, c₂, 1: its deflection in the free motion and in the forced
    /// response.
    point_free: Vec<[f64; 3]>,
    point_forced: Vec<[f64; 3]>,
    /// Per point: the net cubic of the forces on it (monomials in σ), its net forces at the
    /// nodes, and whether any acts.
    point_cubic: Vec<[f64; 4]>,
    point_force: Vec<[f64; 4]>,
    point_pushed: Vec<bool>,
    /// Per point: whether the error norm needs its error, and that error.
    point_needed: Vec<bool>,
    point_errors: Vec<PointError>,
    /// Per point (through the influence): the σ³ part's effect on its position and velocity.
    point_sigma3: Vec<[f64; 2]>,
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
        let n = ode.contacts();
        let y = ode.initial_state();
        let mut ode = ode.clone();
        ode.contact_forces(&y[..q]);
        for c in 0..ode.load_contacts() {
            ode.graph.force_n[c] = ode.load_per_point_n(0.0);
        }
        let static_force = ode
            .static_modal_forces()
            .map_or_else(|| vec![0.0; q], |f| f.to_vec());
        let start = [&y[..q], &y[q + 3..2 * q + 3], &static_force[..]];
        let layout = Layout::new(&ode, &rates, start);
        let (frequencies, kind_frequencies) = sample_frequencies(&layout);
        let groups = layout.groups;
        let grouped = |values: &[f64]| {
            let mut out = vec![V::ZERO; groups];
            layout.gather(values, &mut out);
            out
        };
        let (x, v, static_groups) = (
            grouped(&y[..q]),
            grouped(&y[q + 3..2 * q + 3]),
            grouped(&static_force),
        );
        let (moving, static_loaded) = (
            layout.nonzero_bodies(&[&x, &v]),
            layout.nonzero_bodies(&[&static_groups]),
        );
        let modal_energy_j = layout.modal_energy_j(&x, &v);
        let lab = ode.has_lab().then_some(2 * (q + 3));
        let work_sums_j = [lab.map_or(0.0, |i| y[i + 1]); 2];
        let mut me = GraphModalIntegrator {
            frequencies,
            kind_frequencies,
            moving,
            static_loaded,
            rtol,
            atol,
            t: 0.0,
            t_prev: 0.0,
            h_last: 0.0,
            y_prev: y.clone(),
            y_fresh: true,
            x_prev: x.clone(),
            v_prev: v.clone(),
            y,
            x,
            v,
            coef: vec![[0.0; 4]; n],
            modal_force: vec![[V::ZERO; 4]; groups],
            overlap_coef: vec![[0.0; 4]; n],
            lab,
            damped: rates.iter().any(|&r| r > 0.0),
            modal_energy_j,
            work_sums_j,
            kinks: ode.load_kinks_s(),
            static_groups,
            force: ode.graph.force_n.clone(),
            largest_overlap: ode.graph.overlap_m.iter().map(|d| d.max(0.0)).collect(),
            overlap: ode.graph.overlap_m.clone(),
            control: StepControl::new(h0),
            max_step_s,
            ladder: Ladder::default(),
            lagrange: lagrange(),
            stats: IntegratorStats {
                rhs_evaluations: 1,
                ..IntegratorStats::default()
            },
            sc: Scratch::new(groups, n, layout.bodies.len(), layout.points.len()),
            point_end: Vec::new(),
            sample: Sample::default(),
            layout,
            ode,
        };
        me.points_now();
        me
    }

    /// Every point's deflection and rate in the state now into `point_end`.
    #[inline(always)]
    fn points_now(&mut self) {
        let layout = &self.layout;
        self.point_end.resize(layout.points.len(), [0.0; 2]);
        for (p, end) in self.point_end.iter_mut().enumerate() {
            *end = layout.dot2(p, &self.x, &self.v, &self.moving);
        }
    }

    pub fn t(&self) -> f64 {
        self.t
    }

    /// The state now, in [`LatticeOde`]'s layout.
    pub fn y(&mut self) -> &[f64] {
        if !self.y_fresh {
            let q = self.ode.coordinates();
            let mut y = std::mem::take(&mut self.y);
            self.layout.scatter(&self.x, &mut y[..q]);
            self.layout.scatter(&self.v, &mut y[q + 3..2 * q + 3]);
            self.set_dissipation(self.work_sums_j[1], (&self.x, &self.v), &mut y);
            self.y = y;
            self.y_fresh = true;
        }
        &self.y
    }

    pub fn stats(&self) -> IntegratorStats {
        self.stats
    }

    super::exact_step_in_simd_build!();

    /// The same step without run-time SIMD dispatch (toward t_end, or the load's next kink
    /// before it): the reference the AVX2 build is checked against.
    #[inline(always)]
    pub fn step_portable(&mut self, t_end: f64) -> Result<f64> {
        let t = self.t;
        let kink = self.kinks.iter().find(|&&k| k - t > 1e-12 * k).copied();
        adaptive_step(self, kink.map_or(t_end, |k| k.min(t_end)))
    }

    /// The attempt's free motion at the nodes and the first guess of the node forces (the last
    /// step's cubics continued; constant at the start).
    #[inline(always)]
    fn start_attempt(&mut self, h: f64, step: &StepWeights) {
        let (c_nodes, weights) = (nodes(), &step.groups[..]);
        let sc = &mut self.sc;
        for (b, _) in self.layout.bodies.iter().zip(&self.moving).filter(|m| *m.1) {
            let (g, k) = (b.group..b.group + b.groups, b.kind..b.kind + b.groups);
            let state = self.x[g.clone()].iter().zip(&self.v[g.clone()]);
            for ((free, w), (&x, &v)) in sc.free[g].iter_mut().zip(&weights[k]).zip(state) {
                let at = |j: usize| w.cos[j] * x + w.hsinc[j] * v;
                *free = [at(0), at(1), at(2)];
            }
        }
        let layout = &self.layout;
        layout.deflections3(&sc.free, &self.moving, &mut sc.point_free);
        // The iteration through the influence leaves the static forces out: their response
        // (a constant cubic, the same every step of this size) joins the free motion.
        for (free, d) in sc.point_free.iter_mut().zip(&step.point_static) {
            for (x, dx) in free.iter_mut().zip(d) {
                *x += dx;
            }
        }
        for c in 0..self.force.len() {
            sc.free_overlap[c] = layout.overlap3(c, &sc.point_free);
            sc.node_overlap[c][0] = self.overlap[c];
            let f = &mut sc.node_force[c];
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
            for (f, s) in sc.node_force[c].iter_mut().zip(c_nodes).skip(1) {
                *f = self.ode.load_per_point_n(self.t + s * h);
            }
        }
    }

    /// Each contact's cubic from its node forces, and each group's modal force cubic.
    #[inline(always)]
    fn cubics(&mut self) {
        self.point_cubics();
        self.modal_forces();
    }

    /// Each group's modal force cubic from the points' net cubics ([`Self::point_cubics`]).
    #[inline(always)]
    fn modal_forces(&mut self) {
        let layout = &self.layout;
        let sc = &mut self.sc;
        // Back to the static force where a force acted in the last pass (elsewhere it is there).
        for (body, _) in layout.bodies.iter().zip(&sc.loaded).filter(|b| *b.1) {
            let g = body.group..body.group + body.groups;
            for (b, &f) in sc.modal_force[g.clone()]
                .iter_mut()
                .zip(&self.static_groups[g])
            {
                *b = [f, V::ZERO, V::ZERO, V::ZERO];
            }
        }
        sc.loaded.copy_from_slice(&self.static_loaded);
        // Each pushed point's net cubic on its body's modes through its row.
        for (p, point) in layout.points.iter().enumerate() {
            if !sc.point_pushed[p] {
                continue;
            }
            sc.loaded[point.body] = true;
            let rows = &layout.rows[point.row..point.row + point.groups];
            let b = &mut sc.modal_force[point.group..point.group + point.groups];
            let s = |n: usize| V::splat(sc.point_cubic[p][n]);
            let signed = [s(0), s(1), s(2), s(3)];
            for (bm, &r) in b.iter_mut().zip(rows) {
                for (bn, &an) in bm.iter_mut().zip(&signed) {
                    *bn = *bn + r * an;
                }
            }
        }
    }

    /// Each contact's cubic a from its node forces, and each point's net cubic: −a where the
    /// point is a contact's upper side (pushed up), +a where it is its lower side.
    #[inline(always)]
    fn point_cubics(&mut self) {
        let layout = &self.layout;
        let sc = &mut self.sc;
        sc.point_cubic.fill([0.0; 4]);
        sc.point_pushed.fill(false);
        for (c, (a, f)) in sc.coef.iter_mut().zip(&sc.node_force).enumerate() {
            for (an, l) in a.iter_mut().zip(&self.lagrange) {
                *an = (0..4).map(|j| l[j] * f[j]).sum();
            }
            if f.iter().all(|&x| x == 0.0) {
                continue;
            }
            // −a on the point above, +a below.
            for (p, sign) in [(layout.above[c], -1.0), (layout.below[c], 1.0)] {
                if let Some(p) = p {
                    sc.point_pushed[p] = true;
                    for (b, an) in sc.point_cubic[p].iter_mut().zip(a.iter()) {
                        *b += sign * an;
                    }
                }
            }
        }
    }

    /// Each point's net forces at the four nodes (−f where the point is a contact's upper side,
    /// +f where it is its lower side, as [`Self::point_cubics`]), and whether any acts.
    #[inline(always)]
    fn point_forces(&mut self) {
        let layout = &self.layout;
        let sc = &mut self.sc;
        sc.point_force.fill([0.0; 4]);
        sc.point_pushed.fill(false);
        for (c, f) in sc.node_force.iter().enumerate() {
            if f.iter().all(|&x| x == 0.0) {
                continue;
            }
            for (p, sign) in [(layout.above[c], -1.0), (layout.below[c], 1.0)] {
                if let Some(p) = p {
                    sc.point_pushed[p] = true;
                    for (b, fj) in sc.point_force[p].iter_mut().zip(f) {
                        *b += sign * fj;
                    }
                }
            }
        }
    }

    /// Each group's response at the nodes to its modal force's cubic.
    #[inline(always)]
    fn forced(&mut self, weights: &[WeightGroup]) {
        let sc = &mut self.sc;
        for (i, b) in self.layout.bodies.iter().enumerate() {
            let (g, k) = (b.group..b.group + b.groups, b.kind..b.kind + b.groups);
            if !sc.loaded[i] {
                // No force: no response (written once).
                if !sc.unforced[i] {
                    sc.forced[g].fill([V::ZERO; 3]);
                    sc.unforced[i] = true;
                }
                continue;
            }
            sc.unforced[i] = false;
            let forced = sc.forced[g.clone()].iter_mut().zip(&sc.modal_force[g]);
            for ((x, b), w) in forced.zip(&weights[k]) {
                let at = |p: &[V; 4]| p[0] * b[0] + p[1] * b[1] + p[2] * b[2] + p[3] * b[3];
                *x = [at(&w.pos[0]), at(&w.pos[1]), at(&w.pos[2])];
            }
        }
    }

    /// The fixed-point iteration of the collocation conditions: node forces → cubics → node
    /// overlaps → node forces, the overlaps through the points' influence on each other where
    /// the step has it, else through a pass over the modes. Leaves the modal force cubics and
    /// their response at the nodes of the converged forces. False when it did not converge.
    #[inline(always)]
    fn solve_nodes(&mut self, weights: &StepWeights) -> bool {
        let loads = self.ode.load_contacts();
        for _ in 0..MAX_ITERATIONS {
            if let Some(influence) = &weights.influence {
                self.point_forces();
                let sc = &mut self.sc;
                influence.deflections3(
                    &self.layout,
                    &sc.point_force,
                    &sc.point_pushed,
                    &mut sc.point_forced,
                );
            } else {
                self.cubics();
                self.forced(&weights.groups);
                let sc = &mut self.sc;
                self.layout
                    .deflections3(&sc.forced, &sc.loaded, &mut sc.point_forced);
            }
            let (mut change, mut scale) = (0.0_f64, 0.0_f64);
            for c in 0..self.force.len() {
                let beta = self.ode.graph.beta[c];
                let forced = self.layout.overlap3(c, &self.sc.point_forced);
                for (j, (&free, forced)) in self.sc.free_overlap[c].iter().zip(forced).enumerate() {
                    let d = free + forced;
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
                if weights.influence.is_some() {
                    // The points' cubics for the error; the modes' forces wait for the commit.
                    self.point_cubics();
                } else {
                    self.cubics();
                }
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
    #[inline(always)]
    fn error_norm(&mut self, step: &StepWeights) -> f64 {
        let loaded = |f: &[f64; 4]| f.iter().any(|&f| f != 0.0);
        self.sc.point_needed.fill(false);
        for c in 0..self.force.len() {
            if loaded(&self.sc.node_force[c]) {
                for p in [self.layout.above[c], self.layout.below[c]]
                    .into_iter()
                    .flatten()
                {
                    self.sc.point_needed[p] = true;
                }
            }
        }
        self.point_errors(step);
        let errors = &self.sc.point_errors;
        let (mut worst_point, mut worst_force) = (0.0_f64, 0.0_f64);
        for c in 0..self.force.len() {
            if !loaded(&self.sc.node_force[c]) {
                continue;
            }
            // (A load's side above is empty: no error.)
            let above = self.layout.above[c].map_or_else(PointError::default, |p| errors[p]);
            worst_point = worst_point.max(above.norm2(self.rtol, self.atol));
            let mut overlap_error = above.position;
            if let Some(p) = self.layout.below[c] {
                let below = errors[p];
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

    /// Every needed point's error ([`PointError`]): through the influence where the step has
    /// it, else through a pass over its modes.
    #[inline(always)]
    fn point_errors(&mut self, step: &StepWeights) {
        let Some(influence) = &step.influence else {
            for p in 0..self.layout.points.len() {
                if self.sc.point_needed[p] {
                    let e = self.point_error(p, &step.groups);
                    self.sc.point_errors[p] = e;
                }
            }
            return;
        };
        let sc = &mut self.sc;
        let cubics = (&sc.point_cubic[..], &sc.point_pushed[..]);
        influence.errors(&self.layout, cubics, &sc.point_needed, &mut sc.point_sigma3);
        for (p, e) in sc.point_errors.iter_mut().enumerate() {
            if sc.point_needed[p] {
                let [position, velocity] = sc.point_sigma3[p];
                *e = PointError {
                    position,
                    velocity,
                    x: sc.point_free[p][2] + sc.point_forced[p][2],
                    v: self.point_end[p][1],
                };
            }
        }
    }

    /// The σ³ part's effect on a point's position and velocity, and the point's position at the
    /// step's end and velocity at its start.
    #[inline(always)]
    fn point_error(&self, p: usize, weights: &[WeightGroup]) -> PointError {
        let point = self.layout.points[p];
        let (g, n) = (point.group, point.groups);
        let rows = &self.layout.rows[point.row..point.row + n];
        let w = &weights[point.kind..point.kind + n];
        let modes = self.sc.modal_force[g..g + n].iter().zip(&self.v[g..g + n]);
        let nodes = self.sc.free[g..g + n].iter().zip(&self.sc.forced[g..g + n]);
        let mut acc = [V::ZERO; 4];
        for ((&r, w), ((b, &v), (free, forced))) in rows.iter().zip(w).zip(modes.zip(nodes)) {
            acc[0] = acc[0] + r * w.err_pos * b[3];
            acc[1] = acc[1] + r * w.err_vel * b[3];
            acc[2] = acc[2] + r * (free[2] + forced[2]);
            acc[3] = acc[3] + r * v;
        }
        // (Summed out of sight of the loop, as in `Layout::dot3`.)
        let acc = std::hint::black_box(acc);
        PointError {
            position: acc[0].sum(),
            velocity: acc[1].sum(),
            x: acc[2].sum(),
            v: acc[3].sum(),
        }
    }

    /// Makes sure the weights of the step h are at hand (a rung's, or off the ladder).
    fn weights(&mut self, h: f64, rung: Option<i64>) {
        let modes = &self.layout.kind_modes;
        let layout = &self.layout;
        let statics = (&self.static_groups[..], &self.static_loaded[..]);
        self.ladder.ensure(h, rung, || {
            let groups: Vec<WeightGroup> = modes.iter().map(|m| WeightGroup::new(h, m)).collect();
            // A rung's steps are many: their influence pays for itself. An off-ladder step (a
            // landing, the run's end) is taken once and iterates through the modes, as every
            // step does where the influence would cost more ([`Influence::pays`]).
            let influence = rung
                .filter(|_| Influence::pays(layout))
                .map(|_| Influence::new(layout, &groups));
            let point_static = match influence {
                Some(_) if statics.1.iter().any(|&s| s) => {
                    static_deflections(layout, statics, &groups)
                }
                _ => Vec::new(),
            };
            StepWeights {
                groups,
                influence,
                point_static,
            }
        });
    }

    /// The state at ts inside the last step (the exact flow under the step's cubics) into
    /// `out` ([`LatticeOde`]'s layout), from the groups of the step's start: per distinct
    /// frequency its flow at θ, per group of a kind's modes their flows side by side.
    pub fn observe_at(&mut self, ts: f64, out: &mut [f64]) {
        let h = self.h_last;
        let q = self.ode.coordinates();
        if ts >= self.t || h == 0.0 {
            out.copy_from_slice(self.y());
            self.sample.points.clone_from(&self.point_end);
            return;
        }
        let theta = ((ts - self.t_prev) / h).clamp(0.0, 1.0);
        let mut sample = std::mem::take(&mut self.sample);
        let kernels = self.frequencies.iter();
        sample.kernels.clear();
        sample
            .kernels
            .extend(kernels.map(|&(w, rate)| Flow::new(theta, h, w, rate)));
        sample.flows.clear();
        let flows = self.kind_frequencies.iter();
        sample
            .flows
            .extend(flows.map(|lanes| FlowGroup::new(lanes, &sample.kernels, h)));
        let Sample {
            flows,
            x,
            v,
            points,
            ..
        } = &mut sample;
        x.resize(self.layout.groups, V::ZERO);
        v.resize(self.layout.groups, V::ZERO);
        for body in &self.layout.bodies {
            let (g, k) = (
                body.group..body.group + body.groups,
                body.kind..body.kind + body.groups,
            );
            let from = self.x_prev[g.clone()].iter().zip(&self.v_prev[g.clone()]);
            let to = x[g.clone()].iter_mut().zip(&mut v[g.clone()]);
            for ((f, b), ((&x0, &v0), (x, v))) in
                flows[k].iter().zip(&self.modal_force[g]).zip(from.zip(to))
            {
                (*x, *v) = f.flow(x0, v0, b);
            }
        }
        // (The modes the passes leave out are at rest in the state.)
        out.copy_from_slice(&self.y_prev);
        self.layout.scatter(x, &mut out[..q]);
        self.layout.scatter(v, &mut out[q + 3..2 * q + 3]);
        self.supports_flow(theta, h, &self.y_prev, out);
        let work_sum = self.work_and_dissipation(theta, &self.coef, &self.overlap_coef, x, out);
        self.set_dissipation(work_sum, (x, v), out);
        let layout = &self.layout;
        points.resize(layout.points.len(), [0.0; 2]);
        for (p, d) in points.iter_mut().enumerate() {
            *d = layout.dot2(p, x, v, &self.moving);
        }
        self.sample = sample;
    }

    /// Whether the state now is finite: every point's deflection and rate (a mode with a row at
    /// some point shows there; a mode with none is carried only for its start and moves by its
    /// free flow alone, the modes left out stay at rest), and the supports' impulses and W, D
    /// (in the state's tail).
    pub fn state_finite(&self) -> bool {
        let points: f64 = self.point_end.iter().map(|[d, r]| d + r).sum();
        let q = self.ode.coordinates();
        let tail: f64 = self.y[q..q + 3].iter().chain(&self.y[2 * q + 3..]).sum();
        (points + tail + self.work_sums_j[1]).is_finite()
    }

    /// Every contact's overlap and force at the last step's end into `ode`'s `overlap_m` and
    /// `force_n`, and its force rate into `rate` \[N/s\]: what
    /// [`LatticeOde::contact_forces_and_rates_at`] gives from the state under elastic rates
    /// (the elastic contacts' (3/2) F δ̇ / δ, the load's force and rate at a load point, whose
    /// overlap reads 0), but from the points' deflections and rates, each summed once per step
    /// over its carried modes four at a time, rather than from every side's full row: the same
    /// sums in another order, equal to rounding.
    pub fn contact_forces_and_rates(&mut self, ode: &mut LatticeOde, rate: &mut [f64]) {
        self.set_contacts(ode, self.t, &self.point_end, Some(rate));
    }

    /// Every contact's overlap and force at the last sample ([`Self::observe_at`], at `ts`)
    /// into `ode`'s `overlap_m` and `force_n`, from the points as
    /// [`Self::contact_forces_and_rates`].
    pub fn sample_contact_forces(&self, ode: &mut LatticeOde, ts: f64) {
        self.set_contacts(ode, ts, &self.sample.points, None);
    }

    /// Every contact's overlap and force (and with `rate` its force rate) at t from the
    /// points' deflections and rates `points`.
    fn set_contacts(
        &self,
        ode: &mut LatticeOde,
        t: f64,
        points: &[[f64; 2]],
        mut rate: Option<&mut [f64]>,
    ) {
        let layout = &self.layout;
        let loads = self.ode.load_contacts();
        let (load, load_rate) = if loads > 0 {
            (ode.load_per_point_n(t), ode.load_rate_per_point_n_s(t))
        } else {
            (0.0, 0.0)
        };
        let at = |p: Option<usize>| p.map_or([0.0; 2], |p| points[p]);
        for c in 0..self.force.len() {
            let (f, d, r) = if c < loads {
                (load, 0.0, load_rate)
            } else {
                let (above, below) = (at(layout.above[c]), at(layout.below[c]));
                let (d, dv) = (above[0] - below[0], above[1] - below[1]);
                let f = ContactLaw::elastic_force(self.ode.graph.beta[c], d);
                (f, d, ContactLaw::elastic_force_rate(f, d, dv))
            };
            (ode.graph.force_n[c], ode.graph.overlap_m[c]) = (f, d);
            if let Some(rate) = rate.as_deref_mut() {
                rate[c] = r;
            }
        }
    }

    /// W at θ of the step from the last step's start into `out`, with lab physics: the load
    /// points' forces' work, −∫ a_c p_c' over their cubics (force a_c, overlap p_c: minus the
    /// point's deflection), and the static forces'. Returns S at θ (0 without damped modes): the
    /// work summed on the modes, −∫ a_c p_c' over every loaded contact and the static forces'
    /// f Δq, from which D_modes = S − (E_modes − E_modes(0)) is formed where the state is read
    /// ([`Self::set_dissipation`]): every mode is advanced exactly under the cubics, so the
    /// energy the modes lost beyond the work done on them is what their damping took
    /// (docs/physics.md §8).
    fn work_and_dissipation(
        &self,
        theta: f64,
        coef: &[[f64; 4]],
        overlap_coef: &[[f64; 4]],
        x: &[V],
        out: &mut [f64],
    ) -> f64 {
        let Some(i) = self.lab else { return 0.0 };
        let loads = self.ode.load_contacts();
        let (mut w_loads, mut w_all) = (0.0, 0.0);
        for (c, (a, p)) in coef.iter().zip(overlap_coef).enumerate() {
            if a.iter().all(|&x| x == 0.0) {
                continue;
            }
            let w = -work_of_cubics(a, p, theta);
            w_all += w;
            if c < loads {
                w_loads += w;
            }
        }
        // Gravity's and a striker's preload's constant modal forces: their work is f Δq (a
        // mode they act on is carried).
        let w_static = self
            .static_groups
            .iter()
            .zip(x.iter().zip(&self.x_prev))
            .fold(V::ZERO, |w, (&f, (&q1, &q0))| w + f * (q1 - q0))
            .sum();
        out[i] = self.y_prev[i] + w_loads + w_static;
        if !self.damped {
            out[i + 1] = self.y_prev[i + 1];
            return 0.0;
        }
        self.work_sums_j[0] + w_all + w_static
    }

    /// D_modes = S − (E_modes − E_modes(0)) into `out` (which holds the modes (x, v) whose work
    /// sum is `work_sum_j`), with damped modes.
    fn set_dissipation(&self, work_sum_j: f64, (x, v): (&[V], &[V]), out: &mut [f64]) {
        if let (Some(i), true) = (self.lab, self.damped) {
            out[i + 1] = work_sum_j - (self.layout.modal_energy_j(x, v) - self.modal_energy_j);
        }
    }

    /// The supports' impulses J and their integrals ∫J dt at θ of a step of size h from `from`
    /// (the support forces' cubics of that step) into `out`.
    fn supports_flow(&self, theta: f64, h: f64, from: &[f64], out: &mut [f64]) {
        let q = self.ode.coordinates();
        let (mut dj, mut djint) = ([0.0; 3], [0.0; 3]);
        for &(c, dx, dy) in &self.ode.graph.supports {
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

    #[inline(always)]
    fn attempt(&mut self, h: f64, rung: Option<i64>) -> Attempt {
        self.weights(h, rung);
        // The ladder is lent out for the attempt (the weights are read, never copied).
        let ladder = std::mem::take(&mut self.ladder);
        let weights = ladder.get(rung);
        self.start_attempt(h, weights);
        let converged = self.solve_nodes(weights);
        // (No closure here: it would compile outside the AVX2 build.)
        let err = if converged {
            self.error_norm(weights)
        } else {
            f64::INFINITY
        };
        let err = if err.is_finite() { err } else { f64::INFINITY };
        self.ladder = ladder;
        let missed = if err <= 1.0 {
            first_crossing(&self.sc.node_overlap, &self.ode.graph.beta).map(|theta| theta * h)
        } else {
            None
        };
        Attempt { err, missed }
    }

    #[inline(always)]
    fn commit(&mut self, h: f64, rung: Option<i64>) {
        std::mem::swap(&mut self.y, &mut self.y_prev);
        if self.ladder.get(rung).influence.is_some() {
            // The converged forces on the modes (the iteration ran through the points, whose
            // cubics the error took).
            self.modal_forces();
        }
        self.advance_modes(rung);
        self.points_now();
        self.y_fresh = false;
        let mut y = std::mem::take(&mut self.y);
        self.coef.copy_from_slice(&self.sc.coef);
        self.supports_flow(1.0, h, &self.y_prev, &mut y);
        if self.lab.is_some() {
            for (p, d) in self.overlap_coef.iter_mut().zip(&self.sc.node_overlap) {
                for (pn, l) in p.iter_mut().zip(&self.lagrange) {
                    *pn = (0..4).map(|j| l[j] * d[j]).sum();
                }
            }
            self.work_sums_j[0] = self.work_sums_j[1];
            self.work_sums_j[1] =
                self.work_and_dissipation(1.0, &self.sc.coef, &self.overlap_coef, &self.x, &mut y);
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

impl GraphModalIntegrator {
    /// Every mode over the step just attempted, exactly under its modal force's cubic: the
    /// groups' positions and velocities into `x`, `v` (their values at the step's start into
    /// `x_prev`, `v_prev`), the cubics into `modal_force`. A body passed over has been at rest
    /// from the start (a body once moved is advanced every step): zeros in both.
    #[inline(always)]
    fn advance_modes(&mut self, rung: Option<i64>) {
        std::mem::swap(&mut self.x, &mut self.x_prev);
        std::mem::swap(&mut self.v, &mut self.v_prev);
        let weights = &self.ladder.get(rung).groups;
        let sc = &mut self.sc;
        for (i, body) in self.layout.bodies.iter().enumerate() {
            if !(self.moving[i] || sc.loaded[i]) {
                // At rest and under no force: at rest at the end (both buffers hold zeros).
                continue;
            }
            self.moving[i] = true;
            let (g, k) = (
                body.group..body.group + body.groups,
                body.kind..body.kind + body.groups,
            );
            let from = self.x_prev[g.clone()].iter().zip(&self.v_prev[g.clone()]);
            let to = self.x[g.clone()].iter_mut().zip(&mut self.v[g.clone()]);
            let modes = weights[k].iter().zip(&sc.modal_force[g]);
            for ((w, b), ((&x0, &v0), (x1, v1))) in modes.zip(from.zip(to)) {
                // Each group in its own vectors: without this opaque step the compiler
                // vectorises the loop across groups, gathering every weight lane by lane.
                let w = std::hint::black_box(w);
                let (p, u) = (&w.pos[2], &w.vel);
                *x1 = w.cos[2] * x0
                    + w.hsinc[2] * v0
                    + (p[0] * b[0] + p[1] * b[1] + p[2] * b[2] + p[3] * b[3]);
                *v1 = w.vel_of_pos * x0
                    + w.vel_of_vel * v0
                    + (u[0] * b[0] + u[1] * b[1] + u[2] * b[2] + u[3] * b[3]);
            }
        }
        self.modal_force.copy_from_slice(&sc.modal_force);
    }
}

impl Scratch {
    fn new(groups: usize, contacts: usize, bodies: usize, points: usize) -> Self {
        Scratch {
            point_free: vec![[0.0; 3]; points],
            point_forced: vec![[0.0; 3]; points],
            point_cubic: vec![[0.0; 4]; points],
            point_force: vec![[0.0; 4]; points],
            point_pushed: vec![false; points],
            point_needed: vec![false; points],
            point_errors: vec![PointError::default(); points],
            point_sigma3: vec![[0.0; 2]; points],
            loaded: vec![true; bodies],
            unforced: vec![true; bodies],
            free: vec![[V::ZERO; 3]; groups],
            forced: vec![[V::ZERO; 3]; groups],
            modal_force: vec![[V::ZERO; 4]; groups],
            free_overlap: vec![[0.0; 3]; contacts],
            node_force: vec![[0.0; 4]; contacts],
            node_overlap: vec![[0.0; 4]; contacts],
            coef: vec![[0.0; 4]; contacts],
        }
    }
}

/// The state (in [`LatticeOde`]'s layout) after `steps` accepted steps of
/// [`super::Method::ExactModes`] (rtol, atol \[m\]) on the lattice run `ode` of `duration_s`,
/// stepped with the run-time SIMD dispatch of [`GraphModalIntegrator::step`] or, with
/// `portable`, without it: what the claim `simd_step_bit_identical` compares bit for bit.
#[doc(hidden)]
pub fn exact_modes_lattice_state(
    ode: &LatticeOde,
    (rtol, atol): (f64, f64),
    duration_s: f64,
    steps: usize,
    portable: bool,
) -> Result<Vec<f64>> {
    let mut stepper = GraphModalIntegrator::new(ode, rtol, atol, duration_s);
    for _ in 0..steps {
        if portable {
            stepper.step_portable(duration_s)?;
        } else {
            stepper.step(duration_s)?;
        }
    }
    Ok(stepper.y().to_vec())
}

/// The distinct (frequency \[rad/s\], damping rate \[1/s\]) pairs of the modes the passes
/// carry, and per group of each kind's modes each lane's pair (`usize::MAX`: padding).
fn sample_frequencies(layout: &Layout) -> (Vec<(f64, f64)>, Vec<[usize; 4]>) {
    let mut frequencies = Vec::new();
    let mut seen = std::collections::HashMap::new();
    let lanes = layout
        .kind_modes
        .iter()
        .map(|group| {
            group.map(|mode| {
                mode.map_or(usize::MAX, |(omega, rate)| {
                    *seen
                        .entry((omega.to_bits(), rate.to_bits()))
                        .or_insert_with(|| {
                            frequencies.push((omega, rate));
                            frequencies.len() - 1
                        })
                })
            })
        })
        .collect();
    (frequencies, lanes)
}
