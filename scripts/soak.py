#!/usr/bin/env python3
"""A soak of the simulator: many random valid scenarios, each run by `woodpile simulate`.

Draws scenarios (a fixed seed: the same draws every time) over chains and lattices, every
excitation (impact, blast, force and displacement drives), every contact law, resonator and
on-site damping, preload and gravity, every wall, Table 1, beam-theory and finite-element cells and
spheres, fixed and adaptive steps. Each run must end in one of three ways: exit 0 with a
summary.json whose figures are finite, the wave's ratio null only when no wave arrived and the
energy balance within the accuracy rule (`energy_balance_ok`, or the warning saying it is not); exit
2 with a refusal naming a key (a drawn combination the model refuses, e.g. a drive above the
step's Nyquist frequency); or exit 1 for an inaccurate run, with its message. A panic (exit 101),
a signal, a hang (over --timeout s) or a nonsense figure is a failure. Prints the tally, the
worst energy balance of the runs that passed and every failure's scenario.

Usage: python3 scripts/soak.py --woodpile target/release/woodpile [--runs 10000] [--jobs 2]
"""

from __future__ import annotations

import argparse
import concurrent.futures
import json
import math
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TABLE1 = [20, 30, 40, 50, 60, 70, 80]
MATERIALS = ["fused-quartz", "soda-lime-glass", "stainless-steel", "borosilicate-glass"]
LAWS = ["none", "restitution", "hunt-crossley", "viscoelastic"]


def chain_elements(r: random.Random) -> list[str]:
    n = r.randint(1, 12)
    if r.random() < 0.5:
        return [f"rods_mm = [{', '.join(str(r.choice(TABLE1)) for _ in range(n))}]"]
    items = []
    for _ in range(n):
        kind = r.random()
        if kind < 0.3:
            items.append(f"{{ rod_mm = {r.choice(TABLE1)} }}")
        elif kind < 0.6:
            items.append(
                f'{{ kind = "rod", length_mm = {r.uniform(15, 100):.2f}, diameter_mm = {r.uniform(3, 8):.2f}, '
                f'material = "{r.choice(MATERIALS)}" }}'
            )
        elif kind < 0.8:
            items.append(
                f'{{ kind = "rod", length_mm = {r.uniform(20, 90):.2f}, diameter_mm = 5.0, '
                f'material = "fused-quartz", cell = {{ fe_elements = {r.randint(1, 6)} }} }}'
            )
        else:
            items.append(
                f'{{ kind = "sphere", diameter_mm = {r.uniform(4, 15):.2f}, material = "{r.choice(MATERIALS)}" }}'
            )
    return ["elements = [", *[f"  {i}," for i in items], "]"]


def lattice(r: random.Random) -> tuple[list[str], tuple[int, float]]:
    layers = r.randint(2, 4)
    rods = r.randint(1, 3)
    length = r.uniform(40, 80)
    pitch = r.uniform(7, length / max(rods, 1))
    first = (
        f'  {{ rods = {rods}, pitch_mm = {pitch:.2f}, length_mm = {length:.2f}, diameter_mm = 5.0, '
        f'material = "fused-quartz" }},'
    )
    lines = ["[lattice]", "layers = [", first, *[f"  {{ rods = {rods} }}," for _ in range(layers - 1)], "]"]
    lines.append(f"rod = {{ fe_elements = {r.randint(1, 4)} }}")
    return lines, (rods, float(f"{pitch:.2f}"))


def excitation(r: random.Random, lattice_rods: tuple[int, float] | None) -> tuple[list[str], str]:
    kind = r.choice(["impact", "impact", "blast", "drive"])
    lines = ["[excitation]", f'kind = "{kind}"']
    if kind == "impact":
        lines.append(f"velocity_m_s = {r.uniform(0.05, 5.0):.3f}")
        if lattice_rods:
            rods, pitch = lattice_rods
            # The top layer's rods lie along x, side by side in y.
            y = (r.randrange(rods) - (rods - 1) / 2) * pitch + r.uniform(-1, 1)
            lines.append(f"at_mm = [{r.uniform(-5, 5):.2f}, {y:.2f}]")
    elif kind == "blast":
        lines += [f"peak_force_n = {r.uniform(1, 400):.2f}", f"duration_s = {r.uniform(1e-5, 4e-4):.3e}"]
        lines.append(f"decay = {r.uniform(0, 3):.2f}")
    else:
        drive = r.choice(["force", "displacement"])
        amplitude = r.uniform(0.01, 5.0) if drive == "force" else r.uniform(1e-8, 1e-6)
        lines += [f'drive = "{drive}"', 'signal = "harmonic"', f"amplitude = {amplitude:.3e}"]
        lines.append(f"frequency_hz = {r.uniform(500, 20000):.1f}")
    return lines, kind


def damping(r: random.Random, is_lattice: bool, struck: bool) -> list[str]:
    law = r.choice(LAWS)
    lines = ["[damping]", f'contact = "{law}"']
    if law in ("restitution", "hunt-crossley"):
        lines.append(f"restitution = {r.uniform(0.3, 0.99):.3f}")
    if law == "hunt-crossley" and not struck:
        lines.append(f"impact_speed_m_s = {r.uniform(0.1, 3):.2f}")
    if law == "viscoelastic":
        lines.append(f"viscous_time_s = {10 ** r.uniform(-8, -6):.3e}")
    if r.random() < 0.4:
        ratio = "modal_ratio" if is_lattice else "resonator_ratio"
        lines.append(f"{ratio} = {r.uniform(0, 0.1):.3f}")
    if r.random() < 0.3:
        lines.append(f"on_site_time_s = {10 ** r.uniform(-4, -2):.3e}")
    return lines


