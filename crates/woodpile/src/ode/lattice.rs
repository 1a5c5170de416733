//! A lattice struck by a sphere, loaded or left at rest, as y' = f(t, y) (docs/physics.md §16):
//! a contact graph. A chain is one too, its cells bodies of one point, under its load and lab
//! physics ([`LatticeOde::from_chain`]).
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
//! With lab physics (docs/physics.md §16; `ode::lattice_lab`): the contacts follow the chains'
//! laws (`model::law`), every rod mode is damped, blasts and drives act on load points (contacts
//! of their own at the head of the list, their force prescribed; under a displacement drive
//! each the Hertz contact of the actuator's tip, δ_c = δ_c⁰ + u(t) − w(point)), the run starts from the static
//! equilibrium under the preload and gravity, and the state ends in the work W of the external
//! forces, the energy dissipated by the modes' damping and that dissipated at each contact:
//!
//! ```text
//! y = [ q | ∫J dt (3) | q̇ | J (3) | W | D_modes | D_0 … D_{C−1} ]
//! ```

mod chain;
pub(super) mod graph;

use super::lattice_lab::LabTerms;
use crate::error::{require_positive, Result};
use crate::excitation::Striker;
use crate::integrate::OdeSystem;
use crate::model::{
    hertz_beta, ContactLaw, Lattice, LatticeExcitation, LatticeLab, LoadPoints, RodPoint, Surface,
};
use graph::{ContactGraph, Side};

/// Contacts whose sums [`LatticeOde::contact_forces_and_rates_at`] runs side by side.
const SIDE_BY_SIDE: usize = 2;

/// The compiled equations of a lattice under a striker, a load or nothing.
#[derive(Debug, Clone)]
pub struct LatticeOde {
    /// The bodies' modes, the contacts and their forces at the last evaluation.
    pub(crate) graph: ContactGraph,
    /// Per body (striker, rods): offset, count, centre − reference point \[m\], axis.
    bodies: Vec<(usize, usize, [f64; 2], [f64; 2])>,
    /// ψ_rᵀMφ_j per coordinate.
    rocking: Vec<f64>,
    /// Overlap limit per contact \[m\] (infinite for a load).
    pub(crate) overlap_limit_m: Vec<f64>,
    /// The striker's mass \[kg\] and initial velocity \[m/s\] (0 and 0 without a striker).
    pub(crate) striker_mass_kg: f64,
    pub(crate) striker_velocity_m_s: f64,
    /// Damping, static load, blast or drive; None: the lossless impact (the first slice's path).
    pub(super) lab: Option<Box<LabTerms>>,
}

impl LatticeOde {
    /// The lattice struck by `striker` at `at_m` = (x, y) \[m\] on its top layer (on the axis
    /// of the top rod there, within its radius), lossless and unloaded; errors name
    /// `excitation.at_mm`.
    pub fn new(lattice: &Lattice, striker: &Striker, at_m: [f64; 2]) -> Result<Self> {
        striker.validate()?;
        let hit = lattice.top_point(at_m, "excitation.at_mm")?;
        Self::compile(lattice, Some((striker, hit)), &[])
    }

    /// The lattice under any excitation, with damping and a static load
    /// (docs/physics.md §16). With `lab` none and an impact this is [`LatticeOde::new`], bit
    /// for bit. Errors name the scenario keys.
    pub fn build(
        lattice: &Lattice,
        excitation: &LatticeExcitation,
        lab: &LatticeLab,
    ) -> Result<Self> {
        excitation.validate()?;
        lab.validate()?;
        let mut ode = match excitation {
            LatticeExcitation::Impact { striker, at_m } => {
                let ode = Self::new(lattice, striker, *at_m)?;
                if lab.is_none() {
                    return Ok(ode);
                }
                ode
            }
            LatticeExcitation::Rest { .. } if lab.preload.force_n == 0.0 => {
                Self::compile(lattice, None, &[])?
            }
            _ => {
                let points = excitation
                    .load_points()
                    .expect("a load has points")
                    .on(lattice)?;
                let mut ode = Self::compile(lattice, None, &points)?;
                if let Some(tip) = excitation.actuator_tip() {
                    ode.attach_actuator(lattice, tip, &points)?;
                }
                ode
            }
        };
        let mut preload_points = Vec::new();
        if ode.graph.struck && lab.preload.force_n != 0.0 {
            for p in LoadPoints::TopCrossings.on(lattice)? {
                let row = lattice.rods[p.rod].modes.modal_row(p.s_m);
                preload_points.push((ode.rod_coordinates(p.rod).0, row));
            }
        }
        let terms = LabTerms::compile(&ode.graph, &preload_points, excitation, lab)?;
        ode.lab = Some(Box::new(terms));
        Ok(ode)
    }

