//! The static equilibrium of a lattice under gravity and a preload (docs/physics.md §16,
//! "Gravity and a preload"): the minimum of the potential
//! Π(q) = ½ Σ ω_j² q_j² + Σ_c (2/5) β_c δ_c₊^{5/2} − fᵀq over the rods' modal coordinates,
//! by damped Newton steps (H + μ diag H) Δ = −∇Π with H = diag ω² + Σ_c k_c g_c g_cᵀ.
//!
//! Each step is solved condensed onto the touching contacts and the rigid modes. With
//! D = diag ω² + μ diag H (positive on every elastic mode) and λ = K Gᵀ Δ the contacts' force
//! increments, the step is D Δ + G λ = b, Gᵀ Δ = K⁻¹ λ; the elastic modes are explicit,
//! Δ_e = D_e⁻¹ (b_e − G_e λ), which leaves, with P = I + K^½ G_eᵀ D_e⁻¹ G_e K^½ (contacts ×
//! contacts, eigenvalues ≥ 1) and B = G_r K^½ (rigid modes × contacts),
//!
//! ```text
//! (D_r + B P⁻¹ Bᵀ) Δ_r = b_r − B P⁻¹ K^½ G_eᵀ D_e⁻¹ b_e,   λ = K^½ P⁻¹ (Bᵀ Δ_r + K^½ G_eᵀ D_e⁻¹ b_e)
//! ```
//!
//! two dense Cholesky factorisations of the number of touching contacts and of rigid modes.
//! G_eᵀ D_e⁻¹ G_e couples two contacts only through a rod they share, so P is assembled rod by
//! rod. The step is the dense one's (the same matrix, inverted by blocks): the iteration, its
//! safeguards and its convergence test on the whole gradient are unchanged, at a cost linear in
//! the modes and cubic in the contacts instead of cubic in the modes.
//!
//! Under a displacement drive with a preload F_p the actuator is one more coordinate u (its
//! position, downward, after the rods' Q coordinates): rigid (ω = 0), loaded by F_p, its only
//! stiffness its tips' Hertz contacts δ_i = u − w_i(q), so that Π gains
//! Σ_i (2/5) β_i δ_i₊^{5/2} − F_p u and each tip carries the share the equilibrium gives it.
//! It enters the condensed step as one more rigid mode.

use super::lattice::graph::{ContactGraph, Side};
use crate::error::{Error, Result};
use crate::model::ContactLaw;
use nalgebra::{DMatrix, DVector};
use std::borrow::Cow;
use std::ops::Range;

/// The static solve stops when |∇Π| ≤ this × |f| (f the static generalised forces).
const STATIC_RESIDUAL: f64 = 1e-12;
/// Most Newton steps of the static solve.
const STATIC_ITERATIONS: usize = 500;
/// The overlap at which the contacts' stiffness sets the regularisation's scale when nothing is
/// stiff yet \[m\].
const REFERENCE_OVERLAP_M: f64 = 1e-6;
/// A mode is rigid (kept in the condensed system) if ω² ≤ this × the largest ω².
const RIGID_OMEGA2: f64 = 1e-12;

/// The static state of a lattice: the rods' positions, the actuator's (if it is solved for)
/// and the solve's relative residual |∇Π| / |f|.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StaticState {
    pub q: Vec<f64>,
    /// The actuator's position u* \[m\] (downward), under a displacement drive with a preload.
    pub actuator_m: Option<f64>,
    pub residual: f64,
}

/// The minimum of Π on `ode` for the static generalised forces `f` (zero on the striker's
/// coordinate, which is held) and, with `actuator_force_n` = Some(F_p), a displacement
/// actuator loaded by F_p whose tips are the load contacts: Newton steps with μ raised until Π
/// falls and lowered after (the rigid modes have no stiffness until their contacts close),
/// until |∇Π| ≤ 1e-12 |f| (F_p included in f). An error naming `preload` with that ratio if no
/// minimum is found (a rod that nothing holds).
pub(super) fn static_equilibrium(
    ode: &ContactGraph,
    f: &[f64],
    actuator_force_n: Option<f64>,
) -> Result<StaticState> {
    let pi = Potential::new(ode, f, actuator_force_n);
    let f_norm = norm(&pi.f);
    let mut x = vec![0.0; pi.f.len()];
    if f_norm == 0.0 {
        return Ok(pi.state(x, 0.0));
    }
    let mut mu = 1e-3;
    let mut g = pi.gradient(&x);
    for _ in 0..STATIC_ITERATIONS {
        let residual = norm(&g) / f_norm;
        if residual <= STATIC_RESIDUAL {
            return Ok(pi.state(x, residual));
        }
        let tangent = pi.tangent(&x);
        let b: Vec<f64> = g.iter().map(|v| -v).collect();
        let e0 = pi.value(&x);
        loop {
            if let Some(step) = pi.step(&tangent, mu, &b) {
                let trial: Vec<f64> = x.iter().zip(&step).map(|(x, s)| x + s).collect();
                let g_trial = pi.gradient(&trial);
                if pi.value(&trial) < e0 || norm(&g_trial) < 0.5 * norm(&g) {
                    x = trial;
                    g = g_trial;
                    mu = (mu / 3.0).max(1e-15);
                    break;
                }
            }
            mu *= 4.0;
            if mu > 1e20 {
                return Err(no_equilibrium(norm(&g) / f_norm));
            }
        }
    }
    Err(no_equilibrium(norm(&g) / f_norm))
}

