"""Sums of harmonic components, Re{sum_j c_j e^{-i omega_j t}}, over many times at once.

The one numerical kernel behind wave elevation and excitation time series. Pure NumPy (no
numba): the work is a complex matrix product, which BLAS already does near peak speed.

For a uniform time grid t_n = t_0 + n dt the phase factors are split as
e^{-i omega (t_b + tau_m)} = e^{-i omega t_b} e^{-i omega tau_m}, with tau_m = m dt for
m < block: the block matrix B[m, j] = e^{-i omega_j tau_m} is built once and every block of
times is one product B @ (c e^{-i omega t_b}). This needs one complex exponential per component
and block instead of one per component and time step, and it stays exact (no recurrence, so
no round-off drift over a 3-hour record). Any other time grid is summed directly in chunks.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["harmonic_sum"]

#: Largest number of complex entries of a temporary (time x component) matrix: 2**22 entries
#: are 64 MiB of complex128, small enough beside a simulation, large enough for BLAS.
_MAX_TEMPORARY = 2 ** 22
#: A time grid counts as uniform when every time is within this many ulps (of the largest
#: |t|) of the ideal grid t_0 + n dt: the rounding np.arange / np.linspace leave. The block
#: method then uses the ideal grid, an error no larger than the rounding of t itself.
_UNIFORM_ULPS = 64.0


def _is_uniform(t: NDArray[np.float64]) -> bool:
    if t.size < 3:
        return False
    step = (t[-1] - t[0]) / (t.size - 1)
    ideal = t[0] + step * np.arange(t.size)
    tol = _UNIFORM_ULPS * np.finfo(float).eps * float(np.abs(t).max())
    return step > 0.0 and bool(np.all(np.abs(t - ideal) <= tol))


def harmonic_sum(coefficients: ArrayLike, omega: ArrayLike,
                 times: ArrayLike) -> NDArray[np.float64]:
    """Evaluate f(t) = Re{sum_j c_j e^{-i omega_j t}} at many times.

    Parameters
    ----------
    coefficients
        Complex c_j, shape (N,) or (N, m) for m signals sharing the frequencies.
    omega
        Angular frequencies omega_j [rad/s], shape (N,).
    times
        Times [s], any shape.

    Returns
    -------
    numpy.ndarray
        Real values, shape ``times.shape`` (+ (m,) if ``coefficients`` is 2-D).
    """
    c = np.asarray(coefficients, dtype=complex)
    w = np.asarray(omega, dtype=float)
    t_in = np.asarray(times, dtype=float)
    squeeze = c.ndim == 1
    if squeeze:
        c = c[:, None]
    if c.shape[0] != w.shape[0]:
        raise ValueError(f"{c.shape[0]} coefficients for {w.shape[0]} frequencies")
    t = t_in.ravel()
    out = np.empty((t.size, c.shape[1]))
    n = w.size
    if n == 0 or t.size == 0:
        out[:] = 0.0
    elif _is_uniform(t):
        dt = (t[-1] - t[0]) / (t.size - 1)
        block = int(max(1, min(t.size, _MAX_TEMPORARY // max(n, 1))))
        tau = dt * np.arange(block)
        b = np.exp(-1j * np.outer(tau, w))  # (block, N)
        for start in range(0, t.size, block):
            stop = min(start + block, t.size)
            t_b = t[0] + start * dt
            d = c * np.exp(-1j * w * t_b)[:, None]
            out[start:stop] = (b[:stop - start] @ d).real
    else:
        chunk = int(max(1, _MAX_TEMPORARY // max(n, 1)))
        for start in range(0, t.size, chunk):
            tt = t[start:start + chunk]
            out[start:start + chunk] = (np.exp(-1j * np.outer(tt, w)) @ c).real
    out = out.reshape(t_in.shape + (c.shape[1],))
    return out[..., 0] if squeeze else out
