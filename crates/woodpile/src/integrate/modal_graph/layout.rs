//! The contact graph's coordinates as the exact stepper's passes see them
//! ([`super::GraphModalIntegrator`]): the modes each body carries, in groups of four, and the
//! points its contacts act on, each with its row over those modes.

use super::V;
use crate::ode::LatticeOde;
use crate::real::Real;

/// A mode's row at a point is taken as zero when it is at most this fraction ε of the point's
/// largest row entry: an antisymmetric mode at a rod's centre is zero but for the rounding of
/// the eigenvectors (up to 3e-12 of the largest entry on a rod of 32 elements). Leaving such a
/// mode out changes the point's response by its share of the compliance Σ r_j²/ω_j², at most
/// ε² (ω_max/ω_1)² ≈ 1e-20 · 1e6 of it for these rods.
pub(super) const ZERO_ROW_OF_LARGEST: f64 = 1e-10;

/// Two contacts' sides on one body are one point when their rows agree to this fraction of the
/// largest entry: the same crossing reached from the layer above and from the layer below,
/// whose positions along the rod were computed through different rotations and differ by
/// rounding (of the order of 1e-18 m).
pub(super) const SAME_POINT_ROW_OF_LARGEST: f64 = 1e-13;

/// One body's coordinates: the modes the passes carry (state indices, ascending), where they
/// sit in the groups of four (padded) and in its kind's weights (bodies with equal carried modes
/// share theirs). A mode whose row is zero at every point of the body, and that starts at rest
/// under no static force, is never moved by anything: it is left out of the passes (it stays at
/// rest in the state), as are a centred column's antisymmetric modes.
#[derive(Debug, Clone)]
pub(super) struct Body {
    /// Every coordinate of the body in the state.
    pub(super) state: std::ops::Range<usize>,
    /// The carried modes; `whole` when they are all of `state`.
    pub(super) modes: Vec<usize>,
    pub(super) whole: bool,
    pub(super) group: usize,
    pub(super) kind: usize,
    pub(super) groups: usize,
}

/// A point of a body that contacts act on, in groups of four: its body (index into
/// [`Layout::bodies`]), the body's first group and first weight group, its row's first group in
/// [`Layout::rows`], and the number of groups. Contacts at the same point of a body (a rod
/// pressed from above and below at one crossing) share one point: its deflection is computed
/// once, and their forces act through its row as one.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Point {
    pub(super) body: usize,
    pub(super) group: usize,
    pub(super) kind: usize,
    pub(super) row: usize,
    pub(super) groups: usize,
}

/// A body's points in [`Layout::point_list`] and its family's influence block.
#[derive(Debug, Clone, Copy)]
pub(super) struct BodySpan {
    pub(super) start: usize,
    pub(super) points: usize,
    pub(super) matrix: usize,
}

/// The lattice's coordinates in groups of four: each body's carried modes padded to whole
/// groups with massless modes at rest (zero weights, zero rows), so that the passes over the
/// modes run four modes per vector with no remainder.
#[derive(Debug, Clone, Default)]
pub(super) struct Layout {
    pub(super) bodies: Vec<Body>,
    /// Per distinct body: its carried modes' (frequency, damping rate), padded.
    pub(super) kind_modes: Vec<[Option<(f64, f64)>; 4]>,
    /// Per distinct body: its carried modes' ω² \[1/s²\], padded with zeros.
    pub(super) kind_omega2: Vec<V>,
    /// The distinct points contacts act on.
    pub(super) points: Vec<Point>,
    /// Per contact: its point above and below (None: a load's empty side, a support).
    pub(super) above: Vec<Option<usize>>,
    pub(super) below: Vec<Option<usize>>,
    /// Every point's row over its body's carried modes, padded to whole groups.
    pub(super) rows: Vec<V>,
    /// Number of groups.
    pub(super) groups: usize,
    /// Per body: its points (indices into `points`, ascending).
    pub(super) body_points: Vec<Vec<usize>>,
    /// Per family one body of it: bodies of one kind whose points have the same rows share the
    /// influence of their points on each other ([`super::influence::Influence`]).
    pub(super) families: Vec<usize>,
    /// `body_points` flattened, and per body its points' span in it and where its family's
    /// influence matrix starts ([`super::influence::Influence`]: the families' (points)²
    /// blocks in order).
    pub(super) point_list: Vec<usize>,
    pub(super) body_spans: Vec<BodySpan>,
}

