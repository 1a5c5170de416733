"""Lattice runs (docs/physics.md §16): per-contact forces as NumPy arrays, the contacts as a
pandas table, the supports and their sum, and the run directory of ``woodpile simulate``."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _core
from .errors import StateError
from .scenario import LatticeScenario

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["LatticeRun", "load_lattice_run", "CONTACT_COLUMNS"]

#: A float64 NumPy array.
FloatArray = npt.NDArray[np.float64]

#: The columns of :attr:`LatticeRun.contacts`, as ``run.json`` names them.
CONTACT_COLUMNS = ("layer_above", "rod_above", "layer_below", "rod_below", "x_mm", "y_mm")


class LatticeRun:
    """One lattice run, computed by :func:`~woodpile.simulate` of a :class:`LatticeScenario` or
    read back by :func:`load_lattice_run`.

    Contacts are in output order (``run.json``'s ``contacts``): the striker's (layer 0 above
    layer 1), the crossings layer by layer, then the supports (layer L + 1 below, their rod the
    support's number). With S samples and C contacts:

    - ``time_s`` (S,) [s]; ``forces_n`` (S, C) [N], column c contact c;
    - ``support_forces_n`` (S, supports) [N] and ``transmitted_n`` (S,) [N], their sum;
    - ``energy_j`` (S,) [J], the lattice's and striker's total energy;
    - ``contact_energy_j`` (S, C) [J], each contact's Hertz potential (0 at a load point of a
      prescribed force), and ``contact_dissipated_j`` (S, C) [J], the energy each contact has
      dissipated since the start (None without damping, a static load, a blast or a drive);
    - ``contacts``: a DataFrame indexed by ``contact`` with :data:`CONTACT_COLUMNS`;
    - ``summary``: ``summary.json`` (``contact_peak_forces_n`` in output order, the incident and
      transmitted peaks, ``energy_max_relative_error``);
    - ``rods_per_layer`` (top to bottom) and ``lattice_mass_kg``, the rods' mass [kg];
    - ``actuator_rest_m``: under a displacement drive, its rigid actuator's static position u* [m]
      (downward: every tip's overlap is u* + u(t) − w_i; ``summary.json``'s
      ``lab.actuator_rest_m``), None without a displacement actuator.

    A run read from disk also has ``directory`` and ``run_info`` (``run.json``); both are None
    for a run computed here, which alone can be saved.
    """

    name: str
    summary: dict[str, Any]
    run_info: dict[str, Any] | None
    rods_per_layer: list[int]
    lattice_mass_kg: float
    actuator_rest_m: float | None
    time_s: FloatArray
    forces_n: FloatArray
    energy_j: FloatArray
    contact_energy_j: FloatArray
    contact_dissipated_j: FloatArray | None
    supports: list[int]
    directory: Path | None

    def __init__(self, core_run: _core.LatticeRun):
        """A computed run, from the extension's run (use :func:`~woodpile.simulate`)."""
        self._run: _core.LatticeRun | None = core_run
        self.name = core_run.name
        self.summary = json.loads(core_run.summary_json())
        self.time_s = core_run.time_s
        self.forces_n = core_run.forces_n
        self.energy_j = core_run.energy_j
        self.contact_energy_j = core_run.contact_energy_j
        self.contact_dissipated_j = core_run.contact_dissipated_j
        self.supports = list(core_run.supports)
        self._contacts = [list(c) for c in core_run.contacts]
        self.rods_per_layer = list(core_run.rods_per_layer)
        self.lattice_mass_kg = core_run.lattice_mass_kg
        self.actuator_rest_m = core_run.actuator_rest_m
        self._scenario_toml: str | None = core_run.scenario_toml()
        self.directory = None
        self.run_info = None

    @classmethod
    def _from_directory(cls, directory: Path, name: str, summary: dict[str, Any], run_info: dict[str, Any]) -> LatticeRun:
        """A run read back from its directory (use :func:`load_lattice_run`)."""
        run = cls.__new__(cls)
        run._run = None
        run.name = name
        run.summary = summary
        run.run_info = run_info
        run.directory = directory
        run._contacts = [[c[k] for k in CONTACT_COLUMNS] for c in run_info["contacts"]]
        run._scenario_toml = None
        support_layer = len(run_info["rods_per_layer"]) + 1
        run.supports = [k for k, c in enumerate(run._contacts) if c[2] == support_layer]
        run.rods_per_layer = list(run_info["rods_per_layer"])
        run.lattice_mass_kg = float(run_info["lattice_mass_kg"])
        rest = (summary.get("lab") or {}).get("actuator_rest_m")
        run.actuator_rest_m = None if rest is None else float(rest)
        times: FloatArray = np.load(directory / "time_s.npy")
        forces: FloatArray = np.load(directory / "forces_n.npy")
        energy: FloatArray = np.loadtxt(directory / "energy.csv", delimiter=",", skiprows=1, ndmin=2)[:, 1]
        run.time_s, run.forces_n, run.energy_j = times, forces, energy
        run.contact_energy_j = np.load(directory / "contact_energy_j.npy")
        dissipated = directory / "contact_dissipated_j.npy"
        run.contact_dissipated_j = np.load(dissipated) if dissipated.is_file() else None
        return run

    @property
    def scenario(self) -> LatticeScenario:
        """The scenario that was run."""
        if self._scenario_toml is not None:
            return LatticeScenario(self._scenario_toml, name=self.name)
        assert self.run_info is not None  # a run is either computed or read back
        return LatticeScenario.from_dict(self.run_info["scenario"], name=self.name)

    @property
    def contacts(self) -> pd.DataFrame:
        """The contacts in output order: a DataFrame indexed by ``contact`` (the column of
        :attr:`forces_n`) with :data:`CONTACT_COLUMNS`."""
        import pandas as pd

        frame = pd.DataFrame(self._contacts, columns=list(CONTACT_COLUMNS))
        frame.index.name = "contact"
        return frame

    @property
    def support_forces_n(self) -> FloatArray:
        """Each support's force [N], shape (S, supports), supports in output order."""
        forces: FloatArray = self.forces_n[:, self.supports]
        return forces

    @property
    def transmitted_n(self) -> FloatArray:
        """The transmitted force [N], the sum of the supports' forces, shape (S,)."""
        total: FloatArray = self.support_forces_n.sum(axis=1)
        return total

    @property
    def contact_peak_forces_n(self) -> FloatArray:
        """Each contact's peak force over every step [N], in output order (``summary.json``)."""
        return np.asarray(self.summary["contact_peak_forces_n"], dtype=np.float64)

    @property
    def transmitted_peak_force_n(self) -> float:
        """Peak over the steps of the sum of the support forces [N]."""
        return float(self.summary["transmitted_peak_force_n"])

    @property
    def wave_arrived(self) -> bool:
        """Whether the wave reached the supports: the transmitted peak (less the supports'
        static forces) is at least a thousandth of the incident one's. False: the run was too
        short for ``transmitted_peak_force_n`` to mean anything; lengthen ``run.duration_s``."""
        return bool(self.summary.get("wave_arrived", True))

    @property
    def energy_max_relative_error(self) -> float:
        """Largest |E(t) − E(0)| / E(0) over the samples (the run is lossless)."""
        return float(self.summary["energy_max_relative_error"])

    def to_pandas(self) -> pd.DataFrame:
        """The samples as a DataFrame indexed by ``time_s``: ``contact_{c}_n``,
        ``support_{s}_n``, ``transmitted_n`` and ``total_j`` (the CSV files' column names)."""
        import pandas as pd

        cols: dict[str, FloatArray] = {}
        for c in range(self.forces_n.shape[1]):
            cols[f"contact_{c}_n"] = self.forces_n[:, c]
        for s in range(len(self.supports)):
            cols[f"support_{s + 1}_n"] = self.support_forces_n[:, s]
        cols["transmitted_n"] = self.transmitted_n
        cols["total_j"] = self.energy_j
        return pd.DataFrame(cols, index=pd.Index(self.time_s, name="time_s"))

    def save(self, directory: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
        """Writes the run directory exactly as ``woodpile simulate --out`` does; returns it.

        A directory holding an earlier run is replaced only with ``overwrite=True``; any other
        non-empty directory is refused (:class:`~woodpile.errors.OverwriteError`).
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
        """The run without the extension's object (which does not pickle)."""
        state = dict(self.__dict__)
        state["_run"] = None
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        """Restores a pickled run (it cannot be saved: :meth:`save`)."""
        self.__dict__.update(state)

    def __repr__(self) -> str:
        return (
            f"LatticeRun({self.name!r}: {len(self.rods_per_layer)} layers, {len(self._contacts)} contacts, "
            f"{len(self.time_s)} samples, transmitted {self.transmitted_peak_force_n:.4g} N)"
        )


def load_lattice_run(directory: str | os.PathLike[str]) -> LatticeRun:
    """Reads a lattice run directory written by ``woodpile simulate`` or :meth:`LatticeRun.save`."""
    directory = Path(directory)
    name, summary, run_json = _core.load_lattice_run(str(directory))
    return LatticeRun._from_directory(directory, name, json.loads(summary), json.loads(run_json))
