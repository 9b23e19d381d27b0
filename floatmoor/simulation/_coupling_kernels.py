"""Numba kernel of a coupled run's stage: the body's mooring force from its dynamic lines, when
every line is one of them (floatmoor.simulation.coupled). A body step asks for it four times;
one call in place of the three it composes (fairlead kinematics, the lines' end forces, their
generalised force) saves the two calls from Python, which cost about as much as the lines' end
forces themselves (docs/validation/performance.md)."""

from __future__ import annotations

import numpy as np

from floatmoor._numba import jit
from floatmoor.body._kinematics_kernels import generalised_force_into, points_state_into
from floatmoor.mooring.dg._batch_kernels import dg_end_forces_batch

__all__ = ["batched_mooring_force"]


@jit
def batched_mooring_force(x: np.ndarray, v: np.ndarray, arms: np.ndarray, centre: np.ndarray,
                          positions: np.ndarray, velocities: np.ndarray, r: np.ndarray,
                          rv: np.ndarray, anchors: np.ndarray, fpos: np.ndarray,
                          prm: np.ndarray, D: np.ndarray, LIFT: np.ndarray,
                          weights: np.ndarray, laid: np.ndarray, fair_out: np.ndarray,
                          anch_out: np.ndarray, out: np.ndarray) -> None:
    """The 6-DOF force ``out`` of the lines on the body in state (x, v): the fairleads'
    positions and velocities (``points_state_into``, into ``positions`` and ``velocities``),
    the lines' end forces in their states ``r``, ``rv`` with their fairleads at ``fpos`` moving
    at those velocities (``dg_end_forces_batch``, into ``fair_out``, ``anch_out`` and
    ``laid``), and the fairlead forces' generalised force (``generalised_force_into``)."""
    points_state_into(x, v, arms, centre, positions, velocities)
    dg_end_forces_batch(r, rv, anchors, fpos, velocities, prm, D, LIFT, weights, fair_out,
                        anch_out, laid)
    generalised_force_into(x, fair_out, arms, out)
