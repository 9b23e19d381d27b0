"""Plain NumPy reference of one implicit (generalised-alpha) step of the DG cable.

Written from the method as :mod:`floatmoor.mooring.dg._implicit_kernels` states it (Chung &
Hulbert 1993, the force-interpolating form), on the NumPy right-hand side of
:mod:`tests.oracles.dg_numpy`, with Newton's method on a dense Jacobian taken by central
differences of the force F = M_eff A (no analytic derivative, no band storage, no reuse of
factors): an independent route to the same step.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from tests.oracles import dg_numpy as oracle

Array = NDArray[np.float64]


def generalised_alpha(rho_inf: float) -> tuple[float, float, float, float]:
    """(alpha_m, alpha_f, beta, gamma), Chung & Hulbert (1993) eqs. 25 and 17."""
    am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0)
    af = rho_inf / (rho_inf + 1.0)
    return am, af, 0.25 * (1.0 - am + af) ** 2, 0.5 - am + af


def mass_times(r: Array, q: Array, x: Array, m: float, m_an: float, m_at: float) -> Array:
    """M_eff x per node (Morison added mass below z = 0)."""
    ql = np.linalg.norm(q, axis=-1)
    t = np.where(ql[..., None] > 0.0, q / np.where(ql > 0.0, ql, 1.0)[..., None], 0.0)
    wet = r[..., 2] < 0.0
    mn = m + np.where(wet, m_an, 0.0)
    mt = m + np.where(wet, m_at, 0.0)
    xt = np.sum(x * t, axis=-1)
    return mn[..., None] * x + ((mt - mn) * xt)[..., None] * t


def step(r: Array, v: Array, acc: Array, boundary: Callable[[float], tuple[Array, Array]],
         t: float, dt: float, rho_inf: float, rhs_kwargs: dict, tol: float = 1e-13,
         max_iter: int = 30, fd_step: float = 1e-7) -> tuple[Array, Array, Array]:
    """One step of (r, v, acc) from t to t + dt; ``boundary(time)`` gives the fairlead position
    and velocity; ``rhs_kwargs`` the parameters of :func:`tests.oracles.dg_numpy.rhs` (with
    ``anchor``, ``D``, ``LIFT``, ``h`` and the physical constants). Returns the new state."""
    am, af, beta, gamma = generalised_alpha(rho_inf)
    kw = dict(rhs_kwargs)
    anchor = kw.pop("anchor")
    m, m_an, m_at = kw["m"], kw.get("m_an", 0.0), kw.get("m_at", 0.0)

    def accel(rr: Array, vv: Array, time: float) -> tuple[Array, Array]:
        fpos, fvel = boundary(time)
        a, fields = oracle.rhs(rr, vv, anchor, fpos, fvel, **kw)
        return a, fields.q

    An, _ = accel(r, v, t)
    shape = r.shape

    def residual(a1: Array) -> Array:
        r1 = r + dt * v + dt * dt * ((0.5 - beta) * acc + beta * a1)
        v1 = v + dt * ((1.0 - gamma) * acc + gamma * a1)
        A1, q1 = accel(r1, v1, t + dt)
        R = (1.0 - am) * a1 + am * acc - (1.0 - af) * A1 - af * An
        return mass_times(r1, q1, R, m, m_an, m_at).reshape(-1)

    a1 = acc.copy()
    for _ in range(max_iter):
        R0 = residual(a1)
        n = R0.size
        J = np.empty((n, n))
        scale = fd_step * max(1.0, float(np.max(np.abs(a1))))
        for j in range(n):
            e = np.zeros(n)
            e[j] = scale
            J[:, j] = (residual(a1 + e.reshape(shape)) - residual(a1 - e.reshape(shape))) / (
                2.0 * scale)
        da = np.linalg.solve(J, -R0).reshape(shape)
        a1 = a1 + da
        if np.max(np.abs(beta * dt * dt * da)) <= tol:
            break
    r1 = r + dt * v + dt * dt * ((0.5 - beta) * acc + beta * a1)
    v1 = v + dt * ((1.0 - gamma) * acc + gamma * a1)
    return r1, v1, a1
