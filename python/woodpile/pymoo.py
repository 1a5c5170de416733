"""woodpile's design problems as pymoo problems, so that any pymoo algorithm runs on them
(pymoo is an optional dependency: ``pip install "woodpile[pymoo]"``; importing this module
imports it, ``import woodpile`` does not)::

    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.operators.crossover.sbx import SBX
    from pymoo.operators.mutation.pm import PM
    from pymoo.operators.repair.rounding import RoundingRepair
    from pymoo.operators.sampling.rnd import IntegerRandomSampling
    from pymoo.optimize import minimize

    import woodpile.pymoo

    problem = woodpile.pymoo.Problem("paper-impact", objectives=["transmitted-force", "total-mass"])
    algorithm = NSGA2(
        pop_size=40,
        sampling=IntegerRandomSampling(),
        crossover=SBX(prob=0.9, eta=15, vtype=float, repair=RoundingRepair()),
        mutation=PM(eta=20, vtype=float, repair=RoundingRepair()),
    )
    result = minimize(problem, algorithm, ("n_gen", 20), seed=1)

A design is one integer variable per position: the catalogue index of its element, top to
bottom (a fixed position's bounds are its index). The objectives are those of
``ga.objectives``; the constraints are the problem's, each as ``g ≤ 0`` (named by
:attr:`Problem.constraint_names`). ``_evaluate`` evaluates the whole population in one call into
the SIMD lanes, with the accuracy ``woodpile optimize`` uses.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from . import _core
from .errors import ScenarioError
from .optimize import Problem as ProblemSource
from .optimize import _check_objectives, _problem_source
from .scenario import Scenario

try:
    from pymoo.core.problem import Problem as _PymooProblem
except ImportError as e:  # pragma: no cover - exercised only without pymoo
    raise ImportError('woodpile.pymoo needs pymoo: pip install "woodpile[pymoo]"') from e

__all__ = ["Problem"]


class Problem(_PymooProblem):  # type: ignore[misc]
    """A woodpile design problem as a vectorised pymoo ``Problem``.

    Args:
        problem: A built-in problem's name (``"paper-impact"``), a config file, or a config dict.
        objectives: Overrides ``ga.objectives`` (default: the problem's; one or more of the
            objectives of ``woodpile optimize``).
        threads: Threads for evaluation (0: one per core).

    The constraints, as ``g ≤ 0`` in the order of :attr:`constraint_names`:
    ``max_total_mass_g`` and ``max_stack_height_mm`` as the relative excess (value / limit − 1),
    each ``max_count`` entry as the copies beyond its cap, ``max_contact_pressure_pa`` as the
    relative excess of the worst contact's Hertz pressure (clipped at 0, as woodpile's NSGA-II
    uses it).
    """

    def __init__(self, problem: ProblemSource, *, objectives: Sequence[str] | None = None, threads: int = 0):
        _check_objectives(objectives, None)
        if not (isinstance(threads, int) and not isinstance(threads, bool) and threads >= 0):
            raise ScenarioError(
                f"invalid threads = {threads!r}: must be 0 (one per core) or more",
                "threads",
                repr(threads),
                "0 (one per core) or more",
            )
        kind, text, base_dir = _problem_source(problem)
        obj = None if objectives is None else list(objectives)
        self.session = _core.ParetoSession(kind, text, str(base_dir), None, threads, obj, "nsga2")
        positions, entries, fixed = self.session.bounds()
        xl = np.zeros(positions, dtype=int)
        xu = np.full(positions, entries - 1, dtype=int)
        for position, index in fixed:
            xl[position] = xu[position] = index
        #: The objectives, in the columns of ``F``; ``units`` their SI units.
        self.objectives = [name for name, _ in self.session.objectives()]
        self.units = [unit for _, unit in self.session.objectives()]
        #: The config keys of the constraints, in the columns of ``G``.
        self.constraint_names = self.session.constraint_names()
        super().__init__(
            n_var=positions,
            n_obj=len(self.objectives),
            n_ieq_constr=len(self.constraint_names),
            xl=xl,
            xu=xu,
            vtype=int,
        )

    def designs(self, x: Any) -> list[list[int]]:
        """The designs of a population's variables (rounded to whole catalogue indices)."""
        rows = np.atleast_2d(np.asarray(x, dtype=float))
        return [[int(v) for v in row] for row in np.rint(rows)]

    def scenario(self, design: Sequence[int]) -> Scenario:
        """The scenario of a design (catalogue indices, top to bottom)."""
        return Scenario(self.session.scenario_toml([int(g) for g in design]), name="design")

    def _evaluate(self, x: Any, out: dict[str, Any], *args: Any, **kwargs: Any) -> None:
        objectives, constraints = self.session.evaluate(self.designs(x))
        out["F"] = np.asarray(objectives, dtype=float)
        if self.constraint_names:
            out["G"] = np.asarray(constraints, dtype=float)
