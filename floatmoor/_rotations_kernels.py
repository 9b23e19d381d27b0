"""Numba kernels of the rotation convention (floatmoor.rotations): the matrix of the Euler
angles and the angular velocity of changing angles, for the compiled kernels that move body
points (floatmoor/body/_kinematics_kernels.py, floatmoor/body/_morison_kernels.py), which
cannot call NumPy code. :mod:`floatmoor.rotations` is their NumPy version, and
tests/test_rotations.py checks the two against each other
(docs/conventions.md#rotation-convention-of-body-motion).
"""

from __future__ import annotations

import math

from floatmoor._numba import jit

__all__ = ["rotation", "angular_velocity"]


@jit(inline="always")
def rotation(roll: float, pitch: float, yaw: float
             ) -> tuple[float, float, float, float, float, float, float, float, float]:
    """R = Rz(yaw) Ry(pitch) Rx(roll) (body axes to global axes) as its nine entries, row by
    row (R00, R01, R02, R10, ..., R22); as scalars, so a kernel allocates nothing for it."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
            sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
            -sp, cp * sr, cp * cr)


@jit(inline="always")
def angular_velocity(pitch: float, yaw: float, droll: float, dpitch: float,
                     dyaw: float) -> tuple[float, float, float]:
    """Angular velocity omega = T (roll', pitch', yaw') in global axes of R = Rz Ry Rx
    (omega x = R' R^T; the rows of T: (cy cp, -sy, 0), (sy cp, cy, 0), (-sp, 0, 1))."""
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (droll * cy * cp - dpitch * sy, droll * sy * cp + dpitch * cy, dyaw - droll * sp)