impl Layout {
    /// The layout of `ode` with damping rates `rates` per coordinate, whose state starts at
    /// `start` (positions, velocities and static modal forces, each per coordinate).
    pub(super) fn new(ode: &LatticeOde, rates: &[f64], start: [&[f64]; 3]) -> Self {
        let mut me = Layout::default();
        let mut kinds: Vec<(Vec<(f64, f64)>, usize)> = Vec::new();
        for state in ode.body_ranges() {
            let modes = carried_modes(ode, state.clone(), start);
            let key: Vec<(f64, f64)> = modes
                .iter()
                .map(|&m| (ode.graph.omega2[m], rates[m]))
                .collect();
            let kind = match kinds.iter().find(|(k, _)| *k == key) {
                Some(&(_, k)) => k,
                None => {
                    let k = me.kind_modes.len();
                    for chunk in key.chunks(4) {
                        let (mut g, mut omega2) = ([None; 4], V::ZERO);
                        for (l, &(w2, rate)) in chunk.iter().enumerate() {
                            g[l] = Some((w2.sqrt(), rate));
                            omega2.0[l] = w2;
                        }
                        me.kind_modes.push(g);
                        me.kind_omega2.push(omega2);
                    }
                    kinds.push((key, k));
                    k
                }
            };
            let groups = modes.len().div_ceil(4);
            me.bodies.push(Body {
                whole: modes.len() == state.len(),
                state,
                modes,
                group: me.groups,
                kind,
                groups,
            });
            me.groups += groups;
        }
        me.body_points = vec![Vec::new(); me.bodies.len()];
        for c in 0..ode.graph.beta.len() {
            let above = me.point(ode, Some(ode.graph.above[c]));
            let below = me.point(ode, ode.graph.below[c]);
            me.above.push(above);
            me.below.push(below);
        }
        me.group_families();
        me
    }

    /// The families of bodies (one kind, the same rows at their points) and each body's span
    /// of points and influence block.
    fn group_families(&mut self) {
        let mut families = std::collections::HashMap::new();
        let mut body_family = Vec::with_capacity(self.bodies.len());
        for (b, body) in self.bodies.iter().enumerate() {
            let rows = self.body_points[b].iter().flat_map(|&p| self.point_row(p));
            let key: (usize, Vec<u64>) = (
                body.kind,
                rows.flat_map(|r| r.0).map(f64::to_bits).collect(),
            );
            let next = families.len();
            let family = *families.entry(key).or_insert_with(|| {
                self.families.push(b);
                next
            });
            body_family.push(family);
        }
        let mut matrix_starts = Vec::with_capacity(self.families.len());
        let mut next = 0;
        for &b in &self.families {
            matrix_starts.push(next);
            next += self.body_points[b].len().pow(2);
        }
        for (points, &family) in self.body_points.iter().zip(&body_family) {
            self.body_spans.push(BodySpan {
                start: self.point_list.len(),
                points: points.len(),
                matrix: matrix_starts[family],
            });
            self.point_list.extend_from_slice(points);
        }
    }

    /// Point p's row over its body's carried modes, in groups.
    pub(super) fn point_row(&self, p: usize) -> &[V] {
        let point = &self.points[p];
        &self.rows[point.row..point.row + point.groups]
    }

