"""Rigid-body kinematics of body-fixed points (large angles) and the generalised force of
point loads.

The six DOFs are capytaine's (Surge, Sway, Heave, Roll, Pitch, Yaw) about the body's reference
point (the rotation centre of the BEM database). The linear hydrodynamics stay about the mean
position; the points where lines attach follow the body with the full rotation

    R = Rz(yaw) Ry(pitch) Rx(roll),   p = c0 + x[:3] + R (p0 - c0),

c0 the reference point at rest and p0 the point at rest. Their velocity is
v = x'[:3] + omega x R (p0 - c0) with the angular velocity omega taken as the rotational DOF
rates, the same small-angle identification the linear hydrodynamics make (the exact relation
to the Euler-angle rates differs at second order in the angles).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from floatmoor.body._kinematics_kernels import generalised_force_into, points_state_into

__all__ = ["rotation_matrix", "points_state", "generalised_force"]


def rotation_matrix(roll: float, pitch: float, yaw: float) -> NDArray[np.float64]:
    """R = Rz(yaw) Ry(pitch) Rx(roll): body axes to global axes."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


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
    """The 6-DOF force (3 forces, 3 moments about the displaced reference point) of point
    forces ``forces`` (n, 3) [N] acting at the body-fixed points with rest arms ``arms``."""
    out = np.empty(6)
    generalised_force_into(np.ascontiguousarray(x, dtype=float),
                           np.ascontiguousarray(forces, dtype=float).reshape(-1, 3),
                           np.ascontiguousarray(arms, dtype=float).reshape(-1, 3), out)
    return out
