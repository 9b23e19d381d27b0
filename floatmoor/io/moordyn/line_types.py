"""floatmoor's line description <-> MoorDyn's (MoorDyn-C 2.7, ``Line.cpp``): the one place this
mapping lives (the export, the import and the MoorDyn peer harness use it).

MoorDyn has one line diameter ``d`` that it uses at once as the volume-equivalent diameter
(buoyancy ``rho_w g pi d^2/4`` and added mass ``Ca rho_w pi d^2/4`` per length) and as the drag
reference (normal drag ``0.5 rho_w Cd d |v_n| v_n``, tangential drag
``0.5 rho_w CdAx pi d |v_t| v_t``: the axial coefficient refers to the circumference).
floatmoor (docs/theory/cable.md) has the material area ``A_c = m / rho_c`` for buoyancy and
added mass and a separate drag diameter ``d`` (the nominal chain diameter). Hence:

- MoorDyn ``Diam = d_v = sqrt(4 m / (pi rho_c))``, so MoorDyn's area is ``A_c`` and weight in
  water and added mass are floatmoor's; ``Mass/m = m``; ``Ca = C_a``, ``CaAx = C_at``;
- ``Cd = C_dn d / d_v`` and ``CdAx = C_dt d / (pi d_v)``: the same drag forces per length;
- ``BA`` = floatmoor's Kelvin-Voigt coefficient ``c_int`` [N s] (a positive BA is divided by
  MoorDyn's area and multiplied back); a negative BA (``-zeta_md``) means
  ``c_int = zeta_md (L / N) sqrt(EA m)`` for a line of length L in N segments, while floatmoor's
  ratio is that of the section's first axial mode, ``c_int = 2 zeta L sqrt(EA m) / pi``
  (floatmoor.mooring.dg.line.CableProperties.from_section; L the section's length, one MoorDyn
  line being one section);
- ``EI = 0`` (floatmoor's lines have no bending stiffness).

Seabed: MoorDyn's vertical contact force per length is ``(kBot (z_b - z) - cBot v_z) d_v``;
floatmoor's stiffness ``K`` is per m of contact width, the width being the drag diameter ``d``,
and its damping per length ``2 xi sqrt(m K d)``. So ``kBot = K d / d_v`` and
``cBot = 2 xi sqrt(m K d) / d_v``: one pair per line type, whereas a deck has one pair for all.

Friction: MoorDyn-C 2.7's magnitude on a node in contact is ``min(mu C_v |v_xy|, mu |F_z|)``;
floatmoor's rises from 0 to ``mu |F_z|`` at the slip speed ``v_c``. A node resting on the seabed
carries ``F_z = w l`` (w the weight in water per length, l the segment length), so
``FricDamp = w l / v_c`` saturates MoorDyn's friction at ``v_c`` on such nodes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

__all__ = ["LineDescription", "MoorDynLineType", "moordyn_line_type", "floatmoor_line_type",
           "damping_ratio_from_moordyn", "seabed_to_moordyn",
           "seabed_from_moordyn", "friction_damping", "slip_speed_from_moordyn"]


class LineDescription(Protocol):
    """What the mapping reads of a floatmoor line type (schema.LineType has it)."""

    mass_per_length: float
    axial_stiffness: float
    diameter: float
    material_density: float
    normal_drag_coefficient: float
    tangential_drag_coefficient: float
    added_mass_coefficient: float
    tangential_added_mass_coefficient: float


@dataclass(frozen=True)
class MoorDynLineType:
    """A row of MoorDyn's LINE TYPES."""

    diameter: float  #: Diam: volume-equivalent diameter [m]
    mass_per_length: float  #: Mass/m [kg/m]
    axial_stiffness: float  #: EA [N]
    internal_damping: float  #: BA [N s] (>= 0), or -zeta_md
    normal_drag_coefficient: float  #: Cd, on Diam [-]
    added_mass_coefficient: float  #: Ca [-]
    tangential_drag_coefficient: float  #: CdAx, on pi Diam [-]
    tangential_added_mass_coefficient: float  #: CaAx [-]
    bending_stiffness: float = 0.0  #: EI [N m^2]


