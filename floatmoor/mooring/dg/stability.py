"""Time-step limits of the DG cable from the spectrum of its linearised scheme.

The longitudinal waves of a taut line, with Kelvin-Voigt internal damping, obey
m v_t = d/ds (EA q + c_int q_t), q = dr/ds. Discretised exactly as the kernels do (alternating
traces, Lax-Friedrichs penalty, fixed ends), in units h = c = m = 1, they give a linear system
d/dt (r, v) = A (r, v) whose eigenvalues lambda must satisfy |R(lambda dt)| <= 1 with
R(z) = 1 + z + z^2/2 + z^3/6 for SSP-RK3. The largest such dt, times h / c, is the limit.
Without damping it depends on p only (``reference.STABLE_STEP_FACTOR`` tabulates it); with
damping also on the damping number nu = c_int / (m c h).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from floatmoor.mooring.dg.reference import reference_element

__all__ = ["linear_operator", "rk3_stable_step", "stable_step_factor"]

#: Elements of the model problem: the limit is local, 8 elements resolve it.
_ELEMENTS = 8


def linear_operator(p: int, damping_number: float = 0.0, elements: int = _ELEMENTS
                    ) -> NDArray[np.float64]:
    """The semi-discrete operator A of the scaled problem (h = c = m = 1, EA = 1)."""
    e = reference_element(p)
    K, Np = elements, p + 1
    n = K * Np
    D, LIFT, jac = e.differentiation, e.lift, 2.0

    def strong(u: NDArray[np.float64], faces: NDArray[np.float64]) -> NDArray[np.float64]:
        return jac * (u @ D.T - np.outer(faces[:-1] - u[:, 0], LIFT[:, 0])
                      + np.outer(faces[1:] - u[:, -1], LIFT[:, 1]))

    def gradient(u: NDArray[np.float64]) -> NDArray[np.float64]:
        faces = np.zeros(K + 1)  # fixed ends; interior traces from the anchor side
        faces[1:K] = u[:-1, -1]
        return strong(u, faces)

    def acceleration(r: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray[np.float64]:
        r, v = r.reshape(K, Np), v.reshape(K, Np)
        N = gradient(r) + damping_number * gradient(v)
        flux = np.zeros(K + 1)
        flux[0] = N[0, 0] + v[0, 0]
        flux[K] = N[-1, -1] - v[-1, -1]
        flux[1:K] = N[1:, 0] + 0.5 * (v[1:, 0] - v[:-1, -1])
        return strong(N, flux).reshape(-1)

    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    for j in range(n):
        x = np.zeros(n)
        x[j] = 1.0
        A[n:, j] = acceleration(x, np.zeros(n))
        A[n:, n + j] = acceleration(np.zeros(n), x)
    return A


def rk3_stable_step(eigenvalues: NDArray[np.complex128]) -> float:
    """Largest dt with every lambda dt inside the SSP-RK3 stability region (bisection)."""
    def stable(dt: float) -> bool:
        z = eigenvalues * dt
        return bool(np.all(np.abs(1 + z + z ** 2 / 2 + z ** 3 / 6) <= 1 + 1e-10))

    lo, hi = 0.0, 10.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


@lru_cache(maxsize=256)
def _factor(p: int, damping_key: float) -> float:
    return rk3_stable_step(np.linalg.eigvals(linear_operator(p, damping_key)))


def stable_step_factor(p: int, damping_number: float = 0.0) -> float:
    """dt_max c / h of order p with damping number nu = c_int / (m c h) (to 4 digits)."""
    key = float(f"{damping_number:.4g}")
    return _factor(p, key)
