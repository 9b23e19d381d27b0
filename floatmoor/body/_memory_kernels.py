"""Numba kernel of the radiation memory of the Cummins equation (docs/theory/floater.md).

mu(t_n) = int_0^T_K K(s) v(t_n - s) ds with the velocity piecewise linear between the step
points t_n - k dt: mu_n = sum_k W_k v(t_n - k dt), the weights W_k = int K(s) phi_k(s) ds
integrating the kernel against the hat functions phi_k of the grid (:func:`hat_weights`,
from a finely sampled K: the kernel's sharp peak at s = 0 of DOFs whose damping decays
slowly, e.g. surge, is integrated at the fine resolution, not sampled at dt). The
velocities are held in a ring buffer; before the start they are zero (the body at rest).
Only the DOF pairs with non-zero weights are summed (``pairs``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from floatmoor._numba import jit

__all__ = ["memory_force", "hat_weights"]


def hat_weights(t_fine: NDArray[np.float64], kernel_fine: NDArray[np.float64],
                dt: float, *,
                start: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
                ) -> NDArray[np.float64]:
    """W_k = int_0^T K(s) phi_k(s) ds, k = 0 .. m - 1, with phi_k the hat function of the grid
    k dt (half a hat at k = 0; the last one truncated at T), by the trapezoidal rule on the
    fine grid ``t_fine`` (uniform, from 0, its step dividing dt).

    Parameters
    ----------
    t_fine : (n,)
    kernel_fine : (n, 6, 6)
    dt : float
    start : ((n0,), (n0, 6, 6)), optional
        K sampled more finely over [0, 2 dt] (uniform from 0, its step dividing dt): W_0 and
        W_1, whose hats reach s = 0, are taken from these samples. A kernel whose damping
        decays slowly at high frequency (surge and sway of a semisubmersible, tail exponent
        near 1) has a cusp at s = 0 that the body-step grid under-resolves: on DeepCwind at
        dt = 0.1 s with samples every dt / 10, W_0 of surge is 1.3 % off, which is a
        spurious 3 kN s/m of low-frequency surge damping (the sum of the weights is B(0)).

    Returns
    -------
    ndarray (m, 6, 6), m = floor(T / dt) + 1.
    """
    out = _hat_weights_on(t_fine, kernel_fine, dt)
    if start is not None:
        t0, k0 = np.asarray(start[0], float), np.asarray(start[1], float)
        if t0[0] != 0.0 or t0[-1] < min(2.0 * dt, float(t_fine[-1])) * (1.0 - 1e-12):
            raise ValueError("start: the fine samples must cover [0, 2 dt] from s = 0")
        near = _hat_weights_on(t0, k0, dt)
        n = min(2, out.shape[0], near.shape[0])
        out[:n] = near[:n]
    return out


def _hat_weights_on(t_fine: NDArray[np.float64], kernel_fine: NDArray[np.float64],
                    dt: float) -> NDArray[np.float64]:
    """The hat weights by the trapezoidal rule on ``t_fine`` (see :func:`hat_weights`)."""
    h = float(t_fine[1] - t_fine[0])
    ratio = dt / h
    r = int(round(ratio))
    if r < 1 or abs(ratio - r) > 1e-6 * ratio:
        raise ValueError(f"the fine kernel step {h} must divide the time step {dt}")
    n = t_fine.size
    m = (n - 1) // r + 1
    s = np.arange(n) / r  # fine time in steps
    trap = np.full(n, h)
    trap[0] = trap[-1] = 0.5 * h
    out = np.zeros((m,) + kernel_fine.shape[1:])
    for k in range(m):
        lo, hi = max((k - 1) * r, 0), min((k + 1) * r, n - 1)
        phi = 1.0 - np.abs(s[lo:hi + 1] - k)
        w = trap[lo:hi + 1].copy()
        # the trapezoid weights of the sub-range: ends of the hat support carry half steps
        w[0] = 0.5 * h if lo > 0 else w[0]
        w[-1] = 0.5 * h if hi < n - 1 else w[-1]
        out[k] = np.tensordot(phi * w, kernel_fine[lo:hi + 1], axes=(0, 0))
    return out


@jit
def memory_force(weights: np.ndarray, pairs: np.ndarray, history: np.ndarray, newest: int,
                 filled: int, out: np.ndarray) -> None:
    """mu_i = sum_j sum_k W_k[i, j] v_j(t_n - k dt), written to ``out`` (6,).

    Parameters
    ----------
    weights : float64[m, 6, 6]
        W_k (:func:`hat_weights`), indices (influenced i, radiating j) [N s/m, ...].
    pairs : int64[p, 2]
        The (i, j) pairs to sum.
    history : float64[m, 6]
        Ring buffer of velocities; ``history[newest]`` is v(t_n), ``history[newest - k]``
        (modulo m) is v(t_n - k dt).
    filled : int
        Samples of real history in the buffer (older ones are the rest state, zero).
    """
    m = weights.shape[0]
    for i in range(6):
        out[i] = 0.0
    n = min(filled, m)
    for p in range(pairs.shape[0]):
        i = pairs[p, 0]
        j = pairs[p, 1]
        acc = 0.0
        for k in range(n):
            slot = newest - k
            if slot < 0:
                slot += m
            acc += weights[k, i, j] * history[slot, j]
        out[i] += acc
