//! Exponential Lobatto collocation for x'' = −Ω² x + g(x) in modal form
//! (the chain's cells in their free–free modes, docs/physics.md §8 "Exact linear vibrations"): the linear
//! vibrations are integrated exactly, only the contact forces are approximated.
//!
//! Over a step [t₀, t₀ + h] the net contact force on every primary is replaced by its cubic
//! interpolant through the four Lobatto nodes σ = 0, (5 ∓ √5)/10, 1; every mode c'' + Ω² c =
//! F(t)/μ is then advanced by the variation-of-constants formula with that cubic, exactly:
//!
//! ```text
//! c(θh)  = cos(θz) c₀ + h sin(θz)/z ċ₀ + h²/μ Σ_n S_n(θ, z) a_n,   z = hΩ,
//! ċ(θh)  = −(z/h) sin(θz) c₀ + cos(θz) ċ₀ + h/μ Σ_n C_n(θ, z) a_n,
//! ```
//!
//! with a_n the monomial coefficients of the cubic in σ, and S_n, C_n the kernels
//! ∫₀^θ sin(z(θ−σ))/z σⁿ dσ and ∫₀^θ cos(z(θ−σ)) σⁿ dσ (φ-functions of iθz; [`kernel`]). The
//! node forces depend on the node positions: the collocation conditions are solved by fixed-point
//! iteration on the primaries alone (the contacts see nothing else). For g = 0 the flow is exact
//! (rounding only); for slow modes (z → 0) the method is Lobatto IIIA collocation of order 6
//! (Hairer, Nørsett & Wanner I, §II.7); for fast modes the error is that of the cubic force
//! interpolant, which those modes answer to quasi-statically, ∝ 1/Ω².
//!
//! ## References
//! - M. Hochbruck, C. Lubich, "A Gautschi-type method for oscillatory second-order differential
//!   equations", Numer. Math. 83 (1999) 403–426.
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., Springer 2006,
//!   ch. XIII (trigonometric integrators, filter functions).
//! - M. Hochbruck, A. Ostermann, "Exponential integrators", Acta Numerica 19 (2010) 209–286
//!   (φ-functions, exponential collocation).

use crate::math::Libm;
use crate::real::{Lane, Real};

/// The Lobatto nodes of the force interpolant, σ = 0, (5 − √5)/10, (5 + √5)/10, 1.
pub fn nodes() -> [f64; 4] {
    let r5 = 5f64.sqrt();
    [0.0, (5.0 - r5) / 10.0, (5.0 + r5) / 10.0, 1.0]
}

/// Monomial coefficients of the Lagrange basis on [`nodes`]: the cubic through values F_i at the
/// nodes is Σ_n a_n σⁿ with a_n = Σ_i L\[n\]\[i\] F_i.
pub fn lagrange() -> [[f64; 4]; 4] {
    let c = nodes();
    let mut l = [[0.0; 4]; 4];
    for i in 0..4 {
        // ℓ_i(σ) = Π_{j≠i} (σ − c_j)/(c_i − c_j), expanded into monomials.
        let mut poly = [1.0, 0.0, 0.0, 0.0];
        let mut denom = 1.0;
        for j in (0..4).filter(|&j| j != i) {
            let mut next = [0.0; 4];
            for n in 0..4 {
                if n + 1 < 4 {
                    next[n + 1] += poly[n];
                }
                next[n] -= c[j] * poly[n];
            }
            poly = next;
            denom *= c[i] - c[j];
        }
        for n in 0..4 {
            l[n][i] = poly[n] / denom;
        }
    }
    l
}

/// What the variation-of-constants formula needs of one mode at one point θ of a step, for
/// z = hΩ: cos(θz), sin(θz)/z (θ at z = 0), z sin(θz), and the kernels S_n, C_n, n = 0..3.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Kernel {
    /// cos(θz).
    pub cos: f64,
    /// sin(θz)/z (θ at z = 0).
    pub sinc: f64,
    /// z sin(θz).
    pub zsin: f64,
    /// S_n(θ, z) = ∫₀^θ sin(z(θ−σ))/z σⁿ dσ, n = 0..3.
    pub s: [f64; 4],
    /// C_n(θ, z) = ∫₀^θ cos(z(θ−σ)) σⁿ dσ, n = 0..3.
    pub c: [f64; 4],
}

