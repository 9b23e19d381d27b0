"""The whole quasi-static forced-motion pipeline against MoorPy: along the Lindahl fairlead
path (seabed contact with friction, moving touchdown point) the recorded fairlead and anchor
tensions equal MoorPy's catenary at the same fairlead positions."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE


pytestmark = pytest.mark.peer

#: Required: agreement with MoorPy's catenary to 1e-6 relative; both codes solve the
#: same equations, MoorPy to its Tol = 1e-10 here.
MOORPY_RTOL = 1e-6


@pytest.mark.parametrize("overrides", [
    [],                                                         # r = 0.2 m, T = 1.25 s
    ["motion.radius=0.075", "motion.period=3.5", "lines.chain.quasi_static.seabed_friction=false"],
])
def test_lindahl_path_tensions_match_moorpy(overrides):
    catenary = pytest.importorskip("moorpy.Catenary").catenary
    case = load_case(LINDAHL_CASE, overrides + ['lines.chain.model="quasi-static"', "simulation.duration=5.0",
                                                "simulation.output_interval=0.01"])
    ds = run_forced_motion(case).dataset.sel(line="chain")
    line = case.lines[0]
    w = line.line_type.weight_in_water(case.environment)
    cb = case.seabed.friction_coefficient if line.quasi_static.seabed_friction else 0.0
    worst = 0.0
    for k in range(0, ds.sizes["time"], 5):
        rel = ds["fairlead_position"].values[k] - np.asarray(line.anchor)
        with np.errstate(all="ignore"):  # MoorPy's internals overflow harmlessly in exp/sinh
            fah, fav, fbh, fbv, info = catenary(float(np.hypot(rel[0], rel[1])), float(rel[2]),
                                                line.length, line.line_type.axial_stiffness, w,
                                                CB=cb, Tol=1e-10, MaxIter=200)
        t_fair = np.hypot(fbh, fbv)
        t_anch = np.hypot(fah, fav)
        ours_fair = float(ds["fairlead_tension"].values[k])
        ours_anch = float(ds["anchor_tension"].values[k])
        assert ours_fair == pytest.approx(t_fair, rel=MOORPY_RTOL)
        assert ours_anch == pytest.approx(t_anch, rel=MOORPY_RTOL, abs=MOORPY_RTOL * t_fair)
        worst = max(worst, abs(ours_fair / t_fair - 1.0))
    print(f"worst fairlead-tension relative difference to MoorPy: {worst:.2e}")
