"""The rotation convention of floatmoor's poses: the matrix of the Euler angles (roll, pitch,
yaw) and the angular velocity of changing angles
(docs/conventions.md#rotation-convention-of-body-motion), the one NumPy version of them.

    R = Rz(yaw) Ry(pitch) Rx(roll)   (body axes to global axes),

right-handed rotations: yaw first about z, pitch about the yawed y, roll about the body's own
x, the convention of the floater (:mod:`floatmoor.body.kinematics`), of prescribed body
motions (:mod:`floatmoor.motion.rigid_body`) and of the poses fitted to MoorDyn's coupled
points (:mod:`floatmoor.io.moordyn.motion_fit`, whose ``euler_angles`` inverts
:func:`rotation_matrices`). Compiled kernels, which cannot call NumPy code, use the numba
version of the same expressions, :mod:`floatmoor._rotations_kernels` (tests/test_rotations.py
checks the two agree).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["rotation_matrix", "rotation_matrices", "angular_velocity"]


def rotation_matrices(angles: NDArray[np.float64]) -> NDArray[np.float64]:
    """R = Rz(yaw) Ry(pitch) Rx(roll) (body axes to global axes) for angles (n, 3)
    (roll, pitch, yaw) [rad]; shape (n, 3, 3)."""
    angles = np.asarray(angles, dtype=float).reshape(-1, 3)
    cr, sr = np.cos(angles[:, 0]), np.sin(angles[:, 0])
    cp, sp = np.cos(angles[:, 1]), np.sin(angles[:, 1])
    cy, sy = np.cos(angles[:, 2]), np.sin(angles[:, 2])
    R = np.empty((angles.shape[0], 3, 3))
    R[:, 0, 0] = cy * cp
    R[:, 0, 1] = cy * sp * sr - sy * cr
    R[:, 0, 2] = cy * sp * cr + sy * sr
    R[:, 1, 0] = sy * cp
    R[:, 1, 1] = sy * sp * sr + cy * cr
    R[:, 1, 2] = sy * sp * cr - cy * sr
    R[:, 2, 0] = -sp
    R[:, 2, 1] = cp * sr
    R[:, 2, 2] = cp * cr
    return R


def rotation_matrix(roll: float, pitch: float, yaw: float) -> NDArray[np.float64]:
    """R = Rz(yaw) Ry(pitch) Rx(roll): body axes to global axes.

    Parameters
    ----------
    roll, pitch, yaw
        Rotations about x, y, z [rad].

    Returns
    -------
    numpy.ndarray
        R (3, 3), the one pose's :func:`rotation_matrices`.
    """
    return rotation_matrices(np.array([roll, pitch, yaw], dtype=float))[0]


def angular_velocity(angles: NDArray[np.float64], rates: NDArray[np.float64]
                     ) -> NDArray[np.float64]:
    """Angular velocity [rad/s] in global axes, (n, 3), of the rotation R = Rz Ry Rx with
    Euler angles ``angles`` (n, 3) [rad] changing at ``rates`` (n, 3) [rad/s]."""
    angles = np.asarray(angles, dtype=float).reshape(-1, 3)
    rates = np.asarray(rates, dtype=float).reshape(-1, 3)
    cp, sp = np.cos(angles[:, 1]), np.sin(angles[:, 1])
    cy, sy = np.cos(angles[:, 2]), np.sin(angles[:, 2])
    droll, dpitch, dyaw = rates[:, 0], rates[:, 1], rates[:, 2]
    return np.stack([droll * cy * cp - dpitch * sy,
                     droll * sy * cp + dpitch * cy,
                     dyaw - droll * sp], axis=1)
