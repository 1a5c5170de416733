"""woodpile: locally resonant woodpile metamaterials under impact and blast, from Python.

The physics runs in Rust (the ``woodpile._core`` extension); this package gives it a Python
face: scenarios as objects and dictionaries, runs as NumPy arrays and pandas tables, and design
studies on any ``concurrent.futures`` executor or a ``dask.distributed.Client``.

>>> import woodpile
>>> run = woodpile.simulate(woodpile.Scenario.builtin("paper-impact-80mm").replace(**{"run.duration_s": 2e-4}))
>>> run.forces_n.shape
(201, 21)
"""

from __future__ import annotations

import copy
import itertools
import json
import os
from pathlib import Path
from typing import Any, Iterable, Mapping, Sequence

import numpy as np

from . import _core
from ._core import WoodpileError

__all__ = [
    "Scenario",
    "Run",
    "WoodpileError",
    "simulate",
    "load_run",
    "evaluate",
    "sweep",
    "builtin_scenarios",
    "cells",
    "effective_mass",
    "band_gaps",
    "spectrum",
    "transmission",
    "BreederGA",
    "optimize",
    "OptimizeResult",
]
__version__ = _core.__version__


def builtin_scenarios() -> list[str]:
    """Names of the built-in scenarios (as ``woodpile scenarios`` lists them)."""
    return list(_core.builtin_scenarios())


class Scenario:
    """A scenario: the same TOML structure as a scenario file, every default written out.

    Immutable: :meth:`replace` returns a new scenario. Relative paths in it (a blast table) are
    resolved against ``base_dir``.
    """

    def __init__(self, toml_text: str, *, name: str = "scenario", base_dir: str | os.PathLike = "."):
        self._base_dir = Path(base_dir)
        self._toml = _core.complete_toml(toml_text, str(self._base_dir))
        self.name = name

    @classmethod
    def builtin(cls, name: str) -> "Scenario":
        """A built-in scenario by name (see :func:`builtin_scenarios`)."""
        return cls(_core.builtin_toml(name), name=name)

    @classmethod
    def from_toml(cls, text: str, *, name: str = "scenario", base_dir: str | os.PathLike = ".") -> "Scenario":
        """A scenario from TOML text."""
        return cls(text, name=name, base_dir=base_dir)

    @classmethod
    def load(cls, path: str | os.PathLike) -> "Scenario":
        """A scenario file; its relative paths are relative to the file."""
        path = Path(path)
        return cls(path.read_text(), name=path.stem, base_dir=path.parent)

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], *, name: str = "scenario", base_dir: str | os.PathLike = ".") -> "Scenario":
        """A scenario from a dictionary with the TOML file's structure."""
        return cls(_core.json_to_toml(json.dumps(d)), name=name, base_dir=base_dir)

    def to_dict(self) -> dict[str, Any]:
        """The scenario as a dictionary with the TOML file's structure (every default present)."""
        return json.loads(_core.toml_to_json(self._toml))

    def to_toml(self) -> str:
        """The scenario as complete TOML: ``woodpile simulate`` runs exactly the same model."""
        return self._toml

    @property
    def base_dir(self) -> Path:
        """Directory that relative paths in the scenario are relative to."""
        return self._base_dir

    def replace(self, **changes: Any) -> "Scenario":
        """A new scenario with dotted keys changed, as in the TOML file::

            s.replace(**{"chain.rods_mm": [80, 40, 20], "excitation.velocity_m_s": 2.0})

        Setting one of two alternative keys removes the other (``velocity_m_s`` replaces
        ``drop_height_m``, ``rods_mm`` replaces ``elements``, ``run.peak_tolerance`` replaces the
        integrator settings). Errors name the key.
        """
        d = self.to_dict()
        for dotted, value in changes.items():
            _set_dotted(d, dotted, value)
        return Scenario.from_dict(d, name=self.name, base_dir=self._base_dir)

    def __repr__(self) -> str:
        return f"Scenario({self.name!r})"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scenario) and self._toml == other._toml

    def __getstate__(self) -> dict[str, Any]:
        return {"toml": self._toml, "name": self.name, "base_dir": str(self._base_dir)}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self._toml = state["toml"]
        self.name = state["name"]
        self._base_dir = Path(state["base_dir"])


# Keys that exclude each other: setting the first removes the others.
_ALTERNATIVES = {
    "excitation.velocity_m_s": ["excitation.drop_height_m"],
    "excitation.drop_height_m": ["excitation.velocity_m_s"],
    "chain.rods_mm": ["chain.elements"],
    "chain.elements": ["chain.rods_mm"],
    # A stated peak accuracy replaces the integrator settings, and the other way round.
    "run.peak_tolerance": ["run.integrator", "run.time_step_s", "run.rtol", "run.atol"],
    "run.integrator": ["run.peak_tolerance"],
    "run.time_step_s": ["run.peak_tolerance"],
    "run.rtol": ["run.peak_tolerance"],
    "run.atol": ["run.peak_tolerance"],
}


