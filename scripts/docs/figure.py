"""Figures of the executed tutorials: a matplotlib figure as an inline PNG, so every figure of
the site is drawn by its build and none is committed."""

from __future__ import annotations

import base64
import io
from typing import Any


def png(fig: Any, alt: str = "figure") -> str:
    """`fig` as an `<img>` with the PNG inline, for a markdown-exec block with html="true" to
    print (markdown-exec captures the block's own `print` only)."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    return f'<img alt="{alt}" src="data:image/png;base64,{data}">'


def png_file(path: str, alt: str = "figure") -> str:
    """A PNG file the build wrote (a woodpile figure) as an inline `<img>`."""
    with open(path, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    return f'<img alt="{alt}" src="data:image/png;base64,{data}">'
