"""State-space realisations of the radiation kernel K(t): one pair's, and a database's.

:class:`PairRealisation` holds one K_ij(t) ~ c exp(A t) b in real modal form
(:mod:`floatmoor.hydro.state_space.modal_form`) with its errors against the kernel and the
BEM values; :class:`StateSpaceRadiation` the pairs of a database together with what they were
fitted from. The fit is :mod:`floatmoor.hydro.state_space.kernel_fit` (one kernel) and
:mod:`floatmoor.hydro.state_space.fit` (a database); the file storage
:mod:`floatmoor.hydro.state_space.storage`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from floatmoor.hydro.state_space.modal_form import kernel_of, transfer_of
from floatmoor.io.dataset import DOFS

__all__ = ["DOFS", "PASSIVITY_POINTS", "passivity_grid", "PairRealisation",
           "StateSpaceRadiation"]

#: Frequencies of the passivity constraint (log-spaced from below the slowest to 20 times
#: the fastest pole, plus 0 and infinity); the check uses a grid four times as dense.
PASSIVITY_POINTS = 400


def passivity_grid(poles: NDArray[np.complex128], t_max: float, points: int
                   ) -> NDArray[np.float64]:
    """Frequencies where B_fit(omega) >= 0 is constrained or checked: 0, ``points`` log-spaced
    from below the slowest (0.1 pi / ``t_max``) to 20 times the fastest pole, infinity."""
    fast = max(float(np.abs(poles).max()), 1.0 / t_max)
    lo = 0.1 * math.pi / t_max
    return np.concatenate([[0.0], np.logspace(math.log10(lo), math.log10(20.0 * fast), points),
                           [math.inf]])


@dataclass(frozen=True)
class PairRealisation:
    """The realisation of one K_ij(t) (or of any scalar impulse response).

    Attributes
    ----------
    radiating, influenced
        DOF indices (0..5) of the pair (-1 for a kernel outside a database).
    a, b, c
        Real modal form, (n, n) [1/s], (n,) [1], (n,) [units of K].
    kernel_error
        ||K_fit - K||_2 / ||K||_2 over the truncation time.
    damping_error
        max over the BEM band of |B_fit - B_BEM| / sqrt(max B_ii max B_jj) (nan outside a
        database).
    added_mass_error
        The same for A(omega): A_inf + (A_fit - A_inf) against the BEM A, A_inf the mean over
        the band of A_BEM - (A_fit - A_inf) (as the body's A_inf is chosen), relative to
        sqrt(max A_ii max A_jj).
    min_damping
        Diagonal pairs: min over omega of B_fit / max B_fit (>= 0: passive); nan otherwise.
    dropped, reflected
        Modes dropped (discrete eigenvalue on the negative real axis) and unstable poles
        reflected into the left half-plane.
    passivity_enforced
        Whether the passivity constraint was active in the residue fit.
    within_tolerance
        kernel_error <= the tolerance of the fit.
    """

    radiating: int
    influenced: int
    a: NDArray[np.float64] = field(repr=False)
    b: NDArray[np.float64] = field(repr=False)
    c: NDArray[np.float64] = field(repr=False)
    kernel_error: float
    damping_error: float = math.nan
    min_damping: float = math.nan
    added_mass_error: float = math.nan
    dropped: int = 0
    reflected: int = 0
    passivity_enforced: bool = False
    within_tolerance: bool = True

    @property
    def order(self) -> int:
        """Number of states."""
        return int(self.b.size)

    @property
    def poles(self) -> NDArray[np.complex128]:
        """Eigenvalues of A [1/s]."""
        return np.linalg.eigvals(self.a)

    def kernel(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """K_fit(t) = c exp(A t) b."""
        return kernel_of(self.a, self.b, self.c, np.asarray(t, float))

    def transfer(self, omega: NDArray[np.float64]) -> NDArray[np.complex128]:
        """H(i omega) = c (i omega - A)^-1 b = B_fit + i omega (A_fit - A_inf)."""
        return transfer_of(self.a, self.b, self.c, omega)

    def summary(self) -> dict[str, Any]:
        """JSON-ready errors and counts."""
        def num(x: float) -> float | None:
            return None if math.isnan(x) else float(x)

        return {"radiating": DOFS[self.radiating] if self.radiating >= 0 else None,
                "influenced": DOFS[self.influenced] if self.influenced >= 0 else None,
                "order": self.order, "kernel_error": float(self.kernel_error),
                "damping_error": num(self.damping_error),
                "added_mass_error": num(self.added_mass_error),
                "min_damping": num(self.min_damping),
                "dropped": int(self.dropped), "reflected": int(self.reflected),
                "passivity_enforced": bool(self.passivity_enforced),
                "within_tolerance": bool(self.within_tolerance)}


@dataclass(frozen=True)
class StateSpaceRadiation:
    """The realisations of a database's significant K_ij(t).

    Attributes
    ----------
    pairs
        One :class:`PairRealisation` per significant (radiating, influenced) pair.
    settings
        Fit settings (tolerance, max order, Hankel rows, method).
    kernel_settings
        :func:`floatmoor.hydro.state_space.fit.kernel_settings` of the K the fit was made from.
    """

    pairs: tuple[PairRealisation, ...]
    settings: dict[str, Any]
    kernel_settings: dict[str, Any]
    created: str = ""
    fit_seconds: float = math.nan
    #: :meth:`matrix_passivity` when fitted
    matrix_min_damping: float = math.nan

    @property
    def orders(self) -> dict[tuple[int, int], int]:
        """(radiating, influenced) -> number of states."""
        return {(p.radiating, p.influenced): p.order for p in self.pairs}

    @property
    def n_states(self) -> int:
        """Total number of states."""
        return sum(p.order for p in self.pairs)

    @property
    def worst_kernel_error(self) -> float:
        """Largest relative L2 error of K over the pairs."""
        return max((p.kernel_error for p in self.pairs), default=0.0)

    def kernel(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """K_fit (m, 6, 6), indices (radiating, influenced); zero outside the pairs."""
        t = np.asarray(t, float)
        out = np.zeros((t.size, 6, 6))
        for p in self.pairs:
            out[:, p.radiating, p.influenced] = p.kernel(t)
        return out

    def frequency_response(self, omega: NDArray[np.float64]
                           ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(A_fit(omega) - A_inf, B_fit(omega)), each (n, 6, 6) with indices (radiating,
        influenced): H(i omega) = B + i omega (A - A_inf)."""
        omega = np.asarray(omega, float)
        added = np.zeros((omega.size, 6, 6))
        damping = np.zeros((omega.size, 6, 6))
        for p in self.pairs:
            h = p.transfer(omega)
            damping[:, p.radiating, p.influenced] = h.real
            added[:, p.radiating, p.influenced] = h.imag / omega
        return added, damping

    def matrix_passivity(self, points: int = 4 * PASSIVITY_POINTS) -> float:
        """Smallest eigenvalue over frequency of the symmetric part of the fitted B(omega),
        scaled by D^-1/2 with D the largest diagonal damping of each DOF (>= 0: the coupled
        realisation is passive; the coupling pairs are fitted one by one, so a small negative
        value of the order of the BEM's own asymmetry can remain)."""
        poles = np.concatenate([p.poles for p in self.pairs])
        t_max = float(self.kernel_settings.get("truncation_time", 1.0))
        grid = passivity_grid(poles, t_max, points)[:-1]
        _, b = self.frequency_response(np.where(grid > 0.0, grid, 1e-12))
        sym = 0.5 * (b + b.transpose(0, 2, 1))
        d = np.sqrt(np.abs(np.diagonal(sym, axis1=1, axis2=2)).max(axis=0))
        d = np.where(d > 0.0, d, 1.0)
        return float(np.linalg.eigvalsh(sym / d[None, :, None] / d[None, None, :])[:, 0].min())

    def summary(self) -> dict[str, Any]:
        """JSON-ready per-pair errors."""
        return {"pairs": [p.summary() for p in self.pairs], "n_states": self.n_states,
                "worst_kernel_error": self.worst_kernel_error,
                "matrix_min_damping": None if math.isnan(self.matrix_min_damping)
                else float(self.matrix_min_damping)}
