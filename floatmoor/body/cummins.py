"""The Cummins equation of a rigid floating body (physics.md section 5; gpc paper eq. 8):

    (M + A_inf) x'' + mu(t) + C x = F_0 + f(t, x, x') + f_lin + f_quad,
    mu(t) = int_0^t K(t - tau) x'(tau) d tau,

with M the rigid-body mass matrix and A_inf the infinite-frequency added mass about the
reference point, C the hydrostatic and gravity stiffness, F_0 the constant buoyancy minus
weight (and their moments), f the external forces (wave excitation, mooring lines, member
drag, given by the caller), and optional linear and quadratic damping matrices
f_lin = -B_1 x', f_quad = -B_2 |x'| x'.

Time integration: the classical fourth-order Runge-Kutta scheme on (x, x') at a fixed step dt.
The memory mu convolves K, truncated, with the velocities at the step points taken piecewise
linear (``_memory_kernels``: weights from a finely sampled K); inside a step it is
extrapolated linearly from its last two values (second order, so that it adds no phase lag
of dt / 2 to the radiation damping).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from floatmoor.body._memory_kernels import hat_weights, memory_force

__all__ = ["CumminsBody", "BodyState", "ForceFunction"]

#: f(t, x, x') -> external 6-DOF force [N, N m]
ForceFunction = Callable[[float, NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]
#: Kernel entries below this fraction of the largest are not summed.
_KERNEL_NEGLIGIBLE = 1e-12


@dataclass
class BodyState:
    """A saved state of :class:`CumminsBody`."""

    time: float
    position: NDArray[np.float64]
    velocity: NDArray[np.float64]
    history: NDArray[np.float64]
    newest: int
    filled: int
    memory: NDArray[np.float64]
    memory_before: NDArray[np.float64]


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
    """

    def __init__(self, mass_matrix: NDArray[np.float64], added_mass_infinite: NDArray[np.float64],
                 stiffness: NDArray[np.float64], static_force: NDArray[np.float64],
                 kernel: tuple[NDArray[np.float64], NDArray[np.float64]] | None, dt: float, *,
                 linear_damping: NDArray[np.float64] | None = None,
                 quadratic_damping: NDArray[np.float64] | None = None) -> None:
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
                                  self.dt)
        # (influenced, radiating) for mu_i = sum_j W_ij * v_j
        self.weights = np.ascontiguousarray(np.transpose(weights, (0, 2, 1)))
        peak = float(np.abs(self.weights).max())
        nz = np.argwhere(np.abs(self.weights).max(axis=0) > _KERNEL_NEGLIGIBLE * peak) \
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

    # -- state -----------------------------------------------------------------------------
    def start(self, time: float, position: NDArray[np.float64],
              velocity: NDArray[np.float64] | None = None) -> None:
        """Set the initial state (the body at rest before ``time`` unless ``velocity``)."""
        self.time = float(time)
        self.x = np.array(position, dtype=float)
        self.v = np.zeros(6) if velocity is None else np.array(velocity, dtype=float)
        self.history[:] = 0.0
        self.filled = 0
        self._push(self.v)
        self.memory_before = self.memory.copy()

    def get_state(self) -> BodyState:
        return BodyState(self.time, self.x.copy(), self.v.copy(), self.history.copy(),
                         self.newest, self.filled, self.memory.copy(), self.memory_before.copy())

    def set_state(self, state: BodyState) -> None:
        self.time = state.time
        self.x = state.position.copy()
        self.v = state.velocity.copy()
        self.history[:] = state.history
        self.newest = state.newest
        self.filled = state.filled
        self.memory = state.memory.copy()
        self.memory_before = state.memory_before.copy()

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
        """F_0 - C x - mu - B_1 v - B_2 |v| v at ``tau`` into the current step."""
        mu = self.memory + (self.memory - self.memory_before) * (tau / self.dt)
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
