"""The quasi-static line model: the compiled path kernel against a plain loop over the
Python catenary API (the oracle), warm starts, and failure reporting."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.errors import SolverError
from floatmoor.motion import fairlead_path
from floatmoor.mooring.catenary import solve_catenary
from floatmoor.mooring.quasistatic import QuasiStaticLine
from tests.conftest import LINDAHL_CASE

#: Kernel and oracle run the same Newton to 1e-12 L from different warm starts; the forces
#: agree to the conditioning of the solve, far inside 1e-9 relative.
KERNEL_VS_ORACLE_RTOL = 1e-9


def _model_and_path(overrides=()):
    case = load_case(LINDAHL_CASE, list(overrides))
    line = case.lines[0]
    model = QuasiStaticLine(line, case.environment, case.seabed)
    t = np.linspace(0.0, case.simulation.duration, 1501)
    return case, line, model, t, fairlead_path(case.motion, line, t)


def test_path_kernel_matches_oracle_loop():
    case, line, model, t, path = _model_and_path()
    n = t.size
    ff, af = np.zeros((n, 3)), np.zeros((n, 3))
    lb, it = np.zeros(n), np.zeros(n)
    model.solve_path(t, path, ff, af, lb, it)
    w = line.line_type.weight_in_water(case.environment)
    worst = 0.0
    for k in range(0, n, 7):
        sol = solve_catenary(np.asarray(line.anchor), path[k], line.length,
                             line.line_type.axial_stiffness, w, case.seabed.friction_coefficient,
                             seabed_z=-case.environment.water_depth)
        np.testing.assert_allclose(ff[k], sol.fairlead_force, rtol=KERNEL_VS_ORACLE_RTOL,
                                   atol=1e-12 * sol.fairlead_tension)
        np.testing.assert_allclose(af[k], sol.anchor_force, rtol=KERNEL_VS_ORACLE_RTOL,
                                   atol=1e-12 * sol.fairlead_tension)
        assert lb[k] == pytest.approx(sol.laid_length, rel=KERNEL_VS_ORACLE_RTOL, abs=1e-12)
        worst = max(worst, np.max(np.abs(ff[k] - sol.fairlead_force)) / sol.fairlead_tension)
    print(f"worst kernel/oracle relative difference {worst:.2e}")
    # warm start: after the first solve, Newton needs few iterations per 0.01 s step
    assert np.max(it[1:]) <= 6
    # physics: the line pulls the fairlead towards the anchor and down; it rests on the bed
    assert np.all(ff[:, 0] < 0.0) and np.all(ff[:, 2] < 0.0)
    assert np.all(lb > 0.0) and np.all(lb < line.length)


def test_failure_names_line_time_and_reason():
    case, line, model, t, path = _model_and_path()
    bad = path.copy()
    bad[700:, 2] = -3.5  # fairlead driven below the seabed from sample 700 on
    n = t.size
    ff, af = np.zeros((n, 3)), np.zeros((n, 3))
    lb, it = np.zeros(n), np.zeros(n)
    with pytest.raises(SolverError) as info:
        model.solve_path(t, bad, ff, af, lb, it)
    message = str(info.value)
    assert "line 'chain'" in message and f"t = {t[700]:.6g} s" in message
    assert model.failed_index == 700
    assert np.all(np.isfinite(ff[:700])) and np.all(np.linalg.norm(ff[:700], axis=1) > 0)