def volume_diameter(line: LineDescription) -> float:
    """d_v = sqrt(4 m / (pi rho_c)) [m]."""
    return math.sqrt(4.0 * (line.mass_per_length / line.material_density) / math.pi)


def moordyn_line_type(line: LineDescription, internal_damping: float) -> MoorDynLineType:
    """MoorDyn's line type for ``line`` with Kelvin-Voigt coefficient ``internal_damping``
    (c_int [N s], written as a positive BA)."""
    d_v = volume_diameter(line)
    d = line.diameter
    return MoorDynLineType(
        diameter=d_v, mass_per_length=line.mass_per_length,
        axial_stiffness=line.axial_stiffness, internal_damping=internal_damping,
        normal_drag_coefficient=line.normal_drag_coefficient * d / d_v,
        added_mass_coefficient=line.added_mass_coefficient,
        tangential_drag_coefficient=line.tangential_drag_coefficient * d / (math.pi * d_v),
        tangential_added_mass_coefficient=line.tangential_added_mass_coefficient)


def floatmoor_line_type(md: MoorDynLineType) -> dict[str, float]:
    """floatmoor's line-type values (without the damping ratio, see
    :func:`damping_ratio_from_moordyn`) for a MoorDyn line type: drag diameter = Diam, material
    density = Mass/m over MoorDyn's area (the exact inverse of :func:`moordyn_line_type`)."""
    area = math.pi * md.diameter ** 2 / 4.0
    return {
        "mass_per_length": md.mass_per_length,
        "axial_stiffness": md.axial_stiffness,
        "diameter": md.diameter,
        "material_density": md.mass_per_length / area,
        "normal_drag_coefficient": md.normal_drag_coefficient,
        "tangential_drag_coefficient": md.tangential_drag_coefficient * math.pi,
        "added_mass_coefficient": md.added_mass_coefficient,
        "tangential_added_mass_coefficient": md.tangential_added_mass_coefficient,
    }


def damping_ratio_from_moordyn(ba: float, length: float, segments: int, axial_stiffness: float,
                               mass_per_length: float) -> float:
    """floatmoor's damping ratio giving MoorDyn's internal damping ``ba`` (BA [N s], or -zeta_md
    when negative) on a line of ``length`` in ``segments`` segments."""
    root = math.sqrt(axial_stiffness * mass_per_length)
    c_int = -ba * length / segments * root if ba < 0.0 else ba
    return math.pi * c_int / (2.0 * length * root)


def seabed_to_moordyn(stiffness: float, damping_ratio: float,
                      line: LineDescription) -> tuple[float, float]:
    """(kBot [Pa/m], cBot [Pa s/m]) giving ``line`` floatmoor's seabed force per length."""
    d_v = volume_diameter(line)
    k_per_length = stiffness * line.diameter
    c_per_length = 2.0 * damping_ratio * math.sqrt(line.mass_per_length * k_per_length)
    return k_per_length / d_v, c_per_length / d_v


def seabed_from_moordyn(k_bot: float, c_bot: float,
                        line: LineDescription) -> tuple[float, float]:
    """(stiffness [Pa/m], damping ratio [-]) of floatmoor's seabed for ``line`` giving MoorDyn's
    force per length (inverse of :func:`seabed_to_moordyn`)."""
    d_v = volume_diameter(line)
    stiffness = k_bot * d_v / line.diameter
    ratio = c_bot * d_v / (2.0 * math.sqrt(line.mass_per_length * stiffness * line.diameter))
    return stiffness, ratio


def friction_damping(weight_in_water: float, length: float, segments: int,
                     slip_speed: float) -> float:
    """MoorDyn's FricDamp [N s/m] saturating at ``slip_speed`` on a resting node of a line of
    ``length`` in ``segments`` segments."""
    return max(weight_in_water * length / segments, 0.0) / slip_speed


def slip_speed_from_moordyn(fric_damp: float, weight_in_water: float, length: float,
                            segments: int) -> float:
    """floatmoor's slip speed [m/s] for MoorDyn's FricDamp on a resting node (inverse of
    :func:`friction_damping`)."""
    return weight_in_water * length / segments / fric_damp
