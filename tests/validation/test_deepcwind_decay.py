"""DeepCwind semisubmersible surge free decay from 16.58 m (cases.md D; quasi-dynamic paper
section 5), with the members' Morison drag: the period with quasi-static lines against the
published 107.5 s, and the surge damping the dynamic and quasi-dynamic lines add (the paper's
finding). Slow: the dynamic lines take about 5 minutes on the development machine."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.coupled_run import run_coupled
from tests.conftest import CASES

pytestmark = pytest.mark.slow

CASE = CASES / "deepcwind" / "deepcwind_free_decay.toml"
#: Published surge natural period of the OC4 DeepCwind (cases.md D notes) and the issue's 5 %.
PUBLISHED_SURGE_PERIOD = 107.5
PERIOD_RTOL = 0.05
#: Memory lines must damp more: the first return peak below this fraction of the quasi-static
#: run's (observed with member drag: quasi-dynamic 0.76, dynamic 0.67).
DAMPING_RATIO_MAX = 0.9
OFFSET = 16.58  # m
DURATION = 400.0  # s: three surge cycles


def _decay(model: str):
    """(period, peaks): the time from the release to the first return peak (the period at the
    release amplitude: the catenaries stiffen with the offset, so later, smaller cycles are
    slower) and the successive positive surge peaks."""
    case = load_case(CASE, [f'lines.*.model="{model}"',
        f"simulation.duration={DURATION}", "simulation.output_interval=0.5",
        "simulation.time_step=0.1", f"initial={{surge = {OFFSET}}}"])
    ds = run_coupled(case).dataset
    t = ds["time"].values
    s = ds["body_displacement"].sel(dof="Surge").values
    i = np.nonzero((s[1:-1] > s[:-2]) & (s[1:-1] >= s[2:]) & (s[1:-1] > 0.0))[0] + 1
    y0, y1, y2 = s[i - 1], s[i], s[i + 1]
    times = t[i] + 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2) * (t[1] - t[0])  # parabolic peak
    return times[0], y1


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
