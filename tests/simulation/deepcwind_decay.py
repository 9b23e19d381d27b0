"""The DeepCwind surge free decay of the validation (docs/cases/deepcwind.md), shared by
``test_deepcwind_decay.py`` (the published period, the damping the memory lines add) and
``test_unchanged_dynamic.py`` (the decays unchanged by the dynamic line's numerics).

The platform is released from a surge offset of 16.58 m with the members' Morison drag, the
lines of one model, 400 s (three surge cycles) at the case's body step of 0.1 s, output every
0.5 s.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from floatmoor.case.load import load_case
from floatmoor.simulation.coupled_run import run_coupled
from tests.conftest import CASES, REFERENCE_NUMERICS

CASE = CASES / "deepcwind" / "deepcwind_free_decay.toml"
OFFSET = 16.58  # m
DURATION = 400.0  # s: three surge cycles


@dataclass(frozen=True)
class SurgeDecay:
    """The positive surge peaks after the release (parabolic refinement between samples)."""

    model: str  #: line model of the three lines
    peak_times: np.ndarray  #: [s]
    peaks: np.ndarray  #: surge at the peaks [m]
    wall_time_s: float  #: the run's time loop

    @property
    def period(self) -> float:
        """The time from the release to the first return peak [s]: the period at the release
        amplitude (the catenaries stiffen with the offset, so later, smaller cycles are
        slower)."""
        return float(self.peak_times[0])


def surge_decay(model: str) -> SurgeDecay:
    """Run the decay with every line of ``model`` and find its surge peaks."""
    # dynamic lines at the numerics of the stored figures (10 x p5, explicit: the defaults
    # before the rule; the accuracy default, 6 x p3 "auto", moves cycle 3's period by -0.66 %)
    numerics = REFERENCE_NUMERICS if model == "dynamic" else []
    case = load_case(CASE, [f'lines.*.model="{model}"', *numerics,
                            f"simulation.duration={DURATION}", "simulation.output_interval=0.5",
                            "simulation.time_step=0.1", f"initial={{surge = {OFFSET}}}"])
    result = run_coupled(case)
    ds = result.dataset
    t = ds["time"].values
    s = ds["body_displacement"].sel(dof="Surge").values
    i = np.nonzero((s[1:-1] > s[:-2]) & (s[1:-1] >= s[2:]) & (s[1:-1] > 0.0))[0] + 1
    y0, y1, y2 = s[i - 1], s[i], s[i + 1]
    times = t[i] + 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2) * (t[1] - t[0])  # parabolic peak
    return SurgeDecay(model, times, y1, result.wall_time_s)