def scenario(r: random.Random) -> str:
    is_lattice = r.random() < 0.35
    if is_lattice:
        lines, rods = lattice(r)
    else:
        lines, rods = ["[chain]", *chain_elements(r)], None
    ex, kind = excitation(r, rods)
    lines += ex
    if not is_lattice and r.random() < 0.3:
        lines += ["[wall]", f'kind = "{r.choice(["cap", "free"])}"']
    if r.random() < 0.5:
        lines += damping(r, is_lattice, kind == "impact")
    if r.random() < 0.3:
        lines += ["[preload]", f"gravity_m_s2 = {r.choice([0.0, 9.81])}"]
        if kind != "drive":
            lines.append(f"force_n = {r.uniform(0, 20):.2f}")
    lines += ["[run]", f"duration_s = {r.uniform(5e-5, 6e-4):.3e}"]
    if r.random() < 0.7:
        lines.append(f"peak_tolerance = {10 ** r.uniform(-6, -3):.2e}")
    else:
        lines += ['integrator = "rk4"', f"time_step_s = {r.choice([5e-8, 1e-7])}"]
    return "\n".join(lines) + "\n"


def check(summary: dict, stderr: str) -> str | None:
    """What is wrong with a finished run's summary (None: nothing)."""
    for key in ("incident_peak_force_n", "transmitted_peak_force_n"):
        value = summary.get(key)
        if not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
            return f"{key} = {value!r}"
    ratio = summary.get("transmission_ratio")
    if ratio is None and summary.get("wave_arrived"):
        return "no transmission_ratio although the wave arrived"
    if ratio is not None and not math.isfinite(ratio):
        return f"transmission_ratio = {ratio!r}"
    if not summary.get("energy_balance_ok") and "energy" not in stderr:
        return "energy balance off without a warning"
    return None


def run_one(args: tuple[str, int, float, str]) -> tuple[int, str, str, float | None]:
    """(seed, outcome, detail, the energy balance's error)."""
    woodpile, seed, timeout, scratch = args
    toml = scenario(random.Random(seed))
    with tempfile.TemporaryDirectory(dir=scratch) as tmp:
        file = Path(tmp) / f"soak{seed}.toml"
        file.write_text(toml)
        try:
            done = subprocess.run(
                [woodpile, "simulate", str(file), "--out", f"{tmp}/out", "--quiet"],
                capture_output=True,
                text=True,
                timeout=timeout,
            )
        except subprocess.TimeoutExpired:
            return seed, "FAIL", f"hang (over {timeout} s)\n{toml}", None
        if done.returncode == 0:
            summary = json.loads((Path(tmp) / "out" / "summary.json").read_text())
            wrong = check(summary, done.stderr)
            if wrong:
                return seed, "FAIL", f"{wrong}\n{toml}", None
            return seed, "ran", "", summary["energy"]["max_relative_error"]
        message = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else ""
        if done.returncode == 2 and message.startswith("error: "):
            return seed, "refused", message, None
        if done.returncode == 1 and message.startswith("error: "):
            return seed, "failed run", message, None
        return seed, "FAIL", f"exit {done.returncode}: {done.stderr[-400:]}\n{toml}", None


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--woodpile", required=True)
    parser.add_argument("--runs", type=int, default=10000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--first-seed", type=int, default=1)
    args = parser.parse_args()
    tally: dict[str, int] = {}
    reasons: dict[str, int] = {}
    failures = []
    worst = (0.0, -1)
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="woodpile-soak-") as scratch:
        jobs = [(args.woodpile, s, args.timeout, scratch) for s in range(args.first_seed, args.first_seed + args.runs)]
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            for seed, outcome, detail, error in pool.map(run_one, jobs):
                tally[outcome] = tally.get(outcome, 0) + 1
                if outcome == "FAIL":
                    failures.append((seed, detail))
                elif outcome in ("refused", "failed run"):
                    # The key refused ("invalid KEY = …"), or the kind of failure ("inaccurate run: …").
                    text = detail.removeprefix("error: ")
                    reason = text.split(" = ")[0] if text.startswith("invalid ") else text.split(":")[0]
                    reasons[reason] = reasons.get(reason, 0) + 1
                if error is not None and error > worst[0]:
                    worst = (error, seed)
    print(f"{args.runs} scenarios (seeds {args.first_seed}..{args.first_seed + args.runs - 1}) in "
          f"{time.monotonic() - started:.0f} s: " + ", ".join(f"{k} {v}" for k, v in sorted(tally.items())))
    print(f"worst energy balance of the runs that ran: {worst[0]:.2e} (seed {worst[1]})")
    for reason, count in sorted(reasons.items(), key=lambda kv: -kv[1])[:12]:
        print(f"  {count:5} x {reason}")
    for seed, detail in failures[:20]:
        print(f"FAIL seed {seed}: {detail}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
