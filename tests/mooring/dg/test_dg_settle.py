"""The dynamic line's initial relaxation (DynamicLine.settle, from_case's default).

The interpolated catenary is not exactly the equilibrium of the DG discretisation; on a stiff,
light chain without damping or friction (docs/cases/qd_verification.md, C31: c = 2044 m/s, 1.95 N static
fairlead tension) the mismatch rings on undamped. Settled, the line must stay at rest.
"""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.mooring.catenary import solve_catenary
from floatmoor.mooring.dg import line as dg_line
from floatmoor.mooring.dg.line import DynamicLine
from tests.conftest import CASES


pytestmark = pytest.mark.verification

C31 = CASES / "qd_verification" / "s3_d1.toml"
OVERRIDES = ["lines.chain.dynamic.elements=10"]
#: Peak-to-peak fairlead tension over 0.3 s at rest after settling, relative to its mean:
#: 2.7e-5 measured (the implicit seabed contact leaves node speeds ~1e-4 m/s); unsettled 6.9.
SETTLED_RIPPLE_TOL = 1e-4
#: The unsettled line must ring by more than this (so that the check above can fail).
UNSETTLED_RIPPLE_MIN = 1.0
#: Settled static tension against the elastic catenary: the DG statics tolerance (0.2 %,
#: test_dg_cable), here 0.16 % with the touchdown inside an element of 1.3 m.
STATIC_RTOL = 2e-3


def _ripple(line: DynamicLine, fairlead, duration: float = 0.3) -> tuple[float, float]:
    n = 301
    t = line.time + np.linspace(0.0, duration, n)
    path = np.repeat(np.asarray(fairlead, dtype=float)[None, :], n, axis=0)
    ff = np.zeros((n, 3))
    line.solve_path(t, path, np.zeros_like(path), ff, np.zeros((n, 3)), np.zeros(n),
                    np.zeros(n))
    tension = np.linalg.norm(ff, axis=1)
    return float(np.ptp(tension) / tension.mean()), float(tension.mean())


def test_settled_line_stays_at_rest_and_unsettled_one_rings() -> None:
    dg_line._SETTLED.clear()
    case = load_case(C31, OVERRIDES)
    ln = case.lines[0]
    settled = DynamicLine.from_case(ln, case.environment, case.seabed)
    report = settled.settle_report
    assert report is not None and report.converged
    assert settled.time == 0.0 and not np.any(settled.v)
    ripple, mean = _ripple(settled, ln.fairlead)
    print(f"settled in {report.time:.2f} s simulated: ripple {ripple:.1e} of {mean:.5f} N")
    assert ripple <= SETTLED_RIPPLE_TOL
    sol = solve_catenary(ln.anchor, ln.fairlead, ln.length,
                         ln.line_type.axial_stiffness,
                         settled.properties.submerged_weight, 0.0,
                         seabed_z=case.environment.seabed_z)
    assert abs(mean / np.linalg.norm(sol.fairlead_force) - 1.0) <= STATIC_RTOL

    raw = DynamicLine.from_case(load_case(C31, OVERRIDES + ["lines.chain.dynamic.settle=false"])
                                .lines[0], case.environment, case.seabed)
    assert raw.settle_report is None
    ripple_raw, _ = _ripple(raw, ln.fairlead)
    print(f"unsettled: ripple {ripple_raw:.2f}")
    assert ripple_raw >= UNSETTLED_RIPPLE_MIN


def test_settled_positions_are_reused_for_the_same_line() -> None:
    dg_line._SETTLED.clear()
    case = load_case(C31, OVERRIDES)
    first = DynamicLine.from_case(case.lines[0], case.environment, case.seabed)
    other = load_case(C31, OVERRIDES + ["motion.period=0.5"])  # same line, other motion
    second = DynamicLine.from_case(other.lines[0], other.environment, other.seabed)
    assert second.settle_report is first.settle_report
    assert np.array_equal(second.r, first.r) and second.r is not first.r
    moved = load_case(C31, OVERRIDES + ["lines.chain.fairlead=[0.0, 0.0, 0.01]"])
    third = DynamicLine.from_case(moved.lines[0], moved.environment, moved.seabed)
    assert third.settle_report is not first.settle_report
