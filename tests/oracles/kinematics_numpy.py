"""Plain NumPy reference of the rigid-body point kinematics (floatmoor.body._kinematics_kernels):
the rotation R = Rz(yaw) Ry(pitch) Rx(roll) built as the product of the three elementary
rotations, positions c0 + x[:3] + R a, velocities x'[:3] + omega x (R a) with omega = T rates
(T the Euler-angle-rate matrix, built from the elementary axes: omega = yaw' z + pitch' Rz y +
roll' Rz Ry x), and forces summed with their moments (R a) x f about the displaced reference
point, turned onto the Euler angles by T^T."""

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


def rate_matrix(pitch: float, yaw: float) -> Array:
    """T: omega = T (roll', pitch', yaw'), columns Rz Ry e_x, Rz e_y, e_z."""
    Rz = rotation(0.0, 0.0, yaw)
    Ry = rotation(0.0, pitch, 0.0)
    e = np.eye(3)
    return np.column_stack([Rz @ Ry @ e[0], Rz @ e[1], e[2]])


def points_state(x: Array, v: Array, arms: Array, centre: Array) -> tuple[Array, Array]:
    rotated = arms @ rotation(*x[3:]).T
    omega = rate_matrix(x[4], x[5]) @ v[3:]
    return centre + x[:3] + rotated, v[:3] + np.cross(omega, rotated)


def generalised_force(x: Array, forces: Array, arms: Array) -> Array:
    rotated = arms @ rotation(*x[3:]).T
    moment = np.cross(rotated, forces).sum(axis=0)
    return np.concatenate([forces.sum(axis=0), rate_matrix(x[4], x[5]).T @ moment])
