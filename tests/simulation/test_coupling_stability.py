"""Stability of the explicit body-line coupling ("explicit coupling with a heavy line on a light
body is the hard case"; the scheme is in floatmoor/simulation/coupled.py).

Model problem. A long taut line pulls a body along its own axis. Over times shorter than the
line's wave return time 2 L / c, the line answers a fairlead velocity u with the force
-Z u (Z = m c, the axial impedance, which the Lax-Friedrichs flux of the DG line imposes at
the fairlead): a dashpot. The coupled RK4 step gives every stage the line force of the line's
state at that stage's time (advanced along the predicted fairlead path) evaluated with the
stage's own fairlead velocity, so on the dashpot it is plain RK4 on v' = -lambda v,
lambda = Z / M: the velocity is multiplied per step by

    R(-z) = 1 - z + z^2 / 2 - z^3 / 6 + z^4 / 24,    z = lambda dt = Z dt / M,

stable for z <= 2.785: a body step dt <= 2.785 M / Z, whatever the line's own step; the
heavier (stiffer) the line and the lighter the body, the smaller the body step. For the
shipped cases the bound is far away (docs/cases/cylinder_buoy.md buoy: M + A11 ~ 60 kg against Z = 481 N s/m
per chain, dt <= 0.35 s against the 0.01 s used; DeepCwind: M + A11 ~ 2.3e7 kg against
Z = 3.1e5 N s/m, ~200 s against 0.1 s). Taking the stage forces at the fairlead velocity the
line was driven with (the predicted one) instead made the scheme unstable from z ~ 1; and
replacing the fairlead position as well would feel the end tangent's lift term, a spurious
stiffness ~EA (p + 1)^2 / h.

The test builds the model problem with a 1 kg body on a 300 m chain of docs/cases/cylinder_buoy.md (Z = 481 N
s/m: dt_crit = 5.8 ms) and checks the analytic limit: at z = 2 the kick dies out, at
z = 3.25 the velocity grows by R(-3.25) = 1.96 per step, as predicted.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.body.cummins import CumminsBody
from floatmoor.case.load import load_case
from floatmoor.simulation.coupled import MooredBody

#: The line: docs/cases/cylinder_buoy.md chain (m = 0.1447 kg/m, EA = 1.6 MN: c = 3325 m/s), 300 m long, taut
#: (0.1 % strain, 1.6 kN) and horizontal in air (no buoyancy or drag: the dashpot alone).
CASE = """
title = "coupling stability model problem"
[environment]
water_density = 1000.0
water_depth = 50.0
gravity = 9.81
[seabed]
stiffness = 3.0e8
damping_ratio = 1.0
friction_coefficient = 0.0
slip_speed = 0.01
[line_types.chain]
mass_per_length = 0.1447
axial_stiffness = 1.6e6
diameter = 4.786e-3
material_density = 7800.0
normal_drag_coefficient = 2.5
tangential_drag_coefficient = 0.5
added_mass_coefficient = 3.8
[[lines]]
name = "chain"
type = "chain"
length = 300.0
anchor = [-300.3, 0.0, 10.0]
fairlead = [0.0, 0.0, 10.0]
model = "dynamic"
[lines.dynamic]
elements = 20
order = 4
[simulation]
duration = 1.0
output_interval = 0.001
"""
BODY_MASS = 1.0  # kg
KICK = 1e-2  # m/s
#: The growth per step at z = 3.25 against R(-z) of the dashpot (module docstring): the line is
#: a dashpot only to the DG end flux's discrete impedance and besides a spring EA / L =
#: 5.3 kN/m (omega dt = 0.25); measured 2.00 against 1.96, so 5 %.
RATE_RTOL = 0.05
#: Stable: after 20 steps (0.083 s at z = 2, before the echo at 2 L / c = 0.18 s) the kick
#: has died to the line's own response: below a fifth of it.
DECAYED = 0.2


def _velocities(tmp_path, z: float, steps: int) -> np.ndarray:
    """Surge velocity of the body after each of ``steps`` steps of Z dt / M = z."""
    path = tmp_path / "case.toml"
    path.write_text(CASE)
    case = load_case(path)
    line = case.lines[0]
    impedance = line.line_type.mass_per_length * math.sqrt(
        line.line_type.axial_stiffness / line.line_type.mass_per_length)
    dt = z * BODY_MASS / impedance
    big = 1e9  # every other DOF held by a stiff spring on a heavy mass
    mass = np.diag([BODY_MASS, big, big, big, big, big])
    stiffness = np.diag([0.0, big, big, big, big, big])
    body = CumminsBody(mass, np.zeros((6, 6)), stiffness, np.zeros(6), None, dt)
    moored = MooredBody(body, case.lines, case.environment, case.seabed,
                        np.array(line.fairlead))
    moored.start(np.zeros(6))
    pretension = moored.line_forces(np.zeros(6))[0][0]
    body.static_force = np.array([-pretension[0], 0.0, 0.0, 0.0, 0.0, 0.0])  # balanced at rest
    body.v[0] = KICK
    speeds = []
    for _ in range(steps):
        moored.step()
        speeds.append(body.v[0])
    return np.array(speeds)


def test_explicit_coupling_is_stable_below_the_rk4_limit(tmp_path):
    v = _velocities(tmp_path, 2.0, 30)
    print(f"\nz = 2: |v| / kick after 20-30 steps at most {np.abs(v[20:]).max() / KICK:.3f}")
    assert np.abs(v[20:]).max() <= DECAYED * KICK


def test_explicit_coupling_grows_beyond_it_as_rk4_predicts(tmp_path):
    z = 3.25
    v = _velocities(tmp_path, z, 8)  # before the growing body trips the line's checks
    rate = float(np.exp(np.polyfit(np.arange(2, 8), np.log(np.abs(v[2:])), 1)[0]))
    predicted = 1.0 - z + z**2 / 2 - z**3 / 6 + z**4 / 24
    print(f"\nz = {z}: velocity multiplied by {rate:.4f} per step (RK4 on the dashpot: "
          f"{predicted:.4f})")
    assert np.all(np.diff(np.abs(v)) > 0.0)
    assert rate == pytest.approx(predicted, rel=RATE_RTOL)
