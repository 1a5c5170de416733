//! A lattice struck by a sphere as y' = f(t, y) (docs/physics.md §16): a contact graph.
//!
//! Every body moves in mass-normalised modal coordinates q (the striker: one coordinate
//! q = √m u; a rod: its free–free modes), so that q̈_j = −ω_j² q_j + Σ_c row_cj F_c: contact c
//! joins a point of the body above and a point of the body below (or a fixed support), its
//! overlap is δ_c = row_above·q_above − row_below·q_below (displacements positive downward),
//! and its force F_c = β δ₊^{3/2} pushes the body above up and the body below down through the
//! same rows.
//!
//! State layout (Q modal coordinates in all):
//!
//! ```text
//! y = [ q_0 … q_{Q−1} | ∫J dt (3) | q̇_0 … q̇_{Q−1} | J (3) ]
//! ```
//!
//! J = ∫ (Σ F_s, Σ (x_s − x₀) F_s, Σ (y_s − y₀) F_s) dt over the supports s, the impulse of the
//! supports and its moments about the impact point (x₀, y₀), integrated with the motion so that
//! momentum and moment of momentum can be audited to the integrator's accuracy. (Their time
//! integrals ∫J dt are carried only to keep the state of the form x'' = a(x).)

use crate::error::{require_positive, Result};
use crate::excitation::Striker;
use crate::integrate::OdeSystem;
use crate::model::{hertz_beta, ContactLaw, Lattice, Surface};

/// One side of a contact: a body's first coordinate, its number of coordinates and where its
/// row starts in [`LatticeOde::rows`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Side {
    pub offset: usize,
    pub len: usize,
    pub row: usize,
}

impl Side {
    /// The deflection of this side's point for modal coordinates `q` (all of them) and the
    /// rows `rows` (all of them) \[m\].
    #[inline(always)]
    pub(crate) fn dot(self, rows: &[f64], q: &[f64]) -> f64 {
        rows[self.row..self.row + self.len]
            .iter()
            .zip(&q[self.offset..self.offset + self.len])
            .map(|(r, x)| r * x)
            .sum()
    }
}

/// The compiled equations of a lattice under a striker.
#[derive(Debug, Clone)]
pub struct LatticeOde {
    /// ω_j² per coordinate [1/s²] (0 for the striker and the rigid modes).
    pub(crate) omega2: Vec<f64>,
    /// Per contact (striker first, then the lattice's contacts): above, below, β.
    pub(crate) above: Vec<Side>,
    pub(crate) below: Vec<Option<Side>>,
    pub(crate) beta: Vec<f64>,
    pub(crate) rows: Vec<f64>,
    /// (support's contact index, x − x₀, y − y₀ \[m\]).
    pub(crate) supports: Vec<(usize, f64, f64)>,
    /// Per body (striker, rods): offset, count, centre − impact point \[m\], axis.
    bodies: Vec<(usize, usize, [f64; 2], [f64; 2])>,
    /// ψ_tᵀMφ_j and ψ_rᵀMφ_j per coordinate.
    translation: Vec<f64>,
    rocking: Vec<f64>,
    /// Overlap limit per contact \[m\].
    pub(crate) overlap_limit_m: Vec<f64>,
    /// The striker's mass \[kg\] and initial velocity \[m/s\].
    striker_mass_kg: f64,
    striker_velocity_m_s: f64,
    /// Force and overlap per contact at the last evaluation.
    pub(crate) force_n: Vec<f64>,
    pub(crate) overlap_m: Vec<f64>,
}

