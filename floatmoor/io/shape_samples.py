"""Line shapes as a result dataset stores them, read back per line and shape sample.

A run records its lines' shapes every ``simulation.shape_output_interval`` (variables
``shape_position``, ``shape_tension``, ``arc_length`` on the ``shape_time`` axis,
:mod:`floatmoor.io.dataset`). Lines share one node axis: a line with fewer nodes than the
longest repeats its last node (and arc length) to fill it, and a partial run's unfinished
samples hold NaN. These functions undo both: the nodes of a line up to its last distinct arc
length, and the shape samples whose every value is finite.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.errors import FloatmoorError

__all__ = ["ShapeDataError", "LineShape", "has_shapes", "has_complete_shapes", "node_count", "line_shape",
           "complete_shape_samples", "nearest_shape_samples",
           "window_samples"]

#: Variables a dataset must hold for its line shapes to be read.
SHAPE_VARIABLES = ("shape_position", "shape_tension", "arc_length")


class ShapeDataError(FloatmoorError, ValueError):
    """A result dataset holds no usable line shapes, or a requested time is not among them."""


@dataclass(frozen=True)
class LineShape:
    """One line at one shape sample.

    Attributes
    ----------
    line
        Line name.
    time
        Shape sample time [s].
    arc_length
        Unstretched arc length of the nodes from the anchor [m], shape (n,).
    position
        Node positions [m], shape (n, 3).
    tension
        Effective tension at the nodes [N], shape (n,).
    """

    line: str
    time: float
    arc_length: NDArray[np.float64]
    position: NDArray[np.float64]
    tension: NDArray[np.float64]


def has_shapes(dataset: xr.Dataset) -> bool:
    """True when ``dataset`` holds line shapes (one sample or more)."""
    return (all(name in dataset.variables for name in SHAPE_VARIABLES)
            and dataset.sizes.get("shape_time", 0) > 0)


def has_complete_shapes(dataset: xr.Dataset) -> bool:
    """True when ``dataset`` holds a shape sample with finite values on every line (a
    partial run may hold none)."""
    if not has_shapes(dataset):
        return False
    try:
        complete_shape_samples(dataset)
    except ShapeDataError:
        return False
    return True


def node_count(arc_length: NDArray[np.float64]) -> int:
    """Nodes of one line on the shared node axis: up to the last increase of its arc length
    (the nodes after it repeat the line's last node)."""
    s = np.asarray(arc_length, dtype=float)
    rising = np.flatnonzero(np.diff(s) > 0.0)
    return int(rising[-1]) + 2 if rising.size else 1


def _require(dataset: xr.Dataset) -> None:
    if not has_shapes(dataset):
        raise ShapeDataError("the result holds no line shapes: expected the variables "
                             f"{', '.join(SHAPE_VARIABLES)} on a 'shape_time' axis (run the "
                             "case with simulation.shape_output_interval set, e.g. --set "
                             "simulation.shape_output_interval=0.1)")


def line_shape(dataset: xr.Dataset, line: str, sample: int) -> LineShape:
    """The nodes of ``line`` at shape sample ``sample`` (the padding of the node axis cut).

    Raises
    ------
    ShapeDataError
        Without shapes in ``dataset``.
    """
    _require(dataset)
    arc = np.asarray(dataset["arc_length"].sel(line=line).values, dtype=float)
    n = node_count(arc)
    pos = dataset["shape_position"].sel(line=line).isel(shape_time=sample)
    ten = dataset["shape_tension"].sel(line=line).isel(shape_time=sample)
    return LineShape(line=str(line), time=float(dataset["shape_time"].values[sample]),
                     arc_length=arc[:n],
                     position=np.asarray(pos.transpose("node", "component").values,
                                         dtype=float)[:n],
                     tension=np.asarray(ten.values, dtype=float)[:n])


def complete_shape_samples(dataset: xr.Dataset) -> NDArray[np.int64]:
    """Indices of the shape samples whose positions and tensions are finite on every line
    (a partial run's unfinished samples hold NaN).

    Raises
    ------
    ShapeDataError
        Without shapes, or when no sample is complete.
    """
    _require(dataset)
    pos = np.asarray(dataset["shape_position"].transpose("shape_time", ...).values)
    ten = np.asarray(dataset["shape_tension"].transpose("shape_time", ...).values)
    finite = (np.isfinite(pos).reshape(pos.shape[0], -1).all(axis=1)
              & np.isfinite(ten).reshape(ten.shape[0], -1).all(axis=1))
    samples = np.flatnonzero(finite)
    if samples.size == 0:
        raise ShapeDataError("expected line shapes with finite values, found none complete "
                             f"among {pos.shape[0]} shape samples")
    return samples


def nearest_shape_samples(dataset: xr.Dataset, times: Sequence[float],
                          option: str = "times") -> list[int]:
    """The complete shape sample nearest to each of ``times`` [s].

    Raises
    ------
    ShapeDataError
        When a time lies outside the complete samples by more than half a shape interval.
    """
    samples = complete_shape_samples(dataset)
    t = np.asarray(dataset["shape_time"].values, dtype=float)[samples]
    half = 0.5 * float(np.min(np.diff(t))) if t.size > 1 else 0.0
    out = []
    for value in times:
        k = int(np.argmin(np.abs(t - value)))
        if not np.isfinite(value) or abs(t[k] - value) > half + 1e-9 * max(abs(value), 1.0):
            raise ShapeDataError(f"{option}: expected times within the line-shape samples "
                                 f"({t[0]:g} to {t[-1]:g} s), found {value:g} s")
        out.append(int(samples[k]))
    return out


def window_samples(dataset: xr.Dataset, *, start: float | None = None,
                   end: float | None = None, every: int = 1,
                   option: str = "--start/--end") -> list[int]:
    """Every ``every``-th complete shape sample at ``start`` <= t <= ``end`` [s] (None: the
    first or the last complete sample).

    Raises
    ------
    ShapeDataError
        Without shapes, or when no complete sample lies in the window.
    """
    samples = complete_shape_samples(dataset)
    t = np.asarray(dataset["shape_time"].values, dtype=float)[samples]
    lo = t[0] if start is None else start
    hi = t[-1] if end is None else end
    tol = 1e-9 * max(abs(lo), abs(hi), 1.0)
    inside = samples[(t >= lo - tol) & (t <= hi + tol)]
    if inside.size == 0:
        raise ShapeDataError(f"{option}: expected a window holding line-shape samples (the "
                             f"complete ones span {t[0]:g} to {t[-1]:g} s), found {lo:g} to "
                             f"{hi:g} s")
    return [int(k) for k in inside[::every]]
