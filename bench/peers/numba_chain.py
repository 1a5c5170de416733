#!/usr/bin/env python3
"""The benchmark problem as a tuned, compiled fixed-step RK4 peer written with numba.

Models exactly the problem of scipy_chain.py (imported from there, not copied): P = 21 primary masses
(index 0 = the glass striker, 1..20 = the fused-quartz rods, top to bottom) moving along one axis,
displacements x positive downward (towards the wall), plus R internal resonator masses, each tied to
its rod by a linear spring k_j. Contacts are Hertzian and tension-free:
    contact i (0 <= i < P-1) between primaries i and i+1: delta_i = x_i - x_{i+1},
    contact P-1 between the last rod and the fixed wall (sensor cap): delta_{P-1} = x_{P-1},
    F_i = beta_i * max(delta_i, 0)^{3/2}, computed as d*sqrt(d).
At t = 0 everything is at rest and in touch with zero overlap except the striker, v = v0 = sqrt(2 g 0.20 m).
No gravity, no damping (as in scipy_chain.rhs).

Integrator: classical RK4 with fixed step dt over 2 ms, in one @njit(fastmath=False, error_model="numpy")
(IEEE arithmetic, no Python zero-division checks) function that takes
arrays and returns (peak, rhs_evaluations, peak_sampled). State, stages and scratch are preallocated; the
step loop allocates nothing. The figure of merit, the transmitted peak = max_t beta_wall x_{P-1}^{3/2},
is tracked at each step end (peak_sampled) and also refined inside the step where x_{P-1} has a local
maximum by the cubic Hermite interpolant built from (x, v) at both step ends (peak; x and v are both in
the state, so this costs nothing extra in RHS evaluations).

Usage: bench/.venv/bin/python bench/peers/numba_chain.py --reference 41.54922178 --runs 7 \
           --dt 0.1e-6 0.25e-6 0.5e-6
Prints `numba rk4 dt=<dt> <median_ms> <rhs_evals> <transm_err> <sampled_err>`: transm_err uses the
Hermite-refined peak, sampled_err the plain step-end maximum. The first call (JIT compile) is excluded.
"""
import argparse
import os
import statistics
import sys
import time

import numba
import numpy as np
from numba import njit

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scipy_chain import V0, build  # noqa: E402  (the physics setup lives there)

T_END = 2e-3


@njit(fastmath=False, error_model="numpy", cache=False)
def _hermite_max(x0, x1, v0, v1, h):
    """Maximum of the cubic Hermite interpolant of (x0, v0) -> (x1, v1) on [0, h] (interior or ends)."""
    best = max(x0, x1)
    # p(s) = x0 + v0 s + c2 s^2 + c3 s^3
    dxh = x1 - x0
    c2 = (3.0 * dxh / h - 2.0 * v0 - v1) / h
    c3 = (v0 + v1 - 2.0 * dxh / h) / (h * h)
    # p'(s) = v0 + 2 c2 s + 3 c3 s^2 = 0
    a, b, c = 3.0 * c3, 2.0 * c2, v0
    if a == 0.0:
        if b != 0.0:
            s = -c / b
            if 0.0 < s < h:
                best = max(best, x0 + s * (v0 + s * (c2 + s * c3)))
        return best
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return best
    sq = np.sqrt(disc)
    # numerically stable roots
    q = -0.5 * (b + sq) if b >= 0.0 else -0.5 * (b - sq)
    for s in (q / a, c / q if q != 0.0 else -1.0):
        if 0.0 < s < h:
            best = max(best, x0 + s * (v0 + s * (c2 + s * c3)))
    return best


