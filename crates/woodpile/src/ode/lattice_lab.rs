//! The lab physics of a lattice (docs/physics.md §16): the chains' contact laws at every
//! contact, damping of the rods' modes, a blast or force drive split over load points or a
//! displacement actuator pressing on them, gravity and a preload, the static equilibrium the
//! run starts from (a damped Newton minimisation of the potential energy,
//! `ode::lattice_static`), and the energy integrals W and D.

use super::lattice::graph::{ContactGraph, Side};
use super::lattice_static::StaticState;
use crate::error::{Error, Result};
use crate::model::{ContactDamping, ContactLaw, LatticeExcitation, LatticeLab};

/// The compiled lab terms of a lattice, over its [`ContactGraph`].
#[derive(Debug, Clone)]
pub(crate) struct LabTerms {
    /// Law and coefficient per contact ([`ContactLaw::compile`]; loads: elastic, unused).
    laws: Vec<ContactLaw>,
    law_coef: Vec<f64>,
    allow_pull: bool,
    /// Damping rate per coordinate [1/s]: 2 ζ ω_j + 1/τ on the rods' modes, 0 on the striker.
    damping_rate: Vec<f64>,
    /// Damping that couples a body's modes (a chain cell's resonator dashpots), on top of
    /// `damping_rate`.
    damping_blocks: Vec<DampingBlock>,
    /// Constant generalised force per coordinate: gravity g ψ_tᵀMφ_j on every body, and a
    /// preload beside a striker (on the top-layer crossings).
    static_force: Vec<f64>,
    /// The blast's or drive's history.
    excitation: LatticeExcitation,
    /// The preload F_p \[N\]; per load point of a prescribed force F_p/N (an actuator's tips
    /// carry the shares of the static equilibrium, `static_force_n`), and each point's share
    /// 1/N of the load's force.
    preload_n: f64,
    preload_per_point_n: f64,
    share: f64,
    /// A displacement actuator's static position u* \[m\] (downward), the same δ⁰ for every
    /// tip: δ_c = u* + u(t) − w_c (0 without an actuator).
    pub(super) actuator_rest_m: f64,
    /// The state the run starts from (static equilibrium) and each contact's static force.
    pub(super) q0: Vec<f64>,
    pub(super) static_force_n: Vec<f64>,
    pub(super) static_residual: f64,
    /// Per contact at the last evaluation: overlap rate (a load point's velocity) \[m/s\] and
    /// dissipated power \[W\].
    rate_m_s: Vec<f64>,
    dissipated_w: Vec<f64>,
}

impl LabTerms {
    /// Compiles the laws, damping and loads of `lab` on `ode` and solves for the equilibrium.
    /// `preload_points`: where a preload beside a striker acts, each point's first coordinate
    /// and row (a lattice's top-layer crossings, a chain's top element).
    pub(super) fn compile(
        ode: &ContactGraph,
        preload_points: &[(usize, Vec<f64>)],
        excitation: &LatticeExcitation,
        lab: &LatticeLab,
    ) -> Result<Self> {
        let nc = ode.contacts();
        let (laws, law_coef) = contact_laws(ode, excitation, &lab.damping)?;
        let q = ode.coordinates();
        let first = usize::from(ode.struck);
        let on_site = lab.damping.on_site_time_s.map_or(0.0, |tau| 1.0 / tau);
        let damping_rate: Vec<f64> = (0..q)
            .map(|j| {
                if j < first {
                    0.0
                } else {
                    2.0 * lab.modal_ratio * ode.omega2[j].sqrt() + on_site
                }
            })
            .collect();
        let g = lab.preload.gravity_m_s2;
        let mut static_force: Vec<f64> = ode.translation.iter().map(|t| g * t).collect();
        let preload = lab.preload.force_n;
        if ode.struck && preload != 0.0 {
            let per_point = preload / preload_points.len() as f64;
            for (offset, row) in preload_points {
                for (k, r) in row.iter().enumerate() {
                    static_force[offset + k] += per_point * r;
                }
            }
        }
        let loads = ode.loads;
        let mut terms = LabTerms {
            laws,
            law_coef,
            allow_pull: lab.damping.allow_pull,
            damping_rate,
            damping_blocks: Vec::new(),
            static_force,
            excitation: excitation.clone(),
            preload_n: preload,
            preload_per_point_n: if loads > 0 {
                preload / loads as f64
            } else {
                0.0
            },
            share: if loads > 0 { 1.0 / loads as f64 } else { 0.0 },
            actuator_rest_m: 0.0,
            q0: vec![0.0; q],
            static_force_n: vec![0.0; nc],
            static_residual: 0.0,
            rate_m_s: vec![0.0; nc],
            dissipated_w: vec![0.0; nc],
        };
        let state = terms.static_equilibrium(ode)?;
        let q0 = state.q;
        terms.actuator_rest_m = match state.actuator_m {
            Some(u) => u,
            // An actuator without a preload touches the highest of its points at no force
            // (the lattice's points all at w = 0 without gravity).
            None if ode.actuator => (0..loads)
                .map(|c| ode.deflection(ode.below[c].expect("a load's rod"), &q0))
                .fold(f64::INFINITY, f64::min),
            None => 0.0,
        };
        terms.static_force_n = (0..nc)
            .map(|c| {
                if c < loads && ode.actuator {
                    let overlap = terms.actuator_rest_m + ode.overlap(c, &q0);
                    ContactLaw::elastic_force(ode.beta[c], overlap)
                } else if c < loads {
                    terms.preload_per_point_n
                } else if ode.struck && c == 0 {
                    0.0
                } else {
                    ContactLaw::elastic_force(ode.beta[c], ode.overlap(c, &q0))
                }
            })
            .collect();
        terms.q0 = q0;
        terms.static_residual = state.residual;
        Ok(terms)
    }

