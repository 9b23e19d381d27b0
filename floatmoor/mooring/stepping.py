"""The protocol every line model and mooring-system solver implements, and what a run asks of
them (docs/development.md#adding-a-line-model).

:class:`MooringSolver` is what both kinds share: ``solve_path(time, path, velocity, *outputs)``
advances (or, without memory, solves) the model along a path of its body-side ends, always
in that argument order: the sample times, the ends' positions and velocities, then the
outputs (the forces on the two ends of each line or section, the laid lengths, for a system
its points' positions, and the steps or Newton iterations per sample). Capabilities the runs
query instead of testing the class: :attr:`~MooringSolver.has_memory` (a state carried from
step to step, so that it must be advanced along the whole path in order),
:attr:`~MooringSolver.batched` (a dynamic line advanced with the others of its body over a
coupled step's two samples), :attr:`~MooringSolver.resolves_dynamics` (its own waves and
energy), :attr:`~MooringSolver.accuracy_checked`, the checkpoint state
(``state_arrays`` / ``set_state_arrays``) and :meth:`~MooringSolver.refuse_long_work`.

:class:`PathStepper` is the single line (a fairlead path (n, 3); outputs ``fairlead_force``,
``anchor_force``, ``laid_length``, ``steps``), implemented by the quasi-static, quasi-dynamic
and dynamic lines; :meth:`PathStepper.advance` is that path with one sample. A coupled run
advances a quasi-dynamic line with one-sample paths to the half and the full body step, and
its dynamic lines once per body step over both samples (:mod:`floatmoor.mooring.dg.batch`;
docs/theory/floater.md#coupling-scheme); a quasi-static line is solved at every stage.
Forced-motion runs pass the models the fairlead velocity, and record their shape from
:meth:`PathStepper.current_shape`.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

__all__ = ["MooringSolver", "PathStepper"]


class MooringSolver(ABC):
    """What a run asks of a line model or a mooring-system solver."""

    #: "quasi-static", "quasi-dynamic" or "dynamic" (the case's ``model`` key)
    model: ClassVar[str]
    #: whether the model carries a state from sample to sample (then it is advanced along
    #: the whole path, in order, and its state is in the checkpoint); False: solved at each
    #: instant from where its ends are (its state is a warm start)
    has_memory: ClassVar[bool] = True
    #: whether a coupled run advances it with the body's other batched lines, once per body
    #: step over the step's two samples (:mod:`floatmoor.mooring.dg.batch`)
    batched: ClassVar[bool] = False
    #: whether it resolves the line's own dynamics (waves along it, kinetic energy)
    resolves_dynamics: ClassVar[bool] = False
    #: the first sample of the last path not solved, -1 when all were
    failed_index: int

    @abstractmethod
    def solve_path(self, time: NDArray[np.float64], path: NDArray[np.float64],
                   velocity: NDArray[np.float64], *outputs: NDArray[np.float64]) -> None:
        """Advance along the ends' path (positions and velocities at ``time``), writing the
        outputs at every sample.

        Raises
        ------
        SolverError
            With :attr:`failed_index` the first sample not solved; the outputs before it
            are valid.
        """

    @abstractmethod
    def state_arrays(self) -> dict[str, NDArray[np.float64]]:
        """The state (or warm start) as named arrays, for a checkpoint."""

    @abstractmethod
    def set_state_arrays(self, arrays: dict[str, NDArray[np.float64]]) -> None:
        """Restore a state of :meth:`state_arrays`."""

    @property
    def accuracy_checked(self) -> bool:
        """Whether a run checks its numerics a posteriori along its path
        (:mod:`floatmoor.simulation.line_accuracy`) when the case left them to the accuracy."""
        return False

    def refuse_long_work(self, duration: float, what: str, source: str = "") -> None:
        """Raise a CaseError before a run of ``duration`` [s] that would take it too many
        steps; the default has no such limit."""


class PathStepper(MooringSolver):
    """Base of the single-line models, advanced along a prescribed fairlead path."""

    #: unstretched arc lengths from the anchor of the recorded shape's nodes [m]
    arc_length: NDArray[np.float64]

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

    def current_shape(self, fairlead: NDArray[np.float64]
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Node positions (n, 3) [m] and tensions (n,) [N] at :attr:`arc_length` now, the
        fairlead at ``fairlead`` (where a model without memory is solved; a model with
        memory gives its state, whose fairlead that is)."""
        return self.r.reshape(-1, 3), self.tension()

    def start_moving(self, path_state: Callable[[NDArray[np.float64]],
                                                tuple[NDArray[np.float64], NDArray[np.float64]]],
                     sample_interval: float) -> bool:
        """Start the line in the motion ``path_state(t) -> (positions, velocities)`` of its
        fairlead, sampled ``sample_interval`` [s] apart, rather than at rest; True when it did.
        The default starts at rest (False): a model that needs the motion's past overrides
        it."""
        return False

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
