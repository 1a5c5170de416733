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

use crate::error::{Error, Result};
use crate::excitation::{BlastProfile, Drive, DriveQuantity, Excitation};
use crate::integrate::OdeSystem;
use crate::model::{Chain, ContactDamping};

/// A contact's damping law, compiled for one slot.
#[derive(Debug, Clone, Copy, PartialEq)]
enum SlotLaw {
    None,
    /// η = coef δ^{1/4}.
    Restitution {
        coef: f64,
    },
    /// F = β δ^{3/2} (1 + λ δ̇), λ = χ / v_in [s/m].
    HuntCrossley {
        lambda: f64,
    },
    /// F_d = coef δ^{1/2} δ̇.
    Viscoelastic {
        coef: f64,
    },
}

impl SlotLaw {
    fn new(law: ContactDamping, beta: f64, reduced_mass_kg: f64, impact_speed_m_s: f64) -> Self {
        match law {
            ContactDamping::None => SlotLaw::None,
            ContactDamping::Restitution { coefficient } if coefficient < 1.0 => {
                SlotLaw::Restitution {
                    coef: ContactDamping::restitution_prefactor(coefficient)
                        * (beta * reduced_mass_kg).sqrt(),
                }
            }
            ContactDamping::HuntCrossley { restitution } if restitution < 1.0 => {
                SlotLaw::HuntCrossley {
                    lambda: 8.0 * (1.0 - restitution) / (5.0 * restitution) / impact_speed_m_s,
                }
            }
            ContactDamping::Viscoelastic { time_s } if time_s > 0.0 => SlotLaw::Viscoelastic {
                coef: 1.5 * time_s * beta,
            },
            _ => SlotLaw::None,
        }
    }
}

/// The terms of docs/physics.md §14, present only when a run uses them.
#[derive(Debug, Clone)]
struct Lab {
    /// Damping law per slot 0..=P.
    law: Vec<SlotLaw>,
    allow_pull: bool,
    /// Resonator damping c_j [kg/s], c_j/m_j and c_j/M_owner [1/s].
    res_damping: Vec<f64>,
    res_damping_rate: Vec<f64>,
    res_damping_coupling: Vec<f64>,
    /// On-site damping 1/τ per point mass [1/s] (0 for the striker).
    on_site_rate: Vec<f64>,
    /// Constant external force per primary (gravity; a preload beside a striker) [N].
    external_force_n: Vec<f64>,
    gravity_m_s2: f64,
    /// Constant force added to a force-type load (the preload) [N].
    load_constant_n: f64,
    /// The drive, if any.
    drive: Option<Drive>,
    /// Actuator tip: β and rest position (static equilibrium) [m], for a displacement drive.
    actuator: Option<(f64, f64)>,
    /// Static equilibrium: state and force per slot.
    static_state: Vec<f64>,
    static_force_n: Vec<f64>,
}

/// The compiled equations of motion of one chain under one excitation.
#[derive(Debug, Clone)]
pub struct ChainOde {
    pub(crate) n_primary: usize,
    pub(crate) n_dof: usize,
    /// 0 for impact (primary 0 is the striker), 1 for blast.
    pub(crate) shift: usize,
    mass_kg: Vec<f64>,
    pub(crate) inv_mass: Vec<f64>,
    pub(crate) res_owner: Vec<usize>,
    res_mass_kg: Vec<f64>,
    res_stiffness: Vec<f64>,
    /// k_j / m_j [1/s²].
    pub(crate) res_omega2: Vec<f64>,
    /// k_j / M_owner [1/s²].
    pub(crate) res_coupling: Vec<f64>,
    /// β per slot (slot 0 unused); 0 for a free end.
    pub(crate) beta: Vec<f64>,
    /// Contact slots 1..=P with β = 0 (a free end), for [`OdeSystem::switches`].
    free_slots: Vec<usize>,
    overlap_limit_m: Vec<f64>,
    pub(crate) load: Option<BlastProfile>,
    /// Contact force per slot at the last evaluation \[N\].
    pub(crate) force_n: Vec<f64>,
    /// Signed overlap per slot at the last evaluation \[m\].
    pub(crate) overlap_m: Vec<f64>,
    striker_velocity_m_s: f64,
    /// Damping, static load, drive (docs/physics.md §14); None = the paper's model.
    lab: Option<Box<Lab>>,
}

