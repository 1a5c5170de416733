//! The chain as an ODE system y' = f(t, y): the equations of motion of docs/physics.md §4 in flat arrays.
//!
//! State layout (n = number of point masses = P primaries + R resonators):
//!
//! ```text
//! y = [ u_0 … u_{P−1} | w_0 … w_{R−1} | u̇_0 … u̇_{P−1} | ẇ_0 … ẇ_{R−1} | W (blast only) ]
//! ```
//!
//! Primaries are the striker (impact only) then the elements top to bottom; resonators are stored
//! with the index of their primary. W is the work done by the blast load, ∫ F(t) u̇_1 dt, integrated
//! with the motion so that the energy balance can be closed to the integrator's accuracy.
//!
//! With the physics of docs/physics.md §14 (damping, a preload or gravity, a drive, or a column at
//! rest) the state ends in two integrals instead, `[… | W | D]`: W the work of every external force
//! (load, actuator, preload, gravity) and D the energy dissipated; those runs take a separate
//! evaluation ([`ChainOde`]'s lab path), so that the paper's model keeps its code and its bits.
//!
//! Contact forces are computed once per evaluation into "slots": slot i acts on top of primary i,
//! slot i+1 below it; slot 0 is the load (blast) or nothing (impact, above the striker), slot P the
//! wall. The paper's contact c is slot c + 1 − s and its layer L is primary L − s, where s = 1 for a
//! blast (no striker body) and 0 for an impact.

mod damped_modes;
mod element_modes;
mod equations;
mod lab;
mod lattice;
mod lattice_lab;
mod lattice_static;
mod modal;

pub(crate) use equations::{Equations, LabEquations, LabShape, Load};
pub(crate) use lattice::graph::Side;
pub use lattice::LatticeOde;
#[doc(hidden)]
pub use modal::damped_cell_energies;
pub(crate) use modal::ModalChain;

use crate::error::{Error, Result};
use crate::excitation::{BlastProfile, Drive, Excitation};
use crate::integrate::OdeSystem;
use crate::model::{Chain, ContactLaw};

/// What a run with lab physics needs beyond its equations: the drive and the static state.
#[derive(Debug, Clone)]
struct LabLoad {
    /// Gravity \[m/s²\] (0: none).
    gravity_m_s2: f64,
    /// Constant force added to a force-type load (the preload) \[N\].
    load_constant_n: f64,
    /// The drive, if any.
    drive: Option<Drive>,
    /// Static equilibrium: state and force per slot.
    static_state: Vec<f64>,
    static_force_n: Vec<f64>,
}

/// The compiled equations of motion of one chain under one excitation.
#[derive(Debug, Clone)]
pub struct ChainOde {
    /// The parameters of the equations of motion (shared with the lanes).
    pub(crate) eq: Equations<f64>,
    /// 0 for impact (primary 0 is the striker), 1 for blast.
    pub(crate) shift: usize,
    mass_kg: Vec<f64>,
    res_mass_kg: Vec<f64>,
    res_stiffness: Vec<f64>,
    overlap_limit_m: Vec<f64>,
    pub(crate) load: Option<BlastProfile>,
    /// Contact force per slot at the last evaluation \[N\].
    pub(crate) force_n: Vec<f64>,
    /// Signed overlap per slot at the last evaluation \[m\].
    pub(crate) overlap_m: Vec<f64>,
    striker_velocity_m_s: f64,
    /// Drive and static state of the lab physics (docs/physics.md §14); None = the paper's model.
    lab: Option<Box<LabLoad>>,
}

impl ChainOde {
    /// The resonator with the highest frequency of oscillation against its (fixed) primary
    /// mass, ω = sqrt(k (1/m + 1/M)): (element number from 1, resonator index in its cell, ω
    /// \[rad/s\]). None without resonators.
    pub fn stiffest_resonator(&self) -> Option<(usize, usize, f64)> {
        let mut best: Option<(usize, usize, f64)> = None;
        for (j, (element, index)) in self.resonator_numbers().enumerate() {
            let omega = (self.eq.res_omega2[j] + self.eq.res_coupling[j]).sqrt();
            if best.is_none_or(|b| omega > b.2) {
                best = Some((element, index - 1, omega));
            }
        }
        best
    }

