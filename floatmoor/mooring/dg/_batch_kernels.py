"""Numba kernels of several dynamic lines at once (:mod:`floatmoor.mooring.dg.batch`): the end
forces of every line of one discretisation in one call, as each line's
``DynamicLine.end_forces_moving`` computes them (``_kernels._record_ends``: the tension field and
the end fluxes), and a line's state at the middle of a body step interpolated in time from its
states at both ends (docs/theory/floater.md#coupling-scheme)."""

from __future__ import annotations

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring.dg._kernels import _ZERO3, _record_ends

__all__ = ["dg_end_forces_batch", "hermite_middle"]


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


@jit
def hermite_middle(r0: np.ndarray, v0: np.ndarray, a0: np.ndarray, r1: np.ndarray,
                   v1: np.ndarray, a1: np.ndarray, h: float, quintic: bool, r_mid: np.ndarray,
                   v_mid: np.ndarray) -> None:
    """Each node's position and velocity at the middle of a step of ``h`` [s] from its
    positions ``r0``, ``r1``, velocities ``v0``, ``v1`` and (``quintic``) accelerations
    ``a0``, ``a1`` at the step's ends (all (K, Np, 3)): the cubic Hermite interpolant's value
    and slope at s = 1/2, or the quintic's, into ``r_mid`` and ``v_mid``."""
    K, Np = r0.shape[0], r0.shape[1]
    for k in range(K):
        for i in range(Np):
            for c in range(3):
                dr = r1[k, i, c] - r0[k, i, c]
                sr = r0[k, i, c] + r1[k, i, c]
                dv = v0[k, i, c] - v1[k, i, c]
                sv = v0[k, i, c] + v1[k, i, c]
                if quintic:
                    sa = a0[k, i, c] + a1[k, i, c]
                    da = a0[k, i, c] - a1[k, i, c]
                    r_mid[k, i, c] = 0.5 * sr + 0.15625 * h * dv + 0.015625 * h * h * sa
                    v_mid[k, i, c] = 1.875 * dr / h - 0.4375 * sv - 0.03125 * h * da
                else:
                    r_mid[k, i, c] = 0.5 * sr + 0.125 * h * dv
                    v_mid[k, i, c] = 1.5 * dr / h - 0.25 * sv