impl LatticeOde {
    /// The lattice struck by `striker` at `at_m` = (x, y) \[m\] on its top layer (on the axis
    /// of the top rod there, within its radius); errors name `excitation.at_mm`.
    pub fn new(lattice: &Lattice, striker: &Striker, at_m: [f64; 2]) -> Result<Self> {
        striker.validate()?;
        let hit = lattice.top_point(at_m, "excitation.at_mm")?;
        // The striker's force acts on the top rod's axis (a rod neither twists nor rolls in this
        // model): the impact point is the point of the axis under `at_m`.
        let at_m = lattice.rods[hit.rod].point_m(hit.s_m);
        let mut omega2 = vec![0.0];
        let m_s = striker.mass_kg();
        let mut translation = vec![m_s.sqrt()];
        let mut rocking = vec![0.0];
        let mut bodies = vec![(0, 1, [0.0, 0.0], [1.0, 0.0])];
        for rod in &lattice.rods {
            let offset = omega2.len();
            let modes = &rod.modes;
            omega2.extend(modes.omega_rad_s.iter().map(|w| w * w));
            translation.extend_from_slice(&modes.translation_participation);
            rocking.extend_from_slice(&modes.rocking_participation);
            let c = [rod.centre_m[0] - at_m[0], rod.centre_m[1] - at_m[1]];
            bodies.push((offset, modes.omega_rad_s.len(), c, rod.axis));
        }
        let mut rows = vec![1.0 / m_s.sqrt()];
        let side = |point: crate::model::RodPoint, rows: &mut Vec<f64>| {
            let (offset, len, _, _) = bodies[point.rod + 1];
            let row = rows.len();
            rows.extend(lattice.rods[point.rod].modes.modal_row(point.s_m));
            Side { offset, len, row }
        };
        let top = &lattice.rods[hit.rod];
        let striker_beta = match striker.beta_override {
            Some(b) => require_positive("excitation.beta", b)?,
            None => hertz_beta(
                Surface::Sphere {
                    radius_m: 0.5 * striker.diameter_m,
                },
                &striker.material,
                top.surface(),
                &top.rod.material,
            )?,
        };
        let mut above = vec![Side {
            offset: 0,
            len: 1,
            row: 0,
        }];
        let mut below = vec![Some(side(hit, &mut rows))];
        let mut beta = vec![striker_beta];
        let mut overlap_limit_m =
            vec![0.1 * (0.5 * top.rod.outer_diameter_m).min(0.5 * striker.diameter_m)];
        let mut supports = Vec::new();
        for contact in &lattice.contacts {
            above.push(side(contact.above, &mut rows));
            below.push(contact.below.map(|b| side(b, &mut rows)));
            if contact.below.is_none() {
                let p = contact.point_m;
                supports.push((beta.len(), p[0] - at_m[0], p[1] - at_m[1]));
            }
            beta.push(contact.beta);
            overlap_limit_m.push(contact.overlap_limit_m);
        }
        let n = beta.len();
        Ok(LatticeOde {
            omega2,
            above,
            below,
            beta,
            rows,
            supports,
            bodies,
            translation,
            rocking,
            overlap_limit_m,
            striker_mass_kg: m_s,
            striker_velocity_m_s: striker.velocity_m_s,
            force_n: vec![0.0; n],
            overlap_m: vec![0.0; n],
        })
    }

    /// The striker's Hertz contact time on a rigid half-space \[s\]: 2.94 δ_max / v₀ with
    /// δ_max = (5 m v₀² / (4 β))^{2/5} (Johnson, *Contact Mechanics*, §11.4), the shortest
    /// event of the run's scale.
    pub fn striker_contact_time_s(&self) -> f64 {
        let (m, v) = (self.striker_mass_kg, self.striker_velocity_m_s);
        let delta_max = (1.25 * m * v * v / self.beta[0]).powf(0.4);
        2.94 * delta_max / v
    }

    /// Number of modal coordinates Q.
    pub fn coordinates(&self) -> usize {
        self.omega2.len()
    }

    /// β per contact, in output order [N/m^1.5].
    pub fn contact_betas(&self) -> &[f64] {
        &self.beta
    }

    /// Whether contact c is a support (a rod on a fixed point).
    pub fn is_support(&self, c: usize) -> bool {
        self.below[c].is_none()
    }

    /// Number of contacts (the striker's first).
    pub fn contacts(&self) -> usize {
        self.beta.len()
    }

    /// The state at t = 0: everything at rest, touching, the striker moving down at v₀.
    pub fn initial_state(&self) -> Vec<f64> {
        let q = self.coordinates();
        let mut y = vec![0.0; 2 * (q + 3)];
        y[q + 3] = self.striker_mass_kg.sqrt() * self.striker_velocity_m_s;
        y
    }

    /// The deflection at a contact's side.
    #[inline(always)]
    fn deflection(&self, side: Side, q: &[f64]) -> f64 {
        side.dot(&self.rows, q)
    }

    /// The stiffest mode's angular frequency \[rad/s\] (what sets an explicit method's step).
    pub fn stiffest_mode_rad_s(&self) -> f64 {
        self.omega2.iter().fold(0.0, |m: f64, &w2| m.max(w2)).sqrt()
    }

