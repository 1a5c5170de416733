"""A lab-physics design study through ``woodpile.evaluate``: DESIGNS random orders of the 20 rods of
the built-in ``paper-impact-optimized`` scenario (peaks only: ``run.sample_interval_s`` equal to
the duration), evaluated without and with ``[damping] contact = "restitution"``,
``restitution = 0.9``, ``resonator_ratio = 0.01`` and ``[preload] force_n = 5``, interleaved, on
every core (SIMD lanes fed by one queue). Prints the medians of RUNS, the ratio lab / lossless,
and checks that a sample of the lab designs' rows equal, bit for bit, ``woodpile.simulate`` of
the same scenario (the run ``woodpile simulate`` makes).

Usage: python bench/lab_lanes.py [--designs 400] [--runs 3]
"""

from __future__ import annotations

import argparse
import random
import statistics
import time

import woodpile


def scenarios(base: woodpile.Scenario, designs: int, lab: bool) -> list[woodpile.Scenario]:
    rods = base.to_dict()["chain"]["rods_mm"]
    rng = random.Random(1)
    out = []
    for _ in range(designs):
        order = rods[:]
        rng.shuffle(order)
        changes: dict[str, object] = {"chain.rods_mm": order}
        if lab:
            changes |= {
                "damping.contact": "restitution",
                "damping.restitution": 0.9,
                "damping.resonator_ratio": 0.01,
                "preload.force_n": 5.0,
            }
        out.append(base.replace(**changes))
    return out


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--designs", type=int, default=400)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    base = woodpile.Scenario.builtin("paper-impact-optimized")
    duration = base.to_dict()["run"]["duration_s"]
    base = base.replace(**{"run.sample_interval_s": duration})
    lossless = scenarios(base, args.designs, lab=False)
    lab = scenarios(base, args.designs, lab=True)
    times: dict[str, list[float]] = {"lossless": [], "lab": []}
    rows = {}
    for _ in range(args.runs):
        for name, batch in (("lossless", lossless), ("lab", lab)):
            start = time.perf_counter()
            rows[name] = woodpile.evaluate(batch)
            times[name].append(time.perf_counter() - start)
            assert rows[name]["error"].isna().all(), rows[name]["error"].dropna().iloc[0]
    a, b = statistics.median(times["lossless"]), statistics.median(times["lab"])
    print(f"{args.designs} designs through woodpile.evaluate, medians of {args.runs}:")
    print(f"  lossless:    {a:.3f} s ({args.designs / a:.0f} designs/s)")
    print(f"  lab physics: {b:.3f} s ({args.designs / b:.0f} designs/s)")
    print(f"  lab / lossless: {b / a:.2f}x")
    columns = ["incident_peak_force_n", "transmitted_peak_force_n", "energy_max_relative_error", "dissipated_j"]
    for i in range(0, args.designs, max(1, args.designs // 10)):
        alone = woodpile.simulate(lab[i]).summary
        row = rows["lab"].iloc[i]
        got = [row[c] for c in columns]
        want = [
            alone["incident_peak_force_n"],
            alone["transmitted_peak_force_n"],
            alone["energy"]["max_relative_error"],
            alone["energy"]["dissipated_j"],
        ]
        assert all(float(g).hex() == float(w).hex() for g, w in zip(got, want)), (i, got, want)
    print("  lab rows equal woodpile.simulate bit for bit (every 10th design): yes")


if __name__ == "__main__":
    main()
