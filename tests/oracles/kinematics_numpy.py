"""Plain NumPy reference of the rigid-body point kinematics (floatmoor.body._kinematics_kernels):
the rotation R = Rz(yaw) Ry(pitch) Rx(roll) built as the product of the three elementary
rotations, positions c0 + x[:3] + R a, velocities x'[:3] + omega x (R a), and forces summed
with their moments (R a) x f about the displaced reference point."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]


def rotation(roll: float, pitch: float, yaw: float) -> Array:
    c, s = np.cos, np.sin
    Rx = np.array([[1.0, 0.0, 0.0], [0.0, c(roll), -s(roll)], [0.0, s(roll), c(roll)]])
    Ry = np.array([[c(pitch), 0.0, s(pitch)], [0.0, 1.0, 0.0], [-s(pitch), 0.0, c(pitch)]])
    Rz = np.array([[c(yaw), -s(yaw), 0.0], [s(yaw), c(yaw), 0.0], [0.0, 0.0, 1.0]])
    return Rz @ Ry @ Rx


def points_state(x: Array, v: Array, arms: Array, centre: Array) -> tuple[Array, Array]:
    rotated = arms @ rotation(*x[3:]).T
    return centre + x[:3] + rotated, v[:3] + np.cross(v[3:], rotated)


def generalised_force(x: Array, forces: Array, arms: Array) -> Array:
    rotated = arms @ rotation(*x[3:]).T
    return np.concatenate([forces.sum(axis=0), np.cross(rotated, forces).sum(axis=0)])
