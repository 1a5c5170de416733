"""Global sensitivity: Sobol' indices of the figures of merit over a scenario's ``[uncertainty]``
(Saltelli sampling, the estimators of SALib's ``sobol.analyze``), as ``woodpile sensitivity``
computes them (docs/sensitivity.md)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Optional, Sequence

from . import _core
from .errors import _check_count
from .scenario import Scenario

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["INDEX_COLUMNS", "sensitivity", "sobol_indices", "saltelli_unit_cube"]

#: The columns of :func:`sensitivity`'s DataFrame, as ``indices.csv`` names them.
INDEX_COLUMNS = ["parameter", "figure", "S1", "S1_conf", "ST", "ST_conf"]

#: Base samples when none are given (``woodpile sensitivity``'s default).
DEFAULT_BASE_SAMPLES = 64


def sensitivity(
    scenario: Scenario,
    base_samples: int = DEFAULT_BASE_SAMPLES,
    *,
    seed: Optional[int] = None,
    paper_settings: bool = False,
    threads: Optional[int] = None,
    allow_large: bool = False,
) -> pd.DataFrame:
    """First-order (S1) and total (ST) Sobol' indices of each figure of merit for each
    ``[uncertainty]`` parameter of ``scenario``, with their 95 % bootstrap intervals: one row per
    (parameter, figure), the columns :data:`INDEX_COLUMNS`.

    ``base_samples`` N (a power of two) gives N·(G + 2) runs for G parameters, in SIMD lanes on
    ``threads`` threads (default: one per core). ``seed`` overrides ``[uncertainty] seed`` (it
    also seeds the bootstrap). Unless ``paper_settings`` (the scenario's run settings as they
    are) or the scenario states a ``run.peak_tolerance``, every contact peak is computed within
    1e-5 (a :class:`Scenario` always carries the completed RK4 settings, so they do not count as
    stated here). A study of more than 1e6 elements in all (runs × chain elements) raises
    :class:`woodpile.LimitError` unless ``allow_large``. ``scenario`` other than a
    :class:`Scenario` raises :class:`TypeError`; a negative ``base_samples``, ``seed`` or
    ``threads`` a :class:`woodpile.ScenarioError` naming it.

    The DataFrame's ``attrs`` hold the design: ``attrs["samples"]`` (the Saltelli matrix, SALib's
    row order, one column per drawn value), ``attrs["outputs"]`` (one column per figure, same
    rows), ``attrs["parameters"]``, ``attrs["accuracy"]`` and ``attrs["no_indices"]`` (figure →
    why it has none). Bad input raises :class:`woodpile.ScenarioError` naming ``base_samples`` or
    the scenario key (``uncertainty``).
    """
    import pandas as pd

    if not isinstance(scenario, Scenario):
        raise TypeError(
            f"invalid scenario = {scenario!r}: must be a woodpile.Scenario "
            "(a file: Scenario.load(path); a built-in: Scenario.builtin(name))"
        )
    _check_count("base_samples", base_samples, "a power of two of at least 8, e.g. 64")
    _check_count("seed", seed, "the Sobol' points' seed: an integer 0 ≤ seed < 2**32", 2**32)
    _check_count("threads", threads, "worker threads: 0 (one per core) or more")
    columns, matrix, figures, outputs, rows, meaningless, accuracy = _core.sensitivity(
        scenario.to_toml(),
        str(scenario.base_dir),
        base_samples,
        seed,
        paper_settings,
        threads,
        allow_large,
    )
    indices = pd.DataFrame(rows, columns=INDEX_COLUMNS)
    indices.attrs["samples"] = pd.DataFrame(matrix, columns=columns, dtype=float)
    indices.attrs["outputs"] = pd.DataFrame(outputs, columns=figures, dtype=float)
    indices.attrs["parameters"] = list(dict.fromkeys(c.split("[")[0] for c in columns))
    indices.attrs["accuracy"] = accuracy
    indices.attrs["no_indices"] = dict(meaningless)
    return indices


def sobol_indices(
    outputs: Sequence[float],
    base_samples: int,
    groups: int,
    *,
    resamples: int = 100,
    level: float = 0.95,
    seed: int = 0,
) -> pd.DataFrame:
    """The estimators alone, on the outputs of any Saltelli design of ``base_samples`` points and
    ``groups`` parameters in SALib's row order (``calc_second_order=False``): one row per
    parameter with ``S1, S1_conf, ST, ST_conf``."""
    import pandas as pd

    _check_count("base_samples", base_samples, "the design's base samples N ≥ 1")
    _check_count("groups", groups, "the number of parameters (groups) ≥ 1")
    _check_count("resamples", resamples, "bootstrap resamples ≥ 0")
    _check_count("seed", seed, "the bootstrap's seed: an integer 0 ≤ seed < 2**64")
    rows = _core.sobol_indices([float(y) for y in outputs], base_samples, groups, resamples, level, seed)
    return pd.DataFrame(rows, columns=["S1", "S1_conf", "ST", "ST_conf"])


def saltelli_unit_cube(base_samples: int, group_of: Sequence[int], seed: int = 0) -> list[list[float]]:
    """The Saltelli design in the unit cube (scrambled Sobol' points, SALib's row order):
    ``group_of[j]`` is parameter j's group. A negative ``base_samples`` or ``seed`` raises
    :class:`woodpile.ScenarioError` naming it."""
    _check_count("base_samples", base_samples, "the base samples N, a power of two")
    _check_count("seed", seed, "the Sobol' points' seed: an integer 0 ≤ seed < 2**32", 2**32)
    return _core.saltelli_unit_cube(base_samples, list(group_of), seed)
