"""Coupled runs: a floating body integrated with the Cummins equation, sub-stepped with its
mooring lines (docs/theory/floater.md#coupling-scheme).

Coupling scheme, per body step [t_n, t_n + dt] (classical RK4 for the body):

* from the stage-0 acceleration a_n the body's motion over the step is predicted to second
  order, x(tau) = x_n + v_n tau + a_n tau^2 / 2, and each line with memory (dynamic,
  quasi-dynamic) is advanced along the fairlead path that prediction gives, sampled at
  t_n + dt / 2 and t_n + dt (a dynamic line at its own steps, the fairlead on the cubic Hermite
  curve between the samples): a dynamic line once per step, before stage 1, providing its
  state at t_n + dt / 2 for stages 1 and 2 (:mod:`floatmoor.mooring.dg.batch`: an explicit
  line over both samples, the same steps as two advances, the same bits; an implicit line
  over [t_n, t_n + dt] as one interval, its middle state interpolated in time); a
  quasi-dynamic line and a group to t_n + dt / 2 before stage 1, on to t_n + dt before
  stage 3;
* every stage takes the lines' forces in the state they have reached (t_n for stage 0,
  t_n + dt / 2 for stages 1 and 2, t_n + dt for stage 3), evaluated with the stage's own
  fairlead velocity (``PathStepper.end_forces_moving``): the dynamic line's end flux
  answers the fairlead velocity at once through its axial impedance Z = m c, so each stage
  sees the line's instantaneous (dashpot) response to its own motion, and only the line's
  memory lags;
* quasi-static lines have no memory: each stage solves them at the stage's own position.

The lines thus lag the body's corrected motion by the predictor's error, O(dt^3) per step;
each step's path starts from where the line's fairlead is, so the mismatch does not
accumulate. The scheme is explicit. Its stability limit against a line's axial impedance
(the hard case: a heavy, stiff line on a light body) is that of RK4 on the dashpot:
Z dt / M <= 2.79 (M the body's mass and added mass along the line); taking the lines' forces
at the predicted fairlead velocity instead (the scheme before) made it unstable from
Z dt / M ~ 1 (tests/simulation/test_coupling_stability.py).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from floatmoor.body.cummins import CumminsBody
from floatmoor.body._kinematics_kernels import points_state_into
from floatmoor.body.kinematics import generalised_force, points_state
from floatmoor.case.schema import Case, Environment, Line, Seabed
from floatmoor.errors import CaseError
from floatmoor.mooring.catenary import solve_catenary
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg.batch import DynamicLineBatch
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.mooring.quasidynamic import QuasiDynamicLine
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.mooring.stepping import PathStepper
from floatmoor.simulation._coupling_kernels import batched_mooring_force
from floatmoor.simulation.groups import GroupSamples, SystemGroup, system_groups

__all__ = ["MooredBody", "equilibrium", "line_force_quasi_static"]

#: Relative body displacement step of the finite-difference mooring stiffness in the
#: equilibrium solve [m or rad].
_FD_STEP = 1e-4
#: Equilibrium: residual force below this fraction of the largest static force.
EQUILIBRIUM_RTOL = 1e-9
_MAX_NEWTON = 50
#: Largest Z dt / M (:meth:`MooredBody.dashpot_number`) at which implicit dynamic lines step
#: over the body step as one interval, their middle states interpolated
#: (floatmoor.mooring.dg.batch): on tests/simulation/test_coupling_stability.py's model problem that
#: damps a kick as the exact middle state does up to 0.3 (after 20 steps 1.3 % of it left,
#: against 1.1 %; at 0.1 11.0 % against 11.1 %), at 0.5-0.6 it leaves 28-33 % (5 %), from 0.7
#: it grows; the buoy on its three chains (implicit), at 0.48, blows up within 0.1 s with one
#: interval. 0.1: a factor 5 below that. Beyond, the lines keep the two samples (stable to
#: 2.785). DeepCwind LC34: 0.003.
ONE_INTERVAL_LIMIT = 0.1


def line_force_quasi_static(line: Line, environment: Environment, seabed: Seabed,
                            fairlead: NDArray[np.float64]) -> NDArray[np.float64]:
    """Force the quasi-static catenary of ``line`` exerts on its fairlead at ``fairlead``."""
    lt = line.line_type
    friction = seabed.friction_coefficient if line.quasi_static.seabed_friction else 0.0
    sol = solve_catenary(line.anchor, fairlead, line.length, lt.axial_stiffness,
                         lt.weight_in_water(environment), friction,
                         seabed_z=environment.seabed_z, tol=line.quasi_static.tolerance,
                         max_iter=line.quasi_static.max_iterations)
    return np.asarray(sol.fairlead_force, dtype=float)


def equilibrium(body: CumminsBody, lines: Sequence[Line], arms: NDArray[np.float64],
                centre: NDArray[np.float64], environment: Environment, seabed: Seabed,
                mean_force: NDArray[np.float64] | None = None,
                system_force: Callable[[NDArray[np.float64]], NDArray[np.float64]] | None = None
                ) -> NDArray[np.float64]:
    """The static equilibrium position x (6,) of the body on its lines (quasi-static
    catenaries): F_0 - C x + F_lines(x) + mean_force = 0, by Newton with a finite-difference
    mooring stiffness; DOFs without stiffness stay at zero (least-squares steps). ``lines``
    are the independent lines (``arms`` their fairleads'); ``system_force(x)`` is the 6-DOF
    static force of the lines solved as systems, if any."""
    mean = np.zeros(6) if mean_force is None else np.asarray(mean_force, float)

    def residual(x: NDArray[np.float64]) -> NDArray[np.float64]:
        pos, _ = points_state(x, np.zeros(6), arms, centre)
        forces = np.array([line_force_quasi_static(ln, environment, seabed, p)
                           for ln, p in zip(lines, pos)]).reshape(-1, 3)
        moor = generalised_force(x, forces, arms) if len(lines) else np.zeros(6)
        if system_force is not None:
            moor = moor + system_force(x)
        return body.static_force - body.stiffness @ x + moor + mean

    x = np.zeros(6)
    r = residual(x)
    if not (np.all(np.isfinite(r)) and np.all(np.isfinite(body.stiffness))):
        raise CaseError("", "floater", "a floater whose static forces and stiffness are finite "
                        "(weight, buoyancy, their moments and the lines' pull)",
                        f"a static force {np.array2string(r, precision=3)} N and N m at rest")
    scale = max(float(np.abs(body.static_force).max()), float(np.abs(r).max()), 1.0)
    for _ in range(_MAX_NEWTON):
        if np.abs(r).max() <= EQUILIBRIUM_RTOL * scale:
            return x
        J = np.empty((6, 6))
        for j in range(6):
            e = np.zeros(6)
            e[j] = _FD_STEP
            J[:, j] = (residual(x + e) - residual(x - e)) / (2.0 * _FD_STEP)
        if not np.all(np.isfinite(J)):  # (lstsq would raise LinAlgError: SVD not converged)
            raise CaseError("", "floater", "a floater with a static equilibrium on its lines",
                            f"a mooring stiffness that is not finite at x = "
                            f"{np.array2string(x, precision=3)}")
        dx = np.linalg.lstsq(J, -r, rcond=1e-10)[0]
        step = 1.0
        while True:
            trial = residual(x + step * dx)
            if np.abs(trial).max() < np.abs(r).max() or step < 1e-3:
                break
            step *= 0.5
        x = x + step * dx
        r = trial
    raise RuntimeError(f"no static equilibrium: residual {np.abs(r).max():.3g} N after "
                       f"{_MAX_NEWTON} Newton steps")


#: The line models by the case's ``model`` key.
_MODELS = {"quasi-static": QuasiStaticLine.from_case,
           "quasi-dynamic": QuasiDynamicLine.from_case, "dynamic": DynamicLine.from_case}


class MooredBody:
    """A Cummins body with its lines, advanced one body step at a time.

    Parameters
    ----------
    body
        The body (its state set by :meth:`start`).
    lines, environment, seabed
        The case's lines (fairleads: body-fixed points, at rest) and surroundings.
    centre
        The body's reference point at rest [m].
    external
        f(t, x, v) -> 6-DOF force of everything but the lines (excitation, drag, wind).
    case
        The case, when its mooring has lines solved as systems (free points, sections:
        :mod:`floatmoor.simulation.groups`); their body points follow the body as the
        fairleads do.
    """

    def __init__(self, body: CumminsBody, lines: Sequence[Line], environment: Environment,
                 seabed: Seabed, centre: NDArray[np.float64],
                 external: Callable[[float, NDArray[np.float64], NDArray[np.float64]],
                                    NDArray[np.float64]] | None = None,
                 case: Case | None = None) -> None:
        self.body = body
        self.case = case
        self.lines = list(lines)
        #: which lines are solved on their own (the others: by the groups)
        self.independent = [case is None or case.is_independent(ln) for ln in self.lines]
        self._solo = all(self.independent)
        #: the system groups (built by :meth:`start`) and their body points' arms
        self.groups: list[SystemGroup] = []
        self.group_arms: list[NDArray[np.float64]] = []
        self.environment = environment
        self.seabed = seabed
        self.centre = np.asarray(centre, dtype=float)
        self.arms = np.array([np.subtract(ln.fairlead, self.centre) for ln in self.lines],
                             dtype=float).reshape(-1, 3)
        self.external = external if external is not None else (lambda t, x, v: np.zeros(6))
        #: the model of each independent line (None: a line of a group)
        self.models: list[PathStepper | None] = []
        #: the dynamic lines (built by :meth:`start`), advanced and evaluated together, and
        #: their indices among the lines
        self._batch: DynamicLineBatch | None = None
        self._batch_index = np.zeros(0, dtype=np.int64)
        #: whether the stages take the dynamic lines' states at the step's middle sample
        self._at_mid = False
        #: the lines each stage solves (quasi-static) or evaluates one by one (quasi-dynamic)
        self._solved: list[int] = []
        self._evaluated: list[int] = []
        #: the fairleads' positions and velocities of a stage, and of the dynamic lines' two
        #: samples of a step (work arrays)
        n = len(self.lines)
        self._pos, self._vel = np.zeros((n, 3)), np.zeros((n, 3))
        self._stage_ff, self._stage_af = np.zeros((n, 3)), np.zeros((n, 3))
        #: whether every line is a dynamic line of the batch, in order, of one discretisation
        #: (:meth:`_batched_force`), and the batch's end-force inputs at the step's end and
        #: middle
        self._all_batched = False
        self._stage_arguments: tuple[tuple, tuple] = ((), ())
        self._samples = tuple(np.zeros((0, 3)) for _ in range(4))
        self._batch_arms = np.zeros((0, 3))
        #: laid length of each line at its last evaluation [m]
        self.laid_length = np.zeros(len(self.lines))
        #: one-sample outputs of a memory line's step (time, fairlead force, anchor force, laid
        #: length, steps), reused by every line at every step
        self._sample = (np.zeros(1), np.zeros((1, 3)), np.zeros((1, 3)), np.zeros(1),
                        np.zeros(1))

    # -- set-up ----------------------------------------------------------------------------
    def start(self, position: NDArray[np.float64], time: float = 0.0) -> None:
        """Body at rest at ``position`` (6,), each line at rest in the static shape of its
        fairlead there (a dynamic line settled)."""
        self.body.start(time, position)
        fairleads, _ = points_state(self.body.x, np.zeros(6), self.arms, self.centre)
        self.models = []
        if not self._solo:
            body_points = {p.name: np.subtract(p.position, self.centre)
                           for p in self.case.points if p.kind == "body"}
            names = list(body_points)
            moved_points, _ = points_state(self.body.x, np.zeros(6),
                                           np.array([body_points[n] for n in names]),
                                           self.centre)
            self.groups = system_groups(self.case, dict(zip(names, moved_points)))
            self.group_arms = [np.array([body_points[self.case.points[k].name]
                                         for k in g.body_points]).reshape(-1, 3)
                               for g in self.groups]
            for g in self.groups:
                if g.solver.has_memory:
                    g.solver.time = float(time)
        for ln, p, solo in zip(self.lines, fairleads, self.independent):
            if not solo:
                self.models.append(None)
                continue
            moved = replace(ln, fairlead=tuple(float(c) for c in p))
            model = _MODELS[ln.model](moved, self.environment, self.seabed)
            if model.has_memory:
                model.time = float(time)
            self.models.append(model)
        dynamic = [i for i, m in enumerate(self.models) if m is not None and m.batched]
        self._batch_index = np.array(dynamic, dtype=np.int64)
        self._batch = DynamicLineBatch([self.models[i] for i in dynamic]) if dynamic else None
        if self._batch is not None:
            self._batch.one_interval[:] = self.dashpot_number() <= ONE_INTERVAL_LIMIT
        self._at_mid = False
        self._solved = [i for i, m in enumerate(self.models)
                        if m is not None and not m.has_memory]
        self._evaluated = [i for i, m in enumerate(self.models)
                           if m is not None and m.has_memory and not m.batched]
        self._batch_arms = np.ascontiguousarray(self.arms[self._batch_index])
        self._samples = tuple(np.zeros((len(dynamic), 3)) for _ in range(4))
        self._all_batched = (self._solo and dynamic == list(range(len(self.lines)))
                             and self._batch.end_force_arguments(False) is not None)
        if self._all_batched:
            self._stage_arguments = (self._batch.end_force_arguments(False),
                                     self._batch.end_force_arguments(True))

    def dashpot_number(self) -> float:
        """Z dt / M of the body on its dynamic lines in their current state: the body step
        times the largest eigenvalue of M^-1 C, C = sum J^T e Z e^T J over the lines (Z = m c
        the line's axial impedance [N s/m], e its end tangent, along which the dashpot acts, J
        the fairlead's velocity from the body's at rest), M with the infinite-frequency added
        mass. The lines act together: three chains on one buoy are three dashpots in
        parallel."""
        damping = np.zeros((6, 6))
        for i in self._batch_index:
            line = self.models[i]
            impedance = float(line.prm[_k.P_M] * line.prm[_k.P_C])
            tangent = line.r[-1, -1] - line.r[-1, -2]
            e = tangent / np.linalg.norm(tangent)
            a = self.arms[i]
            skew = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
            je = np.hstack((np.eye(3), -skew)).T @ e
            damping += impedance * np.outer(je, je)
        rates = np.linalg.eigvals(self.body.inverse_mass @ damping).real
        return self.body.dt * float(rates.max())

    # -- state ---------------------------------------------------------------------------
    def state_arrays(self) -> dict[str, NDArray]:
        """The whole state of body and lines as named arrays (copies): ``body/...``,
        ``line{i}/...`` (each model's ``state_arrays``) and ``laid_length``; with the case it
        is all a checkpoint needs (the models' operators are rebuilt by :meth:`start`)."""
        out = {f"body/{k}": np.array(v) for k, v in self.body.state_arrays().items()}
        for i, model in enumerate(self.models):
            if model is None:  # a line of a group
                continue
            out.update({f"line{i}/{k}": np.array(v) for k, v in model.state_arrays().items()})
        for g, group in enumerate(self.groups):
            out.update({f"group{g}/{k}": np.array(v) for k, v in group.state_arrays().items()})
        out["laid_length"] = self.laid_length.copy()
        return out

    def set_state_arrays(self, arrays: dict[str, NDArray]) -> None:
        """Restore a state of :meth:`state_arrays` into a body and lines built by
        :meth:`start` as for the state's run (keys and shapes checked by the caller)."""

        def part(prefix: str) -> dict[str, NDArray]:
            return {k[len(prefix):]: v for k, v in arrays.items() if k.startswith(prefix)}

        self.body.set_state_arrays(part("body/"))
        for i, model in enumerate(self.models):
            if model is not None:
                model.set_state_arrays(part(f"line{i}/"))
        for g, group in enumerate(self.groups):
            group.set_state_arrays(part(f"group{g}/"))
        self.laid_length[:] = arrays["laid_length"]
        if self._batch is not None:
            self._batch.sync()

    # -- line shapes -----------------------------------------------------------------------
    def shape_arc_lengths(self) -> list[NDArray[np.float64]]:
        """Arc lengths of each line's recorded shape [m] (each model's ``arc_length``, as in
        forced-motion runs)."""
        arcs = {i: g.arc_lengths[i] for g in self.groups for i in g.lines}
        return [np.asarray(arcs[i] if i in arcs else model.arc_length, dtype=float)
                for i, model in enumerate(self.models)]

    def line_shapes(self, fairleads: NDArray[np.float64]
                    ) -> list[tuple[NDArray[np.float64], NDArray[np.float64]]]:
        """(positions (n, 3) [m], effective tensions (n,) [N]) of every line now: the memory
        models' states, the quasi-static catenaries at the fairleads (n_lines, 3)
        (:meth:`PathStepper.current_shape`), the groups' lines from their groups."""
        out = []
        owner = {i: g for g in self.groups for i in g.lines}
        for i, model in enumerate(self.models):
            if i in owner:
                out.append(owner[i].line_shape(self.case, i))
            else:
                out.append(model.current_shape(fairleads[i]))
        return out

    # -- line forces -----------------------------------------------------------------------
    def _quasi_static(self, i: int, p: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
        ff, af, lb = np.zeros((1, 3)), np.zeros((1, 3)), np.zeros(1)
        self.models[i].solve_path(np.zeros(1), p[None, :], np.zeros((1, 3)), ff, af, lb,
                                  np.zeros(1))
        self.laid_length[i] = lb[0]
        return ff[0], af[0]

    def line_forces(self, x: NDArray[np.float64], v: NDArray[np.float64] | None = None
                    ) -> tuple[NDArray, NDArray]:
        """Fairlead and anchor forces (n, 3) of the lines now, the body at ``x`` moving at
        ``v`` (default: the memory lines' own fairlead velocities): the memory lines' current
        states with their fairleads moving with the body (``end_forces_moving``), the
        quasi-static ones solved at the position."""
        pos, vel = self._pos, self._vel
        points_state_into(np.ascontiguousarray(x, dtype=float),
                          np.zeros(6) if v is None else np.ascontiguousarray(v, dtype=float),
                          self.arms, self.centre, pos, vel)
        ff = np.zeros((len(self.lines), 3))
        af = np.zeros((len(self.lines), 3))
        for i in self._solved:  # (the lines of groups: recorded from them, group_samples)
            ff[i], af[i] = self._quasi_static(i, pos[i])
        if v is None:
            for i in (*self._evaluated, *self._batch_index):
                ff[i], af[i] = self.models[i].end_forces()
            return ff, af
        for i in self._evaluated:
            ff[i], af[i] = self.models[i].end_forces_moving(vel[i])
        if self._batch is not None:  # the dynamic lines' end_forces_moving, in one call
            rows = self._batch_index
            fb, ab = np.empty((rows.size, 3)), np.empty((rows.size, 3))
            self._batch.end_forces(vel[rows], self._at_mid, fb, ab)
            ff[rows], af[rows] = fb, ab
        return ff, af

    def group_samples(self, x: NDArray[np.float64], v: NDArray[np.float64]
                      ) -> list["GroupSamples"]:
        """Each group now (one sample), its body points where the body state (x, v) puts
        them (:meth:`SystemGroup.current`)."""
        out = []
        for group, arms in zip(self.groups, self.group_arms):
            pos, vel = points_state(x, v, arms, self.centre)
            out.append(group.current(pos, vel))
        return out

    def mooring_force(self, x: NDArray[np.float64], v: NDArray[np.float64]
                      ) -> NDArray[np.float64]:
        """The 6-DOF force of every line on the body at (x, v): the independent lines' at
        their fairleads, the groups' at their body points."""
        if self._all_batched:  # every line dynamic: no per-line work, no allocation
            return self._batched_force(x, v)
        ff, _ = self.line_forces(x, v)
        if self._solo:
            return generalised_force(x, ff, self.arms)
        solo = np.array(self.independent, dtype=bool)
        f = generalised_force(x, ff[solo], self.arms[solo]) if solo.any() else np.zeros(6)
        for group, arms, sample in zip(self.groups, self.group_arms, self.group_samples(x, v)):
            f = f + generalised_force(x, group.body_forces(sample), arms)
        return f

    def _batched_force(self, x: NDArray[np.float64], v: NDArray[np.float64]
                       ) -> NDArray[np.float64]:
        """:meth:`mooring_force` when every line is a dynamic line of the batch, in order:
        the same values, through the work arrays (a body step asks for it four times)."""
        out = np.empty(6)
        batched_mooring_force(np.ascontiguousarray(x, dtype=float),
                              np.ascontiguousarray(v, dtype=float), self.arms, self.centre,
                              self._pos, self._vel, *self._stage_arguments[self._at_mid],
                              self._stage_ff, self._stage_af, out)
        return out

    def _advance_memory_lines(self, time: float, x: NDArray, v: NDArray) -> None:
        """Advance the groups and the quasi-dynamic lines to ``time``, the fairleads moving to
        where the body state (x, v) puts them (the dynamic lines: :meth:`_advance_dynamic`)."""
        for group, arms in zip(self.groups, self.group_arms):
            pos, vel = points_state(x, v, arms, self.centre)
            group.advance(time, pos, vel)
        if not self._evaluated:
            return
        pos, vel = points_state(x, v, self.arms, self.centre)
        times, ff, af, lb, steps = self._sample
        times[0] = time
        for i in self._evaluated:
            self.models[i].solve_path(times, pos[i:i + 1], vel[i:i + 1], ff, af, lb, steps)
            self.laid_length[i] = lb[0]

    def _advance_dynamic(self, t_mid: float, x_mid: NDArray, v_mid: NDArray, t_end: float,
                         x_end: NDArray, v_end: NDArray) -> None:
        """Advance the dynamic lines over the step's two samples in one go (to ``t_mid``,
        the body state (x_mid, v_mid) placing the fairleads, and on to ``t_end``), keeping
        their states at ``t_mid`` for stages 1 and 2."""
        batch = self._batch
        if batch is None:
            return
        pos_mid, vel_mid, pos_end, vel_end = self._samples
        points_state_into(x_mid, v_mid, self._batch_arms, self.centre, pos_mid, vel_mid)
        points_state_into(x_end, v_end, self._batch_arms, self.centre, pos_end, vel_end)
        batch.advance(t_mid, t_end, pos_mid, vel_mid, pos_end, vel_end)
        self.laid_length[self._batch_index] = batch.laid_length

    # -- stepping --------------------------------------------------------------------------
    def step(self) -> None:
        """Advance the body and its lines by one body step."""
        body = self.body
        t, dt = body.time, body.dt
        x0, v0 = body.x.copy(), body.v.copy()
        predicted: dict[str, NDArray] = {}

        def force(stage: int, tau: float, x: NDArray, v: NDArray) -> NDArray:
            if stage == 1:  # a_n from stage 1's velocity: v = v_n + dt/2 a_n
                a0 = (v - v0) / (0.5 * dt)
                predicted["a"] = a0
                h = 0.5 * dt
                x_mid, v_mid = x0 + v0 * h + 0.5 * a0 * h * h, v0 + a0 * h
                self._advance_memory_lines(t + h, x_mid, v_mid)
                self._advance_dynamic(t + h, x_mid, v_mid, t + dt,
                                      x0 + v0 * dt + 0.5 * a0 * dt * dt, v0 + a0 * dt)
                self._at_mid = True
            elif stage == 3:
                a0 = predicted["a"]
                self._advance_memory_lines(t + dt, x0 + v0 * dt + 0.5 * a0 * dt * dt,
                                           v0 + a0 * dt)
                self._at_mid = False
            f = self.external(t + tau, x, v)
            if len(self.lines):
                f = f + self.mooring_force(x, v)
            return f

        try:
            body.step(force)
        finally:
            self._at_mid = False
