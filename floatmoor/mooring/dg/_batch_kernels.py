"""Numba kernels of several dynamic lines at once (:mod:`floatmoor.mooring.dg.batch`): the end
forces of every line of one discretisation in one call, the values each line's
``DynamicLine.end_forces_moving`` computes (``_kernels._record_ends``: the tension field and the
end fluxes) from the end nodes alone, a line's state at the middle of a body step interpolated
in time from its states at both ends (docs/theory/floater.md#coupling-scheme), and the
implicit lines of one discretisation advanced over a body step in one call (a call from Python
costs about as much as a line's implicit step: docs/validation/performance.md)."""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg._implicit_kernels import CS_ACC_VALID, _copy, dg_run_path_implicit
from floatmoor.mooring.dg._kernels import _ZERO3, DG_OK, _node_derivative

__all__ = ["dg_end_forces_batch", "hermite_middle", "dg_advance_implicit_batch"]


@jit
def dg_end_forces_batch(r: np.ndarray, v: np.ndarray, anchors: np.ndarray, fpos: np.ndarray,
                        fvel: np.ndarray, prm: np.ndarray, D: np.ndarray, LIFT: np.ndarray,
                        weights: np.ndarray, fair_out: np.ndarray, anch_out: np.ndarray,
                        laid: np.ndarray) -> None:
    """End forces of lines l = 0 .. n-1 of one discretisation, each in its state r[l], v[l]
    ((n, K, Np, 3)) with its fairlead at fpos[l] moving at fvel[l] ((n, 3)), anchor anchors[l]
    and parameters prm[l] ((n, N_PRM)): the forces on the fairleads and anchors into
    ``fair_out`` and ``anch_out`` (n, 3) and the laid lengths into ``laid`` (n,); the values
    of ``_kernels._record_ends``, which computes the whole tension field for them, from the
    two end nodes' tensions alone (:func:`_end_forces`)."""
    for line in range(r.shape[0]):
        laid[line] = _end_forces(r[line], v[line], anchors[line], fpos[line], fvel[line],
                                 prm[line], D, LIFT, weights, fair_out[line], anch_out[line])


@jit
def _node_gradient(u, left, right, D, LIFT, jac, k, i):
    """(x, y, z) of ``_kernels._gradient``'s derivative of u at node i of element k, alone:
    the same operations in the same order, so the same bits."""
    K, Np = u.shape[0], u.shape[1]
    if k == 0:
        lx, ly, lz = left[0], left[1], left[2]
    else:
        lx, ly, lz = u[k - 1, Np - 1, 0], u[k - 1, Np - 1, 1], u[k - 1, Np - 1, 2]
    if k == K - 1:
        rx, ry, rz = right[0], right[1], right[2]
    else:
        rx, ry, rz = u[k, Np - 1, 0], u[k, Np - 1, 1], u[k, Np - 1, 2]
    return _node_derivative(u, k, i, D, LIFT, jac, lx - u[k, 0, 0], ly - u[k, 0, 1],
                            lz - u[k, 0, 2], rx - u[k, Np - 1, 0], ry - u[k, Np - 1, 1],
                            rz - u[k, Np - 1, 2])


@jit
def _node_tension(r, v, anchor, avel, fpos, fvel, D, LIFT, jac, EA, cint, k, i):
    """(x, y, z) of ``_kernels._tension_field``'s axial force N at node i of element k,
    alone (the same operations in the same order)."""
    qx, qy, qz = _node_gradient(r, anchor, fpos, D, LIFT, jac, k, i)
    ql = math.sqrt(qx ** 2 + qy ** 2 + qz ** 2)
    eps = ql - 1.0
    T = 0.0
    if eps > 0.0:
        T = EA * eps
        if cint > 0.0:
            tx, ty, tz = _node_gradient(v, avel, fvel, D, LIFT, jac, k, i)
            deps = (qx * tx + qy * ty + qz * tz) / ql
            T += cint * deps
            if T < 0.0:
                T = 0.0
    scale = T / ql if ql > 0.0 else 0.0
    return scale * qx, scale * qy, scale * qz