    /// Every contact's overlap and force at state y and time t into the ODE's `overlap_m` and
    /// `force_n`, their rates and dissipated powers into `rate_m_s` and `dissipated_w`.
    pub(super) fn contact_forces(&mut self, ode: &mut ContactGraph, t: f64, y: &[f64]) {
        let q = ode.coordinates();
        let (x, v) = (&y[..q], &y[q + 3..2 * q + 3]);
        let load_n = self.preload_per_point_n + self.share * self.excitation.total_force_n(t);
        let tip = match &self.excitation {
            LatticeExcitation::Drive { drive, .. } if ode.actuator => drive.value_and_rate(t),
            _ => (0.0, 0.0),
        };
        for c in 0..ode.contacts() {
            if c < ode.loads && ode.actuator {
                // The tip presses down by u(t); the point's deflection w is −overlap(c) (the
                // side above is empty).
                let d = self.actuator_rest_m + tip.0 + ode.overlap(c, x);
                let r = tip.1 + ode.overlap(c, v);
                let (f, p) =
                    self.laws[c].force(self.law_coef[c], ode.beta[c], d, r, self.allow_pull);
                ode.overlap_m[c] = d;
                ode.force_n[c] = f;
                // The load's power is F u̇ (W); a damped tip law dissipates p.
                self.rate_m_s[c] = tip.1;
                self.dissipated_w[c] = p;
                continue;
            }
            if c < ode.loads {
                ode.force_n[c] = load_n;
                ode.overlap_m[c] = 0.0;
                self.rate_m_s[c] = ode.deflection(ode.below[c].expect("a load's rod"), v);
                self.dissipated_w[c] = 0.0;
                continue;
            }
            let [d, r] = ode.overlaps(c, [x, v]);
            let (f, p) = self.laws[c].force(self.law_coef[c], ode.beta[c], d, r, self.allow_pull);
            ode.overlap_m[c] = d;
            ode.force_n[c] = f;
            self.rate_m_s[c] = r;
            self.dissipated_w[c] = p;
        }
    }

