//! The equations of motion written once over the number type ([`Real`]): `f64` for one run
//! ([`ChainOde`](super::ChainOde)), one value per lane for runs advanced together
//! (`crate::lanes`). The paper's model and the lab physics of docs/physics.md §14 (damping,
//! static loads, drives) are two branches of one function; each contact's force comes from its
//! [`ContactLaw`].

use crate::model::ContactLaw;
use crate::real::Real;

/// The parameters of the equations of motion: one value per run (R = `f64`) or per lane. The
/// shape (numbers of bodies, laws, which integrals) is shared by every lane.
#[derive(Debug, Clone)]
pub(crate) struct Equations<R> {
    /// Number of primaries P (striker, if any, and elements).
    pub p: usize,
    /// Number of point masses P + R.
    pub nd: usize,
    /// Resonator j's primary.
    pub res_owner: Vec<usize>,
    /// Whether the state ends in the load's work W (a blast without lab physics).
    pub work_integral: bool,
    /// 1 / M per primary [1/kg].
    pub inv_mass: Vec<R>,
    /// β per contact slot 0..=P [N/m^1.5] (slot 0 unused but for an actuator; 0 for a free end).
    pub beta: Vec<R>,
    /// k_j / m_j [1/s²].
    pub res_omega2: Vec<R>,
    /// k_j / M_owner [1/s²].
    pub res_coupling: Vec<R>,
    /// Damping, static load, drive; None: the paper's model.
    pub lab: Option<LabEquations<R>>,
}

/// Which terms of docs/physics.md §14 a run has: what the runs of one lane group share (the
/// terms a run lacks are not evaluated at all).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) struct LabShape {
    /// Law per slot 0..=P (slot 0: an actuator's tip).
    pub laws: Vec<ContactLaw>,
    /// Whether a damped contact may pull.
    pub allow_pull: bool,
    /// Whether slot 0 loads the top element (no striker): a force or an actuator.
    pub loaded: bool,
    /// Whether slot 0 is a displacement actuator's tip contact.
    pub actuator: bool,
    /// Whether a constant external force acts on some primary (gravity, a preload beside a
    /// striker), and gravity on the resonators.
    pub external: bool,
    pub gravity: bool,
    /// Whether the resonators are damped.
    pub resonator_damping: bool,
    /// Whether on-site damping acts.
    pub on_site: bool,
}

/// The terms of docs/physics.md §14; the state then ends in `[W | D]`.
#[derive(Debug, Clone)]
pub(crate) struct LabEquations<R> {
    /// Which terms there are.
    pub shape: LabShape,
    /// Each slot's law coefficient ([`ContactLaw::compile`]).
    pub law_coef: Vec<R>,
    /// The tip's rest position (static equilibrium) \[m\].
    pub actuator_rest_m: R,
    /// Primary masses M \[kg\].
    pub mass: Vec<R>,
    /// On-site damping 1/τ per point mass [1/s] (0 for the striker).
    pub on_site_rate: Vec<R>,
    /// Constant external force per primary (gravity; a preload beside a striker) \[N\].
    pub external_force_n: Vec<R>,
    /// Resonator masses m_j \[kg\], damping c_j [kg/s], c_j/m_j and c_j/M_owner [1/s].
    pub res_mass: Vec<R>,
    pub res_damping: Vec<R>,
    pub res_damping_rate: Vec<R>,
    pub res_damping_coupling: Vec<R>,
    /// Gravity on each resonator [m/s²] (0 on a lane's padding).
    pub res_gravity: Vec<R>,
}

/// What is prescribed at one instant: the force on the top element (a blast, a force drive, a
/// preload) or a displacement actuator's tip position and velocity.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Load<R> {
    pub force_n: R,
    pub tip_m: R,
    pub tip_rate_m_s: R,
}

impl<R: Real> Load<R> {
    /// No load.
    pub const NONE: Self = Load {
        force_n: R::ZERO,
        tip_m: R::ZERO,
        tip_rate_m_s: R::ZERO,
    };
}

