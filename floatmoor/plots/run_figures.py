"""Every view that applies to a run, for ``floatmoor run --plot OUT.png``: the tension
histories in OUT.png, and beside it OUT_motions.png (floater runs), OUT_shapes.png and
OUT_line_tension.png (runs that record line shapes)."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

import numpy as np
import xarray as xr

from floatmoor.io.shape_samples import complete_shape_samples, has_shapes, \
    nearest_shape_samples
from floatmoor.plots.context import RunContext, run_context
from floatmoor.plots.motions import draw_body_motions
from floatmoor.plots.shapes import draw_line_shapes
from floatmoor.plots.style import save_figure
from floatmoor.plots.tensions import draw_tension_along_line, draw_tensions

__all__ = ["figure_paths", "default_shape_samples", "envelope_start", "plot_run",
           "plot_shape_views", "DEFAULT_SHAPE_TIMES"]

#: Shape samples drawn when no times are chosen: evenly spread from the end of the ramp to
#: the end of the run (the first and last included).
DEFAULT_SHAPE_TIMES = 4


def figure_paths(path: str | Path, *, floater: bool, shapes: bool) -> dict[str, Path]:
    """The files ``--plot PATH`` writes: {view: file}; the views after ``tensions`` go beside
    ``path`` with a suffix on its stem."""
    path = Path(path)
    out = {"tensions": path}
    kinds = (["motions"] if floater else []) + (["shapes", "line_tension"] if shapes else [])
    for kind in kinds:
        out[kind] = path.with_name(f"{path.stem}_{kind}{path.suffix}")
    return out


def default_shape_samples(dataset: xr.Dataset, start: float,
                          count: int = DEFAULT_SHAPE_TIMES) -> list[int]:
    """``count`` complete shape samples evenly spread over t >= ``start`` (all samples from
    the first complete one when none follows ``start``)."""
    samples = complete_shape_samples(dataset)
    times = np.asarray(dataset["shape_time"].values, dtype=float)[samples]
    after = samples[times >= start] if np.any(times >= start) else samples
    picks = np.unique(np.round(np.linspace(0, after.size - 1, min(count, after.size))))
    return [int(after[int(i)]) for i in picks]


def envelope_start(dataset: xr.Dataset, ramp: float) -> float:
    """Start of the tension envelope [s]: the end of the ramp, or 0 when the run's shapes
    end within the ramp (a short look at a case)."""
    samples = complete_shape_samples(dataset)
    last = float(dataset["shape_time"].values[samples[-1]])
    return ramp if last >= ramp else 0.0


def plot_run(dataset: xr.Dataset, path: str | Path,
             times: Sequence[float] | None = None) -> dict[str, Path]:
    """Draw every view that applies to ``dataset`` (:func:`figure_paths`).

    Parameters
    ----------
    dataset
        A run's result dataset.
    path
        The tension-history image; the other views are written beside it.
    times
        Times of the line shapes drawn [s] (the nearest shape samples); None: see
        :data:`DEFAULT_SHAPE_TIMES`.

    Returns
    -------
    dict
        {view: file written}.

    Raises
    ------
    ShapeDataError
        When a time is outside the recorded shapes.
    FigureDataError
        When a series is empty or not finite.
    OutputWriteError
        When an image cannot be written.
    """
    context = run_context(dataset)
    paths = figure_paths(path, floater="body_displacement" in dataset,
                         shapes=has_shapes(dataset))
    save_figure(draw_tensions(dataset, ramp_duration=context.ramp), paths["tensions"])
    if "motions" in paths:
        save_figure(draw_body_motions(dataset, ramp_duration=context.ramp), paths["motions"])
    if "shapes" in paths:
        plot_shape_views(dataset, paths["shapes"], paths["line_tension"], start=context.ramp,
                         times=times, context=context)
    return paths


def plot_shape_views(dataset: xr.Dataset, shapes_path: str | Path, tension_path: str | Path,
                     *, start: float, times: Sequence[float] | None = None,
                     context: RunContext | None = None) -> None:
    """The line shapes and the tension along the lines of a run with shapes.

    Parameters
    ----------
    start
        End of the transient [s]: the default shape times and the tension envelope begin
        there (:func:`envelope_start`).
    times
        Times of the shapes drawn [s]; None: :func:`default_shape_samples` after ``start``.
    context
        The run's :func:`run_context` (re-read from ``dataset`` when None).

    Raises
    ------
    ShapeDataError, FigureDataError, OutputWriteError
        As :func:`plot_run`.
    """
    context = run_context(dataset) if context is None else context
    samples = (default_shape_samples(dataset, start) if times is None
               else nearest_shape_samples(dataset, times, "--plot-times"))
    save_figure(draw_line_shapes(dataset, samples, context), shapes_path)
    save_figure(draw_tension_along_line(dataset, samples, start=envelope_start(dataset, start)),
                tension_path)
