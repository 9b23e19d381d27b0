"""Quasi-steady rotor thrust on a floater: wind settings and the 6-DOF force.

Model
-----
The rotor thrust follows the steady curve T(U) (:mod:`floatmoor.wind.thrust`) of the relative
wind at the hub,

    U_rel = u(t) - v_hub . e,     F = T(U_rel) e,

e = (cos beta, sin beta, 0) the direction the wind blows *towards* (from +x towards +y, the
waves' ``direction`` convention; LC43: beta = 0, co-directional with the waves), u(t) the hub
wind series (:mod:`floatmoor.wind.realisation`) and v_hub the hub velocity, v[:3] + omega x
R r_hub (floatmoor.body.kinematics.points_state): for a hub right above the reference point
this is surge velocity + pitch rate * hub height. The force acts horizontally at the hub,
which follows the body (r_hub = (0, 0, 90 m) at rest above the reference point, the
centreline at the still water line); its moment about the displaced reference point is
R r_hub x F (floatmoor.body.kinematics.generalised_force), at rest M_y = +90 m * F: a +x
thrust pitches the floater bow-down about +y.

Relative wind gives aerodynamic damping -dT/dU on the hub velocity: positive below rated,
negative above rated (pitch control sheds thrust as the wind rises; see
:mod:`floatmoor.wind.thrust`). LC43's 13.05 m/s is above rated: with ``relative_velocity`` on,
the quasi-steady rotor *feeds* surge and pitch motion (about -50 kN s/m at the hub), which
hydrodynamic and mooring damping must outweigh. ``relative_velocity=False`` uses u(t) alone.

Simplifications: the rotor plane's tilt with pitch (cos of a few degrees), the rotor's spatial
averaging of turbulence, the controller's dynamics, gyroscopic and aerodynamic moments about
the shaft, and the tower and parked-rotor drag are all left out.

Which height the case's mean wind refers to
-------------------------------------------
``reference_height`` is the height at which ``mean_speed`` is given. The OC5 Phase II load case
LC4.3 (Robertson et al. 2017) gives its 13.05 m/s wind at hub height, so the default is 90 m;
the NPD spectrum is parametrised by the 10 m speed U0, obtained by inverting the NPD profile
(:func:`floatmoor.wind.spectrum.speed_at_10m`: U0 = 10.85 m/s for 13.05 m/s at 90 m). With
``reference_height = 10`` the same number is read as U0 and the hub mean is U(90 m) from the
profile.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from floatmoor.body.kinematics import generalised_force, points_state
from floatmoor.case.wind import DEFAULT_CUTOFF_HZ, SPECTRA, WindSettings
from floatmoor.wind.realisation import WindField, npd_wind, steady_wind
from floatmoor.wind.spectrum import npd_profile, speed_at_10m
from floatmoor.wind.thrust import NREL_5MW, ThrustCurve

__all__ = ["WindSettings", "RotorThrust", "SPECTRA", "DEFAULT_CUTOFF_HZ", "speed_10m",
           "hub_mean_speed"]

_GRID_TOLERANCE = 1e-6  # fraction of a half step: a time counts as on the prepared grid


def speed_10m(settings: WindSettings) -> float:
    """U0, the 1-hour mean at 10 m [m/s] (NPD profile) of ``settings``' mean speed."""
    return speed_at_10m(float(settings.mean_speed), float(settings.reference_height))


def hub_mean_speed(settings: WindSettings) -> float:
    """Mean wind speed at the hub [m/s] (NPD profile)."""
    if settings.reference_height == settings.hub_height:
        return float(settings.mean_speed)
    return float(npd_profile(speed_10m(settings), settings.hub_height))


