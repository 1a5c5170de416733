#!/usr/bin/env python3
"""Driver of the LAMMPS peer (lammps_chain.in) of the woodpile benchmark problem.

Same problem as scipy_chain.py (masses, contact coefficients beta, resonators and v0 are imported from
there): the striker and the 20 rods are granular atoms on the z axis (diameter 4r, so every pair has
R_eff = r = 2.5 mm, the crossed-cylinder radius), the wall (sensor cap) is a fixed granular atom below
the last rod, and each internal resonator is a point atom bonded to its rod by a harmonic bond. For each
contact kind pair_style granular's "hertz" model gives F = k_N sqrt(R_eff) delta^{3/2}; we pass
k_N = beta / sqrt(R_eff) (R_eff computed as LAMMPS does, r_i r_j / (r_i + r_j)), no damping, no
tangential force, no gravity. bond_style harmonic has E = K (r - r0)^2, so K = k/2. Velocity Verlet
(fix nve) with a fixed timestep over 2 ms; the transmitted peak is the maximum over all step ends of the
force on the wall atom (no interpolation between steps).

For each timestep this script writes the data file, runs `taskset -c 1 lmp -in lammps_chain.in` (one
MPI rank, OMP_NUM_THREADS=1) --runs times and prints
    lammps verlet dt=<dt> <median_ms> <steps> <transm_err>
where median_ms is the median of LAMMPS's own "Loop time" (the MD loop only: it excludes start-up,
reading the data file, neighbour-list setup and output); the median wall time of the whole lmp process
(start-up included, nothing subtracted) is printed after it for reference.

Usage: bench/.venv/bin/python bench/peers/lammps_chain.py --reference 41.54922178 --runs 3 \
           --dt 1e-9 2e-9 5e-9 1e-8 2e-8 5e-8
       add --validate to also dump the wall force at every step (at the largest dt) and check that
       the running maximum taken inside LAMMPS equals the maximum of that trace.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from scipy_chain import V0, build  # noqa: E402  (the physics setup lives there)

T_END = 2e-3
ROD_R = 2.5e-3  # rod radius r
DIAM = 4 * ROD_R  # granular diameter of the striker, rod and wall atoms: R_eff = r for every pair
RES_OFFSET = 1e-3  # resonator rest distance above its rod (bond r0)


def lmp_exe():
    for name in ("lmp", "lmp_serial", "lmp_stable"):
        path = shutil.which(name)
        if path:
            return path
    sys.exit("no LAMMPS executable (lmp, lmp_serial, lmp_stable) on PATH: apt-get install lammps")


def write_data(path):
    """Data file for atom_style hybrid sphere bond; returns the k_N values keyed by contact kind."""
    m, owner, m_res, k_res, betas = build()
    m, m_res, k_res = [float(a) for a in m], [float(a) for a in m_res], [float(a) for a in k_res]
    p, r = len(m), len(m_res)
    wall_id = p + 1
    vol = np.pi / 6 * DIAM ** 3
    lines = ["woodpile chain (bench/peers/lammps_chain.py)", "",
             f"{p + 1 + r} atoms", f"{r} bonds", "4 atom types", f"{r} bond types", "",
             "-0.02 0.02 xlo xhi", "-0.02 0.02 ylo yhi", f"{-3 * DIAM!r} {(p + 5) * DIAM!r} zlo zhi", "",
             "Masses", "",  # per-type masses are required by atom_style hybrid but unused (rmass wins)
             "1 1.0", "2 1.0", "3 1.0", "4 1.0", "",
             "Bond Coeffs", ""]
    for j in range(r):
        lines.append(f"{j + 1} {k_res[j] / 2!r} {RES_OFFSET!r}")  # E = K (r - r0)^2, K = k/2
    lines += ["", "Atoms # hybrid", ""]
    # id type x y z diameter density molecule; primary i (0 = striker) at z = (p-1-i) D: last rod at 0
    z = [(p - 1 - i) * DIAM for i in range(p)]
    for i in range(p):
        lines.append(f"{i + 1} {1 if i == 0 else 2} 0.0 0.0 {z[i]!r} {DIAM!r} {m[i] / vol!r} 0")
    lines.append(f"{wall_id} 3 0.0 0.0 {-DIAM!r} {DIAM!r} {m[-1] / vol!r} 0")  # mass irrelevant: fixed
    for j in range(r):
        # point particle (diameter 0): the density column is the mass
        lines.append(f"{wall_id + 1 + j} 4 0.0 0.0 {z[owner[j]] + RES_OFFSET!r} 0.0 {m_res[j]!r} 0")
    lines += ["", "Bonds", ""]
    for j in range(r):
        lines.append(f"{j + 1} {j + 1} {owner[j] + 1} {wall_id + 1 + j}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    rad = DIAM / 2
    reff = rad * rad / (rad + rad)  # as PairGranular::compute
    # betas: [striker-rod, rod-rod x19, rod-wall]
    return {"kn_sr": betas[0] / np.sqrt(reff), "kn_rr": betas[1] / np.sqrt(reff),
            "kn_rw": betas[-1] / np.sqrt(reff)}


def run_lammps(exe, workdir, data, kn, dt, trace=False):
    steps = int(round(T_END / dt))
    var = {"datafile": data, "dt": repr(dt), "nsteps": str(steps), "vz": repr(-float(V0)),
           "trace": "1" if trace else "0", **{k: repr(float(v)) for k, v in kn.items()}}
    cmd = ["taskset", "-c", "1", exe, "-nocite", "-log", "none", "-in", os.path.join(HERE, "lammps_chain.in")]
    for k, v in var.items():
        cmd += ["-var", k, v]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    start = time.perf_counter()
    out = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if out.returncode != 0:
        sys.exit(f"lmp failed ({out.returncode}):\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}")
    loop = re.search(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps", out.stdout)
    peak = re.search(r"^PEAK (\S+)", out.stdout, re.M)
    if not loop or not peak:
        sys.exit(f"could not parse lmp output:\n{out.stdout[-3000:]}")
    return float(loop.group(1)), wall, int(loop.group(2)), float(peak.group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", type=float, required=True, help="converged transmitted peak [N]")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--dt", type=float, nargs="+", default=[1e-9, 2e-9, 5e-9, 1e-8, 2e-8, 5e-8])
    ap.add_argument("--validate", action="store_true")
    args = ap.parse_args()
    exe = lmp_exe()
    head = subprocess.run([exe, "-h"], capture_output=True, text=True).stdout
    version = re.search(r"Large-scale Atomic/Molecular Massively Parallel Simulator - (.*)", head)
    print(f"LAMMPS {version.group(1).strip() if version else '?'} ({exe}); pair_style granular hertz, "
          f"bond_style harmonic, fix nve (velocity Verlet); 1 MPI rank, OMP_NUM_THREADS=1, taskset -c 1")
    with tempfile.TemporaryDirectory() as work:
        data = os.path.join(work, "chain.data")
        kn = write_data(data)
        if args.validate:
            dt = max(args.dt)
            _, _, _, peak = run_lammps(exe, work, data, kn, dt, trace=True)
            tr = np.loadtxt(os.path.join(work, "trace.txt"))
            fmax = -tr[:, 1].min()
            print(f"validate dt={dt:.3g}: running max in LAMMPS {peak:.12f} N, max of the per-step trace "
                  f"{fmax:.12f} N, trace rows {len(tr)}, peak at t = {tr[np.argmin(tr[:, 1]), 0] * dt * 1e6:.3f} us")
        print(f"{'method':<26} {'median_ms':>10} {'steps':>10} {'transm_err':>12} {'process_ms':>11}")
        for dt in args.dt:
            loops, walls = [], []
            for _ in range(args.runs):
                loop, wall, steps, peak = run_lammps(exe, work, data, kn, dt)
                loops.append(loop)
                walls.append(wall)
            err = abs(peak / args.reference - 1)
            name = f"lammps verlet dt={dt:.3g}"
            print(f"{name:<26} {statistics.median(loops) * 1e3:>10.1f} {steps:>10} {err:>12.2e} "
                  f"{statistics.median(walls) * 1e3:>11.1f}   # peak {peak:.8f} N", flush=True)


if __name__ == "__main__":
    main()
