"""The dynamic lines of a coupled run taken together: each advanced once per body step, their
end forces evaluated in one kernel call per stage (docs/theory/floater.md#coupling-scheme).

A body step [t, t + dt] predicts one fairlead path for the step, sampled at t + dt / 2 and
t + dt. :meth:`DynamicLineBatch.advance` takes each line along it in one go and provides the
line's state at t + dt / 2 (its nodes' positions and velocities) for the Runge-Kutta stages 1
and 2; :meth:`DynamicLineBatch.end_forces` then gives any stage the lines' end forces in the
state it needs, with the stage's own fairlead velocities (``DynamicLine.end_forces_moving``'s
operations, ``_batch_kernels.dg_end_forces_batch``).

* An explicit line (an ``"auto"`` line whose window ends inside the step, an implicit line
  not in :attr:`DynamicLineBatch.one_interval`) runs over both samples, the same kernel steps
  in the same order as two :meth:`DynamicLine.solve_path` calls (to the last bit), and keeps
  its exact state at the middle sample.
* An implicit line runs over the step as ONE sample interval [t, t + dt] (its fairlead on
  the cubic Hermite curve between the step's ends; its step control may still cut the
  interval): a sample at t + dt / 2 would end an implicit step there, so every body step
  cost at least two implicit steps and a Jacobian per step size, where the accuracy asks
  for about one (DeepCwind LC34, docs/validation/performance.md). Its state at t + dt / 2
  is interpolated in time, node by node, from its positions and velocities at both ends
  (``_batch_kernels.hermite_middle``, cubic Hermite: :data:`MIDDLE_QUINTIC` says why not
  quintic); the stages 1 and 2 evaluate it with the fairlead at the predicted middle
  sample. It is interpolated even when the step control happened to cut the interval at its
  middle: the state the stages see does not then jump with the step level. The
  interpolated state narrows the coupling's stability range on the line's axial impedance
  Z (docs/theory/floater.md#coupling-scheme): the model problem of
  tests/simulation/test_coupling_stability.py damps a kick as the exact middle state does up to
  Z dt / M = 0.3, poorly at 0.6 and grows from 0.7, where the exact state is stable to
  2.785, and the moored buoy blows up at 0.48; the coupled run keeps its lines on the two
  samples beyond 0.1 (``simulation.coupled.ONE_INTERVAL_LIMIT``). The implicit lines of one
  discretisation (without the stick-spring friction's anchors) take their one interval in one
  kernel call (``_batch_kernels.dg_advance_implicit_batch``), their integrators' states stacked:
  a call from Python costs about what a line's implicit step does.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from floatmoor.mooring.dg import _implicit_kernels as _ik
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg._batch_kernels import (dg_advance_implicit_batch,
                                                 dg_end_forces_batch, hermite_middle)
from floatmoor.mooring.dg.line import DynamicLine

__all__ = ["DynamicLineBatch", "MIDDLE_QUINTIC"]

#: Interpolate an implicit line's middle state with the quintic Hermite curve (positions,
#: velocities and the state's accelerations at both ends) instead of the cubic one (positions
#: and velocities): off. Against the state the same steps reach at the middle (DeepCwind LC34,
#: 8 elements of order 3, 200 s, the three lines each step) the cubic's middle fairlead force
#: is off by 1.2 kN at most (rms 0.03 % of the tension), the quintic's by 3.5 kN (rms 0.12 %);
#: on the moored buoy's chains 0.17 N against 0.55 N (of 4 N). The state's acceleration
#: carries the axial waves the generalised-alpha step does not resolve (and damps): it is not
#: the slope of the velocities the steps produce, which the cubic curve follows.
MIDDLE_QUINTIC = False


#: the batch kernel skips the end forces of the interval's first sample (the state the last
#: advance ended in: the stages take theirs from ``end_forces``)
_NO_FIRST_RECORD = np.bool_(False)
#: the implicit integrator's arrays that carry its state from step to step: stacked per
#: discretisation, for the batch kernel (``_batch_kernels.dg_advance_implicit_batch``)
_STACKED = ("acc", "An", "cs", "ip", "band", "flags")


class _Discretisation:
    """The lines of one element count and order: their states stacked (the lines' own ``r``
    and ``v`` are views of ``r`` and ``v``), the states at the step's middle sample, and the
    kernel's inputs and outputs."""

    def __init__(self, lines: Sequence[DynamicLine], members: list[int]) -> None:
        first = lines[members[0]]
        m = len(members)
        shape = (m,) + first.r.shape
        self.members = members
        #: the batch's rows of these lines: a slice when they are consecutive
        self.rows: slice | NDArray[np.int64] = (
            slice(members[0], members[-1] + 1) if members == list(range(members[0],
                                                                        members[-1] + 1))
            else np.array(members))
        self.r, self.v = np.zeros(shape), np.zeros(shape)
        self.r_mid, self.v_mid = np.zeros(shape), np.zeros(shape)
        #: an implicit line's state and acceleration at the start of the step
        self.r_start, self.v_start, self.a_start = (np.zeros(shape) for _ in range(3))
        self.anchors = np.array([lines[j].anchor for j in members], dtype=float).reshape(m, 3)
        self.anchors.flags.writeable = False  # as each line's anchor: one kernel signature
        self.prm = np.array([lines[j].prm for j in members], dtype=float)
        self.element = first.element
        K, Np = first.r.shape[0], first.r.shape[1]
        self.q, self.qt, self.N = (np.zeros((K, Np, 3)) for _ in range(3))
        self.Nstar, self.faces = np.zeros((K + 1, 3)), np.zeros((K + 1, 3))
        self.slack = np.zeros(K)
        self.fair_now, self.fair_mid = np.zeros((m, 3)), np.zeros((m, 3))
        self.fvel = np.zeros((m, 3))
        self.ff, self.af, self.laid = np.zeros((m, 3)), np.zeros((m, 3)), np.zeros(m)
        #: each line's one sample interval [t, t + dt] of an implicit advance: its kernel
        #: arguments (time, path, velocity, then the outputs: forces, laid length, steps)
        self.ends = (np.zeros((m, 2)), np.zeros((m, 2, 3)), np.zeros((m, 2, 3)),
                     np.zeros((m, 2, 3)), np.zeros((m, 2, 3)), np.zeros((m, 2)),
                     np.zeros((m, 2)))
        #: which lines the batch kernel advances (implicit, no stick-spring friction anchors:
        #: :meth:`bind`), and which of them it advances this step
        self.batchable = np.zeros(m, dtype=bool)
        self.active = np.zeros(m, dtype=bool)
        #: the implicit integrators' state, stacked (each integrator's arrays are views)
        n = 3 * K * Np
        self.acc, self.An = np.zeros(shape), np.zeros(shape)
        self.cs, self.ip = np.zeros((m, _ik.CS_N)), np.zeros((m, _ik.IP_N))
        self.band, self.flags = np.zeros((m, n, 9 * Np + 2)), np.zeros((m, K, Np))
        self.iprm = np.zeros_like(self.prm)
        #: one line's work arrays of the implicit kernel, reused line after line
        self.fpos, self.fvel_one = np.zeros(3), np.zeros(3)
        self.tmp, self.where = np.zeros(max(Np, 6)), np.zeros(2, dtype=np.int64)
        self.fields, self.blocks = np.zeros((7, K, Np, 3)), np.zeros((2, K, Np, 3, 3))
        self.x = np.zeros(n)
        self.no_shape_r, self.no_shape_t = np.zeros((1, 1, 3)), np.zeros((1, 1))
        self.failure = np.zeros(3, dtype=np.int64)
        self.bind(lines)

    def bind(self, lines: Sequence[DynamicLine]) -> None:
        """Make the lines' states views of the stacked arrays (values kept) and take their
        fairleads."""
        for row, j in enumerate(self.members):
            line = lines[j]
            if line.r.base is not self.r:
                self.r[row] = line.r
                line.r = self.r[row]
            if line.v.base is not self.v:
                self.v[row] = line.v
                line.v = self.v[row]
            self.fair_now[row] = line.fairlead
            integ = line.implicit
            self.batchable[row] = integ is not None and line.friction_anchors_in_use() is None
            if not self.batchable[row]:
                continue
            for name in _STACKED:
                stacked, own = getattr(self, name), getattr(integ, name)
                if own.base is not stacked:
                    stacked[row] = own
                    setattr(integ, name, stacked[row])
            if line.implicit_prm.base is not self.iprm:
                self.iprm[row] = line.implicit_prm
                line.implicit_prm = self.iprm[row]