    /// (element number from 1, resonator number from 1 in its cell) of every resonator, in
    /// state order.
    fn resonator_numbers(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let owners = &self.eq.res_owner;
        owners.iter().enumerate().scan(0, |index, (j, &owner)| {
            *index = if j > 0 && owners[j - 1] == owner {
                *index + 1
            } else {
                1
            };
            Some((owner + self.shift, *index))
        })
    }

    /// Compiles a chain and its excitation. Validates the excitation.
    pub fn new(chain: &Chain, excitation: &Excitation) -> Result<Self> {
        excitation.validate()?;
        let n = chain.len();
        let mut mass_kg = Vec::with_capacity(n + 1);
        let mut beta = vec![0.0];
        let mut overlap_limit_m = vec![f64::INFINITY];
        let (shift, load, striker_velocity_m_s) = match excitation {
            Excitation::Impact(s) => {
                mass_kg.push(s.mass_kg());
                beta.push(s.contact_beta(chain)?);
                let top = chain.top_surface().smallest_radius_m();
                overlap_limit_m.push(0.1 * top.min(0.5 * s.diameter_m));
                (0, None, s.velocity_m_s)
            }
            Excitation::Blast(p) => (1, Some(p.clone()), 0.0),
            Excitation::Drive(_) | Excitation::Rest => (1, None, 0.0),
        };
        let n_striker = mass_kg.len();
        let mut res_owner = Vec::new();
        let mut res_mass_kg = Vec::new();
        let mut res_stiffness = Vec::new();
        for (i, e) in chain.elements().iter().enumerate() {
            mass_kg.push(e.cell.primary_mass_kg);
            for r in &e.cell.resonators {
                res_owner.push(n_striker + i);
                res_mass_kg.push(r.mass_kg);
                res_stiffness.push(r.stiffness_n_per_m);
            }
        }
        beta.extend_from_slice(chain.inner_betas());
        beta.push(chain.wall_beta().unwrap_or(0.0));
        overlap_limit_m.extend_from_slice(chain.overlap_limits_m());
        if chain.wall_beta().is_none() {
            // A free end: the last element may move away without bound.
            *overlap_limit_m.last_mut().expect("has the wall slot") = f64::INFINITY;
        }
        let res_omega2 = res_stiffness
            .iter()
            .zip(&res_mass_kg)
            .map(|(k, m)| k / m)
            .collect();
        let res_coupling = res_stiffness
            .iter()
            .zip(&res_owner)
            .map(|(k, &o)| k / mass_kg[o])
            .collect();
        let n_primary = mass_kg.len();
        debug_assert_eq!(beta.len(), n_primary + 1);
        let mut ode = ChainOde {
            eq: Equations {
                p: n_primary,
                nd: n_primary + res_mass_kg.len(),
                work_integral: load.is_some(),
                inv_mass: mass_kg.iter().map(|m| 1.0 / m).collect(),
                beta,
                res_owner,
                res_omega2,
                res_coupling,
                lab: None,
            },
            shift,
            mass_kg,
            res_mass_kg,
            res_stiffness,
            overlap_limit_m,
            load,
            force_n: vec![0.0; n_primary + 1],
            overlap_m: vec![0.0; n_primary + 1],
            striker_velocity_m_s,
            lab: None,
        };
        let needs_lab = !chain.damping().is_lossless()
            || !chain.preload().is_none()
            || matches!(excitation, Excitation::Drive(_) | Excitation::Rest);
        if needs_lab {
            let (equations, load) = ode.compile_lab(chain, excitation)?;
            ode.eq.lab = Some(equations);
            ode.lab = Some(Box::new(load));
        }
        Ok(ode)
    }

