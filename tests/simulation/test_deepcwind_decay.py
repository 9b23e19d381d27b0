"""DeepCwind semisubmersible surge free decay from 16.58 m (docs/cases/deepcwind.md; quasi-dynamic paper
section 5), with the members' Morison drag: the period with quasi-static lines against the
published 107.5 s, and the surge damping the dynamic and quasi-dynamic lines add (the paper's
finding). Slow: the dynamic lines take about 5 minutes on the development machine."""

from __future__ import annotations

import numpy as np
import pytest

from tests.simulation.deepcwind_decay import surge_decay

pytestmark = [pytest.mark.slow, pytest.mark.validation]

#: Published surge natural period of the OC4 DeepCwind (docs/cases/deepcwind.md, notes) and the 5 % required.
PUBLISHED_SURGE_PERIOD = 107.5
PERIOD_RTOL = 0.05
#: Memory lines must damp more: the first return peak below this fraction of the quasi-static
#: run's (observed with member drag: quasi-dynamic 0.76, dynamic 0.67).
DAMPING_RATIO_MAX = 0.9


def _decay(model: str):
    """(period, peaks): the time from the release to the first return peak and the successive
    positive surge peaks (tests/simulation/deepcwind_decay.py)."""
    decay = surge_decay(model)
    return decay.period, decay.peaks


@pytest.fixture(scope="module")
def decays():
    return {m: _decay(m) for m in ("quasi-static", "quasi-dynamic", "dynamic")}


def test_surge_period_with_quasi_static_lines(decays) -> None:
    period, _ = decays["quasi-static"]
    print(f"quasi-static surge period {period:.2f} s (published {PUBLISHED_SURGE_PERIOD} s)")
    assert abs(period / PUBLISHED_SURGE_PERIOD - 1.0) <= PERIOD_RTOL


def test_memory_lines_damp_surge_more_than_quasi_static(decays) -> None:
    qs_peak = decays["quasi-static"][1][0]
    for model in ("quasi-dynamic", "dynamic"):
        period, peaks = decays[model]
        print(f"{model}: period {period:.2f} s, peaks {np.round(peaks, 2)} m; "
              f"quasi-static peak {qs_peak:.2f} m")
        assert peaks[0] <= DAMPING_RATIO_MAX * qs_peak
