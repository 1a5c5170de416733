//! A cell's complex modes under resonator dashpots and on-site damping (docs/physics.md §8,
//! "Exact linear vibrations"): the dashpots c_j between the primary and its resonators are not
//! proportional damping, so the damped cell's modes are not the undamped cell's.
//!
//! The primary's response to its net force F is H(s) = 1 / (s (s + ρ) D(s)) with
//! D(s) = M + Σ_j m_j κ_j / (m_j s (s + ρ) + κ_j), κ_j = k_j + c_j s (ρ = 1/τ the on-site rate).
//! Its poles are the rigid pair 0, −ρ and, per flexible mode, a complex pair λ, λ̄ (the zeros of
//! D, followed from the undamped cell's Ω_k as the damping is switched on). Per pair,
//! r/(s − λ) + r̄/(s − λ̄) = (A s + B) / (s² + 2γ s + ω²), ω = |λ|, γ = −Re λ, A = 2 Re r,
//! B = −2 Re(r λ̄): the pair's part of the primary's displacement is B q + A q̇ of the damped
//! oscillator q'' + 2γ q' + ω² q = F. In the coordinates (c, d) = T (q, q̇), T = B + A K (K the
//! oscillator's companion matrix), the pair's free flow is the oscillator's own (T commutes with
//! e^{Kh}), its response to F is T times the oscillator's, and the primary moves as x = Σ c,
//! v = Σ d (the A terms cancel over the modes: H falls as s^{−2}). The exact stepper's loops
//! are therefore those of undamped modes with these weights; the cell's energy, no longer
//! diagonal in the modes, is rebuilt from every resonator's own residues where it is read (at
//! the samples: a step needs only the damping's part of the primary's acceleration).

use super::element_modes::ElementModes;
use crate::error::{Error, Result};
use nalgebra::{Complex, DMatrix, DVector};

type C = Complex<f64>;

/// Steps of the homotopy that switches the damping on (each root followed by Newton's method).
const HOMOTOPY_STEPS: usize = 16;
/// Newton's iterations per homotopy step, at most.
const NEWTON_ITERATIONS: usize = 60;
/// Resonators whose displacements and velocities the energy sums at once (independent sums,
/// each over the modes in order: they fill the vector lanes instead of waiting on each other).
const RESONATOR_GROUP: usize = 8;

/// One cell's damped modes (rigid first, then one per flexible mode in ascending frequency).
#[derive(Debug, Clone)]
pub(crate) struct DampedCell {
    /// Per mode: ω \[rad/s\], the damping rate 2γ \[1/s\], and the weights B \[1/kg\], A \[s/kg\]
    /// of the oscillator's position and rate in the primary's displacement.
    pub omega: Vec<f64>,
    pub rate: Vec<f64>,
    pub b: Vec<f64>,
    pub a: Vec<f64>,
    /// Per resonator j and mode k: the weights of (c_k, d_k) in its displacement less the
    /// primary's, and in its velocity.
    extension: ModeWeights,
    velocity: ModeWeights,
    primary_mass: f64,
    res_mass: Vec<f64>,
    res_stiffness: Vec<f64>,
    res_damping: Vec<f64>,
    on_site_rate: f64,
    /// The map from every mode's (c, d) to the cell's state (x0, x_j, v0, v_j), factorised.
    to_state: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
}

/// A resonator: mass \[kg\], stiffness \[N/m\], dashpot \[kg/s\].
pub(crate) type DampedResonator = (f64, f64, f64);

