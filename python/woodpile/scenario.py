"""Scenarios: the same TOML structure as a scenario file, as immutable Python objects."""

from __future__ import annotations

import functools
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping, Union

from . import _core
from .errors import ScenarioError

__all__ = [
    "Scenario",
    "LatticeScenario",
    "ScenarioKey",
    "builtin_scenarios",
    "lattice_keys",
    "scenario_keys",
]


def builtin_scenarios() -> list[str]:
    """Names of the built-in scenarios (as ``woodpile scenarios`` lists them)."""
    return list(_core.builtin_scenarios())


@dataclass(frozen=True)
class ScenarioKey:
    """One key of the scenario file, from woodpile-io's table of keys (the same table the
    command line completes, emits and checks scenarios with)."""

    #: Dotted path as errors name it (``run.time_step_s``); a list entry's key is
    #: ``LIST[].KEY`` (``chain.elements[].rod_mm``).
    name: str
    #: Type of the value: ``float``, ``integer``, ``bool``, ``string``, ``name``, ``material``,
    #: ``list of integers``, ``list of numbers``, ``list of tables`` or ``table``.
    type: str
    #: Unit of the value ("" when dimensionless or not a number).
    unit: str
    #: The default when the key is not given (from ``woodpile::defaults``); None when it has
    #: none or when it follows from other keys (then see ``default_rule``).
    default: Union[float, bool, str, None]
    #: How a default that follows from other keys is derived, in words; else None.
    default_rule: str | None
    #: The valid names of a ``name`` key.
    choices: tuple[str, ...]
    #: The keys that setting this one removes (``excitation.velocity_m_s`` ↔
    #: ``excitation.drop_height_m``).
    alternatives: tuple[str, ...]
    #: What values are valid, in words ("" when any value of the type is).
    valid: str
    #: What the key is, in one line.
    doc: str


@functools.lru_cache(maxsize=1)
def _key_table() -> dict[str, ScenarioKey]:
    """The keys by name (the extension's table, read once)."""
    return {
        name: ScenarioKey(name, ty, unit, default, rule, tuple(choices), tuple(alternatives), valid, doc)
        for name, ty, unit, default, rule, choices, alternatives, valid, doc in _core.scenario_keys()
    }


def scenario_keys() -> list[ScenarioKey]:
    """Every key of the scenario file, in the order of the file: name, type, unit, default,
    choices, alternatives, what is valid and what it is."""
    return list(_key_table().values())


def lattice_keys() -> list[ScenarioKey]:
    """Every key of a lattice scenario (``[lattice]``, ``[excitation]``, ``[wall]``, ``[damping]``,
    ``[preload]``, ``[run]``), in the order of the file, as :func:`scenario_keys` gives them."""
    return [
        ScenarioKey(name, ty, unit, default, rule, tuple(choices), tuple(alternatives), valid, doc)
        for name, ty, unit, default, rule, choices, alternatives, valid, doc in _core.lattice_keys()
    ]


