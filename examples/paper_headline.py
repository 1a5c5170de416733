"""The paper's headline from Python: the optimised chain under the impact, its force map, a sweep
of the striker's speed, and a small GA on a two-worker Dask LocalCluster.

    python examples/paper_headline.py --out headline      # writes force_map.png and prints numbers

Needs `pip install ".[test]"` (numpy, pandas, matplotlib, dask.distributed).
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import woodpile  # noqa: E402
from woodpile import plot  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="headline")
    out = Path(ap.parse_args().out)
    out.mkdir(parents=True, exist_ok=True)

    # 1. The paper's blast-optimised chain under its impact.
    run = woodpile.simulate("paper-impact-optimized")
    s = run.summary
    print(f"optimised chain: incident {s['incident_peak_force_n']:.2f} N, transmitted "
          f"{s['transmitted_peak_force_n']:.2f} N, ratio {s['transmission_ratio']:.3f}")
    fig, ax = plt.subplots(figsize=(7, 3.5), constrained_layout=True)
    plot.force_map(run, ax)
    fig.savefig(out / "force_map.png", dpi=150)

    # 2. The striker's speed, swept.
    speeds = [0.5, 1.0, 1.98, 3.0]
    table = woodpile.sweep(run.scenario, {"excitation.velocity_m_s": speeds})
    print(table[["excitation.velocity_m_s", "incident_peak_force_n", "transmitted_peak_force_n", "transmission_ratio"]].to_string(index=False))

    # 3. A small GA over eight Table 1 positions on a two-worker Dask cluster.
    from dask.distributed import Client, LocalCluster

    problem = {"design": {"positions": 8}, "ga": {"population": 20, "generations": 5, "seed": 1}}
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, Client(cluster) as client:
        result = woodpile.optimize(problem, algorithm="breeder", executor=client)
    print(f"GA (8 positions, 20 × 5 generations on 2 Dask workers): best {result.best['objective']:.2f} N "
          f"with {' '.join(result.best['labels'])}; {int(result.history['evaluations'].iloc[-1])} simulations")
    fig, ax = plt.subplots(figsize=(7, 3.5), constrained_layout=True)
    plot.convergence(result, ax)
    fig.savefig(out / "convergence.png", dpi=150)


if __name__ == "__main__":
    main()
