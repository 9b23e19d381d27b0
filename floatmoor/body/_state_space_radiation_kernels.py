"""Numba kernels of the state-space radiation of the Cummins equation
(docs/theory/floater.md#radiation-convolution-or-state-space).

The radiation states z of all the pairs are one vector; pair p owns z[offsets[p]:offsets[p+1]],
is driven by the velocity of DOF ``radiating[p]`` and adds to the force on DOF
``influenced[p]``:

    z_p' = A_p z_p + b_p v_radiating,   mu_influenced += c_p . z_p,

and mu += D v (D: the feedthrough of the modes too fast for the body step, residualised). The
block A_p is stored as rows ``a[offsets[p] + r, :n_p]``. The RK4 stages of the body carry the
states (:meth:`floatmoor.body.cummins.CumminsBody.step`): stage s has
z_s = z_0 + h_s k_{s-1} and k_s = A z_s + B v_s; after the step
z = z_0 + dt / 6 (k_1 + 2 k_2 + 2 k_3 + k_4). tests/body/test_state_space_body.py compares
both kernels with dense NumPy matrices.
"""

from __future__ import annotations

import numpy as np

from floatmoor._numba import jit

__all__ = ["radiation_stage", "radiation_combine"]


@jit
def radiation_stage(a: np.ndarray, b: np.ndarray, c: np.ndarray, offsets: np.ndarray,
                    radiating: np.ndarray, influenced: np.ndarray, feedthrough: np.ndarray,
                    z0: np.ndarray, k_previous: np.ndarray, h: float, v: np.ndarray,
                    z: np.ndarray, k: np.ndarray, mu: np.ndarray) -> None:
    """One RK4 stage of the radiation states.

    Parameters
    ----------
    a : float64[S, w]
        Block rows of the state matrices [1/s].
    b, c : float64[S]
        Input [1] and output [K's units] vectors.
    offsets : int64[P + 1]
        First state of each pair (and the total).
    radiating, influenced : int64[P]
        DOFs of each pair.
    feedthrough : float64[6, 6]
        D, indices (influenced, radiating).
    z0 : float64[S]
        States at the start of the step.
    k_previous : float64[S]
        The previous stage's derivative (ignored when h = 0).
    h : float
        Stage offset of z from z0 [s].
    v : float64[6]
        The stage's body velocity.
    z, k, mu : float64[S], float64[S], float64[6]
        Written: the stage's states z0 + h k_previous, their derivative A z + B v, and the
        radiation force C z + D v.
    """
    n = z0.shape[0]
    for s in range(n):
        z[s] = z0[s] + h * k_previous[s]
    for i in range(6):
        acc = 0.0
        for j in range(6):
            acc += feedthrough[i, j] * v[j]
        mu[i] = acc
    for p in range(offsets.shape[0] - 1):
        lo = offsets[p]
        hi = offsets[p + 1]
        drive = v[radiating[p]]
        out = 0.0
        for r in range(lo, hi):
            acc = b[r] * drive
            for q in range(hi - lo):
                acc += a[r, q] * z[lo + q]
            k[r] = acc
            out += c[r] * z[r]
        mu[influenced[p]] += out


@jit
def radiation_combine(z0: np.ndarray, k1: np.ndarray, k2: np.ndarray, k3: np.ndarray,
                      k4: np.ndarray, dt: float, out: np.ndarray) -> None:
    """out = z0 + dt / 6 (k1 + 2 k2 + 2 k3 + k4) (the RK4 update, as the body's)."""
    sixth = dt / 6.0
    for s in range(z0.shape[0]):
        out[s] = z0[s] + sixth * (k1[s] + 2.0 * k2[s] + 2.0 * k3[s] + k4[s])
