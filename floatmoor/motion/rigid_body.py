"""Prescribed 6-DOF rigid-body motion of the body points (``[motion] kind = "body"``).

The body's displacement x = (surge, sway, heave, roll, pitch, yaw) [m, m, m, rad, rad, rad]
is given about a reference point c0 (the rotation centre at rest, global coordinates). With
the convention floatmoor's floater uses (:mod:`floatmoor.body.kinematics`),

    R = Rz(yaw) Ry(pitch) Rx(roll),    p = c0 + x[:3] + R (p0 - c0),

right-handed rotations about global axes parallel to x, y, z: yaw first about z, pitch about
the yawed y, roll about the body's own x (intrinsic z-y'-x''; the same matrix as extrinsic
x, then y, then z). The angles are large-angle Euler angles, not small rotations: every
point p0 keeps its distance to the reference point exactly. The velocity is exact,

    v = x'[:3] + omega x R (p0 - c0),
    omega = (roll' cos(yaw) cos(pitch) - pitch' sin(yaw),
             roll' sin(yaw) cos(pitch) + pitch' cos(yaw),
             yaw' - roll' sin(pitch)),

omega the angular velocity in global axes from the Euler-angle rates (omega x = R' R^T),
as the coupled floater's points take it (:mod:`floatmoor.body.kinematics`); both, for arrays of
poses, are in :mod:`floatmoor.rotations`. The displacement is ramped DOF by DOF as every
prescribed motion is (:func:`floatmoor.motion.fairlead.ramp`); a table is interpolated in each
DOF by the not-a-knot cubic spline of a translational table
(:func:`floatmoor.motion.fairlead.table_state`), rotations in the Euler angles, with the
spline's exact derivatives as rates.

A motion without rotations moves every point exactly as the translational motions of
:mod:`floatmoor.motion.fairlead` do: the same numbers, bit for bit.

A run starts its lines at the motion's pose at t = 0 (:func:`start_line`): a table whose first
row is not the rest pose, run without a ramp, starts there and not with a jump from rest.

Other programs. MoorDyn-F (OpenFAST) builds the same matrix for its bodies (the transpose of
OpenFAST's EulerConstruct, Rz Ry Rx). MoorDyn-C v2 builds its body quaternion as
Rx(roll) Ry(pitch) Rz(yaw) (Euler2Quat in its Misc.hpp): the reverse order, equal to first
order in the angles and different at second order (products of two angles), so a record
with two large rotations at once is a different attitude there. Both MoorDyn versions take
the rotational rates a coupled body is given as its angular velocity for the points'
velocities (v = v0 + w x r), a small-angle identification; floatmoor converts Euler-angle
rates exactly, for a prescribed motion and a coupled floater alike. OrcaFlex documents
right-handed rotations ("clockwise" looking along the axis) applied in a stated order on
rotating axes, for vessels yaw (heading) first, then pitch, then roll: the convention used
here.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import BodyHarmonicMotion, BodyMotion, BodyTableMotion, Line, Motion
from floatmoor.motion.fairlead import fairlead_state, harmonic_state, ramped, table_state
from floatmoor.rotations import angular_velocity, rotation_matrices

__all__ = ["body_motion_state", "body_points_state", "prescribed_fairlead_state",
           "is_body_motion", "start_line"]


def is_body_motion(motion: Motion | None) -> bool:
    """Whether ``motion`` is a 6-DOF body motion (``[motion] kind = "body"``)."""
    return isinstance(motion, (BodyHarmonicMotion, BodyTableMotion))


def body_motion_state(motion: BodyMotion, t: NDArray[np.float64]
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Ramped displacement x and its time derivative at times ``t``.

    Returns
    -------
    (ndarray, ndarray)
        x (n, 6) [m, rad] and x' (n, 6) [m/s, rad/s]: the rotational rates are the
        Euler-angle rates (:func:`angular_velocity` turns them into omega).
    """
    t = np.asarray(t, dtype=float)
    d = np.zeros((t.size, 6))
    dd = np.zeros((t.size, 6))
    if isinstance(motion, BodyHarmonicMotion):  # translations bit-identical to a fairlead's
        harmonic_state(motion.amplitude, motion.period, motion.phase, t, d, dd)
    elif isinstance(motion, BodyTableMotion):
        d, dd = table_state(motion.time, motion.displacement, t)
    else:  # pragma: no cover - the loader admits no other kind
        raise TypeError(f"not a body motion: {motion!r}")
    return ramped(t, motion.ramp_duration, d, dd)


def body_points_state(motion: BodyMotion, rest_positions: NDArray[np.float64],
                      t: NDArray[np.float64]
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Positions [m] and velocities [m/s] of body points at times ``t``.

    Parameters
    ----------
    motion
        The body motion.
    rest_positions
        The points at rest p0 (k, 3) [m], global coordinates.
    t
        Times [s], shape (n,).

    Returns
    -------
    (ndarray, ndarray)
        Positions and velocities, shape (n, k, 3) each.
    """
    p0 = np.asarray(rest_positions, dtype=float).reshape(-1, 3)
    x, dx = body_motion_state(motion, t)
    positions = p0[None, :, :] + x[:, None, :3]
    velocities = np.broadcast_to(dx[:, None, :3], positions.shape).copy()
    # samples with a rotation; the others keep the pure translation's exact numbers
    turned = np.any(x[:, 3:] != 0.0, axis=1) | np.any(dx[:, 3:] != 0.0, axis=1)
    if np.any(turned):
        arms = p0 - np.asarray(motion.reference_point, dtype=float)  # (k, 3)
        R = rotation_matrices(x[turned, 3:])
        rotated = np.einsum("nij,kj->nki", R, arms)  # R (p0 - c0), (m, k, 3)
        omega = angular_velocity(x[turned, 3:], dx[turned, 3:])
        positions[turned] += rotated - arms[None, :, :]
        velocities[turned] += np.cross(omega[:, None, :], rotated)
    return positions, velocities


def prescribed_fairlead_state(motion: Motion | None, line: Line, t: NDArray[np.float64]
                              ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Fairlead positions [m] and velocities [m/s] of ``line`` at times ``t``, (n, 3) each,
    under any prescribed motion: a body motion moves the fairlead as a body point, the other
    motions as :func:`floatmoor.motion.fairlead.fairlead_state` does."""
    if is_body_motion(motion):
        positions, velocities = body_points_state(motion, np.asarray([line.fairlead]), t)
        return positions[:, 0], velocities[:, 0]
    return fairlead_state(motion, line, t)


def start_line(motion: Motion | None, line: Line) -> Line:
    """``line`` as a run starts it: its fairlead where the prescribed motion puts it at t = 0.

    That is the rest position for every motion with a ramp (the ramp starts from zero
    displacement) and for a table whose first row is zero, and the table's first pose for one
    run without a ramp, so that the line is built (its catenary, its settled dynamic state) in
    the pose the run starts from and not at rest with the fairlead jumping away at t = 0.
    Returns ``line`` itself when its fairlead does not move at t = 0, else a copy with the
    fairlead moved (docs/theory/mooring_systems.md#prescribed-motion-of-the-body-points).
    """
    if motion is None:
        return line
    start = prescribed_fairlead_state(motion, line, np.zeros(1))[0][0]
    if np.array_equal(start, np.asarray(line.fairlead, dtype=float)):
        return line
    return replace(line, fairlead=(float(start[0]), float(start[1]), float(start[2])))