class DynamicLineBatch:
    """The dynamic lines of a coupled run, advanced and evaluated together.

    Parameters
    ----------
    lines
        The lines (their states become views of the batch's arrays: values unchanged).
    """

    def __init__(self, lines: Sequence[DynamicLine]) -> None:
        self.lines = list(lines)
        n = len(self.lines)
        #: each line's path of a step: its time and fairlead now, then the two samples
        self._time = np.zeros((n, 3))
        self._path = np.zeros((n, 3, 3))
        self._velocity = np.zeros((n, 3, 3))
        self._ff, self._af = np.zeros((n, 3, 3)), np.zeros((n, 3, 3))
        self._laid, self._steps = np.zeros((n, 3)), np.zeros((n, 3))
        #: laid length of each line at the end of its last advance [m]
        self.laid_length = np.zeros(n)
        #: whether the implicit lines of one discretisation are advanced in one kernel call
        #: (``_batch_kernels.dg_advance_implicit_batch``); False: one call per line
        #: (:meth:`_advance_implicit`), the same steps to the last bit
        self.batch_kernel = True
        #: the time before which every line takes the batch kernel's step as the last step
        #: did (:meth:`_advance_all`); -inf: the next step looks at each line
        self._plain_until = -math.inf
        #: which lines may step implicitly over the body step as one interval (the coupling's
        #: owner clears those whose body answers them too fast: module docstring)
        self.one_interval = np.ones(n, dtype=bool)
        shapes: dict[tuple[int, ...], list[int]] = {}
        for j, line in enumerate(self.lines):
            shapes.setdefault(line.r.shape, []).append(j)
        self._groups = [_Discretisation(self.lines, members) for members in shapes.values()]
        #: the one group, when it holds every line in order (:meth:`end_force_arguments`,
        #: :meth:`_advance_all`)
        self._whole = (self._groups[0] if len(self._groups) == 1
                       and self._groups[0].members == list(range(n)) else None)
        #: where each line sits: its group and row there
        self._where = [(g, row) for g in self._groups for row in range(len(g.members))]
        self._where.sort(key=lambda gr: gr[0].members[gr[1]])
        #: each line's kernel arguments of its two calls a step (views)
        arrays = (self._time, self._path, self._velocity, self._ff, self._af, self._laid,
                  self._steps)
        self._calls = [tuple(tuple(a[j, first:first + 2] for a in arrays) for first in (0, 1))
                       for j in range(n)]
        #: an implicit line's one sample interval [t, t + dt]: its kernel arguments (views of
        #: its discretisation's)
        self._end_calls = [tuple(a[row] for a in g.ends) for g, row in self._where]

    def sync(self) -> None:
        """Take the lines' states and fairleads again (after they were restored in place or
        replaced)."""
        self._plain_until = -math.inf
        for g in self._groups:
            g.bind(self.lines)

    def advance(self, t_mid: float, t_end: float, pos_mid: NDArray[np.float64],
                vel_mid: NDArray[np.float64], pos_end: NDArray[np.float64],
                vel_end: NDArray[np.float64]) -> None:
        """Advance every line from its time to ``t_end``, its fairlead on the cubic Hermite
        curve through its current position and velocity and the samples ``pos_mid``,
        ``vel_mid`` (an explicit line's; an implicit line's curve skips them) and ``pos_end``,
        ``vel_end`` ((n, 3) each), keeping its state at ``t_mid`` (an implicit line's
        interpolated: module docstring) for :meth:`end_forces` (``mid=True``).

        Raises
        ------
        SolverError
            As :meth:`DynamicLine.solve_path` (the line, time and quantity).
        """
        if t_end < self._plain_until:  # every line as the last step: one kernel call
            self._advance_all(t_end, pos_mid, pos_end, vel_end)
            return
        T, P, U = self._time, self._path, self._velocity
        T[:, 1], T[:, 2] = t_mid, t_end
        P[:, 1], P[:, 2] = pos_mid, pos_end
        U[:, 1], U[:, 2] = vel_mid, vel_end
        ff, af, lb, st = self._ff, self._af, self._laid, self._steps
        for g in self._groups:
            te, pe, ue = g.ends[:3]
            te[:, 1] = t_end
            pe[:, 1] = pos_end[g.rows]
            ue[:, 1] = vel_end[g.rows]
        for j, line in enumerate(self.lines):
            g, row = self._where[j]
            implicit = line.plain_steps_until(t_end)
            if implicit and self.one_interval[j] and g.batchable[row] and self.batch_kernel:
                g.active[row] = True  # (advanced below, with its discretisation's others)
                te, pe, ue = g.ends[:3]
                te[row, 0] = line.time
                pe[row, 0] = line.fairlead
                ue[row, 0] = line.fairlead_velocity
                continue
            if implicit is None:  # an "auto" window may end: solve_path decides there
                line.solve_path(T[j, 1:2], P[j, 1:2], U[j, 1:2], ff[j, 1:2], af[j, 1:2],
                                lb[j, 1:2], st[j, 1:2])
                g.r_mid[row] = line.r
                g.v_mid[row] = line.v
                line.solve_path(T[j, 2:3], P[j, 2:3], U[j, 2:3], ff[j, 2:3], af[j, 2:3],
                                lb[j, 2:3], st[j, 2:3])
            elif implicit and self.one_interval[j]:  # the middle state interpolated
                self._advance_implicit(j, line, g, row, t_end, pos_end[j], vel_end[j])
                continue
            else:
                T[j, 0] = line.time
                P[j, 0] = line.fairlead
                U[j, 0] = line.fairlead_velocity
                for first, args in enumerate(self._calls[j]):  # to the middle, to the end
                    status, index = line.run_kernel(implicit, *args)
                    if status != _k.DG_OK:
                        line.failed_index = 0
                        raise line.unstable(status, float(T[j, first + index]))
                    if first == 0:
                        g.r_mid[row] = line.r
                        g.v_mid[row] = line.v
                line.failed_index = -1
                line.time = float(T[j, 2])
                line.fairlead[:] = P[j, 2]
                line.fairlead_velocity[:] = U[j, 2]
            g.fair_mid[row] = P[j, 1]
            g.fair_now[row] = P[j, 2]
            self.laid_length[j] = lb[j, 2]
        whole = self._whole
        batched = whole is not None and bool(whole.active.all())
        for g in self._groups:
            if g.active.any():
                self._advance_batched(g, t_end)
        # the next steps may take every line in one call while they stay implicit and no
        # "auto" decision is due (lines in the batch kernel's interval ends, as they are now)
        self._plain_until = (min(line.plain_until() for line in self.lines) if batched
                             else -math.inf)

    def _advance_all(self, t_end: float, pos_mid: NDArray[np.float64],
                     pos_end: NDArray[np.float64], vel_end: NDArray[np.float64]) -> None:
        """:meth:`advance` when the last step took every line (one discretisation, in order)
        through the batch kernel and none may leave it before ``t_end``: the intervals start
        where the last ones ended, and the bookkeeping is done on whole arrays."""
        g = self._whole
        te, pe, ue, fe, ae, le, se = g.ends
        te[:, 0], pe[:, 0], ue[:, 0] = te[:, 1], pe[:, 1], ue[:, 1]
        te[:, 1], pe[:, 1], ue[:, 1] = t_end, pos_end, vel_end
        g.active[:] = True
        self._run_batch_kernel(g)
        if g.failure[0] >= 0:
            self._plain_until = -math.inf
            self._commit_batched(g, t_end)  # (raises)
        t_end = float(t_end)
        for j, line in enumerate(self.lines):
            line.time = t_end
            line.fairlead[:] = pos_end[j]
            line.fairlead_velocity[:] = vel_end[j]
        g.fair_mid[:] = pos_mid
        g.fair_now[:] = pos_end
        self.laid_length[:] = le[:, 1]
        g.active[:] = False

    def _advance_batched(self, g: _Discretisation, t_end: float) -> None:
        """The lines of ``g`` marked active, stepping implicitly from their times to
        ``t_end`` as one sample interval, in one kernel call (as :meth:`_advance_implicit`
        line by line: the same steps to the last bit)."""
        self._run_batch_kernel(g)
        self._commit_batched(g, t_end)

    @staticmethod
    def _run_batch_kernel(g: _Discretisation) -> None:
        """``_batch_kernels.dg_advance_implicit_batch`` on the lines of ``g`` marked active,
        over their intervals in ``g.ends`` (the first failure in ``g.failure``)."""
        el = g.element
        te, pe, ue, fe, ae, le, se = g.ends
        dg_advance_implicit_batch(
            g.active, te, pe, ue, g.r, g.v, g.acc, g.An, g.anchors, g.iprm,
            el.differentiation, el.lift, el.filter, el.weights, g.ip, g.cs, fe, ae, le, se, 0,
            g.no_shape_r, g.no_shape_t, g.q, g.qt, g.N, g.Nstar, g.faces, g.slack, g.fpos,
            g.fvel_one, g.tmp, g.where, g.fields, g.blocks, g.band, g.x, g.flags, g.r_start,
            g.v_start, g.a_start, g.r_mid, g.v_mid, MIDDLE_QUINTIC, _NO_FIRST_RECORD,
            g.failure)

    def _commit_batched(self, g: _Discretisation, t_end: float) -> None:
        """After :meth:`_run_batch_kernel`: each active line's time, fairlead and laid length,
        or the error of the line that failed (the lines before it committed)."""
        failed = int(g.failure[0])
        for row, j in enumerate(g.members):
            if not g.active[row]:
                continue
            line = self.lines[j]
            if row == failed:
                g.active[:] = False
                line.failed_index = 0
                raise line.unstable(int(g.failure[1]), float(g.ends[0][row, g.failure[2]]),
                                    g.where)
            self._commit(j, line, g, row, t_end)
        g.active[:] = False

    def _commit(self, j: int, line: DynamicLine, g: _Discretisation, row: int,
                t_end: float) -> None:
        """Line ``j`` (row ``row`` of ``g``) advanced over its interval in ``g.ends`` to
        ``t_end``: its time, fairlead, middle and end samples and laid length."""
        pe, ue, le = g.ends[1], g.ends[2], g.ends[5]
        line.failed_index = -1
        line.time = float(t_end)
        line.fairlead[:] = pe[row, 1]
        line.fairlead_velocity[:] = ue[row, 1]
        g.fair_mid[row] = self._path[j, 1]
        g.fair_now[row] = pe[row, 1]
        self.laid_length[j] = le[row, 1]

    def _advance_implicit(self, j: int, line: DynamicLine, g: _Discretisation, row: int,
                          t_end: float, pos_end: NDArray[np.float64],
                          vel_end: NDArray[np.float64]) -> None:
        """Line ``j`` (row ``row`` of ``g``) stepping implicitly: from its time to ``t_end``
        as one sample interval, its state at the middle interpolated (module docstring)."""
        T, P, U = g.ends[:3]
        integ = line.implicit
        t0 = line.time
        T[row, 0], T[row, 1] = t0, t_end
        P[row, 0], P[row, 1] = line.fairlead, pos_end
        U[row, 0], U[row, 1] = line.fairlead_velocity, vel_end
        g.r_start[row] = line.r
        g.v_start[row] = line.v
        # the state's acceleration at the start: kept by the integrator between calls (the
        # first call computes it: the cubic curve then)
        quintic = MIDDLE_QUINTIC and integ.cs[_ik.CS_ACC_VALID] != 0.0
        if quintic:
            g.a_start[row] = integ.An
        status, index = line.run_kernel(True, *self._end_calls[j])
        if status != _k.DG_OK:
            line.failed_index = 0
            raise line.unstable(status, float(T[row, index]))
        hermite_middle(g.r_start[row], g.v_start[row], g.a_start[row], line.r, line.v,
                       integ.An, t_end - t0, quintic, g.r_mid[row], g.v_mid[row])
        self._commit(j, line, g, row, t_end)

    def end_force_arguments(self, mid: bool) -> tuple[NDArray[np.float64], ...] | None:
        """The inputs of ``_batch_kernels.dg_end_forces_batch`` for every line at once but the
        fairlead velocities and the outputs (r, v, anchors, fairleads, parameters, the
        element's matrices and weights, then the laid lengths' output),
        in the current state (``mid`` False) or the middle sample's (True), when the lines
        are one discretisation in order (None otherwise); arrays the batch updates in
        place."""
        g = self._whole
        if g is None:
            return None
        el = g.element
        return (g.r_mid if mid else g.r, g.v_mid if mid else g.v, g.anchors,
                g.fair_mid if mid else g.fair_now, g.prm, el.differentiation, el.lift,
                el.weights, g.laid)

    def end_forces(self, fairlead_velocity: NDArray[np.float64], mid: bool,
                   fairlead_force: NDArray[np.float64], anchor_force: NDArray[np.float64]
                   ) -> None:
        """Each line's end forces [N] in its current state (``mid`` False) or the state its
        last :meth:`advance` kept at the middle sample (``mid`` True), its fairlead moving at
        ``fairlead_velocity`` (n, 3): ``DynamicLine.end_forces_moving``'s values, into
        ``fairlead_force`` and ``anchor_force`` (n, 3)."""
        for g in self._groups:
            g.fvel[:] = fairlead_velocity[g.rows]
            el = g.element
            dg_end_forces_batch(g.r_mid if mid else g.r, g.v_mid if mid else g.v, g.anchors,
                                g.fair_mid if mid else g.fair_now, g.fvel, g.prm,
                                el.differentiation, el.lift, el.weights, g.ff, g.af, g.laid)
            fairlead_force[g.rows] = g.ff
            anchor_force[g.rows] = g.af
