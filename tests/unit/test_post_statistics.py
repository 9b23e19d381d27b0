"""Statistics and per-cycle maxima against signals with known answers."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.post.statistics import channel_statistics, cycle_maxima


def test_cycle_maxima_of_a_growing_sine():
    period, dt = 1.25, 0.0025
    t = np.arange(0.0, 15.0 + dt / 2, dt)
    # amplitude grows by 1 per cycle after t = 2.5: maxima 10 + k + 1 in cycle k
    k = np.floor((t - 2.5) / period)
    y = 10.0 + (k + 1) * np.sin(2 * np.pi * (t - 2.5) / period + 0.3)
    maxima = cycle_maxima(t, y, start=2.5, period=period)
    assert maxima.size == 10  # (15 - 2.5) / 1.25 complete cycles
    np.testing.assert_allclose(maxima, 10.0 + np.arange(1, 11), rtol=1e-4)


def test_statistics_window_and_moments():
    t = np.linspace(0.0, 10.0, 100001)
    y = np.where(t < 2.0, 1000.0, 5.0 + 2.0 * np.sin(2 * np.pi * t))
    s = channel_statistics(t, y, start=2.0, period=1.0)
    assert s["mean"] == pytest.approx(5.0, abs=1e-4)
    assert s["std"] == pytest.approx(2.0 / np.sqrt(2.0), rel=1e-4)
    assert s["max"] == pytest.approx(7.0, abs=1e-6) and s["min"] == pytest.approx(3.0, abs=1e-6)
    assert s["n_cycles"] == 8 and s["mean_cycle_max"] == pytest.approx(7.0, abs=1e-6)
    assert channel_statistics(t, y, start=2.0)["mean_cycle_max"] is None