    /// The equations: the striker's body and contact (if any), a load contact per point, then
    /// the lattice's contacts.
    fn compile(
        lattice: &Lattice,
        striker: Option<(&Striker, RodPoint)>,
        load_points: &[RodPoint],
    ) -> Result<Self> {
        // The reference point of the moment audit: the impact point on the top rod's axis (a
        // rod neither twists nor rolls in this model, so an off-axis force would act on the
        // axis anyway), or the origin under a load.
        let at_m = striker.map_or([0.0, 0.0], |(_, hit)| {
            lattice.rods[hit.rod].point_m(hit.s_m)
        });
        let (mut omega2, mut translation, mut rocking, mut bodies) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut rows = Vec::new();
        if let Some((striker, _)) = striker {
            let m_s = striker.mass_kg();
            omega2.push(0.0);
            translation.push(m_s.sqrt());
            rocking.push(0.0);
            bodies.push((0, 1, [0.0, 0.0], [1.0, 0.0]));
            rows.push(1.0 / m_s.sqrt());
        }
        let first_rod = bodies.len();
        for rod in &lattice.rods {
            let offset = omega2.len();
            let modes = &rod.modes;
            omega2.extend(modes.omega_rad_s.iter().map(|w| w * w));
            translation.extend_from_slice(&modes.translation_participation);
            rocking.extend_from_slice(&modes.rocking_participation);
            let c = [rod.centre_m[0] - at_m[0], rod.centre_m[1] - at_m[1]];
            bodies.push((offset, modes.omega_rad_s.len(), c, rod.axis));
        }
        let side = |point: RodPoint, rows: &mut Vec<f64>| {
            let (offset, len, _, _) = bodies[point.rod + first_rod];
            let row = rows.len();
            rows.extend(lattice.rods[point.rod].modes.modal_row(point.s_m));
            Side { offset, len, row }
        };
        let (mut above, mut below, mut beta, mut overlap_limit_m) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let (mut striker_mass_kg, mut striker_velocity_m_s) = (0.0, 0.0);
        if let Some((striker, hit)) = striker {
            let top = &lattice.rods[hit.rod];
            beta.push(striker_beta(striker, top)?);
            above.push(Side {
                offset: 0,
                len: 1,
                row: 0,
            });
            below.push(Some(side(hit, &mut rows)));
            overlap_limit_m
                .push(0.1 * (0.5 * top.rod.outer_diameter_m).min(0.5 * striker.diameter_m));
            striker_mass_kg = striker.mass_kg();
            striker_velocity_m_s = striker.velocity_m_s;
        }
        for &point in load_points {
            let empty = Side {
                offset: 0,
                len: 0,
                row: rows.len(),
            };
            above.push(empty);
            below.push(Some(side(point, &mut rows)));
            beta.push(0.0);
            overlap_limit_m.push(f64::INFINITY);
        }
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
            graph: ContactGraph {
                omega2,
                above,
                below,
                beta,
                rows,
                supports,
                translation,
                loads: load_points.len(),
                struck: striker.is_some(),
                actuator: false,
                force_n: vec![0.0; n],
                overlap_m: vec![0.0; n],
            },
            bodies,
            rocking,
            overlap_limit_m,
            striker_mass_kg,
            striker_velocity_m_s,
            lab: None,
        })
    }

    /// Makes the load contacts the Hertz contacts of a displacement actuator's tip on each
    /// point: β of the tip against the top rod there (errors name `excitation.tip`), and an
    /// overlap limit of a tenth of the smaller radius, as at a support.
    fn attach_actuator(
        &mut self,
        lattice: &Lattice,
        tip: &crate::model::Wall,
        points: &[RodPoint],
    ) -> Result<()> {
        let tip_radius = match tip {
            crate::model::Wall::Cap { radius_m, .. } => *radius_m,
            _ => f64::INFINITY,
        };
        for (c, p) in points.iter().enumerate() {
            let rod = &lattice.rods[p.rod];
            let beta = tip
                .beta_against(rod.surface(), &rod.rod.material)
                .map_err(|e| match e {
                    crate::error::Error::InvalidParameter {
                        field,
                        value,
                        reason,
                    } => crate::error::Error::InvalidParameter {
                        field: field.replacen("wall", "excitation.tip", 1),
                        value,
                        reason,
                    },
                    e => e,
                })?
                .expect("a free tip is refused by LatticeExcitation::validate");
            self.graph.beta[c] = beta;
            self.overlap_limit_m[c] = 0.1 * (0.5 * rod.rod.outer_diameter_m).min(tip_radius);
        }
        self.graph.actuator = true;
        Ok(())
    }

    /// Whether the load points are a displacement actuator's tip contacts.
    pub fn has_actuator(&self) -> bool {
        self.graph.actuator
    }

    /// A displacement actuator's static position u* \[m\] (downward; None without one): the
    /// δ⁰ of every tip, whose overlap is δ_i = u* + u(t) − w_i (docs/physics.md §16). With a
    /// preload it is the rigid actuator's equilibrium height, where its tips' forces sum to
    /// F_p; without one the height at which it touches the highest of its points.
    pub fn actuator_rest_m(&self) -> Option<f64> {
        self.lab
            .as_ref()
            .filter(|_| self.graph.actuator)
            .map(|l| l.actuator_rest_m)
    }

    /// (first coordinate, number of coordinates) of rod `rod` (its index in the lattice).
    pub(super) fn rod_coordinates(&self, rod: usize) -> (usize, usize) {
        let (offset, len, _, _) = self.bodies[rod + usize::from(self.graph.struck)];
        (offset, len)
    }

    /// Number of modal coordinates Q.
    pub fn coordinates(&self) -> usize {
        self.graph.coordinates()
    }

    /// β per contact, in output order [N/m^1.5] (0 for a load point of a prescribed force).
    pub fn contact_betas(&self) -> &[f64] {
        &self.graph.beta
    }

    /// Whether contact c is a support (a rod on a fixed point).
    pub fn is_support(&self, c: usize) -> bool {
        self.graph.below[c].is_none()
    }

    /// Number of contacts (the striker's or the load points first).
    pub fn contacts(&self) -> usize {
        self.graph.contacts()
    }

    /// The contacts that load the lattice from above, whose forces sum to the incident force:
    /// the striker's, or the load points (none at rest without a preload).
    pub fn has_striker(&self) -> bool {
        self.graph.struck
    }

    /// The contacts that carry the load: the striker's, or the load points.
    pub fn incident_contacts(&self) -> std::ops::Range<usize> {
        0..if self.graph.struck {
            1
        } else {
            self.graph.loads
        }
    }

    /// Whether the run has lab physics (damping, a static load, a blast or a drive): its
    /// state then ends in W, the modes' and every contact's dissipated energy.
    pub fn has_lab(&self) -> bool {
        self.lab.is_some()
    }

    /// The state at t = 0: everything at rest, touching (in static equilibrium under a static
    /// load), the striker moving down at v₀.
    pub fn initial_state(&self) -> Vec<f64> {
        let q = self.coordinates();
        let mut y = vec![0.0; self.dimension()];
        if let Some(lab) = &self.lab {
            y[..q].copy_from_slice(&lab.q0);
        }
        if self.graph.struck {
            // The striker touches the top rod at zero overlap; rounding must not leave it pressed
            // in by an ulp, where a damped contact law would push at once (c δ̇ at δ = 0⁺).
            let hit = self.graph.below[0].expect("the striker's contact has a rod below");
            y[0] = self.graph.deflection(hit, &y[..q]) / self.graph.rows[0];
            while self.graph.overlap(0, &y[..q]) > 0.0 {
                y[0] = y[0].next_down();
            }
            y[q + 3] = self.striker_mass_kg.sqrt() * self.striker_velocity_m_s;
        }
        y
    }

    /// The stiffest mode's angular frequency \[rad/s\] (what sets an explicit method's step).
    pub fn stiffest_mode_rad_s(&self) -> f64 {
        self.graph
            .omega2
            .iter()
            .fold(0.0, |m: f64, &w2| m.max(w2))
            .sqrt()
    }

    /// The striker's Hertz contact time on a rigid half-space \[s\]
    /// ([`ContactLaw::elastic_contact_time_s`]), the shortest event of the run's scale;
    /// infinite without a striker.
    pub fn striker_contact_time_s(&self) -> f64 {
        let (m, v) = (self.striker_mass_kg, self.striker_velocity_m_s);
        if !self.graph.struck || v <= 0.0 {
            return f64::INFINITY;
        }
        ContactLaw::elastic_contact_time_s(self.graph.beta[0], m, v)
    }

    /// The overlaps of K contacts for each of `qs`, bit for bit [`ContactGraph::overlaps`] of
    /// each (every sum in its order from −0.0), their 2KN sums side by side in one loop: None
    /// unless every side of them has rows of one length (rods of one mesh; no support).
    #[inline(always)]
    fn overlaps_side_by_side<const K: usize, const N: usize>(
        &self,
        contacts: [usize; K],
        qs: [&[f64]; N],
    ) -> Option<[[f64; N]; K]> {
        let len = self.graph.above[contacts[0]].len;
        let mut sides = [[self.graph.above[contacts[0]]; 2]; K];
        for (pair, &c) in sides.iter_mut().zip(&contacts) {
            *pair = [self.graph.above[c], self.graph.below[c]?];
            if pair.iter().any(|s| s.len != len) {
                return None;
            }
        }
        let rows = sides.map(|pair| pair.map(|s| &self.graph.rows[s.row..s.row + len]));
        let values = sides.map(|pair| pair.map(|s| qs.map(|q| &q[s.offset..s.offset + len])));
        let mut sums = [[[-0.0; N]; 2]; K];
        for k in 0..len {
            for ((sum, rows), values) in sums.iter_mut().zip(&rows).zip(&values) {
                for ((sum, rows), values) in sum.iter_mut().zip(rows).zip(values) {
                    for (s, q) in sum.iter_mut().zip(values) {
                        *s += rows[k] * q[k];
                    }
                }
            }
        }
        Some(sums.map(|[above, below]| std::array::from_fn(|n| above[n] - below[n])))
    }

    /// Every contact's overlap and force at (t, y) as [`LatticeOde::contact_forces_at`], and
    /// its force rate dF/dt \[N/s\] into `rate`: with `elastic_rates` (lab physics in a run
    /// that [`LatticeOde::fits_exact_modes`]) the elastic (3/2) F δ̇ / δ at the contacts and the
    /// load's rate at the load points; otherwise the elastic rate when lossless, 0 with lab
    /// physics (the peaks are then those of the step ends). One pass over the rows: the overlap
    /// rates are those the lab's contact laws read, or lossless summed beside the overlaps (bit
    /// for bit separate passes).
    pub(crate) fn contact_forces_and_rates_at(
        &mut self,
        t: f64,
        y: &[f64],
        elastic_rates: bool,
        rate: &mut [f64],
    ) {
        let Some(mut lab) = self.lab.take() else {
            let q = self.coordinates();
            let (x, v) = (&y[..q], &y[q + 3..2 * q + 3]);
            let mut c = 0;
            while c < rate.len() {
                if c + SIDE_BY_SIDE <= rate.len() {
                    let contacts: [usize; SIDE_BY_SIDE] = std::array::from_fn(|k| c + k);
                    if let Some(group) = self.overlaps_side_by_side(contacts, [x, v]) {
                        for [d, dv] in group {
                            rate[c] = self.set_elastic(c, d, dv);
                            c += 1;
                        }
                        continue;
                    }
                }
                let [d, dv] = self.graph.overlaps(c, [x, v]);
                rate[c] = self.set_elastic(c, d, dv);
                c += 1;
            }
            return;
        };
        lab.contact_forces(&mut self.graph, t, y);
        if elastic_rates {
            let load = lab.load_rate_per_point_n_s(t);
            let overlap_rates = lab.overlap_rates_m_s();
            for (c, r) in rate.iter_mut().enumerate() {
                *r = if c < self.graph.loads {
                    load
                } else {
                    let (f, d) = (self.graph.force_n[c], self.graph.overlap_m[c]);
                    ContactLaw::elastic_force_rate(f, d, overlap_rates[c])
                };
            }
        } else {
            rate.fill(0.0);
        }
        self.lab = Some(lab);
    }

    /// Contact c's overlap d and elastic force into `overlap_m` and `force_n`; returns the
    /// force's rate at the overlap's rate `rate_m_s`.
    #[inline(always)]
    fn set_elastic(&mut self, c: usize, d: f64, rate_m_s: f64) -> f64 {
        let f = ContactLaw::elastic_force(self.graph.beta[c], d);
        self.graph.overlap_m[c] = d;
        self.graph.force_n[c] = f;
        ContactLaw::elastic_force_rate(f, d, rate_m_s)
    }

    /// Every contact's overlap and force at state y (positions, and with lab physics
    /// velocities and time) into `overlap_m` and `force_n`.
    pub fn contact_forces_at(&mut self, t: f64, y: &[f64]) {
        match self.lab.take() {
            None => self.contact_forces(&y[..self.coordinates()]),
            Some(mut lab) => {
                lab.contact_forces(&mut self.graph, t, y);
                self.lab = Some(lab);
            }
        }
    }

    /// Every contact's overlap and elastic force at positions q into `overlap_m` and
    /// `force_n` (the lossless path).
    pub(crate) fn contact_forces(&mut self, q: &[f64]) {
        for c in 0..self.graph.beta.len() {
            let d = self.graph.overlap(c, q);
            self.graph.overlap_m[c] = d;
            self.graph.force_n[c] = ContactLaw::elastic_force(self.graph.beta[c], d);
        }
    }

    /// Number of bodies: the striker (if any) and the rods.
    pub fn bodies(&self) -> usize {
        self.bodies.len()
    }

    /// Number of entries of [`LatticeOde::body_energies_j`]: layer 0 (the striker, or a
    /// displacement actuator) if any, then the rods.
    pub fn energy_bodies(&self) -> usize {
        self.bodies.len() + usize::from(self.graph.actuator)
    }

    /// Contact c's Hertz potential (2/5) β δ₊^{5/2} at the overlap of the last evaluation
    /// ([`LatticeOde::contact_forces_at`]) \[J\]: 0 at a load point of a prescribed force (its
    /// work is W).
    #[inline]
    fn contact_potential_j(&self, c: usize) -> f64 {
        if c < self.graph.loads && !self.graph.actuator {
            return 0.0;
        }
        ContactLaw::potential_j(self.graph.beta[c], self.graph.overlap_m[c])
    }

    /// Every contact's Hertz potential into `out` (one per contact, output order) \[J\], at the
    /// state of the last [`LatticeOde::contact_forces_at`] (its overlaps: an actuator's tip
    /// overlaps depend on the time). [`LatticeOde::energy_j`] and
    /// [`LatticeOde::body_energies_j`] take these.
    pub fn contact_energies_j(&self, out: &mut [f64]) {
        for (c, e) in out.iter_mut().enumerate() {
            *e = self.contact_potential_j(c);
        }
    }

    /// Each body's energy in state y into `out` ([`LatticeOde::energy_bodies`] entries: the
    /// striker or a displacement actuator first, if any, then the rods in the lattice's order),
    /// as a chain's layer energies (docs/physics.md §7): its modes' kinetic and strain energy
    /// Σ ½ (q̇_j² + ω_j² q_j²) plus half of the Hertz potential of every contact it takes part
    /// in (the actuator: half of each tip contact's), from `contact_energies_j`
    /// ([`LatticeOde::contact_energies_j`] at y). Returns the supports' halves \[J\]; the sum of
    /// both is [`LatticeOde::energy_j`].
    pub fn body_energies_j(&self, y: &[f64], contact_energies_j: &[f64], out: &mut [f64]) -> f64 {
        let q = self.coordinates();
        let (x, v) = (&y[..q], &y[q + 3..2 * q + 3]);
        let first = usize::from(self.graph.actuator);
        out[..first].fill(0.0);
        for (e, &(offset, len, _, _)) in out[first..].iter_mut().zip(&self.bodies) {
            *e = (offset..offset + len)
                .map(|j| 0.5 * (v[j] * v[j] + self.graph.omega2[j] * x[j] * x[j]))
                .sum();
        }
        let body = |side: Side| first + self.bodies.partition_point(|b| b.0 <= side.offset) - 1;
        let mut supports = 0.0;
        for (c, &potential) in contact_energies_j.iter().enumerate() {
            let half = 0.5 * potential;
            if half == 0.0 {
                continue;
            }
            // A load contact's side above is the actuator (layer 0).
            out[if c < self.graph.loads {
                0
            } else {
                body(self.graph.above[c])
            }] += half;
            match self.graph.below[c] {
                Some(b) => out[body(b)] += half,
                None => supports += half,
            }
        }
        supports
    }

    /// Kinetic, modal strain and contact energy of state y \[J\], the contacts' from
    /// `contact_energies_j` ([`LatticeOde::contact_energies_j`] at y; an actuator's tip
    /// contacts included).
    pub fn energy_j(&self, y: &[f64], contact_energies_j: &[f64]) -> f64 {
        let q = self.coordinates();
        let (x, v) = (&y[..q], &y[q + 3..2 * q + 3]);
        let motion: f64 = (0..q)
            .map(|j| 0.5 * (v[j] * v[j] + self.graph.omega2[j] * x[j] * x[j]))
            .sum();
        // (Load points of a prescribed force have no potential: their work is W.)
        let contacts: f64 = contact_energies_j.iter().sum();
        motion + contacts
    }

    /// (work of the external forces W, energy dissipated by the modes' damping and at every
    /// contact D) of a state \[J\]: (0, 0) without lab physics.
    pub fn work_and_dissipation_j(&self, y: &[f64]) -> (f64, f64) {
        if self.lab.is_none() {
            return (0.0, 0.0);
        }
        let i = 2 * (self.coordinates() + 3);
        (y[i], y[i + 1..].iter().sum())
    }

    /// The energy dissipated at each contact up to a state \[J\], in output order (empty without
    /// lab physics).
    pub fn contact_dissipated_j<'a>(&self, y: &'a [f64]) -> &'a [f64] {
        if self.lab.is_none() {
            return &[];
        }
        &y[2 * (self.coordinates() + 3) + 2..]
    }

    /// Each contact's static force \[N\] (the equilibrium the run starts from; empty without
    /// lab physics), and the static solve's relative residual |∇Π| / |f|.
    pub fn static_forces_n(&self) -> (&[f64], f64) {
        self.lab.as_ref().map_or((&[][..], 0.0), |l| {
            (&l.static_force_n[..], l.static_residual)
        })
    }

    /// The audit of a state: (vertical momentum of every body P \[N s\], its moment about the
    /// impact point H = Σ (r − r₀) p \[N s m\], the supports' impulse J \[N s\] and its moment
    /// \[N s m\]). Newton: P + J_z and H + J_moment are constant. Under a load the reference
    /// point is the origin.
    pub fn momentum_audit(&self, y: &[f64]) -> (f64, [f64; 2], f64, [f64; 2]) {
        let q = self.coordinates();
        let v = &y[q + 3..2 * q + 3];
        let (mut p, mut h) = (0.0, [0.0, 0.0]);
        for &(offset, len, c, axis) in &self.bodies {
            let vb = &v[offset..offset + len];
            let pb: f64 = vb
                .iter()
                .zip(&self.graph.translation[offset..offset + len])
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
        let j = &y[q + 3 + q..2 * q + 6];
        (p, h, j[0], [j[1], j[2]])
    }

    /// Tolerance units per state component for adaptive methods: 1 for every component, so
    /// atol applies to the modal coordinates as given (q = √m u: for rods of a few grams, atol
    /// on q is about ten times atol on the displacement), to the supports' impulses and to the
    /// energy integrals W and D (in J).
    pub fn tolerance_units(&self) -> Vec<f64> {
        vec![1.0; self.dimension()]
    }
}

