"""The quasi-static line model: an elastic catenary in equilibrium at every instant.

The line has no memory beyond the Newton warm start: its fairlead and anchor forces are those
of the static elastic catenary with seabed contact (and optional seabed friction) for the
current fairlead position (docs/theory/quasi_static.md). It neglects line inertia and drag, which is
why it underestimates dynamic tension (quasi-dynamic paper, section 5).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import Environment, Line, Seabed
from floatmoor.errors import SolverError
from floatmoor.mooring._catenary_kernels import N_OUT_3D
from floatmoor.mooring._quasistatic_kernels import quasi_static_series
from floatmoor.mooring.catenary import (
    CatenarySolution, catenary_profile, describe_failure, solve_catenary,
)
from floatmoor.mooring.stepping import PathStepper

__all__ = ["QuasiStaticLine", "SHAPE_POINTS"]


#: Points at which a quasi-static line's shape is recorded (equally spaced in arc length).
SHAPE_POINTS = 51


class QuasiStaticLine(PathStepper):
    """A mooring line modelled as a quasi-static elastic catenary.

    Parameters
    ----------
    line
        The line's definition.
    environment
        Water density and depth, gravity.
    seabed
        Its friction coefficient acts on the resting length when
        ``line.quasi_static.seabed_friction`` is true.
    """

    model = "quasi-static"
    has_memory = False  # solved at each instant (its warm start is its only state)

    def __init__(self, line: Line, environment: Environment, seabed: Seabed) -> None:
        self.line = line
        self.name = line.name
        self.anchor = np.asarray(line.anchor, dtype=float)
        self.length = line.length
        #: unstretched arc lengths from the anchor of the recorded shape points [m] (as the
        #: models with memory have)
        self.arc_length = np.linspace(0.0, line.length, SHAPE_POINTS)
        self.axial_stiffness = line.line_type.axial_stiffness
        self.weight = line.line_type.weight_in_water(environment)
        self.friction = seabed.friction_coefficient if line.quasi_static.seabed_friction else 0.0
        self.seabed_z = environment.seabed_z
        self.tolerance = line.quasi_static.tolerance
        self.max_iterations = line.quasi_static.max_iterations
        self._warm = np.full(2, np.nan)
        self._work = np.zeros(N_OUT_3D)
        self._failure = np.zeros(2, dtype=np.int64)
        #: Index in the last path where the solve failed, -1 if it did not.
        self.failed_index = -1
        #: the fairlead of the last solved sample (:meth:`end_forces`) [m]
        self._fairlead = np.asarray(line.fairlead, dtype=float).copy()

    @classmethod
    def from_case(cls, line: Line, environment: Environment, seabed: Seabed) -> "QuasiStaticLine":
        """The quasi-static model of a case's line."""
        return cls(line, environment, seabed)

    def state_arrays(self) -> dict[str, NDArray[np.float64]]:
        """The line's only memory, the Newton warm start (upper-end HF, VF; NaN: none), as
        named arrays for a checkpoint: it decides the iterates, hence the last bits, of the
        next solutions."""
        return {"warm_start": self._warm.copy()}

    def set_state_arrays(self, arrays: dict[str, NDArray[np.float64]]) -> None:
        """Restore a state of :meth:`state_arrays`."""
        self._warm[:] = arrays["warm_start"]

    def profile(self, fairlead: NDArray[np.float64], arc_lengths: NDArray[np.float64]
                ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Node positions (n, 3) [m] and tensions (n,) [N] of the static line."""
        solution = self.solve(fairlead)
        return catenary_profile(self.anchor, np.asarray(fairlead, dtype=float), self.length,
                                self.axial_stiffness, self.weight, self.friction,
                                seabed_z=self.seabed_z, arc_lengths=arc_lengths,
                                solution=solution)

    def current_shape(self, fairlead: NDArray[np.float64]
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Node positions (n, 3) [m] and tensions (n,) [N] at :attr:`arc_length` of the
        static line with its fairlead at ``fairlead`` (warm-started, updates the warm
        start)."""
        return self.profile(fairlead, self.arc_length)

    def end_forces(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Forces the line exerts on its fairlead and anchor [N] at the fairlead of its last
        solved sample (the warm start left as it is)."""
        guess = (self._warm[0], self._warm[1]) if np.all(np.isfinite(self._warm)) else None
        sol = solve_catenary(self.anchor, self._fairlead, self.length, self.axial_stiffness,
                             self.weight, self.friction, seabed_z=self.seabed_z,
                             initial_guess=guess, tol=self.tolerance,
                             max_iter=self.max_iterations)
        return (np.asarray(sol.fairlead_force, dtype=float),
                np.asarray(sol.anchor_force, dtype=float))

    def solve(self, fairlead: NDArray[np.float64]) -> CatenarySolution:
        """Static solution for one fairlead position (warm-started, updates the warm start)."""
        guess = (self._warm[0], self._warm[1]) if np.all(np.isfinite(self._warm)) else None
        solution = solve_catenary(self.anchor, np.asarray(fairlead, dtype=float), self.length,
                                  self.axial_stiffness, self.weight, self.friction,
                                  seabed_z=self.seabed_z, initial_guess=guess,
                                  tol=self.tolerance, max_iter=self.max_iterations)
        self._warm[:] = solution.warm_start  # upper-end (HF, VF), whichever end is which
        return solution

    def solve_path(self, time: NDArray[np.float64], path: NDArray[np.float64],
                   velocity: NDArray[np.float64], fairlead_force: NDArray[np.float64],
                   anchor_force: NDArray[np.float64], laid_length: NDArray[np.float64],
                   iterations: NDArray[np.float64]) -> None:
        """Solve along a fairlead path, writing into the given arrays.

        Parameters
        ----------
        time
            Times of the path [s], shape (n,), used in error messages.
        path
            Fairlead positions [m], shape (n, 3).
        velocity
            Fairlead velocities [m/s], (n, 3): the protocol's argument (a static line does
            not use them).
        fairlead_force, anchor_force
            Outputs [N], shape (n, 3).
        laid_length, iterations
            Outputs, shape (n,).

        Raises
        ------
        SolverError
            Naming the line, the time and why the catenary has no solution there; the outputs
            before that time are valid.
        """
        index = quasi_static_series(self.anchor, np.ascontiguousarray(path), self.length,
                                    self.axial_stiffness, self.weight, self.friction,
                                    self.seabed_z, self.tolerance, self.max_iterations,
                                    self._warm, self._work, fairlead_force, anchor_force,
                                    laid_length, iterations, self._failure)
        self.failed_index = index
        if index >= 0:
            status = int(self._failure[1])
            point = path[index]
            span = np.subtract(point, self.anchor)
            reason = describe_failure(status, float(np.hypot(span[0], span[1])), float(span[2]),
                                      self.length, self.axial_stiffness, self.weight)
            raise SolverError(f"line '{self.name}' (quasi-static): fairlead force at t = "
                              f"{time[index]:.6g} s, fairlead at {np.array2string(point, precision=6)}"
                              f" m: {reason}")
        if len(path):
            self._fairlead[:] = path[-1]