/// Terms of φ_4's series summed below |x| = 2.
const PHI4_TERMS: usize = 12;

/// The series of φ_4(ix) in y = x²: Re φ_4 = Σ_k (−1)^k y^k/(2k + 4)! and
/// Im φ_4 / x = Σ_k (−1)^k y^k/(2k + 5)!, k < [`PHI4_TERMS`].
const PHI4_SERIES: [[f64; PHI4_TERMS]; 2] = {
    let mut c = [[0.0; PHI4_TERMS]; 2];
    let mut inv_fact = 1.0 / 24.0; // 1/(m + 4)!, m = 0
    let mut m = 0;
    while m < 2 * PHI4_TERMS {
        let sign = if (m / 2) % 2 == 0 { 1.0 } else { -1.0 };
        c[m % 2][m / 2] = sign * inv_fact;
        inv_fact /= (m + 5) as f64;
        m += 1;
    }
    c
};

/// [`Kernel`] at θ ∈ (0, 1] for z = hΩ ≥ 0. With x = θz and φ_k(ix) = Σ_m (ix)^m/(m + k)!,
/// ∫₀^θ e^{iz(θ−σ)} σⁿ dσ = n! θ^{n+1} φ_{n+1}(ix): C_n its real part, S_n its imaginary part
/// over z. Series below |x| = 2, the recurrence φ_{k+1} = (φ_k − 1/k!)/(ix) from φ_0 = e^{ix}
/// above (where it loses no digits).
pub fn kernel(theta: f64, z: f64) -> Kernel {
    let x = theta * z;
    // re[k] = Re φ_k(ix), imx[k] = Im φ_k(ix)/x, k = 0..=4.
    let (mut re, mut imx) = ([0.0; 5], [0.0; 5]);
    if x < 2.0 {
        // φ_4 by its series, Σ_m (ix)^m/(m + 4)!, in y = x² by Horner's rule: twelve terms of
        // each part (the first left out, 4¹²/28! at x = 2, is below 1e-19 of either sum), then
        // downward: φ_k = 1/k! + ix φ_{k+1}, which adds no rounding for x < 2.
        let x2 = x * x;
        let horner = |c: &[f64; PHI4_TERMS]| c.iter().rev().fold(0.0, |acc, &c| acc * x2 + c);
        re[4] = horner(&PHI4_SERIES[0]);
        imx[4] = horner(&PHI4_SERIES[1]);
        const INV_FACT: [f64; 4] = [1.0, 1.0, 0.5, 1.0 / 6.0];
        for k in (0..4).rev() {
            re[k] = INV_FACT[k] - x2 * imx[k + 1];
            imx[k] = re[k + 1];
        }
    } else {
        let (s, c) = x.libm_sin_cos();
        let inv_x = 1.0 / x;
        let (mut r, mut i) = (c, s);
        re[0] = r;
        imx[0] = i * inv_x;
        const INV_FACT: [f64; 4] = [1.0, 1.0, 0.5, 1.0 / 6.0];
        for (k, inv_fact) in INV_FACT.iter().enumerate() {
            let (r1, i1) = (i * inv_x, (inv_fact - r) * inv_x);
            r = r1;
            i = i1;
            re[k + 1] = r;
            imx[k + 1] = i * inv_x;
        }
    }
    let mut kern = Kernel {
        cos: re[0],
        sinc: theta * imx[0],
        zsin: z * x * imx[0],
        ..Kernel::default()
    };
    let mut fact = 1.0; // n!
    let mut pow = theta; // θ^{n+1}
    for n in 0..4 {
        if n > 0 {
            fact *= n as f64;
        }
        kern.c[n] = fact * pow * re[n + 1];
        kern.s[n] = fact * pow * theta * imx[n + 1];
        pow *= theta;
    }
    kern
}