    /// Whether the run uses the terms of docs/physics.md §14 (its state ends in W and D).
    pub fn has_lab_physics(&self) -> bool {
        self.lab.is_some()
    }

    /// Static force of paper contacts 0..=N \[N\] (zeros without a static load).
    pub fn static_contact_forces_n(&self) -> Vec<f64> {
        match &self.lab {
            Some(lab) => lab.static_force_n[1 - self.shift..].to_vec(),
            None => vec![0.0; self.n_layers()],
        }
    }

    /// A displacement drive's tip at rest: its static position u* \[m\] (downward; None without
    /// a displacement actuator), the tip's overlap δ₀ = u* + u(t) − x₁ (docs/physics.md §14).
    /// Under a preload F_p the top element's static displacement plus (F_p/β₀)^{2/3}; without
    /// one the top element's static displacement (the tip touching at no force).
    pub fn actuator_rest_m(&self) -> Option<f64> {
        self.eq
            .lab
            .as_ref()
            .filter(|l| l.shape.actuator)
            .map(|l| l.actuator_rest_m)
    }

    /// Number of layers N + 1 (layer 0 = striker or load) = number of paper contacts.
    pub fn n_layers(&self) -> usize {
        self.eq.p + self.shift
    }

    /// Number of elements N.
    pub fn n_elements(&self) -> usize {
        self.eq.p + self.shift - 1
    }

    /// Number of point masses (primaries and resonators).
    pub fn n_dof(&self) -> usize {
        self.eq.nd
    }

    /// Whether primary 0 is a striker.
    pub fn has_striker(&self) -> bool {
        self.shift == 0
    }

    /// Whether the top element is loaded by a prescribed force.
    pub fn is_blast(&self) -> bool {
        self.load.is_some()
    }

    /// The initial state: everything at rest and touching (or in static equilibrium under a
    /// preload or gravity), the striker moving at v0.
    pub fn initial_state(&self) -> Vec<f64> {
        if let Some(lab) = &self.lab {
            return lab.static_state.clone();
        }
        let mut y = vec![0.0; self.dimension()];
        if self.has_striker() {
            y[self.eq.nd] = self.striker_velocity_m_s;
        }
        y
    }

    /// Initial striker velocity v0 [m/s] (0 for a blast).
    pub fn striker_velocity_m_s(&self) -> f64 {
        self.striker_velocity_m_s
    }

    /// Striker mass \[kg\] (None for a blast).
    pub fn striker_mass_kg(&self) -> Option<f64> {
        self.has_striker().then(|| self.mass_kg[0])
    }

    /// Contact forces \[N\] of paper contacts 0..=N at the last evaluation of [`OdeSystem::rhs`].
    pub fn contact_forces_n(&self) -> &[f64] {
        &self.force_n[1 - self.shift..]
    }

    /// Signed overlaps \[m\] of paper contacts 0..=N at the last evaluation (0 for a load).
    pub fn contact_overlaps_m(&self) -> &[f64] {
        &self.overlap_m[1 - self.shift..]
    }

    /// Largest physical overlaps \[m\] of paper contacts 0..=N.
    pub fn overlap_limits_m(&self) -> &[f64] {
        &self.overlap_limit_m[1 - self.shift..]
    }

    /// Contact coefficients β \[N/m^1.5\] of paper contacts 0..=N (an actuator's tip for a
    /// displacement drive, 0 for a prescribed force).
    pub fn contact_betas(&self) -> &[f64] {
        &self.eq.beta[1 - self.shift..]
    }