/// The striker's contact β with the top rod it hits (given, or Hertz theory).
fn striker_beta(striker: &Striker, top: &crate::model::LatticeRod) -> Result<f64> {
    match striker.beta_override {
        Some(b) => require_positive("excitation.beta", b),
        None => hertz_beta(
            Surface::Sphere {
                radius_m: 0.5 * striker.diameter_m,
            },
            &striker.material,
            top.surface(),
            &top.rod.material,
        ),
    }
}

impl OdeSystem for LatticeOde {
    fn dimension(&self) -> usize {
        2 * (self.coordinates() + 3) + self.lab.as_ref().map_or(0, |_| 2 + self.contacts())
    }

    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let q = self.coordinates();
        let n = q + 3;
        dydt[..n].copy_from_slice(&y[n..2 * n]);
        match self.lab.take() {
            None => self.rhs_accelerations(y, dydt),
            Some(mut lab) => {
                lab.rhs(&mut self.graph, t, y, dydt);
                self.lab = Some(lab);
            }
        }
    }

    fn second_order(&self) -> Option<usize> {
        self.lab.is_none().then(|| self.coordinates() + 3)
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
            a[j] = -self.graph.omega2[j] * x[j];
        }
        self.graph.apply_contact_forces(a);
        let impulse = self.graph.support_impulse_rates();
        a[q..q + 3].copy_from_slice(&impulse);
    }
}

