//! The influence of a body's points on each other over a step: the deflection of point p at
//! the nodes σ = c₁, c₂, 1 per unit force at node i of point q (the force interpolated by the
//! cubic through the four nodes, ℓ_ni its Lagrange coefficients in monomials),
//!
//! G_pq,ji = Σ_n Σ_k r_pk r_qk h² S_n(σ_j, z_k) ℓ_ni,
//!
//! summed once per step size over the body's modes ([`super::WeightGroup`]'s `pos`), so that an
//! iteration maps node forces to node deflections with no cubic in between. With it
//! the node iteration of the contact graph's stepper costs (points of a body)² per body and
//! iteration instead of (points) × (modes): a rod's modes are passed over once per attempt,
//! not once per iteration. The attempt's error comes the same way: the σ³ part's effect on
//! point p's position and velocity is Σ_q E_pq a³_q, with E_pq = Σ_k r_pk r_qk (h² Σ_n E_n
//! S_n(1, z_k), h Σ_n E_n C_n(1, z_k)) (`err_pos`, `err_vel`) and a³_q the σ³ coefficient of the
//! net force at q, so an attempt passes over the modes only for its free motion. Bodies of one
//! family (one kind, the same rows at their points: a layer's rods between equal layers) share
//! their matrices.

use super::layout::Layout;
use super::{WeightGroup, V};
use crate::real::Real;

/// The influence matrices of every family of bodies for one step size.
#[derive(Debug, Clone, Default)]
pub(super) struct Influence {
    /// Per family, row-major over its points (p, q): G_pq per node of the deflection and node
    /// of the force.
    matrices: Vec<[[f64; 4]; 3]>,
    /// Per family, as `matrices`: E_pq for the position and for the velocity.
    errors: Vec<[f64; 2]>,
}

/// The most matrix entries (point pairs, summed over the families) the influence is kept for:
/// each rung of the ladder holds its own, 14 numbers an entry (about 1.8 MB a rung at this
/// bound, a few tens of rungs a run).
const MAX_PAIRS: usize = 16_384;

impl Influence {
    /// Whether iterating through the influence is cheaper than through the modes for `layout`:
    /// per iteration, (points)² × 12 products a body against (points) × (groups) × 7 vector
    /// products of four (the rows' passes) plus (groups) × 12 (the forced response); and its
    /// matrices within [`MAX_PAIRS`]. Rods with many crossings and few modes (`rod = { modes = l
    /// }` with small l) iterate through the modes.
    pub(super) fn pays(layout: &Layout) -> bool {
        let pairs: usize = layout
            .families
            .iter()
            .map(|&b| layout.body_points[b].len().pow(2))
            .sum();
        let (mut influence, mut modes) = (0, 0);
        for (b, points) in layout.bodies.iter().zip(&layout.body_points) {
            let p = points.len();
            influence += p * p * 12;
            modes += 4 * (p * b.groups * 7 + b.groups * 12);
        }
        pairs <= MAX_PAIRS && influence <= modes
    }

    /// The matrices for the step whose weights (per group of each kind's modes) are `weights`.
    pub(super) fn new(layout: &Layout, weights: &[WeightGroup]) -> Self {
        let lagrange = super::lagrange();
        let mut me = Influence::default();
        for &b in &layout.families {
            let body = &layout.bodies[b];
            let points = &layout.body_points[b];
            let n = points.len();
            let start = me.matrices.len();
            me.matrices.resize(start + n * n, [[0.0; 4]; 3]);
            me.errors.resize(start + n * n, [0.0; 2]);
            let w = &weights[body.kind..body.kind + body.groups];
            for (i, &p) in points.iter().enumerate() {
                for (j, &q) in points.iter().enumerate().skip(i) {
                    let (monomials, e) = pair(layout.point_row(p), layout.point_row(q), w);
                    let g = monomials.map(|gj| {
                        std::array::from_fn(|i| (0..4).map(|n| gj[n] * lagrange[n][i]).sum())
                    });
                    me.matrices[start + i * n + j] = g;
                    me.matrices[start + j * n + i] = g;
                    me.errors[start + i * n + j] = e;
                    me.errors[start + j * n + i] = e;
                }
            }
        }
        me
    }

    /// Every point's deflection at the nodes in response to the net forces at the four nodes
    /// at the points of its body (`forces`; `pushed`: the points a force acts on) into `out`.
    #[inline(always)]
    pub(super) fn deflections3(
        &self,
        layout: &Layout,
        forces: &[[f64; 4]],
        pushed: &[bool],
        out: &mut [[f64; 3]],
    ) {
        for span in &layout.body_spans {
            let (n, start) = (span.points, span.matrix);
            let points = &layout.point_list[span.start..span.start + n];
            let matrix = &self.matrices[start..start + n * n];
            let any = points.iter().any(|&q| pushed[q]);
            for (i, &p) in points.iter().enumerate() {
                let mut d = [0.0; 3];
                if any {
                    for (g, &q) in matrix[i * n..(i + 1) * n].iter().zip(points) {
                        if !pushed[q] {
                            continue;
                        }
                        let a = &forces[q];
                        for (dj, gj) in d.iter_mut().zip(g) {
                            *dj += (gj[0] * a[0] + gj[1] * a[1]) + (gj[2] * a[2] + gj[3] * a[3]);
                        }
                    }
                }
                out[p] = d;
            }
        }
    }

    /// The σ³ part's effect on the position and the velocity of every point in `needed`
    /// (the net force cubics at the points of its body: `cubics`, `pushed` as
    /// [`Influence::deflections3`]) into `out`.
    #[inline(always)]
    pub(super) fn errors(
        &self,
        layout: &Layout,
        (cubics, pushed): (&[[f64; 4]], &[bool]),
        needed: &[bool],
        out: &mut [[f64; 2]],
    ) {
        for span in &layout.body_spans {
            let (n, start) = (span.points, span.matrix);
            let points = &layout.point_list[span.start..span.start + n];
            let matrix = &self.errors[start..start + n * n];
            for (i, &p) in points.iter().enumerate().filter(|&(_, &p)| needed[p]) {
                let mut e = [0.0; 2];
                for (g, &q) in matrix[i * n..(i + 1) * n].iter().zip(points) {
                    if pushed[q] {
                        e[0] += g[0] * cubics[q][3];
                        e[1] += g[1] * cubics[q][3];
                    }
                }
                out[p] = e;
            }
        }
    }
}

/// G_pq and E_pq for rows `rp`, `rq` over one body's groups with weights `w`.
fn pair(rp: &[V], rq: &[V], w: &[WeightGroup]) -> ([[f64; 4]; 3], [f64; 2]) {
    let mut acc = [[V::ZERO; 4]; 3];
    let mut err = [V::ZERO; 2];
    for ((&a, &b), w) in rp.iter().zip(rq).zip(w) {
        let ab = a * b;
        for (accj, posj) in acc.iter_mut().zip(&w.pos) {
            for (x, &s) in accj.iter_mut().zip(posj) {
                *x = *x + ab * s;
            }
        }
        err[0] = err[0] + ab * w.err_pos;
        err[1] = err[1] + ab * w.err_vel;
    }
    (acc.map(|row| row.map(|v| v.sum())), err.map(|v| v.sum()))
}
