"""Synthetic records with known spectra for the post-processing tests.

Kept apart from floatmoor's wave module on purpose: these are test signals, written from the
definitions they are checked against.

* :func:`jonswap` is the spectrum of docs/theory/environment.md: ``S(w) = alpha g^2 w^-5 exp(-5/4 (w/w_p)^-4)
  gamma^exp(-(w - w_p)^2 / (2 sigma^2 w_p^2))``, sigma = 0.07 for w <= w_p and 0.09 above,
  alpha set so that 4 sqrt(m0) = Hs (m0 integrated numerically on a fine grid).
* :func:`gaussian_band` is a narrow Gaussian-shaped band ``S(f) ∝ exp(-(f - f0)^2 /
  (2 (delta f0)^2))`` with a prescribed variance.
* :func:`realisation` draws a record from a one-sided spectrum by the random-phase method of
  docs/theory/environment.md (amplitudes ``a_j = sqrt(2 S(f_j) df)``, phases uniform from a seeded
  generator) on the Fourier grid ``f_j = j / (N dt)``, summed by an inverse FFT, so the record is
  periodic and its variance is exactly ``sum a_j^2 / 2``.
"""

from __future__ import annotations

import numpy as np

#: Standard gravity [m/s^2] (the conventional value, CGPM 1901).
G = 9.80665


def _jonswap_shape(w: np.ndarray, tp: float, gamma: float) -> np.ndarray:
    wp = 2.0 * np.pi / tp
    w = np.asarray(w, dtype=float)
    out = np.zeros_like(w)
    pos = w > 0.0
    wq = w[pos]
    sigma = np.where(wq <= wp, 0.07, 0.09)
    peak = gamma ** np.exp(-((wq - wp) ** 2) / (2.0 * sigma**2 * wp**2))
    with np.errstate(under="ignore"):
        out[pos] = G**2 * wq**-5 * np.exp(-1.25 * (wq / wp) ** -4) * peak
    return out


def jonswap(w: np.ndarray, hs: float, tp: float, gamma: float) -> np.ndarray:
    """JONSWAP S(w) [m^2 s/rad] at angular frequencies w [rad/s] (docs/theory/environment.md)."""
    fine = np.linspace(0.0, 40.0 * 2.0 * np.pi / tp, 400_001)
    m0_unit = np.trapezoid(_jonswap_shape(fine, tp, gamma), fine)
    alpha = hs**2 / 16.0 / m0_unit
    return alpha * _jonswap_shape(w, tp, gamma)


def gaussian_band(f: np.ndarray, f0: float, delta: float, variance: float) -> np.ndarray:
    """Narrow Gaussian band S(f) [unit^2/Hz] of relative width ``delta`` and given variance."""
    width = delta * f0
    with np.errstate(under="ignore"):
        shape = np.exp(-((np.asarray(f) - f0) ** 2) / (2.0 * width**2))
    return variance * shape / (width * np.sqrt(2.0 * np.pi))


def realisation(spectrum_hz, n: int, dt: float,
                rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A random-phase record of a one-sided spectrum S(f) [unit^2/Hz].

    Returns times [s], samples and the component amplitudes a_j (on f_j = j / (n dt)).
    """
    df = 1.0 / (n * dt)
    f = np.arange(n // 2 + 1) * df
    s = spectrum_hz(f)
    s[0] = 0.0
    s[-1] = 0.0  # no Nyquist component: every component is a full cosine
    amplitude = np.sqrt(2.0 * s * df)
    phase = rng.uniform(0.0, 2.0 * np.pi, f.size)
    spectrum = 0.5 * n * amplitude * np.exp(1j * phase)
    x = np.fft.irfft(spectrum, n=n)
    return np.arange(n) * dt, x, amplitude
