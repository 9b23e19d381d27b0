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


def test_cycle_maxima_of_an_astronomical_period_are_none_and_immediate():
    # the slack was relative to the period, so a 1e308 s period counted
    # ~1e299 cycles (and looped over them) and a 1e9 s one counted a cycle that is not there
    from floatmoor.post.statistics import channel_statistics, cycle_maxima

    t = np.linspace(0.0, 15.0, 301)
    y = np.sin(t)
    for period in (1e308, 1e9, 15.000001):
        assert cycle_maxima(t, y, start=0.0, period=period).size == 0
        stats = channel_statistics(t, y, start=0.0, period=period)
        assert stats["mean_cycle_max"] is None and stats["n_cycles"] == 0
    assert cycle_maxima(t, y, start=0.0, period=15.0).size == 1


def test_cycle_maxima_match_a_loop_over_cycles():
    from floatmoor.post.statistics import cycle_maxima

    t = np.arange(0.0, 10.0 + 1e-12, 0.01)
    y = np.sin(2.0 * np.pi * t / 1.3) + 0.1 * t
    got = cycle_maxima(t, y, start=0.4, period=1.3)
    expected = [y[(t >= 0.4 + k * 1.3 - 1e-9) & (t < 0.4 + (k + 1) * 1.3 - 1e-9)].max()
                for k in range(int((10.0 - 0.4) // 1.3))]
    np.testing.assert_allclose(got, expected)
