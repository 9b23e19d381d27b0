"""Quantities of interest taken from a campaign dataset: the run summary's statistics of a
line or a floater DOF, and histories cut to their window (both ends kept)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from floatmoor.io.dataset import DOFS
from floatmoor.uq.quantities import history_times, quantity_values
from floatmoor.uq.study import Quantity


def _campaign() -> xr.Dataset:
    """Three runs of two lines and a floater on the layout of floatmoor.campaign.store, with
    values that say where they came from: run k, line i, time t -> 100 k + 10 i + t."""
    runs, lines, time = 3, ["a", "b"], np.arange(0.0, 2.0 + 1e-9, 0.1)
    k = np.arange(runs)[:, None, None]
    i = np.arange(len(lines))[None, :, None]
    tension = 100.0 * k + 10.0 * i + time[None, None, :]
    body = 100.0 * np.arange(runs)[:, None, None] + np.arange(6)[None, None, :] \
        + time[None, :, None]
    dims = ("key",)
    return xr.Dataset({
        "fairlead_tension_max": (dims + ("line",), tension.max(axis=2)),
        "body_displacement_min": (dims + ("dof",), body.min(axis=1)),
        "fairlead_tension": (dims + ("line", "time"), tension),
        "body_displacement": (dims + ("time", "dof"), body),
    }, coords={"line": lines, "dof": list(DOFS), "time": time,
               "key": ("key", [1.0, 2.0, 3.0])})


def test_scalar_statistics_of_a_line_and_a_dof():
    ds = _campaign()
    line = quantity_values(Quantity("t", "line", "b", "max", units="N"), ds)
    assert line.shape == (3, 1)
    assert np.allclose(line[:, 0], [12.0, 112.0, 212.0])
    heave = quantity_values(Quantity("h", "dof", "Heave", "min", units="m"), ds)
    assert np.allclose(heave[:, 0], [2.0, 102.0, 202.0])


def test_histories_are_cut_to_their_window_with_both_ends():
    ds = _campaign()
    q = Quantity("p", "dof", "Pitch", "history", (0.5, 1.2), "rad")
    times = history_times(q, ds)
    assert np.allclose(times, np.arange(0.5, 1.2 + 1e-9, 0.1))
    values = quantity_values(q, ds)
    assert values.shape == (3, times.size)
    assert np.allclose(values, 100.0 * np.arange(3)[:, None] + 4.0 + times[None, :])
    line = quantity_values(Quantity("a", "line", "a", "history", (0.0, 2.0), "N"), ds)
    assert line.shape == (3, 21) and np.allclose(line[2], 200.0 + ds["time"].values)