/// The static solve found no equilibrium: some rod is not held.
fn no_equilibrium(residual: f64) -> Error {
    Error::invalid(
        "preload",
        format!("a relative force residual of {residual:.3e}"),
        format!("the static solve under gravity and the preload did not converge below {STATIC_RESIDUAL:e}: every rod must rest on the rods below or on supports (a rod that touches nothing below falls)"),
    )
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// One side of a Hertz contact: the contact, the body's side and its sign in g_c (+ above,
/// − below).
#[derive(Debug, Clone, Copy)]
struct Entry {
    contact: usize,
    side: Side,
    sign: f64,
}

/// The contact graph Π is taken on: the ODE's, or with the actuator's coordinate appended
/// (ω = 0, its row 1 at the end of `rows`, the side above each of its tips).
struct Graph<'a> {
    omega2: Cow<'a, [f64]>,
    above: Cow<'a, [Side]>,
    below: &'a [Option<Side>],
    beta: &'a [f64],
    rows: Cow<'a, [f64]>,
}

impl<'a> Graph<'a> {
    /// `ode`'s graph, with the actuator as the side above every load contact if `actuator`.
    fn new(ode: &'a ContactGraph, actuator: bool) -> Self {
        let mut graph = Graph {
            omega2: Cow::Borrowed(&ode.omega2),
            above: Cow::Borrowed(&ode.above),
            below: &ode.below,
            beta: &ode.beta,
            rows: Cow::Borrowed(&ode.rows),
        };
        if actuator {
            let u = Side {
                offset: ode.coordinates(),
                len: 1,
                row: ode.rows.len(),
            };
            graph.omega2.to_mut().push(0.0);
            graph.rows.to_mut().push(1.0);
            graph.above.to_mut()[..ode.loads].fill(u);
        }
        graph
    }

    /// The sides of contact c with their signs in g_c (+ above, − below).
    fn sides(&self, c: usize) -> impl Iterator<Item = (Side, f64)> {
        let below = self.below[c].map(|s| (s, -1.0));
        std::iter::once((self.above[c], 1.0)).chain(below)
    }

    /// g_c · x: contact c's overlap at x.
    fn overlap(&self, c: usize, x: &[f64]) -> f64 {
        self.sides(c)
            .map(|(s, sign)| sign * s.dot(&self.rows, x))
            .sum()
    }
}

/// Π on the rods' coordinates (from `first`; the striker's, if any, held at 0) and the
/// actuator's, with the structure the condensed step needs.
struct Potential<'a> {
    graph: Graph<'a>,
    /// The static forces, F_p last with an actuator.
    f: Vec<f64>,
    first: usize,
    /// The ODE's number of coordinates Q (the actuator's is Q).
    rod_coordinates: usize,
    /// The Hertz contacts (not the striker's; the loads' only as an actuator's tips).
    hertz: Range<usize>,
    /// Per coordinate: its index among the rigid modes, or None (elastic, or the striker's).
    rigid: Vec<Option<usize>>,
    /// The rigid modes' coordinates.
    rigid_coordinates: Vec<usize>,
    /// Every Hertz contact's sides, grouped by body (the bodies' ranges in `bodies`).
    entries: Vec<Entry>,
    bodies: Vec<Range<usize>>,
}

/// Π's second derivative at a point: (contact, √k_c) of every touching contact and H's
/// diagonal (0 on held coordinates), with its largest entry.
struct Tangent {
    root_stiffness: Vec<(usize, f64)>,
    slot: Vec<Option<usize>>,
    diagonal: Vec<f64>,
    scale: f64,
}

