"""Design studies: figures of merit of many scenarios as a DataFrame, locally or on an executor
(any ``concurrent.futures.Executor`` or a ``dask.distributed.Client``)."""

from __future__ import annotations

import copy
import itertools
import json
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Iterable, Mapping, Protocol, Sequence, TypeVar

from . import _core
from .errors import ScenarioError
from .scenario import Scenario

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["SUMMARY_COLUMNS", "Executor", "evaluate", "sweep"]

T = TypeVar("T")
T_co = TypeVar("T_co", covariant=True)


class Future(Protocol[T_co]):
    """What an executor's ``submit`` returns: a result to wait for."""

    def result(self) -> T_co:
        """The result, once computed (raises what the function raised)."""
        ...


class Executor(Protocol):
    """Where chunks of work run: a ``concurrent.futures.Executor`` or a ``dask.distributed.Client``
    (anything with ``submit(fn, *args)`` returning a future)."""

    def submit(self, fn: Callable[..., T], /, *args: Any) -> Future[T]:
        """Schedules ``fn(*args)``; its future."""
        ...


#: Columns of :func:`evaluate`'s table, from the library's run summary.
SUMMARY_COLUMNS = [
    "incident_peak_force_n",
    "transmitted_peak_force_n",
    "transmission_ratio",
    "wave_arrived",
    "restitution_coefficient",
    "energy_max_relative_error",
    "dissipated_j",
    "wall_time_s",
    "error",
]


def _row(summary_json: str | None, error: str | None) -> dict[str, Any]:
    """One row of :func:`evaluate`'s table from a run's summary (JSON) or its error message."""
    if summary_json is None:
        row: dict[str, Any] = {k: None for k in SUMMARY_COLUMNS}
        row["error"] = error
        return row
    s = json.loads(summary_json)
    restitution = s.get("restitution")
    return {
        "incident_peak_force_n": s["incident_peak_force_n"],
        "transmitted_peak_force_n": s["transmitted_peak_force_n"],
        "transmission_ratio": s["transmission_ratio"],
        "wave_arrived": s["wave_arrived"],
        "restitution_coefficient": (
            restitution["coefficient"] if restitution and restitution["separated"] else None
        ),
        "energy_max_relative_error": s["energy"]["max_relative_error"],
        "dissipated_j": s["energy"].get("dissipated_j", 0.0),
        "wall_time_s": s["wall_time_s"],
        "error": None,
    }


def _evaluate_chunk(texts: Sequence[str], base_dir: str, threads: int | None = None) -> list[dict[str, Any]]:
    """Runs a chunk of scenarios (TOML texts) in this process; the unit of work an executor gets."""
    return [_row(summary, error) for summary, error in _core.evaluate(list(texts), base_dir, threads)]


def _chunks(items: Sequence[T], n: int) -> list[Sequence[T]]:
    """``items`` in at most ``n`` consecutive chunks of nearly equal size."""
    size = max(1, -(-len(items) // max(1, n)))
    return [items[i : i + size] for i in range(0, len(items), size)]


def _workers(executor: Any) -> int:
    """How many workers an executor has (a dask Client's total threads; 2 when unknown)."""
    info = getattr(executor, "scheduler_info", None)
    if callable(info):
        workers = info().get("workers", {})
        return max(1, sum(int(w.get("nthreads", 1)) for w in workers.values()))
    return max(1, int(getattr(executor, "_max_workers", 2)))


def evaluate(
    scenarios: Iterable[Scenario], executor: Executor | None = None, *, chunks_per_worker: int = 4
) -> pd.DataFrame:
    """Figures of merit of many scenarios, one row each (in order), as a pandas DataFrame with
    the columns :data:`SUMMARY_COLUMNS`.

    Without ``executor`` the runs share this process's cores (rayon, GIL released). With any
    ``concurrent.futures.Executor`` or a ``dask.distributed.Client`` the scenarios are shipped in
    chunks (``chunks_per_worker`` per worker, so scheduling costs stay small) and each chunk runs
    on one worker. A scenario that fails gives a row whose ``error`` column says why.

    Raises :class:`~woodpile.errors.ScenarioError` when the scenarios have different
    ``base_dir``\\ s, and :class:`TypeError` naming ``scenarios[i]`` for one that is not a
    :class:`Scenario`.
    """
    import pandas as pd

    scenarios = list(scenarios)
    for i, s in enumerate(scenarios):
        if not isinstance(s, Scenario):
            raise TypeError(f"invalid scenarios[{i}] = {s!r}: must be a woodpile.Scenario")
    if not scenarios:
        return pd.DataFrame(columns=SUMMARY_COLUMNS)
    base_dirs = {str(s.base_dir) for s in scenarios}
    if len(base_dirs) > 1:
        raise ScenarioError(
            "scenarios with different base directories cannot be evaluated together",
            "base_dir",
            repr(sorted(base_dirs)),
            "give every scenario the same base_dir",
        )
    # Absolute, so that workers started elsewhere find the scenario's files.
    base_dir = str(Path(base_dirs.pop()).resolve())
    texts = [s.to_toml() for s in scenarios]
    if executor is None:
        rows = _evaluate_chunk(texts, base_dir)
    else:
        parts = _chunks(texts, _workers(executor) * chunks_per_worker)
        futures = [executor.submit(_evaluate_chunk, part, base_dir, 1) for part in parts]
        rows = [row for f in futures for row in f.result()]
    return pd.DataFrame(rows, columns=SUMMARY_COLUMNS)


def sweep(scenario: Scenario, grid: Mapping[str, Sequence[Any]], executor: Executor | None = None) -> pd.DataFrame:
    """The Cartesian product of ``grid`` (dotted keys → values) applied to ``scenario``: one row
    per run, the swept values first, then :func:`evaluate`'s columns. A combination that is no
    valid scenario, or whose run fails, gives a row whose ``error`` column says why (naming the
    key); the other rows are computed as usual."""
    import pandas as pd

    if not isinstance(scenario, Scenario):
        raise TypeError(f"invalid scenario = {scenario!r}: must be a woodpile.Scenario")
    if not isinstance(grid, Mapping):
        raise TypeError(
            f"invalid grid = {grid!r}: must be a dict of dotted keys to the values to sweep, "
            'e.g. {"excitation.velocity_m_s": [1.0, 2.0]}'
        )
    keys = list(grid)
    for k in keys:
        if isinstance(grid[k], (str, bytes)) or not isinstance(grid[k], Iterable):
            raise ScenarioError(
                f"invalid grid[{k!r}] = {grid[k]!r}: the values to sweep must be a list",
                k,
                repr(grid[k]),
                "give a list of values, e.g. [1.0, 2.0] (a string is one value: ['rk4'])",
            )
    combos = list(itertools.product(*(grid[k] for k in keys)))
    # A combination the scenario refuses is a row with its error, as a run that fails is.
    scenarios: list[Scenario | None] = []
    refused: list[str | None] = []
    for values in combos:
        try:
            scenarios.append(scenario.replace(**dict(zip(keys, values))))
            refused.append(None)
        except ScenarioError as e:
            scenarios.append(None)
            refused.append(str(e))
    valid = evaluate([s for s in scenarios if s is not None], executor)
    runs = iter(valid.to_dict("records"))
    rows = [next(runs) if error is None else _row(None, error) for error in refused]
    results = pd.DataFrame(rows, columns=SUMMARY_COLUMNS)
    swept = pd.DataFrame([[copy.deepcopy(v) for v in c] for c in combos], columns=keys)
    return pd.concat([swept, results], axis=1)
