"""Numba kernels of banded linear algebra: LU factorisation without pivoting and its solve.

A banded matrix with ``kl`` sub- and ``ku`` super-diagonals is stored row-wise: entry (i, j) at
``band[i, kl + j - i]``, a (n, kl + ku + 1) array. Without pivoting the factors stay inside the
band (Golub & Van Loan, *Matrix Computations*, 4th ed., algorithm 4.3.1); that is safe for the
matrices factored here, the mass matrix plus dt times a dissipative operator or the iteration
matrix of an implicit step, whose diagonal dominates or which are positive definite in the
mass-weighted inner product. A pivot that is zero or not finite is reported, not divided by.
The NumPy reference is ``scipy.linalg.solve_banded`` (tests/mooring/dg/test_dg_implicit_kernels.py).
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit

__all__ = ["band_factor", "band_solve"]


@jit
def band_factor(band: np.ndarray, n: int, kl: int, ku: int) -> int:
    """LU-factor the banded matrix in place (unit lower factor below the diagonal).

    Returns
    -------
    int
        -1 on success, else the row whose pivot was zero or not finite.
    """
    for col in range(n):
        piv = band[col, kl]
        if piv == 0.0 or not math.isfinite(piv):
            return col
        # the pivot row's last nonzero: the updates beyond it would subtract exact zeros (the
        # same bits without them; a DG Jacobian's row ends up to 3 Np before the band's edge)
        last = min(n - 1, col + ku)
        while last > col and band[col, kl + last - col] == 0.0:
            last -= 1
        for rr in range(col + 1, min(n, col + kl + 1)):
            lf = band[rr, kl + col - rr]
            if lf == 0.0:
                continue
            lf /= piv
            band[rr, kl + col - rr] = lf
            for cc in range(col + 1, last + 1):
                band[rr, kl + cc - rr] -= lf * band[col, kl + cc - col]
    return -1


@jit
def band_solve(band: np.ndarray, n: int, kl: int, ku: int, x: np.ndarray) -> None:
    """Solve with the factors of :func:`band_factor`, the right-hand side ``x`` overwritten
    by the solution."""
    for row in range(n):  # forward substitution (unit lower factor)
        acc = x[row]
        for cc in range(max(0, row - kl), row):
            acc -= band[row, kl + cc - row] * x[cc]
        x[row] = acc
    for row in range(n - 1, -1, -1):
        acc = x[row]
        for cc in range(row + 1, min(n, row + ku + 1)):
            acc -= band[row, kl + cc - row] * x[cc]
        x[row] = acc / band[row, kl]