    /// The point of a contact's side (None for an empty side): one of its body's points whose
    /// row agrees with the side's to [`SAME_POINT_ROW_OF_LARGEST`], or a new one, its row
    /// appended to [`Layout::rows`].
    pub(super) fn point(
        &mut self,
        ode: &LatticeOde,
        side: Option<crate::ode::Side>,
    ) -> Option<usize> {
        let side = side.filter(|s| s.len > 0)?;
        // (The bodies lie in the state in order.)
        let index = self.bodies.partition_point(|b| b.state.start < side.offset);
        let body = &self.bodies[index];
        debug_assert_eq!(body.state, side.offset..side.offset + side.len);
        let row: Vec<f64> = body
            .modes
            .iter()
            .map(|&m| ode.graph.rows[side.row + m - side.offset])
            .collect();
        let largest = row.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
        let same = |&p: &usize| {
            let rows = self.point_row(p).iter().flat_map(|r| r.0);
            rows.zip(&row)
                .all(|(a, b)| (a - b).abs() <= SAME_POINT_ROW_OF_LARGEST * largest)
        };
        if let Some(&p) = self.body_points[index].iter().find(|p| same(p)) {
            return Some(p);
        }
        let first = self.rows.len();
        for chunk in row.chunks(4) {
            let mut r = V::ZERO;
            r.0[..chunk.len()].copy_from_slice(chunk);
            self.rows.push(r);
        }
        self.points.push(Point {
            body: index,
            group: body.group,
            kind: body.kind,
            row: first,
            groups: body.groups,
        });
        self.body_points[index].push(self.points.len() - 1);
        Some(self.points.len() - 1)
    }

    /// The values of coordinates `x` (the state's layout) in groups.
    pub(super) fn gather(&self, x: &[f64], out: &mut [V]) {
        for b in &self.bodies {
            let groups = &mut out[b.group..b.group + b.groups];
            groups.fill(V::ZERO);
            for (k, &m) in b.modes.iter().enumerate() {
                groups[k / 4].0[k % 4] = x[m];
            }
        }
    }

    /// Per body: whether any of its grouped `values` is not zero.
    pub(super) fn nonzero_bodies(&self, values: &[&[V]]) -> Vec<bool> {
        let nonzero = |g: &V| g.0.iter().any(|&x| x != 0.0);
        self.bodies
            .iter()
            .map(|b| {
                let groups = b.group..b.group + b.groups;
                values.iter().any(|v| v[groups.clone()].iter().any(nonzero))
            })
            .collect()
    }

    /// Grouped values back into the state's layout (a body of whole groups as one move of four
    /// per group: a copy of a length unknown at compile time is a call to `memcpy` per group).
    #[inline(always)]
    pub(super) fn scatter(&self, groups: &[V], x: &mut [f64]) {
        for b in &self.bodies {
            let groups = &groups[b.group..b.group + b.groups];
            if !b.whole {
                for (g, modes) in groups.iter().zip(b.modes.chunks(4)) {
                    for (&value, &m) in g.0.iter().zip(modes) {
                        x[m] = value;
                    }
                }
                continue;
            }
            for (chunk, g) in x[b.state.clone()].chunks_mut(4).zip(groups) {
                match <&mut [f64; 4]>::try_from(&mut *chunk) {
                    Ok(whole) => *whole = g.0,
                    Err(_) => {
                        let n = chunk.len();
                        chunk.copy_from_slice(&g.0[..n]);
                    }
                }
            }
        }
    }

    /// Σ r x at the three nodes over point p's groups (`values`: per group, the three nodes);
    /// zero without a look where the point's body is not `active` (its values all zero).
    #[inline(always)]
    pub(super) fn dot3(&self, p: usize, values: &[[V; 3]], active: &[bool]) -> [f64; 3] {
        let point = self.points[p];
        if !active[point.body] {
            return [0.0; 3];
        }
        let rows = &self.rows[point.row..point.row + point.groups];
        let values = &values[point.group..point.group + point.groups];
        let (mut a0, mut a1, mut a2) = (V::ZERO, V::ZERO, V::ZERO);
        for (&r, &[x0, x1, x2]) in rows.iter().zip(values) {
            a0 = a0 + r * x0;
            a1 = a1 + r * x1;
            a2 = a2 + r * x2;
        }
        // The lanes summed out of sight of the loop: otherwise the compiler regroups the loop's
        // lanes for the final sums, two per vector.
        let [a0, a1, a2] = std::hint::black_box([a0, a1, a2]);
        [a0.sum(), a1.sum(), a2.sum()]
    }

