"""The coupling scheme with dynamic lines: the body's time step must not change the results
beyond 1 %. The buoy of docs/cases/cylinder_buoy.md in regular waves H = 0.01 m, T = 1.2 s, its chains
made cheaper (EA 2e4 N, 4 elements of order 3, so the test runs in seconds) but still stiff
against the body; the waves are kept small enough that no line snaps, since the sampled
peaks of snap loads are not a property of the coupling (with H = 0.04 m they are, and vary
by 20 % with the output sampling alone)."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.coupled_run import run_coupled
from tests.conftest import CASES

pytestmark = pytest.mark.slow

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: The required 1 %: on the body motions (largest difference over the run, relative to the
#: motion's range) and on each line's mean and maximum fairlead tension.
STEP_RTOL = 0.01
BASE = ["simulation.duration=5.0", "simulation.output_interval=0.02",
        'waves={kind = "regular", height = 0.01, period = 1.2}',
        "line_types.chain.axial_stiffness=2.0e4",
        "lines.*.dynamic.elements=4", "lines.*.dynamic.order=3"]


def test_body_step_does_not_change_results_with_dynamic_lines() -> None:
    runs = {dt: run_coupled(load_case(BUOY_CASE, BASE + [f"simulation.time_step={dt}"]))
            .dataset for dt in (0.01, 0.005)}
    coarse, fine = runs[0.01], runs[0.005]
    for dof in ("Surge", "Heave", "Pitch"):
        a = coarse["body_displacement"].sel(dof=dof).values
        b = fine["body_displacement"].sel(dof=dof).values
        err = np.abs(a - b).max() / np.ptp(b)
        print(f"{dof}: largest difference {err:.2e} of the range")
        assert err <= STEP_RTOL
    late = fine["time"].values > 2.4
    for stat in (np.mean, np.max):
        a = stat(coarse["fairlead_tension"].values[:, late], axis=1)
        b = stat(fine["fairlead_tension"].values[:, late], axis=1)
        err = np.abs(a / b - 1.0).max()
        print(f"fairlead tension {stat.__name__}: {np.round(b, 4)} N, difference {err:.2e}")
        assert err <= STEP_RTOL
    assert fine["fairlead_tension"].values.min() > 0.5  # no line went slack