impl DampedCell {
    /// The damped modes of a primary `primary_mass` carrying `resonators`, every mass under
    /// on-site damping at `on_site_rate` 1/τ, from the undamped cell's modes `undamped`.
    /// Errors when a mode is overdamped or a root cannot be followed.
    pub fn new(
        primary_mass: f64,
        resonators: &[DampedResonator],
        on_site_rate: f64,
        undamped: &ElementModes,
    ) -> Result<Self> {
        let total = primary_mass + resonators.iter().map(|r| r.0).sum::<f64>();
        let roots = follow_roots(primary_mass, resonators, on_site_rate, undamped)?;
        let kk = roots.len() + 1;
        let r = resonators.len();
        let mut cell = DampedCell {
            omega: vec![0.0],
            rate: vec![on_site_rate],
            b: vec![1.0 / total],
            a: vec![0.0],
            extension: ModeWeights::zeros(kk, r),
            velocity: ModeWeights::zeros(kk, r),
            primary_mass,
            res_mass: resonators.iter().map(|r| r.0).collect(),
            res_stiffness: resonators.iter().map(|r| r.1).collect(),
            res_damping: resonators.iter().map(|r| r.2).collect(),
            on_site_rate,
            to_state: DMatrix::<f64>::identity(1, 1).lu(),
        };
        for j in 0..r {
            cell.velocity.set(0, j, [0.0, 1.0]); // the rigid mode moves every mass alike
        }
        for (k, &lambda) in roots.iter().enumerate() {
            let residue = residue(primary_mass, resonators, on_site_rate, lambda);
            let (b, a) = oscillator_weights(residue, lambda);
            let (omega, gamma) = (crate::math::modulus(lambda), -lambda.re);
            cell.omega.push(omega);
            cell.rate.push(2.0 * gamma);
            cell.b.push(b);
            cell.a.push(a);
            // (q, q̇) = T⁻¹ (c, d), T = [[B, A], [−A ω², B − 2γ A]].
            let det = b * (b - 2.0 * gamma * a) + a * a * omega * omega;
            let t_inv = [
                [(b - 2.0 * gamma * a) / det, -a / det],
                [a * omega * omega / det, b / det],
            ];
            let times_t_inv = |row: [f64; 2]| {
                [
                    row[0] * t_inv[0][0] + row[1] * t_inv[1][0],
                    row[0] * t_inv[0][1] + row[1] * t_inv[1][1],
                ]
            };
            for (j, &(m, kj, cj)) in resonators.iter().enumerate() {
                let kappa = lambda * cj + kj;
                let u = lambda * (lambda + on_site_rate);
                let transfer = kappa / (u * m + kappa);
                let (bj, aj) = oscillator_weights(transfer * residue, lambda);
                let x = times_t_inv([bj, aj]);
                cell.extension.set(k + 1, j, [x[0] - 1.0, x[1]]);
                // The velocity's weights: [B_j, A_j] K T⁻¹, K = [[0, 1], [−ω², −2γ]].
                cell.velocity.set(
                    k + 1,
                    j,
                    times_t_inv([-aj * omega * omega, bj - 2.0 * gamma * aj]),
                );
            }
        }
        cell.to_state = cell.state_map().lu();
        if !cell.to_state.is_invertible() {
            return Err(fail(cell.omega.get(1).copied().unwrap_or(0.0)));
        }
        Ok(cell)
    }

    /// Number of modes (rigid included).
    pub fn len(&self) -> usize {
        self.omega.len()
    }

    /// The 2N × 2N map from (c_0, d_0, c_1, d_1, …) to (x0, x_j…, v0, v_j…).
    fn state_map(&self) -> DMatrix<f64> {
        let (r, kk) = (self.res_mass.len(), self.len());
        let n = r + 1;
        let mut map = DMatrix::zeros(2 * n, 2 * kk);
        for k in 0..kk {
            map[(0, 2 * k)] = 1.0;
            map[(n, 2 * k + 1)] = 1.0;
            for j in 0..r {
                let e = self.extension.get(k, j);
                map[(1 + j, 2 * k)] = 1.0 + e[0];
                map[(1 + j, 2 * k + 1)] = e[1];
                let v = self.velocity.get(k, j);
                map[(n + 1 + j, 2 * k)] = v[0];
                map[(n + 1 + j, 2 * k + 1)] = v[1];
            }
        }
        map
    }

    /// Every mode's (c, d) of the cell's state: the primary's position `x0` and velocity `v0`,
    /// the resonators' `w` and `wdot`.
    pub fn project(
        &self,
        (x0, v0): (f64, f64),
        w: &[f64],
        wdot: &[f64],
        c: &mut [f64],
        d: &mut [f64],
    ) {
        let n = w.len() + 1;
        let mut state = DVector::zeros(2 * n);
        state[0] = x0;
        state[n] = v0;
        for j in 0..w.len() {
            state[1 + j] = w[j];
            state[n + 1 + j] = wdot[j];
        }
        let modes = self
            .to_state
            .solve(&state)
            .expect("the damped modes span the state");
        for k in 0..self.len() {
            c[k] = modes[2 * k];
            d[k] = modes[2 * k + 1];
        }
    }

