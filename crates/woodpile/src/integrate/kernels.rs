//! The integrator's arithmetic written once over the number type ([`Real`]): the stage loop, the
//! embedded error's weighted terms and their norm, and the prediction of contact crossings. The
//! [`Integrator`](super::Integrator) runs them on `f64`; the lanes of `crate::lanes` on one value
//! per lane, so both compute the same bits.

// Lane loops index several arrays by the lane number l.
#![allow(clippy::needless_range_loop)]

use super::{crossing_inside, crossing_root, LandingRule, Tableau};
use crate::real::{sign_changed, Mask, Real, MAX_LANES};

/// The stages of a step of size h from y (f at y already in k\[0\]) into `k`, and the new state
/// into `stage`: for an explicit Runge–Kutta tableau the stages and (unless FSAL, whose last stage
/// is the new state) the weighted sum; for a Nyström tableau the stage positions, the new
/// velocities and the error estimate (into `error`). `rhs(c_i, state, out)` evaluates f at stage
/// i (time t + c_i h).
#[inline(always)]
pub(crate) fn attempt<R: Real>(
    tableau: &Tableau,
    y: &[R],
    k: &mut [Vec<R>],
    stage: &mut [R],
    error: &mut [R],
    h: R,
    rhs: impl FnMut(f64, &[R], &mut [R]),
) {
    if tableau.nystrom.is_none() {
        explicit_stages(tableau, y, k, stage, h, rhs);
    } else {
        nystrom_stages(tableau, y, k, stage, error, h, rhs);
    }
}

/// [`attempt`] for an explicit Runge–Kutta tableau.
#[inline(always)]
fn explicit_stages<R: Real>(
    tableau: &Tableau,
    y: &[R],
    k: &mut [Vec<R>],
    stage: &mut [R],
    h: R,
    mut rhs: impl FnMut(f64, &[R], &mut [R]),
) {
    for i in 1..tableau.stages() {
        stage_sum(stage, Some(y), &tableau.a[i], k, |w| h * R::splat(w));
        rhs(tableau.c[i], stage, &mut k[i]);
    }
    if !tableau.fsal {
        stage_sum(stage, Some(y), &tableau.b, k, |w| h * R::splat(w));
    }
}

/// [`attempt`] for a Runge–Kutta–Nyström tableau.
#[inline(always)]
fn nystrom_stages<R: Real>(
    tableau: &Tableau,
    y: &[R],
    k: &mut [Vec<R>],
    stage: &mut [R],
    error: &mut [R],
    h: R,
    mut rhs: impl FnMut(f64, &[R], &mut [R]),
) {
    let nd = y.len() / 2;
    for i in 1..tableau.stages() {
        let (a, c) = (&tableau.a[i], tableau.c[i]);
        nystrom_positions(&mut stage[..nd], y, k, a, c, h, R::splat);
        rhs(c, stage, &mut k[i]);
    }
    nystrom_finish(stage, error, y, k, tableau, h, R::splat);
}

/// The embedded error estimate (an explicit tableau's from its stages; a Nyström tableau's is
/// already in `error`), each component replaced by its weighted square
/// (e_c / (atol_c + rtol · max(|y_c|, |y1_c|)))² (Hairer's sc_c).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn weighted_squares<R: Real>(
    tableau: &Tableau,
    error: &mut [R],
    k: &[Vec<R>],
    h: R,
    y: &[R],
    y1: &[R],
    atol: &[R],
    rtol: R,
) {
    let e = tableau
        .error
        .as_ref()
        .expect("adaptive tableau has error weights");
    if tableau.nystrom.is_none() {
        stage_sum(error, None, e, k, |ej| h * R::splat(ej));
    }
    let n = error.len();
    let (y, y1, atol) = (&y[..n], &y1[..n], &atol[..n]);
    for c in 0..n {
        let r = error[c] / (atol[c] + rtol * y[c].abs().max(y1[c].abs()));
        error[c] = r * r;
    }
}

