//! Compiling the lab physics of docs/physics.md §14: the contact laws per slot, resonator and
//! on-site damping, external forces, the drive, and the static equilibrium a run starts from.

use super::{ChainOde, LabEquations, LabLoad, LabShape};
use crate::error::{Error, Result};
use crate::excitation::{DriveQuantity, Excitation};
use crate::math::Libm;
use crate::model::{Chain, ContactDamping, ContactLaw, Damping};

impl ChainOde {
    /// Compiles damping, the static load and the drive, and finds the static equilibrium. Sets
    /// the actuator's β in slot 0 of the equations.
    pub(super) fn compile_lab(
        &mut self,
        chain: &Chain,
        excitation: &Excitation,
    ) -> Result<(LabEquations<f64>, LabLoad)> {
        let (p, shift) = (self.eq.p, self.shift);
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
        if let Some(b0) = actuator_beta {
            self.eq.beta[0] = b0;
        }
        let (laws, law_coef) = self.contact_laws(damping, actuator_beta.is_some())?;
        let (res_damping, res_damping_rate, res_damping_coupling) = self.resonator_damping(damping);
        let rate = damping.on_site_time_s.map_or(0.0, |tau| 1.0 / tau);
        let mut on_site_rate = vec![rate; self.eq.nd];
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
        let (static_state, actuator_rest_m) =
            self.static_state(&static_force_n, g, preload.force_n, actuator_beta);
        let equations = LabEquations {
            shape: LabShape {
                laws,
                allow_pull: damping.allow_pull,
                loaded: shift == 1,
                actuator: actuator_beta.is_some(),
                external: external_force_n.iter().any(|&f| f != 0.0),
                gravity: g != 0.0,
                resonator_damping: res_damping.iter().any(|&c| c != 0.0),
                on_site: on_site_rate.iter().any(|&r| r != 0.0),
            },
            law_coef,
            actuator_rest_m,
            mass: self.mass_kg.clone(),
            on_site_rate,
            external_force_n,
            res_mass: self.res_mass_kg.clone(),
            res_damping,
            res_damping_rate,
            res_damping_coupling,
            res_gravity: vec![g; self.res_mass_kg.len()],
        };
        let load = LabLoad {
            gravity_m_s2: g,
            load_constant_n,
            drive,
            static_state,
            static_force_n,
        };
        Ok((equations, load))
    }

    /// The law and coefficient of every slot 0..=P, with the reduced mass of the primaries in
    /// contact (slot 0: an actuator's tip, if any).
    fn contact_laws(
        &self,
        damping: &Damping,
        actuator: bool,
    ) -> Result<(Vec<ContactLaw>, Vec<f64>)> {
        let (p, shift) = (self.eq.p, self.shift);
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
        let mut laws = vec![(ContactLaw::Elastic, 0.0); p + 1];
        if actuator {
            laws[0] = ContactLaw::compile(
                damping.striker_law(),
                self.eq.beta[0],
                self.mass_kg[0],
                v_in,
            );
        }
        for (slot, l) in laws.iter_mut().enumerate().skip(1) {
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
            *l = ContactLaw::compile(kind, self.eq.beta[slot], m, v_in);
        }
        Ok(laws.into_iter().unzip())
    }

    /// Resonator damping c_j = 2 ζ √(k_j m_j) (resonators numbered from 1 in each element), and
    /// c_j/m_j and c_j/M_owner.
    fn resonator_damping(&self, damping: &Damping) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let res_damping: Vec<f64> = self
            .resonator_numbers()
            .enumerate()
            .map(|(j, (element, index))| {
                let zeta = damping.ratio_of(element, index);
                2.0 * zeta * (self.res_stiffness[j] * self.res_mass_kg[j]).sqrt()
            })
            .collect();
        let rate = res_damping
            .iter()
            .zip(&self.res_mass_kg)
            .map(|(c, m)| c / m)
            .collect();
        let coupling = res_damping
            .iter()
            .zip(&self.eq.res_owner)
            .map(|(c, &o)| c / self.mass_kg[o])
            .collect();
        (res_damping, rate, coupling)
    }

    /// The static equilibrium under the static slot forces and gravity (overlaps from the wall
    /// up, resonators hanging by m g / k), the striker at its speed; and an actuator's rest
    /// position.
    fn static_state(
        &self,
        static_force_n: &[f64],
        g: f64,
        preload_n: f64,
        actuator_beta: Option<f64>,
    ) -> (Vec<f64>, f64) {
        let (p, nd) = (self.eq.p, self.eq.nd);
        let overlap_of = |f: f64, b: f64| {
            if f > 0.0 {
                (f / b).libm_powf(2.0 / 3.0)
            } else {
                0.0
            }
        };
        let mut state = vec![0.0; 2 * nd + 2];
        state[p - 1] = overlap_of(static_force_n[p], self.eq.beta[p]);
        for slot in (1..p).rev() {
            state[slot - 1] = state[slot] + overlap_of(static_force_n[slot], self.eq.beta[slot]);
        }
        for j in 0..self.eq.res_owner.len() {
            state[p + j] =
                state[self.eq.res_owner[j]] + self.res_mass_kg[j] * g / self.res_stiffness[j];
        }
        if self.shift == 0 {
            state[nd] = self.striker_velocity_m_s;
        }
        let rest = actuator_beta.map_or(0.0, |b0| state[0] + overlap_of(preload_n, b0));
        (state, rest)
    }
}