    /// The stiffest closed contact at the last evaluation (paper numbering): the one with the
    /// highest linearised frequency ω² = (3/2) β δ^{1/2} (1/m_a + 1/m_b) over the primary masses
    /// it joins, i.e. the one an explicit step leaves stable last. `None` when none is closed.
    pub fn stiffest_contact(&self) -> Option<(usize, f64)> {
        let p = self.eq.p;
        let first = 1 - self.shift;
        (1..=p)
            .filter(|&s| self.overlap_m[s] > 0.0 && self.overlap_m[s].is_finite())
            .map(|s| {
                let inv_m = self.eq.inv_mass[s - 1] + if s < p { self.eq.inv_mass[s] } else { 0.0 };
                let k = ContactLaw::stiffness_n_per_m(self.eq.beta[s], self.overlap_m[s]);
                (s, k * inv_m)
            })
            .filter(|(_, w2)| w2.is_finite())
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(s, w2)| (s - first, w2))
    }

    /// Rates dF/dt [N/s] of paper contacts 0..=N at time t for state `y`, which must be the
    /// state of the last evaluation. A blast's rate and a damped contact's are NaN (their peaks
    /// are not refined).
    pub fn contact_force_rates(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let v = &y[self.eq.nd..2 * self.eq.nd];
        if self.lab.is_some() {
            for (c, rate) in out[..self.n_layers()].iter_mut().enumerate() {
                *rate = self.contact_force_rate(t, c, v);
            }
            return;
        }
        // The paper's model (no damping): the same formula without the per-contact law lookup.
        let p = self.eq.p;
        let first = 1 - self.shift;
        for (c, slot) in (first..=p).enumerate() {
            out[c] = if slot == 0 {
                f64::NAN
            } else {
                self.elastic_rate(slot, v)
            };
        }
    }

    /// dF/dt [N/s] of the elastic contact of slot 1..=P: F = β δ^{3/2} gives
    /// 1.5 F δ'/δ while the contact is closed, 0 while it is open.
    #[inline(always)]
    fn elastic_rate(&self, slot: usize, v: &[f64]) -> f64 {
        let (p, d) = (self.eq.p, self.overlap_m[slot]);
        if d <= 0.0 {
            return 0.0; // open: no force, no rate (and no velocities to read)
        }
        let ddot = if slot == p {
            v[p - 1]
        } else {
            v[slot - 1] - v[slot]
        };
        ContactLaw::elastic_force_rate(self.force_n[slot], d, ddot)
    }

    /// Rate dF/dt [N/s] of paper contact c at time t, from the velocities `v` of the state of
    /// the last evaluation (only those of the contact's two primaries are read); NaN for a blast
    /// and a damped contact, as in [`ChainOde::contact_force_rates`].
    #[inline]
    pub(crate) fn contact_force_rate(&self, t: f64, c: usize, v: &[f64]) -> f64 {
        let slot = c + 1 - self.shift;
        let damped = self
            .eq
            .lab
            .as_ref()
            .is_some_and(|lab| lab.shape.laws[slot].is_damped());
        if damped {
            f64::NAN
        } else if slot == 0 {
            self.load_rate(t, v)
        } else {
            self.elastic_rate(slot, v)
        }
    }

    /// dF/dt [N/s] of the load's slot 0 at time t: a drive's rate (0 for a preload alone), an
    /// actuator's elastic tip contact's; NaN for a blast (its profile gives no rate).
    fn load_rate(&self, t: f64, v: &[f64]) -> f64 {
        let (Some(lab), Some(eq)) = (&self.lab, &self.eq.lab) else {
            return f64::NAN;
        };
        if self.load.is_some() {
            return f64::NAN;
        }
        match &lab.drive {
            Some(drive) if eq.shape.actuator => {
                let tip_rate = drive.value_and_rate(t).1;
                let (f, d) = (self.force_n[0], self.overlap_m[0]);
                ContactLaw::elastic_force_rate(f, d, tip_rate - v[0])
            }
            Some(drive) => drive.value_and_rate(t).1,
            None => 0.0,
        }
    }

    /// Overlap limit of every slot 0..=P \[m\] (infinite where there is none): what
    /// [`ChainOde::check_contacts`] compares each overlap with.
    pub(crate) fn overlap_limits_by_slot(&self) -> &[f64] {
        &self.overlap_limit_m
    }

    /// Checks the last evaluation for a blow-up: a non-finite force or an overlap beyond the
    /// physical range of its contact.
    pub fn check_contacts(&self, time_s: f64) -> Result<()> {
        let first = 1 - self.shift;
        for slot in first..=self.eq.p {
            let (f, d) = (self.force_n[slot], self.overlap_m[slot]);
            let contact = slot - first;
            if !f.is_finite() || (slot > 0 && !d.is_finite()) {
                return Err(Error::NonFiniteState { time_s, contact });
            }
            if d > self.overlap_limit_m[slot] {
                return Err(Error::RunawayOverlap {
                    time_s,
                    contact,
                    overlap_m: d,
                    limit_m: self.overlap_limit_m[slot],
                });
            }
        }
        Ok(())
    }

    /// Energy of every layer 0..=N \[J\] into `out` (docs/physics.md §7: kinetic + internal springs + half of
    /// each adjacent contact's Hertz potential (2/5) β δ^{5/2}); returns the wall's half of contact N.
    pub fn layer_energies_j(&self, y: &[f64], out: &mut [f64]) -> f64 {
        let (p, nd) = (self.eq.p, self.eq.nd);
        let (x, v) = (&y[..nd], &y[nd..2 * nd]);
        out.fill(0.0);
        for i in 0..p {
            out[i + self.shift] = 0.5 * self.mass_kg[i] * v[i] * v[i];
        }
        let wall = self.add_contact_potentials(y, out);
        for j in 0..self.eq.res_owner.len() {
            let o = self.eq.res_owner[j];
            let ext = x[p + j] - x[o];
            out[o + self.shift] += 0.5 * self.res_mass_kg[j] * v[p + j] * v[p + j]
                + 0.5 * self.res_stiffness[j] * ext * ext;
        }
        wall
    }

    /// [`ChainOde::layer_energies_j`] with each primary's internal energy (kinetic energy of
    /// its cell and its springs, `internal` \[J\], e.g. from its modes) given; only the
    /// primaries' positions of `y` are read.
    pub(crate) fn layer_energies_with_internal_j(
        &self,
        y: &[f64],
        internal: &[f64],
        out: &mut [f64],
    ) -> f64 {
        out.fill(0.0);
        out[self.shift..self.shift + self.eq.p].copy_from_slice(internal);
        self.add_contact_potentials(y, out)
    }

    /// Adds half of every contact's Hertz potential to the layers it joins (an actuator's half
    /// to layer 0); returns the wall's half of contact N.
    fn add_contact_potentials(&self, y: &[f64], out: &mut [f64]) -> f64 {
        let p = self.eq.p;
        let x = &y[..p];
        let actuator = self.eq.lab.as_ref().is_some_and(|l| l.shape.actuator);
        let potential = |slot: usize| {
            let d = if slot == 0 {
                if !actuator {
                    return 0.0;
                }
                self.overlap_m[0]
            } else if slot == p {
                x[p - 1]
            } else {
                x[slot - 1] - x[slot]
            };
            ContactLaw::potential_j(self.eq.beta[slot], d)
        };
        if self.shift == 1 {
            let u = potential(0);
            out[0] += 0.5 * u;
            out[1] += 0.5 * u;
        }
        for slot in 1..=p {
            let u = potential(slot);
            out[slot - 1 + self.shift] += 0.5 * u;
            if slot < p {
                out[slot + self.shift] += 0.5 * u;
            }
        }
        0.5 * potential(p)
    }

    /// The force cache (each slot's force and overlap) at time t for the primaries' positions of
    /// `y` alone, for a run the exact modal method advances ([`ChainOde::fits_exact_modes`]:
    /// every contact elastic): what [`OdeSystem::rhs`] leaves there, without the accelerations
    /// (the exact modal method's state holds only the primaries, docs/physics.md §8).
    pub(crate) fn set_contacts_at(&mut self, t: f64, y: &[f64]) {
        debug_assert!(self.fits_exact_modes());
        let p = self.eq.p;
        let load = self.load_at(t);
        let rest = self.actuator_rest_m();
        let value = if rest.is_some() {
            load.tip_m
        } else {
            load.force_n
        };
        (self.force_n[0], self.overlap_m[0]) = load_slot(self.eq.beta[0], rest, value, y[0]);
        for slot in 1..=p {
            let d = if slot < p {
                y[slot - 1] - y[slot]
            } else {
                y[p - 1]
            };
            self.overlap_m[slot] = d;
            self.force_n[slot] = ContactLaw::elastic_force(self.eq.beta[slot], d);
        }
    }

    /// Whether [`crate::Method::ExactModes`] can advance this run (docs/physics.md §8): the
    /// paper's model under an impact or a blast, or the lab physics with every contact elastic
    /// (a force or displacement drive, a column at rest, a preload, gravity, on-site and
    /// resonator damping).
    pub(crate) fn fits_exact_modes(&self) -> bool {
        self.eq
            .lab
            .as_ref()
            .is_none_or(|lab| lab.shape.laws.iter().all(|&l| l == ContactLaw::Elastic))
    }

    /// Gravity \[m/s²\] and, per primary, the constant force acting on it besides its weight
    /// (a preload beside a striker) \[N\]: the constant loads as the exact modal method takes
    /// them (gravity pulls every mass alike, so it moves only each element's rigid mode).
    pub(crate) fn constant_loads(&self) -> (f64, Vec<f64>) {
        let (Some(lab), Some(eq)) = (&self.lab, &self.eq.lab) else {
            return (0.0, vec![0.0; self.eq.p]);
        };
        let g = lab.gravity_m_s2;
        let extra = eq
            .external_force_n
            .iter()
            .zip(&self.mass_kg)
            .map(|(f, m)| f - m * g)
            .collect();
        (g, extra)
    }

    /// The shortest Hertz contact time of the run \[s\] ([`ContactLaw::elastic_contact_time_s`]):
    /// the striker's on the top element at its speed; under a load, the shortest of every
    /// contact's (its two bodies' reduced total mass, the wall's and an actuator's the element's
    /// alone) at `load_speed_m_s`, the time growing as the speed falls (∝ v^{−1/5}).
    pub(crate) fn contact_time_s(&self, load_speed_m_s: f64) -> f64 {
        let total = self.primary_total_mass_kg();
        let p = self.eq.p;
        if self.has_striker() {
            let v = self.striker_velocity_m_s;
            return if v > 0.0 {
                ContactLaw::elastic_contact_time_s(self.eq.beta[1], total[0], v)
            } else {
                f64::INFINITY
            };
        }
        (0..=p)
            .filter(|&slot| self.eq.beta[slot] > 0.0)
            .map(|slot| {
                let m = match slot {
                    0 => total[0],
                    s if s == p => total[p - 1],
                    s => total[s - 1] * total[s] / (total[s - 1] + total[s]),
                };
                ContactLaw::elastic_contact_time_s(self.eq.beta[slot], m, load_speed_m_s)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Total mass of each primary with its resonators \[kg\].
    pub(crate) fn primary_total_mass_kg(&self) -> Vec<f64> {
        let mut total = self.mass_kg.clone();
        for (o, m) in self.eq.res_owner.iter().zip(&self.res_mass_kg) {
            total[*o] += m;
        }
        total
    }

    /// Work done by the external forces so far \[J\]: the load (0 for an impact without lab
    /// physics), an actuator, a preload and gravity.
    pub fn input_work_j(&self, y: &[f64]) -> f64 {
        if self.lab.is_some() || self.is_blast() {
            y[2 * self.eq.nd]
        } else {
            0.0
        }
    }

    /// Energy dissipated so far \[J\] (0 without damping).
    pub fn dissipated_j(&self, y: &[f64]) -> f64 {
        if self.lab.is_some() {
            y[2 * self.eq.nd + 1]
        } else {
            0.0
        }
    }

    /// Displacements \[m\] of the elements' primary masses (rods 1..N).
    pub fn element_displacements<'a>(&self, y: &'a [f64]) -> &'a [f64] {
        &y[1 - self.shift..self.eq.p]
    }

    /// Velocities [m/s] of the elements' primary masses.
    pub fn element_velocities<'a>(&self, y: &'a [f64]) -> &'a [f64] {
        &y[self.eq.nd + 1 - self.shift..self.eq.nd + self.eq.p]
    }

    /// Striker (position \[m\], velocity [m/s]), None for a blast.
    pub fn striker_state(&self, y: &[f64]) -> Option<(f64, f64)> {
        self.has_striker().then(|| (y[0], y[self.eq.nd]))
    }

    /// Velocity of the top element's primary mass [m/s].
    pub fn top_element_velocity(&self, y: &[f64]) -> f64 {
        y[self.eq.nd + 1 - self.shift]
    }

    /// Absolute-tolerance units per state component for the adaptive integrator: 1 for
    /// displacements \[m\], 1/τ with τ = 1 µs for velocities [m/s], 100 N for the work \[J\].
    pub fn tolerance_units(&self) -> Vec<f64> {
        let mut u = vec![1.0; self.eq.nd];
        u.extend(std::iter::repeat_n(1e6, self.eq.nd));
        if self.lab.is_some() {
            u.extend([100.0, 100.0]);
        } else if self.is_blast() {
            u.push(100.0);
        }
        u
    }
}

