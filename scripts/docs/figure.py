"""Figures of the executed tutorials: a matplotlib figure as an inline PNG, so every figure of
the site is drawn by its build and none is committed."""

from __future__ import annotations

import base64
import io
from typing import Any


def show(fig: Any, alt: str = "figure") -> None:
    """Print `fig` as an `<img>` with the PNG inline (a markdown-exec block with html="true")."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    print(f'<img alt="{alt}" src="data:image/png;base64,{data}">')


def show_png(path: str, alt: str = "figure") -> None:
    """Print a PNG file the build wrote (a woodpile figure) as an inline `<img>`."""
    with open(path, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    print(f'<img alt="{alt}" src="data:image/png;base64,{data}">')