/// The RMS norm sqrt(Σ_i s_i / n) of the weighted squares s_i = `square(items[i])`, summed in
/// one order for every instance: four partial sums by i mod 4 over the first 4⌊n/4⌋, then the
/// rest (so the reduction vectorises; a single running sum is a chain of dependent additions).
/// One run passes its squares themselves, a lane its run's component order (`place`).
#[inline(always)]
pub(crate) fn rms<T: Copy>(items: &[T], square: impl Fn(T) -> f64) -> f64 {
    let n = items.len();
    let head = n - n % 4;
    let mut partial = [0.0; 4];
    for chunk in items[..head].chunks_exact(4) {
        for (s, &item) in partial.iter_mut().zip(chunk) {
            *s += square(item);
        }
    }
    let mut sum: f64 = partial.iter().sum();
    for &item in &items[head..] {
        sum += square(item);
    }
    (sum / n as f64).sqrt()
}

/// Event-aware stepping: in each lane of `want`, the step that lands on the first predicted sign
/// change of one of n switching functions within the next step of size h, if it lies in the
/// rule's landing window. From each function's value g(s), rate d(s) and rate d_prev(s) at the
/// start of the last step of size dt (> 0): the quadratic g + d τ + c τ²
/// ([`crossing_quadratic`]) is followed over (0, h], its first zero ([`crossing_root`]) that the
/// rule counts is the candidate.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn predict_crossings<R: Real>(
    n: usize,
    g: impl Fn(usize) -> R,
    d: impl Fn(usize) -> R,
    d_prev: impl Fn(usize) -> R,
    dt: R,
    h: R,
    want: Mask,
    rule: LandingRule,
) -> [Option<f64>; MAX_LANES] {
    let mut first = [None; MAX_LANES];
    let half = R::splat(0.5);
    for s in 0..n {
        let (gs, ds) = (g(s), d(s));
        let (c, gh) = crossing_quadratic(gs, ds, d_prev(s), dt, h, half);
        if !sign_changed(gs, gh) {
            continue;
        }
        for l in 0..R::LANES {
            if want[l] && (gs.lane(l) > 0.0) != (gh.lane(l) > 0.0) {
                let hl = h.lane(l);
                let tau = crossing_root(gs.lane(l), ds.lane(l), c.lane(l), gh.lane(l), hl);
                if rule.counts(tau, hl) && first[l].is_none_or(|f: f64| tau < f) {
                    first[l] = Some(tau);
                }
            }
        }
    }
    for l in 0..R::LANES {
        first[l] = rule.window(first[l], h.lane(l));
    }
    first
}

/// [`Method::Rkn64`](super::Method::Rkn64)'s check after an attempted step of size h, in each lane
/// of `check`: the first crossing inside the step (one of n switching functions whose sign changed
/// from g0(s) to g1(s), with rates d0(s) and d1(s) at the ends, read only there) that lies in
/// (0.1 h, 0.999 h) ([`crossing_inside`]).
#[inline(always)]
pub(crate) fn missed_crossings<R: Real>(
    n: usize,
    (g0, g1): (impl Fn(usize) -> R, impl Fn(usize) -> R),
    (d0, d1): (impl Fn(usize) -> R, impl Fn(usize) -> R),
    h: R,
    check: Mask,
) -> [Option<f64>; MAX_LANES] {
    let mut first = [None; MAX_LANES];
    for s in 0..n {
        let (a, b) = (g0(s), g1(s));
        if !sign_changed(a, b) {
            continue;
        }
        let (da, db) = (d0(s), d1(s));
        for l in 0..R::LANES {
            let (al, bl) = (a.lane(l), b.lane(l));
            if !check[l] || (al > 0.0) == (bl > 0.0) {
                continue;
            }
            if let Some(tau) = crossing_inside(al, da.lane(l), bl, db.lane(l), h.lane(l)) {
                if first[l].is_none_or(|f: f64| tau < f) {
                    first[l] = Some(tau);
                }
            }
        }
    }
    first
}

/// The curvature c = (g' − g'_prev) / (2 dt) of the extrapolating quadratic and its value
/// g + h (g' + c h) at the end of a step of size h (`half` is 0.5).
#[inline(always)]
pub(crate) fn crossing_quadratic<R: Real>(g: R, d: R, d_prev: R, dt: R, h: R, half: R) -> (R, R) {
    let c = half * (d - d_prev) / dt;
    (c, g + h * (d + c * h))
}

