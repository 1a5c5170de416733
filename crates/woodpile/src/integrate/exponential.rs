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

/// [`Kernel`] at θ ∈ (0, 1] for z = hΩ ≥ 0. With x = θz and φ_k(ix) = Σ_m (ix)^m/(m + k)!,
/// ∫₀^θ e^{iz(θ−σ)} σⁿ dσ = n! θ^{n+1} φ_{n+1}(ix): C_n its real part, S_n its imaginary part
/// over z. Series below |x| = 2, the recurrence φ_{k+1} = (φ_k − 1/k!)/(ix) from φ_0 = e^{ix}
/// above (where it loses no digits).
pub fn kernel(theta: f64, z: f64) -> Kernel {
    let x = theta * z;
    // re[k] = Re φ_k(ix), imx[k] = Im φ_k(ix)/x, k = 0..=4.
    let (mut re, mut imx) = ([0.0; 5], [0.0; 5]);
    if x < 2.0 {
        // φ_4 by its series (terms x^m/(m + 4)!, below 1e-17 of the sum after at most 22 terms
        // at x = 2), then downward: φ_k = 1/k! + ix φ_{k+1}, which adds no rounding for x < 2.
        let (mut r, mut i) = (0.0, 0.0);
        let (mut pw, mut f) = (1.0, 1.0 / 24.0);
        let x2 = x * x;
        for m in 0..30 {
            let term = pw * f;
            match m % 4 {
                0 => r += term,
                1 => i += term,
                2 => r -= term,
                _ => i -= term,
            }
            if term < 1e-18 * f64::abs(r).max(1e-300) && m % 2 == 1 {
                break;
            }
            if m % 2 == 1 {
                pw *= x2;
            }
            f /= (m + 5) as f64;
        }
        re[4] = r;
        imx[4] = i;
        const INV_FACT: [f64; 4] = [1.0, 1.0, 0.5, 1.0 / 6.0];
        for k in (0..4).rev() {
            re[k] = INV_FACT[k] - x2 * imx[k + 1];
            imx[k] = re[k + 1];
        }
    } else {
        let (s, c) = x.sin_cos();
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

/// The weights of one step size h for a chain, per mode of each distinct element (equal cells
/// share theirs; contiguous, so that the passes over the modes are plain vector loops): the free
/// motion at the nodes, the end-of-step update, and per distinct element its primary's response
/// to the force polynomial summed over its modes.
#[derive(Debug, Clone)]
pub(crate) struct StepWeights {
    /// Per node σ = c₁, c₂, 1 and mode: cos(σz) and h sin(σz)/z.
    pub cos: [Vec<f64>; 3],
    pub hsinc: [Vec<f64>; 3],
    /// Per mode: −(z/h) sin z, the velocity's part of the position.
    pub vel_of_pos: Vec<f64>,
    /// Per n = 0..3 and mode: h² S_n(1, z)/μ and h C_n(1, z)/μ, the end state's response to σⁿ.
    pub pos_force: [Vec<f64>; 4],
    pub vel_force: [Vec<f64>; 4],
    /// Per distinct element: Σ_k S_n(c_j, z_k)/μ_k, node j = 1..3 (rows), n = 0..3.
    pub response: Vec<[[f64; 4]; 3]>,
    /// Per distinct element: the position and velocity error weights, Σ_k W(z_k)/μ_k with W the kernels
    /// against σ(σ − ½)(σ − 1) (the cubic's part its quadratic through 0, ½, 1 lacks).
    pub error: Vec<(f64, f64)>,
}

/// σ³ − (3/2)σ² + (1/2)σ in monomials: the error polynomial of [`StepWeights::error`].
pub(crate) const ERROR_POLY: [f64; 4] = [0.0, 0.5, -1.5, 1.0];

impl StepWeights {
    /// The weights for step h of a chain with distinct frequencies `frequencies`, per mode its
    /// frequency index and 1/μ, per distinct element its range of modes.
    pub fn new(
        h: f64,
        frequencies: &[f64],
        frequency_index: &[usize],
        inv_modal_mass: &[f64],
        ranges: &[std::ops::Range<usize>],
    ) -> Self {
        let c = nodes();
        let kernels: Vec<[Kernel; 3]> = frequencies
            .iter()
            .map(|&w| {
                let z = h * w;
                [kernel(c[1], z), kernel(c[2], z), kernel(1.0, z)]
            })
            .collect();
        let per_mode = |f: &dyn Fn(&[Kernel; 3], f64) -> f64| -> Vec<f64> {
            frequency_index
                .iter()
                .zip(inv_modal_mass)
                .map(|(&u, &inv_mu)| f(&kernels[u], inv_mu))
                .collect()
        };
        let cos = [0, 1, 2].map(|j| per_mode(&|k, _| k[j].cos));
        let hsinc = [0, 1, 2].map(|j| per_mode(&|k, _| h * k[j].sinc));
        let vel_of_pos = per_mode(&|k, _| -k[2].zsin / h);
        let pos_force = [0, 1, 2, 3].map(|n| per_mode(&|k, inv_mu| h * h * k[2].s[n] * inv_mu));
        let vel_force = [0, 1, 2, 3].map(|n| per_mode(&|k, inv_mu| h * k[2].c[n] * inv_mu));
        let mut response = Vec::with_capacity(ranges.len());
        let mut error = Vec::with_capacity(ranges.len());
        for range in ranges {
            let mut g = [[0.0; 4]; 3];
            let (mut ex, mut ev) = (0.0, 0.0);
            for m in range.clone() {
                let k = &kernels[frequency_index[m]];
                let inv_mu = inv_modal_mass[m];
                for (row, kj) in g.iter_mut().zip(k) {
                    for (r, s) in row.iter_mut().zip(&kj.s) {
                        *r += s * inv_mu;
                    }
                }
                let end = &k[2];
                ex += (0..4).map(|n| ERROR_POLY[n] * end.s[n]).sum::<f64>() * inv_mu;
                ev += (0..4).map(|n| ERROR_POLY[n] * end.c[n]).sum::<f64>() * inv_mu;
            }
            response.push(g);
            error.push((ex, ev));
        }
        StepWeights {
            cos,
            hsinc,
            vel_of_pos,
            pos_force,
            vel_force,
            response,
            error,
        }
    }

    /// Σ over the modes of a distinct element (`range`, its primary's amplitudes and rates
    /// `c`, `cdot`) of cos(σ_j z) c + h sin(σ_j z)/z ċ: the primary's free position at node j
    /// (four partial sums, so that the loop runs in vectors).
    pub fn free_position(
        &self,
        j: usize,
        range: std::ops::Range<usize>,
        c: &[f64],
        cdot: &[f64],
    ) -> f64 {
        let (cos, hsinc) = (&self.cos[j][range.clone()], &self.hsinc[j][range]);
        let mut acc = [0.0; 4];
        let mut chunks = cos
            .chunks_exact(4)
            .zip(hsinc.chunks_exact(4))
            .zip(c.chunks_exact(4).zip(cdot.chunks_exact(4)));
        for ((a, b), (x, v)) in chunks.by_ref() {
            for l in 0..4 {
                acc[l] += a[l] * x[l] + b[l] * v[l];
            }
        }
        let done = cos.len() / 4 * 4;
        let tail: f64 = (done..cos.len())
            .map(|m| cos[m] * c[m] + hsinc[m] * cdot[m])
            .sum();
        (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
    }

    /// Advances the modes of one primary (its distinct element's `range`; μ_k and Ω_k² of
    /// those modes in `modes`) over the step under its force polynomial `a` (monomials in σ,
    /// \[N\]): (c, ċ) into (c1, ċ1). Returns, at the end, Σ c, Σ ċ, Σ Ω² c and the modes'
    /// energy Σ ½ μ (ċ² + Ω² c²), summed in the same pass.
    pub fn advance(
        &self,
        range: std::ops::Range<usize>,
        a: &[f64; 4],
        modes: (&[f64], &[f64]),
        (c, cdot): (&[f64], &[f64]),
        (c1, cdot1): (&mut [f64], &mut [f64]),
    ) -> [f64; 4] {
        let r = range;
        let (cos, hsinc, vp) = (
            &self.cos[2][r.clone()],
            &self.hsinc[2][r.clone()],
            &self.vel_of_pos[r.clone()],
        );
        let [p0, p1, p2, p3] = [0, 1, 2, 3].map(|n| &self.pos_force[n][r.clone()]);
        let [v0, v1, v2, v3] = [0, 1, 2, 3].map(|n| &self.vel_force[n][r.clone()]);
        let (mu, w2) = modes;
        let mut sums = [0.0; 4];
        for m in 0..c.len() {
            let x = cos[m] * c[m]
                + hsinc[m] * cdot[m]
                + (p0[m] * a[0] + p1[m] * a[1] + p2[m] * a[2] + p3[m] * a[3]);
            let v = vp[m] * c[m]
                + cos[m] * cdot[m]
                + (v0[m] * a[0] + v1[m] * a[1] + v2[m] * a[2] + v3[m] * a[3]);
            c1[m] = x;
            cdot1[m] = v;
            sums[0] += x;
            sums[1] += v;
            sums[2] += w2[m] * x;
            sums[3] += 0.5 * mu[m] * (v * v + w2[m] * x * x);
        }
        sums
    }
}

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

/// The free flow of c'' + 2a c' + z² c = 0 over θ: (e^{−aθ}(C + aS), e^{−aθ}S, −z² e^{−aθ}S,
/// e^{−aθ}(C − aS)). Near D = 0 (|D| θ² < 1/4) C and S are their series in D; for D < 0 the
/// exponentials e^{−(a∓κ)θ} (κ = √−D, a − κ = z²/(a + κ) without cancellation) are combined so
/// that neither overflows nor cancels.
fn damped_free(theta: f64, a: f64, z: f64) -> [f64; 4] {
    let d = (z - a) * (z + a);
    let x2 = d.abs() * theta * theta;
    let decay = (-a * theta).exp();
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
        let (s, c) = (w * theta).sin_cos();
        (decay * c, decay * s / w)
    } else {
        let kappa = (-d).sqrt();
        let slow = (-z * z / (a + kappa) * theta).exp();
        let fast = (-(a + kappa) * theta).exp();
        let pos = 0.5 * (slow * (kappa + a) - fast * z * z / (a + kappa)) / kappa;
        let rate = 0.5 * (fast * (kappa + a) - slow * z * z / (a + kappa)) / kappa;
        let es = 0.5 * (slow - fast) / kappa;
        return [pos, es, -z * z * es, rate];
    };
    [ec + a * es, es, -z * z * es, ec - a * es]
}

/// [`DampedKernel`] at θ ∈ [0, 1] for a = γh ≥ 0, z = hΩ ≥ 0 (θ = 0: the identity). The responses S_n, C_n: where the
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
    let free = damped_free(theta, a, z);
    let mut k = DampedKernel {
        pos_of_pos: free[0],
        pos_of_rate: free[1],
        rate_of_pos: free[2],
        rate_of_rate: free[3],
        ..DampedKernel::default()
    };
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
