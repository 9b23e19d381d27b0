"""The check every plotted series passes: a figure is never saved with a missing curve."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.errors import FloatmoorError

__all__ = ["FigureDataError", "check_series"]


class FigureDataError(FloatmoorError, ValueError):
    """A series to plot is empty or holds NaN or infinite samples."""


def check_series(values: ArrayLike, what: str) -> NDArray[np.float64]:
    """The samples of ``values`` as floats, after checking they can be plotted.

    Parameters
    ----------
    values
        The series.
    what
        Description for the message (figure, run, line or DOF).

    Raises
    ------
    FigureDataError
        When the series is empty or any sample is NaN or infinite.
    """
    x = np.asarray(values, dtype=float)
    if x.size == 0:
        raise FigureDataError(f"{what}: expected a non-empty series to plot, found no samples")
    bad = ~np.isfinite(x)
    if np.any(bad):
        raise FigureDataError(f"{what}: expected finite samples to plot, found "
                              f"{int(bad.sum())} NaN or infinite of {x.size}")
    return x