impl<'a> Potential<'a> {
    /// Π on `ode` under `f`, with an actuator loaded by F_p if `actuator_force_n` is Some(F_p)
    /// (the ODE has an actuator then).
    fn new(ode: &'a ContactGraph, f: &[f64], actuator_force_n: Option<f64>) -> Self {
        let graph = Graph::new(ode, actuator_force_n.is_some());
        let mut f = f.to_vec();
        f.extend(actuator_force_n);
        let q = f.len();
        let first = usize::from(ode.struck);
        let hertz = match (ode.struck, actuator_force_n) {
            (true, _) => 1,
            (false, Some(_)) => 0,
            (false, None) => ode.loads,
        }..ode.contacts();
        let largest = graph.omega2.iter().fold(0.0_f64, |m, &w| m.max(w));
        let rigid_coordinates: Vec<usize> = (first..q)
            .filter(|&j| graph.omega2[j] <= RIGID_OMEGA2 * largest)
            .collect();
        let mut rigid = vec![None; q];
        for (i, &j) in rigid_coordinates.iter().enumerate() {
            rigid[j] = Some(i);
        }
        let mut entries: Vec<Entry> = hertz
            .clone()
            .flat_map(|c| {
                graph.sides(c).map(move |(side, sign)| Entry {
                    contact: c,
                    side,
                    sign,
                })
            })
            .collect();
        entries.sort_by_key(|e| (e.side.offset, e.contact));
        let mut bodies: Vec<Range<usize>> = Vec::new();
        for (i, e) in entries.iter().enumerate() {
            match bodies.last_mut() {
                Some(r) if entries[r.start].side.offset == e.side.offset => r.end = i + 1,
                _ => bodies.push(i..i + 1),
            }
        }
        Potential {
            graph,
            f,
            first,
            rod_coordinates: ode.coordinates(),
            hertz,
            rigid,
            rigid_coordinates,
            entries,
            bodies,
        }
    }

    /// The static state at the minimum x (the rods' coordinates, then the actuator's).
    fn state(&self, mut x: Vec<f64>, residual: f64) -> StaticState {
        let actuator_m = x.get(self.rod_coordinates).copied();
        x.truncate(self.rod_coordinates);
        StaticState {
            q: x,
            actuator_m,
            residual,
        }
    }

    fn value(&self, x: &[f64]) -> f64 {
        let graph = &self.graph;
        let mut e: f64 = (self.first..x.len())
            .map(|j| 0.5 * graph.omega2[j] * x[j] * x[j] - self.f[j] * x[j])
            .sum();
        for c in self.hertz.clone() {
            e += ContactLaw::potential_j(graph.beta[c], graph.overlap(c, x));
        }
        e
    }

    /// ∇Π: ω_j² q_j − f_j + Σ_c F_c (g_c)_j, zero on held coordinates.
    fn gradient(&self, x: &[f64]) -> Vec<f64> {
        let graph = &self.graph;
        let mut g: Vec<f64> = (0..x.len())
            .map(|j| graph.omega2[j] * x[j] - self.f[j])
            .collect();
        for c in self.hertz.clone() {
            let force = ContactLaw::elastic_force(graph.beta[c], graph.overlap(c, x));
            if force != 0.0 {
                for (s, sign) in graph.sides(c) {
                    for k in 0..s.len {
                        g[s.offset + k] += sign * graph.rows[s.row + k] * force;
                    }
                }
            }
        }
        g[..self.first].iter_mut().for_each(|v| *v = 0.0);
        g
    }

    /// H's diagonal and every touching contact's stiffness k_c = (3/2) β δ^½ at x.
    fn tangent(&self, x: &[f64]) -> Tangent {
        let graph = &self.graph;
        let mut diagonal: Vec<f64> = graph.omega2.to_vec();
        let (mut root_stiffness, mut slot) = (Vec::new(), vec![None; graph.beta.len()]);
        for c in self.hertz.clone() {
            let k = ContactLaw::stiffness_n_per_m(graph.beta[c], graph.overlap(c, x));
            if k == 0.0 {
                continue;
            }
            slot[c] = Some(root_stiffness.len());
            root_stiffness.push((c, k.sqrt()));
            for (s, _) in graph.sides(c) {
                for i in 0..s.len {
                    diagonal[s.offset + i] += k * graph.rows[s.row + i].powi(2);
                }
            }
        }
        diagonal[..self.first].iter_mut().for_each(|v| *v = 0.0);
        let mut scale = diagonal.iter().fold(0.0_f64, |m, &v| m.max(v));
        if scale == 0.0 {
            // Nothing stiff yet (every mode rigid, no contact touching: a chain of rigid cells at
            // the start): the scale of the regularisation from the contacts' stiffness at an
            // overlap of 1 µm, so that μ finds the step in its range.
            for c in self.hertz.clone() {
                let k = ContactLaw::stiffness_n_per_m(graph.beta[c], REFERENCE_OVERLAP_M);
                for (s, _) in graph.sides(c) {
                    for i in 0..s.len {
                        scale = scale.max(k * graph.rows[s.row + i].powi(2));
                    }
                }
            }
        }
        Tangent {
            root_stiffness,
            slot,
            diagonal,
            scale: scale.max(f64::MIN_POSITIVE),
        }
    }