@jit
def _end_forces(r, v, anchor, fpos, fvel, prm, D, LIFT, weights, fair_out, anch_out):
    """``_kernels._record_ends`` of a fixed anchor (its fluxes N* at the two ends, the laid
    length) from the end nodes' tensions: the fluxes at the ends need no other node."""
    K, Np = r.shape[0], r.shape[1]
    jac = 2.0 / prm[_k.P_H]
    EA, cint = prm[_k.P_EA], prm[_k.P_CINT]
    m, c_wave = prm[_k.P_M], prm[_k.P_C]
    first = np.int64(0)  # (a typed index: a literal would compile the kernel once more)
    n0 = _node_tension(r, v, anchor, _ZERO3, fpos, fvel, D, LIFT, jac, EA, cint, first, first)
    sub = 1.0 if r[0, 0, 2] < 0.0 else 0.0
    Z = (m + sub * prm[_k.P_MAT]) * c_wave
    for c in range(3):
        anch_out[c] = n0[c] + Z * v[0, 0, c]  # (the anchor at rest: v - 0.0 is v)
    n1 = _node_tension(r, v, anchor, _ZERO3, fpos, fvel, D, LIFT, jac, EA, cint, K - 1, Np - 1)
    sub = 1.0 if r[K - 1, Np - 1, 2] < 0.0 else 0.0
    Z = (m + sub * prm[_k.P_MAT]) * c_wave
    for c in range(3):
        fair_out[c] = -(n1[c] + Z * (fvel[c] - v[K - 1, Np - 1, c]))
    laid = 0.0
    threshold = prm[_k.P_ZB] + 0.1 * prm[_k.P_D]
    for k in range(K):
        for i in range(Np):
            if r[k, i, 2] <= threshold:
                laid += 0.5 * prm[_k.P_H] * weights[i]
    return laid


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


@jit
def dg_advance_implicit_batch(active, time, path, velocity, r, v, acc, An, anchors, prm, D,
                              LIFT, F, weights, ip, cs, fair_force, anch_force, laid, steps,
                              shape_every, shape_r, shape_t, q, qt, N, Nstar, faces, slack, fpos,
                              fvel, tmp, where, fields, blocks, band, x, flags, r_start, v_start,
                              a_start, r_mid, v_mid, quintic, record_first, failure):
    """Advance each line l with ``active[l]`` of one discretisation over its one sample
    interval ``time[l]`` (2,) along ``path[l]``, ``velocity[l]`` (2, 3): one
    ``_implicit_kernels.dg_run_path_implicit`` call on its state ``r[l]``, ``v[l]``, ``acc[l]``,
    ``An[l]``, its parameters ``prm[l]``, ``ip[l]``, ``cs[l]`` and factors ``band[l]``,
    ``flags[l]`` (outputs ``fair_force[l]`` ... ``steps[l]``; the first sample's with
    ``record_first``), no friction anchors; then its
    state at the interval's middle from both ends (:func:`hermite_middle`, the quintic with
    ``quintic`` when the start's acceleration was known) into ``r_mid[l]``, ``v_mid[l]``.
    ``q`` ... ``where``, ``fields`` (7, K, Np, 3), ``blocks`` (2, K, Np, 3, 3) and ``x`` are one
    line's work arrays, reused line after line.

    ``failure`` (3,) gets (line, status, sample) of the first line that fails (the lines after
    it are not advanced; ``where`` holds its element and node), status ``DG_OK`` otherwise."""
    failure[0], failure[1], failure[2] = -1, DG_OK, 0
    for line in range(active.shape[0]):
        if not active[line]:
            continue
        quintic_here = quintic and cs[line, CS_ACC_VALID] != 0.0
        rs, vs, a_s, rl, vl = r_start[line], v_start[line], a_start[line], r[line], v[line]
        Al = An[line]
        _copy(rl, rs)
        _copy(vl, vs)
        if quintic_here:
            _copy(Al, a_s)
        status, index = dg_run_path_implicit(
            rl, vl, acc[line], Al, time[line], path[line], velocity[line], anchors[line],
            prm[line], D, LIFT, F, weights, ip[line], cs[line], fair_force[line],
            anch_force[line], laid[line], steps[line], shape_every, shape_r, shape_t, q, qt, N,
            Nstar, faces, slack, fpos, fvel, tmp, where, fields[0], fields[1], fields[2],
            fields[3], fields[4], fields[5], fields[6], blocks[0], blocks[1], band[line], x,
            flags[line], record_first, None)
        if status != DG_OK:
            failure[0], failure[1], failure[2] = line, status, index
            return
        hermite_middle(rs, vs, a_s, rl, vl, Al, time[line, 1] - time[line, 0], quintic_here,
                       r_mid[line], v_mid[line])
