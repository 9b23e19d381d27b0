"""The dynamic line model: a discontinuous Galerkin cable (docs/theory/cable.md and docs/theory/dynamic_line.md).

Size: the line's state (with its friction anchors), set-up, settling, stepping and checkpoint
in one class; the kernels are elsewhere.

:class:`DynamicLine` owns the DG state of one line (node positions and velocities), starts it
from the quasi-static catenary, and advances it with the fairlead driven by a prescribed
position and velocity. Forced-motion runs call :meth:`DynamicLine.solve_path`; coupled runs
advance their dynamic lines through :mod:`floatmoor.mooring.dg.batch` (:meth:`run_kernel`).
It is built from the physical properties of :mod:`floatmoor.mooring.dg.cable`.

Size: the one class of a line's state (settle, stepping along a path, the kernel entry of
coupled runs, checkpoints) and its workspace; its methods share the class's private state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import DynamicSettings, Environment, Line, Seabed
from floatmoor.errors import CaseError, SolverError
from floatmoor.mooring.catenary import catenary_profile, solve_catenary
from floatmoor.mooring.dg import _implicit_kernels as _ik
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg.cable import CableProperties
from floatmoor.mooring.dg.implicit import ImplicitIntegrator, ImplicitSettings, implicit_parameters
from floatmoor.mooring.dg.resolution import AutoIntegration, resolve_settings
from floatmoor.mooring.dg.reference import ReferenceElement, reference_element
from floatmoor.mooring.stepping import PathStepper

__all__ = ["CableProperties", "DynamicLine", "DynamicLineState", "SettleReport",
           "SETTLE_RATE_TAU", "SETTLE_CHUNK_TAU", "SETTLE_MAX_TIME_TAU", "SETTLE_TOLERANCE",
           "MAX_DYNAMIC_STEPS"]

#: The initial relaxation runs on the line's own time scale tau = sqrt(L / g) (L unstretched,
#: :meth:`DynamicLine.settle_time_scale`), so that a line scaled by dynamic similitude
#: (floatmoor.similitude: times x sqrt(lambda)) settles through the same dimensionless history:
#: damping rate = SETTLE_RATE_TAU / tau, chunk = SETTLE_CHUNK_TAU tau, at most
#: SETTLE_MAX_TIME_TAU tau. Modes above rate / 2 (the longitudinal and most transverse ones)
#: decay as exp(-rate t / 2). The settle times measured with these values and others:
#: docs/validation/notes.md, "Settling on the line's time scale".
SETTLE_RATE_TAU = 18.0
SETTLE_CHUNK_TAU = 0.05
SETTLE_MAX_TIME_TAU = 11.0
#: Relative change of the end tensions over one chunk below which the line counts as settled.
SETTLE_TOLERANCE = 1e-6
#: Most explicit steps of one dynamic line for its settle or a run (duration / step, estimated
#: before the first step): the shipped cases need at most 6.4e6 (the buoy's chains, 60 s at
#: 9.4 us); a mistyped cfl = 1e-6 asked for 4e10 steps, a run that never ends.
MAX_DYNAMIC_STEPS = 1.0e8
#: Settled lines remembered per process (oldest dropped first).
_SETTLED_SIZE = 64
_SETTLED: dict = {}
#: The kernels' shape outputs when no shapes are recorded.
_NO_SHAPE_R = np.zeros((1, 1, 3))
_NO_SHAPE_T = np.zeros((1, 1))


@dataclass(frozen=True)
class SettleReport:
    """Outcome of :meth:`DynamicLine.settle`."""

    time: float  #: simulated settling time [s]
    converged: bool  #: the end tensions met the tolerance
    change: float  #: relative change of the end tensions over the last chunk [-]
    speed: float  #: largest node speed before the velocities were zeroed [m/s]

_STATUS_TEXT = {
    _k.DG_NOT_FINITE: "the position or velocity is not finite",
    _k.DG_VELOCITY: "a node moves faster than the longitudinal wave speed",
    _k.DG_STRAIN: f"the strain exceeds {_k.MAX_STRAIN:g}",
    _ik.DG_NEWTON: "the implicit step's Newton iteration did not converge at the smallest step",
}
#: Share of the accepted error (``accuracy`` of the fairlead tension) given to the local error
#: of one implicit step in smooth motion (away from slack, below): the global error is the
#: accumulation of local ones, damped by the line's drag. 1 against 1/4 (the one share before,
#: now the share near slack), with Newton's error estimate: DeepCwind lines 1 to 3 on their
#: LC34 paths (600 s, 8 x p3) take 36 % (lines 1 and 3) and 24 % (line 2) fewer steps, and
#: their fairlead-tension STD and maximum move by 0.05 % at most (an earlier measurement put
#: line 2 within 0.38 % (STD) of 16 x p5 explicit at 1, 0.32 % at 1/4).
IMPLICIT_ERROR_SHARE = 1.0
#: The share near slack (below), where a snap's peak follows the local errors of the steps
#: through it directly: the Lindahl chain's snaps (T = 1.25 s) 0.6 % above the explicit steps'
#: mean cycle maximum at 1/4, 1.0 % at 1/2 (the whole accuracy), 8.8 % at 1 used throughout
#: with Newton's error estimate.
#: Near slack Newton also iterates until its correction itself is within its tolerance
#: (``_implicit_kernels.newton_converged``): its error estimate lets through enough to move
#: those snaps by 3 %.
SNAP_ERROR_SHARE = 0.25
#: A line is near slack while its fairlead tension is below this share of its tension scale
#: (the larger initial end tension) and for ``SNAP_WINDOW_PERIODS`` periods of its motion
#: after: a line unloaded to a third of its pretension reaches the impulsive re-tensioning of
#: snap loads within a cycle or two. The Lindahl chain (22.7 N at rest) falls below 6.8 N in
#: the ramp's cycle before its first slack (1.8 s in) and every cycle after. Its snap train's
#: mean cycle maximum, which moves by a few tenths of a per cent with any change of the step
#: pattern, came out on average 1.17 % above the explicit steps' at 0.3 and 1.28 % at 0.1
#: (four perturbations of Newton's tolerance each, measured with a first-iteration Newton
#: test since withdrawn; docs/validation/performance.md).
SLACK_TENSION_SHARE = 0.3
#: Periods of the motion after the last near-slack step during which the line keeps the
#: tolerances of snaps: the Lindahl chain's cycle maximum comes 0.85 s (0.7 periods) after
#: its slack minimum, through a train of smaller snaps.
SNAP_WINDOW_PERIODS = 1.0


@dataclass(frozen=True)
class DynamicLineState:
    """A saved state: time, node positions and velocities, fairlead position and velocity,
    and the friction anchors (None: at the nodes, no stored shear).

    Attributes
    ----------
    time
        The line's time [s].
    positions, velocities
        Node positions [m] and velocities [m/s] (nodes, 3).
    fairlead, fairlead_velocity
        The fairlead's position [m] and velocity [m/s] (3,).
    friction_anchors
        Where each node's seabed friction spring is anchored (nodes, 3) [m], or None."""

    time: float
    positions: NDArray[np.float64]
    velocities: NDArray[np.float64]
    fairlead: NDArray[np.float64]
    fairlead_velocity: NDArray[np.float64]
    friction_anchors: NDArray[np.float64] | None = None


