"""What a mooring engineer reads off the recorded line shapes: touchdown points and the
envelope of the tension along each line.

Touchdown point: the point of the line at the arc length ``laid_length`` from the anchor (the
unstretched length resting on the seabed that every line model records with each output
sample), interpolated linearly between the shape's nodes; a line with nothing laid has none.
Tension envelope: the smallest and largest effective tension at every node over the shape
samples of a time window (the transient before its start excluded).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.io.shape_samples import LineShape, ShapeDataError, complete_shape_samples, \
    line_shape, node_count

__all__ = ["TensionEnvelope", "touchdown_point", "tension_envelope", "LAID_EPS"]

#: Laid lengths at or below this [m] count as none (a line just lifting off records
#: round-off values).
LAID_EPS = 1e-9


@dataclass(frozen=True)
class TensionEnvelope:
    """Extremes of the effective tension along one line over a window of shape samples.

    Attributes
    ----------
    arc_length
        Unstretched arc length from the anchor [m], shape (n,).
    minimum, maximum
        Smallest and largest tension at each node [N], shape (n,).
    start, end
        First and last shape sample time of the window [s].
    samples
        Shape samples in the window.
    """

    arc_length: NDArray[np.float64]
    minimum: NDArray[np.float64]
    maximum: NDArray[np.float64]
    start: float
    end: float
    samples: int


def touchdown_point(dataset: xr.Dataset, shape: LineShape) -> NDArray[np.float64] | None:
    """Position [m] of the touchdown point of ``shape``, or None when nothing is laid (or the
    dataset records no laid length).

    The laid length is taken at the output sample of the shape's time.
    """
    if "laid_length" not in dataset:
        return None
    laid = dataset["laid_length"].sel(line=shape.line).sel(time=shape.time, method="nearest")
    value = float(laid.values)
    if not np.isfinite(value) or value <= LAID_EPS:
        return None
    s = shape.arc_length
    value = min(value, float(s[-1]))
    return np.array([np.interp(value, s, shape.position[:, c]) for c in range(3)])


def tension_envelope(dataset: xr.Dataset, line: str, *, start: float = 0.0) -> TensionEnvelope:
    """Node-wise min and max of the tension along ``line`` over the complete shape samples at
    times >= ``start`` [s].

    Parameters
    ----------
    dataset
        A run's result dataset with line shapes.
    line
        The line's name.
    start
        Start of the window [s] (e.g. the end of the ramp).

    Returns
    -------
    TensionEnvelope
        The envelope along the line's nodes.

    Raises
    ------
    ShapeDataError
        Without shapes, or with no complete shape sample at or after ``start``.
    """
    samples = complete_shape_samples(dataset)
    times = np.asarray(dataset["shape_time"].values, dtype=float)
    inside = samples[times[samples] >= start - 1e-9 * max(abs(start), 1.0)]
    if inside.size == 0:
        raise ShapeDataError(f"expected line shapes at t >= {start:g} s (after the ramp), "
                             f"found the last complete one at t = {times[samples[-1]]:g} s")
    n = node_count(dataset["arc_length"].sel(line=line).values)
    ten = np.asarray(dataset["shape_tension"].sel(line=line).transpose("shape_time", "node")
                     .values, dtype=float)[inside, :n]
    first = line_shape(dataset, line, int(inside[0]))
    return TensionEnvelope(arc_length=first.arc_length, minimum=ten.min(axis=0),
                           maximum=ten.max(axis=0), start=float(times[inside[0]]),
                           end=float(times[inside[-1]]), samples=int(inside.size))