    /// The damped Newton step Δ = (H + μ diag H)⁻¹ b condensed onto the touching contacts and
    /// the rigid modes (the module's notes; a held coordinate's diagonal entry is floored at
    /// 1e-9 of the largest); None if either factorisation fails.
    fn step(&self, t: &Tangent, mu: f64, b: &[f64]) -> Option<Vec<f64>> {
        let graph = &self.graph;
        let d: Vec<f64> = (0..b.len())
            .map(|j| graph.omega2[j] + mu * t.diagonal[j].max(1e-9 * t.scale))
            .collect();
        // coupling = B = G_r K^½ (rigid modes × contacts).
        let (p, coupling, h) = self.condensed(t, &d, b);
        let p = p.cholesky()?;
        let y = p.solve(&coupling.transpose());
        let z = p.solve(&h);
        // (A product by hand: nalgebra hands matrix products to `matrixmultiply`, whose kernels
        // fuse multiply-adds where the CPU has FMA, so the equilibrium's last bits would
        // depend on the machine; `math`'s module notes.)
        let mut s = DMatrix::from_fn(coupling.nrows(), y.ncols(), |i, j| {
            (0..y.nrows()).map(|l| coupling[(i, l)] * y[(l, j)]).sum()
        });
        for (i, &j) in self.rigid_coordinates.iter().enumerate() {
            s[(i, i)] += d[j];
        }
        let rhs = DVector::from_iterator(
            self.rigid_coordinates.len(),
            self.rigid_coordinates.iter().map(|&j| b[j]),
        ) - &coupling * &z;
        let rigid_step = if rhs.is_empty() {
            rhs
        } else {
            s.cholesky()?.solve(&rhs)
        };
        let scaled_force = &y * &rigid_step + z;
        let mut step: Vec<f64> = (0..b.len())
            .map(|j| match self.rigid[j] {
                Some(i) => rigid_step[i],
                None if j < self.first => 0.0,
                None => b[j] / d[j],
            })
            .collect();
        for (a, &(c, root_k)) in t.root_stiffness.iter().enumerate() {
            let lambda = root_k * scaled_force[a];
            for (s, sign) in graph.sides(c) {
                for i in 0..s.len {
                    let j = s.offset + i;
                    if self.rigid[j].is_none() {
                        step[j] -= sign * graph.rows[s.row + i] * lambda / d[j];
                    }
                }
            }
        }
        Some(step)
    }

    /// P = I + K^½ G_eᵀ D_e⁻¹ G_e K^½, B = G_r K^½ as rigid modes × contacts, and
    /// K^½ G_eᵀ D_e⁻¹ b_e, over the touching contacts, assembled body by body.
    fn condensed(
        &self,
        t: &Tangent,
        d: &[f64],
        b: &[f64],
    ) -> (DMatrix<f64>, DMatrix<f64>, DVector<f64>) {
        let rows = &self.graph.rows;
        let m = t.root_stiffness.len();
        let mut p = DMatrix::identity(m, m);
        let mut coupling = DMatrix::zeros(self.rigid_coordinates.len(), m);
        let mut h = DVector::zeros(m);
        let mut touching: Vec<(usize, f64, Side)> = Vec::new();
        for body in &self.bodies {
            touching.clear();
            touching.extend(self.entries[body.clone()].iter().filter_map(|e| {
                let a = t.slot[e.contact]?;
                Some((a, e.sign * t.root_stiffness[a].1, e.side))
            }));
            for (u, &(a, wa, sa)) in touching.iter().enumerate() {
                let row_a = &rows[sa.row..sa.row + sa.len];
                for (i, &r) in row_a.iter().enumerate() {
                    let j = sa.offset + i;
                    match self.rigid[j] {
                        Some(k) => coupling[(k, a)] += wa * r,
                        None => h[a] += wa * r * b[j] / d[j],
                    }
                }
                for (w, &(c, wc, sc)) in touching.iter().enumerate().skip(u) {
                    let row_c = &rows[sc.row..sc.row + sc.len];
                    let flexibility: f64 = (0..sa.len)
                        .filter(|&i| self.rigid[sa.offset + i].is_none())
                        .map(|i| row_a[i] * row_c[i] / d[sa.offset + i])
                        .sum();
                    let v = wa * wc * flexibility;
                    p[(a, c)] += v;
                    if w != u {
                        p[(c, a)] += v;
                    }
                }
            }
        }
        (p, coupling, h)
    }
}
