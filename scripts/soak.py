#!/usr/bin/env python3
"""Runs many random scenarios — chains (Table 1 rods and beam-theory rods, resonant and rigid;
impact, blast and force drive; every contact damping law, resonator damping, gravity) and small
lattices (impact and blast) — and checks each run: no panic, no exception but woodpile's own
(a random combination the scenario refuses counts as refused, with its key), and for every run
that completes, figures that are finite and not negative and an energy balance within the
accuracy rule (1e-2). Prints the counts, the worst energy error and its scenario. Exit status:
the number of failures (0: all passed).

    python3 scripts/soak.py [--chains 10000] [--lattices 200] [--seed 1]

Needs the package installed in the interpreter that runs it.
"""

from __future__ import annotations

import argparse
import math
import random
import sys
import time
from typing import Any

import woodpile
from woodpile.errors import WoodpileError

TABLE1_MM = [20, 30, 40, 50, 60, 70, 80]


def chain_scenario(rng: random.Random) -> dict[str, Any]:
    n = rng.randint(1, 12)
    if rng.random() < 0.6:
        chain: dict[str, Any] = {
            "rods_mm": [rng.choice(TABLE1_MM) for _ in range(n)],
            "model": rng.choice(["resonant", "rigid"]),
        }
    else:
        chain = {"elements": [{"kind": "rod", "length_mm": round(rng.uniform(15.0, 100.0), 3)} for _ in range(n)]}
    kind = rng.choice(["impact", "blast", "drive"])
    if kind == "impact":
        excitation: dict[str, Any] = {"kind": "impact", "velocity_m_s": round(rng.uniform(0.2, 3.0), 4)}
    elif kind == "blast":
        excitation = {
            "kind": "blast",
            "profile": "friedlander",
            "peak_force_n": round(rng.uniform(5.0, 500.0), 3),
            "duration_s": rng.uniform(2e-5, 2e-4),
            "decay": round(rng.uniform(0.0, 3.0), 3),
        }
    else:
        excitation = {
            "kind": "drive",
            "drive": "force",
            "signal": "harmonic",
            "amplitude": round(rng.uniform(0.01, 1.0), 4),
            "frequency_hz": round(rng.uniform(500.0, 20000.0), 1),
        }
    s: dict[str, Any] = {"chain": chain, "excitation": excitation, "run": {"duration_s": rng.uniform(1e-4, 4e-4)}}
    if kind == "drive" or rng.random() < 0.2:
        s["preload"] = {"force_n": round(rng.uniform(1.0, 20.0), 3)}
    if rng.random() < 0.2:
        s.setdefault("preload", {})["gravity_m_s2"] = 9.81
    law = rng.choice(["none", "none", "restitution", "hunt-crossley", "viscoelastic"])
    if law != "none":
        damping: dict[str, Any] = {"contact": law}
        if law in ("restitution", "hunt-crossley"):
            damping["restitution"] = round(rng.uniform(0.5, 0.99), 3)
        else:
            damping["viscous_time_s"] = rng.uniform(1e-7, 1e-5)
        if law == "hunt-crossley" and kind != "impact":
            damping["impact_speed_m_s"] = round(rng.uniform(0.2, 3.0), 4)  # no striker to take it from
        if rng.random() < 0.5:
            damping["resonator_ratio"] = round(rng.uniform(0.0, 0.1), 4)
        s["damping"] = damping
    return s


def on_rod(rng: random.Random, rods: int, pitch: float) -> float:
    """A y on one of the top layer's rods (along x, centred on y = 0), within 2 mm of its axis."""
    return (rng.randrange(rods) - (rods - 1) / 2) * pitch + rng.uniform(-2.0, 2.0)