def _set_dotted(d: dict[str, Any], dotted: str, value: Any) -> None:
    parts = dotted.split(".")
    node = d
    for p in parts[:-1]:
        child = node.get(p)
        if child is None:
            child = node[p] = {}
        if not isinstance(child, dict):
            raise WoodpileError(
                f"invalid {dotted}: `{p}` is not a table", dotted, repr(value), f"`{p}` holds a value, not keys"
            )
        node = child
    node[parts[-1]] = value
    for other in _ALTERNATIVES.get(dotted, []):
        op = other.split(".")
        parent = d
        for p in op[:-1]:
            parent = parent.get(p, {})
        parent.pop(op[-1], None)


class Run:
    """One simulated run: ``summary`` (the keys of ``summary.json``) and the samples as arrays."""

    def __init__(self, core_run: Any):
        self._run = core_run
        self.summary: dict[str, Any] = json.loads(core_run.summary_json())
        self.name: str = core_run.name
        self.time_s: np.ndarray = core_run.time_s
        self.forces_n: np.ndarray = core_run.forces_n
        self.energy_j: np.ndarray = core_run.energy_j
        self.displacements_m: np.ndarray = core_run.displacements_m
        self.velocities_m_s: np.ndarray = core_run.velocities_m_s
        self.wall_energy_j: np.ndarray = core_run.wall_energy_j
        self.input_work_j: np.ndarray = core_run.input_work_j
        self.dissipated_j: np.ndarray = core_run.dissipated_j

    @property
    def scenario(self) -> Scenario:
        """The scenario that was run."""
        return Scenario(self._run.scenario_toml(), name=self.name)

    def to_pandas(self):
        """The samples as a DataFrame indexed by ``time_s``: ``contact_{c}_n``, ``layer_{l}_j``,
        ``element_{i}_m``, ``element_{i}_m_s`` (the CSV files' column names), ``input_work_j``,
        ``dissipated_j``."""
        import pandas as pd

        nc = self.forces_n.shape[1]
        n = self.displacements_m.shape[1]
        cols: dict[str, np.ndarray] = {}
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

    def save(self, directory: str | os.PathLike, *, overwrite: bool = False) -> Path:
        """Writes the run directory exactly as ``woodpile simulate --out`` does; returns it."""
        return Path(self._run.save(str(directory), overwrite))

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"Run({self.name!r}: {s['n_elements']} elements, {s['n_samples']} samples, "
            f"transmitted {s['transmitted_peak_force_n']:.4g} N)"
        )


class LoadedRun:
    """A run directory read back: ``summary``, ``run_info`` (``run.json``) and the arrays."""

    def __init__(self, directory: Path, name: str, summary: dict[str, Any], run_info: dict[str, Any]):
        self.directory = directory
        self.name = name
        self.summary = summary
        self.run_info = run_info
        load = lambda f: np.load(directory / f)  # noqa: E731
        self.time_s = load("time_s.npy")
        self.forces_n = load("forces_n.npy")
        self.energy_j = load("energy_j.npy")
        self.displacements_m = load("displacements_m.npy")
        self.velocities_m_s = load("velocities_m_s.npy")
        self.wall_energy_j = load("wall_energy_j.npy")
        self.input_work_j = load("input_work_j.npy")
        d = directory / "dissipated_j.npy"
        self.dissipated_j = np.load(d) if d.exists() else np.zeros_like(self.time_s)

    @property
    def scenario(self) -> Scenario:
        """The scenario that was run."""
        return Scenario.from_dict(self.run_info["scenario"], name=self.name)


def simulate(scenario: Scenario | str) -> Run:
    """Runs a scenario (or a built-in scenario's name); the GIL is released while Rust runs."""
    if isinstance(scenario, str):
        scenario = Scenario.builtin(scenario)
    return Run(_core.simulate(scenario.to_toml(), str(scenario.base_dir), scenario.name))


def load_run(directory: str | os.PathLike) -> LoadedRun:
    """Reads a run directory written by ``woodpile simulate`` or :meth:`Run.save`."""
    directory = Path(directory)
    name, summary, run_json = _core.load_run(str(directory))
    return LoadedRun(directory, name, json.loads(summary), json.loads(run_json))


# ---------------------------------------------------------------------------------------------
# Many runs: figures of merit as a DataFrame, locally or on an executor.

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


def _row(summary_json: str) -> dict[str, Any]:
    if summary_json.startswith("error: "):
        row = {k: None for k in SUMMARY_COLUMNS}
        row["error"] = summary_json[len("error: "):]
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
    return [_row(s) for s in _core.evaluate(list(texts), base_dir, threads)]


