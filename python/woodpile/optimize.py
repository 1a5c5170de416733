"""Design optimisation: the breeder GA of ``woodpile optimize`` as ask/tell, so that designs can
be evaluated anywhere (this process, an executor, a Dask cluster)."""

from __future__ import annotations

import dataclasses
import json
import os
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, Mapping, Sequence, TypedDict, Union

from . import _core
from .errors import ScenarioError, StateError
from .scenario import Scenario
from .study import Executor, _chunks, _workers

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["BestDesign", "BreederGA", "GenerationStats", "OptimizeResult", "Problem", "optimize"]

#: A problem: a built-in problem's name (``"paper-impact"``), a config file, or a config dict.
Problem = Union[str, "os.PathLike[str]", Mapping[str, Any]]


@dataclass(frozen=True)
class GenerationStats:
    """One generation of the GA: one line of ``history.csv`` and one row of
    :meth:`BreederGA.history` (the fields are the columns, in order)."""

    #: Generation (0 = the initial population).
    generation: int
    #: Best objective in the population.
    best: float
    #: Mean objective.
    mean: float
    #: Worst objective.
    worst: float
    #: Simulations at the run's settings so far.
    evaluations: int
    #: Screening simulations so far (0 without screening).
    screenings: int
    #: Cache hits so far.
    cache_hits: int
    #: Wall-clock seconds so far (not reproducible).
    elapsed_s: float

    @staticmethod
    def to_frame(records: Sequence[GenerationStats]) -> pd.DataFrame:
        """The records as a DataFrame indexed by ``generation``, one column per other field."""
        import pandas as pd

        names = [f.name for f in dataclasses.fields(GenerationStats)]
        table = pd.DataFrame([dataclasses.astuple(r) for r in records], columns=names)
        return table.set_index(names[0])


class BestDesign(TypedDict):
    """The best design found: catalogue indices (top to bottom), objective, element labels."""

    design: list[int]
    objective: float
    labels: list[str]


def _problem_source(problem: Problem) -> tuple[str, str, Path]:
    """(kind, text, base_dir) of a built-in problem name, a config file or a config dict."""
    if isinstance(problem, Mapping):
        return "json", json.dumps(problem), Path(".")
    p = Path(problem)
    if p.suffix == ".toml" or p.exists():
        return "toml", p.read_text(), p.parent
    return "builtin", str(problem), Path(".")


def _check_count(name: str, value: int | None, valid: str) -> None:
    """Refuses a keyword argument that must be a non-negative integer below 2**64 (or None)."""
    ok = value is None or (isinstance(value, int) and not isinstance(value, bool) and 0 <= value < 2**64)
    if not ok:
        raise ScenarioError(f"invalid {name} = {value!r}: must be {valid}", name, repr(value), valid)


def _evaluate_designs(config_json: str, base_dir: str, designs: Sequence[Sequence[int]], threads: int) -> list[float]:
    """A chunk of designs' objective values, computed in this (worker) process."""
    return list(_core.evaluate_designs(config_json, base_dir, [list(d) for d in designs], threads))