/// The weights of one step size h for a chain, per group of four modes of each distinct
/// element (equal cells share theirs; each element's modes padded to whole groups, so that the
/// passes over the modes run four modes per vector): the free motion at the nodes, the
/// end-of-step update, and per distinct element its primary's response to the force at the
/// nodes, summed over its modes.
#[derive(Debug, Clone)]
pub(crate) struct StepWeights {
    /// Per group: the free motion at the nodes.
    pub nodes: Vec<NodeGroup>,
    /// Per group: the end-of-step update.
    pub end: Vec<EndGroup>,
    /// Per distinct element: its primary's response at node j = 1..3 (rows) to the force's
    /// values at the four nodes (columns): Σ_k S_n(c_j, z_k)/μ_k against σⁿ, n = 0..3, with the
    /// Lagrange basis through the nodes folded in.
    pub node_response: Vec<[[f64; 4]; 3]>,
    /// Per distinct element: the position and velocity error weights, Σ_k W(z_k)/μ_k with W the kernels
    /// against σ(σ − ½)(σ − 1) (the cubic's part its quadratic through 0, ½, 1 lacks).
    pub error: Vec<(f64, f64)>,
    /// Per distinct element: its rigid mode's response to a unit acceleration (gravity's part).
    pub rigid: Vec<RigidResponse>,
}

/// A rigid mode's response to a constant unit acceleration over a step from rest: its
/// displacement at the nodes σ = c₁, c₂, 1 (h²σ²/2 undamped) and its velocity at the end.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RigidResponse {
    pub nodes: [f64; 3],
    pub end_velocity: f64,
}

/// One mode's kernels at a point θ of a step, damped or not: the free flow (position's and
/// rate's response to the initial position and rate, in σ = t/h) and the responses S_n, C_n to
/// σⁿ, in [`DampedKernel`]'s form ([`kernel`] undamped, [`damped_kernel`] damped).
pub(crate) type Flow = DampedKernel;

impl Flow {
    /// The kernels at θ of a step h of a mode of frequency ω \[rad/s\] and damping rate
    /// 2γ \[1/s\] (0: undamped).
    #[inline]
    pub fn new(theta: f64, h: f64, omega: f64, rate: f64) -> Self {
        if rate > 0.0 {
            let k = damped_kernel(theta, 0.5 * rate * h, h * omega);
            return Flow {
                pos_of_pos: k.pos_of_pos,
                pos_of_rate: k.pos_of_rate,
                rate_of_pos: k.rate_of_pos,
                rate_of_rate: k.rate_of_rate,
                s: k.s,
                c: k.c,
            };
        }
        let k = kernel(theta, h * omega);
        Flow {
            pos_of_pos: k.cos,
            pos_of_rate: k.sinc,
            rate_of_pos: -k.zsin,
            rate_of_rate: k.cos,
            s: k.s,
            c: k.c,
        }
    }

    /// The kernels at the three nodes σ = c₁, c₂, 1.
    #[inline]
    pub fn at_nodes(h: f64, omega: f64, rate: f64) -> [Self; 3] {
        let c = nodes();
        [
            Flow::new(c[1], h, omega, rate),
            Flow::new(c[2], h, omega, rate),
            Flow::new(1.0, h, omega, rate),
        ]
    }
}

/// Four modes' free motion at the nodes σ = c₁, c₂, 1: cos(σz) and h sin(σz)/z (a damped
/// mode's position's response to its initial position and h times its initial rate).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct NodeGroup {
    cos: [Quad; 3],
    hsinc: [Quad; 3],
}

/// Four modes' end-of-step update: cos z, h sin(z)/z, −(z/h) sin z (the velocity's part of the
/// position), cos z again (the velocity's part of the velocity), h² S_n(1, z)/μ and h C_n(1, z)/μ
/// (the end state's response to σⁿ), and μ/2 and Ω² (for the sums of the end state); a damped
/// mode has the damped kernels' ([`Flow`]) in their places.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct EndGroup {
    cos: Quad,
    hsinc: Quad,
    vel_of_pos: Quad,
    vel_of_vel: Quad,
    pos_force: [Quad; 4],
    vel_force: [Quad; 4],
    half_modal_mass: Quad,
    omega2: Quad,
}

/// σ³ − (3/2)σ² + (1/2)σ in monomials: the error polynomial of [`StepWeights::error`].
pub(crate) const ERROR_POLY: [f64; 4] = [0.0, 0.5, -1.5, 1.0];

