"""Linear (Airy) dispersion relation in water of finite or infinite depth.

.. math::
    \\omega^2 = g k \\tanh(k h)

solved for the wavenumber k > 0 given the angular frequency omega > 0 and the depth h
(``math.inf`` for deep water, where k = omega^2 / g exactly). The solver works on the
dimensionless x = k h, y = omega^2 h / g: x tanh(x) = y, starting from the explicit
approximation of Fenton & McKee (1990), x0 = y coth(y^(3/4))^(2/3) (about 1.5 % error at
worst), then Newton steps until the update is below a few ulps. Everything is vectorised.

References
----------
Fenton, J. D. & McKee, W. D. (1990). On calculating the lengths of water waves.
Coastal Engineering 14, 499-513.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["STANDARD_GRAVITY", "DEEP_WATER_KH", "wavenumber", "wavelength", "group_velocity",
           "angular_frequency"]

#: Standard gravity [m/s^2] (CGPM 1901); only a default, case files give their own.
STANDARD_GRAVITY = 9.80665

#: Above this kh the deep-water form is used for the depth profiles: tanh(20) = 1 - 8.5e-18,
#: below double precision (capytaine's airy_waves uses the same switch at kh = 20).
DEEP_WATER_KH = 20.0

#: Newton stops when the relative update is below this (a few ulps of double precision).
_NEWTON_RTOL = 4.0 * np.finfo(float).eps
_NEWTON_MAX_ITERATIONS = 50


def wavenumber(omega: ArrayLike, depth: float = math.inf,
               gravity: float = STANDARD_GRAVITY) -> NDArray[np.float64]:
    """Wavenumber k [rad/m] of linear waves of angular frequency ``omega`` [rad/s].

    Parameters
    ----------
    omega
        Angular frequencies [rad/s], each > 0 (scalar or array).
    depth
        Water depth h [m] > 0; ``math.inf`` (default) for deep water.
    gravity
        g [m/s^2].

    Returns
    -------
    numpy.ndarray
        k with the shape of ``omega`` (a 0-d array for a scalar), solving
        omega^2 = g k tanh(k h) to a relative residual of about 1e-15.

    Raises
    ------
    ValueError
        If any omega <= 0 or is not finite, or depth <= 0, or gravity <= 0.
    """
    w = np.asarray(omega, dtype=float)
    if not np.all(np.isfinite(w)) or np.any(w <= 0.0):
        raise ValueError("wave angular frequencies must be finite and > 0 rad/s")
    if not depth > 0.0:
        raise ValueError(f"water depth must be > 0 m, got {depth!r}")
    if not (gravity > 0.0 and math.isfinite(gravity)):
        raise ValueError(f"gravity must be finite and > 0, got {gravity!r}")
    k_deep = w * w / gravity
    if math.isinf(depth):
        return k_deep
    y = k_deep * depth
    # Fenton & McKee (1990) explicit start, then Newton on f(x) = x tanh x - y.
    x = y / np.tanh(y ** 0.75) ** (2.0 / 3.0)
    for _ in range(_NEWTON_MAX_ITERATIONS):
        t = np.tanh(x)
        f = x * t - y
        df = t + x * (1.0 - t * t)
        step = f / df
        x = x - step
        if np.all(np.abs(step) <= _NEWTON_RTOL * x):
            break
    else:  # pragma: no cover - Newton from this start converges in < 5 steps
        raise RuntimeError("dispersion relation: Newton did not converge")
    return x / depth


def angular_frequency(k: ArrayLike, depth: float = math.inf,
                      gravity: float = STANDARD_GRAVITY) -> NDArray[np.float64]:
    """omega = sqrt(g k tanh(k h)) [rad/s] for wavenumbers ``k`` [rad/m] (the inverse map).

    Parameters
    ----------
    k
        Wavenumbers [rad/m].
    depth
        Water depth h [m] (inf: deep water).
    gravity
        g [m/s^2].

    Returns
    -------
    numpy.ndarray
        omega with the shape of ``k``.
    """
    kk = np.asarray(k, dtype=float)
    t = 1.0 if math.isinf(depth) else np.tanh(kk * depth)
    return np.sqrt(gravity * kk * t)


def wavelength(period: ArrayLike, depth: float = math.inf,
               gravity: float = STANDARD_GRAVITY) -> NDArray[np.float64]:
    """Wavelength 2 pi / k [m] of linear waves of period ``period`` [s].

    Parameters
    ----------
    period
        Wave periods [s].
    depth
        Water depth h [m] (inf: deep water).
    gravity
        g [m/s^2].

    Returns
    -------
    numpy.ndarray
        Wavelengths with the shape of ``period``.
    """
    return 2.0 * np.pi / wavenumber(2.0 * np.pi / np.asarray(period, dtype=float), depth,
                                    gravity)


def group_velocity(omega: ArrayLike, depth: float = math.inf,
                   gravity: float = STANDARD_GRAVITY) -> NDArray[np.float64]:
    """Group velocity c_g = d omega / d k = (omega / 2k)(1 + 2kh / sinh(2kh)) [m/s].

    Parameters
    ----------
    omega
        Angular frequencies [rad/s].
    depth
        Water depth h [m] (inf: deep water).
    gravity
        g [m/s^2].

    Returns
    -------
    numpy.ndarray
        c_g with the shape of ``omega``.
    """
    w = np.asarray(omega, dtype=float)
    k = wavenumber(w, depth, gravity)
    if math.isinf(depth):
        return w / (2.0 * k)
    kh2 = 2.0 * k * depth
    # 2kh/sinh(2kh) underflows harmlessly to 0 in deep water; guard the overflow of sinh.
    ratio = np.where(kh2 < 700.0, kh2 / np.sinh(np.minimum(kh2, 700.0)), 0.0)
    return w / (2.0 * k) * (1.0 + ratio)