impl<R: Real> Equations<R> {
    /// The state's length: positions, velocities, and the integrals (W, or W and D).
    pub fn dimension(&self) -> usize {
        2 * self.nd
            + if self.lab.is_some() {
                2
            } else {
                usize::from(self.work_integral)
            }
    }

    /// dy/dt at state y under `load`, with each contact slot's force and signed overlap into
    /// `force` and `overlap`. `velocities`: whether dx/dt = v is written (a Nyström stage reads
    /// only the accelerations).
    #[inline(always)]
    pub fn rhs(
        &self,
        load: Load<R>,
        y: &[R],
        dydt: &mut [R],
        force: &mut [R],
        overlap: &mut [R],
        velocities: bool,
    ) {
        let nd = self.nd;
        let (x, v) = (&y[..nd], &y[nd..2 * nd]);
        let (dx, rest) = dydt.split_at_mut(nd);
        if velocities {
            dx.copy_from_slice(v);
        }
        match &self.lab {
            None => self.rhs_paper(load, x, v, rest, force, overlap),
            Some(lab) => self.rhs_lab(lab, load, x, v, rest, force, overlap),
        }
    }

    /// The paper's model: elastic contacts, undamped resonators, the blast's work.
    #[inline(always)]
    fn rhs_paper(
        &self,
        load: Load<R>,
        x: &[R],
        v: &[R],
        rest: &mut [R],
        force: &mut [R],
        overlap: &mut [R],
    ) {
        let (p, nd) = (self.p, self.nd);
        let force = &mut force[..=p];
        let overlap = &mut overlap[..=p];
        let beta = &self.beta[..=p];
        force[0] = load.force_n;
        for i in 1..p {
            let d = x[i - 1] - x[i];
            overlap[i] = d;
            force[i] = ContactLaw::elastic_force(beta[i], d);
        }
        let d = x[p - 1];
        overlap[p] = d;
        force[p] = ContactLaw::elastic_force(beta[p], d);
        let dv = &mut rest[..nd];
        let inv_mass = &self.inv_mass[..p];
        for i in 0..p {
            dv[i] = (force[i] - force[i + 1]) * inv_mass[i];
        }
        let (dvp, dvr) = dv.split_at_mut(p);
        let resonators = self
            .res_owner
            .iter()
            .zip(&self.res_omega2)
            .zip(&self.res_coupling)
            .zip(&x[p..])
            .zip(dvr.iter_mut());
        for ((((&o, &omega2), &coupling), &xj), a) in resonators {
            let ext = xj - x[o];
            *a = -omega2 * ext;
            dvp[o] = dvp[o] + coupling * ext;
        }
        if self.work_integral {
            rest[nd] = force[0] * v[0];
        }
    }