    /// The carried modes' kinetic and strain energy Σ ½ (q̇² + ω² q²) for grouped positions
    /// and velocities `x`, `v` \[J\] (the modes left out are at rest).
    pub(super) fn modal_energy_j(&self, x: &[V], v: &[V]) -> f64 {
        let mut energy = V::ZERO;
        for b in &self.bodies {
            let g = b.group..b.group + b.groups;
            let kinds = &self.kind_omega2[b.kind..b.kind + b.groups];
            for ((&x, &v), &omega2) in x[g.clone()].iter().zip(&v[g]).zip(kinds) {
                energy = energy + V::splat(0.5) * (v * v + omega2 * x * x);
            }
        }
        energy.sum()
    }

    /// Σ r x and Σ r v over point p's groups (`x`, `v`: per group); zero without a look where
    /// the point's body is not `active`.
    #[inline(always)]
    pub(super) fn dot2(&self, p: usize, x: &[V], v: &[V], active: &[bool]) -> [f64; 2] {
        let point = self.points[p];
        if !active[point.body] {
            return [0.0; 2];
        }
        let g = point.group..point.group + point.groups;
        let rows = &self.rows[point.row..point.row + point.groups];
        let (mut a0, mut a1) = (V::ZERO, V::ZERO);
        for (&r, (&x, &v)) in rows.iter().zip(x[g.clone()].iter().zip(&v[g])) {
            a0 = a0 + r * x;
            a1 = a1 + r * v;
        }
        // (Summed out of sight of the loop, as in `Layout::dot3`.)
        let [a0, a1] = std::hint::black_box([a0, a1]);
        [a0.sum(), a1.sum()]
    }

    /// Every point's deflection at the three nodes for grouped values into `out` (`active` as
    /// [`Layout::dot3`]).
    #[inline(always)]
    pub(super) fn deflections3(&self, values: &[[V; 3]], active: &[bool], out: &mut [[f64; 3]]) {
        for (p, d) in out.iter_mut().enumerate() {
            *d = self.dot3(p, values, active);
        }
    }

    /// Contact c's overlap at the three nodes from its points' deflections (above minus below).
    #[inline(always)]
    pub(super) fn overlap3(&self, c: usize, deflections: &[[f64; 3]]) -> [f64; 3] {
        let at = |p: Option<usize>| p.map_or([0.0; 3], |p| deflections[p]);
        let (above, below) = (at(self.above[c]), at(self.below[c]));
        [
            above[0] - below[0],
            above[1] - below[1],
            above[2] - below[2],
        ]
    }
}

/// The modes of the body at `state` that anything moves: a row above [`ZERO_ROW_OF_LARGEST`] at
/// any point of the body a contact acts on, or a start (position, velocity, static force) not
/// zero.
fn carried_modes(
    ode: &LatticeOde,
    state: std::ops::Range<usize>,
    start: [&[f64]; 3],
) -> Vec<usize> {
    let mut carried: Vec<bool> = state
        .clone()
        .map(|m| start.iter().any(|values| values[m] != 0.0))
        .collect();
    let sides = ode
        .graph
        .above
        .iter()
        .copied()
        .chain(ode.graph.below.iter().flatten().copied());
    for side in sides.filter(|s| s.len > 0 && s.offset == state.start) {
        let row = &ode.graph.rows[side.row..side.row + side.len];
        let largest = row.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
        for (keep, r) in carried.iter_mut().zip(row) {
            *keep |= r.abs() > ZERO_ROW_OF_LARGEST * largest;
        }
    }
    state
        .zip(carried)
        .filter(|&(_, keep)| keep)
        .map(|(m, _)| m)
        .collect()
}
