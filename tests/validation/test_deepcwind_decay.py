"""DeepCwind semisubmersible surge free decay from 16.58 m (cases.md D; quasi-dynamic paper
section 5): the period with quasi-static lines against the published 107.5 s, and the surge
damping the dynamic and quasi-dynamic lines add (the paper's finding). Slow: the dynamic lines
take about 4 minutes on the development machine."""

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
#: Memory lines must damp more: the second surge peak below this fraction of the quasi-static
#: run's second peak (observed QD 0.49, dynamic see the printout).
DAMPING_RATIO_MAX = 0.9
OFFSET = 16.58  # m
DURATION = 400.0  # s: three surge cycles


def _decay(model: str):
    case = load_case(CASE, [f'lines.{i}.model="{model}"' for i in range(3)] + [
        f"simulation.duration={DURATION}", "simulation.output_interval=0.5",
        "simulation.time_step=0.1", f"initial={{surge = {OFFSET}}}"])
    ds = run_coupled(case).dataset
    t = ds["time"].values
    s = ds["body_displacement"].sel(dof="Surge").values
    i = np.nonzero((s[:-1] < 0.0) & (s[1:] >= 0.0))[0]
    up = t[i] - s[i] * (t[i + 1] - t[i]) / (s[i + 1] - s[i])
    peaks = np.array([s[(t > a) & (t < b)].max() for a, b in zip(up[:-1], up[1:])])
    return np.diff(up), peaks


@pytest.fixture(scope="module")
def decays():
    return {m: _decay(m) for m in ("quasi-static", "quasi-dynamic", "dynamic")}


def test_surge_period_with_quasi_static_lines(decays) -> None:
    periods, _ = decays["quasi-static"]
    print(f"quasi-static surge periods {np.round(periods, 2)} s (published "
          f"{PUBLISHED_SURGE_PERIOD} s)")
    assert abs(periods[0] / PUBLISHED_SURGE_PERIOD - 1.0) <= PERIOD_RTOL


def test_memory_lines_damp_surge_more_than_quasi_static(decays) -> None:
    qs_peak = decays["quasi-static"][1][0]
    for model in ("quasi-dynamic", "dynamic"):
        periods, peaks = decays[model]
        print(f"{model}: periods {np.round(periods, 2)} s, peaks {np.round(peaks, 2)} m; "
              f"quasi-static peak {qs_peak:.2f} m")
        assert peaks[0] <= DAMPING_RATIO_MAX * qs_peak