    /// The lab physics: damped contacts, an actuator or a force load with a preload, gravity,
    /// resonator and on-site damping, and the rates of the work W and the dissipation D. Terms
    /// the shape lacks are skipped (their values would be exact zeros); the sums of W and D are
    /// kept per kind of term, so that they are not one long chain of dependent additions.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn rhs_lab(
        &self,
        lab: &LabEquations<R>,
        load: Load<R>,
        x: &[R],
        v: &[R],
        rest: &mut [R],
        force: &mut [R],
        overlap: &mut [R],
    ) {
        let (p, nd) = (self.p, self.nd);
        let shape = &lab.shape;
        let (dv, integrals) = rest.split_at_mut(nd);
        let (power_load, diss_contacts) = self.lab_contacts(lab, load, x, v, force, overlap);
        let mut power_bodies = R::ZERO;
        let mut diss_bodies = R::ZERO;
        for i in 0..p {
            let mut a = force[i] - force[i + 1];
            if shape.external {
                a = a + lab.external_force_n[i];
                power_bodies = power_bodies + lab.external_force_n[i] * v[i];
            }
            dv[i] = a * self.inv_mass[i];
            if shape.on_site {
                let on_site = lab.on_site_rate[i];
                dv[i] = dv[i] - on_site * v[i];
                diss_bodies = diss_bodies + on_site * lab.mass[i] * v[i] * v[i];
            }
        }
        let mut power_resonators = R::ZERO;
        let mut diss_resonators = R::ZERO;
        let (dvp, dvr) = dv.split_at_mut(p);
        for (j, a) in dvr.iter_mut().enumerate() {
            let (o, vj) = (self.res_owner[j], v[p + j]);
            let ext = x[p + j] - x[o];
            *a = -self.res_omega2[j] * ext;
            if shape.resonator_damping {
                let rel = vj - v[o];
                *a = *a - lab.res_damping_rate[j] * rel;
                dvp[o] = dvp[o] + (self.res_coupling[j] * ext + lab.res_damping_coupling[j] * rel);
                diss_resonators = diss_resonators + lab.res_damping[j] * rel * rel;
            } else {
                dvp[o] = dvp[o] + self.res_coupling[j] * ext;
            }
            if shape.gravity {
                let g = lab.res_gravity[j];
                *a = *a + g;
                power_resonators = power_resonators + lab.res_mass[j] * g * vj;
            }
            if shape.on_site {
                let on_site = lab.on_site_rate[p + j];
                *a = *a - on_site * vj;
                diss_resonators = diss_resonators + on_site * lab.res_mass[j] * vj * vj;
            }
        }
        integrals[0] = power_load + power_bodies + power_resonators;
        integrals[1] = diss_contacts + diss_bodies + diss_resonators;
    }

    /// The lab physics' contact forces into `force` and `overlap` (slot 0: nothing above a
    /// striker, an actuator's tip contact, or a prescribed force): (the load's power, the power
    /// the contacts dissipate).
    #[inline(always)]
    fn lab_contacts(
        &self,
        lab: &LabEquations<R>,
        load: Load<R>,
        x: &[R],
        v: &[R],
        force: &mut [R],
        overlap: &mut [R],
    ) -> (R, R) {
        let (p, shape) = (self.p, &lab.shape);
        let mut dissipation = R::ZERO;
        let (f0, d0, power) = if !shape.loaded {
            (R::ZERO, R::ZERO, R::ZERO)
        } else if shape.actuator {
            let d = lab.actuator_rest_m + load.tip_m - x[0];
            let law = shape.laws[0];
            let rate = load.tip_rate_m_s - v[0];
            let (f, diss) = law.force(lab.law_coef[0], self.beta[0], d, rate, shape.allow_pull);
            if law.is_damped() {
                dissipation = diss;
            }
            (f, d, f * load.tip_rate_m_s)
        } else {
            (load.force_n, R::ZERO, load.force_n * v[0])
        };
        force[0] = f0;
        overlap[0] = d0;
        for slot in 1..=p {
            let (d, ddot) = if slot == p {
                (x[p - 1], v[p - 1])
            } else {
                (x[slot - 1] - x[slot], v[slot - 1] - v[slot])
            };
            overlap[slot] = d;
            let law = shape.laws[slot];
            let (f, diss) = law.force(
                lab.law_coef[slot],
                self.beta[slot],
                d,
                ddot,
                shape.allow_pull,
            );
            force[slot] = f;
            if law.is_damped() {
                dissipation = dissipation + diss;
            }
        }
        (power, dissipation)
    }

    /// The switching function of contact slot s (1..=P) of event-aware stepping: its overlap
    /// from positions (or its rate, from a derivative); a free end (β = 0, only the wall can be
    /// one: every other β is positive, `ChainBuilder::build`) is constant 1 (it never closes).
    #[inline(always)]
    pub fn switch(&self, y: &[R], s: usize) -> R {
        let p = self.p;
        if s < p {
            y[s - 1] - y[s]
        } else {
            self.beta[p].if_zero(R::splat(1.0), y[p - 1])
        }
    }

    /// Every slot's switching function ([`Equations::switch`]) into `out[..P]`: the inner
    /// slots' overlaps in one pass, then the wall's.
    #[inline(always)]
    pub fn switches(&self, y: &[R], out: &mut [R]) {
        let p = self.p;
        let (x, out) = (&y[..p], &mut out[..p]);
        for i in 0..p - 1 {
            out[i] = x[i] - x[i + 1];
        }
        out[p - 1] = self.switch(y, p);
    }
}