/// What the exact modal method on the contact graph reads of a lattice
/// (`integrate::modal_graph`, docs/physics.md §8).
impl LatticeOde {
    /// Whether the exact modal method advances this run: an impact, a blast or a force drive on
    /// the lossless lattice, or with its modes damped (`damping.modal_ratio`,
    /// `damping.on_site_time_s`), gravity and a preload: every contact elastic.
    pub fn fits_exact_modes(&self) -> bool {
        (self.graph.struck || self.graph.loads > 0)
            && !self.graph.actuator
            && self.lab.as_ref().is_none_or(|lab| lab.linear_modes_only())
    }

    /// Per coordinate: the constant modal force of gravity and a striker's preload (None without
    /// lab physics; a load's preload is in its points' force).
    pub(crate) fn static_modal_forces(&self) -> Option<&[f64]> {
        self.lab.as_ref().map(|lab| lab.static_modal_force())
    }

    /// Per body (the striker, if any, then the rods): the range of its coordinates.
    pub(crate) fn body_ranges(&self) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
        self.bodies
            .iter()
            .map(|&(offset, len, ..)| offset..offset + len)
    }

    /// Damping rate per coordinate, 2 ζ ω_j + 1/τ [1/s] (None without lab physics).
    pub(crate) fn damping_rates(&self) -> Option<&[f64]> {
        self.lab.as_ref().map(|lab| lab.damping_rates())
    }

    /// Number of leading contacts whose force is prescribed (a blast's or a drive's points).
    pub(crate) fn load_contacts(&self) -> usize {
        self.graph.loads
    }

    /// The times where the load's force or its first two derivatives jump \[s\], ascending
    /// (none without a load).
    pub(crate) fn load_kinks_s(&self) -> Vec<f64> {
        self.lab
            .as_ref()
            .map_or_else(Vec::new, |lab| lab.load_kinks_s())
    }

    /// Each load point's prescribed force at t \[N\] (0 without a load).
    pub(crate) fn load_per_point_n(&self, t: f64) -> f64 {
        self.lab.as_ref().map_or(0.0, |lab| lab.load_per_point_n(t))
    }

    /// Each load point's prescribed force rate at t \[N/s\] (a drive's; 0 for a blast, or
    /// without a load).
    pub(crate) fn load_rate_per_point_n_s(&self, t: f64) -> f64 {
        self.lab
            .as_ref()
            .map_or(0.0, |lab| lab.load_rate_per_point_n_s(t))
    }

    /// The shortest Hertz contact time of the run's scale \[s\]: the striker's
    /// ([`LatticeOde::striker_contact_time_s`]), or under a load the shortest of every contact's
    /// two bodies (their whole masses, reduced; a rod's alone on a support) meeting at
    /// `speed_m_s`.
    pub(crate) fn contact_time_s(&self, speed_m_s: f64) -> f64 {
        if self.graph.struck {
            return self.striker_contact_time_s();
        }
        let mass = |s: Side| -> f64 {
            self.graph.translation[s.offset..s.offset + s.len]
                .iter()
                .map(|t| t * t)
                .sum()
        };
        (self.graph.loads..self.contacts())
            .filter(|&c| self.graph.beta[c] > 0.0)
            .map(|c| {
                let above = mass(self.graph.above[c]);
                let m = self.graph.below[c].map_or(above, |b| {
                    let below = mass(b);
                    above * below / (above + below)
                });
                ContactLaw::elastic_contact_time_s(self.graph.beta[c], m, speed_m_s)
            })
            .fold(f64::INFINITY, f64::min)
    }
}
