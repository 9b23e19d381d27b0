"""Plain NumPy reference of the second-order force kernels
(floatmoor/waves/_second_order_kernels.py).

Written literally from the definitions, not from the kernels' factorisation: the QTF at every
pair of the sea's frequencies by bilinear interpolation on its grid (zero for a pair with a
frequency outside it), then the double sum over all ordered pairs

    F(t) = Re sum_i sum_j A_i conj(A_j) Q(w_i, w_j) e^{-i (w_i - w_j) t},

with every phase factor from np.exp. The band amplitudes and the Hermitian forms are
written the same way, one array expression each. O(N^2) per time: small seas only.
"""

from __future__ import annotations

import numpy as np


def bilinear(grid: np.ndarray, values: np.ndarray, w1: float, w2: float) -> np.ndarray:
    """values (M, M, n_dof) interpolated bilinearly at (w1, w2); zero outside the grid."""
    if not (grid[0] <= w1 <= grid[-1] and grid[0] <= w2 <= grid[-1]):
        return np.zeros(values.shape[2], dtype=values.dtype)
    i = min(int(np.searchsorted(grid, w1, side="right")) - 1, grid.size - 2)
    j = min(int(np.searchsorted(grid, w2, side="right")) - 1, grid.size - 2)
    u = (w1 - grid[i]) / (grid[i + 1] - grid[i])
    v = (w2 - grid[j]) / (grid[j + 1] - grid[j])
    return ((1 - u) * (1 - v) * values[i, j] + u * (1 - v) * values[i + 1, j]
            + (1 - u) * v * values[i, j + 1] + u * v * values[i + 1, j + 1])


def qtf_force(times: np.ndarray, omega: np.ndarray, amplitude: np.ndarray,
              grid: np.ndarray, qtf: np.ndarray) -> np.ndarray:
    """F(t) (n_times, n_dof) by the double sum over ordered pairs (complex amplitudes A)."""
    n = omega.size
    q = np.array([[bilinear(grid, qtf, omega[i], omega[j]) for j in range(n)]
                  for i in range(n)])  # (N, N, n_dof)
    pair = amplitude[:, None] * np.conj(amplitude)[None, :]
    out = np.empty((times.size, qtf.shape[2]))
    for k, t in enumerate(times):
        e = np.exp(-1j * (omega[:, None] - omega[None, :]) * t)
        out[k] = np.real(np.einsum("ij,ijd->d", pair * e, q))
    return out


def band_amplitudes(times: np.ndarray, omega: np.ndarray, weight_low: np.ndarray,
                    weight_high: np.ndarray, cell: np.ndarray, m: int) -> np.ndarray:
    """P[k, p] = sum_i phi_p(w_i) A_i e^{-i w_i t_k}, with the weights on the cells' nodes."""
    e = np.exp(-1j * np.outer(times, omega))  # (n, N)
    low = np.zeros((omega.size, m), dtype=complex)
    high = np.zeros((omega.size, m), dtype=complex)
    low[np.arange(omega.size), cell] = weight_low
    high[np.arange(omega.size), cell + 1] = weight_high
    return e @ (low + high)


def hermitian_forms(amplitude: np.ndarray, qtf: np.ndarray) -> np.ndarray:
    """F[k, d] = Re sum_pq Q[p, q, d] P[k, p] conj(P[k, q])."""
    return np.real(np.einsum("kp,pqd,kq->kd", amplitude, qtf, np.conj(amplitude)))
