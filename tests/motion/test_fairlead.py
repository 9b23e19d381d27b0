"""Prescribed motion: circle geometry and sense, ramp, harmonic and tabulated motion."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.motion.fairlead import displacement, fairlead_path, horizontal_direction, ramp
from tests.conftest import LINDAHL_CASE


def test_ramp_is_smooth_and_reaches_one():
    t = np.linspace(0.0, 3.0, 3001)
    r = ramp(t, 2.0)
    assert r[0] == 0.0 and np.all(r[t >= 2.0] == 1.0)
    assert np.all(np.diff(r) >= 0.0)
    slope = np.gradient(r, t)
    assert abs(slope[0]) < 1e-2 and abs(slope[2000]) < 1e-2  # zero slope at both ends


@pytest.mark.parametrize("sense, sign", [("away-from-anchor-at-top", 1.0),
                                         ("toward-anchor-at-top", -1.0)])
def test_circle_radius_plane_and_sense(sense, sign):
    case = load_case(LINDAHL_CASE, [f'motion.sense="{sense}"', "lines.chain.anchor=[-3.0, -4.0, -3.0]",
                                    "lines.chain.fairlead=[16.0, 4.0, 0.3]"])
    line = case.lines[0]
    e_h = horizontal_direction(line)
    t = np.linspace(case.motion.ramp_duration, case.simulation.duration, 4001)
    path = fairlead_path(case.motion, line, t)
    rel = path - np.asarray(line.fairlead)
    # on the circle of radius r in the vertical plane of the line
    np.testing.assert_allclose(np.linalg.norm(rel, axis=1), 0.2, rtol=1e-12)
    normal = np.cross(e_h, [0.0, 0.0, 1.0])
    np.testing.assert_allclose(rel @ normal, 0.0, atol=1e-14)
    # at the top of the circle the end moves away from (+) or toward (-) the anchor
    top = np.argmax(rel[:, 2])
    velocity = np.gradient(rel @ e_h, t)[top]
    assert np.sign(velocity) == sign
    # one revolution per period
    period = case.motion.period
    later = fairlead_path(case.motion, line, t + period)
    np.testing.assert_allclose(later, path, atol=1e-12)


def test_harmonic_and_table_displacements():
    case = load_case(LINDAHL_CASE, [
        'motion={kind = "harmonic", amplitude = [0.1, 0.0, 0.05], period = [2.0, 1.0, 4.0], '
        'phase_deg = [0.0, 0.0, 90.0], ramp_duration = 0.0}'])
    t = np.array([0.5, 1.0])
    d = displacement(case.motion, t, None)
    np.testing.assert_allclose(d[:, 0], 0.1 * np.sin(2 * np.pi * t / 2.0), atol=1e-15)
    np.testing.assert_allclose(d[:, 2], 0.05 * np.cos(2 * np.pi * t / 4.0), atol=1e-15)
    assert case.motion.cycle_period is None  # different periods: not periodic
