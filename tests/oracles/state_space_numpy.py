"""Plain NumPy reference of the state-space radiation of the Cummins body
(floatmoor/body/_state_space_radiation_kernels.py and CumminsBody._step_state_space).

Written as dense matrices of the whole system: A (S, S) block-diagonal from the pairs' blocks,
B (S, 6) with b_p in the column of the pair's radiating DOF, C (6, S) with c_p in the row of
its influenced DOF, and D (6, 6); the stage is z = z0 + h k_prev, k = A z + B v,
mu = C z + D v, and the body step the classical RK4 of
(M + A_inf) x'' = F_0 - K x - mu + f, z' = A z + B x' written out for the state (x, v, z).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def dense(states) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(A, B, C, D) of a :class:`floatmoor.body.state_space_radiation.RadiationStates`."""
    n = states.n_states
    a = np.zeros((n, n))
    b = np.zeros((n, 6))
    c = np.zeros((6, n))
    for p in range(len(states.radiating)):
        lo, hi = states.offsets[p], states.offsets[p + 1]
        a[lo:hi, lo:hi] = states.a[lo:hi, :hi - lo]
        b[lo:hi, states.radiating[p]] = states.b[lo:hi]
        c[states.influenced[p], lo:hi] = states.c[lo:hi]
    return a, b, c, states.feedthrough.copy()


def stage(matrices, z0: np.ndarray, k_previous: np.ndarray, h: float, v: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(z, k, mu) of one RK4 stage."""
    a, b, c, d = matrices
    z = z0 + h * k_previous
    return z, a @ z + b @ v, c @ z + d @ v


def body_step(body, matrices, x: np.ndarray, v: np.ndarray, z: np.ndarray, t: float,
              force: Callable[[float, np.ndarray, np.ndarray], np.ndarray]
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One RK4 step of length body.dt of the state (x, v, z) with the external force
    ``force(t, x, v)`` (no damping matrices)."""
    a, b, c, d = matrices
    m_inv = np.linalg.inv(body.mass)

    def rate(s: np.ndarray, tau: float) -> np.ndarray:
        xs, vs, zs = s[:6], s[6:12], s[12:]
        acc = m_inv @ (body.static_force - body.stiffness @ xs - (c @ zs + d @ vs)
                       + force(t + tau, xs, vs))
        return np.concatenate([vs, acc, a @ zs + b @ vs])

    dt = body.dt
    s0 = np.concatenate([x, v, z])
    k1 = rate(s0, 0.0)
    k2 = rate(s0 + 0.5 * dt * k1, 0.5 * dt)
    k3 = rate(s0 + 0.5 * dt * k2, 0.5 * dt)
    k4 = rate(s0 + dt * k3, dt)
    s = s0 + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return s[:6], s[6:12], s[12:]
