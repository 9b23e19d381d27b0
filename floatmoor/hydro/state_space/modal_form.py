"""Real modal form of a sum of exponential modes: the shape of every state-space realisation.

A realisation of an impulse response K(t) = sum_k r_k e^{lambda_k t} keeps A with a 1 x 1
block per real pole and a 2 x 2 block [[sigma, omega], [-omega, sigma]] per complex pair (b of
ones and zeros), so it is stored as two diagonals and integrated without complex states. These
are the conversions between that form and poles and residues, shared by the fit
(:mod:`floatmoor.hydro.state_space.kernel_fit`) and the body's radiation states
(:mod:`floatmoor.body.state_space_radiation`); nothing here depends on a database.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["modal_realisation", "modes", "kernel_of", "transfer_of"]


def modal_realisation(poles: NDArray[np.complex128], coefficients: NDArray[np.float64]
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Real modal (A, b, c) of K(t) = sum over the modes of their terms.

    Parameters
    ----------
    poles
        One entry per real pole (imaginary part 0) and per complex pair (the one with
        positive imaginary part).
    coefficients
        One real coefficient r per real pole (term r e^{lambda t}), two per complex pair,
        (alpha, beta) for e^{sigma t} (alpha cos(omega t) + beta sin(omega t)), in the order
        of ``poles``.

    Returns
    -------
    a (n, n), b (n,), c (n,)
    """
    n = sum(1 if p.imag == 0.0 else 2 for p in poles)
    a = np.zeros((n, n))
    b = np.zeros(n)
    c = np.zeros(n)
    k = 0
    for p in poles:
        if p.imag == 0.0:
            a[k, k] = p.real
            b[k] = 1.0
            c[k] = coefficients[k]
            k += 1
        else:
            s, w = p.real, p.imag
            a[k:k + 2, k:k + 2] = [[s, w], [-w, s]]
            b[k + 1] = 1.0
            # exp(A t) b = e^{st} (sin wt, cos wt): c = (beta, alpha)
            c[k], c[k + 1] = coefficients[k + 1], coefficients[k]
            k += 2
    return a, b, c


def modes(a: NDArray[np.float64], b: NDArray[np.float64], c: NDArray[np.float64]
          ) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Poles lambda_k and residues r_k of c (sI - A)^-1 b = sum_k r_k / (s - lambda_k) (A
    diagonalisable: distinct poles, as the fits give)."""
    lam, vec = np.linalg.eig(np.asarray(a, float))
    left = np.asarray(c, float) @ vec
    right = np.linalg.solve(vec, np.asarray(b, float).astype(complex))
    return lam, left * right


def kernel_of(a, b, c, t: NDArray[np.float64]) -> NDArray[np.float64]:
    """K(t) = c exp(A t) b at the times ``t``."""
    lam, res = modes(a, b, c)
    return np.real(np.exp(np.outer(t, lam)) @ res)


def transfer_of(a, b, c, omega: NDArray[np.float64]) -> NDArray[np.complex128]:
    """H(i omega) = c (i omega - A)^-1 b at the frequencies ``omega``."""
    lam, res = modes(a, b, c)
    return (1.0 / (1j * np.asarray(omega, float)[:, None] - lam[None, :])) @ res