class DynamicLine(PathStepper):
    """A mooring line solved by the DG cable model.

    Parameters
    ----------
    properties
        Physical properties.
    settings
        Discretisation (elements, order, CFL, filter, seabed contact treatment), resolved
        (:func:`resolution.resolve_settings`: no element count or order left to choose).
    anchor, fairlead
        End positions [m]; the line starts at rest in the quasi-static catenary between them
        (frictionless, the equilibrium of the dynamic model, whose ramped Coulomb friction
        holds nothing at rest), unless ``initial_positions`` (nodes, 3) are given.
    name
        Named in error messages.
    initial_positions
        Node positions (nodes, 3) [m] to start from instead of the catenary (at rest).
    time
        The line's time at the start [s].
    """

    model = "dynamic"
    batched = True  # coupled runs: advanced with the body's other dynamic lines (dg.batch)
    resolves_dynamics = True

    def __init__(self, properties: CableProperties, settings: DynamicSettings,
                 anchor: NDArray[np.float64], fairlead: NDArray[np.float64], *,
                 name: str = "line", initial_positions: NDArray[np.float64] | None = None,
                 time: float = 0.0) -> None:
        if not settings.resolved:
            raise ValueError(f"line '{name}': settings with elements and order chosen "
                             "(resolution.resolve_settings) expected, found "
                             f"elements={settings.elements!r}, order={settings.order!r}")
        self.properties = properties
        self.settings = settings
        self.name = name
        self.anchor = np.array(anchor, dtype=float)
        self.anchor.flags.writeable = False  # as _k._ZERO3 is: kernels compile for one type
        K, p = settings.elements, settings.order
        self.element: ReferenceElement = reference_element(p)
        self.element_length = properties.length / K
        self.prm = properties.packed(settings, self.element_length)
        s = (np.arange(K)[:, None] + 0.5 * (self.element.nodes[None, :] + 1.0)) * self.element_length
        self.arc_length = s.reshape(-1)  #: unstretched arc length of every node [m]
        self.r = np.zeros((K, p + 1, 3))
        self.v = np.zeros((K, p + 1, 3))
        if initial_positions is None:
            initial_positions = self._catenary_positions(np.asarray(fairlead, dtype=float))
        self.r[:] = np.asarray(initial_positions, dtype=float).reshape(K, p + 1, 3)
        #: the stick-spring friction's anchor of every node in the seabed plane [m]
        #: (docs/theory/cable.md#seabed-friction): at the nodes, no stored shear, at the start
        self.friction_anchors = self.r[..., :2].copy()
        self.time = float(time)
        self.fairlead = np.array(fairlead, dtype=float)
        self.fairlead_velocity = np.zeros(3)
        self.time_step = self._time_step()
        self._work = _Workspace(K, p + 1)
        #: the implicit integration, None when the line steps explicitly
        self.implicit: ImplicitIntegrator | None = None
        #: the run-time choice of ``time_integration = "auto"``, None otherwise
        self.auto: AutoIntegration | None = None
        self._settling = False
        if settings.time_integration != "explicit":
            #: the kernels' parameter vector of the implicit steps (contact and damping in
            #: the implicit solve)
            self.implicit_prm = implicit_parameters(self.prm)
            self.implicit = ImplicitIntegrator(
                K, p + 1, self._implicit_settings(), properties.axial_stiffness,
                0.5 * self.element_length * self.element.min_spacing)
        if settings.time_integration == "auto":
            self.auto = AutoIntegration.for_line(
                settings.motion_frequency,
                properties.time_step(replace(settings, time_integration="explicit")), p + 1)
        #: sample index of the last failure in :meth:`solve_path`, -1 if none
        self.failed_index = -1
        #: outcome of the initial relaxation (:meth:`settle`), None if not settled
        self.settle_report: SettleReport | None = None

    @classmethod
    def from_case(cls, line: Line, environment: Environment, seabed: Seabed) -> "DynamicLine":
        """The dynamic model of a case's line, at rest in its mean position: settled
        (:meth:`settle`) unless the case's ``[lines.dynamic] settle = false``.

        Settled positions are remembered per process for the same properties, numerics and
        end positions (``_SETTLED``), so that a campaign over motions settles each line once.
        """
        props = CableProperties.from_case(line, environment, seabed)
        settings = line.dynamic
        if not settings.resolved:
            settings = resolve_settings(settings, props.length, props.transverse_wave_speed(
                np.asarray(line.anchor, dtype=float), np.asarray(line.fairlead, dtype=float)))
        obj = cls(props, settings, np.asarray(line.anchor), np.asarray(line.fairlead),
                  name=line.name)
        if settings.settle:  # (the motion frequency only chose the numerics: not in the key)
            key = (props, replace(settings, motion_frequency=0.0),
                   tuple(obj.anchor), tuple(obj.fairlead))
            if key in _SETTLED:
                obj.r[:], obj.settle_report = _SETTLED[key]
                obj.friction_anchors[...] = obj.r[..., :2]
            else:
                obj.settle_report = obj.settle()
                if len(_SETTLED) >= _SETTLED_SIZE:
                    _SETTLED.pop(next(iter(_SETTLED)))
                _SETTLED[key] = (obj.r.copy(), obj.settle_report)
        return obj

    # -- set-up --------------------------------------------------------------------------------
    def _catenary_positions(self, fairlead: NDArray[np.float64]) -> NDArray[np.float64]:
        pr = self.properties
        weight = pr.submerged_weight
        if weight <= 0.0:  # in vacuum or buoyant: start from the straight line
            return self.anchor + np.outer(self.arc_length / pr.length, fairlead - self.anchor)
        sol = solve_catenary(self.anchor, fairlead, pr.length, pr.axial_stiffness, weight,
                             0.0, seabed_z=pr.seabed_z)
        positions, _ = catenary_profile(self.anchor, fairlead, pr.length, pr.axial_stiffness,
                                        weight, 0.0, seabed_z=pr.seabed_z,
                                        arc_lengths=self.arc_length, solution=sol)
        return positions

    def _implicit_settings(self) -> ImplicitSettings:
        """The implicit step's bounds from the line's tension scale (the larger of its initial
        end tensions, at least 1 % of its weight in water for a line that starts slack, 1 N for
        a weightless unloaded one): the local error of the fairlead force one step may make
        [N], the ``accuracy`` share ``SNAP_ERROR_SHARE`` of the scale near slack and
        ``IMPLICIT_ERROR_SHARE`` away from it; the strain below ``SLACK_TENSION_SHARE`` of the
        scale; and the snap window, ``SNAP_WINDOW_PERIODS`` periods of the motion (for ever
        when its frequency is not known: a line whose history is unknown then keeps the snap
        tolerances all along)."""
        ff, af = self.end_forces()
        scale = max(float(np.linalg.norm(ff)), float(np.linalg.norm(af)),
                    0.01 * abs(self.properties.submerged_weight) * self.properties.length)
        scale = scale if scale > 0.0 else 1.0
        accuracy = self.settings.accuracy
        w = self.settings.motion_frequency
        return ImplicitSettings(
            self.time_step, SNAP_ERROR_SHARE * accuracy * scale,
            smooth_force_tolerance=IMPLICIT_ERROR_SHARE * accuracy * scale,
            snap_window=SNAP_WINDOW_PERIODS * 2.0 * math.pi / w if w > 0.0 else math.inf,
            slack_strain=SLACK_TENSION_SHARE * scale / self.properties.axial_stiffness)

    def _time_step(self) -> float:
        """The time step (:meth:`CableProperties.time_step`), checked usable."""
        dt = self.properties.time_step(self.settings)
        if not (dt > 0.0 and math.isfinite(dt)):  # case loading bounds the wave speed
            raise SolverError(f"line '{self.name}' (dynamic): no usable time step ({dt!r} s) "
                              f"for an axial wave speed of {self.properties.wave_speed:.3g} "
                              "m/s; the axial stiffness or mass per length is out of range")
        return dt

    @property
    def accuracy_checked(self) -> bool:
        """Whether its element count can be checked along a motion (one with a frequency:
        :mod:`floatmoor.simulation.line_accuracy`)."""
        return self.settings.motion_frequency > 0.0

    def refuse_long_work(self, duration: float, what: str, source: str = "",
                         line: str | None = None) -> None:
        """Raise a CaseError at the line's ``dynamic.cfl``, with the estimate, if stepping
        explicitly over ``duration`` [s] (``what``: "the run", ...) takes more than
        :data:`MAX_DYNAMIC_STEPS` steps; ``source``: the case file, "" where unknown;
        ``line``: the case's line name (default: this model's name)."""
        dt = self._explicit_step()
        if self._stepping_implicit() or duration / dt <= MAX_DYNAMIC_STEPS:
            return  # (adaptive implicit steps: their count follows the accuracy)
        raise CaseError(source, f"lines.{line or self.name}.dynamic.cfl", "numerics giving at most "
                        f"{MAX_DYNAMIC_STEPS:.3g} explicit steps of the dynamic line "
                        f"'{self.name}' for {what} (floatmoor.mooring.dg.line.MAX_DYNAMIC_STEPS;"
                        " a larger cfl, fewer elements or time_integration = \"implicit\")",
                        f"cfl {self.settings.cfl!r}: a step of {dt:.3g} s over {duration:.6g} s,"
                        f" ~{duration / dt:.3g} steps")

    def settle_time_scale(self) -> float:
        """The line's own time scale tau [s] the relaxation runs on: sqrt(L / g), the
        pendulum time of the hanging line (L / c, the axial wave's travel time, without
        gravity). It scales sqrt(lambda) like every time under dynamic similitude."""
        pr = self.properties
        if pr.gravity > 0.0:
            return math.sqrt(pr.length / pr.gravity)
        return pr.length / pr.wave_speed

    def settle(self, rate: float | None = None, tolerance: float = SETTLE_TOLERANCE,
               max_time: float | None = None, chunk: float | None = None) -> SettleReport:
        """Relax the line to the static equilibrium of its own discretisation, ends held.

        The interpolated catenary a line starts from is not exactly in equilibrium in the DG
        discretisation (the touchdown kink and the stretch of a stiff line are represented to
        the discretisation error). Left alone, the mismatch rings on as longitudinal and
        transverse waves that nothing damps in an undamped line: on the stiff chains of
        the quasi-dynamic verification lines (docs/cases/qd_verification.md; c ~ 2000 m/s),
        fairlead-tension ripple from 0.03 to 13.5 N about a static 1.95 N. Like MoorDyn's
        initialisation (dynamic relaxation),
        the line is first run with its fairlead still and a linear damping dv/dt -= ``rate`` v
        on every node (kernel parameter ``P_RELAX``; it leaves the stability limit unchanged),
        in chunks of simulated time ``chunk``, until the fairlead and anchor tensions change
        by less than ``tolerance`` (relative) over a chunk; then velocities are zeroed and the
        line's time restored. Underdamped modes (omega > rate / 2) decay as
        exp(-rate t / 2). ``rate``, ``chunk`` and ``max_time`` default to the
        ``SETTLE_*_TAU`` multiples of :meth:`settle_time_scale`.

        Returns
        -------
        SettleReport
            Simulated settling time, whether the tolerance was met, the last relative change
            and the largest node speed before the velocities were zeroed.
        """
        tau = self.settle_time_scale()
        rate = SETTLE_RATE_TAU / tau if rate is None else rate
        max_time = SETTLE_MAX_TIME_TAU * tau if max_time is None else max_time
        chunk = SETTLE_CHUNK_TAU * tau if chunk is None else chunk
        if not (rate > 0.0 and tolerance > 0.0 and max_time > 0.0 and chunk > 0.0):
            raise ValueError("settle needs a positive rate, tolerance, max_time and chunk")
        start = self.time
        self._settling = True  # ("auto" settles with the explicit steps: _stepping_implicit)
        integ = self.implicit if self._stepping_implicit() else None
        if integ is None:
            try:  # the relaxation's explicit steps, estimated before the first
                self.refuse_long_work(max_time, f"the initial settle (at most "
                                      f"{SETTLE_MAX_TIME_TAU:g} sqrt(L / g) = {max_time:.6g} s,"
                                      f" L = {self.properties.length:g} m, g = "
                                      f"{self.properties.gravity:g} m/s^2)")
            except CaseError:
                self._settling = False
                raise
            dt = self._explicit_step()
            chunk = max(int(math.ceil(chunk / dt)), 2) * dt
            prm = self.prm
        else:  # one step a chunk (the relaxation is inside the implicit solve, so any step
            # is stable), no error control: only the end state counts
            prm, saved = self.implicit_prm, integ.ip.copy()
            integ.ip[_ik.IP_FORCE_TOL] = np.inf
            integ.ip[_ik.IP_SMOOTH_TOL] = np.inf
            integ.ip[_ik.IP_DT_MAX] = chunk
            integ.invalidate()
        still = np.repeat(self.fairlead[None, :], 2, axis=0)
        zero = np.zeros_like(still)
        ff, af, scratch = np.zeros((2, 3)), np.zeros((2, 3)), np.zeros(2)
        previous = np.array([np.inf, np.inf])
        change, converged = np.inf, False
        prm[_k.P_RELAX] = rate
        ks = prm[_k.P_KS]
        # the relaxation finds the frictionless equilibrium: the regularised Coulomb law holds
        # nothing at rest, a stick spring would hold the line where the relaxation stopped it
        prm[_k.P_KS] = 0.0
        try:
            while self.time - start < max_time:
                t = self.time + np.array([0.0, chunk])
                self.solve_path(t, still, zero, ff, af, scratch, scratch.copy())
                ends = np.array([np.linalg.norm(ff[1]), np.linalg.norm(af[1])])
                change = float(np.max(np.abs(ends - previous) / np.maximum(ends, 1e-300)))
                previous = ends
                if change < tolerance:
                    converged = True
                    break
        finally:
            self._settling = False
            prm[_k.P_RELAX] = 0.0
            prm[_k.P_KS] = ks
            self.friction_anchors[...] = self.r[..., :2]  # settled: no stored shear
            if integ is not None:
                integ.ip[:] = saved
                integ.invalidate()
                integ.cs[_ik.CS_LEVEL] = 0.0
                integ.cs[_ik.CS_GOOD] = 0.0
        elapsed = self.time - start
        speed = float(np.max(np.linalg.norm(self.v, axis=-1)))
        self.v[:] = 0.0
        self.time = start
        return SettleReport(elapsed, converged, change, speed)

    # -- stepping ------------------------------------------------------------------------------
    def solve_path(self, time: NDArray[np.float64], path: NDArray[np.float64],
                   velocity: NDArray[np.float64], fairlead_force: NDArray[np.float64],
                   anchor_force: NDArray[np.float64], laid_length: NDArray[np.float64],
                   steps: NDArray[np.float64], *, shape_every: int = 0,
                   shape_positions: NDArray[np.float64] | None = None,
                   shape_tension: NDArray[np.float64] | None = None) -> None:
        """Advance along a fairlead path, recording the end forces at every sample.

        Parameters
        ----------
        time
            Sample times [s], increasing, with ``time[0] >= self.time``. When
            ``time[0] == self.time`` sample 0 is the current state.
        path, velocity
            Fairlead positions [m] and velocities [m/s] at the samples, shape (n, 3).
        fairlead_force, anchor_force
            Outputs: forces exerted by the line on its fairlead and anchor [N], (n, 3).
        laid_length
            Output: length resting on the seabed [m], (n,).
        steps
            Output: time steps taken to reach each sample, (n,).
        shape_every, shape_positions, shape_tension
            Every ``shape_every``-th sample, the node positions (m, nodes, 3) and tensions
            (m, nodes) are written.

        Raises
        ------
        SolverError
            When the solution goes unstable, naming the line, the time and the quantity;
            the outputs before that sample are valid.
        """
        time = np.asarray(time, dtype=float)
        prepend = time[0] > self.time
        if prepend:
            time = np.concatenate(([self.time], time))
            path = np.concatenate((self.fairlead[None, :], path))
            velocity = np.concatenate((self.fairlead_velocity[None, :], velocity))
        n = time.size
        w = self._work
        ff, af = np.zeros((n, 3)), np.zeros((n, 3))
        lb, st = np.zeros(n), np.zeros(n)
        if shape_every > 0 and shape_positions is not None and shape_tension is not None:
            sr, sten = shape_positions, shape_tension
            if prepend:  # the shapes count samples of the caller's time axis
                raise ValueError("shape output needs time[0] == the line's time")
        else:
            shape_every, sr, sten = 0, np.zeros((1, 1, 3)), np.zeros((1, 1))
        i0 = 0
        while True:  # with "auto", in segments up to its decisions (_segment_end)
            i1 = self._segment_end(time, i0, shape_every)
            status, index = self._run_segment(self._stepping_implicit(), time, path, velocity,
                                              ff, af, lb, st, shape_every, sr, sten, i0, i1)
            if status != _k.DG_OK or i1 >= n - 1:
                break
            self._auto_update(float(time[i1]))
            i0 = i1
        first = 1 if prepend else 0
        done = index if status != _k.DG_OK else n
        fairlead_force[:done - first] = ff[first:done]
        anchor_force[:done - first] = af[first:done]
        laid_length[:done - first] = lb[first:done]
        steps[:done - first] = st[first:done]
        if status != _k.DG_OK:
            self.failed_index = index - first
            raise self.unstable(status, float(time[index]))
        self.failed_index = -1
        self.time = float(time[-1])
        self.fairlead = np.array(path[-1], dtype=float)
        self.fairlead_velocity = np.array(velocity[-1], dtype=float)
        self._auto_update(self.time)

    def _auto_update(self, time: float) -> None:
        """``"auto"`` (not settling): its decision at ``time`` (AutoIntegration.update)."""
        if (self.auto is not None and not self._settling
                and self.auto.update(time, self.implicit.cs)):
            self._follow_auto()

    def _segment_end(self, time: NDArray[np.float64], i0: int, shape_every: int) -> int:
        """Last sample of the kernel call from sample ``i0``: the path's end, or, with "auto",
        the first (shape) sample at or after its next decision (shapes keep their slots)."""
        if self.auto is None or self._settling:
            return time.size - 1
        return self.auto.segment_end(time, i0, shape_every, self.implicit.cs)

    def _run_segment(self, implicit: bool, time, path, velocity, ff, af, lb, st, shape_every,
                     sr, sten, i0: int, i1: int) -> tuple[int, int]:
        """One kernel call over samples ``i0`` to ``i1`` (its first sample, the state the
        previous call ended in, is recorded again: the earlier record is kept); the status
        and the failing sample's index in the whole path."""
        seg = slice(i0, i1 + 1)
        kept = (ff[i0].copy(), af[i0].copy(), lb[i0], st[i0]) if i0 > 0 else None
        every = shape_every
        shapes_r, shapes_t = sr, sten
        if every > 0:
            shapes_r, shapes_t = sr[i0 // every:], sten[i0 // every:]
        t, x, u = (np.ascontiguousarray(a[seg]) for a in (time, path, velocity))
        status, index = self.run_kernel(implicit, t, x, u, ff[seg], af[seg], lb[seg], st[seg],
                                        every, shapes_r, shapes_t)
        if kept is not None:
            ff[i0], af[i0], lb[i0], st[i0] = kept
        return status, i0 + index

    def run_kernel(self, implicit: bool, t: NDArray[np.float64], x: NDArray[np.float64],
                   u: NDArray[np.float64], ff: NDArray[np.float64], af: NDArray[np.float64],
                   lb: NDArray[np.float64], st: NDArray[np.float64], every: int = 0,
                   shapes_r: NDArray[np.float64] = _NO_SHAPE_R,
                   shapes_t: NDArray[np.float64] = _NO_SHAPE_T) -> tuple[int, int]:
        """One kernel call (implicit or explicit) on the line's state and workspace: samples
        ``t`` (the first the current state), fairlead ``x``, ``u``, outputs ``ff`` ... ``st``
        (C-contiguous); the status and the failing sample's index. No bookkeeping: the line's
        time, fairlead and ``"auto"`` windows are the caller's (:meth:`solve_path`, or the
        coupled runs' :mod:`floatmoor.mooring.dg.batch`)."""
        w = self._work
        if implicit:
            return self.implicit.run(
                self.r, self.v, t, x, u, self.anchor, self.implicit_prm, self.element, w,
                ff, af, lb, st, every, shapes_r, shapes_t, self.friction_anchors_in_use())
        return _k.dg_run_path(
            self.r, self.v, t, x, u, self.anchor, self.prm,
            self.element.differentiation, self.element.lift, self.element.filter,
            self.element.weights, self._explicit_step(), ff, af, lb, st,
            every, shapes_r, shapes_t, w.stages, w.q, w.qt, w.N, w.Nstar, w.faces,
            w.slack, w.fpos, w.fvel, w.tmp, w.boundary, w.where,
            w.damping if self._implicit_damping() else None, self.friction_anchors_in_use())

    def plain_steps_until(self, t_end: float) -> bool | None:
        """Whether the steps from now to ``t_end`` [s] are implicit, when :meth:`run_kernel`
        may take them with no ``"auto"`` decision on the way (no window of it ends by
        ``t_end``: :meth:`solve_path` would run them in one segment and not switch); None
        when a window ends (only :meth:`solve_path` decides there)."""
        return self._stepping_implicit() if t_end < self._decisions_from() else None

    def plain_until(self) -> float:
        """The time [s] before which :meth:`plain_steps_until` is True: the steps implicit and
        no ``"auto"`` decision on the way (-inf when the steps are explicit)."""
        return self._decisions_from() if self._stepping_implicit() else -math.inf

    def _decisions_from(self) -> float:
        """The time [s] from which only :meth:`solve_path` may step the line: its next
        ``"auto"`` decision (inf without one; -inf before the first)."""
        auto = self.auto
        if auto is None or self._settling:
            return math.inf
        # (explicit windows end in decisions too: a probe may start implicit steps there)
        if auto.counters is None:
            return -math.inf
        return auto.next_check() - 1e-9 * auto.window

    def unstable(self, status: int, time: float,
                 where: NDArray[np.int64] | None = None) -> SolverError:
        """The error of a kernel's failing ``status`` at ``time`` [s] (the element and node
        in ``where``, by default the workspace's), naming the line, the arc length and the
        step."""
        where = self._work.where if where is None else where
        k, i = int(where[0]), int(where[1])
        s = self.arc_length[k * (self.settings.order + 1) + i]
        return SolverError(f"line '{self.name}' (dynamic): {_STATUS_TEXT[status]} at arc "
                           f"length s = {s:.4g} m, t = {time:.6g} s; the solution "
                           f"went unstable ({self._step_text()})")

    def friction_anchors_in_use(self) -> NDArray[np.float64] | None:
        """The friction anchors with the stick-spring law, None with the Coulomb law (whose
        kernels then compile without the friction kernels:
        docs/validation/performance.md#first-run)."""
        return self.friction_anchors if self.properties.stick_stiffness > 0.0 else None

    def _stepping_implicit(self) -> bool:
        """Whether the next steps are implicit ("auto": until it went explicit, and not while
        it settles: the explicit relaxation converges where the implicit one may not, e.g.
        on the MHK RM1 deck's lines, 20 s of relaxation and 176k factorisations short of its
        tolerance, against 10 s of wall time for the whole explicit run)."""
        if self.implicit is None:
            return False
        return self.auto is None or not (self.auto.switched or self._settling)

    def _explicit_step(self) -> float:
        """The explicit step [s] (with "auto", the one it would take or takes)."""
        return self.auto.explicit_step if self.auto is not None else self.time_step

    def _follow_auto(self) -> None:
        """``time_integration = "auto"``: continue with the steps it chose (resolution.py)."""
        auto = self.auto
        self.time_step = auto.explicit_step if auto.switched else self.implicit.settings.max_step
        self._work.damping[-1][0] = 0.0  # factors and accelerations of an older state
        self.implicit.invalidate()

    def _step_text(self) -> str:
        """The step, as failure messages name it."""
        if not self._stepping_implicit():
            return f"time step {self.time_step:.3g} s"
        return (f"implicit steps of at most {self.time_step:.3g} s, "
                f"{int(self.implicit.cs[_ik.CS_REJECTED])} rejected")

    def _implicit_damping(self) -> bool:
        """Whether the steps take the backward-Euler internal-damping step: only then do the
        kernels get its work arrays (and compile its code)."""
        return (self.settings.time_integration != "implicit"
                and self.prm[_k.P_IMPLICIT_DAMPING] != 0.0 and self.prm[_k.P_CINT] > 0.0)

    # -- state ---------------------------------------------------------------------------------
    def get_state(self) -> DynamicLineState:
        """A copy of the current state."""
        return DynamicLineState(self.time, self.r.copy(), self.v.copy(), self.fairlead.copy(),
                                self.fairlead_velocity.copy(), self.friction_anchors.copy())

    def set_state(self, state: DynamicLineState) -> None:
        """Restore a state saved by :meth:`get_state`."""
        self.time = state.time
        self.r[:] = state.positions
        self.v[:] = state.velocities
        self.fairlead[:] = state.fairlead
        self.fairlead_velocity[:] = state.fairlead_velocity
        self.friction_anchors[...] = (self.r[..., :2] if state.friction_anchors is None
                                      else state.friction_anchors)
        self._work.damping[-1][0] = 0.0  # the factored damping system belongs to another state
        if self.implicit is not None:
            self.implicit.invalidate()

    def state_arrays(self) -> dict[str, NDArray[np.float64]]:
        """The state of :meth:`get_state` as named arrays (time 0-d), for a checkpoint of
        plain numeric data; with the implicit internal damping also its frozen factors
        (``damping_*``), which later steps reuse until the tangents move (a state restored
        without them refactors earlier, and continues to other last bits)."""
        s = self.get_state()
        out = {"time": np.array(s.time, dtype=np.float64), "positions": s.positions,
               "velocities": s.velocities, "fairlead": s.fairlead,
               "fairlead_velocity": s.fairlead_velocity, "friction_anchors": s.friction_anchors}
        if self._implicit_damping():
            out.update({f"damping_{name}": a.copy()
                        for name, a in zip(_DAMPING_ARRAYS, self._work.damping)})
        if self.implicit is not None:
            out.update(self.implicit.state_arrays())
        if self.auto is not None:
            out.update(self.auto.state())
        return out

    def set_state_arrays(self, arrays: dict[str, NDArray[np.float64]]) -> None:
        """Restore a state of :meth:`state_arrays` (shapes checked by the caller)."""
        self.set_state(DynamicLineState(
            float(arrays["time"]), *(np.asarray(arrays[k], dtype=float) for k in (
                "positions", "velocities", "fairlead", "fairlead_velocity")),
            np.asarray(arrays["friction_anchors"], dtype=float)))
        if self.auto is not None:
            self.auto.set_state(arrays)
            self._follow_auto()
        if self._implicit_damping():
            for name, a in zip(_DAMPING_ARRAYS, self._work.damping):
                a[...] = arrays[f"damping_{name}"]
        if self.implicit is not None:
            self.implicit.set_state_arrays(arrays)

    def end_forces(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Forces the line exerts on its fairlead and anchor in the current state [N]."""
        return self.end_forces_moving(self.fairlead_velocity)

    def end_forces_moving(self, fairlead_velocity: NDArray[np.float64]
                          ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """End forces [N] of the current state with the fairlead's velocity replaced: through
        the end flux N* = N + Z (v_fairlead - v), the fairlead force answers the fairlead
        velocity at once with the axial impedance Z = m c. The coupled body uses this to give
        each Runge-Kutta stage the line's dashpot response to its own velocity
        (floatmoor.simulation.coupled). The position stays the line's own: through the end
        tangent's lift term the end tension would answer a position change with a stiffness of
        order EA (p + 1)^2 / h, an artefact of the discretisation."""
        w = self._work
        ff, af = np.zeros(3), np.zeros(3)
        _k._record(self.r, self.v, self.anchor, self.fairlead,
                   np.asarray(fairlead_velocity, dtype=float), self.prm,
                   self.element.differentiation, self.element.lift, w.q, w.qt, w.N, w.Nstar,
                   w.faces, w.slack, self.element.weights, ff, af)
        return ff, af

    def tension(self) -> NDArray[np.float64]:
        """Effective tension at every node in the current state [N], (nodes,)."""
        self.end_forces()
        return np.linalg.norm(self._work.N, axis=-1).reshape(-1)

    def energy(self) -> dict[str, float]:
        """Kinetic, strain and gravitational energy of the line [J] (the latter with the
        submerged weight below z = 0), integrated with the element quadrature."""
        self.end_forces()
        pr = self.properties
        wq = np.tile(self.element.weights * 0.5 * self.element_length, self.settings.elements)
        v2 = np.sum(self.v.reshape(-1, 3) ** 2, axis=1)
        q = np.linalg.norm(self._work.q.reshape(-1, 3), axis=1)
        eps = np.maximum(q - 1.0, 0.0)
        z = self.r.reshape(-1, 3)[:, 2]
        weight = pr.mass_per_length * pr.gravity * np.where(
            z < 0.0, 1.0 - pr.water_density / pr.material_density, 1.0)
        return {"kinetic": float(0.5 * pr.mass_per_length * np.sum(wq * v2)),
                "strain": float(0.5 * pr.axial_stiffness * np.sum(wq * eps ** 2)),
                "gravity": float(np.sum(wq * weight * z))}


#: Names of the arrays of ``_Workspace.damping``, in order (checkpoint keys).
_DAMPING_ARRAYS = ("tangents", "inverse_masses", "coefficients", "flags", "y", "band", "rhs",
                   "info")


class _Workspace:
    """Preallocated arrays of the kernels (no allocation inside the time loop)."""

    def __init__(self, K: int, Np: int) -> None:
        self.stages = np.zeros((5, K, Np, 3))
        self.boundary = np.zeros((4, 3))  # fairlead position and 3 derivatives
        self.q = np.zeros((K, Np, 3))
        self.qt = np.zeros((K, Np, 3))
        self.N = np.zeros((K, Np, 3))
        self.Nstar = np.zeros((K + 1, 3))
        self.faces = np.zeros((K + 1, 3))
        self.slack = np.zeros(K)
        self.fpos = np.zeros(3)
        self.fvel = np.zeros(3)
        self.tmp = np.zeros(max(Np, 6))
        self.where = np.zeros(2, dtype=np.int64)
        # the backward-Euler system of the internal damping (_kernels._damping_system)
        # (tangents, inverse masses, coefficients, flags, Y, band, rhs, info); info[0] = 0
        # marks the factors invalid
        self.damping = (np.zeros((K, Np, 3)), np.zeros((K, Np, 2)), np.zeros((K, Np)),
                        np.zeros((K, Np)), np.zeros((K, Np, Np + 1, 3)),
                        np.zeros((K * Np, 3 * Np)), np.zeros(K * Np), np.zeros(4))
