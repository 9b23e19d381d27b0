"""Numba kernel of several dynamic lines at once (:mod:`floatmoor.mooring.dg.batch`): the end
forces of every line of one discretisation in one call, as each line's
``DynamicLine.end_forces_moving`` computes them (``_kernels._record_ends``: the tension field and
the end fluxes, docs/theory/floater.md#coupling-scheme)."""

from __future__ import annotations

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring.dg._kernels import _ZERO3, _record_ends

__all__ = ["dg_end_forces_batch"]


@jit
def dg_end_forces_batch(r: np.ndarray, v: np.ndarray, anchors: np.ndarray, fpos: np.ndarray,
                        fvel: np.ndarray, prm: np.ndarray, D: np.ndarray, LIFT: np.ndarray,
                        weights: np.ndarray, q: np.ndarray, qt: np.ndarray, N: np.ndarray,
                        Nstar: np.ndarray, faces: np.ndarray, slack: np.ndarray,
                        fair_out: np.ndarray, anch_out: np.ndarray, laid: np.ndarray) -> None:
    """End forces of lines l = 0 .. n-1 of one discretisation, each in its state r[l], v[l]
    ((n, K, Np, 3)) with its fairlead at fpos[l] moving at fvel[l] ((n, 3)), anchor anchors[l]
    and parameters prm[l] ((n, N_PRM)): the forces on the fairleads and anchors into
    ``fair_out`` and ``anch_out`` (n, 3) and the laid lengths into ``laid`` (n,). ``q`` ...
    ``slack`` are one line's work arrays (``_Workspace``), reused line after line."""
    for line in range(r.shape[0]):
        laid[line] = _record_ends(r[line], v[line], anchors[line], _ZERO3, fpos[line],
                                  fvel[line], prm[line], D, LIFT, q, qt, N, Nstar, faces, slack,
                                  weights, fair_out[line], anch_out[line])
