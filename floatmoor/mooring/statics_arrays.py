"""The system a statics solve works on, and what a solve gives back, as arrays (the Newton
solver that works on them is :mod:`floatmoor.mooring.statics_solver`).

:class:`StaticSystem` is a quasi-static mooring system as arrays: its points (fixed, body,
free) and its catenary sections between them, built from a case's points and lines by
:func:`build_static_system`, which refuses a free point nothing holds.
:class:`StaticSolution` is one equilibrium and :class:`StaticSeries` one along a path; the
solver is :class:`floatmoor.mooring.statics_solver.SystemStatics`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.case.schema import Environment, Seabed
from floatmoor.errors import SolverError

__all__ = ["KIND_FIXED", "KIND_BODY", "KIND_FREE", "section_name", "StaticSystem",
           "StaticSolution", "StaticSeries", "build_static_system", "vector_text"]

KIND_FIXED, KIND_BODY, KIND_FREE = "fixed", "body", "free"


def section_name(line: str, index: int) -> str:
    """Name of a section in outputs and messages: ``LINE[INDEX]``, 0 at the line's start
    (as ``Section.label``)."""
    return f"{line}[{index}]"


@dataclass(frozen=True)
class StaticSystem:
    """A mooring system in the array form of the statics kernels (build with
    :func:`build_static_system`).

    Attributes
    ----------
    point_names, point_kinds
        Every point, in the order of the arrays; kinds ``fixed``, ``body``, ``free``.
    positions
        Point positions at rest (free points: the initial guess) [m]; shape (n_points, 3).
    external_force
        Weight and buoyancy of each point, (0, 0, rho_w g V - m g) [N]; shape (n_points, 3).
    section_names, section_points
        ``LINE[INDEX]`` of each section and the names of its (start, end) points.
    section_start, section_end
        Point indices of each section's ends.
    length, axial_stiffness, weight, friction
        Per section: L [m], EA [N], submerged weight per length W [N/m], seabed friction
        coefficient C_B [-] (0 unless its line's ``quasi_static.seabed_friction``).
    tolerance, max_iterations
        Per section: its line's catenary tolerance [-] and iteration limit.
    seabed_z
        Seabed elevation [m].
    body_index, free_index
        Indices of the body points and of the free points, in point order.
    """

    point_names: tuple[str, ...]
    point_kinds: tuple[str, ...]
    positions: NDArray[np.float64] = field(repr=False)
    external_force: NDArray[np.float64] = field(repr=False)
    section_names: tuple[str, ...]
    section_points: tuple[tuple[str, str], ...]
    section_start: NDArray[np.int64] = field(repr=False)
    section_end: NDArray[np.int64] = field(repr=False)
    length: NDArray[np.float64] = field(repr=False)
    axial_stiffness: NDArray[np.float64] = field(repr=False)
    weight: NDArray[np.float64] = field(repr=False)
    friction: NDArray[np.float64] = field(repr=False)
    tolerance: NDArray[np.float64] = field(repr=False)
    max_iterations: NDArray[np.int64] = field(repr=False)
    seabed_z: float
    body_index: NDArray[np.int64] = field(repr=False)
    free_index: NDArray[np.int64] = field(repr=False)

    @property
    def body_point_names(self) -> tuple[str, ...]:
        """Names of the body points, in the order of body-position arrays."""
        return tuple(self.point_names[i] for i in self.body_index)

    @property
    def free_point_names(self) -> tuple[str, ...]:
        """Names of the free points."""
        return tuple(self.point_names[i] for i in self.free_index)

    def point_index(self, name: str) -> int:
        """Index of the point ``name``."""
        try:
            return self.point_names.index(name)
        except ValueError:
            raise KeyError(f"no point named {name!r} in the mooring system") from None


@dataclass(frozen=True)
class StaticSolution:
    """Static equilibrium of a mooring system.

    Attributes
    ----------
    point_names
        As :attr:`StaticSystem.point_names`.
    positions
        Point positions [m]; shape (n_points, 3).
    section_names, section_points
        As :class:`StaticSystem`.
    start_force, end_force
        Force each section exerts on its start point and on its end point [N]; (n_sections, 3).
    start_tension, end_tension
        Their magnitudes, the section's tension at its ends [N]; (n_sections,).
    laid_length
        Unstretched length of each section resting on the seabed [m]; (n_sections,).
    profile_types
        Catenary profile of each section (``suspended``, ``touchdown``, ...).
    point_force
        Sum of the sections' forces on each point [N]; (n_points, 3). For a free point it
        balances :attr:`StaticSystem.external_force` to the residual.
    iterations
        Newton iterations (0 when the system has no free point).
    residual
        Largest free-point force residual relative to its point's force scale [-].
    on_seabed
        Which points are free points resting on the seabed (z held there); (n_points,).
    seabed_reaction
        Upward force of the seabed on each point resting on it, 0 on the others [N];
        (n_points,): minus the vertical sum of its sections' forces and its weight and
        buoyancy.
    """

    point_names: tuple[str, ...]
    positions: NDArray[np.float64]
    section_names: tuple[str, ...]
    section_points: tuple[tuple[str, str], ...]
    start_force: NDArray[np.float64]
    end_force: NDArray[np.float64]
    start_tension: NDArray[np.float64]
    end_tension: NDArray[np.float64]
    laid_length: NDArray[np.float64]
    profile_types: tuple[str, ...]
    point_force: NDArray[np.float64]
    iterations: int
    residual: float
    #: the sections' 6x6 end stiffnesses (n_sections, 4, 3, 3): K_AA, K_AB, K_BA, K_BB with
    #: K_XY = -d(force on end X)/d(position of end Y), A = start, B = end [N/m]
    section_stiffness: NDArray[np.float64] = field(repr=False)
    #: the sections' catenary warm starts (upper-end HF, VF) [N]
    warm_start: NDArray[np.float64] = field(repr=False)
    on_seabed: NDArray[np.bool_] = field(repr=False, default_factory=lambda: np.zeros(0, bool))
    seabed_reaction: NDArray[np.float64] = field(repr=False,
                                                 default_factory=lambda: np.zeros(0))

    def position(self, name: str) -> NDArray[np.float64]:
        """Position of the point ``name`` [m]."""
        return self.positions[self.point_names.index(name)]

    def forces_on(self, name: str) -> dict[str, NDArray[np.float64]]:
        """Force of each section ending at point ``name`` on it, by section name [N]."""
        out: dict[str, NDArray[np.float64]] = {}
        for s, (a, b) in enumerate(self.section_points):
            if a == name:
                out[self.section_names[s]] = self.start_force[s]
            if b == name:
                out[self.section_names[s]] = self.end_force[s]
        return out


@dataclass(frozen=True)
class StaticSeries:
    """Static equilibria along a path of body-point positions (arrays over time first)."""

    positions: NDArray[np.float64]  #: (n, n_points, 3) [m]
    start_force: NDArray[np.float64]  #: (n, n_sections, 3) force on each start point [N]
    end_force: NDArray[np.float64]  #: (n, n_sections, 3) force on each end point [N]
    laid_length: NDArray[np.float64]  #: (n, n_sections) [m]
    iterations: NDArray[np.float64]  #: (n,) Newton iterations
    residual: NDArray[np.float64]  #: (n,) relative force residual [-]
    on_seabed: NDArray[np.bool_] | None = None  #: (n, n_points) free points on the seabed


def _attr(obj: Any, name: str, default: Any = None) -> Any:
    return getattr(obj, name, default)


def build_static_system(points: Sequence[Any], lines: Sequence[Any], environment: Environment,
                        seabed: Seabed) -> StaticSystem:
    """The array form of a system of the case schema's points and lines.

    Parameters
    ----------
    points
        ``Point``s of the case (every point, implicit ones included): name, kind, position,
        mass, volume.
    lines
        ``Line``s whose ``sections`` make the system (each section: line, index, line_type,
        length, start, end); a line's ``quasi_static`` settings give its sections' catenary
        tolerance, iteration limit and seabed friction.
    environment, seabed
        Water density and depth, gravity; the friction coefficient.

    Raises
    ------
    SolverError
        A section that floats (the catenary needs a sinking line), a section end that is no
        point, a free point with no section, or a group of free points joined to no fixed or
        body point (naming the point and the net force nothing balances).
    """
    names = tuple(str(p.name) for p in points)
    if len(set(names)) != len(names):
        raise SolverError("mooring system: point names are not unique")
    index = {n: i for i, n in enumerate(names)}
    kinds = tuple(str(p.kind) for p in points)
    for n, kind in zip(names, kinds):
        if kind not in (KIND_FIXED, KIND_BODY, KIND_FREE):
            raise SolverError(f"mooring system: point '{n}' has unknown kind {kind!r}")
    positions = np.array([p.position for p in points], dtype=float).reshape(len(names), 3)
    g, rho = environment.gravity, environment.water_density
    ext = np.zeros((len(names), 3))
    for i, p in enumerate(points):
        if kinds[i] == KIND_FREE:
            ext[i, 2] = rho * g * float(_attr(p, "volume", 0.0)) - float(_attr(p, "mass", 0.0)) * g
    sec_names, sec_points, start, end = [], [], [], []
    L, EA, W, CB, tol, maxit = [], [], [], [], [], []
    for line in lines:
        qs = line.quasi_static
        for sec in line.sections:
            name = section_name(sec.line, sec.index)
            for end_name in (sec.start, sec.end):
                if end_name not in index:
                    raise SolverError(f"mooring system: section {name} ends at '{end_name}', "
                                      "which is not a point of the system")
            w = sec.line_type.weight_in_water(environment)
            if not w > 0.0:
                raise SolverError(
                    f"mooring system: section {name} (line type '{sec.line_type.name}') has a "
                    f"submerged weight of {w:.6g} N/m: the quasi-static catenary needs a line "
                    "that sinks (material density above the water's)")
            sec_names.append(name)
            sec_points.append((sec.start, sec.end))
            start.append(index[sec.start])
            end.append(index[sec.end])
            L.append(float(sec.length))
            EA.append(float(sec.line_type.axial_stiffness))
            W.append(float(w))
            CB.append(float(seabed.friction_coefficient) if qs.seabed_friction else 0.0)
            tol.append(float(qs.tolerance))
            maxit.append(int(qs.max_iterations))
    system = StaticSystem(
        point_names=names, point_kinds=kinds, positions=positions, external_force=ext,
        section_names=tuple(sec_names), section_points=tuple(sec_points),
        section_start=np.array(start, dtype=np.int64), section_end=np.array(end, dtype=np.int64),
        length=np.array(L, dtype=float), axial_stiffness=np.array(EA, dtype=float),
        weight=np.array(W, dtype=float), friction=np.array(CB, dtype=float),
        tolerance=np.array(tol, dtype=float), max_iterations=np.array(maxit, dtype=np.int64),
        seabed_z=float(environment.seabed_z),
        body_index=np.array([i for i, k in enumerate(kinds) if k == KIND_BODY], dtype=np.int64),
        free_index=np.array([i for i, k in enumerate(kinds) if k == KIND_FREE], dtype=np.int64),
    )
    _check_support(system)
    return system


def _check_support(system: StaticSystem) -> None:
    """Every free point has a section, and every group of free points joined by sections
    reaches a fixed or body point."""
    n = len(system.point_names)
    neighbours: list[list[int]] = [[] for _ in range(n)]
    for a, b in zip(system.section_start, system.section_end):
        neighbours[a].append(int(b))
        neighbours[b].append(int(a))
    seen: set[int] = set()
    for i in system.free_index:
        i = int(i)
        if i in seen:
            continue
        if not neighbours[i]:
            raise SolverError(
                f"mooring system: free point '{system.point_names[i]}' has no section: nothing "
                f"balances its net force of {vector_text(system.external_force[i])} N")
        group, stack, supported = [], [i], False
        seen.add(i)
        while stack:
            p = stack.pop()
            group.append(p)
            for q in neighbours[p]:
                if system.point_kinds[q] != KIND_FREE:
                    supported = True
                elif q not in seen:
                    seen.add(q)
                    stack.append(q)
        if not supported:
            net = system.external_force[group].sum(axis=0)
            for s in range(len(system.section_names)):
                if int(system.section_start[s]) in group:
                    net[2] -= system.weight[s] * system.length[s]
            members = ", ".join(f"'{system.point_names[p]}'" for p in sorted(group))
            raise SolverError(
                f"mooring system: free point '{system.point_names[i]}' has no support: its group "
                f"of free points ({members}) is joined to no fixed or body point, so nothing "
                f"balances their net force (weights, buoyancy and their sections' weight) of "
                f"{vector_text(net)} N")


def vector_text(v: ArrayLike) -> str:
    """A vector as messages print it: ``(x, y, z)`` to six significant digits."""
    return "(" + ", ".join(f"{x:.6g}" for x in np.asarray(v, dtype=float)) + ")"
