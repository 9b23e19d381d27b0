"""Physics of the DG system (sections joined at points), each check able to fail:

* two equal sections through a massless joint against one line of the same total elements:
  the difference is a discretisation error, falling with the order p;
* a point mass hanging from a taut vertical section oscillates at the analytic frequency of a
  bar with a tip mass, (omega L / c) tan(omega L / c) = m L / M;
* without drag and internal damping the energy of that system is conserved to the stated rate.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from floatmoor.mooring.dg.line import CableProperties, DynamicLine
from floatmoor.mooring.dg.system import DynamicSystem, SystemSection
from tests.unit.test_dg_system import point, settings

#: Fairlead tension, two sections + massless joint against one line, relative to the tension
#: range over two periods of 0.1 m heave-surge at 4 s on a suspended rope: measured 2.0e-2
#: (p = 2), 1.25e-2 (3), 8.2e-3 (4), 5.7e-3 (6) -- the line's own change from p = 2 to 6 is
#: 0.20, so the joint's error is a small part of the discretisation error and falls with p.
JOINT_RTOL_P6 = 1e-2
#: The joint's error at p = 6 must be below this fraction of that at p = 2 (measured 0.29).
JOINT_CONVERGENCE = 0.5
#: Frequency of the mass on the bar: measured -6.2e-5 relative (zero crossings of 3 s of
#: 1 ms samples; the initial stretch also excites the bar's own modes, 30x higher).
FREQUENCY_RTOL = 2e-4
#: Energy change over 3 s (about 5 periods) relative to the oscillation energy 0.5 k A^2:
#: measured -4.5e-3 (the Lax-Friedrichs penalty at the faces and the point only dissipates).
ENERGY_RTOL = 1e-2


def _rope(L: float) -> CableProperties:
    return CableProperties(length=L, mass_per_length=50.0, axial_stiffness=5e6, diameter=0.1,
                           material_density=5000.0, added_mass_coefficient=1.0)


def _joint_error(p: int) -> float:
    anchor, fair = np.array([-90.0, 0.0, -100.0]), np.array([0.0, 0.0, -5.0])
    t = np.linspace(0.0, 8.0, 161)
    w = 2.0 * np.pi / 4.0
    path = fair + 0.1 * np.outer(np.sin(w * t), [1.0, 0.0, 0.5])
    vel = 0.1 * w * np.outer(np.cos(w * t), [1.0, 0.0, 0.5])
    n, K = t.size, 4
    line = DynamicLine(_rope(140.0), settings(K, p), anchor, fair)
    r0 = line.r.reshape(-1, 3).copy()
    line.settle()
    ff = np.zeros((n, 3))
    line.solve_path(t, path, vel, ff, np.zeros((n, 3)), np.zeros(n), np.zeros(n))
    joint = r0[(K // 2) * (p + 1)]  # the node at arc length L / 2
    system = DynamicSystem(
        [point("a", "fixed", anchor), point("j", "free", joint), point("f", "body", fair)],
        [SystemSection("l", 0, _rope(70.0), settings(K // 2, p), "a", "j"),
         SystemSection("l", 1, _rope(70.0), settings(K // 2, p), "j", "f")],
        initial_positions=r0)
    # p = 2 creeps at 1.6e-5 relative per chunk after 20 s (the single line likewise)
    assert system.settle().change <= 1e-4
    sf, ef = np.zeros((n, 2, 3)), np.zeros((n, 2, 3))
    system.solve_path(t, path[:, None], vel[:, None], sf, ef, np.zeros((n, 2)),
                      np.zeros((n, 3, 3)), np.zeros(n))
    # the massless joint balances: the sections' forces on it cancel
    assert np.abs(ef[:, 0] + sf[:, 1]).max() <= 1e-9 * np.abs(ef).max()
    t1, t2 = np.linalg.norm(ff, axis=1), np.linalg.norm(ef[:, 1], axis=1)
    return float(np.abs(t1 - t2).max() / np.ptp(t1))


def test_two_sections_through_a_massless_joint_match_one_line() -> None:
    e2, e6 = _joint_error(2), _joint_error(6)
    print(f"joint error: p=2 {e2:.2e}, p=6 {e6:.2e}")
    assert e6 <= JOINT_RTOL_P6
    assert e6 <= JOINT_CONVERGENCE * e2


def test_point_mass_on_a_taut_section_oscillates_at_the_analytic_frequency() -> None:
    L, m, EA, M, g = 10.0, 1.0, 1e5, 100.0, 9.81
    c = math.sqrt(EA / m)
    props = CableProperties(length=L, mass_per_length=m, axial_stiffness=EA, diameter=0.01,
                            material_density=7800.0, water_density=0.0, gravity=g)
    beta = brentq(lambda b: b * math.tan(b) - m * L / M, 1e-9, 1.5)
    omega = beta * c / L
    amplitude = 0.01
    z0 = -L - (M + 0.5 * m * L) * g / EA * L - amplitude  # below the static position
    system = DynamicSystem([point("top", "fixed", (0.0, 0.0, 0.0)),
                            point("mass", "free", (0.0, 0.0, z0), mass=M)],
                           [SystemSection("l", 0, props, settings(2, 3), "top", "mass")])
    system.r[:] = np.outer(system.arc_length / L, [0.0, 0.0, z0])
    e0 = sum(system.energy().values())
    t = np.linspace(0.0, 3.0, 3001)
    n = t.size
    pp = np.zeros((n, 2, 3))
    system.solve_path(t, np.zeros((n, 0, 3)), np.zeros((n, 0, 3)), np.zeros((n, 1, 3)),
                      np.zeros((n, 1, 3)), np.zeros((n, 1)), pp, np.zeros(n))
    z = pp[:, 1, 2] - 0.5 * (pp[:, 1, 2].max() + pp[:, 1, 2].min())
    i = np.flatnonzero((z[:-1] < 0.0) & (z[1:] >= 0.0))
    crossings = t[i] - z[i] * (t[i + 1] - t[i]) / (z[i + 1] - z[i])
    measured = 2.0 * math.pi / np.diff(crossings).mean()
    print(f"omega {measured:.6f} rad/s, analytic {omega:.6f}")
    assert abs(measured / omega - 1.0) <= FREQUENCY_RTOL
    e1 = sum(system.energy().values())
    oscillation = 0.5 * EA / L * amplitude ** 2
    print(f"energy change {(e1 - e0) / oscillation:.2e} of the oscillation energy")
    assert abs(e1 - e0) <= ENERGY_RTOL * oscillation
