"""The Cummins equation of a rigid floating body (docs/theory/floater.md; gpc paper eq. 8):

    (M + A_inf) x'' + mu(t) + C x = F_0 + f(t, x, x') + f_lin + f_quad,
    mu(t) = int_0^t K(t - tau) x'(tau) d tau,

with M the rigid-body mass matrix and A_inf the infinite-frequency added mass about the
reference point, C the hydrostatic and gravity stiffness, F_0 the constant buoyancy minus
weight (and their moments), f the external forces (wave excitation, mooring lines, member
drag, given by the caller), and optional linear and quadratic damping matrices
f_lin = -B_1 x', f_quad = -B_2 |x'| x'.

Time integration: the classical fourth-order Runge-Kutta scheme on (x, x') at a fixed step dt.
The memory mu has two paths:

* convolution (default): K, truncated, convolved with the velocities at the step points
  taken piecewise linear (``_memory_kernels``: weights from a finely sampled K); inside a
  step it is extrapolated linearly from its last two values (second order, so that it adds
  no phase lag of dt / 2 to the radiation damping);
* state space (``radiation_states``, :class:`~floatmoor.body.state_space_radiation.
  RadiationStates`): mu = C z + D v with z' = A z + B v, the realisations of K_ij of
  :mod:`floatmoor.hydro.state_space`; the states are integrated in the same RK4 step as
  (x, x'), each stage's z from that stage's velocity
  (:mod:`~floatmoor.body._state_space_radiation_kernels`), so the whole system is
  fourth-order consistent.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from floatmoor.body._memory_kernels import hat_weights, memory_force
from floatmoor.body._state_space_radiation_kernels import radiation_combine, radiation_stage
from floatmoor.body.state_space_radiation import RadiationStates
from floatmoor.hydro.radiation import KERNEL_NEGLIGIBLE

__all__ = ["CumminsBody", "BodyState", "ForceFunction"]

#: f(t, x, x') -> external 6-DOF force [N, N m]
ForceFunction = Callable[[float, NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]


@dataclass
class BodyState:
    """A saved state of :class:`CumminsBody`: everything its next steps depend on.

    Made by :meth:`CumminsBody.get_state` and given back to :meth:`CumminsBody.set_state`
    (a checkpoint stores it as :meth:`CumminsBody.state_arrays`), so that a body set to it
    continues to bit-identical results. The arrays are copies, not views of the body's.

    Attributes
    ----------
    time
        Time of the state [s].
    position
        (6,) displacement from the reference position: surge, sway, heave [m], roll,
        pitch, yaw [rad].
    velocity
        (6,) its time derivative [m/s, rad/s].
    history
        (m, 6) ring buffer of the velocities at the past m steps, for the radiation memory
        (convolution path; zero on the state-space path).
    newest
        Index in ``history`` of the latest velocity.
    filled
        How many slots of ``history`` hold real velocities (the older ones are the rest
        state, zero).
    memory, memory_before
        (6,) radiation memory force mu at the state's step and at the step before [N, N m]
        (the force within a step is extrapolated from both; zero on the state-space path).
    radiation
        The state-space path's radiation states z, or None on the convolution path.
    """

    time: float
    position: NDArray[np.float64]
    velocity: NDArray[np.float64]
    history: NDArray[np.float64]
    newest: int
    filled: int
    memory: NDArray[np.float64]
    memory_before: NDArray[np.float64]
    #: state-space path: the radiation states z (None on the convolution path, whose memory
    #: is ``history`` and ``memory``; those stay empty on the state-space path)
    radiation: NDArray[np.float64] | None = None


class CumminsBody:
    """A rigid body integrated with the Cummins equation.

    Parameters
    ----------
    mass_matrix, added_mass_infinite, stiffness
        M, A_inf and C (6, 6) about the reference point.
    static_force
        F_0 (6,): buoyancy minus weight and their moments at the reference position.
    kernel
        (t, K(t)): K on a uniform grid from 0 whose step divides dt, (n,) and (n, 6, 6) with
        indices (radiating, influenced) as a capytaine database's damping; None for no
        radiation memory.
    dt
        Time step [s].
    linear_damping, quadratic_damping
        B_1, B_2 (6, 6) or None.
    radiation_states
        The state-space radiation (then ``kernel`` must be None): the memory is C z + D v of
        states integrated with the body.
    kernel_start
        (t, K(t)) sampled more finely over [0, 2 dt] for the first two memory weights (a
        kernel with a cusp at t = 0; see :func:`~floatmoor.body._memory_kernels.hat_weights`).
    """

    def __init__(self, mass_matrix: NDArray[np.float64], added_mass_infinite: NDArray[np.float64],
                 stiffness: NDArray[np.float64], static_force: NDArray[np.float64],
                 kernel: tuple[NDArray[np.float64], NDArray[np.float64]] | None, dt: float, *,
                 linear_damping: NDArray[np.float64] | None = None,
                 quadratic_damping: NDArray[np.float64] | None = None,
                 radiation_states: RadiationStates | None = None,
                 kernel_start: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
                 ) -> None:
        if not dt > 0.0:
            raise ValueError(f"time step must be positive, got {dt}")
        self.dt = float(dt)
        self.mass = np.asarray(mass_matrix, float) + np.asarray(added_mass_infinite, float)
        self.inverse_mass = np.linalg.inv(self.mass)
        self.stiffness = np.asarray(stiffness, float)
        self.static_force = np.asarray(static_force, float)
        self.linear_damping = None if linear_damping is None else np.asarray(linear_damping, float)
        self.quadratic_damping = (None if quadratic_damping is None
                                  else np.asarray(quadratic_damping, float))
        if kernel is None:
            weights = np.zeros((1, 6, 6))
        else:
            weights = hat_weights(np.asarray(kernel[0], float), np.asarray(kernel[1], float),
                                  self.dt, start=kernel_start)
        # (influenced, radiating) for mu_i = sum_j W_ij * v_j
        self.weights = np.ascontiguousarray(np.transpose(weights, (0, 2, 1)))
        peak = float(np.abs(self.weights).max())
        nz = np.argwhere(np.abs(self.weights).max(axis=0) > KERNEL_NEGLIGIBLE * peak) \
            if peak > 0.0 else np.zeros((0, 2), dtype=np.int64)
        self.pairs = np.ascontiguousarray(nz.astype(np.int64))
        m = self.weights.shape[0]
        self.history = np.zeros((m, 6))
        self.newest = m - 1
        self.filled = 0
        self.time = 0.0
        self.x = np.zeros(6)
        self.v = np.zeros(6)
        self.memory = np.zeros(6)
        self.memory_before = np.zeros(6)
        self.radiation_states = radiation_states
        if radiation_states is not None:
            if kernel is not None:
                raise ValueError("give the kernel or the radiation states, not both")
            if radiation_states.max_amplification(self.dt) >= 1.0:
                raise ValueError(f"a radiation state is unstable under RK4 at dt = {dt} s")
            n = radiation_states.n_states
            self.z = np.zeros(n)
            self._stage_z = np.zeros(n)
            self._stage_k = np.zeros((4, n))
            self._stage_mu = np.zeros(6)

    @property
    def radiation(self) -> str:
        """The radiation path: ``"convolution"`` or ``"state-space"``."""
        return "convolution" if self.radiation_states is None else "state-space"

    # -- state -----------------------------------------------------------------------------
    def start(self, time: float, position: NDArray[np.float64],
              velocity: NDArray[np.float64] | None = None) -> None:
        """Set the initial state (the body at rest before ``time`` unless ``velocity``)."""
        self.time = float(time)
        self.x = np.array(position, dtype=float)
        self.v = np.zeros(6) if velocity is None else np.array(velocity, dtype=float)
        self.history[:] = 0.0
        self.filled = 0
        if self.radiation_states is not None:
            self.z = np.zeros(self.radiation_states.n_states)  # the rest history
            return
        self._push(self.v)
        self.memory_before = self.memory.copy()

    def get_state(self) -> BodyState:
        """A copy of the whole state (body, memory history, radiation states)."""
        return BodyState(self.time, self.x.copy(), self.v.copy(), self.history.copy(),
                         self.newest, self.filled, self.memory.copy(), self.memory_before.copy(),
                         None if self.radiation_states is None else self.z.copy())

    def set_state(self, state: BodyState) -> None:
        """Restore a state of :meth:`get_state`."""
        if self.radiation_states is not None and (
                state.radiation is None or state.radiation.shape != self.z.shape):
            raise ValueError("the state has no radiation states of this body")
        self.time = state.time
        self.x = state.position.copy()
        self.v = state.velocity.copy()
        self.history[:] = state.history
        self.newest = state.newest
        self.filled = state.filled
        self.memory = state.memory.copy()
        self.memory_before = state.memory_before.copy()
        if self.radiation_states is not None:
            self.z = state.radiation.copy()

    def state_arrays(self) -> dict[str, NDArray]:
        """The state of :meth:`get_state` as named arrays (0-d for scalars), for a checkpoint
        of plain numeric data; ``radiation`` only on the state-space path."""
        s = self.get_state()
        out: dict[str, NDArray] = {
            "time": np.array(s.time, dtype=np.float64), "position": s.position,
            "velocity": s.velocity, "history": s.history,
            "newest": np.array(s.newest, dtype=np.int64),
            "filled": np.array(s.filled, dtype=np.int64), "memory": s.memory,
            "memory_before": s.memory_before}
        if s.radiation is not None:
            out["radiation"] = s.radiation
        return out

    def set_state_arrays(self, arrays: dict[str, NDArray]) -> None:
        """Restore a state of :meth:`state_arrays` (shapes checked by the caller)."""
        self.set_state(BodyState(
            float(arrays["time"]), np.array(arrays["position"], dtype=float),
            np.array(arrays["velocity"], dtype=float), np.array(arrays["history"], dtype=float),
            int(arrays["newest"]), int(arrays["filled"]),
            np.array(arrays["memory"], dtype=float),
            np.array(arrays["memory_before"], dtype=float),
            None if "radiation" not in arrays else np.array(arrays["radiation"], dtype=float)))

    def _push(self, v: NDArray[np.float64]) -> None:
        m = self.history.shape[0]
        self.newest = (self.newest + 1) % m
        self.history[self.newest] = v
        self.filled = min(self.filled + 1, m)
        out = np.zeros(6)
        memory_force(self.weights, self.pairs, self.history, self.newest, self.filled, out)
        self.memory = out

    # -- dynamics --------------------------------------------------------------------------
    def internal_force(self, x: NDArray[np.float64], v: NDArray[np.float64],
                       tau: float) -> NDArray[np.float64]:
        """F_0 - C x - mu - B_1 v - B_2 ``|v|`` v at ``tau`` into the current step (convolution
        path: mu extrapolated from the step points; state-space path: mu = C z + D v of the
        states at the start of the step, ``tau`` unused)."""
        if self.radiation_states is not None:
            rs = self.radiation_states
            n = rs.n_states
            mu = np.zeros(6)
            radiation_stage(rs.a, rs.b, rs.c, rs.offsets, rs.radiating, rs.influenced,
                            rs.feedthrough, self.z, np.zeros(n), 0.0, np.asarray(v, float),
                            np.zeros(n), np.zeros(n), mu)
            return self._force_with_memory(x, v, mu)
        mu = self.memory + (self.memory - self.memory_before) * (tau / self.dt)
        return self._force_with_memory(x, v, mu)

    def _force_with_memory(self, x: NDArray[np.float64], v: NDArray[np.float64],
                           mu: NDArray[np.float64]) -> NDArray[np.float64]:
        f = self.static_force - self.stiffness @ x - mu
        if self.linear_damping is not None:
            f -= self.linear_damping @ v
        if self.quadratic_damping is not None:
            f -= self.quadratic_damping @ (np.abs(v) * v)
        return f

    def acceleration(self, x: NDArray[np.float64], v: NDArray[np.float64], tau: float,
                     external: NDArray[np.float64]) -> NDArray[np.float64]:
        """x'' from the Cummins equation with the external force ``external``."""
        return self.inverse_mass @ (self.internal_force(x, v, tau) + external)

    def step(self, force: Callable[[int, float, NDArray[np.float64], NDArray[np.float64]],
                                   NDArray[np.float64]]) -> NDArray[np.float64]:
        """One RK4 step of length dt; ``force(stage, tau, x, v)`` gives the external force at
        stage 0..3 (tau = 0, dt/2, dt/2, dt). Returns the acceleration of stage 0."""
        if self.radiation_states is not None:
            return self._step_state_space(force)
        dt = self.dt
        h = 0.5 * dt
        x0, v0 = self.x, self.v
        a1 = self.acceleration(x0, v0, 0.0, force(0, 0.0, x0, v0))
        x2, v2 = x0 + h * v0, v0 + h * a1
        a2 = self.acceleration(x2, v2, h, force(1, h, x2, v2))
        x3, v3 = x0 + h * v2, v0 + h * a2
        a3 = self.acceleration(x3, v3, h, force(2, h, x3, v3))
        x4, v4 = x0 + dt * v3, v0 + dt * a3
        a4 = self.acceleration(x4, v4, dt, force(3, dt, x4, v4))
        self.x = x0 + dt / 6.0 * (v0 + 2.0 * v2 + 2.0 * v3 + v4)
        self.v = v0 + dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
        self.time += dt
        self.memory_before = self.memory
        self._push(self.v)
        return a1

    def _step_state_space(self, force: Callable[[int, float, NDArray[np.float64],
                                                 NDArray[np.float64]], NDArray[np.float64]]
                          ) -> NDArray[np.float64]:
        """RK4 on (x, x', z): each stage's radiation force C z_s + D v_s and derivative
        A z_s + B v_s from the compiled stage kernel."""
        rs = self.radiation_states
        assert rs is not None
        dt = self.dt
        h = 0.5 * dt
        k, zs, mu = self._stage_k, self._stage_z, self._stage_mu
        x0, v0, z0 = self.x, self.v, self.z
        args = (rs.a, rs.b, rs.c, rs.offsets, rs.radiating, rs.influenced, rs.feedthrough, z0)
        radiation_stage(*args, k[3], 0.0, v0, zs, k[0], mu)
        a1 = self.inverse_mass @ (self._force_with_memory(x0, v0, mu) + force(0, 0.0, x0, v0))
        x2, v2 = x0 + h * v0, v0 + h * a1
        radiation_stage(*args, k[0], h, v2, zs, k[1], mu)
        a2 = self.inverse_mass @ (self._force_with_memory(x2, v2, mu) + force(1, h, x2, v2))
        x3, v3 = x0 + h * v2, v0 + h * a2
        radiation_stage(*args, k[1], h, v3, zs, k[2], mu)
        a3 = self.inverse_mass @ (self._force_with_memory(x3, v3, mu) + force(2, h, x3, v3))
        x4, v4 = x0 + dt * v3, v0 + dt * a3
        radiation_stage(*args, k[2], dt, v4, zs, k[3], mu)
        a4 = self.inverse_mass @ (self._force_with_memory(x4, v4, mu) + force(3, dt, x4, v4))
        self.x = x0 + dt / 6.0 * (v0 + 2.0 * v2 + 2.0 * v3 + v4)
        self.v = v0 + dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
        z = np.empty_like(z0)
        radiation_combine(z0, k[0], k[1], k[2], k[3], dt, z)
        self.z = z
        self.time += dt
        return a1