class RotorThrust:
    """The quasi-steady rotor thrust as a 6-DOF force about the floater's reference point.

    Parameters
    ----------
    settings
        Wind settings (validated here).
    duration
        Run duration [s]: sets the frequency spacing of the wind series (1 / duration).
    curve
        Thrust curve (default the NREL 5 MW reference turbine).

    Notes
    -----
    Use with :class:`floatmoor.simulation.coupled.MooredBody`'s ``external(t, x, v)``: call
    :meth:`prepare` for a chunk of body steps (the RK4 stage times t0 + k dt/2), then
    :meth:`force` with the stage index k, or :meth:`force_at` with the time.
    """

    def __init__(self, settings: WindSettings, duration: float,
                 curve: ThrustCurve = NREL_5MW) -> None:
        settings.validate()
        self.settings = settings
        self.curve = curve
        beta = math.radians(settings.direction_deg)
        #: unit vector the wind blows towards (3,)
        self.direction = np.array([math.cos(beta), math.sin(beta), 0.0])
        #: hub relative to the reference point at rest (1, 3) [m]
        self.hub_arm = np.array([[0.0, 0.0, float(settings.hub_height)]])
        mean = hub_mean_speed(settings)
        if settings.spectrum == "steady":
            self.wind: WindField = steady_wind(mean)
        else:
            self.wind = npd_wind(mean, settings.hub_height, speed_10m(settings), duration,
                                 settings.seed, settings.cutoff_hz)
        self._t0 = math.nan
        self._dt_half = math.nan
        self._u = np.zeros(0)

    # -- wind on the stage grid -----------------------------------------------------------
    def prepare(self, t0: float, n_half: int, dt_half: float) -> None:
        """Precompute the hub wind at t0 + k dt_half, k = 0 .. n_half - 1 (for a chunk of
        ``c`` body steps of dt, n_half = 2 c + 1 and dt_half = dt / 2)."""
        self._t0, self._dt_half = float(t0), float(dt_half)
        self._u = self.wind.series(t0, dt_half, int(n_half))

    def wind_speed(self, k_half: int) -> float:
        """Prepared hub wind u(t0 + k dt_half) [m/s]."""
        return float(self._u[k_half])

    # -- force ----------------------------------------------------------------------------
    def hub_velocity(self, x: NDArray[np.float64], v: NDArray[np.float64]) -> float:
        """Hub velocity along the wind [m/s]."""
        _, vel = points_state(x, v, self.hub_arm, np.zeros(3))
        return float(vel[0] @ self.direction)

    def thrust(self, wind: float, x: NDArray[np.float64], v: NDArray[np.float64]) -> float:
        """Thrust [N] for the hub wind ``wind`` [m/s] and the body state (x, v)."""
        rel = wind - self.hub_velocity(x, v) if self.settings.relative_velocity else wind
        return float(self.curve(rel))

    def _generalised(self, thrust: float, x: NDArray[np.float64]) -> NDArray[np.float64]:
        return generalised_force(np.asarray(x, dtype=float),
                                 (thrust * self.direction)[None, :], self.hub_arm)

    def force(self, k_half: int, x: NDArray[np.float64],
              v: NDArray[np.float64]) -> NDArray[np.float64]:
        """6-DOF force (N, N m) at the prepared stage time t0 + k_half dt_half."""
        return self._generalised(self.thrust(self.wind_speed(k_half), x, v), x)

    def force_at(self, t: float, x: NDArray[np.float64],
                 v: NDArray[np.float64]) -> NDArray[np.float64]:
        """6-DOF force at time ``t``: from the prepared grid when ``t`` is on it, else from
        the wind series evaluated at ``t``."""
        k = (t - self._t0) / self._dt_half if self._u.size else math.nan
        if math.isfinite(k):
            ki = int(round(k))
            if 0 <= ki < self._u.size and abs(k - ki) <= _GRID_TOLERANCE:
                return self.force(ki, x, v)
        wind = float(self.wind.speeds(np.array([t]))[0])
        return self._generalised(self.thrust(wind, x, v), x)

    def steady_force(self) -> NDArray[np.float64]:
        """6-DOF force of the mean hub wind on the body at rest (for the static equilibrium)."""
        return self._generalised(float(self.curve(self.wind.mean)), np.zeros(6))
