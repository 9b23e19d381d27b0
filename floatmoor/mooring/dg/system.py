"""The dynamic model of a mooring system: DG sections joined at points.

:class:`DynamicSystem` owns the DG state of every section (node positions and velocities, each
section with its own elements and order) and the free points' positions and velocities, starts
them from each section's catenary between its ends, settles them, and advances them together,
explicitly (``_system_kernels``) at the smallest of the sections' stable steps or implicitly
with generalised-alpha steps (:mod:`floatmoor.mooring.dg.system_implicit`; ``"auto"``:
implicit until the explicit steps are the cheaper, the single line's rule), with the body
points driven by prescribed paths. The forced runs call :meth:`DynamicSystem.solve_path`; a floater
:meth:`DynamicSystem.advance` once per rigid-body step. Its sections, points and starting
shape are :mod:`floatmoor.mooring.dg.system_parts`.

Size: the joined sections' layout, settle, stepping (explicit, implicit, the "auto" switch in
segments) and records around one set of kernels (_system_kernels.py); split further, each part
would need the whole layout.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from floatmoor.disjoint_sets import DisjointSets
from floatmoor.errors import CaseError, SolverError
from floatmoor.mooring.dg import _implicit_kernels as _ik
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg import _system_kernels as _s
from floatmoor.mooring.dg.line import SETTLE_CHUNK_TAU, SETTLE_MAX_TIME_TAU, SETTLE_RATE_TAU, \
    SETTLE_TOLERANCE, DynamicLine, SettleReport
from floatmoor.mooring.dg.resolution import AutoIntegration
from floatmoor.mooring.dg.system_implicit import SystemImplicit, system_integration
from floatmoor.mooring.stepping import MooringSolver
from floatmoor.mooring.dg.system_parts import PointLike, SystemSection, catenary_positions, \
    point_contact, resolved_sections, section_properties, static_start

__all__ = ["DynamicSystem", "SystemSection", "free_point_groups"]

_STATUS_TEXT = {
    _k.DG_NOT_FINITE: "the position or velocity is not finite",
    _k.DG_VELOCITY: "a node moves faster than the longitudinal wave speed",
    _k.DG_STRAIN: f"the strain exceeds {_k.MAX_STRAIN:g}",
    _ik.DG_NEWTON: "the implicit step's Newton iteration did not converge at the smallest step",
}
#: Settling runs on the system's time scale tau = sqrt(L / g), L its longest line (through
#: its joints, clumps and buoys: the slowest to settle), which scales x sqrt(lambda) under
#: floatmoor.similitude; without free points the line's ``SETTLE_*_TAU`` apply. Why these
#: multiples, and the settle times measured: docs/validation/notes.md, "Settling on the line's
#: time scale".
SYSTEM_SETTLE_RATE_TAU = 13.0
SYSTEM_SETTLE_CHUNK_TAU = 0.015
SYSTEM_SETTLE_MAX_TIME_TAU = 6.0
KINETIC_CHUNK_TAU = 0.003
_KINDS = {"fixed": _s.FIXED, "free": _s.FREE, "body": _s.BODY}


class DynamicSystem(MooringSolver):
    """Sections and points of a mooring system solved by the DG cable model.

    Parameters
    ----------
    points
        Every point (``schema.Point`` or alike): fixed, free (mass, displaced volume, drag
        area, added-mass coefficient) or body (driven by :meth:`solve_path`; in the order
        given here, the body axis of the paths).
    sections
        The sections, each joining two of the points.
    initial_positions
        Node positions (nodes of all sections in order, 3) to start from instead of the
        catenaries.
    point_positions
        Positions of the points (points, 3) to start from instead of theirs (the statics'
        equilibrium, :func:`static_start`); the catenaries run between them.
    time
        Initial time [s].
    """

    model = "dynamic"
    resolves_dynamics = True

    def __init__(self, points: Sequence[PointLike], sections: Sequence[SystemSection], *,
                 initial_positions: NDArray[np.float64] | None = None,
                 point_positions: NDArray[np.float64] | None = None,
                 time: float = 0.0) -> None:
        if not sections:
            raise ValueError("a dynamic system needs at least one section")
        self.points = tuple(points)
        self.sections = tuple(sections)
        self.point_index = {p.name: i for i, p in enumerate(self.points)}
        P, S = len(self.points), len(self.sections)
        self.kind = np.array([_KINDS[p.kind] for p in self.points], dtype=np.int64)
        body_points = [i for i in range(P) if self.kind[i] == _s.BODY]
        self.body_points = tuple(body_points)  #: point indices of the body axis
        self.body = np.full(P, -1, dtype=np.int64)
        self.body[body_points] = np.arange(len(body_points))
        pr0 = self.sections[0].properties
        self.pprm = np.zeros((P, _s.N_PP))
        for i, p in enumerate(self.points):
            self.pprm[i, :_s.PP_KB] = (p.mass, p.volume, p.drag_area, p.added_mass_coefficient)
            self.pprm[i, _s.PP_KB:] = point_contact(p, pr0)
        self.env = np.zeros(_s.N_ENV)
        self.env[_s.E_RHO_W], self.env[_s.E_G] = pr0.water_density, pr0.gravity
        self.env[_s.E_U:_s.E_U + 3] = pr0.current_velocity
        self.env[_s.E_ZB], self.env[_s.E_VC] = pr0.seabed_z, pr0.slip_speed
        #: how the system steps: "explicit" (SSP-RK3 at the smallest section's stable step) or
        #: "implicit" (generalised-alpha, :mod:`floatmoor.mooring.dg.system_implicit`)
        self.integration = system_integration([sec.settings for sec in self.sections])
        # per-section layout (each section's explicit step: the settle and the explicit runs)
        self.lines = [DynamicLine(sec.properties,
                                  replace(sec.settings, time_integration="explicit"),
                                  np.zeros(3), np.zeros(3), name=sec.label,
                                  initial_positions=np.zeros(
                                      (sec.settings.elements * (sec.settings.order + 1), 3)))
                      for sec in self.sections]
        self.sec = np.zeros((S, _s.N_SEC), dtype=np.int64)
        ops, node, elem, face, yoff, boff = [], 0, 0, 0, 0, 0
        op_off = 0
        for j, (sec, ln) in enumerate(zip(self.sections, self.lines)):
            K, Np = sec.settings.elements, sec.settings.order + 1
            e = ln.element
            block = np.concatenate([e.differentiation.ravel(), e.lift.ravel(),
                                    e.filter.ravel(), e.weights])
            self.sec[j] = (K, Np, node, elem, face, op_off, yoff, boff,
                           self.point_index[sec.start], self.point_index[sec.end])
            ops.append(block)
            op_off += block.size
            node += K * Np
            elem += K
            face += K + 1
            yoff += K * Np * (Np + 1) * 3
            boff += K * Np * 3 * Np
        self.ops = np.concatenate(ops)
        self.prm = np.ascontiguousarray(np.stack([ln.prm for ln in self.lines]))
        self.n_nodes = node
        self.time_step = min(ln.time_step for ln in self.lines)
        #: unstretched arc length of every node from its section's start [m]
        self.arc_length = np.concatenate([ln.arc_length for ln in self.lines])
        self.time = float(time)
        self.x = np.array([p.position for p in self.points], dtype=float).reshape(P, 3)
        if point_positions is not None:
            self.x[:] = np.asarray(point_positions, dtype=float).reshape(P, 3)
        #: how the points were started: "statics" (:func:`static_start`), or why not
        self.static_start = "given" if point_positions is not None else "case positions"
        self.u = np.zeros((P, 3))
        self.body_velocity = np.zeros((len(body_points), 3))
        self.r = np.zeros((node, 3))
        self.v = np.zeros((node, 3))
        if initial_positions is None:
            for j, (sec, ln) in enumerate(zip(self.sections, self.lines)):
                a = self.x[self.sec[j, _s.S_START]]
                b = self.x[self.sec[j, _s.S_END]]
                self._section(self.r, j)[:] = catenary_positions(sec.properties, a, b,
                                                                 ln.arc_length)
        else:
            self.r[:] = np.asarray(initial_positions, dtype=float).reshape(node, 3)
        self._w = _SystemWorkspace(self.sec, self.kind, len(body_points), node, elem, face,
                                   yoff, boff)
        #: outcome of :meth:`settle`, None if not settled
        self.settle_report: SettleReport | None = None
        #: sample index of the last failure in :meth:`solve_path`, -1 if none
        self.failed_index = -1
        self._settling = False
        #: the implicit integration, None when the system steps explicitly
        self.implicit: SystemImplicit | None = None
        #: the run-time choice of ``time_integration = "auto"``, None otherwise
        self.auto: AutoIntegration | None = None
        if self.integration == "auto":
            omega = max(sec.settings.motion_frequency for sec in self.sections)
            self.auto = AutoIntegration.for_line(omega, self.time_step,
                                                 int(self.sec[:, _s.S_NP].max()))
        if self.integration != "explicit":
            sf, ef = self._end_forces(self.body_velocity)
            self.implicit = SystemImplicit(self, float(max(
                np.max(np.linalg.norm(sf, axis=1)), np.max(np.linalg.norm(ef, axis=1)))))

    @classmethod
    def from_case(cls, case: Any, *, settle: bool | None = None) -> "DynamicSystem":
        """The dynamic model of a case's system: the sections of its lines of model "dynamic"
        (a case may mix models across unconnected groups of lines) and the points they join.

        Each section's internal damping ratio refers to the section's own first longitudinal
        mode, c_int = 2 zeta L sqrt(EA m) / pi with L the section's length
        (:func:`section_properties`; the MoorDyn exporter uses the same).

        Start: the free points at the static equilibrium of the system (``SystemStatics``,
        every section's catenary, body points at rest) when the statics hold it, else at the
        case's positions (initial guesses) -- for sections that float, or a free point the
        statics refuse (a buoy lifted to the surface); then each section on
        its catenary between its ends, and the dynamic relaxation (:meth:`settle`) unless
        every line says ``settle = false``. :attr:`static_start` says which start was taken.
        """
        dynamic = [ln for ln in case.lines if ln.model == "dynamic"]
        names = {ln.name for ln in dynamic}
        sections = [SystemSection(s.line, s.index,
                                  section_properties(s, case.environment, case.seabed),
                                  s.dynamic, s.start, s.end)
                    for s in case.sections if s.line in names]
        used = {n for s in sections for n in (s.start, s.end)}
        points = [p for p in case.points if p.name in used]
        start, why = static_start(points, dynamic, case.environment, case.seabed)
        sections = resolved_sections(sections)
        obj = cls(points, sections, point_positions=start)
        obj.static_start = why
        if settle if settle is not None else any(s.settings.settle for s in sections):
            obj.settle_report = obj.settle()
        return obj

    # -- views ---------------------------------------------------------------------------------
    def _section(self, a: NDArray[np.float64], j: int) -> NDArray[np.float64]:
        o, n = self.sec[j, _s.S_NODE], self.sec[j, _s.S_K] * self.sec[j, _s.S_NP]
        return a[o:o + n]

    def section_positions(self, j: int) -> NDArray[np.float64]:
        """Node positions of section j [m], (nodes, 3) (a view of the state)."""
        return self._section(self.r, j)

    def section_tensions(self, j: int) -> NDArray[np.float64]:
        """Effective tension at every node of section j in the current state [N]."""
        self.end_forces()
        return np.linalg.norm(self._section(self._w.N, j), axis=-1)

    def section_arc_length(self, j: int) -> NDArray[np.float64]:
        """Unstretched arc length of every node of section j from its start [m]."""
        return self.lines[j].arc_length

    def section_shape(self, j: int, positions: NDArray[np.float64]
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Node positions (nodes, 3) [m] and tensions (nodes,) [N] of section j now (its
        state: ``positions``, the points', are those of the state)."""
        return self.section_positions(j), self.section_tensions(j)

    @property
    def body_positions(self) -> NDArray[np.float64]:
        """Current positions of the body points [m], (bodies, 3)."""
        return self.x[list(self.body_points)]

    # -- set-up --------------------------------------------------------------------------------
    def settle_time_scale(self) -> float:
        """The system's time scale tau [s] the relaxation runs on: sqrt(L / g) with L the
        unstretched length of its longest line (its sections summed), L / c (c the slowest
        axial wave speed) without gravity. It scales sqrt(lambda) like every time under
        dynamic similitude, so a scaled system settles through the same dimensionless
        history."""
        lengths: dict[str, float] = {}
        for sec in self.sections:
            lengths[sec.line] = lengths.get(sec.line, 0.0) + sec.properties.length
        L = max(lengths.values())
        g = self.sections[0].properties.gravity
        if g > 0.0:
            return math.sqrt(L / g)
        return L / min(sec.properties.wave_speed for sec in self.sections)

    def refuse_long_work(self, duration: float, what: str, source: str = "") -> None:
        """:meth:`DynamicLine.refuse_long_work` of the section with the shortest step (not for
        the implicit steps, whose count follows the accuracy; the settle steps explicitly)."""
        if self._stepping_implicit():
            return
        j = min(range(len(self.lines)), key=lambda k: self.lines[k].time_step)
        self.lines[j].refuse_long_work(duration, what, source, self.sections[j].line)

    def settle(self, rate: float | None = None, tolerance: float = SETTLE_TOLERANCE,
               max_time: float | None = None) -> SettleReport:
        """Relax the system to the static equilibrium of its discretisation, body points held.

        Dynamic relaxation with two dampers: a viscous one, dv/dt -= ``rate`` v on every node
        and free point, and, with free points, kinetic damping (every velocity zeroed when
        the kinetic energy has passed a peak, checked every ``KINETIC_CHUNK_TAU`` tau): the
        free points and the line masses they carry make slow modes that a viscous rate high
        enough for the lines' axial and transverse modes overdamps into a long creep. Runs in
        chunks until every section's end tensions change by less than ``tolerance``
        (relative) and every free point moves by less than ``tolerance`` times its longest
        section over a chunk. Rate, chunk and ``max_time`` default to multiples of
        :meth:`settle_time_scale` tau: ``SYSTEM_SETTLE_*_TAU`` with free points, the
        :class:`DynamicLine`'s ``SETTLE_*_TAU`` without."""
        free = self.kind == _s.FREE
        kinetic = bool(free.any())
        tau = self.settle_time_scale()
        if kinetic:
            rate_tau, chunk_tau, max_tau = (SYSTEM_SETTLE_RATE_TAU, SYSTEM_SETTLE_CHUNK_TAU,
                                            SYSTEM_SETTLE_MAX_TIME_TAU)
        else:
            rate_tau, chunk_tau, max_tau = SETTLE_RATE_TAU, SETTLE_CHUNK_TAU, SETTLE_MAX_TIME_TAU
        rate = rate_tau / tau if rate is None else rate
        max_time = max_tau * tau if max_time is None else max_time
        if not (rate >= 0.0 and tolerance > 0.0 and max_time > 0.0):
            raise ValueError("settle needs a rate >= 0 and a positive tolerance and max_time")
        self._settling = True  # (explicit steps: the relaxation's tested path)
        try:
            self.refuse_long_work(max_time,
                                  f"the system's initial settle (at most {max_time:.6g} s)")
        except CaseError:
            self._settling = False
            raise
        start = self.time
        n = max(int(math.ceil(chunk_tau * tau / self.time_step)), 2)
        sub = max(int(round(KINETIC_CHUNK_TAU * tau / self.time_step)), 1) if kinetic else n
        sub = min(sub, n)
        S, P = len(self.sections), len(self.points)
        still = np.repeat(self.body_positions[None], 2, axis=0)
        zero = np.zeros_like(still)
        sf, ef = np.zeros((2, S, 3)), np.zeros((2, S, 3))
        laid, pp, steps = np.zeros((2, S)), np.zeros((2, P, 3)), np.zeros(2)
        scale = np.zeros(P)
        for j, sec in enumerate(self.sections):
            for p in (self.sec[j, _s.S_START], self.sec[j, _s.S_END]):
                scale[p] = max(scale[p], sec.properties.length)
        previous = np.full(2 * S, np.inf)
        change, converged, peak = np.inf, False, 0.0
        self.prm[:, _k.P_RELAX] = rate
        self.env[_s.E_RELAX] = rate
        try:
            while self.time - start < max_time:
                x0 = self.x.copy()
                done = 0
                while done < n:
                    m = min(sub, n - done)
                    t = self.time + np.array([0.0, m * self.time_step])
                    self.solve_path(t, still, zero, sf, ef, laid, pp, steps)
                    done += m
                    if kinetic:
                        ke = self._kinetic_energy()
                        if ke < peak:
                            self._kinetic_reset()
                            peak = 0.0
                        else:
                            peak = ke
                ends = np.concatenate([np.linalg.norm(sf[1], axis=1),
                                       np.linalg.norm(ef[1], axis=1)])
                change = float(np.max(np.abs(ends - previous) / np.maximum(ends, 1e-300)))
                if free.any():
                    moved = np.linalg.norm(self.x - x0, axis=1)[free] / scale[free]
                    change = max(change, float(np.max(moved)))
                previous = ends
                if change < tolerance:
                    converged = True
                    break
        finally:
            self._settling = False
            self.prm[:, _k.P_RELAX] = 0.0
            self.env[_s.E_RELAX] = 0.0
            if self.implicit is not None:
                self.implicit.invalidate()
        elapsed = self.time - start
        speed = float(max(np.max(np.linalg.norm(self.v, axis=-1)),
                          np.max(np.linalg.norm(self.u, axis=-1), initial=0.0)))
        self.v[:] = 0.0
        self.u[:] = 0.0
        self.time = start
        return SettleReport(elapsed, converged, change, speed)

    def _kinetic_reset(self) -> None:
        """Zero the velocities (kinetic damping), but the vertical velocity of nodes and free
        points in seabed contact: after the split implicit contact step their steady velocity
        at rest is -dt g_eff, not zero, and zeroing it knocks them off the contact's steady
        state at every reset (the end tensions then jitter by ~1e-4 relative and the settle
        never meets its tolerance)."""
        zb = self.env[_s.E_ZB]
        self.v[:, :2] = 0.0
        self.v[self.r[:, 2] >= zb, 2] = 0.0
        self.u[:, :2] = 0.0
        self.u[self.x[:, 2] >= zb, 2] = 0.0

    def _kinetic_energy(self) -> float:
        """Kinetic energy of the nodes (mass per length, quadrature weights) and free points
        (their mass) [J], without added mass."""
        out = 0.0
        for j, ln in enumerate(self.lines):
            wq = np.tile(ln.element.weights * 0.5 * ln.element_length, ln.settings.elements)
            out += 0.5 * ln.properties.mass_per_length * float(
                wq @ np.einsum("ij,ij->i", self.v[self.section_slice(j)],
                               self.v[self.section_slice(j)]))
        M = self.pprm[:, _s.PP_MASS]
        return out + 0.5 * float(M @ np.einsum("ij,ij->i", self.u, self.u))

    # -- stepping ------------------------------------------------------------------------------
    def solve_path(self, time: NDArray[np.float64], body_positions: NDArray[np.float64],
                   body_velocities: NDArray[np.float64], start_force: NDArray[np.float64],
                   end_force: NDArray[np.float64], laid_length: NDArray[np.float64],
                   point_positions: NDArray[np.float64], steps: NDArray[np.float64], *,
                   shape_every: int = 0, shape_positions: NDArray[np.float64] | None = None,
                   shape_tension: NDArray[np.float64] | None = None) -> None:
        """Advance along the body points' paths, recording at every sample.

        Parameters
        ----------
        time
            Sample times [s], increasing, ``time[0] >= self.time`` (equal: sample 0 is the
            current state).
        body_positions, body_velocities
            The body points (in :attr:`body_points` order) at the samples [m], [m/s],
            (n, bodies, 3).
        start_force, end_force
            Outputs: force of each section on its start / end point [N], (n, sections, 3).
        laid_length
            Output: each section's length on the seabed [m], (n, sections).
        point_positions
            Output: every point's position [m], (n, points, 3).
        steps
            Output: time steps taken to reach each sample, (n,).
        shape_every, shape_positions, shape_tension
            Every ``shape_every``-th sample, all nodes' positions (m, nodes, 3) and tensions
            (m, nodes), sections one after another (:meth:`section_slice`).

        Raises
        ------
        SolverError
            When the solution goes unstable, naming the section (line and index) or point,
            the time and the quantity; the outputs before that sample are valid.
        """
        time = np.asarray(time, dtype=float)
        nb = len(self.body_points)
        bp = np.asarray(body_positions, dtype=float).reshape(time.size, nb, 3)
        bv = np.asarray(body_velocities, dtype=float).reshape(time.size, nb, 3)
        prepend = time[0] > self.time
        if prepend:
            time = np.concatenate(([self.time], time))
            bp = np.concatenate((self.body_positions[None], bp))
            bv = np.concatenate((self.body_velocity[None], bv))
        n, S, P = time.size, len(self.sections), len(self.points)
        w = self._w
        sf, ef = np.zeros((n, S, 3)), np.zeros((n, S, 3))
        lb, pp, st = np.zeros((n, S)), np.zeros((n, P, 3)), np.zeros(n)
        if shape_every > 0 and shape_positions is not None and shape_tension is not None:
            sr, sten = shape_positions, shape_tension
            if prepend:
                raise ValueError("shape output needs time[0] == the system's time")
        else:
            shape_every, sr, sten = 0, np.zeros((1, 1, 3)), np.zeros((1, 1))
        bp, bv = np.ascontiguousarray(bp), np.ascontiguousarray(bv)
        outs = (sf, ef, lb, pp, st)
        i0 = 0
        while True:  # in segments while "auto" may still switch (_segment_end)
            i1 = self._segment_end(time, i0, shape_every)
            status, index = self._run_segment(time, bp, bv, outs, shape_every, sr, sten, i0, i1)
            if status != _k.DG_OK or i1 >= n - 1:
                break
            self._switch_if_dearer(float(time[i1]))
            i0 = i1
        first = 1 if prepend else 0
        done = index if status != _k.DG_OK else n
        start_force[:done - first] = sf[first:done]
        end_force[:done - first] = ef[first:done]
        laid_length[:done - first] = lb[first:done]
        point_positions[:done - first] = pp[first:done]
        steps[:done - first] = st[first:done]
        if status != _k.DG_OK:
            self.failed_index = index - first
            j, k, i = (int(c) for c in w.where)
            if j < 0:
                raise SolverError(f"point '{self.points[k].name}' (dynamic system): its position "
                                  f"or velocity is not finite at t = {time[index]:.6g} s; the "
                                  f"solution went unstable ({self._step_text()})")
            sec = self.sections[j]
            s = self.lines[j].arc_length[k * (sec.settings.order + 1) + i]
            raise SolverError(f"{sec.label} (dynamic): {_STATUS_TEXT[status]} at arc length "
                              f"s = {s:.4g} m from its start, t = {time[index]:.6g} s; the "
                              f"solution went unstable ({self._step_text()})")
        self.failed_index = -1
        self.time = float(time[-1])
        for b, p in enumerate(self.body_points):
            self.x[p] = bp[-1, b]
        self.body_velocity = np.array(bv[-1], dtype=float)
        self._switch_if_dearer(self.time)

    def _run_segment(self, time: NDArray, bp: NDArray, bv: NDArray, outs: tuple, shape_every: int,
                     sr: NDArray, sten: NDArray, i0: int, i1: int) -> tuple[int, int]:
        """One kernel call over samples ``i0`` to ``i1`` (its first sample, the state the
        previous call ended in, is recorded again: the earlier record is kept); the status
        and the failing sample's index in the whole path."""
        w = self._w
        seg = slice(i0, i1 + 1)
        kept = tuple(a[i0].copy() for a in outs) if i0 > 0 else None
        if shape_every > 0:
            sr, sten = sr[i0 // shape_every:], sten[i0 // shape_every:]
        t, x, u = (np.ascontiguousarray(a[seg]) for a in (time, bp, bv))
        sf, ef, lb, pp, st = (a[seg] for a in outs)
        if self._stepping_implicit():
            status, index = self.implicit.run(self, t, x, u, sf, ef, lb, pp, st, shape_every,
                                              sr, sten)
        else:
            if self.implicit is not None:
                self.implicit.invalidate()
            status, index = _s.dgs_run_path(
                self.r, self.v, self.x, self.u, t, x, u, self.sec, self.prm, self.ops,
                self.kind, self.body, self.pprm, self.env, self.time_step, sf, ef, lb, pp, st,
                shape_every, sr, sten, w.stages, w.pstages, w.q, w.qt, w.N, w.Nstar, w.faces,
                w.slack, w.ppos, w.pvel, w.G, w.Zs, w.tmp, w.bcd, *w.damping, w.coupling,
                w.where)
        if kept is not None:
            for a, k in zip(outs, kept):
                a[i0] = k
        return status, i0 + index

    def _segment_end(self, time: NDArray[np.float64], i0: int, shape_every: int) -> int:
        """Last sample of the kernel call starting at ``i0``: the path's end, or, with
        ``"auto"``, the first (shape) sample at or after its next decision
        (``AutoIntegration.segment_end``)."""
        if self.auto is None or self._settling:
            return time.size - 1
        return self.auto.segment_end(time, i0, shape_every, self.implicit.cs)

    def _switch_if_dearer(self, time: float) -> None:
        """``"auto"`` (not settling): at ``time``, switch between implicit and explicit steps
        where its windows say so (``resolution.AutoIntegration.update``, the single line's
        rule, window by window)."""
        if (self.auto is not None and not self._settling
                and self.auto.update(time, self.implicit.cs)):
            self._w.damping[7][:, 0] = 0.0  # no factored damping system of this state yet
            self.implicit.invalidate()  # accelerations and factors of an older state

    def _stepping_implicit(self) -> bool:
        """Whether the next steps are implicit (not while settling: the explicit relaxation;
        ``"auto"``: until it went explicit)."""
        return (self.implicit is not None and not self._settling
                and not (self.auto is not None and self.auto.switched))

    def _step_text(self) -> str:
        """The step, as failure messages name it."""
        if not self._stepping_implicit():
            return f"time step {self.time_step:.3g} s"
        return (f"implicit steps of at most {self.implicit.max_step:.3g} s, "
                f"{int(self.implicit.cs[_ik.CS_REJECTED])} rejected")

    def section_slice(self, j: int) -> slice:
        """The nodes of section j in the system's node axis."""
        o = int(self.sec[j, _s.S_NODE])
        return slice(o, o + int(self.sec[j, _s.S_K] * self.sec[j, _s.S_NP]))

    def advance(self, t1: float, body_positions: NDArray[np.float64],
                body_velocities: NDArray[np.float64]) -> NDArray[np.float64]:
        """Advance to ``t1``, the body points moving (cubic Hermite) to the given positions and
        velocities (bodies, 3); returns the force of the lines on each body point at ``t1``
        [N], (bodies, 3)."""
        S, P, nb = len(self.sections), len(self.points), len(self.body_points)
        sf, ef = np.zeros((1, S, 3)), np.zeros((1, S, 3))
        self.solve_path(np.array([float(t1)]),
                        np.asarray(body_positions, dtype=float).reshape(1, nb, 3),
                        np.asarray(body_velocities, dtype=float).reshape(1, nb, 3), sf, ef,
                        np.zeros((1, S)), np.zeros((1, P, 3)), np.zeros(1))
        return self._body_forces(sf[0], ef[0])

    def _body_forces(self, sf: NDArray[np.float64], ef: NDArray[np.float64]
                     ) -> NDArray[np.float64]:
        out = np.zeros((len(self.body_points), 3))
        for j in range(len(self.sections)):
            for col, f in ((_s.S_START, sf[j]), (_s.S_END, ef[j])):
                b = self.body[self.sec[j, col]]
                if b >= 0:
                    out[b] += f
        return out

    def end_forces(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Forces of every section on its start and end point in the current state [N],
        (sections, 3) each."""
        return self._end_forces(self.body_velocity)

    def end_forces_moving(self, body_velocities: NDArray[np.float64]) -> NDArray[np.float64]:
        """Forces of the lines on each body point [N], (bodies, 3), in the current state with
        the body points' velocities replaced (as ``PathStepper.end_forces_moving``: the end
        fluxes answer the velocity at once through the axial impedance)."""
        return self._body_forces(*self._end_forces(body_velocities))

    def section_end_forces(self, body_velocities: NDArray[np.float64]
                           ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Forces of every section on its start and end point [N], (sections, 3) each, in the
        current state with the body points moving at ``body_velocities`` (bodies, 3)."""
        return self._end_forces(body_velocities)

    def _end_forces(self, body_velocities: NDArray[np.float64]
                    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        w, S = self._w, len(self.sections)
        bv = np.asarray(body_velocities, dtype=float).reshape(-1, 3)
        for p in range(len(self.points)):
            w.ppos[p] = self.x[p]
            w.pvel[p] = bv[self.body[p]] if self.kind[p] == _s.BODY else 0.0
        sf, ef, laid = np.zeros((S, 3)), np.zeros((S, 3)), np.zeros(S)
        _s.dgs_record(self.r, self.v, self.x, self.u, self.sec, self.prm, self.ops, self.kind,
                      self.pprm, self.env, w.ppos, w.pvel, w.G, w.Zs, w.q, w.qt, w.N, w.Nstar,
                      w.faces, w.slack, w.pstages[4], sf, ef, laid)
        return sf, ef

    def seabed_forces(self) -> NDArray[np.float64]:
        """Force of the seabed on every point in the current state [N], (points, 3): the
        normal spring-damper and the friction of free points resting on it (zero for other
        points, and for free points without volume, which rest on their sections' nodes)."""
        out = np.zeros((len(self.points), 3))
        zb, vc = self.env[_s.E_ZB], self.env[_s.E_VC]
        for p in np.flatnonzero((self.kind == _s.FREE) & (self.pprm[:, _s.PP_KB] > 0.0)):
            z = self.x[p, 2]
            if z >= zb:
                continue
            kb, cb, mu = self.pprm[p, _s.PP_KB:_s.PP_KB + 3]
            out[p, 2] = -kb * (z - zb) - cb * min(self.u[p, 2], 0.0)
            speed = float(np.hypot(self.u[p, 0], self.u[p, 1]))
            if speed > 0.0:
                mag = mu * math.sin(0.5 * math.pi * speed / max(vc, speed))
                out[p, :2] = -mag * self.u[p, :2] / speed
        return out

    def energy(self) -> dict[str, float]:
        """Kinetic, strain and gravitational energy [J] of the sections and free points (the
        sections' gravity with their submerged weight below z = 0, the points' with
        (M - rho_w V) g below z = 0; added mass not counted)."""
        self.end_forces()
        out = {"kinetic": 0.0, "strain": 0.0, "gravity": 0.0}
        for j, ln in enumerate(self.lines):
            sl = self.section_slice(j)
            pr = ln.properties
            wq = np.tile(ln.element.weights * 0.5 * ln.element_length, ln.settings.elements)
            v2 = np.sum(self.v[sl] ** 2, axis=1)
            ql = np.linalg.norm(self._w.q[sl], axis=1)
            eps = np.maximum(ql - 1.0, 0.0)
            z = self.r[sl, 2]
            weight = pr.mass_per_length * pr.gravity * np.where(
                z < 0.0, 1.0 - pr.water_density / pr.material_density, 1.0)
            out["kinetic"] += float(0.5 * pr.mass_per_length * np.sum(wq * v2))
            out["strain"] += float(0.5 * pr.axial_stiffness * np.sum(wq * eps ** 2))
            out["gravity"] += float(np.sum(wq * weight * z))
        rho_w, g = self.env[_s.E_RHO_W], self.env[_s.E_G]
        for p in np.flatnonzero(self.kind == _s.FREE):
            M, V = self.pprm[p, _s.PP_MASS], self.pprm[p, _s.PP_VOLUME]
            z = self.x[p, 2]
            out["kinetic"] += 0.5 * M * float(self.u[p] @ self.u[p])
            out["gravity"] += (M - (rho_w * V if z < 0.0 else 0.0)) * g * z
        return out

    # -- state ---------------------------------------------------------------------------------
    def state_arrays(self) -> dict[str, NDArray[np.float64]]:
        """The state as named arrays (time 0-d), for a checkpoint: node positions and
        velocities, point positions and velocities, body velocities, and the implicit
        damping's frozen factors."""
        out = {"time": np.array(self.time, dtype=np.float64), "positions": self.r.copy(),
               "velocities": self.v.copy(), "point_positions": self.x.copy(),
               "point_velocities": self.u.copy(), "body_velocities": self.body_velocity.copy()}
        out.update({f"damping_{i}": a.copy() for i, a in enumerate(self._w.damping)})
        if self.implicit is not None:
            out.update(self.implicit.state_arrays())
        if self.auto is not None:
            out.update(self.auto.state())
        return out

    def set_state_arrays(self, arrays: dict[str, NDArray[np.float64]]) -> None:
        """Restore a state of :meth:`state_arrays` (shapes checked by the caller)."""
        self.time = float(arrays["time"])
        self.r[:] = arrays["positions"]
        self.v[:] = arrays["velocities"]
        self.x[:] = arrays["point_positions"]
        self.u[:] = arrays["point_velocities"]
        self.body_velocity = np.array(arrays["body_velocities"], dtype=float)
        for i, a in enumerate(self._w.damping):
            a[...] = arrays[f"damping_{i}"]
        if self.implicit is not None:
            self.implicit.set_state_arrays(arrays)
        if self.auto is not None:
            self.auto.set_state(arrays)
            if self.auto.switched:
                self._w.damping[7][:, 0] = 0.0


class _SystemWorkspace:
    """Preallocated arrays of the system kernels (no allocation inside the time loop)."""

    def __init__(self, sec: NDArray[np.int64], kind: NDArray[np.int64], nb: int, nodes: int,
                 elems: int, faces: int, ysize: int, bandsize: int) -> None:
        S, P = sec.shape[0], kind.shape[0]
        npmax = int(sec[:, _s.S_NP].max())
        self.stages = np.zeros((5, nodes, 3))
        self.pstages = np.zeros((5, P, 3))
        self.q = np.zeros((nodes, 3))
        self.qt = np.zeros((nodes, 3))
        self.N = np.zeros((nodes, 3))
        self.Nstar = np.zeros((faces, 3))
        self.faces = np.zeros((faces, 3))
        self.slack = np.zeros(elems)
        self.ppos = np.zeros((P, 3))
        self.pvel = np.zeros((P, 3))
        self.G = np.zeros((P, 3))
        self.Zs = np.zeros(P)
        self.tmp = np.zeros(max(npmax, 6))
        self.bcd = np.zeros((max(nb, 1), 4, 3))
        self.where = np.zeros(3, dtype=np.int64)
        # the implicit damping systems of all sections: tangents, inverse masses,
        # coefficients, flags, Y, band, rhs, info (per section: valid, dt, any node taut,
        # factorisations, factorisation of the responses; info[:, 0] = 0: invalid), and the
        # responses of the damping tensions to the velocity of a free end point (start / end,
        # component, node): frozen data of the state, kept in checkpoints
        self.damping = (np.zeros((nodes, 3)), np.zeros((nodes, 2)), np.zeros(nodes),
                        np.zeros(nodes), np.zeros(max(ysize, 1)), np.zeros(max(bandsize, 1)),
                        np.zeros(nodes), np.zeros((S, 5)), np.zeros((2, 3, nodes)))
        gpts, goff, gidx = free_point_groups(sec, kind)
        m3 = 3 * int(np.max(np.diff(goff), initial=1))
        # scratch of the free points' damping step: active sections, the group's dense
        # system and right-hand side, velocity changes; the groups (points, offsets,
        # (group, slot) of every point); the unit velocities and a zero one (rows 0-2, 3),
        # writable as the points' velocities are, so that the kernels they are passed to
        # compile once (docs/development.md#numba-compile-time)
        self.coupling = (np.zeros(S), np.zeros((m3, m3)), np.zeros(m3), np.zeros((P, 3)),
                         gpts, goff, gidx, np.vstack([np.eye(3), np.zeros((1, 3))]))


def free_point_groups(sec: NDArray[np.int64], kind: NDArray[np.int64]
                      ) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """The free points in groups joined through sections between free points (each group's
    damping step is one dense solve, ``_system_kernels._damping_phase``).

    Returns
    -------
    points, offsets, index
        The free points group by group, the groups' offsets into them (groups + 1), and of
        every point its (group, slot in the group), -1 for fixed and body points.
    """
    P = kind.shape[0]
    joined = DisjointSets(range(P))
    for a, b in sec[:, [_s.S_START, _s.S_END]]:
        if kind[a] == _s.FREE and kind[b] == _s.FREE:
            joined.union(int(a), int(b))
    groups: dict[int, list[int]] = {}
    for p in range(P):
        if kind[p] == _s.FREE:
            groups.setdefault(joined.find(p), []).append(p)
    index = np.full((P, 2), -1, dtype=np.int64)
    points, offsets = [], [0]
    for g, members in enumerate(groups.values()):
        for slot, p in enumerate(members):
            index[p] = (g, slot)
        points.extend(members)
        offsets.append(len(points))
    return (np.array(points, dtype=np.int64), np.array(offsets, dtype=np.int64), index)
