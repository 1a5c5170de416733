"""Throughput of the Python package against the command line, on the paper's impact problem.

1. The same 1,000 designs (generation 0 of the paper-impact GA, seed 1: 20 Table 1 rods, 2 ms of
   RK4 at 0.1 µs) evaluated by `woodpile optimize` (population 1000, no further generation) and
   from Python by `BreederGA.evaluate` and by `woodpile.evaluate` of their scenarios, each on all
   cores; the ratio Python / CLI, median of --repeats runs.
2. 2,000 designs on a Dask LocalCluster of 1 and of 2 worker processes (one thread each),
   shipped in chunks by `woodpile.optimize`'s evaluation path; the speed-up 1 → 2 workers.

Usage: python bench/python_throughput.py [--woodpile target/release/woodpile] [--repeats 3]
Needs the package installed (pip install ".[test]") and a release build of the CLI.
"""

import argparse
import json
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import woodpile
from woodpile.optimize import _evaluate_designs
from woodpile.study import _chunks


def cli_seconds(binary: str, population: int) -> float:
    with tempfile.TemporaryDirectory() as d:
        cfg = Path(d) / "p.toml"
        cfg.write_text(f"[ga]\npopulation = {population}\ngenerations = 0\nseed = 1\n")
        cfg.write_text(cfg.read_text().replace("[ga]", "[design]\npositions = 20\n[ga]"))
        started = time.perf_counter()
        subprocess.run([binary, "optimize", str(cfg), "--out", str(Path(d) / "o"), "-q"], check=True)
        return time.perf_counter() - started


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--woodpile", default="target/release/woodpile")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--designs", type=int, default=1000)
    ap.add_argument("--dask-designs", type=int, default=2000)
    args = ap.parse_args()

    problem = {"design": {"positions": 20}, "ga": {"population": args.designs, "generations": 0, "seed": 1}}
    ga = woodpile.BreederGA(problem)
    designs = ga.ask()
    scenarios = [ga_scenario for ga_scenario in (woodpile.Scenario(ga._session.scenario_toml(d)) for d in designs)]
    rows = {"cli": [], "BreederGA.evaluate": [], "woodpile.evaluate": []}
    for _ in range(args.repeats):
        rows["cli"].append(cli_seconds(args.woodpile, args.designs))
        t = time.perf_counter()
        ga.evaluate(designs)
        rows["BreederGA.evaluate"].append(time.perf_counter() - t)
        t = time.perf_counter()
        table = woodpile.evaluate(scenarios)
        rows["woodpile.evaluate"].append(time.perf_counter() - t)
        assert table["error"].isna().all()
    cli = statistics.median(rows["cli"])
    print(f"{args.designs} designs of the paper's impact problem, median of {args.repeats} runs [s]:")
    for name, times in rows.items():
        m = statistics.median(times)
        print(f"  {name:20s} {m:7.2f}  ({m / cli:.3f} x the CLI)   runs: {', '.join(f'{x:.2f}' for x in times)}")

    from dask.distributed import Client, LocalCluster

    big = woodpile.BreederGA({"design": {"positions": 20}, "ga": {"population": args.dask_designs, "generations": 0, "seed": 2}})
    many = big.ask()
    config, base = big.config_json, "."
    seconds = {}
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            with Client(cluster) as client:
                # Warm the workers (import, problem build) outside the timing.
                client.submit(_evaluate_designs, config, base, many[:2], 1).result()
                t = time.perf_counter()
                parts = _chunks(many, workers * 2)
                futures = [client.submit(_evaluate_designs, config, base, p, 1, pure=False) for p in parts]
                values = [v for f in futures for v in f.result()]
                seconds[workers] = time.perf_counter() - t
                assert len(values) == len(many)
    print(f"{args.dask_designs} designs on a Dask LocalCluster (processes, 1 thread each) [s]: "
          f"1 worker {seconds[1]:.2f}, 2 workers {seconds[2]:.2f}, speed-up {seconds[1] / seconds[2]:.2f}x")
    print(json.dumps({"cli_s": rows["cli"], "ga_evaluate_s": rows["BreederGA.evaluate"],
                      "evaluate_s": rows["woodpile.evaluate"], "dask_s": seconds}))


if __name__ == "__main__":
    main()