    /// The cell's energy (kinetic and in its springs) \[J\], the power its dashpots and on-site
    /// damping dissipate \[W\], and Σ_k 2γ_k d_k \[m/s²\] (the damping's part of the primary's
    /// acceleration), from every mode's (c, d). Run in the AVX2 build where the CPU has it (its
    /// groups of resonators then fill 256-bit vectors): bit for bit [`DampedCell::energy_portable`],
    /// with no FMA contraction and every sum in its order (claim `simd_step_bit_identical`).
    #[allow(unsafe_code)]
    pub fn energy(&self, c: &[f64], d: &[f64]) -> (f64, f64, f64) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked on the line above).
            return unsafe { self.energy_avx2(c, d) };
        }
        self.energy_portable(c, d)
    }

    /// [`DampedCell::energy`] compiled with 256-bit vectors.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[allow(unsafe_code)]
    unsafe fn energy_avx2(&self, c: &[f64], d: &[f64]) -> (f64, f64, f64) {
        self.energy_portable(c, d)
    }

    /// [`DampedCell::energy`] without run-time SIMD dispatch: the reference the AVX2 build is
    /// checked against.
    #[inline(always)]
    pub fn energy_portable(&self, c: &[f64], d: &[f64]) -> (f64, f64, f64) {
        let kk = self.len();
        let v0: f64 = d[..kk].iter().sum();
        let mut kinetic = self.primary_mass * v0 * v0;
        let (mut strain, mut dashpots) = (0.0, 0.0);
        for (group, masses) in self.res_mass.chunks(RESONATOR_GROUP).enumerate() {
            let first = group * RESONATOR_GROUP;
            let ext = self.extension.group_sum(first, &c[..kk], &d[..kk]);
            let vel = self.velocity.group_sum(first, &c[..kk], &d[..kk]);
            for (jj, &m) in masses.iter().enumerate() {
                let (j, ext, v) = (first + jj, ext[jj], vel[jj]);
                kinetic += m * v * v;
                strain += self.res_stiffness[j] * ext * ext;
                dashpots += self.res_damping[j] * (v - v0) * (v - v0);
            }
        }
        (
            0.5 * (kinetic + strain),
            dashpots + self.on_site_rate * kinetic,
            self.damping_accel(d),
        )
    }

    /// Σ_k 2γ_k d_k \[m/s²\]: the damping's part of the primary's acceleration, from every
    /// mode's rate d (what a step needs of the cell; its energy is needed only where read).
    pub fn damping_accel(&self, d: &[f64]) -> f64 {
        (0..self.len()).map(|k| self.rate[k] * d[k]).sum()
    }
}

/// Weights of every mode's (c_k, d_k) in a quantity of each resonator j, stored mode by mode
/// (the resonators padded with zeros to whole groups of [`RESONATOR_GROUP`]).
#[derive(Debug, Clone)]
struct ModeWeights {
    c: Vec<f64>,
    d: Vec<f64>,
    /// The resonators' count, padded.
    stride: usize,
}

impl ModeWeights {
    fn zeros(modes: usize, resonators: usize) -> Self {
        let stride = resonators.div_ceil(RESONATOR_GROUP) * RESONATOR_GROUP;
        ModeWeights {
            c: vec![0.0; modes * stride],
            d: vec![0.0; modes * stride],
            stride,
        }
    }

    fn set(&mut self, mode: usize, resonator: usize, [wc, wd]: [f64; 2]) {
        let at = mode * self.stride + resonator;
        (self.c[at], self.d[at]) = (wc, wd);
    }

    fn get(&self, mode: usize, resonator: usize) -> [f64; 2] {
        let at = mode * self.stride + resonator;
        [self.c[at], self.d[at]]
    }

    /// Σ_k (w_c c_k + w_d d_k) for the group of resonators from `first`, each summed over the
    /// modes in order.
    #[inline(always)]
    fn group_sum(&self, first: usize, c: &[f64], d: &[f64]) -> [f64; RESONATOR_GROUP] {
        let mut sum = [0.0; RESONATOR_GROUP];
        for (k, (&ck, &dk)) in c.iter().zip(d).enumerate() {
            let at = k * self.stride + first;
            let wc: &[f64; RESONATOR_GROUP] = self.c[at..at + RESONATOR_GROUP]
                .try_into()
                .expect("padded to whole groups");
            let wd: &[f64; RESONATOR_GROUP] = self.d[at..at + RESONATOR_GROUP]
                .try_into()
                .expect("padded to whole groups");
            for jj in 0..RESONATOR_GROUP {
                sum[jj] += wc[jj] * ck + wd[jj] * dk;
            }
        }
        sum
    }
}

/// The pair's weights (B, A) of the residue r at λ: r/(s − λ) + r̄/(s − λ̄) = (A s + B)/(…).
fn oscillator_weights(residue: C, lambda: C) -> (f64, f64) {
    (-2.0 * (residue * lambda.conj()).re, 2.0 * residue.re)
}

/// D(s) and D'(s) of the cell (the resonators' dashpots and the on-site rate ρ as given).
fn effective_mass(primary_mass: f64, resonators: &[DampedResonator], rho: f64, s: C) -> (C, C) {
    let u = s * (s + rho);
    let du = s * 2.0 + rho;
    let (mut value, mut slope) = (C::new(primary_mass, 0.0), C::new(0.0, 0.0));
    for &(m, k, c) in resonators {
        let kappa = s * c + k;
        let den = u * m + kappa;
        value += kappa * m / den;
        slope += (u * c - kappa * du) * (m * m) / (den * den);
    }
    (value, slope)
}

