"""Tension views of one run: fairlead and anchor tension histories, and the tension along
each line (at chosen shape times, with its min/max envelope after the ramp)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

import xarray as xr

from floatmoor.io.shape_samples import line_shape
from floatmoor.plots.series import check_series
from floatmoor.plots.style import figure_title, plain_axes, pyplot, tension_unit
from floatmoor.post.line_shapes import tension_envelope

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["draw_tensions", "draw_tension_along_line"]


def _line_panels(n: int, height: float):
    plt = pyplot()
    fig, axes = plt.subplots(n, 1, figsize=(9.0, height * n + 0.6), squeeze=False)
    return fig, list(axes[:, 0])


def _finish_panel(ax, xlabel: str, ylabel: str, title: str) -> None:
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    plain_axes(ax)
    ax.legend(loc="upper left", bbox_to_anchor=(1.005, 1.0), fontsize=8)


def _finish(fig, dataset: xr.Dataset) -> Figure:
    fig.suptitle(figure_title(dataset.attrs.get("title")), fontsize=11)
    fig.tight_layout()
    return fig


def draw_tensions(dataset: xr.Dataset, *, ramp_duration: float = 0.0) -> Figure:
    """Fairlead and anchor tension histories of every line, one panel per line.

    Parameters
    ----------
    dataset
        A result dataset.
    ramp_duration
        The start-up ramp, shaded [s].

    Raises
    ------
    FigureDataError
        When a series is empty or not finite.
    """
    lines = [str(x) for x in dataset["line"].values]
    factor, unit = tension_unit([dataset["fairlead_tension"].values,
                                 dataset["anchor_tension"].values])
    fig, axes = _line_panels(len(lines), 2.8)
    time = check_series(dataset["time"].values, "time")
    for ax, name in zip(axes, lines):
        for end in ("fairlead", "anchor"):
            y = check_series(dataset[f"{end}_tension"].sel(line=name).values,
                             f"{end} tension of line {name}")
            ax.plot(time, y / factor, lw=1.0, label=end)
        if ramp_duration > 0.0:
            ax.axvspan(0.0, min(ramp_duration, float(time[-1])), color="0.9", label="ramp")
        model = str(dataset["model"].sel(line=name).values)
        _finish_panel(ax, "time [s]", f"tension [{unit}]", f"line {name} ({model})")
    return _finish(fig, dataset)



def draw_tension_along_line(dataset: xr.Dataset, samples: Sequence[int], *,
                            start: float = 0.0) -> Figure:
    """Effective tension against arc length from the anchor, one panel per line: at the shape
    samples ``samples`` and the envelope (min to max at every node) over the shape samples at
    t >= ``start`` [s].

    Parameters
    ----------
    dataset
        A run's result dataset with line shapes.
    samples
        Indices of the shape samples to draw.
    start
        Start of the envelope's window [s] (e.g. the end of the ramp).

    Returns
    -------
    matplotlib.figure.Figure
        The figure (not saved).

    Raises
    ------
    ShapeDataError
        Without shapes, or none complete after ``start``.
    FigureDataError
        When a series is empty or not finite.
    """
    lines = [str(x) for x in dataset["line"].values]
    envelopes = {name: tension_envelope(dataset, name, start=start) for name in lines}
    factor, unit = tension_unit([e.maximum for e in envelopes.values()])
    fig, axes = _line_panels(len(lines), 2.6)
    for ax, name in zip(axes, lines):
        env = envelopes[name]
        s = check_series(env.arc_length, f"arc length of line {name}")
        lo = check_series(env.minimum, f"tension envelope of line {name}") / factor
        hi = check_series(env.maximum, f"tension envelope of line {name}") / factor
        ax.fill_between(s, lo, hi, color="0.85", label=f"envelope {env.start:g} to "
                        f"{env.end:g} s ({env.samples} shapes)")
        ax.plot(s, lo, color="0.5", lw=0.8)
        ax.plot(s, hi, color="0.5", lw=0.8)
        for i, k in enumerate(samples):
            shape = line_shape(dataset, name, k)
            t = check_series(shape.tension, f"tension along line {name} at t = {shape.time:g} s")
            ax.plot(shape.arc_length, t / factor, lw=1.1, color=f"C{(i + 1) % 10}",
                    label=f"t = {shape.time:g} s")
        _finish_panel(ax, "arc length from the anchor [m]", f"tension [{unit}]",
                      f"line {name}: effective tension along the line")
    return _finish(fig, dataset)
