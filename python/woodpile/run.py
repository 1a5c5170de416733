"""Runs: one simulation of a chain or a lattice, its samples as NumPy arrays, and its run
directory. A chain is a path graph of the contact graph a lattice is: both give one :class:`Run`
with the same arrays, figures and contacts table (docs/reference/outputs.md)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any, Union

import numpy as np
import numpy.typing as npt

from . import _core
from .errors import StateError
from .scenario import Scenario

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["Run", "simulate", "load_run", "CONTACT_COLUMNS"]

#: A float64 NumPy array.
FloatArray = npt.NDArray[np.float64]

#: The columns of :attr:`Run.contacts`, as a lattice's ``run.json`` names them.
CONTACT_COLUMNS = ("layer_above", "rod_above", "layer_below", "rod_below", "x_mm", "y_mm")

_CoreRun = Union[_core.Run, _core.LatticeRun]


class Run:
    """One run of a chain or a lattice, computed by :func:`simulate` or read back by
    :func:`load_run`: ``name``, ``structure`` (``"chain"`` or ``"lattice"``), ``summary`` (the
    keys and values of ``summary.json``, the same for both) and the samples as arrays.

    Arrays of every run (S samples, C contacts, B bodies):

    - ``time_s`` (S,) [s]; ``forces_n`` (S, C) [N], column c contact c;
    - ``energy_j`` (S, B) [J], each body's energy (kinetic, strain and half of each of its
      contacts' potential: a chain's layers 0..N, the striker first; a lattice's striker or
      actuator, then its rods), ``wall_energy_j`` (S,) the wall's or supports' halves, and
      :attr:`total_energy_j` (S,) their sum;
    - ``input_work_j`` and ``dissipated_j`` (S,) [J] (zeros without lab physics);
    - :attr:`contacts`, a DataFrame indexed by ``contact`` with :data:`CONTACT_COLUMNS` (a
      chain is a path: contact c joins layer c to layer c + 1, the wall is layer N + 1),
      :attr:`supports` (the contacts on the wall or supports) and :attr:`transmitted_n`, their
      summed force.

    A chain's run also has ``displacements_m`` and ``velocities_m_s`` (S, N) of the primary
    masses; a lattice's has ``contact_energy_j`` and ``contact_dissipated_j`` (S, C),
    ``rods_per_layer`` and ``lattice_mass_kg``. Asking a run for the other structure's array
    raises :class:`~woodpile.errors.StateError` saying so.

    A run read from disk also has ``directory`` and ``run_info`` (``run.json``); both are None
    for a run computed here. Only a computed run can be saved, in the process that computed it: a
    run pickles (to come back from an executor's worker) with its arrays, summary and scenario.
    """

    name: str
    structure: str
    summary: dict[str, Any]
    time_s: FloatArray
    forces_n: FloatArray
    energy_j: FloatArray
    wall_energy_j: FloatArray
    input_work_j: FloatArray
    dissipated_j: FloatArray
    supports: list[int]
    directory: Path | None
    run_info: dict[str, Any] | None

    def __init__(self, core_run: _CoreRun):
        """A computed run, from the extension's run (use :func:`simulate`)."""
        self._run: _CoreRun | None = core_run
        self.name = core_run.name
        self.summary = json.loads(core_run.summary_json())
        self.directory = None
        self.run_info = None
        self._scenario_toml: str | None = None
        self.time_s = core_run.time_s
        self.forces_n = core_run.forces_n
        self.input_work_j = core_run.input_work_j
        self.dissipated_j = core_run.dissipated_j
        self._chain: dict[str, FloatArray] | None = None
        self._lattice: dict[str, Any] | None = None
        if isinstance(core_run, _core.LatticeRun):
            self.structure = "lattice"
            self.energy_j = core_run.body_energies_j
            self.wall_energy_j = core_run.support_energy_j
            self.supports = list(core_run.supports)
            self._contacts = [list(c) for c in core_run.contacts]
            self._lattice = {
                "contact_energy_j": core_run.contact_energy_j,
                "contact_dissipated_j": core_run.contact_dissipated_j,
                "rods_per_layer": list(core_run.rods_per_layer),
                "lattice_mass_kg": core_run.lattice_mass_kg,
            }
        else:
            self.structure = "chain"
            self.energy_j = core_run.energy_j
            self.wall_energy_j = core_run.wall_energy_j
            self._chain = {"displacements_m": core_run.displacements_m, "velocities_m_s": core_run.velocities_m_s}
            self._set_path_contacts()

    def _set_path_contacts(self) -> None:
        """A chain's contacts as a path graph: contact c joins layer c to layer c + 1."""
        n = self.forces_n.shape[1]
        self._contacts = [[c, 1, c + 1, 1, 0.0, 0.0] for c in range(n)]
        self.supports = [n - 1]

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
        run._chain = None
        run._lattice = None

        def load(stem: str) -> FloatArray:
            array: FloatArray = np.load(directory / f"{stem}.npy")
            return array

        run.time_s = load("time_s")
        run.forces_n = load("forces_n")
        run.energy_j = load("energy_j")
        if _core.is_lattice_run(str(directory)):
            run.structure = "lattice"
            run._read_lattice(directory, load)
        else:
            run.structure = "chain"
            run.wall_energy_j = load("wall_energy_j")
            run.input_work_j = load("input_work_j")
            # Runs written before dissipation was recorded lack it: none was.
            lost = directory / "dissipated_j.npy"
            run.dissipated_j = load("dissipated_j") if lost.exists() else np.zeros_like(run.time_s)
            run._chain = {"displacements_m": load("displacements_m"), "velocities_m_s": load("velocities_m_s")}
            run._set_path_contacts()
        return run

    def _read_lattice(self, directory: Path, load: Any) -> None:
        """A lattice's own files: its contacts, supports, energies and integrals."""
        info = self.run_info
        assert info is not None
        self._contacts = [[c[k] for k in CONTACT_COLUMNS] for c in info["contacts"]]
        support_layer = len(info["rods_per_layer"]) + 1
        self.supports = [k for k, c in enumerate(self._contacts) if c[2] == support_layer]
        self.wall_energy_j = load("support_energy_j")
        table = np.loadtxt(directory / "energy.csv", delimiter=",", skiprows=1, ndmin=2)
        with open(directory / "energy.csv") as f:
            header = f.readline().strip().split(",")
        column = {h: table[:, k] for k, h in enumerate(header)}
        zeros = np.zeros_like(self.time_s)
        self.input_work_j = column.get("work_j", zeros)
        self.dissipated_j = column.get("dissipated_j", zeros)
        dissipated = directory / "contact_dissipated_j.npy"
        self._lattice = {
            "contact_energy_j": load("contact_energy_j"),
            "contact_dissipated_j": np.load(dissipated) if dissipated.is_file() else None,
            "rods_per_layer": list(info["rods_per_layer"]),
            "lattice_mass_kg": float(info["lattice_mass_kg"]),
        }

    def _only(self, structure: str, what: str) -> dict[str, Any]:
        """The arrays only a ``structure`` run has, or the error naming ``what`` for the other."""
        part = self._chain if structure == "chain" else self._lattice
        if part is None:
            raise StateError(
                f"a {self.structure} run has no {what}: only a {structure} run records it",
                what,
                self.name,
                f"use a {structure} scenario, or the arrays every run has (forces_n, energy_j, contacts)",
            )
        return part

    @property
    def is_lattice(self) -> bool:
        """Whether this is a lattice's run."""
        return self.structure == "lattice"

    @property
    def displacements_m(self) -> FloatArray:
        """A chain's primary-mass displacements [m], shape (S, N)."""
        array: FloatArray = self._only("chain", "displacements_m")["displacements_m"]
        return array

    @property
    def velocities_m_s(self) -> FloatArray:
        """A chain's primary-mass velocities [m/s], shape (S, N)."""
        array: FloatArray = self._only("chain", "velocities_m_s")["velocities_m_s"]
        return array

    @property
    def contact_energy_j(self) -> FloatArray:
        """A lattice's Hertz potential per contact [J], shape (S, C) (0 at a load point of a
        prescribed force)."""
        array: FloatArray = self._only("lattice", "contact_energy_j")["contact_energy_j"]
        return array

    @property
    def contact_dissipated_j(self) -> FloatArray | None:
        """A lattice's energy dissipated at each contact since the start [J], shape (S, C); None
        without damping, a static load, a blast or a drive."""
        array: FloatArray | None = self._only("lattice", "contact_dissipated_j")["contact_dissipated_j"]
        return array

    @property
    def rods_per_layer(self) -> list[int]:
        """A lattice's rods per layer, top to bottom."""
        rods: list[int] = self._only("lattice", "rods_per_layer")["rods_per_layer"]
        return rods

    @property
    def lattice_mass_kg(self) -> float:
        """A lattice's rods' total mass [kg]."""
        return float(self._only("lattice", "lattice_mass_kg")["lattice_mass_kg"])

    @property
    def total_energy_j(self) -> FloatArray:
        """The total energy E(t) [J], shape (S,): every body's share and the wall's or supports'."""
        total: FloatArray = self.energy_j.sum(axis=1) + self.wall_energy_j
        return total

    @property
    def contacts(self) -> pd.DataFrame:
        """The contacts in output order: a DataFrame indexed by ``contact`` (the column of
        :attr:`forces_n`) with :data:`CONTACT_COLUMNS`. A chain's contact c joins layer c
        (0: the striker or the load) to layer c + 1 (N + 1: the wall), on the axis."""
        import pandas as pd

        frame = pd.DataFrame(self._contacts, columns=list(CONTACT_COLUMNS))
        frame.index.name = "contact"
        return frame

    @property
    def support_forces_n(self) -> FloatArray:
        """Each support's force [N], shape (S, supports) (a chain: the wall's, one column)."""
        forces: FloatArray = self.forces_n[:, self.supports]
        return forces

    @property
    def transmitted_n(self) -> FloatArray:
        """The transmitted force [N], the supports' summed force (a chain: the wall's), (S,)."""
        total: FloatArray = self.support_forces_n.sum(axis=1)
        return total

    @property
    def contact_peak_forces_n(self) -> FloatArray:
        """Each contact's peak force over every step [N], in output order (``summary.json``)."""
        return np.asarray(self.summary["contact_peak_forces_n"], dtype=np.float64)

    @property
    def transmitted_peak_force_n(self) -> float:
        """Peak over the steps of the transmitted force [N]."""
        return float(self.summary["transmitted_peak_force_n"])

    @property
    def wave_arrived(self) -> bool:
        """Whether the wave reached the wall or supports (``summary.json``'s ``wave_arrived``).
        False: the run was too short for the transmitted force to mean anything; lengthen
        ``run.duration_s``."""
        return bool(self.summary.get("wave_arrived", True))

    @property
    def energy_max_relative_error(self) -> float:
        """The energy balance's largest error over the samples, relative to the larger of E(0)
        and the largest work done (``summary.json``'s ``energy.max_relative_error``)."""
        return float(self.summary["energy"]["max_relative_error"])

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
        """Under a displacement drive, its tip's (a lattice: its rigid actuator's) static
        position u* [m] (downward: a tip's overlap is u* + u(t) − x; ``summary.json``'s
        ``actuator_rest_m``); None without one."""
        rest = self.summary.get("actuator_rest_m")
        return None if rest is None else float(rest)

    def to_pandas(self) -> pd.DataFrame:
        """The samples as a DataFrame indexed by ``time_s``, with the CSV files' column names:
        a chain's ``contact_{c}_n``, ``layer_{l}_j``, ``wall_j``, ``input_work_j``,
        ``dissipated_j``, ``element_{i}_m``, ``element_{i}_m_s``; a lattice's ``contact_{c}_n``,
        ``support_{s}_n``, ``transmitted_n`` and ``total_j``."""
        import pandas as pd

        cols: dict[str, FloatArray] = {}
        for c in range(self.forces_n.shape[1]):
            cols[f"contact_{c}_n"] = self.forces_n[:, c]
        if self.is_lattice:
            for s in range(len(self.supports)):
                cols[f"support_{s + 1}_n"] = self.support_forces_n[:, s]
            cols["transmitted_n"] = self.transmitted_n
            cols["total_j"] = self.total_energy_j
            return pd.DataFrame(cols, index=pd.Index(self.time_s, name="time_s"))
        for layer in range(self.energy_j.shape[1]):
            cols[f"layer_{layer}_j"] = self.energy_j[:, layer]
        cols["wall_j"] = self.wall_energy_j
        cols["input_work_j"] = self.input_work_j
        cols["dissipated_j"] = self.dissipated_j
        n = self.displacements_m.shape[1]
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
        shape = (
            f"{len(self.rods_per_layer)} layers, {len(self._contacts)} contacts"
            if self.is_lattice
            else f"{self.forces_n.shape[1] - 1} elements"
        )
        return (
            f"Run({self.name!r}: {self.structure}, {shape}, {len(self.time_s)} samples, "
            f"transmitted {self.transmitted_peak_force_n:.4g} N)"
        )


def simulate(
    scenario: Scenario | str,
    *,
    allow_long: bool = False,
    allow_large: bool = False,
    allow_inaccurate: bool = False,
) -> Run:
    """Runs a scenario, a chain's or a lattice's (or a built-in scenario's name); the GIL is
    released while Rust runs, and Ctrl-C stops it within a step (``KeyboardInterrupt``).

    The command line's rules apply: a run whose energy balance is off by more than 1e-2 of the
    larger of the initial energy and the largest work done raises
    :class:`~woodpile.errors.InaccurateRunError` unless ``allow_inaccurate``; a run of more
    integration steps than the limit (``woodpile simulate --allow-long``) raises
    :class:`~woodpile.errors.LimitError` unless ``allow_long``; a trajectory larger than the
    output limit unless ``allow_large``.

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
    if scenario.is_lattice:
        return Run(
            _core.simulate_lattice(scenario.to_toml(), scenario.name, allow_long, allow_large, allow_inaccurate)
        )
    return Run(
        _core.simulate(
            scenario.to_toml(), str(scenario.base_dir), scenario.name, allow_long, allow_large, allow_inaccurate
        )
    )


def load_run(directory: str | os.PathLike[str]) -> Run:
    """Reads a run directory, a chain's or a lattice's, written by ``woodpile simulate`` or
    :meth:`Run.save`."""
    directory = Path(directory)
    if _core.is_lattice_run(str(directory)):
        name, summary, run_json = _core.load_lattice_run(str(directory))
    else:
        name, summary, run_json = _core.load_run(str(directory))
    return Run._from_directory(directory, name, json.loads(summary), json.loads(run_json))
