"""Calibration: the parameters of a scenario that best explain measured signals, with their
uncertainties (docs/fit.md). The fit file, its checks and its outputs are those of
``woodpile fit``; the work runs in Rust with the GIL released."""

from __future__ import annotations

import io
import json
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union

from . import _core
from .errors import _check_count

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["FitResult", "fit"]


@dataclass(frozen=True)
class FitResult:
    """The result of :func:`fit`.

    ``estimates``: one row per parameter (index ``key``; the time shift is ``time_shift_s``) with
    ``estimate``, ``std_error``, ``ci95_low``, ``ci95_high`` (NaN where the data do not determine
    it) and ``at_bound``. ``correlation``: the correlation matrix, indexed by key both ways.
    ``residuals``: every measured row (``file``, ``signal``, ``time_s``, ``measured``, ``model``,
    ``residual``, ``in_window``). ``raw``: ``fit.json`` as a dictionary.
    """

    estimates: "pd.DataFrame"
    correlation: "pd.DataFrame"
    residuals: "pd.DataFrame"
    condition_number: Optional[float]
    cost: float
    evaluations: int
    warnings: list[str]
    raw: dict[str, Any]


def fit(
    path: Union[str, Path],
    out: Union[str, Path, None] = None,
    *,
    overwrite: bool = False,
    threads: Optional[int] = None,
    allow_large: bool = False,
) -> FitResult:
    """Fits the fit file at ``path`` (docs/fit.md) and returns a :class:`FitResult`.

    ``out``: also write ``fit.json``, ``fitted.toml`` and ``residuals.csv`` there (an earlier
    fit's files are replaced only with ``overwrite=True``). ``threads``: worker threads for a
    Jacobian's runs (default: one per core); a negative count raises
    :class:`woodpile.ScenarioError` naming ``threads``. A fit planning more than 1e6 model runs
    (``fit.starts`` × ``fit.max_evaluations``) raises :class:`woodpile.LimitError` unless
    ``allow_large``. Bad input raises :class:`woodpile.ScenarioError`
    (or :class:`woodpile.FileError`) naming the file and line or the key.
    """
    import pandas as pd

    _check_count("threads", threads, "worker threads: 0 (one per core) or more")
    text, csv = _core.fit_file(
        str(path), None if out is None else str(out), overwrite, threads, allow_large
    )
    raw: dict[str, Any] = json.loads(text)
    rows = []
    for p in raw["parameters"]:
        ci = p["ci95"] or [None, None]
        rows.append(
            {
                "key": p["key"],
                "estimate": p["estimate"],
                "std_error": p["std_error"],
                "ci95_low": ci[0],
                "ci95_high": ci[1],
                "at_bound": p["at_bound"],
            }
        )
    estimates = pd.DataFrame(rows).set_index("key").astype(
        {"estimate": float, "std_error": float, "ci95_low": float, "ci95_high": float}
    )
    keys = list(estimates.index)
    correlation = pd.DataFrame(raw["correlation"] or [], index=keys, columns=keys, dtype=float)
    residuals = pd.read_csv(io.StringIO(csv))
    return FitResult(
        estimates=estimates,
        correlation=correlation,
        residuals=residuals,
        condition_number=raw["condition_number"],
        cost=raw["cost"],
        evaluations=raw["evaluations"],
        warnings=list(raw["warnings"]),
        raw=raw,
    )
