//! The contact graph of a lattice (docs/physics.md §16): every body's modal coordinates, each
//! contact joining a point of the body above to a point of the body below (or a fixed
//! support) through their modal rows, and the contacts' forces at the last evaluation. What
//! the lattice's equations, its lab terms (`ode::lattice_lab`) and its static equilibrium
//! (`ode::lattice_static`) all read.

/// One side of a contact: a body's first coordinate, its number of coordinates and where its
/// row starts in [`ContactGraph::rows`] (a load's side above is empty: `len` 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Side {
    pub offset: usize,
    pub len: usize,
    pub row: usize,
}

impl Side {
    /// The deflection of this side's point for modal coordinates `q` (all of them) and the
    /// rows `rows` (all of them) \[m\] (or its rate, given velocities).
    #[inline(always)]
    pub(crate) fn dot(self, rows: &[f64], q: &[f64]) -> f64 {
        rows[self.row..self.row + self.len]
            .iter()
            .zip(&q[self.offset..self.offset + self.len])
            .map(|(r, x)| r * x)
            .sum()
    }
}

/// The bodies and contacts of a lattice: each contact's overlap δ_c = row_above·q_above −
/// row_below·q_below, and its force F_c pushing the body above up and the body below down
/// through the same rows.
#[derive(Debug, Clone)]
pub(crate) struct ContactGraph {
    /// ω_j² per coordinate [1/s²] (0 for the striker and the rigid modes).
    pub(crate) omega2: Vec<f64>,
    /// Per contact (the striker's or the loads first, then the lattice's contacts): above,
    /// below, β (0 for a load).
    pub(crate) above: Vec<Side>,
    pub(crate) below: Vec<Option<Side>>,
    pub(crate) beta: Vec<f64>,
    pub(crate) rows: Vec<f64>,
    /// (support's contact index, x − x₀, y − y₀ \[m\]).
    pub(crate) supports: Vec<(usize, f64, f64)>,
    /// ψ_tᵀMφ_j per coordinate.
    pub(crate) translation: Vec<f64>,
    /// Number of leading contacts whose force is prescribed (a blast's or drive's points).
    pub(crate) loads: usize,
    /// Whether contact 0 is the striker's.
    pub(crate) struck: bool,
    /// Whether the load points are a displacement actuator's tip contacts (their β the tip's).
    pub(crate) actuator: bool,
    /// Force and overlap per contact at the last evaluation.
    pub(crate) force_n: Vec<f64>,
    pub(crate) overlap_m: Vec<f64>,
}

impl ContactGraph {
    /// Number of modal coordinates Q.
    pub(crate) fn coordinates(&self) -> usize {
        self.omega2.len()
    }

    /// Number of contacts (the striker's or the load points first).
    pub(crate) fn contacts(&self) -> usize {
        self.beta.len()
    }

    /// The deflection at a contact's side (or its rate, given velocities).
    #[inline(always)]
    pub(crate) fn deflection(&self, side: Side, q: &[f64]) -> f64 {
        side.dot(&self.rows, q)
    }

    /// Contact c's overlap at positions q (or its rate at velocities q̇).
    #[inline(always)]
    pub(crate) fn overlap(&self, c: usize, q: &[f64]) -> f64 {
        self.overlaps(c, [q])[0]
    }

    /// Contact c's overlap for each of `qs` (positions, velocities): the deflection above minus
    /// the one below, each [`Side::dot`]'s sum in its order from its −0.0 (`Iterator::sum` of
    /// f64), so bit for bit [`Side::dot`] of each. One pass over the rows: where both sides
    /// have rows of one length (rods of one mesh), the 2N sums run side by side, independent
    /// chains of additions that the processor overlaps.
    #[inline(always)]
    pub(crate) fn overlaps<const N: usize>(&self, c: usize, qs: [&[f64]; N]) -> [f64; N] {
        let above = self.above[c];
        let rows_above = &self.rows[above.row..above.row + above.len];
        let mut d = [-0.0; N];
        let mut below_d = [-0.0; N];
        match self.below[c] {
            Some(below) if below.len == above.len => {
                let rows_below = &self.rows[below.row..below.row + below.len];
                let at = |side: Side| qs.map(|q| &q[side.offset..side.offset + side.len]);
                let (qa, qb) = (at(above), at(below));
                for (k, (&ra, &rb)) in rows_above.iter().zip(rows_below).enumerate() {
                    for n in 0..N {
                        d[n] += ra * qa[n][k];
                        below_d[n] += rb * qb[n][k];
                    }
                }
            }
            below => {
                for n in 0..N {
                    d[n] = above.dot(&self.rows, qs[n]);
                }
                if let Some(b) = below {
                    below_d = qs.map(|q| b.dot(&self.rows, q));
                }
            }
        }
        if self.below[c].is_some() {
            for n in 0..N {
                d[n] -= below_d[n];
            }
        }
        d
    }

    /// The supports' impulse rates (Σ F_s, Σ (x_s − x₀) F_s, Σ (y_s − y₀) F_s) from `force_n`.
    pub(crate) fn support_impulse_rates(&self) -> [f64; 3] {
        let mut impulse = [0.0; 3];
        for &(c, dx, dy) in &self.supports {
            let f = self.force_n[c];
            impulse[0] += f;
            impulse[1] += dx * f;
            impulse[2] += dy * f;
        }
        impulse
    }

    /// Adds every contact's force (in `force_n`) to the accelerations a through its rows.
    #[inline(always)]
    pub(crate) fn apply_contact_forces(&self, a: &mut [f64]) {
        for c in 0..self.beta.len() {
            let f = self.force_n[c];
            if f == 0.0 {
                continue;
            }
            let s = self.above[c];
            for (k, r) in self.rows[s.row..s.row + s.len].iter().enumerate() {
                a[s.offset + k] -= r * f;
            }
            if let Some(s) = self.below[c] {
                for (k, r) in self.rows[s.row..s.row + s.len].iter().enumerate() {
                    a[s.offset + k] += r * f;
                }
            }
        }
    }
}
