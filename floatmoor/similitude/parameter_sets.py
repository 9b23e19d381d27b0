"""The alternative similarity parameters of Webster and of Papazoglou et al.

Chain-experiment paper section 3.3: Webster (1995, the paper's ref. [9]; its Tables 4 and
5) and Papazoglou & Mavrakos (1990, ref. [2]; Table 6) group the same data differently from
alpha_1 to alpha_5. The paper's printed tables carry slips this module does not copy (see
docs/guide/similitude.md): Table 5's second parameter is w L / T_s (labelled T_s / (w V)), its
prototype entries of parameters 4 and 5 use C_v = 3.80 and 3.82 instead of Table 3's 3.58
(the ratios 1.14 and 1.30 follow 3.58), and Table 6's parameter 8 uses the equivalent
solid-rod diameter d_e (rho_c pi d_e^2 / 4 = m), not d_o.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from floatmoor.case.schema import Case
from floatmoor.similitude.groups import WATER_KINEMATIC_VISCOSITY, characteristic_motion

__all__ = ["LineData", "line_data", "webster_parameters", "papazoglou_parameters"]


@dataclass(frozen=True)
class LineData:
    """What the parameters need of a line and its motion (the rows of the paper's Table 3)."""

    length: float  #: L, unstretched [m]
    vertical_span: float  #: V, seabed to the mean upper end [m]
    diameter: float  #: d_o, the material (nominal) diameter [m]
    mass_per_length: float  #: gamma_o [kg/m]
    axial_stiffness: float  #: K = EA [N]
    static_tension: float  #: T_s at the upper end [N]
    water_density: float  #: [kg/m^3]
    material_density: float  #: [kg/m^3]
    amplitude: float  #: r, radius of the circular motion [m]
    period: float  #: T [s]
    gravity: float  #: [m/s^2]
    kinematic_viscosity: float  #: nu [m^2/s]

    @property
    def weight(self) -> float:
        """w = (1 - rho_w / rho_c) g gamma_o, weight in water per length [N/m] (eq. 5)."""
        return (1.0 - self.water_density / self.material_density) * self.gravity \
            * self.mass_per_length

    @property
    def volume_coefficient(self) -> float:
        """C_v = gamma_o / (rho_c pi d_o^2 / 4) (eq. 30)."""
        return self.mass_per_length / (self.material_density * math.pi * self.diameter ** 2 / 4)

    @property
    def speed(self) -> float:
        """u_max = 2 pi r / T, the largest speed of the upper end [m/s] (section 3.1)."""
        return 2.0 * math.pi * self.amplitude / self.period


def line_data(case: Case, name: str, static_tension: float | None = None) -> LineData:
    """The :class:`LineData` of one single-section line of ``case``: the vertical span from
    anchor to fairlead, the motion's period and amplitude, and the static fairlead tension
    of the catenary at the mean position unless ``static_tension`` is given."""
    from floatmoor.mooring.static_strength import static_line_loads

    line = next(ln for ln in case.lines if ln.name == name)
    if static_tension is None:
        load = next(ld for ld in static_line_loads(case) if ld.line == name)
        static_tension = load.fairlead_tension
    lt, env = line.line_type, case.environment
    period, amplitude, _ = characteristic_motion(case)
    return LineData(length=line.length, vertical_span=line.fairlead[2] - line.anchor[2],
                    diameter=lt.diameter, mass_per_length=lt.mass_per_length,
                    axial_stiffness=lt.axial_stiffness, static_tension=float(static_tension),
                    water_density=env.water_density, material_density=lt.material_density,
                    amplitude=amplitude, period=period, gravity=env.gravity,
                    kinematic_viscosity=WATER_KINEMATIC_VISCOSITY)


def webster_parameters(d: LineData) -> dict[str, float]:
    """Webster's parameters 1 to 9 as the paper's Table 5 lists them (parameter 2 as w L /
    T_s; parameters 4 and 5 as the factors sqrt(C_v) and C_v of C_D and C_m)."""
    return {
        "scope L/V": d.length / d.vertical_span,
        "wL/Ts": d.weight * d.length / d.static_tension,
        "r/V": d.amplitude / d.vertical_span,
        "C_D factor sqrt(C_v)": math.sqrt(d.volume_coefficient),
        "C_m factor C_v": d.volume_coefficient,
        "T/(2 pi) sqrt(g/V)": d.period / (2.0 * math.pi) * math.sqrt(d.gravity
                                                                    / d.vertical_span),
        "rho_w/rho_c": d.water_density / d.material_density,
        "K/(wL)": d.axial_stiffness / (d.weight * d.length),
        "d_o/V": d.diameter / d.vertical_span,
    }


def papazoglou_parameters(d: LineData) -> dict[str, float]:
    """Papazoglou and Mavrakos's parameters 1 to 8 of the paper's Table 6 (parameter 9,
    the angle of the motion to the horizontal, is geometry the scaling keeps)."""
    return {
        "scope L/V": d.length / d.vertical_span,
        "d_o/L": d.diameter / d.length,
        "wL/Ts": d.weight * d.length / d.static_tension,
        "Re_max": d.speed * d.diameter / d.kinematic_viscosity,
        "rho_c/rho_w": d.material_density / d.water_density,
        "K/Ts": d.axial_stiffness / d.static_tension,
        "r/d_o": d.amplitude / d.diameter,
        # T_s / (rho_c pi d_e^2 / 4) = T_s / gamma_o: the paper's values use d_e
        "omega^2 L^2 gamma_o/Ts": (2.0 * math.pi / d.period) ** 2 * d.length ** 2
        * d.mass_per_length / d.static_tension,
    }