impl StepWeights {
    /// The weights for step h of the chain `m` (its modes per distinct element, padded to
    /// groups of four).
    pub fn new(h: f64, m: &crate::ode::ModalChain) -> Self {
        let kernels: Vec<[Flow; 3]> = m
            .frequencies
            .iter()
            .map(|&(w, rate)| Flow::at_nodes(h, w, rate))
            .collect();
        debug_assert_eq!(
            m.frequency_index.len() % 4,
            0,
            "modes padded to groups of four"
        );
        let groups = m.frequency_index.len() / 4;
        let mut node_groups = vec![NodeGroup::default(); groups];
        let mut end = vec![EndGroup::default(); groups];
        for (mode, &u) in m.frequency_index.iter().enumerate() {
            let (k, b, a) = (&kernels[u], m.inv_modal_mass[mode], m.a_weight[mode]);
            let (w2, r) = (m.frequencies[u].0 * m.frequencies[u].0, m.frequencies[u].1);
            let (g, l) = (mode / 4, mode % 4);
            let node = &mut node_groups[g];
            for ((cos, hsinc), kj) in node.cos.iter_mut().zip(&mut node.hsinc).zip(k) {
                cos[l] = kj.pos_of_pos;
                hsinc[l] = h * kj.pos_of_rate;
            }
            let e = &mut end[g];
            e.cos[l] = k[2].pos_of_pos;
            e.hsinc[l] = h * k[2].pos_of_rate;
            e.vel_of_pos[l] = k[2].rate_of_pos / h;
            e.vel_of_vel[l] = k[2].rate_of_rate;
            // The mode's response to the force: the oscillator's, times T = B + A K (B = 1/μ and
            // A = 0 but under dashpots, `ode::damped_modes`).
            for n in 0..4 {
                e.pos_force[n][l] = h * h * k[2].s[n] * b + a * h * k[2].c[n];
                e.vel_force[n][l] = h * k[2].c[n] * (b - r * a) - a * w2 * h * h * k[2].s[n];
            }
            e.half_modal_mass[l] = 0.5 * m.modal_mass[mode];
            e.omega2[l] = m.omega2[mode];
        }
        let lagrange = lagrange();
        let (mut node_response, mut error, mut rigid) = (Vec::new(), Vec::new(), Vec::new());
        for range in &m.kind_ranges {
            let mut g = [[0.0; 4]; 3];
            let (mut ex, mut ev) = (0.0, 0.0);
            for mode in range.clone() {
                let u = m.frequency_index[mode];
                let k = &kernels[u];
                let (b, a) = (m.inv_modal_mass[mode], m.a_weight[mode]);
                let (w2, r) = (m.frequencies[u].0 * m.frequencies[u].0, m.frequencies[u].1);
                for (row, kj) in g.iter_mut().zip(k) {
                    for (n, x) in row.iter_mut().enumerate() {
                        *x += kj.s[n] * b + kj.c[n] * a / h;
                    }
                }
                let end = &k[2];
                let error_s = (0..4).map(|n| ERROR_POLY[n] * end.s[n]).sum::<f64>();
                let error_c = (0..4).map(|n| ERROR_POLY[n] * end.c[n]).sum::<f64>();
                ex += error_s * b + error_c * a / h;
                ev += error_c * (b - r * a) - error_s * a * w2 * h;
            }
            node_response.push(g.map(|row| {
                [0, 1, 2, 3].map(|k| (0..4).map(|n| row[n] * lagrange[n][k]).sum::<f64>())
            }));
            error.push((ex, ev));
            // The rigid mode (first) under a unit acceleration: gravity's part.
            let k = &kernels[m.frequency_index[range.start]];
            rigid.push(RigidResponse {
                nodes: [0, 1, 2].map(|j| h * h * k[j].s[0]),
                end_velocity: h * k[2].c[0],
            });
        }
        StepWeights {
            nodes: node_groups,
            end,
            rigid,
            node_response,
            error,
        }
    }

    /// Σ over the modes of a distinct element (its `groups` of four; its primary's amplitudes
    /// and rates `c`, `cdot` in the same groups) of cos(σ_j z) c + h sin(σ_j z)/z ċ at the three
    /// nodes j: the primary's free positions there, in one pass.
    #[inline(always)]
    pub fn free_positions(
        &self,
        groups: std::ops::Range<usize>,
        c: &[[f64; 4]],
        cdot: &[[f64; 4]],
    ) -> [f64; 3] {
        let mut acc = [L4::ZERO; 3];
        for (w, (&x, &v)) in self.nodes[groups].iter().zip(c.iter().zip(cdot)) {
            let (x, v) = (Lane(x), Lane(v));
            for ((acc, &cos), &hsinc) in acc.iter_mut().zip(&w.cos).zip(&w.hsinc) {
                *acc = *acc + (Lane(cos) * x + Lane(hsinc) * v);
            }
        }
        // Summed out of sight of the loop (else the vectoriser packs it two lanes per register).
        std::hint::black_box(acc).map(L4::sum)
    }