class Scenario:
    """A scenario: the same TOML structure as a scenario file, every default written out.

    Immutable: :meth:`replace` returns a new scenario. Relative paths in it (a blast table) are
    resolved against ``base_dir``. A value that is not valid raises
    :class:`~woodpile.errors.ScenarioError` naming its dotted key.

    A lattice is a scenario with a ``[lattice]`` table instead of ``[chain]`` (docs/physics.md
    §16; :attr:`is_lattice`): the same constructors read it, :meth:`replace` takes its dotted
    keys (``excitation.at_mm``; a layer is changed as a whole list, ``lattice.layers``), and
    :func:`~woodpile.simulate` runs it into the same :class:`~woodpile.Run`.

    Args:
        toml_text: The scenario as TOML (missing keys take their defaults).
        name: The scenario's name (a run directory's ``scenario`` entry).
        base_dir: The directory that relative paths in the scenario are relative to.
    """

    name: str

    def __init__(self, toml_text: str, *, name: str = "scenario", base_dir: str | os.PathLike[str] = "."):
        self._base_dir = Path(base_dir)
        self._toml = _core.complete_toml(toml_text, str(self._base_dir))
        self.name = name

    @classmethod
    def builtin(cls, name: str) -> Scenario:
        """A built-in scenario by name (see :func:`builtin_scenarios`)."""
        return cls(_core.builtin_toml(name), name=name)

    @classmethod
    def from_toml(cls, text: str, *, name: str = "scenario", base_dir: str | os.PathLike[str] = ".") -> Scenario:
        """A scenario from TOML text."""
        return cls(text, name=name, base_dir=base_dir)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Scenario:
        """A scenario file; its relative paths are relative to the file."""
        path = Path(path)
        return cls(path.read_text(), name=path.stem, base_dir=path.parent)

    @classmethod
    def from_dict(
        cls, d: Mapping[str, Any], *, name: str = "scenario", base_dir: str | os.PathLike[str] = "."
    ) -> Scenario:
        """A scenario from a dictionary with the TOML file's structure. Values are numbers,
        strings, booleans, lists and tables; NumPy scalars and arrays are taken as their Python
        values. Anything else raises :class:`~woodpile.errors.ScenarioError` naming its key."""
        return cls(_core.json_to_toml(json.dumps(_plain(d, ""))), name=name, base_dir=base_dir)

    def to_dict(self) -> dict[str, Any]:
        """The scenario as a dictionary with the TOML file's structure (every default present)."""
        d: dict[str, Any] = json.loads(_core.toml_to_json(self._toml))
        return d

    def to_toml(self) -> str:
        """The scenario as complete TOML: ``woodpile simulate`` runs exactly the same model."""
        return self._toml

    @property
    def base_dir(self) -> Path:
        """Directory that relative paths in the scenario are relative to."""
        return self._base_dir

    def replace(self, **changes: Any) -> Scenario:
        """A new scenario with dotted keys changed, as in the TOML file::

            s.replace(**{"chain.rods_mm": [80, 40, 20], "excitation.velocity_m_s": 2.0})

        Setting one of two alternative keys removes the other (``velocity_m_s`` replaces
        ``drop_height_m``, ``rods_mm`` replaces ``elements``, ``run.peak_tolerance`` replaces the
        integrator settings: each key's ``alternatives`` in :func:`scenario_keys`). Errors name
        the key.
        """
        d = self.to_dict()
        for dotted, value in changes.items():
            _set_dotted(d, dotted, value)
        return Scenario.from_dict(d, name=self.name, base_dir=self._base_dir)

    @property
    def is_lattice(self) -> bool:
        """Whether this is a lattice's scenario (a ``[lattice]`` table)."""
        return _core.is_lattice(self._toml)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r})"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scenario) and self._toml == other._toml

    def __getstate__(self) -> dict[str, Any]:
        return {"toml": self._toml, "name": self.name, "base_dir": str(self._base_dir)}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self._toml = state["toml"]
        self.name = state["name"]
        self._base_dir = Path(state["base_dir"])


#: The name lattice scenarios had when they were a class of their own: :class:`Scenario` itself.
LatticeScenario = Scenario


def _plain(value: Any, key: str) -> Any:
    """``value`` as plain JSON-able Python (NumPy scalars and arrays as their values), checked
    all the way down; ``key`` is its dotted path, named by the error for anything else."""
    if isinstance(value, Mapping):
        return {k: _plain(v, f"{key}.{k}" if key else str(k)) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v, f"{key}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, float) and value != value:
        raise ScenarioError(
            f"invalid {key} = nan: a scenario value must be a number, not NaN",
            key,
            "nan",
            "a finite number",
        )
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    item = getattr(value, "tolist", None)  # NumPy scalars and arrays
    if callable(item) and type(value).__module__ == "numpy":
        return _plain(item(), key)
    raise ScenarioError(
        f"invalid {key} = {value!r}: a {type(value).__name__} is not a scenario value",
        key,
        repr(value),
        "give a number, a string, a boolean, a list or a table",
    )


def _set_dotted(d: dict[str, Any], dotted: str, value: Any) -> None:
    """Sets ``dotted`` in the nested dictionary ``d`` and removes the keys it excludes."""
    parts = dotted.split(".")
    node = d
    for p in parts[:-1]:
        child = node.get(p)
        if child is None:
            child = node[p] = {}
        if not isinstance(child, dict):
            raise ScenarioError(
                f"invalid {dotted}: `{p}` is not a table",
                dotted,
                repr(value),
                f"`{p}` holds a value, not keys",
            )
        node = child
    node[parts[-1]] = value
    known = _key_table().get(dotted)
    for other in known.alternatives if known is not None else ():
        *path, last = other.split(".")
        parent: Any = d
        for p in path:
            parent = parent.get(p, {})
        parent.pop(last, None)
