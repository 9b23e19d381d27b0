"""Numba kernels of the Morison drag on a floater's strips (floatmoor/body/morison.py).

:func:`drag_force` is the per-stage evaluation: for every strip i (body-fixed point with rest
arm r0_i from the reference point, rest axis e0_i, transverse coefficient cn_i = 1/2 rho Cd D ds
[kg/m] and axial coefficient ca_i [kg/m]) at the body state (x, v):

    R       = Rz(x5) Ry(x4) Rx(x3)                    (floatmoor.body.kinematics)
    r_i     = R r0_i,   e_i = R e0_i
    u_i     = u_fluid_i - (v[:3] + v[3:] x r_i)       relative velocity
    u_a     = (u_i . e_i) e_i,   u_n = u_i - u_a
    f_i     = cn_i |u_n| u_n + ca_i |u_i . e_i| u_a
    F       = sum_i f_i,   M = sum_i r_i x f_i        (about the displaced reference point)

:func:`lagrange_fill` interpolates the fluid velocity from a coarse time grid to the half-step
grid with the 4-point (cubic) Lagrange polynomial.

Both kernels allocate nothing: outputs are written into arrays the caller owns. Plain NumPy
references: tests/oracles/morison_numpy.py.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from floatmoor._numba import jit
from floatmoor._rotations_kernels import rotation

__all__ = ["drag_force", "lagrange_fill", "lagrange_weights"]


@jit
def drag_force(x: NDArray[np.float64], v: NDArray[np.float64], arms: NDArray[np.float64],
               axes: NDArray[np.float64], cn: NDArray[np.float64], ca: NDArray[np.float64],
               fluid: NDArray[np.float64], k: int, out: NDArray[np.float64]) -> None:
    """Write the 6-DOF drag force (N, N m) into ``out`` (6,).

    Parameters
    ----------
    x, v : (6,)
        Body displacement [m, rad] and velocity [m/s, rad/s] about the reference point.
    arms, axes : (n, 3)
        Rest arms r0 [m] and unit rest axes e0 of the strips.
    cn, ca : (n,)
        Transverse and axial quadratic coefficients [kg/m].
    fluid : (m, n, 3)
        Fluid velocity at the strips [m/s]; row ``k`` is used.
    k : int
        Row of ``fluid``.
    out : (6,)
        Output.
    """
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = rotation(x[3], x[4], x[5])
    vx, vy, vz = v[0], v[1], v[2]
    wx, wy, wz = v[3], v[4], v[5]
    fx = fy = fz = 0.0
    mx = my = mz = 0.0
    for i in range(arms.shape[0]):
        a0, a1, a2 = arms[i, 0], arms[i, 1], arms[i, 2]
        px = r00 * a0 + r01 * a1 + r02 * a2
        py = r10 * a0 + r11 * a1 + r12 * a2
        pz = r20 * a0 + r21 * a1 + r22 * a2
        b0, b1, b2 = axes[i, 0], axes[i, 1], axes[i, 2]
        ex = r00 * b0 + r01 * b1 + r02 * b2
        ey = r10 * b0 + r11 * b1 + r12 * b2
        ez = r20 * b0 + r21 * b1 + r22 * b2
        # relative velocity: fluid minus body point (v + omega x r)
        ux = fluid[k, i, 0] - (vx + wy * pz - wz * py)
        uy = fluid[k, i, 1] - (vy + wz * px - wx * pz)
        uz = fluid[k, i, 2] - (vz + wx * py - wy * px)
        ua = ux * ex + uy * ey + uz * ez
        nx = ux - ua * ex
        ny = uy - ua * ey
        nz = uz - ua * ez
        un = math.sqrt(nx * nx + ny * ny + nz * nz)
        gn = cn[i] * un
        ga = ca[i] * abs(ua) * ua
        f0 = gn * nx + ga * ex
        f1 = gn * ny + ga * ey
        f2 = gn * nz + ga * ez
        fx += f0
        fy += f1
        fz += f2
        mx += py * f2 - pz * f1
        my += pz * f0 - px * f2
        mz += px * f1 - py * f0
    out[0] = fx
    out[1] = fy
    out[2] = fz
    out[3] = mx
    out[4] = my
    out[5] = mz


def lagrange_weights(m: int) -> NDArray[np.float64]:
    """Weights (m, 4) of the cubic Lagrange polynomial through the nodes -1, 0, 1, 2 at the
    fractions s = r / m, r = 0 .. m - 1 (value at s from the samples at -1, 0, 1, 2)."""
    s = np.arange(m) / m
    w = np.empty((m, 4))
    w[:, 0] = -s * (s - 1.0) * (s - 2.0) / 6.0
    w[:, 1] = (s + 1.0) * (s - 1.0) * (s - 2.0) / 2.0
    w[:, 2] = -(s + 1.0) * s * (s - 2.0) / 2.0
    w[:, 3] = (s + 1.0) * s * (s - 1.0) / 6.0
    return w


@jit
def lagrange_fill(coarse: NDArray[np.float64], weights: NDArray[np.float64],
                  out: NDArray[np.float64]) -> None:
    """Interpolate rows of ``coarse`` (J, c) onto a grid m times finer into ``out`` (n, c).

    Coarse row j + 1 sits at fine index j m (coarse row 0 is one coarse step before the first
    fine time); fine index k = j m + r takes the rows j, j + 1, j + 2, j + 3 with the weights
    ``weights[r]`` (:func:`lagrange_weights`). Needs J >= (n - 1) // m + 4.
    """
    m = weights.shape[0]
    for k in range(out.shape[0]):
        j = k // m
        r = k - j * m
        w0, w1, w2, w3 = weights[r, 0], weights[r, 1], weights[r, 2], weights[r, 3]
        for c in range(out.shape[1]):
            out[k, c] = (w0 * coarse[j, c] + w1 * coarse[j + 1, c] + w2 * coarse[j + 2, c]
                         + w3 * coarse[j + 3, c])
