"""Rigid-body kinematics of body-fixed points (large angles) and the generalised force of
point loads.

The six DOFs are capytaine's (Surge, Sway, Heave, Roll, Pitch, Yaw) about the body's reference
point (the rotation centre of the BEM database). The linear hydrodynamics stay about the mean
position; the points where lines attach follow the body with the full rotation

    R = Rz(yaw) Ry(pitch) Rx(roll),   p = c0 + x[:3] + R (p0 - c0),

c0 the reference point at rest and p0 the point at rest. Their velocity is the time
derivative of that position, v = x'[:3] + omega x R (p0 - c0), with the angular velocity
omega = T(pitch, yaw) (roll', pitch', yaw') of the Euler-angle rates (as
:func:`floatmoor.rotations.angular_velocity`); a point force f there acts on the body with
the generalised force (f, T^T M), M = R (p0 - c0) x f its moment about the displaced reference
point, so that the power the body's equations see, (f, T^T M) . x', is the power f . v the
force does at the point. The small-angle identification omega = (roll', pitch', yaw') with
(f, M) broke that balance at second order in the angles: on the moored buoy pitching
0.2 rad it fed roll and yaw from the dynamic lines' end impedance (docs/theory/floater.md,
"Energy consistency of the coupling").
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from floatmoor.body._kinematics_kernels import generalised_force_into, points_state_into

__all__ = ["points_state", "generalised_force"]


def points_state(x: NDArray[np.float64], v: NDArray[np.float64], arms: NDArray[np.float64],
                 centre: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Global positions and velocities (n, 3) of body-fixed points.

    Parameters
    ----------
    x, v
        Body displacement and velocity (6,) [m, rad; m/s, rad/s].
    arms
        Points at rest relative to the reference point at rest, p0 - c0 (n, 3) [m].
    centre
        Reference point at rest c0 (3,) [m].
    """
    arms = np.ascontiguousarray(arms, dtype=float).reshape(-1, 3)
    positions = np.empty_like(arms)
    velocities = np.empty_like(arms)
    points_state_into(np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(v, dtype=float),
                      arms, np.ascontiguousarray(centre, dtype=float), positions, velocities)
    return positions, velocities


def generalised_force(x: NDArray[np.float64], forces: NDArray[np.float64],
                      arms: NDArray[np.float64]) -> NDArray[np.float64]:
    """The 6-DOF generalised force of point forces ``forces`` (n, 3) [N] acting at the
    body-fixed points with rest arms ``arms``: the 3 forces, and the moment M about the
    displaced reference point turned onto the Euler angles, T^T M (module docstring; M
    itself when the pitch and yaw are zero)."""
    out = np.empty(6)
    generalised_force_into(np.ascontiguousarray(x, dtype=float),
                           np.ascontiguousarray(forces, dtype=float).reshape(-1, 3),
                           np.ascontiguousarray(arms, dtype=float).reshape(-1, 3), out)
    return out