    /// Every contact's force rate dF/dt \[N/s\] in state y into `rate` (after
    /// [`LatticeOde::contact_forces`] at y's positions): β (3/2) δ₊^{1/2} δ̇.
    pub(crate) fn contact_force_rates(&self, y: &[f64], rate: &mut [f64]) {
        let q = self.coordinates();
        let v = &y[q + 3..2 * q + 3];
        for (c, r) in rate.iter_mut().enumerate() {
            let mut dv = self.deflection(self.above[c], v);
            if let Some(b) = self.below[c] {
                dv -= self.deflection(b, v);
            }
            *r = ContactLaw::elastic_force_rate(self.force_n[c], self.overlap_m[c], dv);
        }
    }

    /// Every contact's overlap and force at positions q into `overlap_m` and `force_n`.
    pub(crate) fn contact_forces(&mut self, q: &[f64]) {
        for c in 0..self.beta.len() {
            let mut d = self.deflection(self.above[c], q);
            if let Some(b) = self.below[c] {
                d -= self.deflection(b, q);
            }
            self.overlap_m[c] = d;
            self.force_n[c] = ContactLaw::elastic_force(self.beta[c], d);
        }
    }

    /// Kinetic, modal strain and contact energy of a state \[J\].
    pub fn energy_j(&self, y: &[f64]) -> f64 {
        let q = self.coordinates();
        let (x, v) = (&y[..q], &y[q + 3..2 * q + 3]);
        let motion: f64 = (0..q)
            .map(|j| 0.5 * (v[j] * v[j] + self.omega2[j] * x[j] * x[j]))
            .sum();
        let mut contacts = 0.0;
        for c in 0..self.beta.len() {
            let mut d = self.deflection(self.above[c], x);
            if let Some(b) = self.below[c] {
                d -= self.deflection(b, x);
            }
            contacts += ContactLaw::potential_j(self.beta[c], d);
        }
        motion + contacts
    }

    /// The audit of a state: (vertical momentum of every body P \[N s\], its moment about the
    /// impact point H = Σ (r − r₀) p \[N s m\], the supports' impulse J \[N s\] and its moment
    /// \[N s m\]). Newton: P + J_z and H + J_moment are constant.
    pub fn momentum_audit(&self, y: &[f64]) -> (f64, [f64; 2], f64, [f64; 2]) {
        let q = self.coordinates();
        let v = &y[q + 3..2 * q + 3];
        let (mut p, mut h) = (0.0, [0.0, 0.0]);
        for &(offset, len, c, axis) in &self.bodies {
            let vb = &v[offset..offset + len];
            let pb: f64 = vb
                .iter()
                .zip(&self.translation[offset..offset + len])
                .map(|(a, b)| a * b)
                .sum();
            let rb: f64 = vb
                .iter()
                .zip(&self.rocking[offset..offset + len])
                .map(|(a, b)| a * b)
                .sum();
            p += pb;
            h[0] += c[0] * pb + axis[0] * rb;
            h[1] += c[1] * pb + axis[1] * rb;
        }
        let j = &y[2 * q + 3..];
        (p, h, j[0], [j[1], j[2]])
    }

    /// Tolerance units per state component for adaptive methods: 1 for every component, so
    /// atol applies to the modal coordinates as given (q = √m u: for rods of a few grams, atol
    /// on q is about ten times atol on the displacement) and to the supports' impulses.
    pub fn tolerance_units(&self) -> Vec<f64> {
        vec![1.0; 2 * (self.coordinates() + 3)]
    }
}

impl OdeSystem for LatticeOde {
    fn dimension(&self) -> usize {
        2 * (self.coordinates() + 3)
    }

    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        let q = self.coordinates();
        let n = q + 3;
        dydt[..n].copy_from_slice(&y[n..2 * n]);
        self.rhs_accelerations(y, dydt);
    }

    fn second_order(&self) -> Option<usize> {
        Some(self.coordinates() + 3)
    }
}

impl LatticeOde {
    /// The accelerations (and the supports' impulse rates) into dydt's second half.
    fn rhs_accelerations(&mut self, y: &[f64], dydt: &mut [f64]) {
        let q = self.coordinates();
        let x = &y[..q];
        self.contact_forces(x);
        let a = &mut dydt[q + 3..];
        for j in 0..q {
            a[j] = -self.omega2[j] * x[j];
        }
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
        let mut impulse = [0.0; 3];
        for &(c, dx, dy) in &self.supports {
            let f = self.force_n[c];
            impulse[0] += f;
            impulse[1] += dx * f;
            impulse[2] += dy * f;
        }
        a[q..q + 3].copy_from_slice(&impulse);
    }
}
