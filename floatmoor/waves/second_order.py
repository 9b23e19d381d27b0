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

    O(N) per time (one harmonic sum of 14 real signals, floatmoor.waves.synthesis; with D
    given on a frequency grid, :func:`newman_on_grid`, from the grid's band amplitudes as
    ``full`` below, about six times cheaper); its time mean (over the repeat period of an
    equally spaced sea) is the ``mean`` force. Components outside the coefficients' band are
    left out of S and S_D (as out of ``full``'s pairs), so that ``full`` with the QTF
    (D_p + D_q) / 2 is ``newman`` for any sea.
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

from floatmoor.case.sea import DRIFT_ROUTES, SECOND_ORDER_MODELS
from floatmoor.waves.realisation import WaveField
from floatmoor.waves.synthesis import harmonic_sum

__all__ = ["SECOND_ORDER_MODELS", "DRIFT_ROUTES", "MeanDriftForce", "NewmanForce", "QTFForce",
           "SecondOrderForce", "hat_weights", "newman_on_grid"]


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
        power = field.amplitude ** 2
        if inside is not None:
            a = np.where(np.asarray(inside, dtype=bool), a, 0.0)
            power = np.where(np.asarray(inside, dtype=bool), power, 0.0)
        self.omega = field.omega
        self.n_dof = d.shape[1]
        sd = a[:, None] * d
        # Re and Im of S and S_D as real parts of harmonic sums: Im z = Re(-i z)
        self.coefficients = np.concatenate([a[:, None], -1j * a[:, None], sd, -1j * sd],
                                           axis=1)
        self.coefficients.setflags(write=False)
        self.mean = power @ d
        self.mean.setflags(write=False)
        #: (bands, D on their hats) when built by :func:`newman_on_grid`
        self._grid: tuple[_Bands, NDArray[np.float64]] | None = None

    def __call__(self, t: float) -> NDArray[np.float64]:
        """F(t), shape (n_dof,) [N, N m]."""
        return self.series(np.array([float(t)]))[0]

    def series(self, times: ArrayLike) -> NDArray[np.float64]:
        """F at many times, shape times.shape + (n_dof,) (fast on uniform grids)."""
        if self._grid is not None:
            t_in = np.asarray(times, dtype=float)
            out = np.zeros((t_in.size, self.n_dof))
            bands, drift = self._grid
            if t_in.size and bands.omega.size:
                _newman_on_grid(bands, drift, t_in.ravel(), out)
            return out.reshape(t_in.shape + (self.n_dof,))
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


class _Bands:
    """A sea's components on the hat functions of a frequency grid (the hats it touches):
    the band amplitudes P_p(t) (floatmoor/waves/_second_order_kernels.py) in blocks."""

    def __init__(self, field: WaveField, grid: NDArray[np.float64]) -> None:
        cell, frac, inside = hat_weights(grid, field.omega)
        a = np.where(inside, field.complex_amplitude, 0.0)
        keep = np.nonzero(inside)[0]
        self.inside = inside
        self.first, self.last = (0, 1) if keep.size == 0 else \
            (int(cell[keep].min()), int(cell[keep].max()) + 1)
        self.omega = np.ascontiguousarray(field.omega[keep])
        self.cell = np.ascontiguousarray(cell[keep] - self.first)
        self.weight_low = np.ascontiguousarray((a * (1.0 - frac))[keep])
        self.weight_high = np.ascontiguousarray((a * frac)[keep])

    @property
    def hats(self) -> slice:
        """The grid nodes the sea touches."""
        return slice(self.first, self.last + 1)

    def blocks(self, t: NDArray[np.float64]):
        """(start, stop, P) for blocks of the 1-D times ``t``, P (stop - start, hats)."""
        from floatmoor.waves._second_order_kernels import band_amplitudes

        m = self.last + 1 - self.first
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
            yield start, stop, p


def _check_grid(grid: ArrayLike, values: ArrayLike, what: str, axes: int
                ) -> tuple[NDArray[np.float64], NDArray]:
    g = np.asarray(grid, dtype=float)
    v = np.asarray(values)
    if g.ndim != 1 or g.size < 2 or np.any(np.diff(g) <= 0.0):
        raise ValueError(f"the {what} grid must hold two or more ascending frequencies")
    if v.ndim != axes + 1 or v.shape[:axes] != (g.size,) * axes:
        raise ValueError(f"{what} must have shape ({', '.join(['M'] * axes)}, n_dof) with M = "
                         f"{g.size}, got {v.shape}")
    return g, v


def _newman_on_grid(bands: _Bands, drift: NDArray[np.float64], times: NDArray[np.float64],
                    out: NDArray[np.float64]) -> None:
    """Newman's force from the band amplitudes: S = sum_p P_p, S_D = sum_p D_p P_p."""
    for start, stop, p in bands.blocks(times):
        s = p.sum(axis=1)
        sd = p @ drift
        out[start:stop] = sd.real * s.real[:, None] + sd.imag * s.imag[:, None]


def newman_on_grid(field: WaveField, grid: ArrayLike, drift: ArrayLike) -> NewmanForce:
    """Newman's force with D given on a frequency grid (linear between its nodes, the
    components outside it left out, as :class:`NewmanForce` with ``inside``), evaluated from
    the grid's band amplitudes: S = sum_p P_p, S_D = sum_p D_p P_p, O(N + M) per time
    instead of a harmonic sum of 14 signals (the same force to round-off).

    Parameters
    ----------
    field
        The sea (one direction).
    grid
        Frequencies of the coefficients [rad/s], ascending, shape (M,).
    drift
        D at the grid's frequencies and the sea's direction, shape (M, n_dof).
    """
    g, d = _check_grid(grid, np.asarray(drift, dtype=float), "drift coefficients", 1)
    if field.n_components and np.ptp(field.direction) > 0.0:
        raise ValueError("Newman's force on a grid needs a long-crested sea (one direction)")
    bands = _Bands(field, g)
    if not np.all(np.isfinite(d[bands.hats])):
        raise ValueError("drift coefficients contain NaN or infinity in the sea's band")
    clean = np.where(np.isfinite(d), d, 0.0)  # (outside the sea's band: unused)
    per_component = np.array([np.interp(field.omega, g, clean[:, k])
                              for k in range(d.shape[1])]).T
    force = NewmanForce(field, per_component.reshape(field.n_components, d.shape[1]),
                        bands.inside)
    force._grid = (bands, np.ascontiguousarray(d[bands.hats]))
    return force


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
        g, q = _check_grid(grid, np.asarray(qtf, dtype=complex), "QTF", 2)
        if not np.all(np.isfinite(q)):
            raise ValueError("QTF contains NaN or infinity")
        if field.n_components and np.ptp(field.direction) > 0.0:
            raise ValueError("the full QTF force needs a long-crested sea (one direction)")
        self.n_dof = q.shape[2]
        hermitian = 0.5 * (q + np.conj(q.transpose(1, 0, 2)))
        self.bands = _Bands(field, g)
        # only the hats the sea touches
        self.qtf = np.ascontiguousarray(hermitian[self.bands.hats, self.bands.hats])
        lo, hi, c = self.bands.weight_low, self.bands.weight_high, self.bands.cell
        self.mean = (np.abs(lo) ** 2 @ self.qtf[c, c].real
                     + np.abs(hi) ** 2 @ self.qtf[c + 1, c + 1].real
                     + 2.0 * ((lo * np.conj(hi))[:, None] * self.qtf[c, c + 1]).real.sum(0)
                     if c.size else np.zeros(self.n_dof))
        self.mean.setflags(write=False)

    def __call__(self, t: float) -> NDArray[np.float64]:
        """F(t), shape (n_dof,) [N, N m]."""
        return self.series(np.array([float(t)]))[0]

    def series(self, times: ArrayLike) -> NDArray[np.float64]:
        """F at many times, shape times.shape + (n_dof,) (one kernel call per block of a
        uniform grid)."""
        from floatmoor.waves._second_order_kernels import hermitian_forms

        t_in = np.asarray(times, dtype=float)
        t = t_in.ravel()
        out = np.zeros((t.size, self.n_dof))
        if t.size and self.bands.omega.size:
            for start, stop, p in self.bands.blocks(t):
                hermitian_forms(p, self.qtf, out[start:stop])
        return out.reshape(t_in.shape + (self.n_dof,))


SecondOrderForce = MeanDriftForce | NewmanForce | QTFForce
