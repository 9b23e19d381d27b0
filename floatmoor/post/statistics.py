"""Statistics of tension time series: moments, extremes and per-cycle maxima."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["channel_statistics", "cycle_maxima"]

#: Relative slack on times when cutting cycles, to absorb round-off in t = k * dt [-].
_TIME_EPS = 1e-9


def cycle_maxima(time: NDArray[np.float64], values: NDArray[np.float64], *, start: float,
                 period: float) -> NDArray[np.float64]:
    """Maximum of each complete cycle ``[start + k T, start + (k + 1) T)``.

    Parameters
    ----------
    time
        Sample times [s], increasing.
    values
        Samples.
    start
        Start of the first cycle [s].
    period
        Cycle length T [s].

    Returns
    -------
    ndarray
        One maximum per cycle that the record covers completely.
    """
    time = np.asarray(time, dtype=float)
    values = np.asarray(values, dtype=float)
    eps = _TIME_EPS * max(period, 1.0)
    n_cycles = int(np.floor((time[-1] - start) / period + eps)) if time.size else 0
    maxima = []
    for k in range(max(n_cycles, 0)):
        a, b = start + k * period, start + (k + 1) * period
        inside = (time >= a - eps) & (time < b - eps)
        if np.any(inside):
            maxima.append(values[inside].max())
    return np.array(maxima)


def channel_statistics(time: NDArray[np.float64], values: NDArray[np.float64], *, start: float,
                       period: float | None = None) -> dict[str, float | int | None]:
    """Mean, standard deviation, min, max from ``start`` on, and per-cycle maxima.

    Parameters
    ----------
    time
        Sample times [s].
    values
        Samples.
    start
        Start of the window (e.g. the end of the ramp) [s].
    period
        Motion period [s], or None for non-periodic motion.

    Returns
    -------
    dict
        ``mean``, ``std`` (population), ``min``, ``max``, ``mean_cycle_max`` and ``n_cycles``
        (None and 0 without a period or a complete cycle), ``window_start``.
    """
    time = np.asarray(time, dtype=float)
    values = np.asarray(values, dtype=float)
    inside = time >= start - _TIME_EPS * max(abs(start), 1.0)
    if not np.any(inside):
        inside = np.ones_like(time, dtype=bool)
        start = float(time[0]) if time.size else 0.0
    window = values[inside]
    stats: dict[str, float | int | None] = {
        "mean": float(window.mean()),
        "std": float(window.std()),
        "min": float(window.min()),
        "max": float(window.max()),
        "mean_cycle_max": None,
        "n_cycles": 0,
        "window_start": float(start),
    }
    if period is not None:
        maxima = cycle_maxima(time, values, start=start, period=period)
        if maxima.size:
            stats["mean_cycle_max"] = float(maxima.mean())
            stats["n_cycles"] = int(maxima.size)
    return stats
