"""Second-order (difference-frequency) wave forces on a floater in the time domain.

Theory: docs/theory/hydrodynamics.md#second-order-wave-loads. With the sea's complex
amplitudes A_j = a_j e^{i phi_j} (:attr:`WaveField.complex_amplitude`, capytaine's
e^{-i omega t} convention) and coefficients per unit wave amplitude squared about the body's
reference point (N/m^2, N m/m^2; this module takes them as arrays, the hydrodynamics package
looks them up in the database: floatmoor.hydro.second_order):

``"mean"`` (:class:`MeanDriftForce`)
    F = sum_j a_j^2 D(omega_j, beta_j): the mean drift, constant.
``"newman"`` (:class:`NewmanForce`)
    Newman's (1974) approximation Q_ij ~ (D_i + D_j) / 2 of the difference-frequency QTF,

        F(t) = Re[S_D(t) conj(S(t))],  S(t) = sum_j A_j e^{-i omega_j t},
                                       S_D(t) = sum_j A_j D_j e^{-i omega_j t},

    O(N) per time (one harmonic sum of 14 real signals, floatmoor.waves.synthesis); its time
    mean (over the repeat period of an equally spaced sea) is the ``mean`` force. Components
    outside the coefficients' band are left out of S and S_D (as out of ``full``'s pairs), so
    that ``full`` with the QTF (D_p + D_q) / 2 is ``newman`` for any sea.
``"full"`` (:class:`QTFForce`)
    F(t) = Re sum_i sum_j A_i conj(A_j) Q(omega_i, omega_j) e^{-i (omega_i - omega_j) t}
    over all ordered pairs, Q the difference-frequency QTF interpolated bilinearly on its
    grid; Q = 0 for a pair with a frequency outside the grid (as the first-order excitation is
    zero outside the database's band). Evaluated through the grid's hat functions
    (floatmoor/waves/_second_order_kernels.py): exact for the bilinear interpolant, O(N + M^2)
    per time for M grid frequencies, for equally spaced and random-in-bin seas alike.

No sum-frequency terms. Each force's :attr:`mean` is its constant part, sum_j a_j^2 Q(w_j,
w_j); the run applies it unramped (the body starts at the equilibrium that includes it) and
ramps the rest with the square of the wave ramp (floatmoor.simulation.assembly.BodyLoads).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.waves.realisation import WaveField
from floatmoor.waves.synthesis import harmonic_sum

__all__ = ["SECOND_ORDER_MODELS", "DRIFT_ROUTES", "MeanDriftForce", "NewmanForce", "QTFForce",
           "SecondOrderForce", "hat_weights"]

#: The case's ``[waves] second_order`` choices ("none": first-order forces only).
SECOND_ORDER_MODELS = ("none", "mean", "newman", "full")
#: The case's ``[waves] drift_coefficients`` choices (docs/theory/hydrodynamics.md).
DRIFT_ROUTES = ("far_field", "near_field")

#: Relative tolerance of a uniform time grid (as floatmoor.waves.synthesis: the rounding
#: np.arange and np.linspace leave, in units of the largest time).
_UNIFORM_RTOL = 64.0 * np.finfo(float).eps
#: Times per kernel call of a long uniform grid: bounds the (times x grid) scratch of the
#: band amplitudes (4096 x 100 complex: 6.6 MB).
_BLOCK = 4096


def _drift_array(field: WaveField, drift: ArrayLike) -> NDArray[np.float64]:
    d = np.asarray(drift, dtype=float)
    if d.ndim != 2 or d.shape[0] != field.n_components:
        raise ValueError(f"drift coefficients must have shape (N={field.n_components}, n_dof),"
                         f" got {d.shape}")
    if not np.all(np.isfinite(d)):
        raise ValueError("drift coefficients contain NaN or infinity")
    return d


class MeanDriftForce:
    """The mean drift force F = sum_j a_j^2 D_j (constant).

    Parameters
    ----------
    field
        The sea.
    drift
        D at each component's frequency and direction, shape (N, n_dof) [N/m^2, N m/m^2].
    """

    model = "mean"

    def __init__(self, field: WaveField, drift: ArrayLike) -> None:
        d = _drift_array(field, drift)
        self.mean = (field.amplitude ** 2) @ d
        self.mean.setflags(write=False)

    def __call__(self, t: float) -> NDArray[np.float64]:
        """F(t), shape (n_dof,) [N, N m]."""
        return self.mean.copy()

    def series(self, times: ArrayLike) -> NDArray[np.float64]:
        """F at many times, shape times.shape + (n_dof,)."""
        t = np.asarray(times, dtype=float)
        return np.broadcast_to(self.mean, t.shape + self.mean.shape).copy()


class NewmanForce:
    """The slow-drift force by Newman's approximation (module docstring).

    Parameters
    ----------
    field
        The sea.
    drift
        D at each component's frequency and direction, shape (N, n_dof) [N/m^2, N m/m^2].
    inside
        Which components the coefficients cover, shape (N,) (default all); the others are
        left out.
    """

    model = "newman"

    def __init__(self, field: WaveField, drift: ArrayLike,
                 inside: ArrayLike | None = None) -> None:
        d = _drift_array(field, drift)
        a = field.complex_amplitude
        if inside is not None:
            a = np.where(np.asarray(inside, dtype=bool), a, 0.0)
        self.omega = field.omega
        self.n_dof = d.shape[1]
        sd = a[:, None] * d
        # Re and Im of S and S_D as real parts of harmonic sums: Im z = Re(-i z)
        self.coefficients = np.concatenate([a[:, None], -1j * a[:, None], sd, -1j * sd],
                                           axis=1)
        self.coefficients.setflags(write=False)
        self.mean = np.abs(a) ** 2 @ d
        self.mean.setflags(write=False)

    def __call__(self, t: float) -> NDArray[np.float64]:
        """F(t), shape (n_dof,) [N, N m]."""
        return self.series(np.array([float(t)]))[0]

    def series(self, times: ArrayLike) -> NDArray[np.float64]:
        """F at many times, shape times.shape + (n_dof,) (fast on uniform grids)."""
        s = harmonic_sum(self.coefficients, self.omega, times)
        n = self.n_dof
        return s[..., 2:2 + n] * s[..., :1] + s[..., 2 + n:] * s[..., 1:2]


def hat_weights(grid: NDArray[np.float64], omega: NDArray[np.float64]
                ) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.bool_]]:
    """(cell, fraction, inside) of frequencies on an ascending grid: omega lies in
    [grid[cell], grid[cell + 1]] at ``fraction`` of the cell; ``inside`` False (cell 0,
    fraction 0) for frequencies outside [grid[0], grid[-1]]."""
    g = np.asarray(grid, dtype=float)
    w = np.asarray(omega, dtype=float)
    inside = (w >= g[0]) & (w <= g[-1])
    cell = np.clip(np.searchsorted(g, w, side="right") - 1, 0, g.size - 2).astype(np.int64)
    frac = np.where(inside, (w - g[cell]) / (g[cell + 1] - g[cell]), 0.0)
    cell[~inside] = 0
    return cell, frac, inside


class QTFForce:
    """The difference-frequency force of the full QTF (module docstring).

    Parameters
    ----------
    field
        The sea (one direction: the QTF is for unidirectional pairs).
    grid
        The QTF's frequencies [rad/s], ascending, at least two, shape (M,).
    qtf
        Q(grid_p, grid_q) at the sea's direction, complex, shape (M, M, n_dof)
        [N/m^2, N m/m^2]; only its Hermitian part (Q + Q^H) / 2 enters the real force.
    """

    model = "full"

    def __init__(self, field: WaveField, grid: ArrayLike, qtf: ArrayLike) -> None:
        g = np.asarray(grid, dtype=float)
        q = np.asarray(qtf, dtype=complex)
        if g.ndim != 1 or g.size < 2 or np.any(np.diff(g) <= 0.0):
            raise ValueError("the QTF grid must hold two or more ascending frequencies")
        if q.ndim != 3 or q.shape[:2] != (g.size, g.size):
            raise ValueError(f"qtf must have shape (M={g.size}, M, n_dof), got {q.shape}")
        if not np.all(np.isfinite(q)):
            raise ValueError("QTF contains NaN or infinity")
        if field.n_components and np.ptp(field.direction) > 0.0:
            raise ValueError("the full QTF force needs a long-crested sea (one direction)")
        self.n_dof = q.shape[2]
        hermitian = 0.5 * (q + np.conj(q.transpose(1, 0, 2)))
        cell, frac, inside = hat_weights(g, field.omega)
        a = np.where(inside, field.complex_amplitude, 0.0)
        keep = np.nonzero(inside)[0]
        if keep.size == 0:
            first, last = 0, 1
        else:
            first, last = int(cell[keep].min()), int(cell[keep].max()) + 1
        # only the hats the sea touches
        self.omega = np.ascontiguousarray(field.omega[keep])
        self.cell = np.ascontiguousarray(cell[keep] - first)
        self.weight_low = np.ascontiguousarray((a * (1.0 - frac))[keep])
        self.weight_high = np.ascontiguousarray((a * frac)[keep])
        self.qtf = np.ascontiguousarray(hermitian[first:last + 1, first:last + 1])
        lo, hi = self.weight_low, self.weight_high
        c = self.cell
        self.mean = (np.abs(lo) ** 2 @ self.qtf[c, c].real
                     + np.abs(hi) ** 2 @ self.qtf[c + 1, c + 1].real
                     + 2.0 * ((lo * np.conj(hi))[:, None] * self.qtf[c, c + 1]).real.sum(0)
                     if keep.size else np.zeros(self.n_dof))
        self.mean.setflags(write=False)

    def __call__(self, t: float) -> NDArray[np.float64]:
        """F(t), shape (n_dof,) [N, N m]."""
        return self.series(np.array([float(t)]))[0]

    def series(self, times: ArrayLike) -> NDArray[np.float64]:
        """F at many times, shape times.shape + (n_dof,) (one kernel call on a uniform
        grid)."""
        from floatmoor.waves._second_order_kernels import band_amplitudes, hermitian_forms

        t_in = np.asarray(times, dtype=float)
        t = t_in.ravel()
        out = np.zeros((t.size, self.n_dof))
        if t.size == 0 or self.omega.size == 0:
            return out.reshape(t_in.shape + (self.n_dof,))
        m = self.qtf.shape[0]
        step = (t[-1] - t[0]) / (t.size - 1) if t.size > 1 else 0.0
        ideal = t[0] + step * np.arange(t.size)
        uniform = bool(np.all(np.abs(t - ideal) <= _UNIFORM_RTOL * float(np.abs(t).max())))
        pieces = [(k, min(k + _BLOCK, t.size), t[0] + k * step, step)
                  for k in range(0, t.size, _BLOCK)] if uniform else \
            [(k, k + 1, t[k], 0.0) for k in range(t.size)]
        for start, stop, t0, h in pieces:
            p = np.empty((stop - start, m), dtype=complex)
            band_amplitudes(float(t0), float(h), self.omega, self.weight_low, self.weight_high,
                            self.cell, p)
            hermitian_forms(p, self.qtf, out[start:stop])
        return out.reshape(t_in.shape + (self.n_dof,))


SecondOrderForce = MeanDriftForce | NewmanForce | QTFForce
