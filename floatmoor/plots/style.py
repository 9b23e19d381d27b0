"""Shared look of floatmoor's run figures: plain tick labels, units, the atomic save.

Tick labels are plain numbers (no offset such as ``+3.1`` and no ``1e-5`` multiplier above
the axis), so every value reads directly in the unit of its axis label. Tensions are drawn in
the SI unit that keeps them between 1 and 1000 for the largest of a figure (N for a tank
model's chain, kN or MN at full scale), named in the label.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from floatmoor.io.output_files import atomic_target

__all__ = ["SUPPORTED_FORMATS", "DPI", "pyplot", "plain_axes", "tension_unit", "save_figure",
           "figure_title"]

#: File formats the Agg-based backends write.
SUPPORTED_FORMATS = (".png", ".pdf", ".svg")
#: Resolution of saved figures [dots per inch].
DPI = 110
#: Characters per line of a figure title: about what 9 inches hold at 11 pt.
TITLE_WRAP = 95
#: Tension units by size: (factor to divide N by, label); the largest whose factor is at most
#: the largest tension of the figure is used.
_TENSION_UNITS = ((1.0, "N"), (1e3, "kN"), (1e6, "MN"))


def pyplot():
    """matplotlib.pyplot on the Agg backend (no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plain_axes(ax) -> None:
    """Plain tick labels on both axes: no offset, no scientific multiplier."""
    from matplotlib.ticker import ScalarFormatter

    for axis in (ax.xaxis, ax.yaxis):
        if isinstance(axis.get_major_formatter(), ScalarFormatter):
            formatter = ScalarFormatter(useOffset=False)
            formatter.set_scientific(False)
            axis.set_major_formatter(formatter)


def tension_unit(values: ArrayLike) -> tuple[float, str]:
    """(divisor, unit name) for tensions of this size in N (N, kN or MN)."""
    top = float(np.nanmax(np.abs(np.asarray(values, dtype=float)))) if np.size(values) else 0.0
    chosen = _TENSION_UNITS[0]
    for factor, name in _TENSION_UNITS:
        if top >= factor:
            chosen = (factor, name)
    return chosen


def figure_title(dataset_title: object) -> str:
    """A run's title wrapped to the figure width."""
    return textwrap.fill(str(dataset_title or ""), TITLE_WRAP)


def save_figure(fig, path: str | Path) -> Path:
    """Save ``fig`` to ``path`` atomically (an old file is kept on failure) and close it.

    Raises
    ------
    OutputWriteError
        When the image cannot be written.
    """
    plt = pyplot()
    try:
        with atomic_target(path, suffix=Path(path).suffix) as tmp:
            fig.savefig(tmp, dpi=DPI, bbox_inches="tight")
    finally:
        plt.close(fig)
    return Path(path)
