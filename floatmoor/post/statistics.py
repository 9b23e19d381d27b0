"""Statistics of time series: moments, extremes and per-cycle maxima.

Two levels: NumPy functions on one record (:func:`channel_statistics`, :func:`cycle_maxima`)
and xarray functions on any DataArray with a ``time`` dimension, vectorised over its other
dimensions (:func:`time_window`, :func:`time_statistics`), e.g. ``ds["fairlead_tension"]``
(line, time) of a floatmoor result dataset.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import NDArray

__all__ = ["channel_statistics", "cycle_maxima", "time_window", "time_statistics"]

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
    if time.size == 0 or not (np.isfinite(period) and period > 0.0):
        return np.empty(0)
    # round-off slack relative to the times (not the period: a period of 1e308 s must not
    # make the slack, and with it the cycle count, astronomically large)
    eps = _TIME_EPS * max(abs(float(time[-1])), abs(start), 1.0)
    n_cycles = int(min(np.floor((time[-1] - start + eps) / period), time.size))
    if n_cycles < 1:  # not one complete cycle: no cycle statistics
        return np.empty(0)
    # the cycle of each sample; cycles are counted once, whatever their number
    cycle = np.floor((time - start + eps) / period)
    inside = (cycle >= 0) & (cycle < n_cycles)
    if not np.any(inside):
        return np.empty(0)
    index = cycle[inside].astype(np.int64)
    maxima = np.full(n_cycles, -np.inf)
    np.maximum.at(maxima, index, values[inside])
    return maxima[np.isin(np.arange(n_cycles), index)]


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


def time_window(data: xr.DataArray, *, start: float) -> xr.DataArray:
    """The samples of ``data`` at times ``t >= start`` (the transient before ``start`` cut).

    Parameters
    ----------
    data
        A DataArray with a ``time`` dimension and coordinate [s], increasing.
    start
        First time kept [s]; a sample within round-off of ``start`` is kept.

    Returns
    -------
    DataArray
        The window, attributes kept.

    Raises
    ------
    ValueError
        Without a ``time`` dimension, or when fewer than two samples remain.
    """
    if "time" not in data.dims:
        raise ValueError(f"expected a DataArray with a 'time' dimension, got dims {data.dims}")
    time = np.asarray(data["time"].values, dtype=float)
    inside = time >= start - _TIME_EPS * max(abs(start), 1.0)
    if np.count_nonzero(inside) < 2:
        raise ValueError(f"fewer than two samples at t >= {start} s (record ends at "
                         f"{time[-1] if time.size else 'no sample'} s)")
    return data.isel(time=np.flatnonzero(inside))


def time_statistics(data: xr.DataArray, *, start: float) -> xr.Dataset:
    """Mean, standard deviation, min, max, skewness and kurtosis over time from ``start`` on.

    Moments are population (biased) moments of the window, as :func:`channel_statistics`:
    ``std = sqrt(m2)``, ``skewness = m3 / m2^1.5`` and the plain (Pearson) ``kurtosis =
    m4 / m2^2``, which is 3 for a Gaussian process (not the excess kurtosis), with
    ``m_k`` the k-th central moment. Skewness and kurtosis are NaN for a constant record.

    Parameters
    ----------
    data
        A DataArray with a ``time`` dimension, e.g. ``ds["fairlead_tension"]``; statistics
        are taken per element of its other dimensions.
    start
        Samples before ``start`` [s] (the transient) are excluded.

    Returns
    -------
    Dataset
        Variables ``mean``, ``std``, ``min``, ``max`` (in the unit of ``data``), ``skewness``
        and ``kurtosis`` (dimensionless), each with ``units`` and ``long_name``; attribute
        ``window_start`` [s].
    """
    window = time_window(data, start=start)
    units = data.attrs.get("units", "")
    name = data.attrs.get("long_name", data.name or "series")
    mean = window.mean("time")
    deviation = window - mean
    m2 = (deviation**2).mean("time")
    m3 = (deviation**3).mean("time")
    m4 = (deviation**4).mean("time")
    positive = m2 > 0.0
    safe_m2 = xr.where(positive, m2, 1.0)
    skewness = xr.where(positive, m3 / safe_m2**1.5, np.nan)
    kurtosis = xr.where(positive, m4 / safe_m2**2, np.nan)
    out = xr.Dataset({
        "mean": mean.assign_attrs(long_name=f"mean of {name}", units=units),
        "std": np.sqrt(m2).assign_attrs(long_name=f"standard deviation of {name}",
                                        units=units),
        "min": window.min("time").assign_attrs(long_name=f"minimum of {name}", units=units),
        "max": window.max("time").assign_attrs(long_name=f"maximum of {name}", units=units),
        "skewness": skewness.assign_attrs(long_name=f"skewness of {name}", units="1"),
        "kurtosis": kurtosis.assign_attrs(
            long_name=f"kurtosis (Pearson, 3 for a Gaussian) of {name}", units="1"),
    })
    out.attrs["window_start"] = float(start)
    return out
