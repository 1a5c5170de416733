"""Claims of the Pareto studies in Python: ``woodpile.optimize`` with several objectives runs the
command line's NSGA-II (same front, history and reference point for a seed), and
``woodpile.pymoo.Problem`` lets pymoo's own NSGA-II run on woodpile with objective values equal
to woodpile's simulation of the same designs; a reference point below the front (a hypervolume of 0
that measures nothing) warns.

Problems are kept small (5 positions × 4 rods, 0.4 ms of the impact) so the suite takes seconds.
"""

import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import woodpile
from woodpile.errors import ScenarioError

MO_TOML = """[design]
positions = 5
catalogue_mm = [20, 40, 60, 80]
[run]
duration_s = 4e-4
peak_tolerance = 1e-4
[ga]
objectives = ["transmitted-force", "total-mass"]
population = 12
generations = 4
"""

MO = {
    "design": {"positions": 5, "catalogue_mm": [20, 40, 60, 80]},
    "run": {"duration_s": 4e-4, "peak_tolerance": 1e-4},
    "ga": {"objectives": ["transmitted-force", "total-mass"], "population": 12, "generations": 4},
}

REPO = Path(__file__).resolve().parents[2]


def _cli():
    """The `woodpile` binary: $WOODPILE_BIN, else the one `cargo test` / `cargo build` left in
    target/ (CI runs `cargo test --workspace` before pytest)."""
    candidates = [os.environ.get("WOODPILE_BIN")]
    candidates += [str(REPO / "target" / p / "woodpile") for p in ("debug", "release")]
    candidates += [shutil.which("woodpile")]
    for c in candidates:
        if c and Path(c).is_file():
            return c
    pytest.skip("no woodpile binary: run `cargo build -p woodpile-cli` (CI builds it before pytest)")


