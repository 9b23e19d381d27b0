"""Steady rotor thrust curve of the NREL 5 MW reference turbine.

Turbine (Jonkman et al. 2009, NREL/TP-500-38060, Table 1-1): rotor diameter 126 m, hub height
90 m, cut-in 3 m/s, rated 11.4 m/s, cut-out 25 m/s; variable speed, collective pitch control.

Source of the table
-------------------
The steady-state thrust T(U) [kN] is stored as data from the NREL turbine-models library,
repository ``NREL/turbine-models``, file ``Offshore/NREL_5MW_126_RWT.csv`` (columns
``Wind Speed [m/s]``, ``Thrust [kN]``; the library's page ``NREL_5MW_126_RWT`` names
Jonkman et al. 2009 as its origin). The source gives the thrust itself, so no air density or
thrust coefficient enters here; its peak, 819 kN at 11.3 m/s and 805 kN at rated (11.4 m/s),
is the "about 800 kN" rated thrust commonly quoted for this rotor (Jonkman et al. 2009,
Figure 9-3, steady-state rotor thrust).

An alternative, FLORIS's ``floris/turbine_library/nrel_5MW.yaml`` (repository ``NREL/floris``,
Ct(U) at rho_air = 1.225 kg/m^3, T = 0.5 rho_air A Ct U^2), gives markedly lower thrusts:
373, 674, 508 and 419 kN at 8, 11, 13 and 15 m/s against 478, 790.6, 608.4 and 491.2 kN here
(-15 to -22 %). The turbine-models table is preferred because it tabulates the thrust itself,
resolves the peak at 0.1 m/s and reproduces the ~800 kN rated thrust of the definition report.

Between tabulated speeds the thrust is interpolated linearly (the table is dense, 0.1 m/s,
around the peak). Outside [cut-in, cut-out] the rotor is parked and its thrust is taken as zero
(the drag of a parked rotor and of the tower is neglected).

Physics to keep in mind
-----------------------
Below rated the thrust grows with the wind (dT/dU > 0); above rated the blade pitch controller
holds the power and sheds thrust, dT/dU < 0. In a quasi-steady model with the relative wind
U - x'_hub, the thrust derivative acts as a damping -dT/dU on the hub velocity: positive below
rated, *negative* above rated. This is the known "negative damping" of floating wind turbines
(Larsen & Hanson 2007, J. Phys. Conf. Ser. 75 012073; Jonkman 2008, NREL/CP-500-42589): a real
controller is detuned to keep it stable, which a steady curve cannot represent.

References
----------
Jonkman, J., Butterfield, S., Musial, W., Scott, G. (2009). Definition of a 5-MW Reference Wind
Turbine for Offshore System Development. NREL/TP-500-38060.
NREL turbine-models library, https://github.com/NREL/turbine-models,
``Offshore/NREL_5MW_126_RWT.csv``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.case.wind import HUB_HEIGHT  # NREL 5 MW's, the case's default hub height

__all__ = ["ThrustCurve", "NREL_5MW", "NREL_5MW_WIND_SPEED", "NREL_5MW_THRUST",
           "ROTOR_DIAMETER", "HUB_HEIGHT", "CUT_IN_SPEED", "RATED_SPEED", "CUT_OUT_SPEED"]

#: NREL 5 MW rotor diameter [m] (Jonkman et al. 2009, Table 1-1).
ROTOR_DIAMETER = 126.0
#: Cut-in, rated and cut-out wind speeds at hub height [m/s] (Jonkman et al. 2009, Table 1-1).
CUT_IN_SPEED = 3.0
RATED_SPEED = 11.4
CUT_OUT_SPEED = 25.0

#: Hub-height wind speed [m/s] of the NREL turbine-models table (Offshore/NREL_5MW_126_RWT.csv).
NREL_5MW_WIND_SPEED = np.array([
    3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 10.1, 10.2, 10.3, 10.4, 10.5, 10.6, 10.7, 10.8,
    10.9, 11.0, 11.1, 11.2, 11.3, 11.4, 11.5, 11.6, 11.7, 11.8, 11.9, 12.0, 13.0, 14.0, 15.0,
    16.0, 17.0, 18.0, 19.0, 20.0, 21.0, 22.0, 23.0, 24.0, 25.0])
#: Steady rotor thrust [kN] of the same table, column ``Thrust [kN]``.
NREL_5MW_THRUST = np.array([
    171.7, 215.9, 268.9, 330.3, 398.6, 478.0, 579.2, 691.496, 703.315, 715.25, 725.765,
    734.875, 744.041, 753.249, 762.527, 771.832, 781.193, 790.615, 800.098, 809.666, 819.271,
    805.112, 771.67, 748.743, 730.721, 715.414, 701.99, 689.957, 608.4, 557.9, 520.5, 491.2,
    467.7, 448.4, 432.3, 418.8, 406.7, 395.3, 385.1, 376.7, 369.3])


@dataclass(frozen=True)
class ThrustCurve:
    """A tabulated steady thrust curve T(U), linear between points, zero outside.

    Attributes
    ----------
    wind_speed
        Hub-height wind speeds [m/s], increasing.
    thrust
        Rotor thrust at those speeds [N].
    name
        Label.
    """

    wind_speed: NDArray[np.float64]
    thrust: NDArray[np.float64]
    name: str = ""

    def __post_init__(self) -> None:
        u = np.asarray(self.wind_speed, dtype=float)
        t = np.asarray(self.thrust, dtype=float)
        if u.ndim != 1 or u.shape != t.shape or u.size < 2:
            raise ValueError("thrust curve: wind_speed and thrust must be 1-D of equal length >= 2")
        if not (np.all(np.isfinite(u)) and np.all(np.isfinite(t))):
            raise ValueError("thrust curve: values must be finite")
        if np.any(np.diff(u) <= 0.0):
            raise ValueError("thrust curve: wind_speed must increase strictly")
        object.__setattr__(self, "wind_speed", u)
        object.__setattr__(self, "thrust", t)

    @property
    def cut_in(self) -> float:
        """Lowest tabulated speed [m/s]."""
        return float(self.wind_speed[0])

    @property
    def cut_out(self) -> float:
        """Highest tabulated speed [m/s]."""
        return float(self.wind_speed[-1])

    def __call__(self, speed: ArrayLike) -> NDArray[np.float64] | float:
        """Thrust [N] at hub-height wind speed(s) ``speed`` [m/s]; zero outside the table."""
        u = np.asarray(speed, dtype=float)
        out = np.interp(u, self.wind_speed, self.thrust, left=0.0, right=0.0)
        return float(out) if out.ndim == 0 else out

    def slope(self, speed: float) -> float:
        """dT/dU [N s/m] of the linear interpolant at ``speed`` (right derivative at nodes)."""
        u = self.wind_speed
        if not (u[0] <= speed < u[-1]):
            return 0.0
        i = int(np.searchsorted(u, speed, side="right")) - 1
        return float((self.thrust[i + 1] - self.thrust[i]) / (u[i + 1] - u[i]))


#: The NREL 5 MW reference turbine's steady thrust curve (thrust in N).
NREL_5MW = ThrustCurve(NREL_5MW_WIND_SPEED, 1.0e3 * NREL_5MW_THRUST, name="NREL 5 MW")