@njit(fastmath=False, error_model="numpy", cache=False)
def integrate(m, betas, owner, m_res, k_res, v0, dt, t_end):
    """RK4 with fixed step dt; returns (peak_hermite, rhs_evaluations, peak_sampled)."""
    p = m.shape[0]
    n = p + m_res.shape[0]
    inv_m = 1.0 / m  # multiply by reciprocal masses in the loop (<= 1 ulp from dividing)
    inv_mr = 1.0 / m_res
    x = np.zeros(n)
    v = np.zeros(n)
    v[0] = v0
    xt = np.empty(n)  # stage state
    vt = np.empty(n)
    f = np.empty(p)  # contact forces
    kx = np.empty((4, n))  # stage derivatives: dx/dt = v, dv/dt = acceleration
    kv = np.empty((4, n))
    steps = int(round(t_end / dt))
    h = dt
    half = 0.5 * h
    sixth = h / 6.0
    w = p - 1  # the primary touching the wall
    nr = n - p
    xmax_s = 0.0  # largest step-end x_w
    xmax_h = 0.0  # largest x_w including the Hermite refinement inside steps
    for _ in range(steps):
        for st in range(4):
            # stage state: y + c * k_{st-1}, c = 0, h/2, h/2, h
            if st == 0:
                for i in range(n):
                    xt[i] = x[i]
                    vt[i] = v[i]
            else:
                c = h if st == 3 else half
                for i in range(n):
                    xt[i] = x[i] + c * kx[st - 1, i]
                    vt[i] = v[i] + c * kv[st - 1, i]
            # the right-hand side (same equations as scipy_chain.rhs), written inline: a separate
            # @njit function taking arrays cost NRT refcounting per call (~3x slower)
            for i in range(n):
                kx[st, i] = vt[i]
            # tension-free Hertz, branch-free so that the loop vectorises: d = max(delta, 0)
            for i in range(p - 1):
                d = max(xt[i] - xt[i + 1], 0.0)
                f[i] = betas[i] * d * np.sqrt(d)
            d = max(xt[w], 0.0)
            f[w] = betas[w] * d * np.sqrt(d)
            kv[st, 0] = -f[0] * inv_m[0]
            for i in range(1, p):
                kv[st, i] = (f[i - 1] - f[i]) * inv_m[i]
            for j in range(nr):
                o = owner[j]
                sp = k_res[j] * (xt[p + j] - xt[o])
                kv[st, p + j] = -sp * inv_mr[j]
                kv[st, o] += sp * inv_m[o]
        xw0 = x[w]
        vw0 = v[w]
        for i in range(n):
            x[i] += sixth * (kx[0, i] + 2.0 * (kx[1, i] + kx[2, i]) + kx[3, i])
            v[i] += sixth * (kv[0, i] + 2.0 * (kv[1, i] + kv[2, i]) + kv[3, i])
        xw1 = x[w]
        if xw1 > xmax_s:
            xmax_s = xw1
        # a local maximum of x_w inside this step: refine with the cubic Hermite interpolant
        if vw0 > 0.0 and v[w] <= 0.0:
            xh = _hermite_max(xw0, xw1, vw0, v[w], h)
            if xh > xmax_h:
                xmax_h = xh
        if xw1 > xmax_h:
            xmax_h = xw1
    bw = betas[p - 1]
    return bw * xmax_h * np.sqrt(xmax_h), 4 * steps, bw * xmax_s * np.sqrt(xmax_s)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", type=float, required=True, help="converged transmitted peak [N]")
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--dt", type=float, nargs="+", default=[0.1e-6, 0.25e-6, 0.5e-6])
    args = ap.parse_args()
    m, owner, m_res, k_res, betas = build()
    owner = owner.astype(np.int64)
    print(f"numba {numba.__version__}, numpy {np.__version__}; RK4 fixed step, fastmath=False, "
          f"one thread; compile excluded from timing")
    integrate(m, betas, owner, m_res, k_res, V0, 1e-5, 1e-4)  # warm-up: JIT compile
    print(f"{'method':<26} {'median_ms':>10} {'rhs_evals':>10} {'transm_err':>12} {'sampled_err':>12}")
    for dt in args.dt:
        times = []
        for _ in range(args.runs):
            start = time.perf_counter()
            peak, nfev, peak_s = integrate(m, betas, owner, m_res, k_res, V0, dt, T_END)
            times.append(time.perf_counter() - start)
        err = abs(peak / args.reference - 1)
        err_s = abs(peak_s / args.reference - 1)
        name = f"numba rk4 dt={dt:.3g}"
        print(f"{name:<26} {statistics.median(times) * 1e3:>10.3f} {nfev:>10} {err:>12.2e} {err_s:>12.2e}"
              f"   # peak {peak:.8f} N", flush=True)


if __name__ == "__main__":
    main()