    /// Advances the modes of one primary (its distinct element's `groups` of four) over the
    /// step under its force polynomial `a` (monomials in σ, \[N\]): (c, ċ) into (c1, ċ1).
    /// Returns, at the end, Σ c, Σ ċ, Σ Ω² c and the modes' energy Σ ½ μ (ċ² + Ω² c²), summed
    /// in the same pass.
    #[inline(always)]
    pub fn advance(
        &self,
        groups: std::ops::Range<usize>,
        a: &[f64; 4],
        (c, cdot): (&[[f64; 4]], &[[f64; 4]]),
        (c1, cdot1): (&mut [[f64; 4]], &mut [[f64; 4]]),
    ) -> [f64; 4] {
        let [a0, a1, a2, a3] = a.map(L4::splat);
        let z = L4::ZERO;
        let (mut sum_x, mut sum_v, mut sum_w2x, mut energy) = (z, z, z, z);
        let from = c.iter().zip(cdot);
        let to = c1.iter_mut().zip(cdot1.iter_mut());
        for (w, ((&x0, &v0), (x1, v1))) in self.end[groups].iter().zip(from.zip(to)) {
            let (x0, v0) = (Lane(x0), Lane(v0));
            let [p0, p1, p2, p3] = w.pos_force.map(Lane);
            let [q0, q1, q2, q3] = w.vel_force.map(Lane);
            let cos = Lane(w.cos);
            let x = cos * x0 + Lane(w.hsinc) * v0 + (p0 * a0 + p1 * a1 + p2 * a2 + p3 * a3);
            let v = Lane(w.vel_of_pos) * x0
                + Lane(w.vel_of_vel) * v0
                + (q0 * a0 + q1 * a1 + q2 * a2 + q3 * a3);
            *x1 = x.0;
            *v1 = v.0;
            let w2x = Lane(w.omega2) * x;
            sum_x = sum_x + x;
            sum_v = sum_v + v;
            sum_w2x = sum_w2x + w2x;
            energy = energy + Lane(w.half_modal_mass) * (v * v + w2x * x);
        }
        // Summed out of sight of the loop, as above.
        std::hint::black_box([sum_x, sum_v, sum_w2x, energy]).map(L4::sum)
    }
}

/// ∫₀^θ a(σ) dp(σ) for the cubics a and p (monomials in σ): the work of a force along a
/// displacement over the fraction θ of a step, both interpolated through the nodes.
pub(crate) fn work_of_cubics(a: &[f64; 4], p: &[f64; 4], theta: f64) -> f64 {
    let mut w = 0.0;
    for (n, an) in a.iter().enumerate() {
        for (k, pk) in p.iter().enumerate().skip(1) {
            let e = (n + k) as i32;
            w += an * k as f64 * pk * theta.powi(e) / f64::from(e);
        }
    }
    w
}

/// Four modes' weights, stored.
type Quad = [f64; 4];

/// Four modes at once in arithmetic.
type L4 = Lane<4>;

/// What the variation-of-constants formula needs of one damped mode c'' + 2a c' + z² c = f(σ)
/// (σ = t/h; a = γh with γ half the mode's damping rate, z = hΩ) at one point θ of a step: the
/// free flow e^{−aθ}(C + aS), e^{−aθ}S, −z² e^{−aθ}S, e^{−aθ}(C − aS), with C(θ) = cos(√D θ),
/// S(θ) = sin(√D θ)/√D, D = z² − a² (cosh and sinh when D < 0, the series through D = 0), and
/// the responses S_n(θ), C_n(θ) (position and its σ-rate) to f = σⁿ from rest, n = 0..3.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DampedKernel {
    /// The position's response to the initial position, e^{−aθ}(C + aS).
    pub pos_of_pos: f64,
    /// The position's response to the initial σ-rate c'(0) = h ċ(0), e^{−aθ} S.
    pub pos_of_rate: f64,
    /// The σ-rate's response to the initial position, −z² e^{−aθ} S.
    pub rate_of_pos: f64,
    /// The σ-rate's response to the initial σ-rate, e^{−aθ}(C − aS).
    pub rate_of_rate: f64,
    /// S_n(θ) = ∫₀^θ G(θ − σ) σⁿ dσ, G the impulse response e^{−aσ} S(σ), n = 0..3.
    pub s: [f64; 4],
    /// C_n(θ) = ∫₀^θ G'(θ − σ) σⁿ dσ, n = 0..3.
    pub c: [f64; 4],
}

