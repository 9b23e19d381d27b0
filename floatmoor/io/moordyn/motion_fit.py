"""Rigid-body motion from the positions of points fixed to one body: a least-squares fit of a
rotation and a translation per time row (Kabsch's SVD solution), as the 6-DOF pose of
``[motion] kind = "body"`` (surge, sway, heave about the reference point, then roll, pitch,
yaw with R = Rz(yaw) Ry(pitch) Rx(roll): docs/conventions.md).

The points' rest positions ``p0`` are their positions at the zero pose (MoorDyn's coupled
points are given in the platform's frame, its reference point at the origin), so a pose maps
them to ``c0 + t + R (p0 - c0)`` with ``c0`` the reference point. One point fixes the
translation only (no rotation); two points, or points on one line, fix the rotation up to a
turn about that line: the smallest rotation taking the rest direction to the row's is used
(the points' positions, all a line needs, are the same for every such rotation).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["RigidFit", "fit_rigid_motion", "euler_angles"]

#: Relative size of the second singular value of the centred rest positions below which the
#: points count as lying on one line [-]: round-off of coordinates given to ~1e-9 relative.
_COLLINEAR_RTOL = 1e-9
#: |cos(pitch)| below which roll and yaw are not separable (pitch at +-90 deg) [-].
_GIMBAL_LOCK_COS = 1e-6


@dataclass(frozen=True)
class RigidFit:
    """The fitted motion and how well it reproduces the points."""

    pose: NDArray[np.float64]  #: (n, 6) surge, sway, heave [m], roll, pitch, yaw [rad]
    residual: NDArray[np.float64]  #: (n,) largest distance of a point from the fit [m]
    rotation_fitted: bool  #: False: one point, the translation only


def euler_angles(R: NDArray[np.float64]) -> NDArray[np.float64]:
    """Roll, pitch, yaw [rad] (n, 3) of rotation matrices R = Rz(yaw) Ry(pitch) Rx(roll)
    (n, 3, 3), roll and yaw unwrapped along the rows (continuous for interpolation).

    Raises
    ------
    ValueError
        A row with the pitch at +-90 deg (roll and yaw not separable); the message names it.
    """
    R = np.asarray(R, dtype=float).reshape(-1, 3, 3)
    cos_pitch = np.hypot(R[:, 0, 0], R[:, 1, 0])
    bad = np.flatnonzero(cos_pitch < _GIMBAL_LOCK_COS)
    if bad.size:
        raise ValueError(f"row {bad[0]}: a pitch of +-90 deg (roll and yaw not separable)")
    pitch = np.arctan2(-R[:, 2, 0], cos_pitch)
    roll = np.unwrap(np.arctan2(R[:, 2, 1], R[:, 2, 2]))
    yaw = np.unwrap(np.arctan2(R[:, 1, 0], R[:, 0, 0]))
    return np.stack([roll, pitch, yaw], axis=1)


def _smallest_rotation(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotations (n, 3, 3) taking the unit vector ``a`` (3,) to the unit vectors ``b`` (n, 3)
    by the smallest angle (Rodrigues); ``b`` opposite to ``a`` has no unique one: ValueError."""
    v = np.cross(a[None, :], b)
    c = b @ a
    bad = np.flatnonzero(c <= -1.0 + 1e-12)
    if bad.size:
        raise ValueError(f"row {bad[0]}: the points' line turned by 180 deg (no unique rotation)")
    K = np.zeros((b.shape[0], 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -v[:, 2], v[:, 1], -v[:, 0]
    K[:, 1, 0], K[:, 2, 0], K[:, 2, 1] = v[:, 2], -v[:, 1], v[:, 0]
    return np.eye(3)[None] + K + K @ K / (1.0 + c)[:, None, None]


def fit_rigid_motion(rest: NDArray[np.float64], positions: NDArray[np.float64],
                     reference_point: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> RigidFit:
    """Fit a rigid-body pose to every row of point positions.

    Parameters
    ----------
    rest
        The points at the zero pose, (k, 3) [m].
    positions
        The points' positions, (n, k, 3) [m].
    reference_point
        The rotation centre at the zero pose [m].

    Returns
    -------
    RigidFit
        Pose per row and the largest point residual per row.

    Raises
    ------
    ValueError
        A row where the pose is not defined (pitch +-90 deg, a two-point line reversed).
    """
    p0 = np.asarray(rest, dtype=float).reshape(-1, 3) - np.asarray(reference_point, float)
    x = np.asarray(positions, dtype=float).reshape(-1, p0.shape[0], 3) \
        - np.asarray(reference_point, float)
    n = x.shape[0]
    c0 = p0.mean(axis=0)
    c = x.mean(axis=1)  # (n, 3)
    a0 = p0 - c0
    a = x - c[:, None, :]
    spread = np.linalg.svd(a0, compute_uv=False) if p0.shape[0] > 1 else np.zeros(3)
    if p0.shape[0] == 1 or spread[0] == 0.0:
        R = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        fitted = False
    elif spread[1] <= _COLLINEAR_RTOL * spread[0]:
        k = int(np.argmax(np.linalg.norm(a0, axis=1)))
        d0 = a0[k] / np.linalg.norm(a0[k])
        d = a[:, k, :] / np.linalg.norm(a[:, k, :], axis=1)[:, None]
        R = _smallest_rotation(d0, d)
        fitted = True
    else:
        H = np.einsum("ki,nkj->nij", a0, a)  # (n, 3, 3): sum of a0 a^T
        U, _, Vt = np.linalg.svd(H)
        V = np.transpose(Vt, (0, 2, 1))
        sign = np.sign(np.linalg.det(V @ np.transpose(U, (0, 2, 1))))
        D = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        D[:, 2, 2] = sign
        R = V @ D @ np.transpose(U, (0, 2, 1))
        fitted = True
    translation = c - np.einsum("nij,j->ni", R, c0)
    fit = np.einsum("nij,kj->nki", R, p0) + translation[:, None, :]
    residual = np.linalg.norm(fit - x, axis=2).max(axis=1)
    pose = np.concatenate([translation, euler_angles(R)], axis=1)
    return RigidFit(pose=pose, residual=residual, rotation_fitted=fitted)
