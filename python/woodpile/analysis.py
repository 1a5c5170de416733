"""Cells and analysis: unit cells, effective mass, band gaps, spectra and transmission spectra.

Settings left None take the library's defaults (``woodpile::defaults``, through the extension):
nothing here restates them.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any, Literal, Mapping, Sequence, TypedDict

import numpy as np
import numpy.typing as npt

from . import _core
from .errors import ScenarioError
from .scenario import Scenario

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["Cell", "cells", "effective_mass", "band_gaps", "spectrum", "transmission"]

#: A float64 NumPy array.
FloatArray = npt.NDArray[np.float64]


class Cell(TypedDict):
    """A rod's unit cell as :func:`cells` returns it (SI units)."""

    #: Primary mass [kg].
    primary_mass_kg: float
    #: Resonator masses [kg].
    resonator_masses_kg: FloatArray
    #: Resonator stiffnesses [N/m].
    resonator_stiffnesses_n_per_m: FloatArray
    #: Local resonance frequencies √(k/m)/2π [Hz].
    local_resonances_hz: FloatArray


class BandGaps(TypedDict):
    """Pass bands and gaps as :func:`band_gaps` returns them: arrays of shape (k, 2) [Hz]."""

    #: (lower, upper) edge of each pass band.
    pass_bands_hz: FloatArray
    #: (lower, upper) edge of each gap; an open gap's upper edge is ``inf``.
    gaps_hz: FloatArray


def cells(
    length_mm: float, *, diameter_mm: float | None = None, material: str | None = None, modes: int | None = None
) -> Cell:
    """A rod's unit cell: the paper's Table 1 row for its lengths (20–80 mm, nothing else given),
    otherwise derived by Timoshenko beam theory (``diameter_mm`` and ``material`` default to the
    scenario's defaults). ``primary_mass_kg``, ``resonator_masses_kg``,
    ``resonator_stiffnesses_n_per_m``, ``local_resonances_hz``."""
    primary, masses, stiffnesses = _core.cell(float(length_mm), diameter_mm, material, modes)
    m = np.asarray(masses, dtype=np.float64)
    k = np.asarray(stiffnesses, dtype=np.float64)
    return {
        "primary_mass_kg": primary,
        "resonator_masses_kg": m,
        "resonator_stiffnesses_n_per_m": k,
        "local_resonances_hz": np.sqrt(k / m) / (2 * np.pi),
    }


def _cell_args(cell: Mapping[str, Any]) -> tuple[float, list[float], list[float]]:
    """(primary mass, resonator masses, resonator stiffnesses) of a cell, as plain floats."""
    return (
        float(cell["primary_mass_kg"]),
        [float(m) for m in cell["resonator_masses_kg"]],
        [float(k) for k in cell["resonator_stiffnesses_n_per_m"]],
    )


def effective_mass(
    cell: Mapping[str, Any], frequencies_hz: Sequence[float], *, resonator_ratio: float | None = None
) -> tuple[FloatArray, FloatArray]:
    """M_eff(2πf)/M_total of a cell (as :func:`cells` returns it): (real part, imaginary part),
    the resonators damped at ``resonator_ratio`` (None: the scenario's default
    ``damping.resonator_ratio``, undamped)."""
    primary, masses, stiffnesses = _cell_args(cell)
    ratio = None if resonator_ratio is None else float(resonator_ratio)
    return _core.effective_mass(primary, masses, stiffnesses, [float(f) for f in frequencies_hz], ratio)


def band_gaps(cell: Mapping[str, Any], beta: float, precompression_n: float) -> BandGaps:
    """Pass bands and gaps [Hz] of a homogeneous chain of ``cell`` with contact coefficient β
    [N/m^1.5] under a static force [N] (the linearised Bloch relation): arrays of shape (k, 2);
    an open gap's upper edge is ``inf``."""
    primary, masses, stiffnesses = _cell_args(cell)
    passes, gaps = _core.band_gaps(primary, masses, stiffnesses, float(beta), float(precompression_n))
    return {"pass_bands_hz": np.array(passes, dtype=np.float64), "gaps_hz": np.array(gaps, dtype=np.float64)}


def spectrum(
    signal: Sequence[float] | FloatArray,
    sample_interval_s: float,
    scaling: Literal["fourier", "amplitude"] = "fourier",
) -> tuple[FloatArray, FloatArray]:
    """One-sided spectrum of a uniformly sampled signal: (frequencies [Hz], values).

    ``scaling="fourier"`` (default) gives the magnitude of the Fourier transform
    |F̂(f)| in the signal's unit times seconds (N/Hz for a force): for a transient (an impact, a
    blast) it does not depend on the record length or the sample interval, so spectra of two
    runs compare directly; the figures use it. ``scaling="amplitude"`` gives the sine amplitude
    (N), right for steady signals only: the same pulse in a record twice as long reads half.
    Another name raises :class:`~woodpile.errors.ScenarioError` with ``field == "scaling"``; a
    signal that is not one-dimensional, one with ``field == "signal"``."""
    values = np.asarray(signal, dtype=np.float64)
    if values.ndim != 1:
        raise ScenarioError(
            f"invalid signal of shape {values.shape}: must be one-dimensional, one value per sample "
            "(for a run's forces, one column: forces[:, k])",
            "signal",
            f"an array of shape {values.shape}",
            "a one-dimensional sequence of samples",
        )
    return _core.spectrum(values.tolist(), float(sample_interval_s), scaling)


def transmission(
    scenario: Scenario | str,
    *,
    start_hz: float | None = None,
    end_hz: float | None = None,
    resolution_hz: float | None = None,
    relative_amplitude: float | None = None,
    threshold_db: float | None = None,
    damping_time_s: float | None = None,
) -> tuple[pd.DataFrame, dict[str, Any]]:
    """The transmission spectrum of a scenario's preloaded chain (as ``woodpile transmission``):
    a DataFrame indexed by ``frequency_hz`` with ``transmission``, ``transmission_db`` and
    ``linear_transmission_db`` (the exact linear response of the finite preloaded chain), and
    the record of ``transmission.json`` (measured stop bands, predicted gaps, the edge table).

    Settings left None take ``woodpile transmission``'s defaults (the library's
    ``woodpile::defaults::TRANSMISSION_*``, applied by the extension); ``damping_time_s`` is
    the on-site damping time added to a chain without damping for the measurement (None: 20 ms;
    0: the lossless chain), refused for a chain with damping of its own.
    """
    import pandas as pd

    if isinstance(scenario, str):
        scenario = Scenario.builtin(scenario)

    def opt(x: float | None) -> float | None:
        return None if x is None else float(x)

    (f, t), (db, linear_db), record = _core.transmission(
        scenario.to_toml(),
        str(scenario.base_dir),
        scenario.name,
        opt(start_hz),
        opt(end_hz),
        opt(resolution_hz),
        opt(relative_amplitude),
        opt(threshold_db),
        opt(damping_time_s),
    )
    table = pd.DataFrame(
        {"transmission": t, "transmission_db": db, "linear_transmission_db": linear_db},
        index=pd.Index(f, name="frequency_hz"),
    )
    parsed: dict[str, Any] = json.loads(record)
    return table, parsed