impl DampedKernel {
    /// The kernel with the free flow `free` ([`damped_free`]'s order) and no responses yet.
    fn free_flow(free: [f64; 4]) -> Self {
        DampedKernel {
            pos_of_pos: free[0],
            pos_of_rate: free[1],
            rate_of_pos: free[2],
            rate_of_rate: free[3],
            ..DampedKernel::default()
        }
    }
}

/// The free flow of c'' + 2a c' + z² c = 0 over θ: (e^{−aθ}(C + aS), e^{−aθ}S, −z² e^{−aθ}S,
/// e^{−aθ}(C − aS)). Near D = 0 (|D| θ² < 1/4) C and S are their series in D; for D < 0 the
/// exponentials e^{−(a∓κ)θ} (κ = √−D, a − κ = z²/(a + κ) without cancellation) are combined so
/// that neither overflows nor cancels.
fn damped_free(theta: f64, a: f64, z: f64) -> [f64; 4] {
    let d = (z - a) * (z + a);
    let x2 = d.abs() * theta * theta;
    let decay = (-a * theta).libm_exp();
    let (ec, es) = if x2 < 0.25 {
        // C = Σ (−Dθ²)^m/(2m)!, S = θ Σ (−Dθ²)^m/(2m+1)!: 12 terms reach 1e-19 at |Dθ²| = 1/4.
        let y = -d * theta * theta;
        let (mut c, mut s) = (0.0, 0.0);
        let (mut tc, mut ts) = (1.0, 1.0);
        for m in 0..12 {
            c += tc;
            s += ts;
            let k = (2 * m + 1) as f64;
            tc *= y / (k * (k + 1.0));
            ts *= y / ((k + 1.0) * (k + 2.0));
        }
        (decay * c, decay * theta * s)
    } else if d > 0.0 {
        let w = d.sqrt();
        let (s, c) = (w * theta).libm_sin_cos();
        (decay * c, decay * s / w)
    } else {
        let kappa = (-d).sqrt();
        let slow = (-z * z / (a + kappa) * theta).libm_exp();
        let fast = (-(a + kappa) * theta).libm_exp();
        let pos = 0.5 * (slow * (kappa + a) - fast * z * z / (a + kappa)) / kappa;
        let rate = 0.5 * (fast * (kappa + a) - slow * z * z / (a + kappa)) / kappa;
        let es = 0.5 * (slow - fast) / kappa;
        return [pos, es, -z * z * es, rate];
    };
    [ec + a * es, es, -z * z * es, ec - a * es]
}