/// out = base + Σ_j hw(w_j) k_j over the non-zero weights w_j (out = Σ_j hw(w_j) k_j when `base`
/// is None: `out` is only written), for f64 states and for SIMD lanes (`crate::lanes`) alike: the
/// stages, the new state and the error estimate. The terms go in groups of up to four per pass
/// over the state (each element's sum in a register), so a DOPRI5 step makes 8 passes instead of
/// 21; the additions run left to right as with one pass per term, so the bits are those of one
/// pass per term (without a base, those of 0 + Σ but for the sign of a zero sum). No allocation.
#[inline(always)]
pub(crate) fn stage_sum<T>(
    out: &mut [T],
    base: Option<&[T]>,
    weights: &[f64],
    k: &[Vec<T>],
    hw: impl Fn(f64) -> T,
) where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<Output = T>,
{
    const MAX_TERMS: usize = 16;
    let zero = hw(0.0);
    let mut factors = [zero; MAX_TERMS];
    let mut ks: [&[T]; MAX_TERMS] = [&[]; MAX_TERMS];
    let mut terms = 0;
    for (&w, kj) in weights.iter().zip(k) {
        if w != 0.0 {
            assert!(
                terms < MAX_TERMS,
                "a tableau has at most {MAX_TERMS} stages"
            );
            factors[terms] = hw(w);
            ks[terms] = kj;
            terms += 1;
        }
    }
    sum_terms(out, base, &factors[..terms], &ks[..terms], zero);
}

/// out = base + Σ_j factors_j ks_j (out = Σ_j factors_j ks_j without a base; `zero` fills `out`
/// when there are no terms and no base): the terms in groups of up to four per pass over the
/// state, added left to right ([`stage_sum`]).
#[inline(always)]
pub(crate) fn sum_terms<T>(out: &mut [T], base: Option<&[T]>, factors: &[T], ks: &[&[T]], zero: T)
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<Output = T>,
{
    let terms = factors.len();
    if terms == 0 {
        match base {
            Some(y) => out.copy_from_slice(y),
            None => out.fill(zero),
        }
        return;
    }
    let mut done = 0;
    while done < terms {
        let group = (terms - done).min(4);
        let (f, ks) = (&factors[done..done + group], &ks[done..done + group]);
        let start = match (done, base) {
            (0, Some(y)) => Start::From(y),
            (0, None) => Start::Nothing,
            _ => Start::Out,
        };
        match group {
            1 => add_terms::<T, 1>(out, start, f, ks),
            2 => add_terms::<T, 2>(out, start, f, ks),
            3 => add_terms::<T, 3>(out, start, f, ks),
            _ => add_terms::<T, 4>(out, start, f, ks),
        }
        done += group;
    }
}

/// The stage positions of a Runge–Kutta–Nyström step, X = x + (c h) v + Σ_j (h² a_j) A_j over the
/// non-zero a_j (A_j: the second halves of k_j), from y = [x | v]; for f64 states and SIMD lanes
/// alike (`splat` makes a coefficient a T), so both add in the same order.
#[inline(always)]
pub(crate) fn nystrom_positions<T>(
    out: &mut [T],
    y: &[T],
    k: &[Vec<T>],
    a_row: &[f64],
    c: f64,
    h: T,
    splat: impl Fn(f64) -> T,
) where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<Output = T>,
{
    const MAX_TERMS: usize = 16;
    let nd = out.len();
    let (x, v) = (&y[..nd], &y[nd..2 * nd]);
    let h2 = h * h;
    let zero = splat(0.0);
    let mut factors = [zero; MAX_TERMS];
    let mut ks: [&[T]; MAX_TERMS] = [&[]; MAX_TERMS];
    factors[0] = splat(c) * h;
    ks[0] = v;
    let mut terms = 1;
    for (&w, kj) in a_row.iter().zip(k) {
        if w != 0.0 {
            factors[terms] = h2 * splat(w);
            ks[terms] = &kj[nd..2 * nd];
            terms += 1;
        }
    }
    sum_terms(out, Some(x), &factors[..terms], &ks[..terms], zero);
}

