"""The rotation convention (floatmoor/rotations.py) and its numba kernels
(floatmoor/_rotations_kernels.py): R = Rz(yaw) Ry(pitch) Rx(roll) and the angular velocity of
changing Euler angles, one NumPy version and one compiled one that agree."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor._rotations_kernels import angular_velocity as angular_velocity_kernel
from floatmoor._rotations_kernels import rotation
from floatmoor.rotations import angular_velocity, rotation_matrices, rotation_matrix

#: Identities that hold to round-off.
ROUND_OFF = 1e-13
#: Kernel against its NumPy version: docs/development.md#54-kernel-oracle-tolerance.
KERNEL_RTOL = 1e-12


def _elementary(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rz Ry Rx from the three elementary rotations (the documented convention)."""
    c, s = math.cos, math.sin
    rx = np.array([[1, 0, 0], [0, c(roll), -s(roll)], [0, s(roll), c(roll)]])
    ry = np.array([[c(pitch), 0, s(pitch)], [0, 1, 0], [-s(pitch), 0, c(pitch)]])
    rz = np.array([[c(yaw), -s(yaw), 0], [s(yaw), c(yaw), 0], [0, 0, 1]])
    return rz @ ry @ rx


def test_rotation_is_orthonormal_and_composes_z_y_x() -> None:
    rng = np.random.default_rng(3)
    angles = rng.uniform(-math.pi, math.pi, size=(50, 3))
    R = rotation_matrices(angles)
    for a, r in zip(angles, R):
        assert np.abs(r @ r.T - np.eye(3)).max() <= ROUND_OFF
        assert abs(np.linalg.det(r) - 1.0) <= ROUND_OFF
        # yaw about z, then pitch about the yawed y, roll about body x
        assert np.abs(r - _elementary(*a)).max() <= ROUND_OFF
        np.testing.assert_array_equal(rotation_matrix(*a), r)  # one pose, the same numbers
    # a positive pitch turns +x downwards (z up): capytaine's right-handed rotation about +y
    assert rotation_matrix(0.0, 0.1, 0.0)[2, 0] < 0.0


@pytest.mark.oracle
def test_the_kernels_are_the_numpy_rotation_and_angular_velocity() -> None:
    rng = np.random.default_rng(11)
    angles = rng.uniform(-math.pi, math.pi, size=(200, 3))
    rates = rng.uniform(-2.0, 2.0, size=(200, 3))
    R = rotation_matrices(angles)
    omega = angular_velocity(angles, rates)
    for k in range(len(angles)):
        compiled = np.reshape(rotation(*angles[k]), (3, 3))
        np.testing.assert_allclose(compiled, R[k], rtol=0.0, atol=KERNEL_RTOL)
        w = angular_velocity_kernel(angles[k, 1], angles[k, 2], *rates[k])
        np.testing.assert_allclose(w, omega[k], rtol=0.0,
                                   atol=KERNEL_RTOL * np.abs(rates[k]).max())
    # not a trivially small comparison
    assert np.abs(omega).max() > 1.0