    /// dy/dt's second half: accelerations, the supports' impulse rates, and the rates of W,
    /// D_modes and every contact's D.
    pub(super) fn rhs(&mut self, ode: &mut ContactGraph, t: f64, y: &[f64], dydt: &mut [f64]) {
        self.contact_forces(ode, t, y);
        let q = ode.coordinates();
        let (x, v) = (&y[..q], &y[q + 3..2 * q + 3]);
        let (a, integrals) = dydt[q + 3..].split_at_mut(q + 3);
        let (mut work, mut modal) = (0.0, 0.0);
        for j in 0..q {
            let damping = self.damping_rate[j] * v[j];
            a[j] = -ode.omega2[j] * x[j] - damping + self.static_force[j];
            work += self.static_force[j] * v[j];
            modal += damping * v[j];
        }
        for block in &self.damping_blocks {
            modal += block.apply(v, a);
        }
        ode.apply_contact_forces(a);
        a[q..q + 3].copy_from_slice(&ode.support_impulse_rates());
        for c in 0..ode.loads {
            work += ode.force_n[c] * self.rate_m_s[c];
        }
        integrals[0] = work;
        integrals[1] = modal;
        integrals[2..].copy_from_slice(&self.dissipated_w);
    }

    /// The static equilibrium of the rods under gravity and the preload
    /// (`ode::lattice_static`): the static forces f, a force load's preload included, and the
    /// minimum of the potential for them; under a displacement drive with a preload, the
    /// actuator's position too (its tips carry the shares the equilibrium gives them).
    fn static_equilibrium(&self, ode: &ContactGraph) -> Result<StaticState> {
        let first = usize::from(ode.struck);
        let mut f = self.static_force.clone();
        if !ode.actuator {
            for c in 0..ode.loads {
                let s = ode.below[c].expect("a load's rod");
                for k in 0..s.len {
                    f[s.offset + k] += self.preload_per_point_n * ode.rows[s.row + k];
                }
            }
        }
        f[..first].iter_mut().for_each(|x| *x = 0.0);
        let actuator = (ode.actuator && self.preload_n > 0.0).then_some(self.preload_n);
        super::lattice_static::static_equilibrium(ode, &f, actuator)
    }
}

/// A damping matrix C (len × len, row-major) [1/s] over one body's modal velocities
/// `offset..offset + len`: the accelerations −C q̇.
#[derive(Debug, Clone)]
pub(super) struct DampingBlock {
    pub offset: usize,
    pub len: usize,
    pub matrix: Vec<f64>,
}

impl DampingBlock {
    /// Subtracts C q̇ from the accelerations `a`; returns the power it dissipates, q̇ᵀ C q̇ \[W\].
    fn apply(&self, v: &[f64], a: &mut [f64]) -> f64 {
        let v = &v[self.offset..self.offset + self.len];
        let mut power = 0.0;
        for (i, row) in self.matrix.chunks_exact(self.len).enumerate() {
            let f: f64 = row.iter().zip(v).map(|(c, v)| c * v).sum();
            a[self.offset + i] -= f;
            power += f * v[i];
        }
        power
    }
}

impl LabTerms {
    /// Replaces every contact's law and coefficient (a chain's, as the chain compiles them).
    pub(super) fn set_laws(&mut self, laws: Vec<ContactLaw>, law_coef: Vec<f64>) {
        debug_assert_eq!(laws.len(), self.laws.len());
        self.laws = laws;
        self.law_coef = law_coef;
    }

    /// Adds damping that couples one body's modes.
    pub(super) fn add_damping_block(&mut self, block: DampingBlock) {
        self.damping_blocks.push(block);
    }
}

