"""Type stubs of the extension module ``woodpile._core`` (crates/woodpile-py), one section per
binding file. Errors are raised as the classes of :mod:`woodpile.errors`."""

from typing import Literal, Optional, Union

import numpy as np
import numpy.typing as npt

_F = npt.NDArray[np.float64]

__version__: str

# scenario.rs ------------------------------------------------------------------------------

def builtin_scenarios() -> list[str]: ...
def builtin_toml(name: str) -> str: ...
def complete_toml(text: str, base_dir: str) -> str: ...
def toml_to_json(text: str) -> str: ...
def json_to_toml(json: str) -> str: ...
def scenario_keys() -> list[
    tuple[str, str, str, Union[float, bool, str, None], Optional[str], list[str], list[str], str, str]
]: ...

# run.rs -----------------------------------------------------------------------------------

class Run:
    """One run: what was run, its figures of merit and its samples."""

    @property
    def name(self) -> str: ...
    @property
    def time_s(self) -> _F: ...
    @property
    def forces_n(self) -> _F: ...
    @property
    def energy_j(self) -> _F: ...
    @property
    def displacements_m(self) -> _F: ...
    @property
    def velocities_m_s(self) -> _F: ...
    @property
    def wall_energy_j(self) -> _F: ...
    @property
    def input_work_j(self) -> _F: ...
    @property
    def dissipated_j(self) -> _F: ...
    def summary_json(self) -> str: ...
    def scenario_toml(self) -> str: ...
    def save(self, dir: str, overwrite: bool) -> str: ...

def simulate(
    text: str, base_dir: str, name: str, allow_long: bool = False, allow_large: bool = False
) -> Run: ...
def load_run(dir: str) -> tuple[str, str, str]: ...

# study.rs ---------------------------------------------------------------------------------

def evaluate(
    texts: list[str], base_dir: str, threads: Optional[int] = None
) -> list[tuple[Optional[str], Optional[str]]]: ...

# analysis.rs ------------------------------------------------------------------------------

def cell(
    length_mm: float,
    diameter_mm: Optional[float] = None,
    material: Optional[str] = None,
    modes: Optional[int] = None,
) -> tuple[float, list[float], list[float]]: ...
def effective_mass(
    primary_kg: float,
    masses_kg: list[float],
    stiffnesses: list[float],
    frequencies_hz: list[float],
    ratio: Optional[float] = None,
) -> tuple[_F, _F]: ...
def band_gaps(
    primary_kg: float,
    masses_kg: list[float],
    stiffnesses: list[float],
    beta: float,
    precompression_n: float,
) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]: ...
def spectrum(signal: list[float], sample_interval_s: float, scaling: str) -> tuple[_F, _F]: ...
def transmission(
    text: str,
    base_dir: str,
    name: str,
    start_hz: Optional[float] = None,
    end_hz: Optional[float] = None,
    resolution_hz: Optional[float] = None,
    relative_amplitude: Optional[float] = None,
    threshold_db: Optional[float] = None,
    damping_time_s: Optional[float] = None,
) -> tuple[tuple[_F, _F], tuple[_F, _F], str]: ...

# optimize.rs (a design: catalogue indices, returned as bytes) -------------------------------

class GaSession:
    """One optimisation: the problem of a config and the GA's state between generations."""

    def __init__(
        self, kind: str, text: str, base_dir: str, seed: Optional[int] = None, threads: int = 0
    ) -> None: ...
    def config_json(self) -> str: ...
    def ask(self) -> list[bytes]: ...
    def tell(self, designs: list[list[int]], objectives: list[float], elapsed_s: float) -> None: ...
    def evaluate(self, designs: list[list[int]]) -> list[float]: ...
    def stop_reason(self) -> Optional[Literal["generation-limit", "stalled", "stopped"]]: ...
    def generation(self) -> Optional[int]: ...
    def best(self) -> tuple[bytes, float, list[str]]: ...
    def history(self) -> list[tuple[int, float, float, float, int, int, int, float]]: ...
    def scenario_toml(self, design: list[int]) -> str: ...
    def state_json(self) -> Optional[str]: ...
    def restore(self, json: str) -> None: ...
    def run_to_end(self) -> None: ...

def evaluate_designs(config_json: str, base_dir: str, designs: list[list[int]], threads: int) -> list[float]: ...

# sensitivity.rs ---------------------------------------------------------------------------

def sensitivity(
    text: str,
    base_dir: str,
    base_samples: int,
    seed: Optional[int] = None,
    paper_settings: bool = False,
    threads: Optional[int] = None,
    allow_large: bool = False,
) -> tuple[
    list[str],
    list[list[float]],
    list[str],
    list[list[Optional[float]]],
    list[tuple[str, str, float, float, float, float]],
    list[tuple[str, str]],
    str,
]: ...
def saltelli_unit_cube(base_samples: int, group_of: list[int], seed: int = 0) -> list[list[float]]: ...
def sobol_indices(
    y: list[float], base_samples: int, groups: int, resamples: int = 100, level: float = 0.95, seed: int = 0
) -> list[tuple[float, float, float, float]]: ...

# fit.rs -----------------------------------------------------------------------------------

def fit_file(
    path: str, out: Optional[str] = None, overwrite: bool = False, threads: Optional[int] = None
) -> tuple[str, str]: ...
