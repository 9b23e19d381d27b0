"""Wave spectra: JONSWAP (Pierson-Moskowitz as gamma = 1) and their spectral moments.

One-sided spectral density S(omega) [m^2 s/rad] of the wave elevation over the angular
frequency omega [rad/s] (docs/theory/environment.md; DNV-RP-C205 section 3.5.5):

.. math::
    S(\\omega) = \\alpha g^2 \\omega^{-5} \\exp\\left(-\\tfrac54 (\\omega/\\omega_p)^{-4}\\right)
                 \\gamma^{\\exp\\left(-(\\omega-\\omega_p)^2 / (2\\sigma^2\\omega_p^2)\\right)}

with omega_p = 2 pi / Tp, spectral width sigma = 0.07 for omega <= omega_p and 0.09 above
(DNV-RP-C205 3.5.5.1), and alpha set so that the zeroth moment m0 = integral S d omega
gives 4 sqrt(m0) = Hs **exactly**: alpha = Hs^2 / (16 g^2 omega_p^-4 I(gamma)) with the shape
integral I(gamma) = integral_0^inf nu^-5 exp(-5/4 nu^-4) gamma^r(nu) d nu (nu = omega/omega_p)
evaluated by adaptive quadrature (:func:`shape_integral`). For gamma = 1 (Pierson-Moskowitz)
I = 1/5 in closed form, so alpha g^2 = 5/16 Hs^2 omega_p^4.

DNV-RP-C205 (eq. 3.5.5.1) instead offers the closed-form approximation
alpha_DNV g^2 = 5/16 Hs^2 omega_p^4 A_gamma with A_gamma = 1 - 0.287 ln(gamma); it is kept here
only as documentation: it misses m0 by up to about 1-2 % over 1 <= gamma <= 7
(tests/waves/test_spectra.py::test_dnv_closed_form_alpha_is_only_approximate measures it).

The peak-enhancement default gamma = 3.3 and the Hs-Tp rule :func:`dnv_peak_enhancement` are
DNV-RP-C205 3.5.5.5.

References
----------
DNV-RP-C205 (2010/2021). Environmental conditions and environmental loads, section 3.5.5.
Hasselmann, K. et al. (1973). Measurements of wind-wave growth and swell decay during the Joint
North Sea Wave Project (JONSWAP). Dtsch. Hydrogr. Z. A8(12).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.case.sea import DEFAULT_GAMMA  # the case's default (DNV-RP-C205 3.5.5.5)
from floatmoor.dispersion import STANDARD_GRAVITY

__all__ = ["SIGMA_BELOW_PEAK", "SIGMA_ABOVE_PEAK", "DEFAULT_GAMMA", "jonswap",
           "pierson_moskowitz", "jonswap_alpha", "shape_integral", "spectral_moment",
           "jonswap_moment", "peak_omega", "peak_period", "dnv_peak_enhancement",
           "significant_height"]

#: JONSWAP spectral width parameters (DNV-RP-C205 3.5.5.1).
SIGMA_BELOW_PEAK = 0.07
SIGMA_ABOVE_PEAK = 0.09

#: Requested relative accuracy of the shape integral; the quadrature reaches ~1e-14 here,
#: far below the 1e-6 on Hs that the tests ask.
_QUAD_EPSREL = 1e-13


def peak_omega(tp: float) -> float:
    """Peak angular frequency omega_p = 2 pi / Tp [rad/s]."""
    if not tp > 0.0:
        raise ValueError(f"peak period must be > 0 s, got {tp!r}")
    return 2.0 * math.pi / tp


def _gamma_exponent(nu: NDArray[np.float64]) -> NDArray[np.float64]:
    sigma = np.where(nu <= 1.0, SIGMA_BELOW_PEAK, SIGMA_ABOVE_PEAK)
    return np.exp(-((nu - 1.0) ** 2) / (2.0 * sigma * sigma))


def _shape(nu: NDArray[np.float64], gamma: float) -> NDArray[np.float64]:
    """nu^-5 exp(-5/4 nu^-4) gamma^r(nu), zero at nu <= 0 (its limit)."""
    nu = np.asarray(nu, dtype=float)
    out = np.zeros_like(nu)
    pos = nu > 0.0
    v = nu[pos]
    inv4 = v ** -4.0
    # exp(-1.25 / nu^4) underflows to 0 for nu < 0.15, which is the right value.
    with np.errstate(under="ignore"):
        out[pos] = inv4 / v * np.exp(-1.25 * inv4) * gamma ** _gamma_exponent(v)
    return out


@lru_cache(maxsize=256)
def shape_integral(gamma: float, moment: int = 0) -> float:
    """I_n(gamma) = integral_0^inf nu^n nu^-5 exp(-5/4 nu^-4) gamma^r(nu) d nu.

    m_n = alpha g^2 omega_p^(n-4) I_n(gamma). For gamma = 1 and n = 0, I_0 = 1/5 exactly.
    Only n <= 3 converge (the omega^-5 tail).
    """
    if not 0 <= moment <= 3:
        raise ValueError("JONSWAP moments exist for n = 0..3 only (omega^-5 tail)")

    def f(nu: float) -> float:
        return float(nu ** moment * _shape(np.array([nu]), gamma)[0])

    from scipy import integrate  # here, not at import: case loading needs none of scipy

    # Split at the peak (sigma changes there) and where the enhancement has died out.
    pieces = [(0.0, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, 10.0), (10.0, math.inf)]
    total = 0.0
    for a, b in pieces:
        value, _ = integrate.quad(f, a, b, epsabs=0.0, epsrel=_QUAD_EPSREL, limit=200)
        total += value
    return total


def jonswap_alpha(hs: float, tp: float, gamma: float = DEFAULT_GAMMA,
                  gravity: float = STANDARD_GRAVITY) -> float:
    """The Phillips constant alpha that makes 4 sqrt(m0) = Hs exactly (see module docstring)."""
    wp = peak_omega(tp)
    return hs * hs * wp ** 4 / (16.0 * gravity * gravity * shape_integral(float(gamma), 0))


def jonswap(omega: ArrayLike, hs: float, tp: float, gamma: float = DEFAULT_GAMMA,
            gravity: float = STANDARD_GRAVITY) -> NDArray[np.float64]:
    """JONSWAP spectral density S(omega) [m^2 s/rad], normalised so that 4 sqrt(m0) = Hs.

    Parameters
    ----------
    omega
        Angular frequencies [rad/s] (>= 0; S(0) = 0).
    hs
        Significant wave height Hs = 4 sqrt(m0) [m].
    tp
        Peak period [s].
    gamma
        Peak-enhancement factor (1 gives Pierson-Moskowitz); default 3.3 (DNV-RP-C205).
    gravity
        g [m/s^2].

    Returns
    -------
    numpy.ndarray
        S with the shape of ``omega``.
    """
    if not hs > 0.0:
        raise ValueError(f"significant wave height must be > 0 m, got {hs!r}")
    if not gamma >= 1.0:
        raise ValueError(f"JONSWAP gamma must be >= 1, got {gamma!r}")
    w = np.asarray(omega, dtype=float)
    wp = peak_omega(tp)
    alpha = jonswap_alpha(hs, tp, gamma, gravity)
    return alpha * gravity ** 2 * wp ** -5 * _shape(w / wp, float(gamma))


def pierson_moskowitz(omega: ArrayLike, hs: float, tp: float,
                      gravity: float = STANDARD_GRAVITY) -> NDArray[np.float64]:
    """Pierson-Moskowitz spectrum: JONSWAP with gamma = 1,
    S = 5/16 Hs^2 omega_p^4 omega^-5 exp(-5/4 (omega/omega_p)^-4).

    Parameters
    ----------
    omega
        Angular frequencies [rad/s] (>= 0; S(0) = 0).
    hs
        Significant wave height [m].
    tp
        Peak period [s].
    gravity
        g [m/s^2].

    Returns
    -------
    numpy.ndarray
        S [m^2 s/rad] with the shape of ``omega``.
    """
    return jonswap(omega, hs, tp, 1.0, gravity)


def jonswap_moment(n: int, hs: float, tp: float, gamma: float = DEFAULT_GAMMA,
                   gravity: float = STANDARD_GRAVITY) -> float:
    """Spectral moment m_n = integral omega^n S(omega) d omega of the untruncated spectrum
    (n = 0..3); m0 = Hs^2 / 16 by construction."""
    wp = peak_omega(tp)
    return (jonswap_alpha(hs, tp, gamma, gravity) * gravity ** 2 * wp ** (n - 4)
            * shape_integral(float(gamma), n))


def spectral_moment(omega: ArrayLike, density: ArrayLike, n: int = 0) -> float:
    """m_n = integral omega^n S d omega of a tabulated spectrum (trapezoidal rule)."""
    w = np.asarray(omega, dtype=float)
    return float(np.trapezoid(w ** n * np.asarray(density, dtype=float), w))


def significant_height(m0: float) -> float:
    """Hs = 4 sqrt(m0) [m].

    Parameters
    ----------
    m0
        Zeroth spectral moment (the variance of the elevation) [m^2].

    Returns
    -------
    float
        Hs [m].
    """
    return 4.0 * math.sqrt(m0)


def peak_period(omega: ArrayLike, density: ArrayLike) -> float:
    """Peak period 2 pi / omega_peak [s] of a tabulated spectrum, the peak located by a
    parabola through the largest sample and its neighbours."""
    w = np.asarray(omega, dtype=float)
    s = np.asarray(density, dtype=float)
    i = int(np.argmax(s))
    if 0 < i < len(s) - 1:
        x = w[i - 1:i + 2]
        y = s[i - 1:i + 2]
        a, b, _ = np.polyfit(x, y, 2)
        if a < 0.0:
            return 2.0 * math.pi / (-b / (2.0 * a))
    return 2.0 * math.pi / w[i]


def dnv_peak_enhancement(hs: float, tp: float) -> float:
    """gamma from Hs and Tp (DNV-RP-C205 3.5.5.5): 5 for Tp/sqrt(Hs) <= 3.6,
    exp(5.75 - 1.15 Tp/sqrt(Hs)) up to 5, then 1 (Hs in m, Tp in s: full scale only)."""
    r = tp / math.sqrt(hs)
    if r <= 3.6:
        return 5.0
    if r < 5.0:
        return math.exp(5.75 - 1.15 * r)
    return 1.0
