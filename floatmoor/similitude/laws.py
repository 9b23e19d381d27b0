"""Scale factors of a cable (and its floater) under dynamic similitude.

Bergdahl, Palm, Eskilsson & Lindahl (2016), "Dynamically scaled model experiment of a mooring
cable", section 2.3 (docs/theory/similitude.md): the cable equation has five groups alpha_1 to
alpha_5 (eqs. 29-31); they are kept when, with lambda = L_new / L_old (eq. 32), beta =
d_new / d_old (eq. 35) and phi = C_v,new / C_v,old (eq. 36), the time scales sqrt(lambda)
(eq. 33), the stiffness and every force phi lambda beta^2 (eqs. 36-37) and the drag
coefficients beta phi / lambda (eq. 38). Every factor here is new / old.

Two differences from the paper, both following its equations rather than its text:

* floatmoor's added-mass coefficient refers to the material area m / rho_c (docs/theory/cable.md), the paper's C_MN to the nominal area pi d^2 / 4, so C_MN = C_a C_v. Keeping
  alpha_1 = C_MN rho_w / (C_v rho_c) (eq. 31a) therefore keeps C_a rho_w / rho_c: C_a is
  unchanged when the water is (the paper's C_MN scales with phi, eq. 43).
* the water density may change (sea water for a fresh-water model): the drag and added-mass
  coefficients then also absorb rho_w (eqs. 31a, d, e), and alpha_3 = (1 - rho_w / rho_c)
  g T^2 / L is no longer kept exactly (the paper's Table 6, parameter 5).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["ScaleLaw", "QUANTITY_KINDS", "LAW_NAMES", "froude_volume_coefficient_ratio",
           "SAME_FACTOR"]

#: Two scale factors count as the same within this relative difference: round-off of the
#: decimal inputs and of the products that make a factor (~1e-16 each).
SAME_FACTOR = 1e-12

#: How ``floatmoor scale`` sets phi: given by the user, ``froude`` (line forces scale like a
#: Froude-scaled floater's, rho lambda^3) or ``elastic`` (phi = 1: the line keeps its volume
#: coefficient, Collier's law with C_v = 1, the paper's reference [1]).
LAW_NAMES = ("given", "froude", "elastic")


def froude_volume_coefficient_ratio(length: float, diameter: float,
                                    water_density: float = 1.0) -> float:
    """phi making the line force scale phi lambda beta^2 (eq. 37) equal rho lambda^3, the
    force scale of a Froude-scaled floater (mass rho lambda^3, g unchanged)."""
    return water_density * (length / diameter) ** 2


@dataclass(frozen=True)
class ScaleLaw:
    """The scale factors (new / old) of one similitude law.

    Parameters
    ----------
    length
        lambda, eq. 32.
    diameter
        beta, eq. 35.
    volume_coefficient
        phi = C_v,new / C_v,old, eq. 36 (the line's mass per length scales phi beta^2).
    water_density
        rho_w,new / rho_w,old (1 when the water is not changed).
    name
        How phi was chosen (one of :data:`LAW_NAMES`).
    """

    length: float
    diameter: float
    volume_coefficient: float
    water_density: float = 1.0
    name: str = "given"

    def __post_init__(self) -> None:
        for key in ("length", "diameter", "volume_coefficient", "water_density"):
            value = getattr(self, key)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{key} scale must be a finite number > 0, not {value!r}")

    @property
    def time(self) -> float:
        """Times and periods: alpha_3 kept with g unchanged (eq. 33)."""
        return math.sqrt(self.length)

    @property
    def velocity(self) -> float:
        """Velocities, also the wave celerity (eqs. 34, 39)."""
        return math.sqrt(self.length)

    @property
    def frequency(self) -> float:
        """Frequencies [rad/s, Hz]: the inverse of :attr:`time`."""
        return 1.0 / self.time

    @property
    def mass_per_length(self) -> float:
        """gamma_0 = C_v (pi d^2 / 4) rho_c, material density unchanged (eq. 30)."""
        return self.volume_coefficient * self.diameter ** 2

    @property
    def force(self) -> float:
        """Tensions, forces and the axial stiffness EA: phi lambda beta^2 (eqs. 36, 37)."""
        return self.volume_coefficient * self.length * self.diameter ** 2

    @property
    def drag_coefficient(self) -> float:
        """C_dn, C_dt keeping alpha_4, alpha_5 = C_d L rho_w d / (2 gamma_0) (eqs. 29d-e,
        31d-e): beta phi / lambda (eq. 38) over the water-density ratio."""
        return self.diameter * self.volume_coefficient / (self.length * self.water_density)

    @property
    def added_mass_coefficient(self) -> float:
        """C_a on the material area, keeping alpha_1 = C_a rho_w / rho_c (eqs. 31a, 42)."""
        return 1.0 / self.water_density

    @property
    def seabed_stiffness(self) -> float:
        """Seabed stiffness per contact area [Pa/m]: a force per length (phi beta^2) per
        penetration (lambda) per contact width (the diameter, beta)."""
        return self.volume_coefficient * self.diameter / self.length

    @property
    def mass(self) -> float:
        """Floater and point masses, displaced-volume loads: rho lambda^3 (Froude)."""
        return self.water_density * self.length ** 3

    @property
    def inertia(self) -> float:
        """Floater moments of inertia: rho lambda^5 (Froude)."""
        return self.water_density * self.length ** 5

    @property
    def reynolds_number(self) -> float:
        """Re = u d / nu with the same viscosity: beta sqrt(lambda) (eq. 40)."""
        return self.diameter * math.sqrt(self.length)

    @property
    def keulegan_carpenter_number(self) -> float:
        """KC = u T / d: lambda / beta (section 3.1)."""
        return self.length / self.diameter

    @property
    def point_mass(self) -> float:
        """Clump weights on the lines: their weight is a line force (eq. 37)."""
        return self.force

    @property
    def point_volume(self) -> float:
        """Buoys on the lines: their buoyancy rho_w g V is a line force (eq. 37)."""
        return self.force / self.water_density

    @property
    def point_drag_area(self) -> float:
        """C_d A of points: 0.5 rho_w C_d A u^2 is a line force (eqs. 37, 39)."""
        return self.force / (self.water_density * self.length)

    def alpha_3_ratio(self, water_to_material_density: float) -> float:
        """new / old alpha_3 for a line of old rho_w / rho_c (material density unchanged)."""
        old = 1.0 - water_to_material_density
        new = 1.0 - water_to_material_density * self.water_density
        return new / old

    def factor(self, kind: str) -> float:
        """The factor of one quantity kind of :data:`QUANTITY_KINDS`."""
        if kind == "same":
            return 1.0
        if kind == "length":
            return self.length
        if kind == "volume":
            return self.length ** 3
        if kind == "area":
            return self.length ** 2
        if kind == "water_density":
            return self.water_density
        return float(getattr(self, kind))

    def inverse(self) -> ScaleLaw:
        """The law undoing this one (old / new)."""
        return ScaleLaw(1.0 / self.length, 1.0 / self.diameter, 1.0 / self.volume_coefficient,
                        1.0 / self.water_density, self.name)


#: The kinds of scaled quantities (:meth:`ScaleLaw.factor`).
QUANTITY_KINDS = ("same", "length", "area", "volume", "time", "velocity", "frequency",
                  "mass_per_length", "force", "drag_coefficient", "added_mass_coefficient",
                  "seabed_stiffness", "mass", "inertia", "water_density", "point_mass",
                  "point_volume", "point_drag_area")
