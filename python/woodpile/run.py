"""Runs: one simulation, its samples as NumPy arrays, and its run directory."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any, overload

import numpy as np
import numpy.typing as npt

from . import _core
from .errors import StateError
from .lattice import LatticeRun
from .scenario import LatticeScenario, Scenario

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["Run", "simulate", "load_run"]

#: A float64 NumPy array.
FloatArray = npt.NDArray[np.float64]


class Run:
    """One run, computed by :func:`simulate` or read back by :func:`load_run`: ``name``,
    ``summary`` (the keys and values of ``summary.json``) and the samples as arrays.

    Arrays (S samples, N elements, contacts 0..N):
    ``time_s`` (S,) [s], ``forces_n`` (S, N+1) [N], ``energy_j`` (S, N+1) [J] per layer,
    ``displacements_m`` and ``velocities_m_s`` (S, N) of the primary masses [m, m/s],
    ``wall_energy_j``, ``input_work_j`` and ``dissipated_j`` (S,) [J].

    A run read from disk also has ``directory`` and ``run_info`` (``run.json``); both are None
    for a run computed here. Only a computed run can be saved, in the process that computed it: a
    run pickles (to come back from an executor's worker) with its arrays, summary and scenario.
    """

    name: str
    summary: dict[str, Any]
    time_s: FloatArray
    forces_n: FloatArray
    energy_j: FloatArray
    displacements_m: FloatArray
    velocities_m_s: FloatArray
    wall_energy_j: FloatArray
    input_work_j: FloatArray
    dissipated_j: FloatArray
    directory: Path | None
    run_info: dict[str, Any] | None

    def __init__(self, core_run: _core.Run):
        """A computed run, from the extension's run (use :func:`simulate`)."""
        self._run: _core.Run | None = core_run
        self.name = core_run.name
        self.summary = json.loads(core_run.summary_json())
        self.time_s = core_run.time_s
        self.forces_n = core_run.forces_n
        self.energy_j = core_run.energy_j
        self.displacements_m = core_run.displacements_m
        self.velocities_m_s = core_run.velocities_m_s
        self.wall_energy_j = core_run.wall_energy_j
        self.input_work_j = core_run.input_work_j
        self.dissipated_j = core_run.dissipated_j
        self.directory = None
        self.run_info = None
        self._scenario_toml: str | None = None

    @classmethod
    def _from_directory(cls, directory: Path, name: str, summary: dict[str, Any], run_info: dict[str, Any]) -> Run:
        """A run read back from its directory (use :func:`load_run`)."""
        run = cls.__new__(cls)
        run._run = None
        run._scenario_toml = None
        run.name = name
        run.summary = summary
        run.directory = directory
        run.run_info = run_info

        def load(stem: str) -> FloatArray:
            array: FloatArray = np.load(directory / f"{stem}.npy")
            return array

        run.time_s = load("time_s")
        run.forces_n = load("forces_n")
        run.energy_j = load("energy_j")
        run.displacements_m = load("displacements_m")
        run.velocities_m_s = load("velocities_m_s")
        run.wall_energy_j = load("wall_energy_j")
        run.input_work_j = load("input_work_j")
        # Runs written before dissipation was recorded lack it: none was.
        lost = directory / "dissipated_j.npy"
        run.dissipated_j = load("dissipated_j") if lost.exists() else np.zeros_like(run.time_s)
        return run

    @property
    def scenario(self) -> Scenario:
        """The scenario that was run."""
        if self._run is not None:
            return Scenario(self._run.scenario_toml(), name=self.name)
        if self._scenario_toml is not None:
            return Scenario(self._scenario_toml, name=self.name)
        assert self.run_info is not None  # a run is either computed or read back
        return Scenario.from_dict(self.run_info["scenario"], name=self.name)

    @property
    def actuator_rest_m(self) -> float | None:
        """Under a displacement drive, its tip's static position u* [m] (downward: the tip's
        overlap is u* + u(t) − x₁; ``summary.json``'s ``actuator_rest_m``); None without one."""
        rest = self.summary.get("actuator_rest_m")
        return None if rest is None else float(rest)

    def to_pandas(self) -> pd.DataFrame:
        """The samples as a DataFrame indexed by ``time_s``: ``contact_{c}_n``, ``layer_{l}_j``,
        ``wall_j``, ``input_work_j``, ``dissipated_j``, ``element_{i}_m``, ``element_{i}_m_s``
        (the CSV files' column names)."""
        import pandas as pd

        nc = self.forces_n.shape[1]
        n = self.displacements_m.shape[1]
        cols: dict[str, FloatArray] = {}
        for c in range(nc):
            cols[f"contact_{c}_n"] = self.forces_n[:, c]
        for layer in range(nc):
            cols[f"layer_{layer}_j"] = self.energy_j[:, layer]
        cols["wall_j"] = self.wall_energy_j
        cols["input_work_j"] = self.input_work_j
        cols["dissipated_j"] = self.dissipated_j
        for i in range(n):
            cols[f"element_{i + 1}_m"] = self.displacements_m[:, i]
        for i in range(n):
            cols[f"element_{i + 1}_m_s"] = self.velocities_m_s[:, i]
        return pd.DataFrame(cols, index=pd.Index(self.time_s, name="time_s"))

    def save(self, directory: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
        """Writes the run directory exactly as ``woodpile simulate --out`` does; returns it.

        A directory holding an earlier run is replaced only with ``overwrite=True`` (its other
        files are kept); any other non-empty directory is refused. Both raise
        :class:`~woodpile.errors.OverwriteError` and leave the directory as it was.
        """
        if self._run is None:
            where = f"read from {self.directory}" if self.directory else "unpickled"
            raise StateError(
                f"this run was {where}; only a run computed in this process can be saved",
                "directory",
                str(directory),
                "copy the run's directory instead",
            )
        return Path(self._run.save(str(directory), overwrite))

    def __getstate__(self) -> dict[str, Any]:
        """The run without the extension's object (which does not pickle): arrays, summary and
        the scenario's TOML."""
        state = dict(self.__dict__)
        if self._run is not None:
            state["_scenario_toml"] = self._run.scenario_toml()
        state["_run"] = None
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        """Restores a pickled run (it cannot be saved: :meth:`save`)."""
        self.__dict__.update(state)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"Run({self.name!r}: {s['n_elements']} elements, {s['n_samples']} samples, "
            f"transmitted {s['transmitted_peak_force_n']:.4g} N)"
        )


@overload
def simulate(  # type: ignore[overload-overlap]
    scenario: LatticeScenario,
    *,
    allow_long: bool = False,
    allow_large: bool = False,
    allow_inaccurate: bool = False,
) -> LatticeRun: ...


@overload
def simulate(
    scenario: Scenario | str,
    *,
    allow_long: bool = False,
    allow_large: bool = False,
    allow_inaccurate: bool = False,
) -> Run: ...


def simulate(
    scenario: Scenario | str,
    *,
    allow_long: bool = False,
    allow_large: bool = False,
    allow_inaccurate: bool = False,
) -> Run | LatticeRun:
    """Runs a scenario (or a built-in scenario's name); the GIL is released while Rust runs,
    and Ctrl-C stops it within a step (``KeyboardInterrupt``).

    A lattice's scenario (a :class:`LatticeScenario`, which :class:`Scenario` gives for a text
    with a ``[lattice]`` table) returns a :class:`~woodpile.LatticeRun`; as ``woodpile
    simulate``, a lattice run whose energy balance is off by more than 1e-2 of the initial
    energy raises :class:`~woodpile.errors.InaccurateRunError` unless ``allow_inaccurate``
    (chains' runs report theirs in ``summary``). Type checkers see the lattice's return type
    when the argument is typed :class:`LatticeScenario` (``LatticeScenario.load``).

    The command line's up-front limits apply: a run of more integration steps than the limit
    (``woodpile simulate --allow-long``) raises :class:`~woodpile.errors.LimitError` unless
    ``allow_long``; a trajectory larger than the output limit unless ``allow_large``.

    Raises :class:`~woodpile.errors.ScenarioError` for a value that is not valid and
    :class:`~woodpile.errors.RunError` when the run fails numerically.
    """
    if isinstance(scenario, str):
        scenario = Scenario.builtin(scenario)
    if not isinstance(scenario, Scenario):
        raise TypeError(
            f"simulate takes a Scenario or a built-in scenario's name, not {type(scenario).__name__}"
        )
    flags = (("allow_long", allow_long), ("allow_large", allow_large), ("allow_inaccurate", allow_inaccurate))
    for name, flag in flags:
        if not isinstance(flag, bool):
            raise TypeError(f"{name} must be True or False, not {flag!r}")
    if isinstance(scenario, LatticeScenario):
        return LatticeRun(
            _core.simulate_lattice(scenario.to_toml(), scenario.name, allow_long, allow_large, allow_inaccurate)
        )
    return Run(
        _core.simulate(
            scenario.to_toml(), str(scenario.base_dir), scenario.name, allow_long, allow_large
        )
    )


def load_run(directory: str | os.PathLike[str]) -> Run:
    """Reads a run directory written by ``woodpile simulate`` or :meth:`Run.save`."""
    directory = Path(directory)
    name, summary, run_json = _core.load_run(str(directory))
    return Run._from_directory(directory, name, json.loads(summary), json.loads(run_json))
