"""Plots of result datasets (matplotlib is imported only when a plot is asked for)."""

from __future__ import annotations

import textwrap
from pathlib import Path

import xarray as xr

from floatmoor.io.output_files import atomic_target

__all__ = ["plot_tensions", "SUPPORTED_FORMATS"]

#: File formats the Agg-based backends write.
SUPPORTED_FORMATS = (".png", ".pdf", ".svg")
#: Characters per line of the figure title: about what 9 inches hold at 11 pt.
_TITLE_WRAP = 95


def plot_tensions(dataset: xr.Dataset, path: str | Path, *, ramp_duration: float = 0.0) -> None:
    """Fairlead and anchor tension histories of every line, one panel per line.

    Parameters
    ----------
    dataset
        A result dataset.
    path
        Image file (.png, .pdf or .svg).
    ramp_duration
        The motion ramp, shaded [s].

    Raises
    ------
    OutputWriteError
        When the image cannot be written (written atomically: an old file is kept).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lines = list(dataset["line"].values)
    fig, axes = plt.subplots(len(lines), 1, figsize=(9.0, 2.8 * len(lines) + 0.6), sharex=True,
                             squeeze=False)
    time = dataset["time"].values
    for ax, name in zip(axes[:, 0], lines):
        ax.plot(time, dataset["fairlead_tension"].sel(line=name), lw=1.0, label="fairlead")
        ax.plot(time, dataset["anchor_tension"].sel(line=name), lw=1.0, label="anchor")
        if ramp_duration > 0.0:
            ax.axvspan(0.0, ramp_duration, color="0.9", label="ramp")
        model = str(dataset["model"].sel(line=name).values)
        ax.set_ylabel("tension [N]")
        ax.set_title(f"line {name} ({model})", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(loc="upper left", bbox_to_anchor=(1.005, 1.0), fontsize=8)
    axes[-1, 0].set_xlabel("time [s]")
    # the title carries the run's overrides: wrapped, and the image grown to hold it all
    fig.suptitle(textwrap.fill(str(dataset.attrs.get("title", "")), _TITLE_WRAP), fontsize=11)
    fig.tight_layout()
    try:
        with atomic_target(path, suffix=Path(path).suffix) as tmp:
            fig.savefig(tmp, dpi=120, bbox_inches="tight")
    finally:
        plt.close(fig)
