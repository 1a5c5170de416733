"""A lattice from Python: examples/lattice.toml run, each support's peak and the contacts that
carry the most force, and the run directory `woodpile simulate` would write.

    python examples/lattice_python.py --out runs/lattice-py

Needs numpy and pandas (`pip install .`).
"""

import argparse
from pathlib import Path

import woodpile


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", type=Path, default=Path("runs/lattice-py"))
    args = parser.parse_args()
    scenario = woodpile.Scenario.load(Path(__file__).with_name("lattice.toml"))
    run = woodpile.simulate(scenario)
    print(run)
    for s, peak in enumerate(run.support_forces_n.max(axis=0), start=1):
        print(f"support {s}: sampled peak {peak:.3f} N")
    table = run.contacts.assign(peak_n=run.contact_peak_forces_n)
    print(table.sort_values("peak_n", ascending=False).head(5).to_string())
    print("written:", run.save(args.out, overwrite=True))


if __name__ == "__main__":
    main()
