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

use super::lattice::{LatticeOde, Side};
use crate::error::{Error, Result};
use crate::model::ContactLaw;
use nalgebra::{DMatrix, DVector};
use std::ops::Range;

/// The static solve stops when |∇Π| ≤ this × |f| (f the static generalised forces).
const STATIC_RESIDUAL: f64 = 1e-12;
/// Most Newton steps of the static solve.
const STATIC_ITERATIONS: usize = 500;
/// A mode is rigid (kept in the condensed system) if ω² ≤ this × the largest ω².
const RIGID_OMEGA2: f64 = 1e-12;

/// The minimum of Π on `ode` for the static generalised forces `f` (zero on the striker's
/// coordinate, which is held): Newton steps with μ raised until Π falls and lowered after (the
/// rigid modes have no stiffness until their contacts close), until |∇Π| ≤ 1e-12 |f|.
/// Returns the positions and |∇Π| / |f|; an error naming `preload` with that ratio if no
/// minimum is found (a rod that nothing holds).
pub(super) fn static_equilibrium(ode: &LatticeOde, f: &[f64]) -> Result<(Vec<f64>, f64)> {
    let q = ode.coordinates();
    let f_norm = norm(f);
    let mut x = vec![0.0; q];
    if f_norm == 0.0 {
        return Ok((x, 0.0));
    }
    let pi = Potential::new(ode, f);
    let mut mu = 1e-3;
    let mut g = pi.gradient(&x);
    for _ in 0..STATIC_ITERATIONS {
        let residual = norm(&g) / f_norm;
        if residual <= STATIC_RESIDUAL {
            return Ok((x, residual));
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

/// Π on the rods' coordinates (from `first`; the striker's, if any, held at 0), with the
/// structure the condensed step needs.
struct Potential<'a> {
    ode: &'a LatticeOde,
    f: &'a [f64],
    first: usize,
    /// The Hertz contacts (not the striker's, not the loads').
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
    fn new(ode: &'a LatticeOde, f: &'a [f64]) -> Self {
        let q = ode.coordinates();
        let first = usize::from(ode.struck);
        let hertz = if ode.struck { 1 } else { ode.loads }..ode.contacts();
        let largest = ode.omega2.iter().fold(0.0_f64, |m, &w| m.max(w));
        let rigid_coordinates: Vec<usize> = (first..q)
            .filter(|&j| ode.omega2[j] <= RIGID_OMEGA2 * largest)
            .collect();
        let mut rigid = vec![None; q];
        for (i, &j) in rigid_coordinates.iter().enumerate() {
            rigid[j] = Some(i);
        }
        let mut entries: Vec<Entry> = Vec::new();
        for c in hertz.clone() {
            let side = ode.above[c];
            entries.push(Entry {
                contact: c,
                side,
                sign: 1.0,
            });
            if let Some(side) = ode.below[c] {
                entries.push(Entry {
                    contact: c,
                    side,
                    sign: -1.0,
                });
            }
        }
        entries.sort_by_key(|e| (e.side.offset, e.contact));
        let mut bodies: Vec<Range<usize>> = Vec::new();
        for (i, e) in entries.iter().enumerate() {
            match bodies.last_mut() {
                Some(r) if entries[r.start].side.offset == e.side.offset => r.end = i + 1,
                _ => bodies.push(i..i + 1),
            }
        }
        Potential {
            ode,
            f,
            first,
            hertz,
            rigid,
            rigid_coordinates,
            entries,
            bodies,
        }
    }

    fn value(&self, x: &[f64]) -> f64 {
        let ode = self.ode;
        let mut e: f64 = (self.first..x.len())
            .map(|j| 0.5 * ode.omega2[j] * x[j] * x[j] - self.f[j] * x[j])
            .sum();
        for c in self.hertz.clone() {
            e += ContactLaw::potential_j(ode.beta[c], ode.overlap(c, x));
        }
        e
    }

    /// ∇Π: ω_j² q_j − f_j + Σ_c F_c (g_c)_j, zero on held coordinates.
    fn gradient(&self, x: &[f64]) -> Vec<f64> {
        let ode = self.ode;
        let mut g: Vec<f64> = (0..x.len())
            .map(|j| ode.omega2[j] * x[j] - self.f[j])
            .collect();
        for c in self.hertz.clone() {
            let force = ContactLaw::elastic_force(ode.beta[c], ode.overlap(c, x));
            if force != 0.0 {
                add_row(ode, c, force, &mut g);
            }
        }
        g[..self.first].iter_mut().for_each(|v| *v = 0.0);
        g
    }

    /// H's diagonal and every touching contact's stiffness k_c = (3/2) β δ^½ at x.
    fn tangent(&self, x: &[f64]) -> Tangent {
        let ode = self.ode;
        let mut diagonal: Vec<f64> = ode.omega2.clone();
        let (mut root_stiffness, mut slot) = (Vec::new(), vec![None; ode.contacts()]);
        for c in self.hertz.clone() {
            let k = ContactLaw::stiffness_n_per_m(ode.beta[c], ode.overlap(c, x));
            if k == 0.0 {
                continue;
            }
            slot[c] = Some(root_stiffness.len());
            root_stiffness.push((c, k.sqrt()));
            for s in std::iter::once(ode.above[c]).chain(ode.below[c]) {
                for i in 0..s.len {
                    diagonal[s.offset + i] += k * ode.rows[s.row + i].powi(2);
                }
            }
        }
        diagonal[..self.first].iter_mut().for_each(|v| *v = 0.0);
        let scale = diagonal.iter().fold(0.0_f64, |m, &v| m.max(v));
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
        let ode = self.ode;
        let d: Vec<f64> = (0..b.len())
            .map(|j| ode.omega2[j] + mu * t.diagonal[j].max(1e-9 * t.scale))
            .collect();
        // coupling = B = G_r K^½ (rigid modes × contacts).
        let (p, coupling, h) = self.condensed(t, &d, b);
        let p = p.cholesky()?;
        let y = p.solve(&coupling.transpose());
        let z = p.solve(&h);
        let mut s = &coupling * &y;
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
            let below = ode.below[c].map(|s| (s, -1.0));
            for (s, sign) in std::iter::once((ode.above[c], 1.0)).chain(below) {
                for i in 0..s.len {
                    let j = s.offset + i;
                    if self.rigid[j].is_none() {
                        step[j] -= sign * ode.rows[s.row + i] * lambda / d[j];
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
        let ode = self.ode;
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
                let row_a = &ode.rows[sa.row..sa.row + sa.len];
                for (i, &r) in row_a.iter().enumerate() {
                    let j = sa.offset + i;
                    match self.rigid[j] {
                        Some(k) => coupling[(k, a)] += wa * r,
                        None => h[a] += wa * r * b[j] / d[j],
                    }
                }
                for (w, &(c, wc, sc)) in touching.iter().enumerate().skip(u) {
                    let row_c = &ode.rows[sc.row..sc.row + sc.len];
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

/// Adds F (g_c) to `g`: +F × contact c's row above, −F × its row below.
fn add_row(ode: &LatticeOde, c: usize, force: f64, g: &mut [f64]) {
    let s = ode.above[c];
    for k in 0..s.len {
        g[s.offset + k] += ode.rows[s.row + k] * force;
    }
    if let Some(s) = ode.below[c] {
        for k in 0..s.len {
            g[s.offset + k] -= ode.rows[s.row + k] * force;
        }
    }
}