/// The end of a Runge–Kutta–Nyström step whose stages are in k (the last at the new positions,
/// already in `stage`'s first half): the new velocities v + Σ_j (h b'_j) A_j into `stage`'s
/// second half and into k\[last\]'s first half (so that k\[last\] is f at the new point), and the
/// error estimates Σ_j (h² e_j) A_j of the positions and Σ_j (h e'_j) A_j of the velocities.
#[inline(always)]
pub(crate) fn nystrom_finish<T>(
    stage: &mut [T],
    error: &mut [T],
    y: &[T],
    k: &mut [Vec<T>],
    tableau: &Tableau,
    h: T,
    splat: impl Fn(f64) -> T,
) where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<Output = T>,
{
    let nd = y.len() / 2;
    let weights = tableau.nystrom.as_ref().expect("a Nyström tableau");
    let position_error = tableau.error.as_ref().expect("an embedded estimate");
    let h2 = h * h;
    let (v, v_new) = (&y[nd..2 * nd], &mut stage[nd..2 * nd]);
    acceleration_sum(v_new, Some(v), &weights.b, h, k, &splat);
    let (ex, ev) = error[..2 * nd].split_at_mut(nd);
    acceleration_sum(ex, None, position_error, h2, k, &splat);
    acceleration_sum(ev, None, &weights.error, h, k, &splat);
    let last = k.len() - 1;
    k[last][..nd].copy_from_slice(&stage[nd..2 * nd]);
}

/// out = base + Σ_j (factor w_j) A_j over the non-zero w_j, A_j the second half of k_j (of
/// length 2 · out.len()). A function, not a closure, so that it is inlined into the SIMD build.
#[inline(always)]
fn acceleration_sum<T>(
    out: &mut [T],
    base: Option<&[T]>,
    w: &[f64],
    factor: T,
    k: &[Vec<T>],
    splat: &impl Fn(f64) -> T,
) where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<Output = T>,
{
    const MAX_TERMS: usize = 16;
    let nd = out.len();
    let zero = splat(0.0);
    let mut factors = [zero; MAX_TERMS];
    let mut ks: [&[T]; MAX_TERMS] = [&[]; MAX_TERMS];
    let mut terms = 0;
    for (&wj, kj) in w.iter().zip(k) {
        if wj != 0.0 {
            factors[terms] = factor * splat(wj);
            ks[terms] = &kj[nd..2 * nd];
            terms += 1;
        }
    }
    sum_terms(out, base, &factors[..terms], &ks[..terms], zero);
}

/// What a pass of [`add_terms`] adds its terms to.
#[derive(Clone, Copy)]
enum Start<'a, T> {
    /// A base vector.
    From(&'a [T]),
    /// The output's own values.
    Out,
    /// Nothing: the first term starts the sum.
    Nothing,
}

/// out_i = (base_i, out_i or nothing) + f₀ k₀_i + … + f_{N-1} k_{N-1}_i, left to right.
#[inline(always)]
fn add_terms<T, const N: usize>(out: &mut [T], start: Start<'_, T>, f: &[T], ks: &[&[T]])
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<Output = T>,
{
    let n = out.len();
    let f: [T; N] = std::array::from_fn(|j| f[j]);
    let ks: [&[T]; N] = std::array::from_fn(|j| &ks[j][..n]);
    match start {
        Start::From(y) => {
            let y = &y[..n];
            for i in 0..n {
                let mut acc = y[i];
                for j in 0..N {
                    acc = acc + f[j] * ks[j][i];
                }
                out[i] = acc;
            }
        }
        Start::Out => {
            for i in 0..n {
                let mut acc = out[i];
                for j in 0..N {
                    acc = acc + f[j] * ks[j][i];
                }
                out[i] = acc;
            }
        }
        Start::Nothing => {
            for i in 0..n {
                let mut acc = f[0] * ks[0][i];
                for j in 1..N {
                    acc = acc + f[j] * ks[j][i];
                }
                out[i] = acc;
            }
        }
    }
}
