"""Airy (linear) wave kinematics at points, for Morison loads.

For each component of a :class:`~floatmoor.waves.realisation.WaveField` (complex amplitude
C_j = A_j e^{i k_j (x cos beta_j + y sin beta_j)} at the point, capytaine's e^{-i omega t}
convention, see floatmoor.waves.realisation) and a depth z' at which the profile is evaluated:

.. math::
    u_h &= \\Re\\{\\omega C \\frac{\\cosh k(z'+h)}{\\sinh kh} e^{-i\\omega t}\\}
           (\\cos\\beta, \\sin\\beta), &
    w   &= \\Re\\{-i\\omega C \\frac{\\sinh k(z'+h)}{\\sinh kh} e^{-i\\omega t}\\}, \\\\
    \\dot u_h &= \\Re\\{-i\\omega^2 C \\frac{\\cosh k(z'+h)}{\\sinh kh} e^{-i\\omega t}\\}
           (\\cos\\beta, \\sin\\beta), &
    \\dot w &= \\Re\\{-\\omega^2 C \\frac{\\sinh k(z'+h)}{\\sinh kh} e^{-i\\omega t}\\},

the gradient and time derivative of capytaine's incident potential (capytaine/bem/airy_waves.py,
``airy_waves_velocity``: g k / omega / cosh kh = omega / sinh kh). The profiles are evaluated as
(e^{kz'} +- e^{-k(z'+2h)}) / (1 - e^{-2kh}), which is exact, cannot overflow in deep water and
becomes e^{kz'} for h = inf. Accelerations are the local (Eulerian) d/dt of linear theory;
convective terms are second order and left out.

Stretching (points between the still water line and the instantaneous surface)
-------------------------------------------------------------------------------
Linear theory only defines the field below z = 0. With eta the total elevation at the point:

``"wheeler"`` (default; Wheeler 1970)
    z' = (z - eta) h / (h + eta) (z' = z - eta in deep water): the surface maps to z' = 0 and
    the seabed to itself, so the crest carries the z = 0 kinematics and the troughs do not get
    the exponentially larger values of the extrapolated profile.
``"vertical"`` (vertical extrapolation)
    z' = min(z, 0): the z = 0 values continued vertically up to the surface.
``"none"``
    z' = z: the Airy profile, extrapolated exponentially above z = 0 (overpredicts at crests).

Points above the instantaneous surface (z > eta) are dry: velocity and acceleration zero. Points
below the seabed (z < -h) are an error.

Cost: one call is O(P N) complex exponentials for P points and N components, then matrix-vector
products. For points fixed in the wave frame :class:`PointKinematics` keeps the horizontal phase
factors (P x N) so that each time costs one exponential per component plus the depth profiles.

References
----------
Wheeler, J. D. (1970). Method for calculating forces produced by irregular waves. Journal of
Petroleum Technology 22(3), 359-367.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.waves.realisation import WaveField

__all__ = ["STRETCHINGS", "Kinematics", "PointKinematics", "airy_kinematics",
           "elevation_at_points"]

#: Supported stretching methods (module docstring).
STRETCHINGS = ("wheeler", "vertical", "none")

#: Points up to this far below the seabed, relative to the depth, are put on it (rounding of
#: node positions that sit on the seabed); deeper is an error.
_SEABED_RTOL = 1e-9


@dataclass(frozen=True)
class Kinematics:
    """Wave kinematics at P points at one time.

    Attributes
    ----------
    elevation
        Incident elevation eta above each point [m], shape (P,).
    velocity
        Fluid velocity [m/s], shape (P, 3) (zero at dry points).
    acceleration
        Local fluid acceleration [m/s^2], shape (P, 3) (zero at dry points).
    wet
        True where the point is at or below the instantaneous surface, shape (P,).
    """

    elevation: NDArray[np.float64]
    velocity: NDArray[np.float64]
    acceleration: NDArray[np.float64]
    wet: NDArray[np.bool_]


def _profiles(k: NDArray[np.float64], z: NDArray[np.float64], depth: float
              ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """cosh k(z+h)/sinh kh and sinh k(z+h)/sinh kh for z (P,1), k (N,) -> (P, N)."""
    kz = np.minimum(k * z, 700.0)  # exp overflow guard; only reachable with "none"
    up = np.exp(kz)
    if math.isinf(depth):
        return up, up
    with np.errstate(under="ignore"):
        down = np.exp(-k * (z + 2.0 * depth))
    denom = -np.expm1(-2.0 * k * depth)
    return (up + down) / denom, (up - down) / denom


def _stretch(z: NDArray[np.float64], eta: NDArray[np.float64], depth: float,
             stretching: str) -> NDArray[np.float64]:
    if stretching == "wheeler":
        if math.isinf(depth):
            return z - eta
        return (z - eta) * depth / (depth + eta)
    if stretching == "vertical":
        return np.minimum(z, 0.0)
    return z


def _check_points(points: ArrayLike, depth: float) -> NDArray[np.float64]:
    p = np.atleast_2d(np.asarray(points, dtype=float))
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"points must have shape (P, 3), got {np.shape(points)}")
    if not np.all(np.isfinite(p)):
        raise ValueError("points must be finite")
    if not math.isinf(depth):
        floor = -depth * (1.0 + _SEABED_RTOL)
        if np.any(p[:, 2] < floor):
            raise ValueError(f"point below the seabed (z < -{depth:g} m): "
                             f"min z = {p[:, 2].min():g} m")
        p = p.copy()
        p[:, 2] = np.maximum(p[:, 2], -depth)
    return p


class PointKinematics:
    """Kinematics at points fixed in the wave frame, with their horizontal phases cached.

    Parameters
    ----------
    field
        The sea.
    points
        Positions (x, y, z) [m], shape (P, 3).
    stretching
        ``"wheeler"`` (default), ``"vertical"`` or ``"none"`` (module docstring).
    """

    def __init__(self, field: WaveField, points: ArrayLike,
                 stretching: str = "wheeler") -> None:
        if stretching not in STRETCHINGS:
            raise ValueError(f"stretching must be one of {STRETCHINGS}, got {stretching!r}")
        self.field = field
        self.stretching = stretching
        self.points = _check_points(points, field.depth)
        #: C_j / e^{-i omega t}: complex elevation amplitudes at the points, shape (P, N).
        self.spatial = field.complex_elevation(self.points[:, 0], self.points[:, 1])

    def elevation(self, t: float) -> NDArray[np.float64]:
        """eta at the points at time t [m], shape (P,)."""
        return (self.spatial @ np.exp(-1j * self.field.omega * t)).real

    def __call__(self, t: float) -> Kinematics:
        """Elevation, velocity and acceleration at the points at time ``t`` [s]."""
        f = self.field
        n_points = self.points.shape[0]
        c = self.spatial * np.exp(-1j * f.omega * t)  # (P, N)
        eta = c.sum(axis=1).real
        z = self.points[:, 2]
        wet = z <= eta
        velocity = np.zeros((n_points, 3))
        acceleration = np.zeros((n_points, 3))
        if f.n_components == 0 or not np.any(wet):
            return Kinematics(eta, velocity, acceleration, wet)
        if not math.isinf(f.depth) and np.any(eta <= -f.depth):
            raise ValueError("wave trough reaches the seabed: linear waves are not valid here")
        cw = c[wet]
        zs = _stretch(z[wet], eta[wet], f.depth, self.stretching)[:, None]
        ch, sh = _profiles(f.wavenumber, zs, f.depth)
        w = f.omega
        horizontal = cw * (w * ch)  # (P_wet, N): complex horizontal velocity amplitudes
        vertical = cw * (w * sh)
        cos_b, sin_b = np.cos(f.direction), np.sin(f.direction)
        h_cos = horizontal @ cos_b
        h_sin = horizontal @ sin_b
        velocity[wet, 0] = h_cos.real
        velocity[wet, 1] = h_sin.real
        velocity[wet, 2] = (vertical.sum(axis=1)).imag  # Re{-i z} = Im{z}
        acc_h = horizontal * w
        acceleration[wet, 0] = (acc_h @ cos_b).imag  # Re{-i omega z} = omega Im{z}
        acceleration[wet, 1] = (acc_h @ sin_b).imag
        acceleration[wet, 2] = -(vertical @ w).real  # Re{-omega^2 C sh}
        return Kinematics(eta, velocity, acceleration, wet)


def airy_kinematics(field: WaveField, points: ArrayLike, t: float,
                    stretching: str = "wheeler") -> Kinematics:
    """Airy kinematics at ``points`` (P, 3) [m] at time ``t`` [s] (module docstring).

    For points that stay put over many times use :class:`PointKinematics`.

    Parameters
    ----------
    field
        The sea.
    points
        Positions (x, y, z) [m], shape (P, 3).
    t
        Time [s].
    stretching
        ``"wheeler"`` (default), ``"vertical"`` or ``"none"`` (module docstring).

    Returns
    -------
    Kinematics
        The elevation, velocities and accelerations at the points.
    """
    return PointKinematics(field, points, stretching)(t)


def elevation_at_points(field: WaveField, x: ArrayLike, y: ArrayLike,
                        t: float) -> NDArray[np.float64]:
    """Incident elevation eta(x, y, t) [m] at many points at one time, shape of ``x``."""
    return (field.complex_elevation(x, y) @ np.exp(-1j * field.omega * t)).real