/// [`DampedKernel`] at θ ∈ [0, 1] for a = γh ≥ 0, z = hΩ ≥ 0 (θ = 0: the identity). The
/// responses S_n, C_n of a lightly damped mode (a ≤ z/2): from the φ-functions of its complex
/// root (as the undamped [`kernel`]'s from those of iz). Otherwise, where the
/// roots of λ² + 2aλ + z² are small on [0, θ] (r θ ≤ 1, r the larger root's modulus), the Taylor
/// series of the response (its coefficients by the equation's recurrence); where the mode is
/// stiff (z²θ² ≥ 16 and z²θ ≥ 8a), the polynomial particular solution p (p'' + 2ap' + z²p = σⁿ,
/// by back-substitution: coefficients in powers of 1/z², no cancellation) less the free flow of
/// its initial values; otherwise the kernels at θ/2 composed with themselves (the second half's
/// force σⁿ re-expanded about θ/2), recursively down to the series.
pub fn damped_kernel(theta: f64, a: f64, z: f64) -> DampedKernel {
    if theta == 0.0 {
        return DampedKernel {
            pos_of_pos: 1.0,
            rate_of_rate: 1.0,
            ..DampedKernel::default()
        };
    }
    if a <= LIGHT_DAMPING * z {
        return light_kernel(theta, a, z);
    }
    let free = damped_free(theta, a, z);
    let mut k = DampedKernel::free_flow(free);
    let d = (z - a) * (z + a);
    let r = if d >= 0.0 { z } else { a + (-d).sqrt() };
    if r * theta <= 1.0 {
        for n in 0..4 {
            (k.s[n], k.c[n]) = damped_series(theta, a, z, n);
        }
    } else if z * z * theta * theta >= 16.0 && z * z * theta >= 8.0 * a {
        for n in 0..4 {
            let p = particular(a, z, n);
            let (mut y, mut dy) = (0.0, 0.0);
            for i in (0..=n).rev() {
                y = y * theta + p[i];
                if i > 0 {
                    dy = dy * theta + i as f64 * p[i];
                }
            }
            k.s[n] = y - (free[0] * p[0] + free[1] * p[1]);
            k.c[n] = dy - (free[2] * p[0] + free[3] * p[1]);
        }
    } else {
        let half = damped_kernel(0.5 * theta, a, z);
        let tau = 0.5 * theta;
        for (n, binomial) in BINOMIAL.iter().enumerate() {
            // σⁿ on the second half, σ = τ + s: Σ_j C(n, j) τ^{n−j} s^j.
            let (mut y, mut dy) = (0.0, 0.0);
            for (j, b) in binomial.iter().enumerate().take(n + 1) {
                let w = b * tau.powi((n - j) as i32);
                y += w * half.s[j];
                dy += w * half.c[j];
            }
            k.s[n] = half.pos_of_pos * half.s[n] + half.pos_of_rate * half.c[n] + y;
            k.c[n] = half.rate_of_pos * half.s[n] + half.rate_of_rate * half.c[n] + dy;
        }
    }
    k
}

/// Modes with a ≤ this × z (ζ ≤ 1/2: every structural damping) take their responses from the
/// φ-functions of the complex root ([`light_kernel`]); heavier ones (and rigid modes under
/// on-site damping) by series, particular solutions and halving.
const LIGHT_DAMPING: f64 = 0.5;

/// Terms of φ_4's series summed below |x| = 2: the first left out, 2²⁴/28!, is below 1e-22 of
/// φ_4 ≥ 1/24 · e^{−2}.
const PHI4_COMPLEX_TERMS: usize = 24;

/// Terms of φ_4(x)'s series for |x|² = `r2` < 4: the first left out, |x|^m/(m + 4)!, is below
/// 1e-17 of φ_4 ≥ e^{−|x|}/24 (m = 9 below |x| = 0.1: 1.6e-19; 13 below 0.5: 3.4e-19; 17
/// below 1: 2.0e-20; 24 below 2: 5.5e-23).
fn phi4_terms(r2: f64) -> usize {
    if r2 < 0.01 {
        9
    } else if r2 < 0.25 {
        13
    } else if r2 < 1.0 {
        17
    } else {
        PHI4_COMPLEX_TERMS
    }
}

/// 1/(m + 4)!, m < [`PHI4_COMPLEX_TERMS`].
const PHI4_COEFFICIENTS: [f64; PHI4_COMPLEX_TERMS] = {
    let mut c = [0.0; PHI4_COMPLEX_TERMS];
    let mut inv_fact = 1.0 / 24.0;
    let mut m = 0;
    while m < PHI4_COMPLEX_TERMS {
        c[m] = inv_fact;
        inv_fact /= (m + 5) as f64;
        m += 1;
    }
    c
};