/// D(s) times the denominators m_q s (s + ρ) + κ_q of the resonators `poles` (one or two: the
/// poles next to a mode), and its slope: the same zeros near those poles without their
/// poles, so that Newton's steps converge even for a mode of tiny effective mass lying next to
/// its pole (as for the undamped cell's secular equation, `ode::modal`).
fn deflated(
    primary_mass: f64,
    resonators: &[DampedResonator],
    rho: f64,
    s: C,
    poles: &[usize],
) -> (C, C) {
    let u = s * (s + rho);
    let du = s * 2.0 + rho;
    let den = |j: usize| {
        let (m, k, c) = resonators[j];
        (u * m + s * c + k, du * m + c)
    };
    // P = Π den_q, P' and, per pole, P_j = P / den_j and its slope.
    let (mut p, mut dp) = (C::new(1.0, 0.0), C::new(0.0, 0.0));
    for &q in poles {
        let (d, dd) = den(q);
        dp = dp * d + p * dd;
        p *= d;
    }
    let (mut rest, mut drest) = (C::new(primary_mass, 0.0), C::new(0.0, 0.0));
    for (j, &(m, k, c)) in resonators.iter().enumerate() {
        if poles.contains(&j) {
            continue;
        }
        let kappa = s * c + k;
        let d = u * m + kappa;
        rest += kappa * m / d;
        drest += (u * c - kappa * du) * (m * m) / (d * d);
    }
    let (mut value, mut slope) = (p * rest, dp * rest + p * drest);
    for &j in poles {
        let (m, k, c) = resonators[j];
        let kappa = s * c + k;
        let (mut pj, mut dpj) = (C::new(1.0, 0.0), C::new(0.0, 0.0));
        for &q in poles.iter().filter(|&&q| q != j) {
            let (d, dd) = den(q);
            dpj = dpj * d + pj * dd;
            pj *= d;
        }
        value += kappa * m * pj;
        slope += pj * (m * c) + kappa * m * dpj;
    }
    (value, slope)
}

/// The residue of H(s) = 1/(s (s + ρ) D(s)) at a zero λ of D: 1/(λ (λ + ρ) D'(λ)).
fn residue(primary_mass: f64, resonators: &[DampedResonator], rho: f64, lambda: C) -> C {
    let (_, slope) = effective_mass(primary_mass, resonators, rho, lambda);
    C::new(1.0, 0.0) / (lambda * (lambda + rho) * slope)
}

/// The zeros of D with Im > 0, one per flexible mode of `undamped`, followed from iΩ_k as the
/// dashpots and the on-site rate grow from 0 to their values.
fn follow_roots(
    primary_mass: f64,
    resonators: &[DampedResonator],
    rho: f64,
    undamped: &ElementModes,
) -> Result<Vec<C>> {
    let mut roots: Vec<C> = undamped.omega[1..]
        .iter()
        .map(|&w| C::new(0.0, w))
        .collect();
    // Mode k lies between the poles of the resonators k − 1 and k in ascending frequency.
    let mut order: Vec<usize> = (0..resonators.len()).collect();
    let w2 = |j: usize| resonators[j].1 / resonators[j].0;
    order.sort_by(|&a, &b| w2(a).total_cmp(&w2(b)));
    for step in 1..=HOMOTOPY_STEPS {
        let t = step as f64 / HOMOTOPY_STEPS as f64;
        let scaled: Vec<DampedResonator> =
            resonators.iter().map(|&(m, k, c)| (m, k, c * t)).collect();
        for (mode, root) in roots.iter_mut().enumerate() {
            let poles = &order[mode..(mode + 2).min(order.len())];
            let mut s = *root;
            let mut last = f64::INFINITY;
            for _ in 0..NEWTON_ITERATIONS {
                let (value, slope) = deflated(primary_mass, &scaled, rho * t, s, poles);
                let delta = value / slope;
                s -= delta;
                last = crate::math::modulus(delta) / crate::math::modulus(s);
                if last <= 4.0 * f64::EPSILON {
                    break;
                }
            }
            // Converged to rounding (Newton's steps then stall at a few ulps).
            if last > 1e-12 || s.im <= 0.0 || !s.re.is_finite() {
                return Err(fail(root.im));
            }
            *root = s;
        }
    }
    // Each root followed to its own mode: no two the same.
    let mut sorted: Vec<f64> = roots.iter().map(|r| r.im).collect();
    sorted.sort_by(f64::total_cmp);
    if sorted.windows(2).any(|w| w[1] - w[0] <= 1e-9 * w[1]) {
        return Err(fail(sorted[0]));
    }
    Ok(roots)
}

fn fail(omega: f64) -> Error {
    Error::invalid(
        "damping.resonator_ratio",
        format!("mode at {:.4e} Hz", omega / std::f64::consts::TAU),
        "the exact modal method could not follow this damped mode (overdamped, or too close to \
         another): use dopri5, or run.peak_tolerance with a smaller damping",
    )
}