impl ChainOde {
    /// The resonator with the highest frequency of oscillation against its (fixed) primary
    /// mass, ω = sqrt(k (1/m + 1/M)): (element number from 1, resonator index in its cell, ω
    /// \[rad/s\]). None without resonators.
    pub fn stiffest_resonator(&self) -> Option<(usize, usize, f64)> {
        let mut best: Option<(usize, usize, f64)> = None;
        for (j, (element, index)) in self.resonator_numbers().enumerate() {
            let omega = (self.res_omega2[j] + self.res_coupling[j]).sqrt();
            if best.is_none_or(|b| omega > b.2) {
                best = Some((element, index - 1, omega));
            }
        }
        best
    }

    /// (element number from 1, resonator number from 1 in its cell) of every resonator, in
    /// state order.
    fn resonator_numbers(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.res_owner
            .iter()
            .enumerate()
            .scan(0, |index, (j, &owner)| {
                *index = if j > 0 && self.res_owner[j - 1] == owner {
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
        let n_primary = mass_kg.len();
        debug_assert_eq!(beta.len(), n_primary + 1);
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
        let free_slots = (1..=n_primary).filter(|&s| beta[s] == 0.0).collect();
        let mut ode = ChainOde {
            n_primary,
            n_dof: n_primary + res_mass_kg.len(),
            shift,
            inv_mass: mass_kg.iter().map(|m| 1.0 / m).collect(),
            mass_kg,
            res_owner,
            res_omega2,
            res_coupling,
            res_mass_kg,
            res_stiffness,
            beta,
            free_slots,
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
            ode.lab = Some(Box::new(ode.compile_lab(chain, excitation)?));
        }
        Ok(ode)
    }

    /// Compiles damping, the static load and the drive, and finds the static equilibrium.
    fn compile_lab(&self, chain: &Chain, excitation: &Excitation) -> Result<Lab> {
        let (p, nd, shift) = (self.n_primary, self.n_dof, self.shift);
        let damping = chain.damping();
        let preload = chain.preload();
        let g = preload.gravity_m_s2;
        let drive = match excitation {
            Excitation::Drive(d) => Some(d.clone()),
            _ => None,
        };
        let actuator_beta = match drive.as_ref().map(|d| &d.quantity) {
            Some(DriveQuantity::Displacement { tip }) => Some(
                tip.beta_against(chain.top_surface(), &chain.elements()[0].material)?
                    .ok_or_else(|| {
                        Error::invalid(
                            "excitation.tip",
                            "free",
                            "a displacement drive pushes through its tip: give it a cap, flat or beta",
                        )
                    })?,
            ),
            _ => None,
        };
        // Damping law per slot, with the reduced mass of the primaries in contact.
        let reduced = |a: f64, b: f64| a * b / (a + b);
        let v_in = match damping.impact_speed_m_s {
            Some(v) => v,
            None if shift == 0 => self.striker_velocity_m_s,
            None => f64::NAN,
        };
        let hunt_crossley = [damping.contacts, damping.striker_law(), damping.wall_law()]
            .iter()
            .any(
                |l| matches!(l, ContactDamping::HuntCrossley { restitution } if *restitution < 1.0),
            );
        if hunt_crossley && v_in.is_nan() {
            return Err(Error::invalid(
                "damping.impact_speed_m_s",
                "(none)",
                "the Hunt–Crossley law needs the impact speed v_in of its contacts: give it, or use a striker (its speed is the default)",
            ));
        }
        let mut law = vec![SlotLaw::None; p + 1];
        if let Some(b0) = actuator_beta {
            law[0] = SlotLaw::new(damping.striker_law(), b0, self.mass_kg[0], v_in);
        }
        for (slot, l) in law.iter_mut().enumerate().skip(1) {
            let kind = if slot == p {
                damping.wall_law()
            } else if slot == 1 && shift == 0 {
                damping.striker_law()
            } else {
                damping.contacts
            };
            let m = if slot == p {
                self.mass_kg[p - 1]
            } else {
                reduced(self.mass_kg[slot - 1], self.mass_kg[slot])
            };
            *l = SlotLaw::new(kind, self.beta[slot], m, v_in);
        }
        // Resonator damping c_j = 2 ζ √(k_j m_j), resonators numbered from 1 in each element.
        let res_damping: Vec<f64> = self
            .resonator_numbers()
            .enumerate()
            .map(|(j, (element, index))| {
                let zeta = damping.ratio_of(element, index);
                2.0 * zeta * (self.res_stiffness[j] * self.res_mass_kg[j]).sqrt()
            })
            .collect();
        let res_damping_rate = res_damping
            .iter()
            .zip(&self.res_mass_kg)
            .map(|(c, m)| c / m)
            .collect();
        let res_damping_coupling = res_damping
            .iter()
            .zip(&self.res_owner)
            .map(|(c, &o)| c / self.mass_kg[o])
            .collect();
        let rate = damping.on_site_time_s.map_or(0.0, |tau| 1.0 / tau);
        let mut on_site_rate = vec![rate; nd];
        if shift == 0 {
            on_site_rate[0] = 0.0; // the striker flies freely
        }
        // External forces: gravity on every primary; a preload beside a striker acts on element 1.
        let mut external_force_n: Vec<f64> = self.mass_kg.iter().map(|m| m * g).collect();
        let force_type_load = drive
            .as_ref()
            .is_none_or(|d| d.quantity == DriveQuantity::Force);
        let load_constant_n = if shift == 0 {
            external_force_n[1] += preload.force_n;
            0.0
        } else if force_type_load {
            preload.force_n
        } else {
            0.0
        };
        // Static forces per slot: the load slot carries the preload, element contacts the rest.
        let mut static_force_n = vec![0.0; p + 1];
        if shift == 1 {
            static_force_n[0] = preload.force_n;
        }
        for (c, f) in chain.static_contact_forces_n().into_iter().enumerate() {
            static_force_n[c + 2 - shift] = f;
        }
        let overlap_of = |f: f64, b: f64| {
            if f > 0.0 {
                (f / b).powf(2.0 / 3.0)
            } else {
                0.0
            }
        };
        let mut state = vec![0.0; 2 * nd + 2];
        state[p - 1] = overlap_of(static_force_n[p], self.beta[p]);
        for slot in (1..p).rev() {
            state[slot - 1] = state[slot] + overlap_of(static_force_n[slot], self.beta[slot]);
        }
        for j in 0..self.res_owner.len() {
            state[p + j] =
                state[self.res_owner[j]] + self.res_mass_kg[j] * g / self.res_stiffness[j];
        }
        if shift == 0 {
            state[nd] = self.striker_velocity_m_s;
        }
        let actuator = actuator_beta.map(|b0| (b0, state[0] + overlap_of(preload.force_n, b0)));
        Ok(Lab {
            law,
            allow_pull: damping.allow_pull,
            res_damping,
            res_damping_rate,
            res_damping_coupling,
            on_site_rate,
            external_force_n,
            gravity_m_s2: g,
            load_constant_n,
            drive,
            actuator,
            static_state: state,
            static_force_n,
        })
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

    /// Number of layers N + 1 (layer 0 = striker or load) = number of paper contacts.
    pub fn n_layers(&self) -> usize {
        self.n_primary + self.shift
    }

    /// Number of elements N.
    pub fn n_elements(&self) -> usize {
        self.n_primary + self.shift - 1
    }

    /// Number of point masses (primaries and resonators).
    pub fn n_dof(&self) -> usize {
        self.n_dof
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
            y[self.n_dof] = self.striker_velocity_m_s;
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

    /// Contact coefficients β \[N/m^1.5\] of paper contacts 0..=N (NaN for a prescribed load).
    pub fn contact_betas(&self) -> &[f64] {
        &self.beta[1 - self.shift..]
    }

    /// The stiffest closed contact at the last evaluation (paper numbering): the one with the
    /// highest linearised frequency ω² = (3/2) β δ^{1/2} (1/m_a + 1/m_b) over the primary masses
    /// it joins, i.e. the one an explicit step leaves stable last. `None` when none is closed.
    pub fn stiffest_contact(&self) -> Option<(usize, f64)> {
        let p = self.n_primary;
        let first = 1 - self.shift;
        (1..=p)
            .filter(|&s| self.overlap_m[s] > 0.0 && self.overlap_m[s].is_finite())
            .map(|s| {
                let inv_m = self.inv_mass[s - 1] + if s < p { self.inv_mass[s] } else { 0.0 };
                (s, 1.5 * self.beta[s] * self.overlap_m[s].sqrt() * inv_m)
            })
            .filter(|(_, w2)| w2.is_finite())
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(s, w2)| (s - first, w2))
    }

    /// Rates dF/dt [N/s] of paper contacts 0..=N for state `y`, which must be the state of the last
    /// evaluation. The load's rate and a damped contact's are NaN (their peaks are not refined).
    pub fn contact_force_rates(&self, y: &[f64], out: &mut [f64]) {
        let v = &y[self.n_dof..2 * self.n_dof];
        if self.lab.is_some() {
            for (c, rate) in out[..self.n_layers()].iter_mut().enumerate() {
                *rate = self.contact_force_rate(c, v);
            }
            return;
        }
        // The paper's model (no damping): the same formula without the per-contact law lookup.
        let p = self.n_primary;
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
    #[inline]
    fn elastic_rate(&self, slot: usize, v: &[f64]) -> f64 {
        let p = self.n_primary;
        let d = self.overlap_m[slot];
        if d > 0.0 {
            let ddot = if slot == p {
                v[p - 1]
            } else {
                v[slot - 1] - v[slot]
            };
            1.5 * self.force_n[slot] * ddot / d
        } else {
            0.0
        }
    }

    /// Rate dF/dt [N/s] of paper contact c, from the velocities `v` of the state of the last
    /// evaluation (only those of the contact's two primaries are read); NaN for the load and a
    /// damped contact, as in [`ChainOde::contact_force_rates`].
    #[inline]
    pub(crate) fn contact_force_rate(&self, c: usize, v: &[f64]) -> f64 {
        let slot = c + 1 - self.shift;
        let damped = self
            .lab
            .as_ref()
            .is_some_and(|lab| lab.law[slot] != SlotLaw::None);
        if slot == 0 || damped {
            f64::NAN
        } else {
            self.elastic_rate(slot, v)
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
        for slot in first..=self.n_primary {
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
        let (p, nd) = (self.n_primary, self.n_dof);
        let (x, v) = (&y[..nd], &y[nd..2 * nd]);
        let actuator_beta = self.lab.as_ref().and_then(|l| l.actuator).map(|a| a.0);
        let potential = |slot: usize| {
            let d = if slot == 0 {
                match actuator_beta {
                    Some(b0) => {
                        let d = self.overlap_m[0].max(0.0);
                        return 0.4 * b0 * d * d * d.sqrt();
                    }
                    None => return 0.0,
                }
            } else if slot == p {
                x[p - 1]
            } else {
                x[slot - 1] - x[slot]
            };
            if d > 0.0 {
                0.4 * self.beta[slot] * d * d * d.sqrt()
            } else {
                0.0
            }
        };
        out.fill(0.0);
        for i in 0..p {
            out[i + self.shift] = 0.5 * self.mass_kg[i] * v[i] * v[i];
        }
        // Contact potentials, split half–half between the two bodies (an actuator's half goes to
        // layer 0).
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
        for j in 0..self.res_owner.len() {
            let o = self.res_owner[j];
            let ext = x[p + j] - x[o];
            out[o + self.shift] += 0.5 * self.res_mass_kg[j] * v[p + j] * v[p + j]
                + 0.5 * self.res_stiffness[j] * ext * ext;
        }
        0.5 * potential(p)
    }

    /// Work done by the external forces so far \[J\]: the load (0 for an impact without lab
    /// physics), an actuator, a preload and gravity.
    pub fn input_work_j(&self, y: &[f64]) -> f64 {
        if self.lab.is_some() || self.is_blast() {
            y[2 * self.n_dof]
        } else {
            0.0
        }
    }

    /// Energy dissipated so far \[J\] (0 without damping).
    pub fn dissipated_j(&self, y: &[f64]) -> f64 {
        if self.lab.is_some() {
            y[2 * self.n_dof + 1]
        } else {
            0.0
        }
    }

    /// Displacements \[m\] of the elements' primary masses (rods 1..N).
    pub fn element_displacements<'a>(&self, y: &'a [f64]) -> &'a [f64] {
        &y[1 - self.shift..self.n_primary]
    }

    /// Velocities [m/s] of the elements' primary masses.
    pub fn element_velocities<'a>(&self, y: &'a [f64]) -> &'a [f64] {
        &y[self.n_dof + 1 - self.shift..self.n_dof + self.n_primary]
    }

    /// Striker (position \[m\], velocity [m/s]), None for a blast.
    pub fn striker_state(&self, y: &[f64]) -> Option<(f64, f64)> {
        self.has_striker().then(|| (y[0], y[self.n_dof]))
    }

    /// Velocity of the top element's primary mass [m/s].
    pub fn top_element_velocity(&self, y: &[f64]) -> f64 {
        y[self.n_dof + 1 - self.shift]
    }

    /// Absolute-tolerance units per state component for the adaptive integrator: 1 for
    /// displacements \[m\], 1/τ with τ = 1 µs for velocities [m/s], 100 N for the work \[J\].
    pub fn tolerance_units(&self) -> Vec<f64> {
        let mut u = vec![1.0; self.n_dof];
        u.extend(std::iter::repeat_n(1e6, self.n_dof));
        if self.lab.is_some() {
            u.extend([100.0, 100.0]);
        } else if self.is_blast() {
            u.push(100.0);
        }
        u
    }
}

impl OdeSystem for ChainOde {
    fn dimension(&self) -> usize {
        if self.lab.is_some() {
            2 * self.n_dof + 2
        } else {
            2 * self.n_dof + usize::from(self.is_blast())
        }
    }

    #[inline(always)]
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        if self.lab.is_some() {
            self.rhs_lab(t, y, dydt);
            return;
        }
        let (p, nd) = (self.n_primary, self.n_dof);
        let (x, v) = (&y[..nd], &y[nd..2 * nd]);
        let (dx, rest) = dydt.split_at_mut(nd);
        let dv = &mut rest[..nd];
        dx.copy_from_slice(v);
        let force = &mut self.force_n[..=p];
        let overlap = &mut self.overlap_m[..=p];
        let beta = &self.beta[..=p];
        force[0] = match &self.load {
            Some(l) => l.force_n(t),
            None => 0.0,
        };
        for i in 1..p {
            let d = x[i - 1] - x[i];
            overlap[i] = d;
            let dp = d.max(0.0);
            force[i] = beta[i] * dp * dp.sqrt();
        }
        let d = x[p - 1];
        overlap[p] = d;
        let dp = d.max(0.0);
        force[p] = beta[p] * dp * dp.sqrt();
        let inv_mass = &self.inv_mass[..p];
        for i in 0..p {
            dv[i] = (force[i] - force[i + 1]) * inv_mass[i];
        }
        let r = self.res_owner.len();
        let xr = &x[p..p + r];
        let (dvp, dvr) = dv.split_at_mut(p);
        for ((((&o, &w2), &cpl), &xj), a) in self.res_owner[..r]
            .iter()
            .zip(&self.res_omega2[..r])
            .zip(&self.res_coupling[..r])
            .zip(xr)
            .zip(dvr.iter_mut())
        {
            let ext = xj - x[o];
            *a = -w2 * ext;
            dvp[o] += cpl * ext;
        }
        if self.load.is_some() {
            rest[nd] = force[0] * v[0];
        }
    }

    fn switch_count(&self) -> usize {
        self.n_primary
    }

    fn second_order(&self) -> Option<usize> {
        // A blast's state ends in its work W, whose rate F(t) u̇_1 needs the velocity; the lab
        // physics damps with velocities.
        (self.lab.is_none() && !self.is_blast()).then_some(self.n_dof)
    }

    fn switches(&self, y: &[f64], out: &mut [f64]) {
        // Contact slots 1..=P: their overlaps, linear in the positions; a free end (β = 0) never
        // closes: constant 1.
        let p = self.n_primary;
        let (x, out) = (&y[..p], &mut out[..p]);
        for i in 0..p - 1 {
            out[i] = x[i] - x[i + 1];
        }
        out[p - 1] = x[p - 1];
        for &slot in &self.free_slots {
            out[slot - 1] = 1.0;
        }
    }
}

impl ChainOde {
    /// The equations of motion with damping, static loads and drives (docs/physics.md §14), and
    /// the rates of the work W and the dissipated energy D.
    fn rhs_lab(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let lab = self.lab.as_deref().expect("lab physics compiled");
        let (p, nd) = (self.n_primary, self.n_dof);
        let (x, v) = (&y[..nd], &y[nd..2 * nd]);
        let (dx, rest) = dydt.split_at_mut(nd);
        let (dv, integrals) = rest.split_at_mut(nd);
        dx.copy_from_slice(v);
        let mut power_in = 0.0;
        let mut dissipation = 0.0;
        // One contact: elastic Hertz force plus its damping law; tension-free unless pulling is
        // allowed; the damping force's power is dissipated.
        let contact = |slot: usize, beta: f64, d: f64, ddot: f64, diss: &mut f64| -> f64 {
            if d <= 0.0 {
                return 0.0;
            }
            let root = d.sqrt();
            let elastic = beta * d * root;
            let damping = match lab.law[slot] {
                SlotLaw::None => return elastic,
                SlotLaw::Restitution { coef } => coef * root.sqrt() * ddot,
                SlotLaw::HuntCrossley { lambda } => elastic * lambda * ddot,
                SlotLaw::Viscoelastic { coef } => coef * root * ddot,
            };
            let mut f = elastic + damping;
            if !lab.allow_pull && f < 0.0 {
                f = 0.0;
            }
            *diss += (f - elastic) * ddot;
            f
        };
        // The load slot.
        let (f0, d0) = if self.shift == 0 {
            (0.0, 0.0)
        } else {
            match (&lab.drive, lab.actuator) {
                (Some(drive), Some((b0, rest))) => {
                    let (s, ds) = drive.value_and_rate(t);
                    let d = rest + s - x[0];
                    let f = contact(0, b0, d, ds - v[0], &mut dissipation);
                    power_in += f * ds;
                    (f, d)
                }
                (drive, _) => {
                    let signal = drive.as_ref().map_or(0.0, |d| d.value_and_rate(t).0);
                    let blast = self.load.as_ref().map_or(0.0, |l| l.force_n(t));
                    let f = lab.load_constant_n + signal + blast;
                    power_in += f * v[0];
                    (f, 0.0)
                }
            }
        };
        self.force_n[0] = f0;
        self.overlap_m[0] = d0;
        for slot in 1..=p {
            let (d, ddot) = if slot == p {
                (x[p - 1], v[p - 1])
            } else {
                (x[slot - 1] - x[slot], v[slot - 1] - v[slot])
            };
            self.overlap_m[slot] = d;
            self.force_n[slot] = contact(slot, self.beta[slot], d, ddot, &mut dissipation);
        }
        let force = &self.force_n;
        for i in 0..p {
            let on_site = lab.on_site_rate[i];
            dv[i] = (force[i] - force[i + 1] + lab.external_force_n[i]) * self.inv_mass[i]
                - on_site * v[i];
            power_in += lab.external_force_n[i] * v[i];
            dissipation += on_site * self.mass_kg[i] * v[i] * v[i];
        }
        let g = lab.gravity_m_s2;
        let (dvp, dvr) = dv.split_at_mut(p);
        for (j, a) in dvr.iter_mut().enumerate() {
            let o = self.res_owner[j];
            let ext = x[p + j] - x[o];
            let rel = v[p + j] - v[o];
            let on_site = lab.on_site_rate[p + j];
            *a = -self.res_omega2[j] * ext - lab.res_damping_rate[j] * rel + g - on_site * v[p + j];
            dvp[o] += self.res_coupling[j] * ext + lab.res_damping_coupling[j] * rel;
            let m = self.res_mass_kg[j];
            power_in += m * g * v[p + j];
            dissipation += lab.res_damping[j] * rel * rel + on_site * m * v[p + j] * v[p + j];
        }
        integrals[0] = power_in;
        integrals[1] = dissipation;
    }
}