def test_optimize_with_two_objectives_gives_the_command_lines_front(tmp_path):
    """For a seed, woodpile.optimize(config, seed=3) and `woodpile optimize config --seed 3`
    give the same pareto.csv (every value, exactly), the same history except wall time, the same
    reference point and the same designs as scenarios."""
    config = tmp_path / "mo.toml"
    config.write_text(MO_TOML)
    out = tmp_path / "o"
    done = subprocess.run(
        [_cli(), "optimize", str(config), "--out", str(out), "--seed", "3", "--quiet"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    result = woodpile.optimize(config, seed=3)
    assert isinstance(result, woodpile.ParetoResult)
    cli_front = pd.read_csv(out / "pareto.csv")
    assert list(result.front.columns) == list(cli_front.columns)
    pd.testing.assert_frame_equal(result.front, cli_front, check_exact=True)
    cli_history = pd.read_csv(out / "history.csv").set_index("generation")
    pd.testing.assert_frame_equal(
        result.history.drop(columns=["elapsed_s"]), cli_history.drop(columns=["elapsed_s"]), check_exact=True
    )
    summary = json.loads((out / "summary.json").read_text())
    assert result.reference_point == summary["reference_point"]
    assert result.hypervolume == summary["hypervolume"]
    assert result.objectives == ["transmitted-force", "total-mass"] and result.units == ["N", "kg"]
    assert result.designs == [d["genome"] for d in summary["front"]]
    for k, scenario in enumerate(result.scenarios):
        cli = woodpile.Scenario.load(out / "pareto" / f"{k + 1:03d}.toml")
        assert scenario.to_dict()["chain"] == cli.to_dict()["chain"]


def test_objectives_keyword_turns_a_breeder_problem_into_a_pareto_study(tmp_path):
    """objectives=[...] overrides the problem's objective (dict or built-in alike), and a
    checkpoint of a finished study resumes to the same front without simulating again."""
    breeder = {**MO, "ga": {"population": 12, "generations": 2, "objective": "transmitted-force"}}
    plain = woodpile.optimize(breeder)
    assert isinstance(plain, woodpile.OptimizeResult)
    cp = tmp_path / "nsga2.json"
    first = woodpile.optimize(breeder, objectives=["transmitted-force", "total-mass"], checkpoint=cp)
    assert isinstance(first, woodpile.ParetoResult) and cp.is_file()
    again = woodpile.optimize(breeder, objectives=["transmitted-force", "total-mass"], checkpoint=cp)
    pd.testing.assert_frame_equal(first.front, again.front, check_exact=True)
    assert again.history["evaluations"].iloc[-1] == first.history["evaluations"].iloc[-1]
    # Every front row is non-dominated: no other row is at least as good in both and different.
    values = first.front[["transmitted-force", "total-mass"]].to_numpy()
    for a in values:
        assert not any(np.all(b <= a) and np.any(b < a) for b in values)


def test_bad_pareto_keywords_raise_scenario_error_naming_the_keyword():
    """An unknown objective given by keyword names `objectives[k]`; an unknown algorithm names
    `algorithm`; an executor for NSGA-II names `executor`; BreederGA refuses a Pareto study
    naming `ga.algorithm` — all before any simulation."""
    cases = [
        (dict(objectives=["transmitted-force", "weight"]), "objectives[1]", "weight"),
        (dict(algorithm="genetic"), "algorithm", "genetic"),
        (dict(objectives="total-mass"), "objectives", "'total-mass'"),
    ]
    for kwargs, field, value in cases:
        with pytest.raises(ScenarioError) as info:
            woodpile.optimize(MO, **kwargs)
        assert info.value.field == field and info.value.value == value, (kwargs, info.value)
    import concurrent.futures

    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        with pytest.raises(ScenarioError) as info:
            woodpile.optimize(MO, executor=pool)
    assert info.value.field == "executor"
    with pytest.raises(ScenarioError) as info:
        woodpile.BreederGA(MO)
    assert info.value.field == "ga.algorithm"


def test_pymoo_nsga2_runs_on_woodpile_and_its_values_are_woodpiles():
    """pymoo's NSGA2 (integer operators) runs on woodpile.pymoo.Problem; for every design of its
    final population, F's transmitted force equals woodpile.simulate of the design's scenario and
    F's mass the sum of the rods' Table 1 cell masses (woodpile.cells), both to 1e-12 relative;
    G is the mass constraint's relative excess."""
    pytest.importorskip("pymoo")
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.operators.crossover.sbx import SBX
    from pymoo.operators.mutation.pm import PM
    from pymoo.operators.repair.rounding import RoundingRepair
    from pymoo.operators.sampling.rnd import IntegerRandomSampling
    from pymoo.optimize import minimize

    import woodpile.pymoo

    config = {**MO, "design": {**MO["design"], "constraints": {"max_total_mass_g": 10.0}}}
    problem = woodpile.pymoo.Problem(config)
    assert problem.n_var == 5 and problem.n_obj == 2
    assert problem.constraint_names == ["design.constraints.max_total_mass_g"]
    algorithm = NSGA2(
        pop_size=8,
        sampling=IntegerRandomSampling(),
        crossover=SBX(prob=0.9, eta=15, vtype=float, repair=RoundingRepair()),
        mutation=PM(eta=20, vtype=float, repair=RoundingRepair()),
        eliminate_duplicates=True,
    )
    res = minimize(problem, algorithm, ("n_gen", 3), seed=1)
    X, F, G = res.pop.get("X"), res.pop.get("F"), res.pop.get("G")
    assert F.shape == (8, 2)
    catalogue = MO["design"]["catalogue_mm"]
    for design, f, g in zip(problem.designs(X), F, G):
        run = woodpile.simulate(problem.scenario(design))
        force = run.summary["transmitted_peak_force_n"]
        assert abs(f[0] - force) <= 1e-12 * force, (design, f[0], force)
        cells = [woodpile.cells(catalogue[i]) for i in design]
        mass = sum(c["primary_mass_kg"] + float(np.sum(c["resonator_masses_kg"])) for c in cells)
        assert abs(f[1] - mass) <= 1e-12 * mass, (design, f[1], mass)
        assert abs(g[0] - (mass * 1e3 / 10.0 - 1.0)) <= 1e-12


def test_a_reference_point_below_the_front_warns() -> None:
    # [-1, -1] lies below every force and mass: the hypervolume is 0 at every generation and
    # measures nothing, so the result warns as `woodpile optimize` does.
    config = {**MO, "ga": {**MO["ga"], "reference_point": [-1.0, -1.0]}}
    with pytest.warns(RuntimeWarning, match="hypervolume is 0"):
        result = woodpile.optimize(config, algorithm="nsga2")
    assert result.hypervolume == 0.0 and len(result.front) > 0
