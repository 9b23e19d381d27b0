"""Numba kernels of the difference-frequency (full QTF) wave force (floatmoor/waves/second_order.py).

With the QTF interpolated bilinearly on its frequency grid g_0 < ... < g_{M-1}, the
interpolant is a tensor product of the grid's hat functions phi_p (phi_p(g_q) = delta_pq,
linear between nodes, zero outside the grid):

    Q(w_i, w_j) = sum_p sum_q phi_p(w_i) Q_pq phi_q(w_j),

so the double sum over the sea's N components collapses onto the M grid nodes:

    F(t) = Re sum_i sum_j A_i conj(A_j) Q(w_i, w_j) e^{-i (w_i - w_j) t}
         = Re sum_p sum_q Q_pq P_p(t) conj(P_q(t)),   P_p(t) = sum_i phi_p(w_i) A_i e^{-i w_i t}.

Each component feeds the two hats of its grid cell, so the P_p cost 2 N products per time
(:func:`band_amplitudes`) and the Hermitian form M^2 / 2 per DOF (:func:`hermitian_forms`),
for any frequencies (equally spaced or random in their bins): no N x N pair loop. This is exact
for the bilinear interpolant, not an approximation of it.

Phase factors: e^{-i w t} is computed exactly at the first time and every :data:`RESYNC`
steps, and advanced between by the exact one-step factor e^{-i w h}; the rounding of that
recurrence grows by a few ulps per step, so RESYNC = 64 bounds it by about 1e-14 of a phase
factor's magnitude (the oracle comparison in tests/waves/test_second_order.py).

Both kernels allocate only their scratch at entry, nothing in their time loops; outputs go
into arrays the caller owns. Plain NumPy references: tests/oracles/second_order_numpy.py.
"""

from __future__ import annotations

import cmath

import numpy as np
from numpy.typing import NDArray

from floatmoor._numba import jit

__all__ = ["band_amplitudes", "hermitian_forms", "RESYNC"]

#: Steps between exact evaluations of the phase factors (see the module docstring).
RESYNC = 64


@jit
def band_amplitudes(t0: float, h: float, omega: NDArray[np.float64],
                    weight_low: NDArray[np.complex128], weight_high: NDArray[np.complex128],
                    cell: NDArray[np.int64], out: NDArray[np.complex128]) -> None:
    """Write P[k, p] = sum_i phi_p(w_i) A_i e^{-i w_i (t0 + k h)} into ``out``.

    Parameters
    ----------
    t0, h
        First time and time step [s] of the uniform grid of ``out.shape[0]`` times.
    omega : (N,)
        Component frequencies [rad/s].
    weight_low, weight_high : (N,)
        phi_c(w_i) A_i and phi_{c+1}(w_i) A_i, c = ``cell[i]``: the component's weights on the
        lower and upper node of its grid cell (zero for a component outside the grid).
    cell : (N,)
        Lower node of each component's cell, 0 <= cell < M - 1.
    out : (n, M) complex
        Output (overwritten).
    """
    n, m = out.shape
    count = omega.shape[0]
    phase = np.empty(count, dtype=np.complex128)
    step = np.empty(count, dtype=np.complex128)
    for i in range(count):
        step[i] = cmath.exp(-1j * omega[i] * h)
    for k in range(n):
        if k % RESYNC == 0:
            t = t0 + k * h
            for i in range(count):
                phase[i] = cmath.exp(-1j * omega[i] * t)
        for p in range(m):
            out[k, p] = 0.0
        for i in range(count):
            e = phase[i]
            c = cell[i]
            out[k, c] += weight_low[i] * e
            out[k, c + 1] += weight_high[i] * e
            phase[i] = e * step[i]


@jit
def hermitian_forms(amplitude: NDArray[np.complex128], qtf: NDArray[np.complex128],
                    out: NDArray[np.float64]) -> None:
    """Write F[k, d] = sum_p sum_q Q[p, q, d] P[k, p] conj(P[k, q]) into ``out``.

    ``qtf`` must be Hermitian in (p, q) for every d (the caller makes it so: the real part of
    the form only sees the Hermitian part); the kernel reads its upper triangle.

    Parameters
    ----------
    amplitude : (n, M) complex
        P[k, p] (:func:`band_amplitudes`).
    qtf : (M, M, n_dof) complex
        Hermitian QTF on the grid nodes.
    out : (n, n_dof)
        Output [the QTF's unit times m^2] (overwritten).
    """
    n, m = amplitude.shape
    n_dof = qtf.shape[2]
    acc = np.empty(n_dof)
    for k in range(n):
        for d in range(n_dof):
            acc[d] = 0.0
        for p in range(m):
            a = amplitude[k, p]
            power = a.real * a.real + a.imag * a.imag
            for d in range(n_dof):
                acc[d] += qtf[p, p, d].real * power
            for q in range(p + 1, m):
                z = a * amplitude[k, q].conjugate()
                zr, zi = 2.0 * z.real, 2.0 * z.imag
                for d in range(n_dof):
                    acc[d] += qtf[p, q, d].real * zr - qtf[p, q, d].imag * zi
        for d in range(n_dof):
            out[k, d] = acc[d]
