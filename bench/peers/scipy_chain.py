#!/usr/bin/env python3
"""The benchmark problem written independently as a plain SciPy `solve_ivp` script.

The docs/physics.md §9 chain (20 fused-quartz rods, resonant Table 1 cells) hit by the default striker
(10 mm soda-lime glass sphere, v0 = sqrt(2 g 0.20 m)) on the default sensor (stainless-steel cap,
R = 5 mm), 2 ms. Contact coefficients are computed here with SciPy's elliptic integrals (which
take the parameter m = e^2) and brentq, independently of the Rust code.

Prints, for each tolerance, the median wall time of several runs, the RHS evaluations, the
transmitted peak and its relative error against the reference passed with --reference.
"""
import argparse
import statistics
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar
from scipy.special import ellipe, ellipk

CHAIN_MM = [50, 80, 80, 80, 60, 70, 80, 80, 40, 30, 40, 40, 40, 30, 50, 40, 20, 20, 30, 50]
# Table 1: M [g], [(m_j [g], k_j [kN/mm])]
TABLE1 = {
    20: (0.423, [(0.443, 26.27)]),
    30: (0.570, [(0.729, 8.782)]),
    40: (0.838, [(0.894, 3.961)]),
    50: (0.450, [(1.350, 2.008), (0.365, 18.31)]),
    60: (0.600, [(1.600, 1.172), (0.398, 11.31)]),
    70: (0.750, [(1.850, 0.748), (0.431, 7.263)]),
    80: (1.00, [(1.800, 0.532), (0.664, 6.423)]),
}
QUARTZ = (72e9, 0.17)
GLASS = (63e9, 0.22, 2500.0)
STEEL = (200e9, 0.29)


def beta(k1, k2, phi, mat1, mat2):
    """Hertz F = beta delta^1.5 for curvature pairs k1, k2 whose principal planes meet at phi."""
    d1, d2 = k1[0] - k1[1], k2[0] - k2[1]
    s = 0.5 * (sum(k1) + sum(k2))
    diff = 0.5 * np.sqrt(max(d1 * d1 + d2 * d2 + 2 * d1 * d2 * np.cos(2 * phi), 0.0))
    a, b = 0.5 * (s - diff), 0.5 * (s + diff)
    e_star = 1.0 / ((1 - mat1[1] ** 2) / mat1[0] + (1 - mat2[1] ** 2) / mat2[0])
    if b / a - 1 < 1e-12:
        return 4.0 / 3.0 * e_star * np.sqrt(1 / (2 * a))
    g = lambda e2: (ellipe(e2) / (1 - e2) - ellipk(e2)) / (ellipk(e2) - ellipe(e2)) - b / a
    e2 = brentq(g, 1e-12, 1 - 1e-15, xtol=1e-16, rtol=1e-15)
    kk, ee = ellipk(e2), ellipe(e2)
    return 2 * np.pi * e_star / 3 * kk ** -1.5 * np.sqrt((kk - ee) / (e2 * a))


def build():
    r = 2.5e-3
    rod_rod = beta((1 / r, 0), (1 / r, 0), np.pi / 2, QUARTZ, QUARTZ)
    striker_rod = beta((1 / 5e-3, 1 / 5e-3), (1 / r, 0), 0.0, GLASS, QUARTZ)
    rod_wall = beta((1 / r, 0), (1 / 5e-3, 1 / 5e-3), 0.0, QUARTZ, STEEL)
    m_s = GLASS[2] * np.pi * 10e-3 ** 3 / 6
    masses = [m_s] + [TABLE1[l][0] * 1e-3 for l in CHAIN_MM]
    owner, m_res, k_res = [], [], []
    for i, l in enumerate(CHAIN_MM):
        for mj, kj in TABLE1[l][1]:
            owner.append(i + 1)
            m_res.append(mj * 1e-3)
            k_res.append(kj * 1e6)
    betas = np.array([striker_rod] + [rod_rod] * (len(CHAIN_MM) - 1) + [rod_wall])
    return np.array(masses), np.array(owner), np.array(m_res), np.array(k_res), betas


M, OWNER, MR, KR, BETAS = build()
P, R = len(M), len(MR)
N = P + R
V0 = np.sqrt(2 * 9.81 * 0.20)


def contact_forces(x):
    d = np.empty(P)
    d[:-1] = x[:P - 1] - x[1:P]
    d[-1] = x[P - 1]
    d = np.maximum(d, 0.0)
    return BETAS * d * np.sqrt(d)


def rhs(t, y):
    x, v = y[:N], y[N:]
    f = contact_forces(x)
    acc = np.empty(N)
    above = np.concatenate(([0.0], f[:-1]))
    acc[:P] = (above - f) / M
    s = KR * (x[P:] - x[OWNER])
    acc[P:] = -s / MR
    np.add.at(acc, OWNER, s / M[OWNER])
    return np.concatenate((v, acc))


def run(rtol, atol, method):
    y0 = np.zeros(2 * N)
    y0[N] = V0
    start = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, 2e-3), y0, method=method, rtol=rtol, atol=atol, dense_output=True)
    # Transmitted peak: wall force on a 0.1 µs grid from the dense output, then refined.
    t = np.linspace(0.0, 2e-3, 20001)
    xs = sol.sol(t)[P - 1]
    wall = lambda tt: -BETAS[-1] * max(float(sol.sol(tt)[P - 1]), 0.0) ** 1.5
    k = int(np.argmax(xs))
    lo, hi = t[max(k - 1, 0)], t[min(k + 1, len(t) - 1)]
    peak = -minimize_scalar(wall, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12}).fun
    elapsed = time.perf_counter() - start
    return elapsed, sol.nfev, peak


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--reference", type=float, required=True, help="converged transmitted peak [N]")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--method", default="DOP853")
    args = ap.parse_args()
    print(f"{'method':<24} {'median_ms':>10} {'rhs_evals':>10} {'transm_err':>12}")
    for rtol in [1e-5, 1e-6, 1e-7, 1e-8, 1e-9]:
        times, nfev, peak = [], 0, 0.0
        for _ in range(args.runs):
            el, nfev, peak = run(rtol, rtol * 1e-6, args.method)
            times.append(el)
        err = abs(peak / args.reference - 1)
        print(f"{args.method + ' rtol=' + format(rtol, '.0e'):<24} {statistics.median(times) * 1e3:>10.1f} {nfev:>10} {err:>12.2e}", flush=True)


if __name__ == "__main__":
    main()
