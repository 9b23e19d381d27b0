"""Cost of a 3 h full-scale JONSWAP record (benchmark: not in the default run)."""

from __future__ import annotations

import time

import numpy as np
import pytest

from floatmoor.waves.excitation_series import WaveExcitation
from floatmoor.waves.realisation import WaveField

#: Generous ceiling on a loaded machine (measured 2-3 s of thread time for both records).
MAX_THREAD_SECONDS = 20.0


@pytest.mark.benchmark
@pytest.mark.parametrize("dt", [0.05, 0.1])
def test_three_hour_record_cost(dt):
    field = WaveField.jonswap(6.0, 12.0, gamma=3.3, seed=1, duration=10800.0, omega_min=0.2,
                              omega_max=2.0, depth=200.0, gravity=9.81)
    rng = np.random.default_rng(0)
    x = rng.normal(size=(field.n_components, 6)) * (1 + 1j)
    t = np.arange(0.0, 10800.0, dt)
    start = time.thread_time()
    eta = field.elevation(t)
    mid = time.thread_time()
    force = WaveExcitation(field, x).series(t)
    end = time.thread_time()
    print(f"\n{field.n_components} components, {t.size} times (dt {dt} s): elevation "
          f"{mid - start:.2f} s, 6-DOF excitation {end - mid:.2f} s (thread time)")
    assert eta.shape == t.shape and force.shape == (t.size, 6)
    assert end - start < MAX_THREAD_SECONDS