impl<R: Real> Equations<R> {
    /// Equations for a group of lanes shaped like `like` (the same laws and integrals) with the
    /// resonator slots `res_owner` (each primary's slots the most resonators any run of the
    /// group has on it): every lane empty (inert: unit inverse masses, zero forces).
    pub fn empty_like(like: &Equations<f64>, res_owner: Vec<usize>) -> Self {
        let (p, r) = (like.p, res_owner.len());
        let zeros = |n: usize| vec![R::ZERO; n];
        Equations {
            p,
            nd: p + r,
            res_owner,
            work_integral: like.work_integral,
            inv_mass: vec![R::splat(1.0); p],
            beta: zeros(p + 1),
            res_omega2: zeros(r),
            res_coupling: zeros(r),
            lab: like.lab.as_ref().map(|lab| LabEquations {
                shape: lab.shape.clone(),
                law_coef: zeros(p + 1),
                actuator_rest_m: R::ZERO,
                mass: zeros(p),
                on_site_rate: zeros(p + r),
                external_force_n: zeros(p),
                res_mass: zeros(r),
                res_damping: zeros(r),
                res_damping_rate: zeros(r),
                res_damping_coupling: zeros(r),
                res_gravity: zeros(r),
            }),
        }
    }

    /// Puts one run's equations into lane `l`; its resonator j goes to slot `res_slot[j]`, the
    /// other slots of the lane are padding that exerts no force (k = 0, c = 0, m = 0, g = 0).
    pub fn set_lane(&mut self, l: usize, run: &Equations<f64>, res_slot: &[usize]) {
        let p = self.p;
        for i in 0..p {
            self.inv_mass[i].set_lane(l, run.inv_mass[i]);
        }
        for s in 0..=p {
            self.beta[s].set_lane(l, run.beta[s]);
        }
        let spread = |to: &mut [R], from: &[f64]| {
            to.iter_mut().for_each(|v| v.set_lane(l, 0.0));
            for (j, &slot) in res_slot.iter().enumerate() {
                to[slot].set_lane(l, from[j]);
            }
        };
        spread(&mut self.res_omega2, &run.res_omega2);
        spread(&mut self.res_coupling, &run.res_coupling);
        let (Some(lab), Some(src)) = (self.lab.as_mut(), run.lab.as_ref()) else {
            return;
        };
        debug_assert_eq!(lab.shape, src.shape, "a lane group shares its terms");
        for s in 0..=p {
            lab.law_coef[s].set_lane(l, src.law_coef[s]);
        }
        lab.actuator_rest_m.set_lane(l, src.actuator_rest_m);
        for i in 0..p {
            lab.mass[i].set_lane(l, src.mass[i]);
            lab.external_force_n[i].set_lane(l, src.external_force_n[i]);
            lab.on_site_rate[i].set_lane(l, src.on_site_rate[i]);
        }
        spread(&mut lab.on_site_rate[p..], &src.on_site_rate[p..]);
        spread(&mut lab.res_mass, &src.res_mass);
        spread(&mut lab.res_damping, &src.res_damping);
        spread(&mut lab.res_damping_rate, &src.res_damping_rate);
        spread(&mut lab.res_damping_coupling, &src.res_damping_coupling);
        spread(&mut lab.res_gravity, &src.res_gravity);
    }
}
