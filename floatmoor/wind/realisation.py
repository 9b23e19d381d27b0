"""A seeded point wind speed series: a finite sum of random-phase harmonics.

.. math::
    u(t) = U + \\sum_j a_j \\cos(2\\pi f_j t + \\phi_j), \\qquad a_j = \\sqrt{2 \\int_{bin_j} S(f) df}

(for a narrow bin, a_j -> sqrt(2 S(f_j) df), docs/theory/environment.md's wave synthesis applied to
the wind). The longitudinal wind at one point (the hub) stands for the whole rotor; the spatial
averaging of a 126 m rotor, which filters the incoherent high-frequency gusts, is not modelled,
and the band cutoff (default 0.5 Hz) is where the point spectrum stops.

Frequency discretisation
------------------------
The band [1/D, f_cut] (D the run's duration) is cut into bins of width df = 1/D; each bin holds
one component at a frequency drawn uniformly inside it ("random in bin") and the amplitude of the
bin's exact spectral integral, so that sum a_j^2 / 2 is the band variance (closed form,
:func:`~floatmoor.wind.spectrum.npd_band_variance`). With df = 1/D the record holds no repeat
of itself: equal spacing alone would already make it periodic only with period D, and the
random offsets remove even that. The variance below 1/D (the missing first bin) is left out:
a 3-hour record cannot hold it as fluctuation.

Phases and frequency offsets come from ``numpy.random.default_rng(seed)``: same seed, same wind.

Evaluation
----------
:meth:`WindField.series` evaluates a uniform grid t0 + k dt in blocks of M samples:
u(t_b + m dt) = U + Re sum_j [a_j e^{i(2 pi f_j t_b + phi_j)}] e^{i 2 pi f_j m dt}, a
(blocks x N) by (N x M) product whose right factor depends only on dt and is cached. A 3-hour
series at 0.05 s (216 000 samples, 5 400 components) takes well under a second.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray
from floatmoor.wind.spectrum import npd_fraction_below, npd_variance

__all__ = ["WindField", "npd_wind", "steady_wind", "BLOCK"]

#: Samples per block of :meth:`WindField.series` (the cached phase matrix is N x BLOCK).
BLOCK = 256
_SMALL_PRODUCT_BLOCKS = 256


@dataclass
class WindField:
    """A realised point wind speed u(t) = mean + sum a_j cos(2 pi f_j t + phi_j).

    Attributes
    ----------
    mean
        Mean wind speed U [m/s].
    frequency
        f_j [Hz] (N,).
    amplitude
        a_j [m/s] (N,).
    phase
        phi_j [rad] (N,).
    """

    mean: float
    frequency: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    phase: NDArray[np.float64]
    _rotations: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def n_components(self) -> int:
        """Number of harmonics N."""
        return int(self.frequency.size)

    @property
    def variance(self) -> float:
        """Variance of the fluctuation, sum a_j^2 / 2 [m^2/s^2]."""
        return float(0.5 * np.sum(self.amplitude ** 2))

    def speeds(self, times: ArrayLike) -> NDArray[np.float64]:
        """u at arbitrary times [s] (direct sum, blocked over times)."""
        t = np.atleast_1d(np.asarray(times, dtype=float))
        out = np.full(t.shape, self.mean)
        if self.n_components == 0:
            return out
        w = 2.0 * math.pi * self.frequency
        for s in range(0, t.size, BLOCK):
            tb = t[s:s + BLOCK]
            out[s:s + BLOCK] += np.cos(np.outer(tb, w) + self.phase) @ self.amplitude
        return out

    def _rotation(self, dt: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        key = float(dt)
        if key not in self._rotations:
            arg = np.outer(2.0 * math.pi * self.frequency, dt * np.arange(BLOCK))
            self._rotations.clear()
            self._rotations[key] = (np.cos(arg), np.sin(arg))
        return self._rotations[key]

    def series(self, t0: float, dt: float, n: int) -> NDArray[np.float64]:
        """u on the uniform grid t0 + k dt, k = 0 .. n-1 [m/s] (blocked matrix products)."""
        if n < 0 or not (dt > 0.0):
            raise ValueError(f"wind series: need n >= 0 and dt > 0, got n={n}, dt={dt}")
        if self.n_components == 0 or n == 0:
            return np.full(n, self.mean)
        n_blocks = -(-n // BLOCK)
        starts = t0 + dt * BLOCK * np.arange(n_blocks)
        arg = np.outer(starts, 2.0 * math.pi * self.frequency) + self.phase
        cr = np.cos(arg) * self.amplitude
        ci = np.sin(arg) * self.amplitude
        er, ei = self._rotation(dt)
        # Re{(cr + i ci)(er + i ei)} = cr er - ci ei. A few blocks (a simulation chunk) go
        # through einsum: multi-threaded OpenBLAS on a (4 x N) (N x M) product was measured
        # 50x slower than single-threaded on a loaded 2-core machine (0.36 s against 7 ms).
        if n_blocks <= _SMALL_PRODUCT_BLOCKS:
            block = np.einsum("bj,jm->bm", cr, er) - np.einsum("bj,jm->bm", ci, ei)
        else:
            block = cr @ er - ci @ ei
        return self.mean + block.reshape(-1)[:n]


def steady_wind(mean: float) -> WindField:
    """A constant wind ``mean`` [m/s]."""
    empty = np.zeros(0)
    return WindField(float(mean), empty, empty.copy(), empty.copy())


def npd_wind(mean_speed: float, height: float, mean_speed_10m: float, duration: float,
             seed: int, cutoff_hz: float = 0.5) -> WindField:
    """A random-in-bin realisation of the NPD spectrum at ``height``.

    Parameters
    ----------
    mean_speed
        Mean wind speed at ``height`` [m/s] (the series' mean).
    height
        z [m] of the point (the hub).
    mean_speed_10m
        U0, the 1-hour mean at 10 m that sets the spectrum [m/s].
    duration
        D [s]: bins of width 1/D from 1/D up to ``cutoff_hz``.
    seed
        Seed of ``numpy.random.default_rng``.
    cutoff_hz
        Upper end of the realised band [Hz].
    """
    if not (math.isfinite(duration) and duration > 0.0):
        raise ValueError(f"wind: duration must be > 0, got {duration!r}")
    df = 1.0 / duration
    if not (math.isfinite(cutoff_hz) and cutoff_hz > 2.0 * df):
        raise ValueError(f"wind: cutoff_hz must exceed 2 / duration = {2.0 * df:.3g} Hz, "
                         f"got {cutoff_hz!r}")
    n_bins = int(math.floor(cutoff_hz / df + 1e-9)) - 1
    edges = df * np.arange(1, n_bins + 2)
    # exact spectral integral of each bin (closed form)
    band = npd_variance(mean_speed_10m, height) * np.diff(
        npd_fraction_below(edges, mean_speed_10m, height))
    rng = np.random.default_rng(seed)
    phase = rng.uniform(0.0, 2.0 * math.pi, n_bins)
    frequency = edges[:-1] + df * rng.uniform(0.0, 1.0, n_bins)
    amplitude = np.sqrt(2.0 * np.maximum(band, 0.0))
    return WindField(float(mean_speed), frequency, amplitude, phase)

