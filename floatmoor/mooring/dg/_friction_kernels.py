"""Numba kernels of the stick-spring seabed friction (docs/theory/cable.md#seabed-friction).

Each DG node below the seabed holds a friction anchor a in the seabed plane (the nodes, not
extra quadrature points: the DG operator is collocated at the LGL nodes, where the seabed's
normal force, the drag and the lumped mass of ``_kernels._acceleration`` act, so the friction
force lives where the forces it balances do). With d = a - x (horizontal components), the
normal contact force per length N = k_b (z_b - z) and the stick stiffness k_s:

    f = k_s d                  if k_s |d| <= mu N  (stick)
    f = mu N d / |d|           otherwise           (slip)

The anchor moves only at committed steps (:func:`return_map`): in slip it is dragged to
x + (mu N / k_s) d / |d|, so that |f| = mu N; off the seabed it follows the node (a node
touches down with no stored shear). A rejected step leaves it where it was. The force is
continuous at contact (N -> 0) and at the stick-slip switch, and its tangent
(:func:`stick_tangent`) is exact on both sides, which is what Newton's method needs.

The kernels take scalars; ``_kernels`` and ``_implicit_kernels`` read them from ``prm``
(``P_KS``: k_s, 0 for the regularised Coulomb law of ``_kernels``).
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit

__all__ = ["stick_force", "stick_tangent", "return_map", "reset_anchors"]


@jit
def stick_force(dx: float, dy: float, cap: float, ks: float) -> tuple[float, float]:
    """Friction force per length (fx, fy) of a node displaced d = (dx, dy) from its anchor
    (anchor minus node), capped at ``cap`` = mu N [N/m]; ``ks`` the stick stiffness [N/m^2]."""
    fx, fy = ks * dx, ks * dy
    mag = math.sqrt(fx * fx + fy * fy)
    if mag > cap:
        s = cap / mag
        return fx * s, fy * s
    return fx, fy


@jit
def stick_tangent(dx: float, dy: float, cap: float, ks: float,
                  mu_kb: float) -> tuple[float, float, float, float, float, float]:
    """-df/d(x, y, z) of :func:`stick_force`, as (xx, xy, yx, yy, xz, yz): stick, k_s on the
    horizontal diagonal; slip, (mu N / |d|) (I - u u^T) with u = d / |d|, and mu k_b u in the
    z column (N = k_b (z_b - z) grows as the node sinks); ``mu_kb`` = mu k_b."""
    dl = math.sqrt(dx * dx + dy * dy)
    if ks * dl > cap:
        ux, uy = dx / dl, dy / dl
        s = cap / dl
        return (s * (1.0 - ux * ux), -s * ux * uy, -s * uy * ux, s * (1.0 - uy * uy),
                mu_kb * ux, mu_kb * uy)
    return ks, 0.0, 0.0, ks, 0.0, 0.0


@jit
def return_map(r: np.ndarray, fa: np.ndarray, ks: float, mu_kb: float, zb: float) -> None:
    """Commit a step: drag every sliding node's anchor to the friction cone's edge, set the
    anchors of nodes off the seabed (z >= ``zb``) to the nodes' horizontal positions;
    ``fa`` (K, Np, 2), ``ks`` the stick stiffness, ``mu_kb`` = mu k_b."""
    for k in range(r.shape[0]):
        for i in range(r.shape[1]):
            x, y = r[k, i, 0], r[k, i, 1]
            if r[k, i, 2] >= zb or ks <= 0.0:
                fa[k, i, 0], fa[k, i, 1] = x, y
                continue
            dx, dy = fa[k, i, 0] - x, fa[k, i, 1] - y
            dl = math.sqrt(dx * dx + dy * dy)
            cap = mu_kb * (zb - r[k, i, 2])
            if ks * dl > cap:
                s = cap / (ks * dl)
                fa[k, i, 0], fa[k, i, 1] = x + s * dx, y + s * dy


@jit
def reset_anchors(r: np.ndarray, fa: np.ndarray) -> None:
    """Every anchor at its node's horizontal position (no stored shear)."""
    for k in range(r.shape[0]):
        for i in range(r.shape[1]):
            fa[k, i, 0], fa[k, i, 1] = r[k, i, 0], r[k, i, 1]
