"""First-order wave excitation force time series from transfer functions (the transfer
functions of a database, interpolated: :mod:`floatmoor.hydro.excitation_transfer`).

With X_j the complex excitation force per unit wave amplitude of component j (capytaine's
``excitation_force`` at omega_j and beta_j about the body's reference point, 6 DOF;
:mod:`floatmoor.hydro.excitation_transfer` interpolates it, this module only takes the
array), the force is

.. math::
    f(t) = \\Re\\Big\\{\\sum_j X_j A_j e^{-i\\omega_j t}\\Big\\} = \\Re\\Big\\{\\sum_j c_j
           e^{-i\\omega_j t}\\Big\\},\\qquad c_j = X_j a_j e^{i\\phi_j},

capytaine's e^{-i omega t} convention (see floatmoor.waves.realisation for why this equals
the WAMIT-style Re{X_W a_j e^{i(omega_j t + phi_j)}} with WAMIT-convention X_W,
docs/conventions.md). The
coefficients c_j are computed once; one time then costs N complex exponentials and an (N x 6)
product, a whole record a blocked matrix product (floatmoor.waves.synthesis).

A 3 h full-scale record costs a few seconds (benchmark
tests/waves/test_bench_waves.py::test_three_hour_record_cost; figures in
docs/validation/notes.md).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.waves.realisation import WaveField
from floatmoor.waves.synthesis import harmonic_sum

__all__ = ["WaveExcitation", "excitation_coefficients"]


def excitation_coefficients(field: WaveField, transfer: ArrayLike) -> NDArray[np.complex128]:
    """c_j = X_j a_j e^{i phi_j}, shape (N, n_dof).

    Parameters
    ----------
    field
        The sea (N components).
    transfer
        X at each component's frequency and direction, complex, shape (N, n_dof) [N/m, N m/m],
        capytaine convention.
    """
    x = np.asarray(transfer, dtype=complex)
    if x.ndim != 2 or x.shape[0] != field.n_components:
        raise ValueError(f"transfer must have shape (N={field.n_components}, n_dof), "
                         f"got {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError("transfer functions contain NaN or infinity")
    return x * field.complex_amplitude[:, None]


class WaveExcitation:
    """The excitation force of a sea on one body.

    Parameters
    ----------
    field
        The sea.
    transfer
        X[j, dof], complex, shape (N, n_dof) (see :func:`excitation_coefficients`).
    """

    def __init__(self, field: WaveField, transfer: ArrayLike) -> None:
        self.omega = field.omega
        self.coefficients = excitation_coefficients(field, transfer)
        self.coefficients.setflags(write=False)

    def __call__(self, t: float) -> NDArray[np.float64]:
        """f(t), shape (n_dof,) [N, N m]."""
        return (np.exp(-1j * self.omega * float(t)) @ self.coefficients).real

    def series(self, times: ArrayLike) -> NDArray[np.float64]:
        """f at many times, shape times.shape + (n_dof,) (fast on uniform grids)."""
        return harmonic_sum(self.coefficients, self.omega, times)
