"""Implicit (generalised-alpha) steps of a mooring system against its explicit steps on the
clump line and the lazy wave of tests/data/systems under their forced harmonic motion (the
cases of tests/simulation/test_system_moordyn.py; docs/theory/dynamic_line.md#mooring-systems).

Both start from the same settled state (the settle is explicit in both), so the difference is
the time integration's: the implicit step controls its local error of the end forces to a
quarter of ``accuracy`` (1 %) of the tension scale, which bounds the fairlead tension's
difference (:data:`TENSION_FRACTION`) and the free points' (:data:`POINT_ATOL`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.forced import run_forced_motion

SYSTEMS = Path(__file__).parents[1] / "data" / "systems"
#: Max |implicit - explicit| fairlead tension over the largest tension: the cases' accuracy
#: (1 %). Observed: clump line 0.30 % (0.36 % of its range), lazy wave 0.22 % (1.8 % of its
#: small 14 kN range).
TENSION_FRACTION = 0.01
#: Free points' positions, implicit against explicit [m]: observed 0.3 mm (clump line's
#: points), 15 mm (the lazy wave's massless joint, which moves about 1 m), 7 mm (its buoy).
POINT_ATOL = 0.05


def _run(name: str, mode: str):
    case = load_case(SYSTEMS / f"{name}.toml", [f'lines.*.dynamic.time_integration="{mode}"'])
    return run_forced_motion(case).dataset


@pytest.mark.slow  # two 30 s runs of a 3-section system (about 1 min CPU)
@pytest.mark.parametrize("name", ["chain_rope_chain_clump", "lazy_wave_buoy"])
def test_implicit_system_follows_the_explicit_one(name: str) -> None:
    exp, imp = _run(name, "explicit"), _run(name, "implicit")
    te = exp["fairlead_tension"].sel(line="line1").values
    ti = imp["fairlead_tension"].sel(line="line1").values
    error = np.abs(ti - te).max() / te.max()
    points = {str(p): float(np.linalg.norm(exp["point_position"].sel(point=p).values
                                           - imp["point_position"].sel(point=p).values,
                                           axis=1).max()) for p in exp["point"].values}
    print(f"\n{name}: max tension difference {error:.3%} of the max; points (m) {points}")
    assert error <= TENSION_FRACTION
    assert max(points.values()) <= POINT_ATOL
