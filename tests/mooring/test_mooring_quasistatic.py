"""The quasi-static line model: the compiled path kernel against the plain SciPy catenary
oracle (tests/oracles), warm starts, and failure reporting."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.errors import SolverError
from floatmoor.motion.fairlead import fairlead_path
from floatmoor.mooring.quasistatic import QuasiStaticLine
from tests.conftest import LINDAHL_CASE
from tests.oracles import catenary_numpy as oracle


pytestmark = pytest.mark.oracle

#: The kernel solves to 1e-12 L (Newton) and the oracle with nested brentq; on this moderately
#: conditioned touchdown line both are within ~1e-11 of the exact tensions, so 1e-9 relative
#: leaves room for round-off while catching any equation or bookkeeping error.
KERNEL_VS_ORACLE_RTOL = 1e-9


def _model_and_path(overrides=()):
    case = load_case(LINDAHL_CASE, list(overrides))
    line = case.lines[0]
    model = QuasiStaticLine(line, case.environment, case.seabed)
    t = np.linspace(0.0, case.simulation.duration, 1501)
    return case, line, model, t, fairlead_path(case.motion, line, t)


def test_path_kernel_matches_oracle():
    """Every sample of the compiled path solve against the plain SciPy oracle."""
    case, line, model, t, path = _model_and_path()
    n = t.size
    ff, af = np.zeros((n, 3)), np.zeros((n, 3))
    lb, it = np.zeros(n), np.zeros(n)
    model.solve_path(t, path, np.zeros_like(path), ff, af, lb, it)
    w = line.line_type.weight_in_water(case.environment)
    worst = 0.0
    for k in range(0, n, 7):
        rel = path[k] - np.asarray(line.anchor)
        sol = oracle.solve(oracle.Line(XF=float(np.hypot(rel[0], rel[1])), ZF=float(rel[2]),
                                       L=line.length, EA=line.line_type.axial_stiffness, W=w,
                                       CB=case.seabed.friction_coefficient, seabed=True))
        t_fair, t_anch = np.hypot(sol.HF, sol.VF), np.hypot(sol.HA, sol.VA)
        errors = (np.linalg.norm(ff[k]) / t_fair - 1.0, np.linalg.norm(af[k]) / t_fair
                  - t_anch / t_fair, (lb[k] - sol.LB) / line.length,
                  ff[k, 2] / sol.VF + 1.0)  # the line pulls the fairlead down by VF
        worst = max(worst, max(abs(e) for e in errors))
    print(f"worst kernel/oracle relative difference {worst:.2e}")
    assert worst < KERNEL_VS_ORACLE_RTOL
    # warm start: after the first solve, Newton needs few iterations per 0.01 s step
    assert np.max(it[1:]) <= 6
    # physics: the line pulls the fairlead towards the anchor and down; it rests on the bed
    assert np.all(ff[:, 0] < 0.0) and np.all(ff[:, 2] < 0.0)
    assert np.all(lb > 0.0) and np.all(lb < line.length)


def test_single_solve_matches_path_solve():
    case, line, model, t, path = _model_and_path()
    ff, af = np.zeros((3, 3)), np.zeros((3, 3))
    model.solve_path(t[:3], path[:3], np.zeros((3, 3)), ff, af, np.zeros(3), np.zeros(3))
    other = QuasiStaticLine(line, case.environment, case.seabed)
    for k in range(3):
        sol = other.solve(path[k])
        np.testing.assert_allclose(sol.fairlead_force, ff[k], rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(sol.anchor_force, af[k], rtol=1e-12, atol=1e-12)


def test_failure_names_line_time_and_reason():
    case, line, model, t, path = _model_and_path()
    bad = path.copy()
    bad[700:, 2] = -3.5  # fairlead driven below the seabed from sample 700 on
    n = t.size
    ff, af = np.zeros((n, 3)), np.zeros((n, 3))
    lb, it = np.zeros(n), np.zeros(n)
    with pytest.raises(SolverError) as info:
        model.solve_path(t, bad, np.zeros_like(bad), ff, af, lb, it)
    message = str(info.value)
    assert "line 'chain'" in message and f"t = {t[700]:.6g} s" in message
    assert model.failed_index == 700
    assert np.all(np.isfinite(ff[:700])) and np.all(np.linalg.norm(ff[:700], axis=1) > 0)
