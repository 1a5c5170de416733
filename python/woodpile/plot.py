"""Matplotlib figures of runs and optimisations (``pip install "woodpile[plot]"``).

Each function draws on ``ax`` (a new figure when None) and returns the Axes; units are in the
labels. They take a :class:`woodpile.Run` (computed, or read back by :func:`woodpile.load_run`)
or an :class:`woodpile.OptimizeResult`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Sequence, Union

import numpy as np

from .analysis import spectrum

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes

    from .optimize import BreederGA, OptimizeResult
    from .run import Run

__all__ = ["force_map", "energy_map", "spectra", "convergence"]


def _integer_rows(ax: Axes) -> None:
    """Integer ticks on the y axis (contacts, layers)."""
    from matplotlib.ticker import MaxNLocator

    ax.yaxis.set_major_locator(MaxNLocator(integer=True))


def _axes(ax: Axes | None) -> Axes:
    """``ax``, or the Axes of a new figure."""
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(7, 3.5), constrained_layout=True)
    return ax


def force_map(run: Run, ax: Axes | None = None, *, cmap: str = "viridis") -> Axes:
    """Contact force [N], contact × time [ms] (the paper's Figs. 5 and 9 a, c, e, g)."""
    ax = _axes(ax)
    t_ms = run.time_s * 1e3
    f = run.forces_n
    image = ax.pcolormesh(t_ms, np.arange(f.shape[1]), f.T, shading="nearest", cmap=cmap)
    ax.figure.colorbar(image, ax=ax, label="contact force [N]")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("contact (0 = striker or load, N = wall)")
    _integer_rows(ax)
    return ax


def energy_map(run: Run, ax: Axes | None = None, *, cmap: str = "magma") -> Axes:
    """Layer energy over the injected energy [%], layer × time [ms] (the paper's Fig. 6). The
    injected energy is the initial energy for an impact, the largest input work otherwise."""
    ax = _axes(ax)
    e = run.energy_j
    injected = max(float(e[0].sum() + run.wall_energy_j[0]), float(np.max(np.abs(run.input_work_j))))
    image = ax.pcolormesh(run.time_s * 1e3, np.arange(e.shape[1]), 100 * e.T / injected, shading="nearest", cmap=cmap)
    ax.figure.colorbar(image, ax=ax, label="layer energy / injected [%]")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("layer (0 = striker or load)")
    _integer_rows(ax)
    return ax


def spectra(
    run: Run, contacts: Sequence[int] | None = None, ax: Axes | None = None, *, max_frequency_hz: float = 60e3
) -> Axes:
    """Spectra of contact forces, the Fourier transform's magnitude |F̂(f)| [N/Hz] (independent of
    the record length), against frequency [kHz] (the paper's Fig. 9 b, d, f, h); by default the
    first element contact and the wall."""
    ax = _axes(ax)
    n = run.forces_n.shape[1] - 1
    dt = float(run.time_s[1] - run.time_s[0])
    for c in contacts if contacts is not None else [1, n]:
        f, a = spectrum(run.forces_n[:, c], dt)
        keep = (f > 0) & (f <= max_frequency_hz)
        ax.semilogy(f[keep] * 1e-3, a[keep], label=f"contact {c}")
    ax.set_xlabel("frequency [kHz]")
    ax.set_ylabel("|F̂(f)| [N/Hz]")
    ax.legend()
    return ax


def convergence(result: Union[OptimizeResult, BreederGA, pd.DataFrame], ax: Axes | None = None) -> Axes:
    """Best and mean objective per generation of an optimisation (an ``OptimizeResult``, a
    ``BreederGA`` or its history DataFrame)."""
    ax = _axes(ax)
    found: Any = getattr(result, "history", result)
    history: pd.DataFrame = found() if callable(found) else found
    ax.plot(history.index, history["best"], marker="o", label="best")
    ax.plot(history.index, history["mean"], label="mean")
    ax.set_xlabel("generation")
    ax.set_ylabel("objective")
    ax.legend()
    return ax