def lattice_text(rng: random.Random) -> str:
    layers = rng.randint(2, 4)
    rods = rng.randint(2, 3)
    pitch = round(rng.uniform(12.0, 22.0), 2)
    length = round(rng.uniform(50.0, 90.0), 2)
    excitation = (
        '[excitation]\nkind = "blast"\npeak_force_n = %.3f\nduration_s = %.3e\n' % (rng.uniform(5, 200), rng.uniform(2e-5, 1e-4))
        if rng.random() < 0.4
        else "[excitation]\nvelocity_m_s = %.4f\nat_mm = [%.3f, %.3f]\n"
        % (rng.uniform(0.3, 2.5), rng.uniform(-length / 3, length / 3), on_rod(rng, rods, pitch))
    )
    rows = ",\n".join(
        [f'  {{ rods = {rods}, pitch_mm = {pitch}, length_mm = {length}, diameter_mm = 5.0, material = "fused-quartz" }}']
        + ["  { rods = %d }" % rods] * (layers - 1)
    )
    return f"[lattice]\nlayers = [\n{rows},\n]\nrod = {{ fe_elements = 2 }}\n{excitation}[run]\nduration_s = {rng.uniform(1e-4, 3e-4):.3e}\n"


def check_figures(fig: dict[str, Any]) -> str | None:
    """Why a completed run's figures are not sane, or None."""
    for key in ("incident_peak_force_n", "transmitted_peak_force_n"):
        v = fig.get(key)
        if v is None or not math.isfinite(v) or v < 0:
            return f"{key} = {v}"
    err = fig.get("energy_max_relative_error")
    if err is None or not math.isfinite(err) or err > 1e-2:
        return f"energy_max_relative_error = {err}"
    # None (a NaN in the table) where the wave did not reach the wall: no ratio, rightly.
    ratio = fig.get("transmission_ratio")
    if ratio is not None and not math.isnan(ratio) and not (math.isfinite(ratio) and ratio >= 0):
        return f"transmission_ratio = {ratio}"
    return None


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chains", type=int, default=10000)
    parser.add_argument("--lattices", type=int, default=200)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    failures: list[str] = []
    refused: dict[str, int] = {}
    worst = (-1.0, "")
    started = time.monotonic()
    scenarios, dicts = [], []
    for _ in range(args.chains):
        d = chain_scenario(rng)
        try:
            scenarios.append(woodpile.Scenario.from_dict(d))
            dicts.append(d)
        except WoodpileError as e:
            refused[str(getattr(e, "field", None))] = refused.get(str(getattr(e, "field", None)), 0) + 1
    table = woodpile.evaluate(scenarios) if scenarios else None
    ran = 0
    if table is not None:
        for d, row in zip(dicts, table.to_dict("records")):
            if row["error"] is not None:
                if "panicked" in row["error"]:
                    failures.append(f"chain panic: {row['error']} :: {d}")
                else:
                    key = row["error"].split(" = ")[0].replace("invalid ", "")[:60]
                    refused[key] = refused.get(key, 0) + 1
                continue
            ran += 1
            why = check_figures(row)
            if why:
                failures.append(f"chain: {why} :: {d}")
            if row["energy_max_relative_error"] > worst[0]:
                worst = (row["energy_max_relative_error"], repr(d))
    for _ in range(args.lattices):
        text = lattice_text(rng)
        try:
            run = woodpile.simulate(woodpile.Scenario.from_toml(text))
        except WoodpileError as e:
            key = str(getattr(e, "field", None))
            refused[key] = refused.get(key, 0) + 1
            continue
        except Exception as e:  # noqa: BLE001 - anything else is a failure to report
            failures.append(f"lattice: {type(e).__name__}: {e} :: {text!r}")
            continue
        ran += 1
        s = run.summary
        fig = {
            "incident_peak_force_n": s.get("incident_peak_force_n", 0.0),
            "transmitted_peak_force_n": s["transmitted_peak_force_n"],
            "energy_max_relative_error": s["energy"]["max_relative_error"],
        }
        why = check_figures(fig)
        if why:
            failures.append(f"lattice: {why} :: {text!r}")
        if fig["energy_max_relative_error"] > worst[0]:
            worst = (fig["energy_max_relative_error"], text)
    total = args.chains + args.lattices
    print(f"{total} scenarios in {time.monotonic() - started:.0f} s: {ran} ran, "
          f"{sum(refused.values())} refused, {len(failures)} failed")
    for key, n in sorted(refused.items(), key=lambda kv: -kv[1])[:10]:
        print(f"  refused {n:6d} × {key}")
    print(f"worst energy error {worst[0]:.3e}: {worst[1][:400]}")
    for f in failures[:20]:
        print("FAILED", f[:500])
    return len(failures)


if __name__ == "__main__":
    sys.exit(main())
