"""Numba kernel of the quasi-static line model: the catenary solved along a fairlead path.

Each fairlead position is solved warm-started from the previous one (docs/theory/quasi_static.md);
results go into preallocated arrays, and the first failure stops the loop and is reported
through ``failure`` rather than an exception.
"""

from __future__ import annotations

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring._catenary_kernels import (
    CAT_OK, I3_ANCHOR_FORCE, I3_FAIRLEAD_FORCE, I3_HF, I3_ITER, I3_LB, I3_VF, catenary_solve_3d,
)

__all__ = ["quasi_static_series"]


@jit
def quasi_static_series(anchor: np.ndarray, path: np.ndarray, L: float, EA: float, W: float,
                        CB: float, seabed_z: float, tol: float, max_iter: int, warm: np.ndarray,
                        work: np.ndarray, fairlead_force: np.ndarray, anchor_force: np.ndarray,
                        laid_length: np.ndarray, iterations: np.ndarray,
                        failure: np.ndarray) -> int:
    """Solve the elastic catenary at every fairlead position of ``path``.

    Parameters
    ----------
    anchor : float64[3]
        Anchor position [m].
    path : float64[n, 3]
        Fairlead positions [m].
    L, EA, W, CB, seabed_z, tol, max_iter
        As :func:`~floatmoor.mooring._catenary_kernels.catenary_solve_3d`.
    warm : float64[2]
        (HF, VF) warm start [N]; updated with the last solution (non-finite = cold start).
    work : float64[N_OUT_3D]
        Scratch output of the 3-D solve.
    fairlead_force, anchor_force : float64[n, 3]
        Forces exerted by the line on its fairlead and on its anchor [N] (written).
    laid_length : float64[n]
        Unstretched length on the seabed [m] (written).
    iterations : float64[n]
        Newton iterations per solve (written).
    failure : int64[2]
        Written on failure: (index in path, catenary status).

    Returns
    -------
    int
        -1 if every position was solved, else the index of the first failure.
    """
    n = path.shape[0]
    for k in range(n):
        status = catenary_solve_3d(anchor, path[k], L, EA, W, CB, seabed_z, warm[0], warm[1],
                                   tol, max_iter, work)
        if status != CAT_OK:
            failure[0] = k
            failure[1] = status
            return k
        for j in range(3):
            fairlead_force[k, j] = work[I3_FAIRLEAD_FORCE + j]
            anchor_force[k, j] = work[I3_ANCHOR_FORCE + j]
        laid_length[k] = work[I3_LB]
        iterations[k] = work[I3_ITER]
        warm[0] = work[I3_HF]
        warm[1] = work[I3_VF]
    return -1
