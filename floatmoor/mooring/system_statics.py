"""Static equilibrium of a quasi-static mooring system: points joined by catenary sections.

A system is a set of points (``fixed``: stay; ``body``: given, at rest or moved; ``free``:
unknown) and sections, each the elastic catenary of :mod:`floatmoor.mooring.catenary` (seabed
contact at its lower end when that end is on the seabed, friction when its line's
``quasi_static.seabed_friction``) between its two end points. A free point balances its
sections' end forces, its weight m g (down) and its buoyancy rho_w g V (up); the positions of
the free points that achieve it are found by Newton's method with the analytic Jacobian (the
sections' 6x6 end stiffnesses, :mod:`floatmoor.mooring._system_statics_kernels`), a step limit,
a line search and a Levenberg-Marquardt shift, as MoorPy's ``System.solveEquilibrium`` finds
them. The stiffness at the body follows by condensing the free points out, as MoorPy's
``System.getCoupledStiffness``.

A free point whose equilibrium would lie below the seabed rests on it: its z is held at the
seabed, its x and y are solved, and the seabed carries what is left of its vertical force
(:attr:`StaticSolution.seabed_reaction`); it lifts off when the seabed would have to pull it
down (an active set, in the kernels). The point has no seabed friction of its own: a massless
joint has no contact area, and the friction of a clump weight resting on the seabed is static
friction, whose force (anywhere up to mu N) the statics cannot determine without the load
history; its sections carry the catenary's friction on their laid lengths. MoorPy 1.3 (its
``Point`` has a vertical seabed force only) and MoorDyn-C (a ``Point`` has no seabed contact;
its lines' end nodes do) put no friction on a point either. With this a line split by a
massless joint lying on the seabed is the same catenary as the unsplit line, friction or not.

Entry points: :func:`build_static_system` (the case's points and lines in array form, checked
once), :class:`SystemStatics` (the solver with its warm start: :meth:`~SystemStatics.solve`
for one state, :meth:`~SystemStatics.solve_path` for a forced run), :func:`solve_statics`,
:func:`body_point_stiffness` and :func:`coupled_stiffness`.

Size: the system, its solution and the :class:`SystemStatics` solver (Newton with line
search over the free points and the body's equilibrium), with the stiffness matrices derived
from a solution; the numba kernels are in ``_system_statics_kernels``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.case.schema import Environment, Seabed
from floatmoor.errors import SolverError
from floatmoor.mooring import _system_statics_kernels as _k
from floatmoor.mooring.catenary import PROFILE_NAMES, describe_failure

__all__ = [
    "FORCE_RTOL", "MAX_ITERATIONS", "MAX_STEP_FRACTION", "StaticSystem", "StaticSolution",
    "StaticSeries", "SystemStatics", "build_static_system", "solve_statics",
    "body_point_stiffness", "coupled_stiffness", "section_name",
]

#: Convergence of the equilibrium: every free-point force component within FORCE_RTOL of the
#: point's force scale (|weight + buoyancy| + the larger end tension of each of its sections).
#: The sections' forces carry the catenary's error, ~1e-12 L of end position (its tolerance) times
#: the end stiffness, which for a taut section (EA/L) is ~1e-12 EA, ~1e-9 of its tension at a
#: strain of 1e-3; 1e-9 sits at that floor and keeps point positions within ~1e-9 of the span
#: of the converged answer, far inside the 1e-6 agreement asked against MoorPy.
FORCE_RTOL = 1e-9
#: Newton iterations per equilibrium (cold starts of the test systems need 5 to 30, warm
#: starts along a path 1 to 3).
MAX_ITERATIONS = 200
#: No free point moves further than this fraction of its shortest section in one Newton step:
#: keeps a far-off start from jumping across the catenaries' regimes (MoorPy limits steps to
#: 30 m for the same reason).
MAX_STEP_FRACTION = 0.2

_KIND_FIXED, _KIND_BODY, _KIND_FREE = "fixed", "body", "free"


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
        if kind not in (_KIND_FIXED, _KIND_BODY, _KIND_FREE):
            raise SolverError(f"mooring system: point '{n}' has unknown kind {kind!r}")
    positions = np.array([p.position for p in points], dtype=float).reshape(len(names), 3)
    g, rho = environment.gravity, environment.water_density
    ext = np.zeros((len(names), 3))
    for i, p in enumerate(points):
        if kinds[i] == _KIND_FREE:
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
        body_index=np.array([i for i, k in enumerate(kinds) if k == _KIND_BODY], dtype=np.int64),
        free_index=np.array([i for i, k in enumerate(kinds) if k == _KIND_FREE], dtype=np.int64),
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
                f"balances its net force of {_vector(system.external_force[i])} N")
        group, stack, supported = [], [i], False
        seen.add(i)
        while stack:
            p = stack.pop()
            group.append(p)
            for q in neighbours[p]:
                if system.point_kinds[q] != _KIND_FREE:
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
                f"{_vector(net)} N")


def _vector(v: ArrayLike) -> str:
    return "(" + ", ".join(f"{x:.6g}" for x in np.asarray(v, dtype=float)) + ")"


class _Workspace:
    """Preallocated arrays of one equilibrium problem (a given table of unknowns)."""

    def __init__(self, system: StaticSystem) -> None:
        n_sec = len(system.section_names)
        n_pts = len(system.point_names)
        n_dof = 3 * len(system.free_index)
        self.free = np.array([k == _KIND_FREE for k in system.point_kinds])
        self.dof = np.full((n_pts, 3), -1, dtype=np.int64)  # numbered by the kernel
        self.sec_out = np.zeros((n_sec, _k.N_SECTION_OUT))
        self.trial_out = np.zeros((n_sec, _k.N_SECTION_OUT))
        self.trial_pos = np.zeros((n_pts, 3))
        self.R = np.zeros(n_dof)
        self.Rt = np.zeros(n_dof)
        self.K = np.zeros((n_dof, n_dof))
        self.Kt = np.zeros((n_dof, n_dof))
        self.A = np.zeros((n_dof, n_dof))
        self.rhs = np.zeros(n_dof)
        self.dx = np.zeros(n_dof)
        self.scale = np.zeros(n_pts)
        self.info = np.zeros(_k.N_INFO)
        cap = np.full(n_pts, np.inf)
        for s in range(n_sec):
            for p in (system.section_start[s], system.section_end[s]):
                cap[p] = min(cap[p], MAX_STEP_FRACTION * system.length[s])
        self.step_cap = cap
        self.check_surface = self.free.copy()


class SystemStatics:
    """The statics solver of one system, with its warm start (free-point positions and the
    sections' catenary warm starts), like the quasi-static line model's.

    Parameters
    ----------
    system
        From :func:`build_static_system`.
    force_rtol
        Convergence on the relative force residual (default :data:`FORCE_RTOL`).
    max_iterations
        Newton iterations per equilibrium.
    """

    def __init__(self, system: StaticSystem, force_rtol: float = FORCE_RTOL,
                 max_iterations: int = MAX_ITERATIONS) -> None:
        self.system = system
        self.force_rtol = float(force_rtol)
        self.max_iterations = int(max_iterations)
        self._pos = np.array(system.positions, dtype=float)
        self._warm = np.full((len(system.section_names), 2), np.nan)
        self._pinned = np.zeros(len(system.point_names), dtype=np.int64)
        self._ws = _Workspace(system)
        self.failed_index = -1

    # ------------------------------------------------------------------ state
    def state_arrays(self) -> dict[str, NDArray[np.float64]]:
        """The warm start as named arrays (for a checkpoint): point positions, the sections'
        (HF, VF) and which free points rest on the seabed (1.0) or not (0.0)."""
        return {"positions": self._pos.copy(), "warm_start": self._warm.copy(),
                "on_seabed": (self._pinned == _k.PIN_SEABED).astype(float)}

    def set_state_arrays(self, arrays: Mapping[str, NDArray[np.float64]]) -> None:
        """Restore a state of :meth:`state_arrays`."""
        self._pos[:] = arrays["positions"]
        self._warm[:] = arrays["warm_start"]
        on_seabed = arrays.get("on_seabed")
        self._pinned[:] = _k.PIN_NONE
        if on_seabed is not None:
            self._pinned[np.asarray(on_seabed) != 0.0] = _k.PIN_SEABED

    def _set_body(self, body_positions: ArrayLike | Mapping[str, ArrayLike] | None) -> None:
        sys_ = self.system
        if body_positions is None:
            self._pos[sys_.body_index] = sys_.positions[sys_.body_index]
            return
        if isinstance(body_positions, Mapping):
            unknown = set(body_positions) - set(sys_.body_point_names)
            if unknown:
                raise ValueError(f"not body points of the system: {sorted(unknown)}")
            for name, value in body_positions.items():
                self._pos[sys_.point_index(name)] = np.asarray(value, dtype=float)
            return
        arr = np.asarray(body_positions, dtype=float)
        if arr.shape != (len(sys_.body_index), 3):
            raise ValueError(f"body positions must have shape ({len(sys_.body_index)}, 3), "
                             f"one row per body point {sys_.body_point_names}; got {arr.shape}")
        self._pos[sys_.body_index] = arr

    # ------------------------------------------------------------------ kernels
    def _run(self, ws: _Workspace, pos: NDArray[np.float64], warm: NDArray[np.float64],
             pinned: NDArray[np.int64]) -> int:
        s = self.system
        return int(_k.solve_equilibrium(
            pos, s.section_start, s.section_end, s.length, s.axial_stiffness, s.weight,
            s.friction, s.seabed_z, s.tolerance, s.max_iterations, ws.free, pinned, ws.dof,
            s.external_force, ws.step_cap, ws.check_surface, self.force_rtol,
            self.max_iterations, warm, ws.sec_out, ws.trial_out, ws.trial_pos, ws.R, ws.Rt,
            ws.K, ws.Kt, ws.A, ws.rhs, ws.dx, ws.scale, ws.info))

    def solve(self, body_positions: ArrayLike | Mapping[str, ArrayLike] | None = None
              ) -> StaticSolution:
        """Static equilibrium with the body points at ``body_positions``.

        Parameters
        ----------
        body_positions
            (n_body, 3) in the order of :attr:`StaticSystem.body_point_names`, or a mapping
            from body-point name to position [m]; None: at rest. Free points start from the
            last solution (or the system's initial guesses), its seabed contacts too.

        Raises
        ------
        SolverError
            Naming the point (or section) and the residual when there is no equilibrium.
        """
        self._set_body(body_positions)
        pos = self._pos.copy()
        warm = self._warm.copy()
        pinned = self._pinned.copy()
        status = self._run(self._ws, pos, warm, pinned)
        if status != _k.SYS_OK:
            raise SolverError(self._failure(status, self._ws, pos, warm, pinned, when=""))
        self._pos[:] = pos
        self._warm[:] = warm
        self._pinned[:] = pinned
        return self._solution(self._ws, pos, pinned)

    def solve_path(self, time: NDArray[np.float64], body_path: NDArray[np.float64],
                   positions: NDArray[np.float64], start_force: NDArray[np.float64],
                   end_force: NDArray[np.float64], laid_length: NDArray[np.float64],
                   iterations: NDArray[np.float64], residual: NDArray[np.float64] | None = None,
                   on_seabed: NDArray[np.bool_] | None = None) -> None:
        """Equilibria along a path of body-point positions, written into the given arrays.

        Parameters
        ----------
        time
            (n,) times of the path [s], for messages.
        body_path
            (n, n_body, 3) body-point positions [m].
        positions
            (n, n_points, 3) output point positions [m].
        start_force, end_force
            (n, n_sections, 3) output forces of the sections on their start / end points [N].
        laid_length
            (n, n_sections) output laid lengths [m].
        iterations
            (n,) output Newton iterations.
        residual
            (n,) output relative residuals, or None.
        on_seabed
            (n, n_points) output: True where a free point rests on the seabed, or None.

        Raises
        ------
        SolverError
            Naming the time, the point (or section) and why; the samples before are valid and
            the free points restart from their positions (and seabed contacts) at the last
            valid sample.
        """
        s, ws = self.system, self._ws
        n = len(time)
        res = residual if residual is not None else np.empty(n)
        pins = np.zeros((n, len(s.point_names)), dtype=np.int64)
        path = np.ascontiguousarray(body_path, dtype=float)
        if path.shape != (n, len(s.body_index), 3):
            raise ValueError(f"body path must have shape ({n}, {len(s.body_index)}, 3), "
                             f"got {path.shape}")
        pos = self._pos
        warm = self._warm
        pinned = self._pinned
        failed = int(_k.statics_series(
            path, s.body_index, pos, s.section_start, s.section_end, s.length,
            s.axial_stiffness, s.weight, s.friction, s.seabed_z, s.tolerance,
            s.max_iterations, ws.free, pinned, ws.dof, s.external_force, ws.step_cap,
            ws.check_surface, self.force_rtol, self.max_iterations, warm, ws.sec_out,
            ws.trial_out, ws.trial_pos, ws.R, ws.Rt, ws.K, ws.Kt, ws.A, ws.rhs, ws.dx, ws.scale,
            ws.info, positions, start_force, end_force, laid_length, pins, iterations, res))
        if on_seabed is not None:
            done = n if failed < 0 else failed
            on_seabed[:done] = pins[:done] == _k.PIN_SEABED
        #: the first sample of the last path not solved, -1 when all were
        self.failed_index = int(failed)
        if failed >= 0:
            info_status = self._status_from_info(ws, pos, pinned)
            fail_pos, fail_warm, fail_pins = pos.copy(), warm.copy(), pinned.copy()
            if failed > 0:  # restore the warm start of the last valid sample
                self._pos[:] = positions[failed - 1]
                self._pinned[:] = pins[failed - 1]
            message = self._failure(info_status, ws, fail_pos, fail_warm, fail_pins,
                                    when=f" at t = {time[failed]:.6g} s")
            raise SolverError(message)

    # ------------------------------------------------------------------ results
    def _status_from_info(self, ws: _Workspace, pos: NDArray[np.float64],
                          pinned: NDArray[np.int64]) -> int:
        info = ws.info
        if info[_k.INFO_CONTACT_CHANGES] > _k.MAX_CONTACT_CHANGES_PER_POINT * len(
                self.system.free_index):
            return _k.SYS_CONTACT_CYCLING
        if info[_k.INFO_POINT] >= 0:
            return _k.SYS_ABOVE_SURFACE
        if info[_k.INFO_SECTION] >= 0:
            if int(info[_k.INFO_CAT_STATUS]) == _k.CAT_SAG_BELOW_SEABED:
                return _k.SYS_SAG_BELOW_SEABED
            return _k.SYS_SECTION_FAILED
        return _k.SYS_NOT_CONVERGED

    def _solution(self, ws: _Workspace, pos: NDArray[np.float64],
                  pinned: NDArray[np.int64]) -> StaticSolution:
        s = self.system
        out = ws.sec_out
        fa = out[:, _k.S_FA:_k.S_FA + 3].copy()
        fb = out[:, _k.S_FB:_k.S_FB + 3].copy()
        point_force = np.zeros_like(pos)
        np.add.at(point_force, s.section_start, fa)
        np.add.at(point_force, s.section_end, fb)
        stiff = np.stack([out[:, k:k + 9].reshape(-1, 3, 3)
                          for k in (_k.S_KAA, _k.S_KAB, _k.S_KBA, _k.S_KBB)], axis=1)
        on_seabed = pinned == _k.PIN_SEABED
        reaction = np.where(on_seabed, -(point_force[:, 2] + s.external_force[:, 2]), 0.0) + 0.0
        return StaticSolution(
            point_names=s.point_names, positions=pos.copy(), section_names=s.section_names,
            section_points=s.section_points, start_force=fa, end_force=fb,
            start_tension=np.linalg.norm(fa, axis=1), end_tension=np.linalg.norm(fb, axis=1),
            laid_length=out[:, _k.S_LB].copy(),
            profile_types=tuple(PROFILE_NAMES[int(p)] for p in out[:, _k.S_PROFILE]),
            point_force=point_force, iterations=int(ws.info[_k.INFO_ITER]),
            residual=float(ws.info[_k.INFO_RESIDUAL]) if len(s.free_index) else 0.0,
            section_stiffness=stiff, warm_start=out[:, [_k.S_HF, _k.S_VF]].copy(),
            on_seabed=on_seabed, seabed_reaction=reaction,
        )

    def _failure(self, status: int, ws: _Workspace, pos: NDArray[np.float64],
                 warm: NDArray[np.float64], pinned: NDArray[np.int64], when: str) -> str:
        s, info = self.system, ws.info
        head = f"mooring system statics{when}: "
        if status in (_k.SYS_SECTION_FAILED, _k.SYS_SAG_BELOW_SEABED):
            j = int(info[_k.INFO_SECTION])
            a, b = pos[s.section_start[j]], pos[s.section_end[j]]
            span = b - a
            lo, hi = (a, b) if a[2] <= b[2] else (b, a)
            span = hi - lo
            reason = describe_failure(int(info[_k.INFO_CAT_STATUS]),
                                      float(np.hypot(span[0], span[1])), float(span[2]),
                                      float(s.length[j]), float(s.axial_stiffness[j]),
                                      float(s.weight[j]))
            start, end = s.section_points[j]
            return (f"{head}section {s.section_names[j]} from '{start}' at {_vector(a)} m to "
                    f"'{end}' at {_vector(b)} m has no valid catenary: {reason}")
        if status == _k.SYS_ABOVE_SURFACE:
            p = int(info[_k.INFO_POINT])
            name = s.point_names[p]
            if s.external_force[p, 2] > 0.0:
                lift = self._surface_residual(p, pos, warm, pinned)
                return (f"{head}free point '{name}' has no equilibrium below the surface: its "
                        f"buoyancy exceeds what holds it, and it would rise to z = "
                        f"{pos[p, 2]:.6g} m (held at the surface z = 0, a net upward force of "
                        f"{lift} remains on it)")
            return (f"{head}free point '{name}' rises above the water surface to z = "
                    f"{pos[p, 2]:.6g} m, where the submerged catenary does not hold")
        p = int(info[_k.INFO_WORST_POINT])
        if status == _k.SYS_CONTACT_CYCLING:
            resting = [f"'{s.point_names[q]}'" for q in s.free_index
                       if pinned[q] == _k.PIN_SEABED]
            name = s.point_names[p] if p >= 0 else "?"
            return (f"{head}no equilibrium found: the free points kept landing on and lifting "
                    f"off the seabed ({int(info[_k.INFO_CONTACT_CHANGES])} changes, the last "
                    f"at '{name}'; resting at the end: {', '.join(resting) or 'none'}): a point "
                    "balanced within the force tolerance of the seabed")
        name = s.point_names[p] if p >= 0 else "?"
        comps = [ws.R[ws.dof[p, c]] if p >= 0 and ws.dof[p, c] >= 0 else np.nan
                 for c in range(3)]
        where = _vector(pos[p]) if p >= 0 else "?"
        return (f"{head}no equilibrium found for free point '{name}' at {where} m after "
                f"{int(info[_k.INFO_ITER])} Newton iterations: residual force {_vector(comps)} N, "
                f"{info[_k.INFO_RESIDUAL]:.3g} of its force scale (tolerance "
                f"{self.force_rtol:.0e})")

    def _surface_residual(self, p: int, pos: NDArray[np.float64],
                          warm: NDArray[np.float64], pinned: NDArray[np.int64]) -> str:
        """The vertical force left on free point ``p`` held at z = 0 (its other coordinates
        and the other free points in equilibrium)."""
        ws = _Workspace(self.system)
        trial = pos.copy()
        trial[p, 2] = 0.0
        pins = pinned.copy()
        pins[p] = _k.PIN_HELD
        status = self._run(ws, trial, warm.copy(), pins)
        if status not in (_k.SYS_OK, _k.SYS_ABOVE_SURFACE):
            return "an unknown force (the pinned solve failed too)"
        fz = self.system.external_force[p, 2]
        fa = ws.sec_out[:, _k.S_FA + 2]
        fb = ws.sec_out[:, _k.S_FB + 2]
        fz += fa[self.system.section_start == p].sum() + fb[self.system.section_end == p].sum()
        return f"{fz:.6g} N"


def solve_statics(system: StaticSystem,
                  body_positions: ArrayLike | Mapping[str, ArrayLike] | None = None,
                  force_rtol: float = FORCE_RTOL) -> StaticSolution:
    """Static equilibrium of ``system`` from its initial guesses (see
    :meth:`SystemStatics.solve`)."""
    return SystemStatics(system, force_rtol=force_rtol).solve(body_positions)


def _global_stiffness(system: StaticSystem, solution: StaticSolution) -> NDArray[np.float64]:
    """K = -dF/dx over every point coordinate (3 n_points square) from the sections."""
    n = len(system.point_names)
    K = np.zeros((3 * n, 3 * n))
    for s in range(len(system.section_names)):
        a, b = int(system.section_start[s]), int(system.section_end[s])
        kaa, kab, kba, kbb = solution.section_stiffness[s]
        K[3 * a:3 * a + 3, 3 * a:3 * a + 3] += kaa
        K[3 * a:3 * a + 3, 3 * b:3 * b + 3] += kab
        K[3 * b:3 * b + 3, 3 * a:3 * a + 3] += kba
        K[3 * b:3 * b + 3, 3 * b:3 * b + 3] += kbb
    return K


def body_point_stiffness(system: StaticSystem, solution: StaticSolution) -> NDArray[np.float64]:
    """Stiffness of the body points with the free points in equilibrium (condensed out).

    K = K_bb - K_bf K_ff^-1 K_fb, with K = -d(force of the mooring on the points)/d(positions)
    from the sections' end stiffnesses at ``solution`` (as MoorPy's
    ``System.getCoupledStiffnessA`` for coupled points). The z of a free point resting on the
    seabed is held there (the seabed takes up its vertical force change), so it is not among
    the condensed coordinates f: the stiffness of small motions that keep it on the seabed.

    Returns
    -------
    ndarray, shape (3 n_body, 3 n_body)
        Rows and columns (x, y, z) of each body point in the order of
        :attr:`StaticSystem.body_point_names` [N/m]; the 3x3 diagonal blocks are each
        point's own stiffness.
    """
    K = _global_stiffness(system, solution)
    b = (3 * system.body_index[:, None] + np.arange(3)).ravel()
    f = np.array([3 * p + c for p in system.free_index for c in range(3)
                  if not (c == 2 and solution.on_seabed.size and solution.on_seabed[p])],
                 dtype=np.int64)
    kbb = K[np.ix_(b, b)]
    if f.size == 0:
        return kbb
    kff = K[np.ix_(f, f)]
    try:
        return kbb - K[np.ix_(b, f)] @ np.linalg.solve(kff, K[np.ix_(f, b)])
    except np.linalg.LinAlgError:
        raise SolverError("mooring system stiffness: the free points' stiffness matrix is "
                          "singular (a free point held only by slack sections)") from None


def _skew(r: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def coupled_stiffness(system: StaticSystem, solution: StaticSolution,
                      reference_point: ArrayLike) -> NDArray[np.float64]:
    """6x6 stiffness of the mooring on a rigid body that carries every body point.

    With r_i = p_i - reference_point and T_i = [I, -skew(r_i)] mapping the body's small
    (translation, rotation) to point i's displacement, and F_i the mooring's force on point
    i::

        K6 = sum_ij T_i' Kc_ij T_j  +  [[0, 0], [0, -sum_i skew(F_i) skew(r_i)]]

    where Kc is :func:`body_point_stiffness` and the last term is the change of the moments'
    lever arms under rotation (the force keeps its global direction). K6 = -d(F, M)/d(x, theta)
    with M about the reference point moving with the body, as MoorPy's
    ``System.getCoupledStiffness`` for a coupled body.

    Returns
    -------
    ndarray, shape (6, 6)
        [N/m, N, N/rad, N m/rad] in surge, sway, heave, roll, pitch, yaw.
    """
    kc = body_point_stiffness(system, solution)
    ref = np.asarray(reference_point, dtype=float)
    nb = len(system.body_index)
    T = np.zeros((3 * nb, 6))
    K6 = np.zeros((6, 6))
    for j, p in enumerate(system.body_index):
        r = solution.positions[p] - ref
        T[3 * j:3 * j + 3, :3] = np.eye(3)
        T[3 * j:3 * j + 3, 3:] = -_skew(r)
        K6[3:, 3:] -= _skew(solution.point_force[p]) @ _skew(r)
    return K6 + T.T @ kc @ T


def case_statics(case: Any) -> SystemStatics | None:
    """The statics of a case's lines that are not independent (``case.is_independent``: one
    section from a fixed to a body point), every model's (the static equilibrium is the same
    physics), or None when every line is independent.

    Raises
    ------
    SolverError
        As :func:`build_static_system`.
    """
    lines = [ln for ln in case.lines if not case.is_independent(ln)]
    if not lines:
        return None
    used = {n for ln in lines for s in ln.sections for n in (s.start, s.end)}
    points = [p for p in case.points if p.name in used]
    return SystemStatics(build_static_system(points, lines, case.environment, case.seabed))