/// [`DampedKernel`] of a lightly damped mode (a ≤ z/2). The responses S_n(θ), C_n(θ),
/// n = 0..3, through the φ-functions of x = λθ, λ = −a + iw the root of λ² + 2aλ + z²
/// (w = √(z² − a²) ≥ 0.86 z): the impulse response is G(σ) = Im e^{λσ}/w, and
/// ∫₀^θ e^{λ(θ−σ)} σⁿ dσ = n! θ^{n+1} φ_{n+1}(x), so S_n = n! θ^{n+1} Im φ_{n+1}/w and
/// C_n = n! θ^{n+1} (Re φ_{n+1} − (a/w) Im φ_{n+1}). As the undamped [`kernel`]: φ_4 by its
/// series below |x| = 2 and downward φ_k = 1/k! + x φ_{k+1}; above, φ_0 = e^x and upward
/// φ_{k+1} = (φ_k − 1/k!)/x, which divides each rounding by |x| ≥ 2. There the free flow comes
/// from φ_0 = e^{−aθ}(cos wθ + i sin wθ), as [`damped_free`] computes it (the same products:
/// bit for bit); below, from [`damped_free`].
fn light_kernel(theta: f64, a: f64, z: f64) -> DampedKernel {
    use rustfft::num_complex::Complex64;
    const INV_FACT: [f64; 4] = [1.0, 1.0, 0.5, 1.0 / 6.0];
    let w = ((z - a) * (z + a)).sqrt();
    let x = Complex64::new(-a * theta, w * theta);
    let mut phi = [Complex64::new(0.0, 0.0); 5];
    let r2 = x.norm_sqr();
    let free = if r2 < 4.0 {
        phi[4] = PHI4_COEFFICIENTS[..phi4_terms(r2)]
            .iter()
            .rev()
            .fold(Complex64::new(0.0, 0.0), |acc, &c| acc * x + c);
        for k in (0..4).rev() {
            phi[k] = x * phi[k + 1] + INV_FACT[k];
        }
        damped_free(theta, a, z)
    } else {
        let (sin, cos) = (w * theta).libm_sin_cos();
        let decay = (-a * theta).libm_exp();
        phi[0] = Complex64::new(decay * cos, decay * sin);
        for k in 0..4 {
            phi[k + 1] = (phi[k] - INV_FACT[k]) / x;
        }
        let (ec, es) = (phi[0].re, phi[0].im / w);
        [ec + a * es, es, -z * z * es, ec - a * es]
    };
    let mut k = DampedKernel::free_flow(free);
    let (s, c) = (&mut k.s, &mut k.c);
    let mut scale = theta; // n! θ^{n+1}
    for n in 0..4 {
        if n > 0 {
            scale *= n as f64 * theta;
        }
        let p = phi[n + 1];
        s[n] = scale * p.im / w;
        c[n] = scale * (p.re - a / w * p.im);
    }
    k
}

const BINOMIAL: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [1.0, 1.0, 0.0, 0.0],
    [1.0, 2.0, 1.0, 0.0],
    [1.0, 3.0, 3.0, 1.0],
];

/// The response y(θ), y'(θ) to σⁿ from rest by its Taylor series: with e_k = d_k θ^k,
/// (k + 2)(k + 1) e_{k+2} = [k = n] θ^{n+2} − 2aθ (k + 1) e_{k+1} − z²θ² e_k; for rθ ≤ 1 the
/// terms fall faster than 1/k!, summed until two in a row are below 1e-18 of the sum.
fn damped_series(theta: f64, a: f64, z: f64, n: usize) -> (f64, f64) {
    let (at, zt2) = (a * theta, z * z * theta * theta);
    let (mut e0, mut e1) = (0.0_f64, 0.0_f64);
    let (mut y, mut dy) = (0.0, 0.0);
    for k in 0..60 {
        let src = if k == n {
            theta.powi(n as i32 + 2)
        } else {
            0.0
        };
        let kf = k as f64;
        let e2 = (src - 2.0 * at * (kf + 1.0) * e1 - zt2 * e0) / ((kf + 2.0) * (kf + 1.0));
        y += e2;
        dy += (kf + 2.0) * e2;
        if k > n + 2 && e2.abs() <= 1e-18 * y.abs() && e1.abs() <= 1e-18 * y.abs() {
            break;
        }
        e0 = e1;
        e1 = e2;
    }
    (y, dy / theta)
}

/// The polynomial p = Σ p_k σ^k of degree n with p'' + 2a p' + z² p = σⁿ (z > 0): from the top,
/// z² p_k = [k = n] − 2a (k + 1) p_{k+1} − (k + 2)(k + 1) p_{k+2}.
fn particular(a: f64, z: f64, n: usize) -> [f64; 4] {
    let mut p = [0.0; 6];
    let z2 = z * z;
    for k in (0..=n).rev() {
        let kf = k as f64;
        let src = if k == n { 1.0 } else { 0.0 };
        p[k] = (src - 2.0 * a * (kf + 1.0) * p[k + 1] - (kf + 2.0) * (kf + 1.0) * p[k + 2]) / z2;
    }
    [p[0], p[1], p[2], p[3]]
}
