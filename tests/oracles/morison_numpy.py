"""Plain NumPy reference of the Morison drag kernels (floatmoor/body/_morison_kernels.py).

Written literally, one array expression per equation of floatmoor/body/morison.py: rotation
R = Rz Ry Rx built from elementary matrices (not the closed form of the kernel), point
velocities v + omega x R r0, relative velocity u = u_fluid - v_point, axial and normal parts,
f = cn |u_n| u_n + ca |u . e| (u . e) e, and the sums F = sum f, M = sum (R r0) x f. The time
interpolation is the cubic Lagrange polynomial through four samples written with
numpy.polyfit-free Lagrange basis products. Units SI.
"""

from __future__ import annotations

import numpy as np


def rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rz(yaw) @ Ry(pitch) @ Rx(roll) from the three elementary rotations."""
    cr, sr = np.cos(roll), np.sin(roll)
    cp, sp = np.cos(pitch), np.sin(pitch)
    cy, sy = np.cos(yaw), np.sin(yaw)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
    ry = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    return rz @ ry @ rx


def drag_force(x: np.ndarray, v: np.ndarray, arms: np.ndarray, axes: np.ndarray,
               cn: np.ndarray, ca: np.ndarray, fluid: np.ndarray) -> np.ndarray:
    """6-DOF drag force of strips (arms, axes (n, 3); cn, ca (n,)) for fluid velocities
    ``fluid`` (n, 3) at body state x, v (6,)."""
    r = rotation(x[3], x[4], x[5])
    arm = arms @ r.T
    e = axes @ r.T
    v_point = v[:3] + np.cross(v[3:], arm)
    u = fluid - v_point
    ua = np.sum(u * e, axis=1)
    u_axial = ua[:, None] * e
    u_normal = u - u_axial
    f = (cn * np.linalg.norm(u_normal, axis=1))[:, None] * u_normal \
        + (ca * np.abs(ua))[:, None] * u_axial
    return np.concatenate([f.sum(axis=0), np.cross(arm, f).sum(axis=0)])


def lagrange_interpolate(times_coarse: np.ndarray, values: np.ndarray,
                         t: float) -> np.ndarray:
    """Cubic Lagrange interpolation at ``t`` through the four coarse samples around it
    (times_coarse uniform; t between the second and third of the chosen four)."""
    h = times_coarse[1] - times_coarse[0]
    j = int(np.floor((t - times_coarse[0]) / h + 1e-12))
    idx = np.arange(j - 1, j + 3)
    nodes = times_coarse[idx]
    out = np.zeros(values.shape[1:])
    for a in range(4):
        basis = 1.0
        for b in range(4):
            if b != a:
                basis *= (t - nodes[b]) / (nodes[a] - nodes[b])
        out = out + basis * values[idx[a]]
    return out
