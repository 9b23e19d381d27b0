"""The NPD (Froya) wind spectrum and mean wind profile.

Spectrum (DNV-RP-C205 section 2.3.4; API RP 2A-WSD; ISO 19901-1), one-sided, of the
longitudinal wind speed at height z:

.. math::
    S(f) = \\frac{320 (U_0/10)^2 (z/10)^{0.45}}{(1 + \\tilde f^{\\,n})^{5/(3n)}}, \\qquad
    \\tilde f = 172 f (z/10)^{2/3} (U_0/10)^{-0.75}, \\qquad n = 0.468,

U0 the 1-hour mean wind speed at 10 m [m/s], z [m], f [Hz], S [m^2/s^2/Hz].

Variance, in closed form. With y = f~^n, the integral over 0 < f < inf is a Beta function:

.. math::
    \\sigma_u^2 = \\frac{320 (U_0/10)^2 (z/10)^{0.45}}{172 (z/10)^{2/3} (U_0/10)^{-0.75}}
                 \\; \\frac{1}{n} B\\!\\left(\\frac1n, \\frac{2}{3n}\\right),

which :func:`npd_variance` returns (and :func:`npd_band_variance` for a band, from the
regularised incomplete Beta function). High frequencies follow Kolmogorov's inertial
subrange, S ~ f^(-5/3).

Mean wind profile (same sources), for a 1-hour mean:

.. math::
    U(z) = U_0 \\left(1 + C \\ln\\frac{z}{10}\\right), \\qquad C = 5.73\\times10^{-2}\\sqrt{1 + 0.148 U_0}.

:func:`speed_at_10m` inverts it (monotone in U0) to turn a hub-height speed into U0.

References
----------
DNV-RP-C205 (2010). Environmental conditions and environmental loads, section 2.3.4
(wind speed profile and the Froya spectrum).
Andersen, O. J., Lovseth, J. (2006). The Froya database and maritime boundary layer wind
description. Marine Structures 19, 173-192.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["NPD_EXPONENT", "npd_spectrum", "npd_variance", "npd_band_variance",
           "npd_fraction_below", "npd_profile", "speed_at_10m"]

#: Exponent n of the NPD spectrum (DNV-RP-C205 2.3.4).
NPD_EXPONENT = 0.468
_REFERENCE_HEIGHT = 10.0


def _check(mean_speed_10m: float, height: float) -> None:
    if not (math.isfinite(mean_speed_10m) and mean_speed_10m > 0.0):
        raise ValueError(f"NPD spectrum: the 10 m mean wind speed must be > 0, "
                         f"got {mean_speed_10m!r}")
    if not (math.isfinite(height) and height > 0.0):
        raise ValueError(f"NPD spectrum: the height must be > 0, got {height!r}")


def _scales(mean_speed_10m: float, height: float) -> tuple[float, float]:
    """(S(0) [m^2/s], a [s]) with f~ = a f."""
    u, z = mean_speed_10m / 10.0, height / 10.0
    return 320.0 * u * u * z ** 0.45, 172.0 * z ** (2.0 / 3.0) * u ** -0.75


def npd_spectrum(frequency: ArrayLike, mean_speed_10m: float,
                 height: float) -> NDArray[np.float64]:
    """NPD (Froya) spectrum S(f) [m^2/s^2/Hz].

    Parameters
    ----------
    frequency
        f [Hz], >= 0.
    mean_speed_10m
        U0, the 1-hour mean wind speed at 10 m [m/s].
    height
        z, the height above the still water level [m].
    """
    _check(mean_speed_10m, height)
    s0, a = _scales(mean_speed_10m, height)
    f = np.asarray(frequency, dtype=float)
    n = NPD_EXPONENT
    return s0 * (1.0 + (a * f) ** n) ** (-5.0 / (3.0 * n))


def npd_variance(mean_speed_10m: float, height: float) -> float:
    """sigma_u^2 [m^2/s^2], the integral of :func:`npd_spectrum` over 0 < f < inf."""
    _check(mean_speed_10m, height)
    s0, a = _scales(mean_speed_10m, height)
    n = NPD_EXPONENT
    from scipy.special import beta  # here, not at import: case loading needs none of scipy

    return s0 / a * beta(1.0 / n, 2.0 / (3.0 * n)) / n


def npd_fraction_below(frequency: ArrayLike, mean_speed_10m: float,
                       height: float) -> NDArray[np.float64]:
    """Fraction of the NPD variance below ``frequency`` [Hz] (closed form, vectorised).

    With y = f~^n and x = y / (1 + y), the integrand becomes the Beta density
    x^(1/n - 1) (1 - x)^(2/(3n) - 1), so the fraction is the regularised incomplete Beta
    function I_x(1/n, 2/(3n)).
    """
    _check(mean_speed_10m, height)
    _, a = _scales(mean_speed_10m, height)
    n = NPD_EXPONENT
    f = np.asarray(frequency, dtype=float)
    if np.any(f < 0.0):
        raise ValueError("NPD spectrum: frequencies must be >= 0")
    with np.errstate(over="ignore", invalid="ignore"):
        y = (a * f) ** n
        x = np.where(np.isinf(y), 1.0, y / (1.0 + y))
    from scipy.special import betainc

    return betainc(1.0 / n, 2.0 / (3.0 * n), x)


def npd_band_variance(f_low: float, f_high: float, mean_speed_10m: float,
                      height: float) -> float:
    """The integral of :func:`npd_spectrum` over f_low < f < f_high [m^2/s^2] (closed form,
    :func:`npd_fraction_below` times :func:`npd_variance`)."""
    if not (0.0 <= f_low <= f_high):
        raise ValueError(f"NPD band: need 0 <= f_low <= f_high, got {f_low}, {f_high}")
    frac = npd_fraction_below(np.array([f_low, f_high]), mean_speed_10m, height)
    return npd_variance(mean_speed_10m, height) * float(frac[1] - frac[0])


def npd_profile(mean_speed_10m: float, height: ArrayLike) -> NDArray[np.float64] | float:
    """1-hour mean wind speed U(z) [m/s] from U0 at 10 m: U0 (1 + C ln(z / 10))."""
    _check(mean_speed_10m, 1.0)
    c = 5.73e-2 * math.sqrt(1.0 + 0.148 * mean_speed_10m)
    z = np.asarray(height, dtype=float)
    out = mean_speed_10m * (1.0 + c * np.log(z / _REFERENCE_HEIGHT))
    return float(out) if out.ndim == 0 else out


def speed_at_10m(mean_speed: float, reference_height: float) -> float:
    """U0 [m/s]: the 10 m speed whose NPD profile gives ``mean_speed`` at ``reference_height``."""
    _check(mean_speed, reference_height)
    if reference_height == _REFERENCE_HEIGHT:
        return float(mean_speed)
    g = lambda u0: npd_profile(u0, reference_height) - mean_speed  # noqa: E731
    lo, hi = 1e-6, 1.0
    while g(hi) < 0.0:
        hi *= 2.0
        if hi > 1e4:
            raise ValueError(f"no 10 m wind speed gives {mean_speed} m/s at "
                             f"{reference_height} m")
    if g(lo) > 0.0:
        raise ValueError(f"no 10 m wind speed gives {mean_speed} m/s at {reference_height} m")
    from scipy.optimize import brentq

    return float(brentq(g, lo, hi, xtol=1e-12, rtol=1e-14))