impl ChainOde {
    /// The prescribed load at time t: the blast, a force drive and the preload, or a
    /// displacement actuator's tip (nothing beside a striker).
    #[inline(always)]
    pub(crate) fn load_at(&self, t: f64) -> Load<f64> {
        let Some(lab) = &self.lab else {
            return Load {
                force_n: self.load.as_ref().map_or(0.0, |l| l.force_n(t)),
                ..Load::NONE
            };
        };
        if self.shift == 0 {
            return Load::NONE;
        }
        match &lab.drive {
            Some(drive) if self.eq.lab.as_ref().is_some_and(|l| l.shape.actuator) => {
                let (s, ds) = drive.value_and_rate(t);
                Load {
                    tip_m: s,
                    tip_rate_m_s: ds,
                    ..Load::NONE
                }
            }
            drive => {
                let signal = drive.as_ref().map_or(0.0, |d| d.value_and_rate(t).0);
                let blast = self.load.as_ref().map_or(0.0, |l| l.force_n(t));
                Load {
                    force_n: lab.load_constant_n + signal + blast,
                    ..Load::NONE
                }
            }
        }
    }
}

/// Slot 0's force and overlap for the exact modal method (elastic contacts): under a
/// displacement actuator resting at `actuator_rest_m`, its tip's Hertz contact (β `beta`) with
/// the tip at `value` \[m\] and the top primary at `x0` \[m\]; otherwise the prescribed force
/// `value` \[N\] (0 beside a striker), with no overlap.
#[inline(always)]
pub(crate) fn load_slot(
    beta: f64,
    actuator_rest_m: Option<f64>,
    value: f64,
    x0: f64,
) -> (f64, f64) {
    match actuator_rest_m {
        Some(rest) => {
            let d = rest + value - x0;
            (ContactLaw::elastic_force(beta, d), d)
        }
        None => (value, 0.0),
    }
}

impl OdeSystem for ChainOde {
    fn dimension(&self) -> usize {
        self.eq.dimension()
    }

    #[inline(always)]
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let load = self.load_at(t);
        self.eq
            .rhs(load, y, dydt, &mut self.force_n, &mut self.overlap_m, true);
    }

    fn switch_count(&self) -> usize {
        self.eq.p
    }

    fn second_order(&self) -> Option<usize> {
        // A blast's state ends in its work W, whose rate F(t) u̇_1 needs the velocity; the lab
        // physics damps with velocities.
        (self.lab.is_none() && !self.is_blast()).then_some(self.eq.nd)
    }

    fn switches(&self, y: &[f64], out: &mut [f64]) {
        self.eq.switches(y, out);
    }
}
