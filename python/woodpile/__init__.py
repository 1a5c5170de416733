"""woodpile: locally resonant woodpile metamaterials under impact and blast, from Python.

The physics runs in Rust (the ``woodpile._core`` extension); this package gives it a Python
face: scenarios as objects and dictionaries, runs as NumPy arrays and pandas tables, and design
studies on any ``concurrent.futures`` executor or a ``dask.distributed.Client``.

One module per domain, everything public re-exported here:

- :mod:`woodpile.scenario`: :class:`Scenario` (a chain's or a lattice's), :func:`builtin_scenarios`,
  :func:`scenario_keys`, :func:`lattice_keys`
- :mod:`woodpile.run`: :class:`Run` (a chain's or a lattice's), :func:`simulate`, :func:`load_run`
- :mod:`woodpile.study`: :func:`evaluate`, :func:`sweep`
- :mod:`woodpile.analysis`: :func:`cells`, :func:`effective_mass`, :func:`band_gaps`,
  :func:`spectrum`, :func:`transmission`
- :mod:`woodpile.optimize`: :class:`BreederGA`, :func:`optimize`, :class:`OptimizeResult`,
  :class:`ParetoResult` (NSGA-II), :class:`GenerationStats`
- :mod:`woodpile.calibration`: :func:`fit`, :class:`FitResult`
- :mod:`woodpile.sobol`: :func:`sensitivity` (Sobol' indices over ``[uncertainty]``)
- :mod:`woodpile.errors`: :class:`WoodpileError` and its subclasses
- :mod:`woodpile.plot`: matplotlib figures (imported on demand)
- :mod:`woodpile.pymoo`: a design problem as a pymoo ``Problem`` (imported on demand; needs pymoo)

>>> import woodpile
>>> run = woodpile.simulate(woodpile.Scenario.builtin("paper-impact-80mm").replace(**{"run.duration_s": 2e-4}))
>>> run.forces_n.shape
(201, 21)
"""

from __future__ import annotations

from . import _core
from .analysis import Cell, band_gaps, cells, effective_mass, spectrum, transmission
from .calibration import FitResult, fit
from .errors import (
    FileError,
    InaccurateRunError,
    InterruptedRunError,
    LimitError,
    OverwriteError,
    RunError,
    ScenarioError,
    StateError,
    WoodpileError,
)
from .optimize import BestDesign, BreederGA, GenerationStats, OptimizeResult, ParetoResult, optimize
from .run import CONTACT_COLUMNS, Run, load_run, simulate
from .scenario import (
    LatticeScenario,
    Scenario,
    ScenarioKey,
    builtin_scenarios,
    lattice_keys,
    scenario_keys,
)
from .sobol import INDEX_COLUMNS, sensitivity
from .study import SUMMARY_COLUMNS, evaluate, sweep

__all__ = [
    "Scenario",
    "LatticeScenario",
    "Run",
    "LatticeRun",
    "load_lattice_run",
    "CONTACT_COLUMNS",
    "WoodpileError",
    "ScenarioError",
    "FileError",
    "OverwriteError",
    "RunError",
    "InaccurateRunError",
    "LimitError",
    "InterruptedRunError",
    "StateError",
    "simulate",
    "load_run",
    "evaluate",
    "sweep",
    "SUMMARY_COLUMNS",
    "builtin_scenarios",
    "scenario_keys",
    "lattice_keys",
    "ScenarioKey",
    "cells",
    "Cell",
    "effective_mass",
    "band_gaps",
    "spectrum",
    "transmission",
    "BreederGA",
    "GenerationStats",
    "BestDesign",
    "optimize",
    "OptimizeResult",
    "ParetoResult",
    "fit",
    "FitResult",
    "sensitivity",
    "INDEX_COLUMNS",
]
__version__: str = _core.__version__

#: Kept for code written before runs read back and runs computed were one type.
LoadedRun = Run
#: Kept for code written before chains' and lattices' runs were one type.
LatticeRun = Run
#: Kept for code written before chains' and lattices' run directories were read by one function.
load_lattice_run = load_run
