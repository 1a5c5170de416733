"""Design optimisation: the breeder GA of ``woodpile optimize`` as ask/tell, so that designs can
be evaluated anywhere (this process, an executor, a Dask cluster), and NSGA-II's Pareto fronts
(``objectives=[...]``, :class:`ParetoResult`)."""

from __future__ import annotations

import dataclasses
import json
import os
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, Mapping, Sequence, TypedDict, Union, overload

from . import _core
from .errors import ScenarioError, StateError, _check_count
from .scenario import Scenario
from .study import Executor, _chunks, _workers

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["BestDesign", "BreederGA", "GenerationStats", "OptimizeResult", "ParetoResult", "Problem", "optimize"]

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


def _is_lattice_study(problem: Problem, kind: str, text: str) -> bool:
    """Whether a problem is a lattice design study (its config has a ``lattice`` table)."""
    if kind == "json":
        return isinstance(problem, Mapping) and "lattice" in problem
    return kind == "toml" and _core.is_lattice(text)


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
        objectives: Overrides ``ga.objectives`` (one objective of a run for the breeder GA).
        algorithm: Overrides ``ga.algorithm`` (``"breeder"``).
    """

    def __init__(
        self,
        problem: Problem,
        *,
        seed: int | None = None,
        threads: int = 0,
        objectives: Sequence[str] | None = None,
        algorithm: str | None = None,
    ):
        _check_count("seed", seed, "the GA's seed: an integer 0 ≤ seed < 2**64")
        _check_count("threads", threads, "threads for evaluation: 0 (one per core) or more")
        _check_objectives(objectives, algorithm)
        self._source = _problem_source(problem)
        self._seed = seed
        self._threads = threads
        self._objectives = None if objectives is None else list(objectives)
        self._algorithm = algorithm
        kind, text, base_dir = self._source
        self._session = _core.GaSession(kind, text, str(base_dir), seed, threads, self._objectives, algorithm)
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
            "objectives": self._objectives,
            "algorithm": self._algorithm,
            "state": self._session.state_json(),
        }

    def __setstate__(self, st: dict[str, Any]) -> None:
        kind, text, base_dir = st["source"]
        self._source = (kind, text, Path(base_dir))
        self._seed = st["seed"]
        self._threads = st["threads"]
        self._objectives = st.get("objectives")
        self._algorithm = st.get("algorithm")
        self._session = _core.GaSession(kind, text, base_dir, self._seed, self._threads, self._objectives, self._algorithm)
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


class ParetoResult:
    """What :func:`optimize` found with NSGA-II (``ga.algorithm = "nsga2"``, or two or more
    objectives): the command line's ``pareto.csv``, ``pareto/NNN.toml`` and ``history.csv``.

    Attributes:
        front: The front as ``pareto.csv`` holds it: one row per non-dominated feasible design,
            one column per objective named as in ``objectives`` (SI units), then ``layer_1`` …
            ``layer_N`` (a rod's length in mm, another element's label).
        designs: Each row's catalogue indices, top to bottom.
        labels: Each row's element labels, top to bottom.
        scenarios: Each row's scenario (``pareto/001`` …), which :func:`woodpile.simulate`
            re-runs to the row's figures.
        history: ``history.csv`` indexed by ``generation``: ``hypervolume``, ``front_size``,
            ``feasible``, ``evaluations``, ``cache_hits``, ``elapsed_s``.
        objectives: The objectives, in column order; ``units`` their SI units.
        reference_point: The hypervolume's reference point (one value per objective).
        hypervolume: The final front's hypervolume (0 with designs on the front: a reference point
            below the front, which measures nothing, and a ``RuntimeWarning`` says so).
        stop_reason: ``"generation-limit"``, ``"stalled"`` or ``"interrupted"``.
        seed: The seed.
    """

    front: pd.DataFrame
    designs: list[list[int]]
    labels: list[list[str]]
    scenarios: list[Scenario]
    history: pd.DataFrame
    objectives: list[str]
    units: list[str]
    reference_point: list[float]
    hypervolume: float
    stop_reason: str | None
    seed: int

    def __init__(self, session: _core.ParetoSession | _core.LatticeParetoSession):
        import io

        import pandas as pd

        self.front = pd.read_csv(io.StringIO(session.pareto_csv()))
        rows = session.front()
        self.designs = [list(g) for g, _, _ in rows]
        self.labels = [list(labels) for _, _, labels in rows]
        self.scenarios = [
            Scenario(session.scenario_toml(list(g)), name=f"pareto/{k + 1:03d}") for k, (g, _, _) in enumerate(rows)
        ]
        self.history = pd.read_csv(io.StringIO(session.history_csv())).set_index("generation")
        names = session.objectives()
        self.objectives = [n for n, _ in names]
        self.units = [u for _, u in names]
        self.reference_point = list(session.reference_point())
        self.hypervolume = float(self.history["hypervolume"].iloc[-1])
        self.stop_reason = session.stop_reason()
        self.seed = session.seed()
        if self.hypervolume == 0.0 and len(self.front) > 0:
            # As woodpile optimize warns: a reference point below the front in some objective.
            warnings.warn(
                f"the hypervolume is 0: no design of the front is below the reference point {self.reference_point} "
                "in every objective, so the hypervolume measures nothing; set ga.reference_point above the "
                "front's values, or leave it out to take it from generation 0",
                RuntimeWarning,
                stacklevel=3,
            )

    def __repr__(self) -> str:
        return (
            f"ParetoResult({len(self.front)} designs on the front of {', '.join(self.objectives)}; "
            f"hypervolume {self.hypervolume:.6g})"
        )


def _check_objectives(objectives: Sequence[str] | None, algorithm: str | None) -> None:
    """Refuses keyword arguments of the wrong type (their values are checked with the config)."""
    if objectives is not None and (
        isinstance(objectives, str) or not all(isinstance(o, str) for o in objectives)
    ):
        raise ScenarioError(
            f"invalid objectives = {objectives!r}: must be a list of objective names",
            "objectives",
            repr(objectives),
            'a list such as ["transmitted-force", "total-mass"]',
        )
    if algorithm is not None and not isinstance(algorithm, str):
        raise ScenarioError(
            f"invalid algorithm = {algorithm!r}: must be \"breeder\" or \"nsga2\"",
            "algorithm",
            repr(algorithm),
            '"breeder" or "nsga2"',
        )


def _optimize_pareto(
    problem: Problem,
    seed: int | None,
    objectives: Sequence[str] | None,
    algorithm: str | None,
    checkpoint: str | os.PathLike[str] | None,
    threads: int,
) -> ParetoResult:
    """NSGA-II in this process, exactly as ``woodpile optimize`` runs it."""
    kind, text, base_dir = _problem_source(problem)
    obj = None if objectives is None else list(objectives)
    session = _core.ParetoSession(kind, text, str(base_dir), seed, threads, obj, algorithm)
    if checkpoint is not None and Path(checkpoint).exists():
        session.restore(Path(checkpoint).read_text())
    session.run(None if checkpoint is None else str(checkpoint))
    return ParetoResult(session)


@overload
def optimize(
    problem: Problem,
    *,
    seed: int | None = None,
    objectives: Sequence[str] | None = None,
    algorithm: Literal["nsga2"],
    executor: None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    chunks_per_worker: int = 2,
    threads: int = 0,
) -> ParetoResult: ...


@overload
def optimize(
    problem: Problem,
    *,
    seed: int | None = None,
    objectives: None = None,
    algorithm: Literal["breeder"],
    executor: Executor | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    chunks_per_worker: int = 2,
    threads: int = 0,
) -> OptimizeResult: ...


@overload
def optimize(
    problem: Problem,
    *,
    seed: int | None = None,
    objectives: Sequence[str] | None = None,
    algorithm: str | None = None,
    executor: Executor | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    chunks_per_worker: int = 2,
    threads: int = 0,
) -> OptimizeResult | ParetoResult: ...


def optimize(
    problem: Problem,
    *,
    seed: int | None = None,
    objectives: Sequence[str] | None = None,
    algorithm: str | None = None,
    executor: Executor | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    chunks_per_worker: int = 2,
    threads: int = 0,
) -> OptimizeResult | ParetoResult:
    """Runs the optimisation of ``problem`` (a built-in name such as ``"paper-impact"``, a
    config file, or a config dict) until its generation or stall limit. NSGA-II runs with the
    accuracy ``woodpile optimize`` uses by default (every contact peak within 1e-5 unless the
    problem states its integration; ``ga.paper_settings = true`` for RK4 at 0.1 µs); the
    breeder GA with the problem's own run settings (the command line adds screening and early
    stopping by default).

    ``objectives`` (``ga.objectives``, e.g. ``["transmitted-force", "total-mass"]``) and
    ``algorithm`` (``ga.algorithm``: ``"breeder"`` or ``"nsga2"``) override the problem's. One
    objective of a run: the breeder GA, returning an :class:`OptimizeResult`; designs are
    evaluated in this process, or in chunks on ``executor`` (any
    ``concurrent.futures.Executor`` or a ``dask.distributed.Client``). Two or more objectives,
    or ``algorithm="nsga2"``: NSGA-II in this process (all cores or ``threads``, SIMD lanes),
    returning a :class:`ParetoResult`. With ``checkpoint`` the state is saved after every
    generation (the command line's checkpoint format of that algorithm) and a run resumes from
    an existing file exactly. For a seed the result is the command line's. A config with a
    ``[lattice]`` table is a lattice design study (rod length per layer and the pitch,
    docs/optimization.md): NSGA-II in this process, a :class:`ParetoResult` whose ``scenarios``
    are lattice scenarios (:class:`~woodpile.Scenario` with ``is_lattice``; ``executor`` and
    ``algorithm="breeder"`` are refused). Bad keywords raise
    :class:`~woodpile.errors.ScenarioError` naming them (``objectives[1]``, ``algorithm``,
    ``executor``).
    """
    _check_objectives(objectives, algorithm)
    _check_count("threads", threads, "threads for evaluation: 0 (one per core) or more")
    _check_count("seed", seed, "the GA's seed: an integer 0 ≤ seed < 2**64")
    kind, text, base_dir = _problem_source(problem)
    obj = None if objectives is None else list(objectives)
    if _is_lattice_study(problem, kind, text):
        if executor is not None or algorithm not in (None, "nsga2"):
            raise ScenarioError(
                "invalid executor/algorithm: a lattice study runs NSGA-II in this process",
                "executor" if executor is not None else "algorithm",
                repr(executor if executor is not None else algorithm),
                "leave executor and algorithm unset (or algorithm=\"nsga2\") for a lattice study",
            )
        session = _core.LatticeParetoSession(kind, text, seed, threads, obj)
        if checkpoint is not None and Path(checkpoint).exists():
            session.restore(Path(checkpoint).read_text())
        session.run(None if checkpoint is None else str(checkpoint))
        return ParetoResult(session)
    if _core.study_algorithm(kind, text, str(base_dir), obj, algorithm) == "nsga2":
        if executor is not None:
            raise ScenarioError(
                "invalid executor: NSGA-II evaluates its generations in this process",
                "executor",
                repr(executor),
                "None for NSGA-II (it runs on all cores in SIMD lanes; executor= is for the breeder GA)",
            )
        return _optimize_pareto(problem, seed, objectives, algorithm, checkpoint, threads)
    ga = BreederGA(problem, seed=seed, threads=threads, objectives=objectives, algorithm=algorithm)
    if checkpoint is not None and Path(checkpoint).exists():
        ga.restore(checkpoint)
    config_json = ga.config_json
    worker_dir = str(ga.base_dir.resolve())
    while not ga.done:
        designs = ga.ask()
        if executor is None or not designs:
            values = ga.evaluate(designs)
        else:
            parts = _chunks(designs, _workers(executor) * chunks_per_worker)
            futures = [executor.submit(_evaluate_designs, config_json, worker_dir, part, 1) for part in parts]
            values = [v for f in futures for v in f.result()]
        ga.tell(designs, values)
        if checkpoint is not None:
            ga.save(checkpoint)
    return OptimizeResult(ga)
