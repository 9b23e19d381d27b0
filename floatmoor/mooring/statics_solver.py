"""Static equilibrium of a quasi-static mooring system: points joined by catenary sections
(the solver; the system and solution types it works on are :mod:`floatmoor.mooring.statics_arrays`).

A system is a set of points (``fixed``: stay; ``body``: given, at rest or moved; ``free``:
unknown) and sections, each the elastic catenary of :mod:`floatmoor.mooring.catenary` (seabed
contact at its lower end when that end is on the seabed, friction when its line's
``quasi_static.seabed_friction``) between its two end points. A free point balances its
sections' end forces, its weight m g (down) and its buoyancy rho_w g V (up); the positions of
the free points that achieve it are found by Newton's method with the analytic Jacobian (the
sections' 6x6 end stiffnesses, :mod:`floatmoor.mooring._statics_solver_kernels`), a step limit,
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
once; :mod:`floatmoor.mooring.statics_arrays`, with the solution types), :class:`SystemStatics`
(the solver with its warm start: :meth:`~SystemStatics.solve` for one state,
:meth:`~SystemStatics.solve_path` for a forced run), :func:`solve_statics`,
:func:`body_point_stiffness` and :func:`coupled_stiffness`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.errors import SolverError
from floatmoor.mooring import _statics_solver_kernels as _k
from floatmoor.mooring.catenary import PROFILE_NAMES, catenary_profile, describe_failure
from floatmoor.mooring.quasistatic import SHAPE_POINTS
from floatmoor.mooring.stepping import MooringSolver
from floatmoor.mooring.statics_arrays import (
    KIND_FREE, StaticSolution, StaticSystem, build_static_system, vector_text,
)

__all__ = [
    "FORCE_RTOL", "MAX_ITERATIONS", "MAX_STEP_FRACTION", "StaticSolution", "SystemStatics",
    "build_static_system", "solve_statics", "body_point_stiffness", "coupled_stiffness",
    "case_statics",
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

class _Workspace:
    """Preallocated arrays of one equilibrium problem (a given table of unknowns)."""

    def __init__(self, system: StaticSystem) -> None:
        n_sec = len(system.section_names)
        n_pts = len(system.point_names)
        n_dof = 3 * len(system.free_index)
        self.free = np.array([k == KIND_FREE for k in system.point_kinds])
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


class SystemStatics(MooringSolver):
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

    model = "quasi-static"
    has_memory = False  # an equilibrium at each instant (the warm start is its only state)

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
    def section_arc_length(self, j: int) -> NDArray[np.float64]:
        """Unstretched arc lengths from its start of section j's recorded shape points [m]
        (equally spaced, as a quasi-static line's)."""
        return np.linspace(0.0, self.system.length[j], SHAPE_POINTS)

    def section_shape(self, j: int, positions: NDArray[np.float64]
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Positions (n, 3) [m] and tensions (n,) [N] at :meth:`section_arc_length` of
        section j's catenary between its points at ``positions`` (points, 3)."""
        s = self.system
        return catenary_profile(positions[s.section_start[j]], positions[s.section_end[j]],
                                s.length[j], s.axial_stiffness[j], s.weight[j], s.friction[j],
                                seabed_z=s.seabed_z, n_points=SHAPE_POINTS)

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
                   body_velocities: NDArray[np.float64], start_force: NDArray[np.float64],
                   end_force: NDArray[np.float64], laid_length: NDArray[np.float64],
                   positions: NDArray[np.float64], iterations: NDArray[np.float64], *,
                   residual: NDArray[np.float64] | None = None,
                   on_seabed: NDArray[np.bool_] | None = None) -> None:
        """Equilibria along a path of body-point positions, written into the given arrays
        (the arguments in the order of :meth:`MooringSolver.solve_path
        <floatmoor.mooring.stepping.MooringSolver.solve_path>` and of the dynamic system's).

        Parameters
        ----------
        time
            (n,) times of the path [s], for messages.
        body_path
            (n, n_body, 3) body-point positions [m].
        body_velocities
            (n, n_body, 3) their velocities [m/s] (statics does not use them).
        start_force, end_force
            (n, n_sections, 3) output forces of the sections on their start / end points [N].
        laid_length
            (n, n_sections) output laid lengths [m].
        positions
            (n, n_points, 3) output point positions [m].
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
            return (f"{head}section {s.section_names[j]} from '{start}' at {vector_text(a)} m to "
                    f"'{end}' at {vector_text(b)} m has no valid catenary: {reason}")
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
        where = vector_text(pos[p]) if p >= 0 else "?"
        return (f"{head}no equilibrium found for free point '{name}' at {where} m after "
                f"{int(info[_k.INFO_ITER])} Newton iterations: residual force "
                f"{vector_text(comps)} N, "
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
    :meth:`SystemStatics.solve`).

    The free points' positions at which each balances its sections' end forces, its weight
    and its buoyancy (Newton's method, as MoorPy's ``System.solveEquilibrium``); a one-off
    solve: a solver kept for a path of states is :class:`SystemStatics`, whose warm start
    this drops.

    Parameters
    ----------
    system
        The points and sections (:func:`build_static_system`).
    body_positions
        (n_body, 3) in the order of :attr:`StaticSystem.body_point_names`, or a mapping
        from body-point name to position [m]; None: at rest.
    force_rtol
        Convergence: every free-point force component within this fraction of its point's
        force scale [-] (default :data:`FORCE_RTOL`).

    Returns
    -------
    StaticSolution
        Point positions, the sections' end forces, tensions, laid lengths and end
        stiffnesses, and the seabed's reaction on resting points, SI units.

    Raises
    ------
    SolverError
        Naming the point (or section) and the residual when there is no equilibrium.
    """
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

    Parameters
    ----------
    system
        The points and sections (:func:`build_static_system`).
    solution
        An equilibrium of ``system`` (:func:`solve_statics`, :meth:`SystemStatics.solve`),
        whose section end stiffnesses are used.

    Returns
    -------
    ndarray, shape (3 n_body, 3 n_body)
        Rows and columns (x, y, z) of each body point in the order of
        :attr:`StaticSystem.body_point_names` [N/m]; the 3x3 diagonal blocks are each
        point's own stiffness.

    Raises
    ------
    SolverError
        When the free points' stiffness matrix is singular (a free point held only by
        slack sections).
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
