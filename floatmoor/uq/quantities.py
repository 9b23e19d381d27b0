"""Quantities of interest from the results of a study's runs.

A study's case runs as a campaign (:mod:`floatmoor.campaign`) with time series kept; its
dataset already holds, per run, the statistics of every line's fairlead tension and of every
floater DOF after the ramp, computed by the run summary
(:func:`floatmoor.post.summary.run_summary`), and the histories. A scalar quantity is one of
those statistics; a history quantity is the samples of a history inside its time window
(:func:`floatmoor.post.statistics.time_window`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.post.statistics import time_window
from floatmoor.uq.study import Quantity

__all__ = ["quantity_values", "history_times"]

#: Slack on the window end when cutting a history [s relative to the end]: output times are
#: k * dt, which round-off can put a hair past an end that is a multiple of dt.
_END_EPS = 1e-9


def _history(quantity: Quantity, campaign: xr.Dataset) -> xr.DataArray:
    """The quantity's history (run, time) inside its window."""
    if quantity.kind == "line":
        series = campaign["fairlead_tension"].sel(line=quantity.target)
    else:
        series = campaign["body_displacement"].sel(dof=quantity.target)
    start, end = quantity.window
    inside = time_window(series, start=start)
    keep = inside["time"].values <= end + _END_EPS * max(abs(end), 1.0)
    return inside.isel(time=np.flatnonzero(keep))


def history_times(quantity: Quantity, campaign: xr.Dataset) -> NDArray[np.float64]:
    """The output times [s] of a history quantity's window."""
    return np.asarray(_history(quantity, campaign)["time"].values, dtype=float)


def quantity_values(quantity: Quantity, campaign: xr.Dataset) -> NDArray[np.float64]:
    """The values of ``quantity`` in every run of a one-axis campaign: (runs, outputs), one
    output for a scalar, one per sample of the window for a history. Runs that failed hold
    NaN (the campaign's)."""
    if quantity.is_history:
        values = _history(quantity, campaign)
        dims = [d for d in values.dims if d != "time"] + ["time"]
        return np.asarray(values.transpose(*dims).values, dtype=float)
    if quantity.kind == "line":
        values = campaign[f"fairlead_tension_{quantity.statistic}"].sel(line=quantity.target)
    else:
        values = campaign[f"body_displacement_{quantity.statistic}"].sel(dof=quantity.target)
    return np.asarray(values.values, dtype=float)[:, None]