class BreederGA:
    """The breeder genetic algorithm of ``woodpile optimize`` (docs/physics.md §11) as ask/tell::

        ga = woodpile.BreederGA("paper-impact", seed=1)
        while not ga.done:
            designs = ga.ask()                        # catalogue indices, top to bottom
            ga.tell(designs, ga.evaluate(designs))    # or evaluate them anywhere

    For a seed the generations are identical to the command line's, whoever evaluates the
    designs: the draws depend only on the seed and the generation. ``ask`` returns only the
    designs the fitness cache does not hold yet. With ``ga.screen_peak_tolerance`` in the
    problem, ``evaluate`` (and a worker's evaluation) gives screened values, and ``tell``
    simulates here, at the run's settings, the few designs whose rank needs it: the choices are
    those of the unscreened GA (docs/physics.md §11). Picklable (the state travels as the
    command line's checkpoint JSON).

    Args:
        problem: A built-in problem's name, a config file, or a config dict.
        seed: Overrides the config's ``ga.seed``.
        threads: Threads for evaluation in this process (0: one per core).
    """

    def __init__(self, problem: Problem, *, seed: int | None = None, threads: int = 0):
        _check_count("seed", seed, "the GA's seed: an integer 0 ≤ seed < 2**64")
        _check_count("threads", threads, "threads for evaluation: 0 (one per core) or more")
        self._source = _problem_source(problem)
        self._seed = seed
        self._threads = threads
        kind, text, base_dir = self._source
        self._session = _core.GaSession(kind, text, str(base_dir), seed, threads)
        self._asked_at: float | None = None

    @property
    def base_dir(self) -> Path:
        """The directory the problem's relative paths are relative to."""
        return self._source[2]

    def ask(self) -> list[list[int]]:
        """The designs of the next generation still to evaluate."""
        self._asked_at = time.perf_counter()
        return [list(d) for d in self._session.ask()]

    def tell(self, designs: Sequence[Sequence[int]], objectives: Sequence[float]) -> None:
        """Their objective values (smaller is better); completes the generation.

        Raises :class:`~woodpile.errors.StateError` without a pending :meth:`ask`, and
        :class:`~woodpile.errors.ScenarioError` (``field`` ``"objectives"`` or ``"designs"``)
        for values that do not match the designs asked for.
        """
        elapsed = time.perf_counter() - self._asked_at if self._asked_at is not None else 0.0
        self._session.tell([list(d) for d in designs], [float(v) for v in objectives], elapsed)
        self._asked_at = None

    def evaluate(self, designs: Sequence[Sequence[int]]) -> list[float]:
        """The values ``tell`` expects for designs (screened ones with screening), simulated in
        this process (all cores, GIL released)."""
        return list(self._session.evaluate([list(d) for d in designs]))

    @property
    def config_json(self) -> str:
        """The completed problem (what a worker needs)."""
        return self._session.config_json()

    @property
    def done(self) -> bool:
        """Whether the generation or stall limit is reached."""
        return self._session.stop_reason() is not None

    @property
    def stop_reason(self) -> Literal["generation-limit", "stalled", "stopped"] | None:
        """``"generation-limit"``, ``"stalled"`` or None."""
        return self._session.stop_reason()

    @property
    def generation(self) -> int | None:
        """Generations completed (None before the first tell)."""
        return self._session.generation()

    @property
    def best(self) -> BestDesign:
        """The best design: ``design`` (indices), ``objective``, ``labels``."""
        design, objective, labels = self._session.best()
        return {"design": list(design), "objective": objective, "labels": list(labels)}

    def best_scenario(self) -> Scenario:
        """The scenario of the best design."""
        return Scenario(self._session.scenario_toml(self.best["design"]), name="best")

    def generations(self) -> list[GenerationStats]:
        """The history as typed records, one per generation."""
        return [GenerationStats(*row) for row in self._session.history()]

    def history(self) -> pd.DataFrame:
        """The history as a DataFrame indexed by ``generation``: the other fields of
        :class:`GenerationStats` as columns (``best``, ``mean``, ``worst``, ``evaluations`` at
        the run's settings, ``screenings``, ``cache_hits``, ``elapsed_s``)."""
        return GenerationStats.to_frame(self.generations())

    def save(self, path: str | os.PathLike[str]) -> None:
        """Writes the state as the command line's checkpoint (atomically: a temporary file
        renamed into place). Raises :class:`~woodpile.errors.StateError` before the first
        generation."""
        state = self._session.state_json()
        if state is None:
            raise StateError(
                "nothing to save before the first generation", "checkpoint", str(path), "ask() and tell() first"
            )
        path = Path(path)
        tmp = path.with_name(path.name + ".partial")
        tmp.write_text(state)
        os.replace(tmp, path)

    def restore(self, path_or_json: str | os.PathLike[str]) -> None:
        """Continues from a checkpoint file (or its JSON text) of the same problem; a damaged
        checkpoint or one of another problem raises :class:`~woodpile.errors.ScenarioError`
        with ``field == "checkpoint"``."""
        text = str(path_or_json)
        if not text.lstrip().startswith("{"):
            text = Path(path_or_json).read_text()
        self._session.restore(text)

    def run_to_end(self) -> None:
        """Runs the GA in this process exactly as ``woodpile optimize`` does."""
        self._session.run_to_end()

    def __getstate__(self) -> dict[str, Any]:
        kind, text, base_dir = self._source
        return {
            "source": (kind, text, str(base_dir)),
            "seed": self._seed,
            "threads": self._threads,
            "state": self._session.state_json(),
        }

    def __setstate__(self, st: dict[str, Any]) -> None:
        kind, text, base_dir = st["source"]
        self._source = (kind, text, Path(base_dir))
        self._seed = st["seed"]
        self._threads = st["threads"]
        self._session = _core.GaSession(kind, text, base_dir, self._seed, self._threads)
        self._asked_at = None
        if st["state"] is not None:
            self._session.restore(st["state"])


class OptimizeResult:
    """What :func:`optimize` found: ``best`` (design, objective, labels), ``scenario`` (the
    best design's scenario), ``history`` (DataFrame), ``stop_reason``, and the ``ga`` itself."""

    ga: BreederGA
    best: BestDesign
    scenario: Scenario
    history: pd.DataFrame
    stop_reason: str | None

    def __init__(self, ga: BreederGA):
        self.ga = ga
        self.best = ga.best
        self.scenario = ga.best_scenario()
        self.history = ga.history()
        self.stop_reason = ga.stop_reason

    def __repr__(self) -> str:
        return f"OptimizeResult(best {self.best['objective']:.6g}: {' '.join(self.best['labels'])})"


def optimize(
    problem: Problem,
    *,
    seed: int | None = None,
    executor: Executor | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    chunks_per_worker: int = 2,
) -> OptimizeResult:
    """Runs the breeder GA on ``problem`` (a built-in name such as ``"paper-impact"``, a config
    file, or a config dict) until its generation or stall limit.

    Designs are evaluated in this process, or in chunks on ``executor`` (any
    ``concurrent.futures.Executor`` or a ``dask.distributed.Client``). With ``checkpoint`` the
    state is saved after every generation (the command line's checkpoint format) and a run
    resumes from an existing file exactly. For a seed the result is the command line's.
    """
    ga = BreederGA(problem, seed=seed)
    if checkpoint is not None and Path(checkpoint).exists():
        ga.restore(checkpoint)
    config_json = ga.config_json
    base_dir = str(ga.base_dir.resolve())
    while not ga.done:
        designs = ga.ask()
        if executor is None or not designs:
            objectives = ga.evaluate(designs)
        else:
            parts = _chunks(designs, _workers(executor) * chunks_per_worker)
            futures = [executor.submit(_evaluate_designs, config_json, base_dir, part, 1) for part in parts]
            objectives = [v for f in futures for v in f.result()]
        ga.tell(designs, objectives)
        if checkpoint is not None:
            ga.save(checkpoint)
    return OptimizeResult(ga)