def _chunks(items: Sequence[Any], n: int) -> list[Sequence[Any]]:
    size = max(1, -(-len(items) // max(1, n)))
    return [items[i : i + size] for i in range(0, len(items), size)]


def _workers(executor: Any) -> int:
    """How many workers an executor has (a dask Client's total threads; 2 when unknown)."""
    info = getattr(executor, "scheduler_info", None)
    if callable(info):
        workers = info().get("workers", {})
        return max(1, sum(w.get("nthreads", 1) for w in workers.values()))
    return max(1, getattr(executor, "_max_workers", 2))


def evaluate(scenarios: Iterable[Scenario], executor: Any = None, *, chunks_per_worker: int = 4):
    """Figures of merit of many scenarios, one row each (in order), as a pandas DataFrame.

    Without ``executor`` the runs share this process's cores (rayon, GIL released). With any
    ``concurrent.futures.Executor`` or a ``dask.distributed.Client`` the scenarios are shipped in
    chunks (``chunks_per_worker`` per worker, so scheduling costs stay small) and each chunk runs
    on one worker. A scenario that fails gives a row whose ``error`` column says why.
    """
    import pandas as pd

    scenarios = list(scenarios)
    if not scenarios:
        return pd.DataFrame(columns=SUMMARY_COLUMNS)
    base_dirs = {str(s.base_dir) for s in scenarios}
    if len(base_dirs) > 1:
        raise WoodpileError(
            "scenarios with different base directories cannot be evaluated together", "base_dir", repr(sorted(base_dirs)), "give every scenario the same base_dir"
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


def sweep(scenario: Scenario, grid: Mapping[str, Sequence[Any]], executor: Any = None):
    """The Cartesian product of ``grid`` (dotted keys → values) applied to ``scenario``: one row
    per run, the swept values first, then :func:`evaluate`'s columns."""
    import pandas as pd

    keys = list(grid)
    combos = list(itertools.product(*(grid[k] for k in keys)))
    scenarios = [scenario.replace(**dict(zip(keys, values))) for values in combos]
    results = evaluate(scenarios, executor)
    swept = pd.DataFrame([[copy.deepcopy(v) for v in c] for c in combos], columns=keys)
    return pd.concat([swept, results], axis=1)


# ---------------------------------------------------------------------------------------------
# Cells and analysis.


def cells(length_mm: float, *, diameter_mm: float | None = None, material: str | None = None, modes: int | None = None) -> dict[str, Any]:
    """A rod's unit cell: the paper's Table 1 row for its lengths (20–80 mm, nothing else given),
    otherwise derived by Timoshenko beam theory. ``primary_mass_kg``, ``resonator_masses_kg``,
    ``resonator_stiffnesses_n_per_m``, ``local_resonances_hz``."""
    primary, masses, stiffnesses = _core.cell(float(length_mm), diameter_mm, material, modes)
    masses = np.asarray(masses)
    stiffnesses = np.asarray(stiffnesses)
    return {
        "primary_mass_kg": primary,
        "resonator_masses_kg": masses,
        "resonator_stiffnesses_n_per_m": stiffnesses,
        "local_resonances_hz": np.sqrt(stiffnesses / masses) / (2 * np.pi),
    }


def effective_mass(cell: Mapping[str, Any], frequencies_hz: Sequence[float], *, resonator_ratio: float = 0.0):
    """M_eff(2πf)/M_total of a cell (as :func:`cells` returns it): (real part, imaginary part),
    the resonators damped at ``resonator_ratio``."""
    return _core.effective_mass(
        cell["primary_mass_kg"],
        list(map(float, cell["resonator_masses_kg"])),
        list(map(float, cell["resonator_stiffnesses_n_per_m"])),
        list(map(float, frequencies_hz)),
        float(resonator_ratio),
    )


def band_gaps(cell: Mapping[str, Any], beta: float, precompression_n: float) -> dict[str, np.ndarray]:
    """Pass bands and gaps [Hz] of a homogeneous chain of ``cell`` with contact coefficient β
    [N/m^1.5] under a static force [N] (the linearised Bloch relation): arrays of shape (k, 2);
    an open gap's upper edge is ``inf``."""
    passes, gaps = _core.band_gaps(
        cell["primary_mass_kg"],
        list(map(float, cell["resonator_masses_kg"])),
        list(map(float, cell["resonator_stiffnesses_n_per_m"])),
        float(beta),
        float(precompression_n),
    )
    return {"pass_bands_hz": np.array(passes), "gaps_hz": np.array(gaps)}


def spectrum(signal: Sequence[float], sample_interval_s: float, scaling: str = "fourier"):
    """One-sided spectrum of a uniformly sampled signal: (frequencies [Hz], values).

    ``scaling="fourier"`` (default) gives the magnitude of the Fourier transform |F̂(f)| in the
    signal's unit times seconds (N/Hz for a force): for a transient (an impact, a blast) it does
    not depend on the record length or the sample interval, so spectra of two runs compare
    directly; the figures use it. ``scaling="amplitude"`` gives the sine amplitude (N), right for
    steady signals only: the same pulse in a record twice as long reads half."""
    return _core.spectrum(list(map(float, signal)), float(sample_interval_s), str(scaling))


def transmission(
    scenario: Scenario | str,
    *,
    start_hz: float = 100.0,
    end_hz: float = 30e3,
    resolution_hz: float = 20.0,
    relative_amplitude: float = 0.01,
    threshold_db: float = -20.0,
):
    """The transmission spectrum of a scenario's preloaded chain (as ``woodpile transmission``):
    a DataFrame indexed by ``frequency_hz`` with ``transmission`` and ``transmission_db``, and
    the record of ``transmission.json`` (measured stop bands, predicted gaps, edges compared)."""
    import pandas as pd

    if isinstance(scenario, str):
        scenario = Scenario.builtin(scenario)
    (f, t), db, record = _core.transmission(
        scenario.to_toml(), str(scenario.base_dir), scenario.name,
        float(start_hz), float(end_hz), float(resolution_hz), float(relative_amplitude), float(threshold_db),
    )
    table = pd.DataFrame({"transmission": t, "transmission_db": db}, index=pd.Index(f, name="frequency_hz"))
    return table, json.loads(record)


# ---------------------------------------------------------------------------------------------
# The breeder GA, as ask/tell: designs can be evaluated anywhere.


def _problem_source(problem: Any) -> tuple[str, str, Path]:
    """(kind, text, base_dir) of a built-in problem name, a config file or a config dict."""
    if isinstance(problem, Mapping):
        return "json", json.dumps(problem), Path(".")
    p = Path(problem)
    if p.suffix == ".toml" or p.exists():
        return "toml", p.read_text(), p.parent
    return "builtin", str(problem), Path(".")


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
    """

    def __init__(self, problem: Any, *, seed: int | None = None, threads: int = 0):
        self._source = _problem_source(problem)
        self._seed = seed
        self._threads = threads
        kind, text, base_dir = self._source
        self._session = _core.GaSession(kind, text, str(base_dir), seed, threads)
        self._asked_at: float | None = None

    def ask(self) -> list[list[int]]:
        """The designs of the next generation still to evaluate."""
        import time

        self._asked_at = time.perf_counter()
        return [list(d) for d in self._session.ask()]

    def tell(self, designs: Sequence[Sequence[int]], objectives: Sequence[float]) -> None:
        """Their objective values (smaller is better); completes the generation."""
        import time

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
    def stop_reason(self) -> str | None:
        """``"generation-limit"``, ``"stalled"`` or None."""
        return self._session.stop_reason()

    @property
    def generation(self) -> int | None:
        """Generations completed (None before the first tell)."""
        return self._session.generation()

    @property
    def best(self) -> dict[str, Any]:
        """The best design: ``design`` (indices), ``objective``, ``labels``."""
        design, objective, labels = self._session.best()
        return {"design": list(design), "objective": objective, "labels": list(labels)}

    def best_scenario(self) -> Scenario:
        """The scenario of the best design."""
        return Scenario(self._session.scenario_toml(self.best["design"]), name="best")

    def history(self):
        """One row per generation: best, mean, worst, evaluations (at the run's settings),
        screenings, cache_hits, elapsed_s."""
        import pandas as pd

        cols = ["generation", "best", "mean", "worst", "evaluations", "screenings", "cache_hits", "elapsed_s"]
        return pd.DataFrame(self._session.history(), columns=cols).set_index("generation")

    def save(self, path: str | os.PathLike) -> None:
        """Writes the state as the command line's checkpoint (atomically: a temporary file
        renamed into place)."""
        state = self._session.state_json()
        if state is None:
            raise WoodpileError("nothing to save before the first generation", "checkpoint", str(path), "ask() and tell() first")
        path = Path(path)
        tmp = path.with_name(path.name + ".partial")
        tmp.write_text(state)
        os.replace(tmp, path)

    def restore(self, path_or_json: str | os.PathLike) -> None:
        """Continues from a checkpoint file (or its JSON text) of the same problem."""
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

    def __init__(self, ga: BreederGA):
        self.ga = ga
        self.best = ga.best
        self.scenario = ga.best_scenario()
        self.history = ga.history()
        self.stop_reason = ga.stop_reason

    def __repr__(self) -> str:
        return f"OptimizeResult(best {self.best['objective']:.6g}: {' '.join(self.best['labels'])})"


def optimize(
    problem: Any,
    *,
    seed: int | None = None,
    executor: Any = None,
    checkpoint: str | os.PathLike | None = None,
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
    base_dir = str(Path(ga._source[2]).resolve())
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
