"""Numba kernels of the rigid-body point kinematics (floatmoor.body.kinematics): positions and
velocities of body-fixed points, and the generalised force of point loads. They run several
times per RK4 stage of a coupled run, where NumPy's per-call overhead on (n, 3) arrays
dominated the step (tests/oracles/kinematics_numpy.py is their NumPy reference). The rotation
and the angular velocity are the kernels of :mod:`floatmoor._rotations_kernels`."""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor._rotations_kernels import angular_velocity, rotation

__all__ = ["points_state_into", "generalised_force_into"]


@jit
def points_state_into(x: np.ndarray, v: np.ndarray, arms: np.ndarray, centre: np.ndarray,
                      positions: np.ndarray, velocities: np.ndarray) -> None:
    """Global positions and velocities (n, 3) of the body-fixed points with rest arms
    ``arms`` (n, 3): p = c0 + x[:3] + R a, v = x'[:3] + omega x (R a), omega the angular
    velocity of the Euler-angle rates v[3:]: v = dp/dt exactly."""
    R00, R01, R02, R10, R11, R12, R20, R21, R22 = rotation(x[3], x[4], x[5])
    wx, wy, wz = angular_velocity(x[4], x[5], v[3], v[4], v[5])
    for i in range(arms.shape[0]):
        a0, a1, a2 = arms[i, 0], arms[i, 1], arms[i, 2]
        r0 = R00 * a0 + R01 * a1 + R02 * a2
        r1 = R10 * a0 + R11 * a1 + R12 * a2
        r2 = R20 * a0 + R21 * a1 + R22 * a2
        positions[i, 0] = centre[0] + x[0] + r0
        positions[i, 1] = centre[1] + x[1] + r1
        positions[i, 2] = centre[2] + x[2] + r2
        velocities[i, 0] = v[0] + wy * r2 - wz * r1
        velocities[i, 1] = v[1] + wz * r0 - wx * r2
        velocities[i, 2] = v[2] + wx * r1 - wy * r0


@jit
def generalised_force_into(x: np.ndarray, forces: np.ndarray, arms: np.ndarray,
                           out: np.ndarray) -> None:
    """The 6-DOF generalised force of point forces ``forces`` (n, 3) at the body-fixed points
    with rest arms ``arms``, into ``out`` (6,): the forces, and the moment M about the
    displaced reference point turned onto the Euler angles, T^T M (T of
    :func:`~floatmoor._rotations_kernels.angular_velocity`), so that out . x' = sum f . v
    exactly (v of :func:`points_state_into`)."""
    R00, R01, R02, R10, R11, R12, R20, R21, R22 = rotation(x[3], x[4], x[5])
    for c in range(6):
        out[c] = 0.0
    for i in range(arms.shape[0]):
        a0, a1, a2 = arms[i, 0], arms[i, 1], arms[i, 2]
        r0 = R00 * a0 + R01 * a1 + R02 * a2
        r1 = R10 * a0 + R11 * a1 + R12 * a2
        r2 = R20 * a0 + R21 * a1 + R22 * a2
        f0, f1, f2 = forces[i, 0], forces[i, 1], forces[i, 2]
        out[0] += f0
        out[1] += f1
        out[2] += f2
        out[3] += r1 * f2 - r2 * f1
        out[4] += r2 * f0 - r0 * f2
        out[5] += r0 * f1 - r1 * f0
    mx, my, mz = out[3], out[4], out[5]
    cp, sp = math.cos(x[4]), math.sin(x[4])
    cy, sy = math.cos(x[5]), math.sin(x[5])
    out[3] = cy * cp * mx + sy * cp * my - sp * mz
    out[4] = -sy * mx + cy * my
    out[5] = mz
