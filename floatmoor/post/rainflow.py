"""Rainflow cycle counting per ASTM E1049-85 (reapproved 2017), section 5.4.4.

The counting is the standard's three-point algorithm on the sequence of reversals (peaks and
valleys, the first and the last sample included, as in the standard's example):

* read reversals onto a stack; while it holds three or more, let X be the range of the two most
  recent and Y the range of the two before (ranges are absolute differences);
* if X < Y read the next reversal; otherwise, if Y contains the starting point S (the oldest
  reversal on the stack) count Y as one half cycle and drop S, else count Y as one cycle and
  drop its two reversals;
* at the end of the record, count every range left on the stack as one half cycle.

Every counted range carries its mean, (P_a + P_b) / 2 of its two reversals. The kernel is
compiled with :func:`floatmoor._numba.jit`; ``tests/oracles/rainflow_numpy.py`` holds an
independent plain-Python reference (the four-point method with the residue counted as half
cycles), which gives the same cycles.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor._numba import jit

__all__ = ["RainflowCycles", "turning_points", "rainflow_cycles", "aggregate_ranges"]


class RainflowCycles(NamedTuple):
    """Ranges counted by rainflow, one entry per counted (half or full) cycle.

    Attributes
    ----------
    ranges
        Cycle ranges ``|P_a - P_b|``, in the unit of the counted signal.
    means
        Cycle means (P_a + P_b) / 2.
    counts
        0.5 for a half cycle, 1.0 for a full cycle.
    """

    ranges: NDArray[np.float64]
    means: NDArray[np.float64]
    counts: NDArray[np.float64]


def turning_points(values: ArrayLike) -> NDArray[np.float64]:
    """The reversals of a load history: its local peaks and valleys and its two end points.

    Consecutive equal samples count once (a plateau is one point), so a flat peak is one
    reversal. A constant record reduces to its first point.

    Parameters
    ----------
    values
        Samples of the load history, shape (n,), finite.

    Returns
    -------
    ndarray
        The reversal values in time order.
    """
    x = np.asarray(values, dtype=float)
    if x.ndim != 1:
        raise ValueError(f"turning_points expects a 1-D record, got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError("turning_points: the record holds NaN or infinite samples")
    if x.size == 0:
        return x.copy()
    keep = np.concatenate(([True], np.diff(x) != 0.0))
    x = x[keep]
    if x.size < 3:
        return x
    slope = np.sign(np.diff(x))
    interior = slope[1:] != slope[:-1]
    return np.concatenate((x[:1], x[1:-1][interior], x[-1:]))


@jit
def _astm_three_point(points, stack, ranges, means, counts):  # pragma: no cover - compiled
    """ASTM E1049 section 5.4.4 on ``points`` (reversals); returns the number of entries.

    ``stack``, ``ranges``, ``means`` and ``counts`` are work and output arrays of at least
    ``points.size`` entries (a record of n reversals gives at most n - 1 counted ranges).
    The stack lives in ``stack[bottom:top]``; dropping the starting point moves ``bottom``.
    """
    n_out = 0
    bottom = 0
    top = 0
    for k in range(points.size):
        stack[top] = points[k]
        top += 1
        while top - bottom >= 3:
            x_range = abs(stack[top - 1] - stack[top - 2])
            y_range = abs(stack[top - 2] - stack[top - 3])
            if x_range < y_range:
                break
            ranges[n_out] = y_range
            means[n_out] = 0.5 * (stack[top - 2] + stack[top - 3])
            if top - 3 == bottom:
                counts[n_out] = 0.5
                bottom += 1
            else:
                counts[n_out] = 1.0
                stack[top - 3] = stack[top - 1]
                top -= 2
            n_out += 1
    for i in range(bottom, top - 1):
        ranges[n_out] = abs(stack[i + 1] - stack[i])
        means[n_out] = 0.5 * (stack[i + 1] + stack[i])
        counts[n_out] = 0.5
        n_out += 1
    return n_out


def rainflow_cycles(values: ArrayLike) -> RainflowCycles:
    """Rainflow cycles of a load history (ASTM E1049-85, section 5.4.4).

    Parameters
    ----------
    values
        Samples of the load history, shape (n,), in time order. Any uniform or non-uniform
        sampling: only the sequence of reversals matters.

    Returns
    -------
    RainflowCycles
        Ranges, means and counts (0.5 or 1.0) in the order the standard counts them.

    Examples
    --------
    The standard's example (its Fig. 6) gives ranges 3 (0.5), 4 (1.5), 6 (0.5), 8 (1.0) and
    9 (0.5):

    >>> c = rainflow_cycles([-2, 1, -3, 5, -1, 3, -4, 4, -2])
    >>> aggregate_ranges(c.ranges, c.counts)[1].tolist()
    [0.5, 1.5, 0.5, 1.0, 0.5]
    """
    points = turning_points(values)
    n = max(points.size, 1)
    stack = np.empty(n)
    ranges, means, counts = np.empty(n), np.empty(n), np.empty(n)
    n_out = _astm_three_point(points, stack, ranges, means, counts)
    return RainflowCycles(ranges[:n_out], means[:n_out], counts[:n_out])


def aggregate_ranges(ranges: ArrayLike,
                     counts: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Sum the counts of equal ranges.

    Parameters
    ----------
    ranges, counts
        Counted ranges and their counts, e.g. from :func:`rainflow_cycles`.

    Returns
    -------
    unique_ranges, total_counts
        Distinct ranges in increasing order and the summed counts of each.
    """
    r = np.asarray(ranges, dtype=float)
    c = np.asarray(counts, dtype=float)
    unique, inverse = np.unique(r, return_inverse=True)
    totals = np.zeros(unique.size)
    np.add.at(totals, inverse, c)
    return unique, totals