/// The law and coefficient of every contact (the chains' [`ContactLaw::compile`]): the
/// striker's law at the striker and at a displacement actuator's tips, the wall's at every support, `damping.contacts` at every
/// crossing; m_eff the reduced mass of the two bodies' whole masses (a rod's alone at a
/// support).
fn contact_laws(
    ode: &ContactGraph,
    excitation: &LatticeExcitation,
    damping: &crate::model::Damping,
) -> Result<(Vec<ContactLaw>, Vec<f64>)> {
    let v_in = match (damping.impact_speed_m_s, excitation) {
        (Some(v), _) => v,
        (None, LatticeExcitation::Impact { striker, .. }) => striker.velocity_m_s,
        (None, _) => f64::NAN,
    };
    let lossy_hc = |l: &ContactDamping| matches!(l, ContactDamping::HuntCrossley { restitution } if *restitution < 1.0);
    if [damping.contacts, damping.striker_law(), damping.wall_law()]
        .iter()
        .any(lossy_hc)
        && v_in.is_nan()
    {
        return Err(Error::invalid(
            "damping.impact_speed_m_s",
            "(none)",
            "the Hunt–Crossley law needs the impact speed v_in of its contacts: give it, or use a striker (its speed is the default)",
        ));
    }
    // A body's mass: Σ_j (ψ_tᵀMφ_j)² over its coordinates = ψ_tᵀMψ_t.
    let mass = |s: Side| -> f64 {
        ode.translation[s.offset..s.offset + s.len]
            .iter()
            .map(|t| t * t)
            .sum()
    };
    Ok((0..ode.contacts())
        .map(|c| {
            if c < ode.loads {
                // A displacement actuator's tip: the striker's law (as the chains' actuator),
                // m_eff the rod's mass.
                return match ode.below[c] {
                    Some(b) if ode.actuator => {
                        ContactLaw::compile(damping.striker_law(), ode.beta[c], mass(b), v_in)
                    }
                    _ => (ContactLaw::Elastic, 0.0),
                };
            }
            let (law, m) = match ode.below[c] {
                None => (damping.wall_law(), mass(ode.above[c])),
                Some(b) => {
                    let (ma, mb) = (mass(ode.above[c]), mass(b));
                    let law = if ode.struck && c == 0 {
                        damping.striker_law()
                    } else {
                        damping.contacts
                    };
                    (law, ma * mb / (ma + mb))
                }
            };
            ContactLaw::compile(law, ode.beta[c], m, v_in)
        })
        .unzip())
}

/// What the exact modal method on the contact graph reads of the lab terms
/// (`integrate::modal_graph`, docs/physics.md §8).
impl LabTerms {
    /// Whether the lab terms keep the equations linear in the modes between the contacts'
    /// elastic forces: every contact law elastic (damping of the modes, prescribed load forces,
    /// gravity and a preload — constant modal forces — are what the method advances exactly).
    pub(super) fn linear_modes_only(&self) -> bool {
        self.laws.iter().all(|&l| l == ContactLaw::Elastic) && self.damping_blocks.is_empty()
    }

    /// Per coordinate: the constant generalised force of gravity and a striker's preload.
    pub(super) fn static_modal_force(&self) -> &[f64] {
        &self.static_force
    }

    /// Damping rate per coordinate, 2 ζ ω_j + 1/τ [1/s].
    pub(super) fn damping_rates(&self) -> &[f64] {
        &self.damping_rate
    }

    /// Each load point's prescribed force at t \[N\].
    pub(super) fn load_per_point_n(&self, t: f64) -> f64 {
        self.preload_per_point_n + self.share * self.excitation.total_force_n(t)
    }

    /// The times where the load's force or its first or second derivative jumps \[s\],
    /// ascending: a Friedlander blast's end, a table's times, a drive's ramp ends and a chirp's
    /// end.
    pub(super) fn load_kinks_s(&self) -> Vec<f64> {
        use crate::excitation::{BlastProfile, Signal};
        let mut kinks = match &self.excitation {
            LatticeExcitation::Blast { profile, .. } => match profile {
                BlastProfile::Friedlander { duration_s, .. } => vec![*duration_s],
                BlastProfile::Table { times_s, .. } => times_s.clone(),
            },
            LatticeExcitation::Drive { drive, .. } => {
                let mut k = vec![drive.ramp_s];
                match &drive.signal {
                    Signal::Chirp { duration_s, .. } => {
                        k.extend([duration_s - drive.ramp_s, *duration_s]);
                    }
                    Signal::Table { times_s, .. } => k.extend_from_slice(times_s),
                    Signal::Harmonic { .. } => {}
                }
                k
            }
            _ => Vec::new(),
        };
        kinks.retain(|&t| t > 0.0);
        kinks.sort_by(f64::total_cmp);
        kinks
    }

    /// Per contact at the last evaluation: the overlap rate (a load point's velocity) \[m/s\].
    pub(super) fn overlap_rates_m_s(&self) -> &[f64] {
        &self.rate_m_s
    }

    /// Each load point's force rate at t \[N/s\]: a drive's; 0 for a blast (a Friedlander
    /// blast's peak is its start, a table's at its breakpoints).
    pub(super) fn load_rate_per_point_n_s(&self, t: f64) -> f64 {
        match &self.excitation {
            LatticeExcitation::Drive { drive, .. } => self.share * drive.value_and_rate(t).1,
            _ => 0.0,
        }
    }
}
