"""The quasi-dynamic line model of Trubat, Molins & Gironella (quasi-dynamic paper, section 3).

The line keeps the static catenary shape of the quasi-static model at every instant, but its
fairlead tension is the static one scaled by the quasi-dynamic factor (eqs. 1 and 2),

    T_QD = k_QD T_S,   k_QD = int_{s_0}^{l} (f_w + f_HD - f_I).k ds / int_{s_0}^{l} f_w.k ds >= 0,

the ratio of the vertical resultant of weight, Morison drag and added mass and line inertia on
the suspended part to its weight (docs/theory/quasi_dynamic.md). Velocities and accelerations come from
backward differences of the static positions over the time steps (eq. 4); the integrals from the
composite Simpson rule. The model adds the inertia and drag that the quasi-static line lacks
and predicts slack (k_QD = 0), at the cost of one catenary solve and O(stations) work per step,
a few times the quasi-static model's; it does not carry the line's own vibrations or snap
waves, and it assumes the line follows its static shape, which fails when the static shapes
would move the line fast (drag then dominates k_QD: on the Lindahl chain at T = 1.25 s the
static shapes move its middle by +-0.5 m, alpha = w^2 Z_m / g = 1.3, against the 0.1 to 0.6
of the paper's verification).

Model choices (the paper leaves them open; see :mod:`floatmoor.mooring._quasidynamic_kernels`):

* **Stations.** Fixed material stations ("nodes") at unstretched arc lengths s_j = L - j h
  from the anchor, h = (suspended length at rest) / (``integration_points`` - 1): at rest,
  ``integration_points`` (odd) of them span the suspended part, from the touchdown point (the
  anchor for a line free of the seabed) to the fairlead. At each step composite Simpson runs
  over the stations on the suspended part, and the panel between the moving touchdown point
  and the lowest station used over the quadratic through the three lowest stations. Stations
  inside the layer |dL_B/dt| dt above the touchdown point whose material points lifted off
  the seabed within the last two steps (eq. (4) differences across the kink of their history
  there) are left to that panel. The quadrature keeps Simpson's order as the touchdown point
  moves: errors in k_QD of 1.1e-3, 7.8e-5 and 5.7e-6 with 21, 41 and 81 stations on the
  verification chain of case B.
* **Backward differences.** Of the *material* points at the stations: their positions on the
  two previous steps' static catenaries at the same unstretched arc length, kept from those
  steps (or evaluated on those lines, on the resting part for points that were on the seabed
  then). Each step evaluates one static profile at the stations, not three.
* **Time step.** One step per sample given (the output interval in a forced-motion run, or the
  interval of each :meth:`QuasiDynamicLine.advance`), or, with
  ``[lines.quasi_dynamic] max_time_step``, the fewest equal sub-steps no longer than it, the
  fairlead on the cubic Hermite curve between samples. Unequal steps use
  a = (v_n - v_{n-1}) / ((dt_n + dt_{n-1}) / 2), eq. 4 when they are equal. The catenary's
  tolerance enters the accelerations as about tol L / dt^2: keep dt above ~1e-4 s for chain.
* **Start.** At rest (k_QD = 1, the two earlier static lines the initial one), or with
  :meth:`QuasiDynamicLine.start_moving` on a fairlead already moving: the line steps from rest
  two steps back on the fairlead's path (extrapolated on the cubic Hermite curve of the first
  sample interval) to its start, so that its first differences are those of a line in motion
  (docs/theory/quasi_dynamic.md#the-start-of-a-run).
* **End forces.** The fairlead force is k_QD times the static one (its direction unchanged). The
  anchor force is that of the same apparent-weight catenary: k_QD times the static force for a
  fully suspended line, and with a resting length L_B the horizontal tension k_QD H at touchdown
  reduced by the friction C_B W L_B of the resting part, floored at zero.
* The static catenary is the quasi-static model's, configured by ``[lines.quasi_static]``
  (tolerance, iterations, seabed friction). Like it, the model gives the whole line its
  submerged weight and ignores the current; the Morison forces act on the whole suspended part.

The object offers the step API of :class:`~floatmoor.mooring.dg.line.DynamicLine`
(``solve_path`` with fairlead velocities, ``advance``, ``get_state`` / ``set_state``, ``time``,
``fairlead``, ``fairlead_velocity``, ``failed_index``, ``r`` / ``tension()`` for shapes), so a
floater can use either.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import Environment, Line, Seabed
from floatmoor.errors import SolverError
from floatmoor.mooring import _quasidynamic_kernels as _k
from floatmoor.mooring._catenary_kernels import N_OUT_3D
from floatmoor.mooring._catenary_profile import catenary_profile_3d
from floatmoor.mooring.catenary import describe_failure, solve_catenary
from floatmoor.mooring.dg._kernels import hermite
from floatmoor.mooring.stepping import PathStepper

__all__ = ["QuasiDynamicLine", "QuasiDynamicLineState", "SHAPE_NODES"]

#: Points of the recorded line shape, evenly spaced over the whole line (those of the
#: quasi-static model, so both shapes share an arc-length axis).
SHAPE_NODES = 51


@dataclass(frozen=True)
class QuasiDynamicLineState:
    """A saved state: time, fairlead position and velocity, the static solutions of the last
    two steps (``history``, rows of ``_quasidynamic_kernels.H_*``), the outputs and bookkeeping
    of the last step (``current``, entries ``C_*``), the log references of the stations
    (``references``) and their in-plane positions on the last three static lines
    (``positions``)."""

    time: float
    fairlead: NDArray[np.float64]
    fairlead_velocity: NDArray[np.float64]
    history: NDArray[np.float64]
    current: NDArray[np.float64]
    references: NDArray[np.float64]
    positions: NDArray[np.float64]


class QuasiDynamicLine(PathStepper):
    """A mooring line modelled with the quasi-dynamic factor on the static catenary.

    Parameters
    ----------
    line
        The line's definition: ``line.quasi_dynamic`` (stations, step cap) and
        ``line.quasi_static`` (the catenary's numerics and seabed friction).
    environment
        Water density and depth, gravity.
    seabed
        Its friction coefficient acts on the resting length when
        ``line.quasi_static.seabed_friction`` is true.
    time
        Time of the initial state [s]: the line at rest in the static catenary of its mean
        fairlead position ``line.fairlead`` (:meth:`start_moving` starts it in motion).

    Raises
    ------
    SolverError
        When the static catenary of the initial position has no solution.
    """

    model = "quasi-dynamic"

    def __init__(self, line: Line, environment: Environment, seabed: Seabed, *,
                 time: float = 0.0) -> None:
        lt = line.line_type
        self.line = line
        self.name = line.name
        self.anchor = np.asarray(line.anchor, dtype=float).copy()
        self.length = line.length
        self.axial_stiffness = lt.axial_stiffness
        self.weight = lt.weight_in_water(environment)
        self.friction = seabed.friction_coefficient if line.quasi_static.seabed_friction else 0.0
        self.seabed_z = environment.seabed_z
        self.integration_points = line.quasi_dynamic.integration_points
        self.max_time_step = line.quasi_dynamic.max_time_step
        if self.integration_points < 3 or self.integration_points % 2 == 0:
            raise ValueError("integration_points must be an odd integer >= 3 (composite "
                             f"Simpson rule), got {self.integration_points}")
        prm = np.zeros(_k.N_QPRM)
        prm[_k.Q_L] = line.length
        prm[_k.Q_EA] = lt.axial_stiffness
        prm[_k.Q_W] = self.weight
        prm[_k.Q_CB] = self.friction
        prm[_k.Q_ZB] = self.seabed_z
        prm[_k.Q_TOL] = line.quasi_static.tolerance
        prm[_k.Q_MAXIT] = line.quasi_static.max_iterations
        prm[_k.Q_M] = lt.mass_per_length
        prm[_k.Q_DRAG] = 0.5 * environment.water_density * lt.normal_drag_coefficient \
            * lt.diameter
        prm[_k.Q_MA] = (lt.added_mass_coefficient * environment.water_density
                        * lt.mass_per_length / lt.material_density)
        prm[_k.Q_MAXDT] = self.max_time_step if self.max_time_step is not None else 0.0
        # W <= 0 is refused by the catenary of _start_at_rest below
        prm[_k.Q_INV_W] = 1.0 / self.weight if self.weight > 0.0 else np.nan
        prm[_k.Q_INV_EA] = 1.0 / lt.axial_stiffness
        self.prm = prm
        #: unstretched arc lengths from the anchor of the shape points :attr:`r` [m]
        self.arc_length = np.linspace(0.0, line.length, SHAPE_NODES)
        self._factor1 = np.empty(1)  # k_QD of a one-sample step (the coupled body's)
        self._work = np.zeros(N_OUT_3D)
        self._fpos = np.zeros(3)
        self._fvel = np.zeros(3)
        self._failure = np.zeros(2, dtype=np.int64)
        self.hist = np.zeros((2, _k.N_HIST))
        self.cur = np.zeros(_k.N_CUR)
        self.time = float(time)
        self.fairlead = np.asarray(line.fairlead, dtype=float).copy()
        self.fairlead_velocity = np.zeros(3)
        start = self._static(self.fairlead)
        # stations s_j = L - j h: at rest, integration_points of them span the suspended part
        suspended = line.length - start.laid_length
        if not suspended > 0.0:
            suspended = line.length
        self.station_spacing = suspended / (self.integration_points - 1)
        prm[_k.Q_H] = self.station_spacing
        m = _k.station_count(line.length, self.station_spacing)
        #: unstretched arc lengths from the anchor of the stations [m]
        self.stations = line.length - np.arange(m) * self.station_spacing
        self._jf = np.arange(m, dtype=float)  # station indices, as floats
        self._F = np.zeros(m)
        #: in-plane station positions (x, z) on the last three static lines
        self.X = np.zeros((3, m))
        self.Z = np.zeros((3, m))
        #: two buffers of q and log q per station (the logs' references)
        self.refs = np.zeros((4, m))
        self._start_at_rest(self.fairlead, start)
        #: sample index of the last failure in :meth:`solve_path`, -1 if none
        self.failed_index = -1

    @classmethod
    def from_case(cls, line: Line, environment: Environment, seabed: Seabed
                  ) -> "QuasiDynamicLine":
        """The quasi-dynamic model of a case's line, at rest in its mean position."""
        return cls(line, environment, seabed)

    def _static(self, fairlead: NDArray[np.float64]):
        return solve_catenary(self.anchor, fairlead, self.length, self.axial_stiffness,
                              self.weight, self.friction, seabed_z=self.seabed_z,
                              tol=self.prm[_k.Q_TOL], max_iter=int(self.prm[_k.Q_MAXIT]))

    def _start_at_rest(self, fairlead: NDArray[np.float64], sol) -> None:
        """The static line ``sol`` at ``fairlead``, at rest for all earlier time (k_QD = 1)."""
        for row in range(2):
            self.hist[row, _k.H_FAIRLEAD:_k.H_FAIRLEAD + 3] = fairlead
            self.hist[row, _k.H_HF], self.hist[row, _k.H_VF] = sol.warm_start
            self.hist[row, _k.H_LB] = sol.laid_length
        self.cur[_k.C_K] = 1.0
        self.cur[_k.C_FAIRLEAD_FORCE:_k.C_FAIRLEAD_FORCE + 3] = sol.fairlead_force
        self.cur[_k.C_ANCHOR_FORCE:_k.C_ANCHOR_FORCE + 3] = sol.anchor_force
        self.cur[_k.C_LB] = sol.laid_length
        self.cur[_k.C_DT] = 0.0
        self.cur[_k.C_CHAIN] = _k.CHAIN_STEPS  # the first step evaluates its logs directly
        self.refs[0::2] = 1.0  # q = 1, log q = 0: a valid reference
        self.refs[1::2] = 0.0
        self.cur[_k.C_REF] = 0.0
        plane = _k._plane(self.anchor, *(float(c) for c in fairlead))[1:6]
        for level in range(3):
            self.cur[_k.C_PLANE + 5 * level:_k.C_PLANE + 5 * level + 5] = plane
        self.cur[_k.C_SLOT] = 0.0
        self.cur[_k.C_LO:_k.C_LO + 3] = 1.0  # no station evaluated at any level
        self.cur[_k.C_HI:_k.C_HI + 3] = 0.0

    def start_moving(self, path_state: Callable[[NDArray[np.float64]],
                                                tuple[NDArray[np.float64], NDArray[np.float64]]],
                     sample_interval: float) -> bool:
        """Start on a fairlead path already moving at the line's time, as if the fairlead had
        followed it before (docs/theory/quasi_dynamic.md#the-start-of-a-run).

        The fairlead's positions one and two steps before the start are those of the cubic
        Hermite curve of its positions and velocities at the start and one sample later (the
        curve the model follows between samples), extrapolated back; the line steps from rest
        there to its start. The backward differences of the first steps and k_QD at the start
        are then those of a path in motion, not of a line at rest (k_QD = 1) whose first step
        meets the whole fairlead velocity at once. A fairlead at rest at the start (zero
        velocity) keeps the start at rest, bit for bit.

        Parameters
        ----------
        path_state
            Fairlead positions [m] and velocities [m/s], (n, 3) each, at times (n,) [s]; at
            the line's time its position is the line's fairlead.
        sample_interval
            Time between the samples the line will be stepped along [s], > 0; the history's
            step is that of the first interval (split by ``max_time_step``).

        Returns
        -------
        bool
            Whether the fairlead moves at the start (and the history was set).

        Raises
        ------
        SolverError
            When a static catenary before the start has no solution.
        ValueError
            When the line has already been stepped, or the interval is not positive.
        """
        if self.cur[_k.C_DT] != 0.0:
            raise ValueError(f"line '{self.name}' (quasi-dynamic): start_moving before the "
                             "first step only")
        interval = float(sample_interval)
        if not interval > 0.0:
            raise ValueError(f"sample_interval must be > 0, got {sample_interval!r}")
        t0 = self.time
        positions, velocities = path_state(np.array([t0, t0 + interval]))
        v0 = np.array(velocities[0], dtype=float)
        if not np.any(v0 != 0.0):
            return False
        p1 = np.array(positions[1], dtype=float)
        v1 = np.array(velocities[1], dtype=float)
        steps = 1  # the kernel's split of a sample interval (quasi_dynamic_series)
        if self.max_time_step is not None and interval > self.max_time_step:
            steps = int(np.ceil(interval / self.max_time_step * (1.0 - 1e-12)))
        dt = interval / steps
        times = np.array([t0 - 2.0 * dt, t0 - dt, t0])
        path = np.zeros((3, 3))
        velocity = np.zeros((3, 3))
        for i in range(2):
            hermite(t0, t0 + interval, self.fairlead, v0, p1, v1, times[i], path[i],
                    velocity[i])
        path[2], velocity[2] = self.fairlead, v0
        self._start_at_rest(path[0], self._static(path[0]))
        self.time = float(times[0])
        self.fairlead[:] = path[0]
        self.fairlead_velocity[:] = velocity[0]
        n = 2
        self.solve_path(times[1:], path[1:], velocity[1:], np.zeros((n, 3)), np.zeros((n, 3)),
                        np.zeros(n), np.zeros(n))
        return True

    # -- stepping ------------------------------------------------------------------------------
    def solve_path(self, time: NDArray[np.float64], path: NDArray[np.float64],
                   velocity: NDArray[np.float64], fairlead_force: NDArray[np.float64],
                   anchor_force: NDArray[np.float64], laid_length: NDArray[np.float64],
                   iterations: NDArray[np.float64], *,
                   factor: NDArray[np.float64] | None = None) -> None:
        """Step along a fairlead path, recording the end forces at every sample.

        Parameters
        ----------
        time
            Sample times [s], increasing, with ``time[0] >= self.time``. When
            ``time[0] == self.time`` sample 0 is the current state.
        path, velocity
            Fairlead positions [m] and velocities [m/s] at the samples, shape (n, 3). The
            velocities only shape the fairlead's path between samples when sub-stepping
            (``max_time_step``); the model's own velocities are the backward differences.
        fairlead_force, anchor_force
            Outputs: forces exerted by the line on its fairlead and anchor [N], (n, 3).
        laid_length
            Output: unstretched length resting on the seabed [m], (n,).
        iterations
            Output: Newton iterations of the catenary per sample, (n,).
        factor
            Optional output: the quasi-dynamic factor k_QD per sample, (n,).

        Raises
        ------
        SolverError
            Naming the line, the time and why the catenary has no solution there; the outputs
            before that sample are valid, the line's state is not (restore a saved one).
        ValueError
            When the times do not increase from the line's time.
        """
        time = np.ascontiguousarray(time, dtype=float)
        path = np.ascontiguousarray(path, dtype=float)
        velocity = np.ascontiguousarray(velocity, dtype=float)
        n = time.size
        if n == 0:
            return
        if time[0] < self.time or (n > 1 and np.any(np.diff(time) <= 0.0)):
            raise ValueError(f"line '{self.name}' (quasi-dynamic): sample times must increase "
                             f"from the line's time {self.time:.6g} s")
        if factor is None:
            factor = self._factor1 if n == 1 else np.empty(n)
        index = _k.quasi_dynamic_series(
            self.anchor, self.time, self.fairlead, self.fairlead_velocity, time, path, velocity,
            self.prm, self.hist, self.cur, self.X, self.Z, self.refs[0], self.refs[1],
            self.refs[2], self.refs[3], self._F, self._jf, self._work, self._fpos, self._fvel, fairlead_force, anchor_force,
            laid_length, iterations, factor, self._failure)
        if index >= 0:
            self.failed_index = index
            point = path[index]
            span = np.subtract(point, self.anchor)
            reason = describe_failure(int(self._failure[1]), float(np.hypot(span[0], span[1])),
                                      float(span[2]), self.length, self.axial_stiffness,
                                      self.weight)
            raise SolverError(f"line '{self.name}' (quasi-dynamic): fairlead force at t = "
                              f"{time[index]:.6g} s, fairlead at "
                              f"{np.array2string(point, precision=6)} m: {reason}")
        self.failed_index = -1
        self.time = float(time[-1])
        self.fairlead[:] = path[-1]
        self.fairlead_velocity[:] = velocity[-1]

    # -- state ---------------------------------------------------------------------------------
    def get_state(self) -> QuasiDynamicLineState:
        """A copy of the current state."""
        return QuasiDynamicLineState(self.time, self.fairlead.copy(),
                                     self.fairlead_velocity.copy(), self.hist.copy(),
                                     self.cur.copy(), self.refs.copy(),
                                     np.stack((self.X, self.Z)))

    def set_state(self, state: QuasiDynamicLineState) -> None:
        """Restore a state saved by :meth:`get_state`."""
        self.time = state.time
        self.fairlead[:] = state.fairlead
        self.fairlead_velocity[:] = state.fairlead_velocity
        self.hist[:] = state.history
        self.cur[:] = state.current
        self.refs[:] = state.references
        self.X[:], self.Z[:] = state.positions

    def state_arrays(self) -> dict[str, NDArray[np.float64]]:
        """The state of :meth:`get_state` as named arrays (time 0-d), for a checkpoint of
        plain numeric data."""
        s = self.get_state()
        return {"time": np.array(s.time, dtype=np.float64), "fairlead": s.fairlead,
                "fairlead_velocity": s.fairlead_velocity, "history": s.history,
                "current": s.current, "references": s.references, "positions": s.positions}

    def set_state_arrays(self, arrays: dict[str, NDArray[np.float64]]) -> None:
        """Restore a state of :meth:`state_arrays` (shapes checked by the caller)."""
        self.set_state(QuasiDynamicLineState(
            float(arrays["time"]), *(np.asarray(arrays[k], dtype=float) for k in (
                "fairlead", "fairlead_velocity", "history", "current", "references",
                "positions"))))

    @property
    def factor(self) -> float:
        """The quasi-dynamic factor k_QD of the current state [-]."""
        return float(self.cur[_k.C_K])

    @property
    def laid_length(self) -> float:
        """Unstretched length resting on the seabed in the current state [m]."""
        return float(self.cur[_k.C_LB])

    def end_forces(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Forces the line exerts on its fairlead and anchor in the current state [N]."""
        return (self.cur[_k.C_FAIRLEAD_FORCE:_k.C_FAIRLEAD_FORCE + 3].copy(),
                self.cur[_k.C_ANCHOR_FORCE:_k.C_ANCHOR_FORCE + 3].copy())

    # -- shape ---------------------------------------------------------------------------------
    def shape(self, arc_lengths: NDArray[np.float64] | None = None
              ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Positions (n, 3) [m] and effective tensions (n,) [N] of the current state.

        The shape is the static catenary; the tension is that of the apparent-weight catenary:
        k_QD times the static tension on the suspended part, and on the resting part the
        touchdown tension k_QD H reduced by seabed friction, floored at zero.

        Parameters
        ----------
        arc_lengths
            Unstretched arc lengths from the anchor [m]; default :attr:`arc_length`.
        """
        s = self.arc_length if arc_lengths is None else np.ascontiguousarray(
            arc_lengths, dtype=np.float64).reshape(-1)
        row = self.hist[0]
        fairlead = np.ascontiguousarray(row[_k.H_FAIRLEAD:_k.H_FAIRLEAD + 3])
        positions = np.empty((s.size, 3))
        static = np.empty(s.size)
        catenary_profile_3d(self.anchor, fairlead, self.length, self.axial_stiffness,
                            self.weight, self.friction, self.seabed_z, row[_k.H_HF],
                            row[_k.H_VF], s, positions, static)
        k, laid = self.factor, self.laid_length
        sigma = self.length - s if fairlead[2] < self.anchor[2] else s  # from the lower end
        resting = np.maximum(k * row[_k.H_HF] - self.friction * self.weight * (laid - sigma), 0.0)
        return positions, np.where(sigma >= laid, k * static, resting)

    @property
    def r(self) -> NDArray[np.float64]:
        """Positions of the shape points :attr:`arc_length` in the current state [m], (n, 3)."""
        return self.shape()[0]

    def tension(self) -> NDArray[np.float64]:
        """Effective tension at the shape points :attr:`arc_length` [N], (n,)."""
        return self.shape()[1]

    def __repr__(self) -> str:
        return (f"QuasiDynamicLine('{self.name}', {self.integration_points} stations, "
                f"t = {self.time:.6g} s, k_QD = {self.factor:.6g})")
