"""The step API shared by the line models with memory (dynamic, quasi-dynamic).

The models implement ``solve_path`` (a whole fairlead path at once); :meth:`PathStepper.advance`
is that path with one sample. A coupled run advances a quasi-dynamic line with one-sample paths
to the half and the full body step, and its dynamic lines once per body step over both samples
(:mod:`floatmoor.mooring.dg.batch`; docs/theory/floater.md#coupling-scheme). Forced-motion
runs pass these models the fairlead velocity, and record their shape from their current state
(``r``, ``tension()`` at ``arc_length``).
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import NDArray

__all__ = ["PathStepper"]


class PathStepper(ABC):
    """Base of line models advanced along a prescribed fairlead path."""

    @abstractmethod
    def solve_path(self, time: NDArray[np.float64], path: NDArray[np.float64],
                   velocity: NDArray[np.float64], fairlead_force: NDArray[np.float64],
                   anchor_force: NDArray[np.float64], laid_length: NDArray[np.float64],
                   steps: NDArray[np.float64]) -> None:
        """Advance along the path, writing the outputs at every sample."""

    def end_forces_moving(self, fairlead_velocity: NDArray[np.float64]
                          ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Forces the line exerts on its fairlead and anchor [N] in its current state, with
        the fairlead moving at ``fairlead_velocity`` instead of the velocity its last step
        left it with. A model whose end force answers the fairlead's velocity at once (the
        dynamic line's end flux holds its axial impedance) overrides this; the default is
        :meth:`end_forces` (the quasi-dynamic force is a function of its steps' path)."""
        return self.end_forces()

    @abstractmethod
    def end_forces(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Forces the line exerts on its fairlead and anchor in the current state [N]."""

    def advance(self, t1: float, fairlead: NDArray[np.float64],
                fairlead_velocity: NDArray[np.float64]) -> NDArray[np.float64]:
        """Advance from the current time to ``t1``, the fairlead moving (cubic Hermite) from
        its current position and velocity to ``fairlead`` and ``fairlead_velocity``.

        Returns
        -------
        ndarray
            The force the line exerts on the fairlead at ``t1`` [N], shape (3,).
        """
        ff, af = np.zeros((1, 3)), np.zeros((1, 3))
        self.solve_path(np.array([float(t1)]), np.asarray(fairlead, dtype=float)[None, :],
                        np.asarray(fairlead_velocity, dtype=float)[None, :], ff, af,
                        np.zeros(1), np.zeros(1))
        return ff[0]
