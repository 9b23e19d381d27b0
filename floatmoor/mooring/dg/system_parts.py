"""The parts of a DG mooring system: its sections, what it reads of its points, its start.

:class:`SystemSection` is one DG section between two named points; :func:`point_contact`
the seabed contact of a free point; :func:`static_start` the points' static equilibrium
the system starts from, and :func:`catenary_positions` the nodes of a section on its static
catenary between its ends. :class:`~floatmoor.mooring.dg.system.DynamicSystem` is built
from them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import DynamicSettings, Environment, Seabed
from floatmoor.errors import SolverError
from floatmoor.mooring.catenary import catenary_profile, solve_catenary
from floatmoor.mooring.dg.cable import CableProperties
from floatmoor.mooring.dg.resolution import resolve_settings
from floatmoor.mooring.statics_solver import SystemStatics, build_static_system

__all__ = ["PointLike", "SystemSection", "resolved_sections", "section_properties",
           "point_contact", "static_start", "catenary_positions"]


class PointLike(Protocol):
    """What the system reads of a point (``floatmoor.case.schema.Point``)."""

    name: str
    kind: str
    position: tuple[float, float, float]
    mass: float
    volume: float
    drag_area: float
    added_mass_coefficient: float


@dataclass(frozen=True)
class SystemSection:
    """One DG section of a system: its line's name, index from the line's start, properties,
    numerics and the names of the points at its start (s = 0) and end."""

    line: str
    index: int
    properties: CableProperties
    settings: DynamicSettings
    start: str
    end: str

    @property
    def label(self) -> str:
        """How messages name it: line name and section index."""
        return f"line '{self.line}' section {self.index}"


def resolved_sections(sections: list["SystemSection"]) -> list["SystemSection"]:
    """The sections, their element counts and orders chosen where the case leaves them
    (resolution.resolve_settings for a line system's sections: their own discretisation, no
    catenary needed), each keeping the time integration it asks for: a system of "auto"
    sections starts implicit and goes explicit when that is cheaper (``DynamicSystem``)."""
    return [replace(sec, settings=resolve_settings(sec.settings, sec.properties.length, 0.0,
                                                   several_sections=True))
            if not sec.settings.resolved else sec for sec in sections]


def section_properties(section: Any, environment: Environment, seabed: Seabed
                       ) -> CableProperties:
    """The :class:`CableProperties` of a case's section (``schema.Section``): its line type and
    length, with the internal damping ratio on the section's own first longitudinal mode."""
    return CableProperties.from_section(section, environment, seabed)


def point_contact(point: PointLike, props: CableProperties) -> tuple[float, float, float]:
    """Seabed contact of a free point (``_system_kernels`` docstring): stiffness k_p = K_b A_p
    [N/m] with A_p the projected area of the sphere of its displaced volume, damping
    2 xi sqrt(M_eff k_p) [N s/m] and the full friction force mu (M - rho_w V) g [N] (zero for
    a point without volume, or that floats). ``props`` carries the sea and the seabed."""
    V = float(point.volume)
    if point.kind != "free" or V <= 0.0:
        return 0.0, 0.0, 0.0
    area = math.pi * (3.0 * V / (4.0 * math.pi)) ** (2.0 / 3.0)
    k = props.seabed_stiffness * area
    meff = point.mass + point.added_mass_coefficient * props.water_density * V
    c = 2.0 * props.seabed_damping_ratio * math.sqrt(meff * k)
    weight = (point.mass - props.water_density * V) * props.gravity
    return k, c, props.friction_coefficient * max(weight, 0.0)


def static_start(points: Sequence[PointLike], lines: Sequence[Any], environment: Environment,
                 seabed: Seabed) -> tuple[NDArray[np.float64] | None, str]:
    """Point positions of the system's static equilibrium (``SystemStatics``, body points at
    rest, free points resting on the seabed included), to start the dynamic model from.

    Returns
    -------
    positions, why
        The positions (points in the order given, (points, 3)) and "statics"; or None and
        the statics' message when they cannot give the equilibrium: a section that floats,
        a free point held at the surface (the dynamic model handles these; it then starts
        from the case's positions and relaxes).
    """
    if not any(p.kind == "free" for p in points):
        return None, "no free point"
    try:
        system = build_static_system(points, lines, environment, seabed)
        solution = SystemStatics(system).solve()
    except SolverError as exc:
        return None, str(exc)
    return np.array(solution.positions, dtype=float), "statics"


def catenary_positions(props: CableProperties, start: NDArray, end: NDArray, s: NDArray) -> NDArray:
    """Node positions of the frictionless static catenary between two ends (inverted for a
    buoyant section, straight for a weightless one)."""
    w = props.submerged_weight
    if w == 0.0:
        return start + np.outer(s / props.length, end - start)
    flip = np.array([1.0, 1.0, 1.0 if w > 0.0 else -1.0])
    bed = props.seabed_z if w > 0.0 else -math.inf
    a, f = start * flip, end * flip
    try:
        sol = solve_catenary(a, f, props.length, props.axial_stiffness, abs(w), 0.0,
                             seabed_z=bed)
        pos, _ = catenary_profile(a, f, props.length, props.axial_stiffness, abs(w), 0.0,
                                  seabed_z=bed, arc_lengths=s, solution=sol)
    except SolverError:
        return start + np.outer(s / props.length, end - start)
    return pos * flip
