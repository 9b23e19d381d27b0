"""Numba kernels of a DG mooring system: sections joined at points (physics.md sections 1-2).

Every section is a DG cable (``_kernels``) with its own elements, order and parameters, its
start and end driven by the points it joins. Points are fixed, free (a 3-DOF mass) or body
(a prescribed path). All sections and free points advance together in the same SSP-RK3 stages
at one time step.

Free points. A free point of mass M, displaced volume V, drag area C_d A and added-mass
coefficient C_a obeys (M + C_a rho_w V) du/dt = sum_j F_j + (rho_w V - M) g e_z
+ 0.5 rho_w C_d A |u_c - u| (u_c - u), F_j the end fluxes of its sections (buoyancy, added mass
and drag only below z = 0). Each end flux is linear in the point's velocity, F_j = G_j - Z_j u
(G_j = N + Z_j v at a section's start, -N + Z_j v at its end, v the end node's velocity, Z_j =
m_t c the section's axial impedance). Every forward-Euler substep of SSP-RK3 takes the point
velocity linearly implicit in those terms and in the linearised drag,

    u* = (M_eff u + dt (F_o + sum_j G_j + c_d u_c)) / (M_eff + dt (sum_j Z_j + c_d)),

c_d = 0.5 rho_w C_d A |u_c - u|, and the sections' end fluxes of that substep use u*, so the
point takes exactly the reaction of the forces it exerts (momentum is conserved). For
M_eff = 0 (a massless joint) u* is the upwind (Riemann) junction velocity and the force balance
is algebraic; for a large M_eff it is the explicit update. Each substep is then dissipative in
the junction terms whatever the mass, so SSP-RK3 keeps the sections' stability limit. The
point's position takes the explicit step x + dt u, like the nodes'.

Data layout (no allocation inside the time loop): the nodes of all sections in one (nodes, 3)
array, each section's slice reshaped to (K, Np, 3); ``sec`` holds per section K, Np, the node,
element, face, operator, Y and band offsets and the start and end point; ``ops`` the reference
element operators (D, LIFT, F, weights) of every section one after another.
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring.dg import _kernels as _k

__all__ = ["FIXED", "FREE", "BODY", "S_K", "S_NP", "N_SEC", "PP_MASS", "PP_VOLUME",
           "PP_DRAG_AREA", "PP_CA", "N_PP", "E_RHO_W", "E_G", "E_U", "N_ENV", "dgs_rhs",
           "dgs_run_path", "dgs_record"]

# -- point kinds ----------------------------------------------------------------------------
FIXED = 0
FREE = 1
BODY = 2

# -- columns of ``sec`` (int64, one row per section) ------------------------------------------
S_K = 0  #: elements
S_NP = 1  #: nodes per element
S_NODE = 2  #: offset of the first node
S_ELEM = 3  #: offset of the first element (slack flags)
S_FACE = 4  #: offset of the first face (K + 1 faces)
S_OPS = 5  #: offset of the operators in ``ops``
S_Y = 6  #: offset of the damping system's Y in its flat array
S_BAND = 7  #: offset of the damping band in its flat array
S_START = 8  #: start point
S_END = 9  #: end point
N_SEC = 10

# -- columns of ``pprm`` (one row per point) ------------------------------------------------
PP_MASS = 0  #: [kg]
PP_VOLUME = 1  #: displaced volume [m^3]
PP_DRAG_AREA = 2  #: C_d A [m^2]
PP_CA = 3  #: added-mass coefficient on the displaced volume [-]
N_PP = 4

# -- ``env`` ---------------------------------------------------------------------------------
E_RHO_W = 0  #: water density [kg/m^3]
E_G = 1  #: gravity [m/s^2]
E_U = 2  #: current velocity [m/s], 3 entries
E_RELAX = 5  #: relaxation rate of the free points [1/s] (settling only; 0)
N_ENV = 6

#: statuses beyond ``_kernels``': a free point is not finite
DGS_POINT = 10


@jit
def _ops(ops, sec, s):
    """The reference-element operators (D, LIFT, F, weights) of section s."""
    Np = sec[s, S_NP]
    o = sec[s, S_OPS]
    n2 = Np * Np
    D = ops[o:o + n2].reshape((Np, Np))
    LIFT = ops[o + n2:o + n2 + 2 * Np].reshape((Np, 2))
    F = ops[o + n2 + 2 * Np:o + 2 * n2 + 2 * Np].reshape((Np, Np))
    w = ops[o + 2 * n2 + 2 * Np:o + 2 * n2 + 3 * Np]
    return D, LIFT, F, w


@jit
def _nodes(a, sec, s):
    """Section s's slice of a (nodes, 3) array as (K, Np, 3)."""
    K, Np, o = sec[s, S_K], sec[s, S_NP], sec[s, S_NODE]
    return a[o:o + K * Np].reshape((K, Np, 3))


@jit
def _end_impedance(r, prm, start):
    """Z = m_t c at a section's start (``start``) or end node, as in ``_tension_field``."""
    K, Np = r.shape[0], r.shape[1]
    if start:
        sub = 1.0 if r[0, 0, 2] < 0.0 else 0.0
    else:
        sub = 1.0 if r[K - 1, Np - 1, 2] < 0.0 else 0.0
    return (prm[_k.P_M] + sub * prm[_k.P_MAT]) * prm[_k.P_C]


@jit
def _free_velocity(x, u, pprm, env, G, Zs, dt, out):
    """u* of a free point (module docstring); ``dt = 0`` gives u for a point with mass and
    the balance velocity of a massless one."""
    rho_w, g = env[E_RHO_W], env[E_G]
    sub = x[2] < 0.0
    M = pprm[PP_MASS]
    meff = M + (pprm[PP_CA] * rho_w * pprm[PP_VOLUME] if sub else 0.0)
    fz = ((rho_w * pprm[PP_VOLUME] if sub else 0.0) - M) * g
    cd = 0.0
    if sub and pprm[PP_DRAG_AREA] > 0.0:
        w2 = 0.0
        for c in range(3):
            w2 += (env[E_U + c] - u[c]) ** 2
        cd = 0.5 * rho_w * pprm[PP_DRAG_AREA] * math.sqrt(w2)
    for c in range(3):
        f = G[c] + cd * env[E_U + c] + (fz if c == 2 else 0.0)
        if meff == 0.0:
            out[c] = f / (Zs + cd)
        else:
            out[c] = (meff * u[c] + dt * f) / (meff + dt * (Zs + cd + env[E_RELAX] * meff))


@jit
def _prescribed(kind, body, bcd, stage, dt, x, u, ppos, pvel):
    """Point positions and velocities of a stage: fixed points where they are, body points
    the stage-consistent Taylor data of their path (as ``_ssp_rk3_step``'s fairlead), free
    points their state (their velocity is replaced by u* later)."""
    P = kind.shape[0]
    for p in range(P):
        if kind[p] == BODY:
            g = bcd[body[p]]
            for c in range(3):
                if stage == 0:
                    ppos[p, c] = g[0, c]
                    pvel[p, c] = g[1, c]
                elif stage == 1:
                    ppos[p, c] = g[0, c] + dt * g[1, c]
                    pvel[p, c] = g[1, c] + dt * g[2, c]
                else:
                    ppos[p, c] = g[0, c] + 0.5 * dt * g[1, c] + 0.25 * dt * dt * g[2, c]
                    pvel[p, c] = g[1, c] + 0.5 * dt * g[2, c] + 0.25 * dt * dt * g[3, c]
        else:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c] if kind[p] == FREE else 0.0


@jit
def _system_rhs(r, v, x, u, dt, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N,
                Nstar, faces, slack, a, ue):
    """One forward-Euler substep's rates: node accelerations ``a`` and the free points' u*
    (``ue``), with ``ppos``/``pvel`` holding the stage's prescribed data (free points: their
    state); on return ``pvel`` holds u* for the free points."""
    S = sec.shape[0]
    P = kind.shape[0]
    for p in range(P):
        Zs[p] = 0.0
        for c in range(3):
            G[p, c] = 0.0
    for s in range(S):
        K, Np = sec[s, S_K], sec[s, S_NP]
        ps = prm[s]
        D, LIFT, F, w = _ops(ops, sec, s)
        rs, vs = _nodes(r, sec, s), _nodes(v, sec, s)
        qs, qts, Ns = _nodes(q, sec, s), _nodes(qt, sec, s), _nodes(N, sec, s)
        fo, eo = sec[s, S_FACE], sec[s, S_ELEM]
        sp, ep = sec[s, S_START], sec[s, S_END]
        cint = ps[_k.P_CINT] if ps[_k.P_IMPLICIT_DAMPING] == 0.0 else 0.0
        _k._tension_field(rs, vs, ppos[sp], pvel[sp], ppos[ep], pvel[ep], ps, D, LIFT, qs, qts,
                          Ns, Nstar[fo:fo + K + 1], faces[fo:fo + K + 1], slack[eo:eo + K],
                          cint)
        if kind[sp] == FREE:
            Z = _end_impedance(rs, ps, True)
            Zs[sp] += Z
            for c in range(3):
                G[sp, c] += Ns[0, 0, c] + Z * vs[0, 0, c]
        if kind[ep] == FREE:
            Z = _end_impedance(rs, ps, False)
            Zs[ep] += Z
            for c in range(3):
                G[ep, c] += -Ns[K - 1, Np - 1, c] + Z * vs[K - 1, Np - 1, c]
    for p in range(P):
        if kind[p] == FREE:
            _free_velocity(x[p], u[p], pprm[p], env, G[p], Zs[p], dt, ue[p])
            for c in range(3):
                pvel[p, c] = ue[p, c]
    for s in range(S):
        K, Np = sec[s, S_K], sec[s, S_NP]
        ps = prm[s]
        D, LIFT, F, w = _ops(ops, sec, s)
        rs, vs = _nodes(r, sec, s), _nodes(v, sec, s)
        fo = sec[s, S_FACE]
        Ns = _nodes(N, sec, s)
        Nst = Nstar[fo:fo + K + 1]
        sp, ep = sec[s, S_START], sec[s, S_END]
        if kind[sp] == FREE:
            Z = _end_impedance(rs, ps, True)
            for c in range(3):
                Nst[0, c] = Ns[0, 0, c] + Z * (vs[0, 0, c] - pvel[sp, c])
        if kind[ep] == FREE:
            Z = _end_impedance(rs, ps, False)
            for c in range(3):
                Nst[K, c] = Ns[K - 1, Np - 1, c] + Z * (pvel[ep, c] - vs[K - 1, Np - 1, c])
        _k._acceleration(rs, vs, ps, D, LIFT, _nodes(q, sec, s), Ns, Nst, _nodes(a, sec, s))


@jit
def dgs_rhs(r, v, x, u, dt, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N, Nstar,
            faces, slack, a, ue):
    """The system's right-hand side at a state: node accelerations ``a`` (nodes, 3) and the
    free points' substep velocities u* (``ue``, points, 3) for a forward-Euler substep of
    ``dt``. Fixed and body points take ``ppos``/``pvel`` as given; free points their state
    (x, u). For the tests against the NumPy reference (``system_reference``)."""
    for p in range(kind.shape[0]):
        if kind[p] == FREE:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c]
    _system_rhs(r, v, x, u, dt, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N,
                Nstar, faces, slack, a, ue)


@jit
def _system_step(r, v, x, u, t, dt, t0, t1, bp0, bw0, bp1, bw1, sec, prm, ops, kind, body,
                 pprm, env, work, pwork, q, qt, N, Nstar, faces, slack, ppos, pvel, G, Zs, tmp,
                 bcd, tng, minv, cn, flags, Y, band, e, info):
    """One SSP-RK3 step of every section and free point from t to t + dt, then each
    section's implicit contact, implicit internal damping and slack filter."""
    r1, v1, r2, v2, a = work[0], work[1], work[2], work[3], work[4]
    x1, u1, x2, u2, ue = pwork[0], pwork[1], pwork[2], pwork[3], pwork[4]
    n = r.shape[0]
    P = kind.shape[0]
    for b in range(bp0.shape[0]):
        _k._hermite_derivatives(t0, t1, bp0[b], bw0[b], bp1[b], bw1[b], t, bcd[b])
    # stage 1
    _prescribed(kind, body, bcd, 0, dt, x, u, ppos, pvel)
    _system_rhs(r, v, x, u, dt, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N,
                Nstar, faces, slack, a, ue)
    for i in range(n):
        for c in range(3):
            r1[i, c] = r[i, c] + dt * v[i, c]
            v1[i, c] = v[i, c] + dt * a[i, c]
    for p in range(P):
        if kind[p] == FREE:
            for c in range(3):
                x1[p, c] = x[p, c] + dt * u[p, c]
                u1[p, c] = ue[p, c]
        else:
            for c in range(3):
                x1[p, c] = x[p, c]
                u1[p, c] = u[p, c]
    # stage 2
    _prescribed(kind, body, bcd, 1, dt, x1, u1, ppos, pvel)
    _system_rhs(r1, v1, x1, u1, dt, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt,
                N, Nstar, faces, slack, a, ue)
    for i in range(n):
        for c in range(3):
            r2[i, c] = 0.75 * r[i, c] + 0.25 * (r1[i, c] + dt * v1[i, c])
            v2[i, c] = 0.75 * v[i, c] + 0.25 * (v1[i, c] + dt * a[i, c])
    for p in range(P):
        if kind[p] == FREE:
            for c in range(3):
                x2[p, c] = 0.75 * x[p, c] + 0.25 * (x1[p, c] + dt * u1[p, c])
                u2[p, c] = 0.75 * u[p, c] + 0.25 * ue[p, c]
        else:
            for c in range(3):
                x2[p, c] = x[p, c]
                u2[p, c] = u[p, c]
    # stage 3
    _prescribed(kind, body, bcd, 2, dt, x2, u2, ppos, pvel)
    _system_rhs(r2, v2, x2, u2, dt, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt,
                N, Nstar, faces, slack, a, ue)
    third, two_thirds = 1.0 / 3.0, 2.0 / 3.0
    for i in range(n):
        for c in range(3):
            r[i, c] = third * r[i, c] + two_thirds * (r2[i, c] + dt * v2[i, c])
            v[i, c] = third * v[i, c] + two_thirds * (v2[i, c] + dt * a[i, c])
    for p in range(P):
        if kind[p] == FREE:
            for c in range(3):
                x[p, c] = third * x[p, c] + two_thirds * (x2[p, c] + dt * u2[p, c])
                u[p, c] = third * u[p, c] + two_thirds * ue[p, c]
    # the end data at t + dt for the damping step
    for p in range(P):
        if kind[p] == BODY:
            b = body[p]
            _k.hermite(t0, t1, bp0[b], bw0[b], bp1[b], bw1[b], t + dt, ppos[p], pvel[p])
        else:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c] if kind[p] == FREE else 0.0
    for s in range(sec.shape[0]):
        K, Np = sec[s, S_K], sec[s, S_NP]
        ps = prm[s]
        D, LIFT, F, w = _ops(ops, sec, s)
        rs, vs = _nodes(r, sec, s), _nodes(v, sec, s)
        if ps[_k.P_IMPLICIT_CONTACT] != 0.0:
            _k._implicit_contact(rs, vs, ps, dt)
        if ps[_k.P_IMPLICIT_DAMPING] != 0.0 and ps[_k.P_CINT] > 0.0:
            no, fo, eo = sec[s, S_NODE], sec[s, S_FACE], sec[s, S_ELEM]
            sp, ep = sec[s, S_START], sec[s, S_END]
            nn = K * Np
            yo, bo = sec[s, S_Y], sec[s, S_BAND]
            Ys = Y[yo:yo + nn * (Np + 1) * 3].reshape((K, Np, Np + 1, 3))
            bs = band[bo:bo + nn * 3 * Np].reshape((nn, 3 * Np))
            tngs = _nodes(tng, sec, s)
            minvs = minv[no:no + nn].reshape((K, Np, 2))
            cns = cn[no:no + nn].reshape((K, Np))
            flg = flags[no:no + nn].reshape((K, Np))
            es = e[no:no + nn]
            qs, qts, Ns = _nodes(q, sec, s), _nodes(qt, sec, s), _nodes(N, sec, s)
            fcs = faces[fo:fo + K + 1]
            if _k._damping_system(rs, ppos[sp], ppos[ep], ps, D, LIFT, dt, qs, fcs, tngs,
                                  minvs, cns, flg, Ys, bs, info[s]):
                _k._damping_solve_ends(vs, pvel[sp], pvel[ep], ps, D, LIFT, dt, qts, Ns, fcs,
                                       tngs, minvs, cns, bs, es)
        if ps[_k.P_FILTER] != 0.0:
            eo = sec[s, S_ELEM]
            _k._filter_slack(vs, F, slack[eo:eo + K], tmp)


@jit
def _record_velocities(x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, v, r, ue):
    """Free points' velocities for the recorded end fluxes: the state's for points with mass,
    the balance velocity (sum of the end fluxes zero) for massless joints. ``ppos`` must hold
    every point's position and ``pvel`` the others' velocities; G and Zs need the nodal
    forces of the sections in N (the caller's first pass)."""
    for p in range(kind.shape[0]):
        if kind[p] == FREE:
            _free_velocity(x[p], u[p], pprm[p], env, G[p], Zs[p], 0.0, ue[p])
            for c in range(3):
                pvel[p, c] = ue[p, c]


@jit
def dgs_record(r, v, x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N, Nstar,
               faces, slack, ue, start_out, end_out, laid_out):
    """End forces of every section on its start and end point [N] (``start_out``,
    ``end_out``: (sections, 3)) and laid lengths [m] at the current state, with the internal
    damping in the tension. ``ppos``/``pvel`` hold the body points' data; fixed points take
    their position at rest, free points their state (massless ones their balance
    velocity)."""
    S = sec.shape[0]
    P = kind.shape[0]
    for p in range(P):
        if kind[p] != BODY:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c] if kind[p] == FREE else 0.0
        Zs[p] = 0.0
        for c in range(3):
            G[p, c] = 0.0
    for s in range(S):  # first pass: nodal forces, G and Z of the free points
        K, Np = sec[s, S_K], sec[s, S_NP]
        ps = prm[s]
        D, LIFT, F, w = _ops(ops, sec, s)
        rs, vs = _nodes(r, sec, s), _nodes(v, sec, s)
        Ns = _nodes(N, sec, s)
        fo, eo = sec[s, S_FACE], sec[s, S_ELEM]
        sp, ep = sec[s, S_START], sec[s, S_END]
        _k._tension_field(rs, vs, ppos[sp], pvel[sp], ppos[ep], pvel[ep], ps, D, LIFT,
                          _nodes(q, sec, s), _nodes(qt, sec, s), Ns, Nstar[fo:fo + K + 1],
                          faces[fo:fo + K + 1], slack[eo:eo + K], ps[_k.P_CINT])
        if kind[sp] == FREE:
            Z = _end_impedance(rs, ps, True)
            Zs[sp] += Z
            for c in range(3):
                G[sp, c] += Ns[0, 0, c] + Z * vs[0, 0, c]
        if kind[ep] == FREE:
            Z = _end_impedance(rs, ps, False)
            Zs[ep] += Z
            for c in range(3):
                G[ep, c] += -Ns[K - 1, Np - 1, c] + Z * vs[K - 1, Np - 1, c]
    _record_velocities(x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, v, r, ue)
    for s in range(S):
        K, Np = sec[s, S_K], sec[s, S_NP]
        ps = prm[s]
        D, LIFT, F, w = _ops(ops, sec, s)
        fo, eo = sec[s, S_FACE], sec[s, S_ELEM]
        sp, ep = sec[s, S_START], sec[s, S_END]
        laid_out[s] = _k._record_ends(
            _nodes(r, sec, s), _nodes(v, sec, s), ppos[sp], pvel[sp], ppos[ep], pvel[ep], ps,
            D, LIFT, _nodes(q, sec, s), _nodes(qt, sec, s), _nodes(N, sec, s),
            Nstar[fo:fo + K + 1], faces[fo:fo + K + 1], slack[eo:eo + K], w, end_out[s],
            start_out[s])


@jit
def _check(r, v, q, x, u, sec, prm, kind, where):
    """Status of the state; ``where`` gets (section, element, node), or (-1, point, 0)."""
    for s in range(sec.shape[0]):
        status = _k._check(_nodes(r, sec, s), _nodes(v, sec, s), _nodes(q, sec, s), prm[s],
                           where[1:])
        if status != _k.DG_OK:
            where[0] = s
            return status
    for p in range(kind.shape[0]):
        acc = 0.0
        for c in range(3):
            acc += x[p, c] + u[p, c]
        if not math.isfinite(acc):
            where[0], where[1], where[2] = -1, p, 0
            return DGS_POINT
    return _k.DG_OK


@jit
def dgs_run_path(r, v, x, u, time, bpos, bvel, sec, prm, ops, kind, body, pprm, env, dt_max,
                 start_force, end_force, laid, point_pos, steps, shape_every, shape_r, shape_t,
                 work, pwork, q, qt, N, Nstar, faces, slack, ppos, pvel, G, Zs, tmp, bcd, tng,
                 minv, cn, flags, Y, band, e, info, where):
    """Advance the system along its body points' paths, recording at every sample.

    ``time`` (n,), ``bpos``/``bvel`` (n, bodies, 3) give the body points at the samples (the
    state must be the one at ``time[0]``). Outputs per sample: ``start_force``/``end_force``
    (n, sections, 3) the forces of each section on its start / end point, ``laid`` (n,
    sections), ``point_pos`` (n, points, 3), ``steps`` (n,); every ``shape_every``-th sample
    (if > 0) node positions and tensions go to ``shape_r`` (m, nodes, 3) / ``shape_t``.

    Returns
    -------
    (status, index)
        ``DG_OK`` and n, or the first failing status and the sample where it occurred
        (``where``: section, element, node; or -1, point, 0).
    """
    n = time.shape[0]
    nodes = r.shape[0]
    P = kind.shape[0]
    for p in range(P):
        if kind[p] == BODY:
            for c in range(3):
                ppos[p, c] = bpos[0, body[p], c]
                pvel[p, c] = bvel[0, body[p], c]
    dgs_record(r, v, x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N, Nstar,
               faces, slack, pwork[4], start_force[0], end_force[0], laid[0])
    for p in range(P):
        for c in range(3):
            point_pos[0, p, c] = ppos[p, c]
    steps[0] = 0.0
    n_shape = 0
    for s in range(n):
        if shape_every > 0 and s % shape_every == 0:
            for i in range(nodes):
                shape_t[n_shape, i] = math.sqrt(N[i, 0] ** 2 + N[i, 1] ** 2 + N[i, 2] ** 2)
                for c in range(3):
                    shape_r[n_shape, i, c] = r[i, c]
            n_shape += 1
        if s == n - 1:
            break
        t0, t1 = time[s], time[s + 1]
        n_sub = int(math.ceil((t1 - t0) / dt_max * (1.0 - 1e-12)))
        if n_sub < 1:
            n_sub = 1
        dt = (t1 - t0) / n_sub
        for j in range(n_sub):
            _system_step(r, v, x, u, t0 + j * dt, dt, t0, t1, bpos[s], bvel[s], bpos[s + 1],
                         bvel[s + 1], sec, prm, ops, kind, body, pprm, env, work, pwork, q, qt,
                         N, Nstar, faces, slack, ppos, pvel, G, Zs, tmp, bcd, tng, minv, cn,
                         flags, Y, band, e, info)
        for p in range(P):
            if kind[p] == BODY:
                for c in range(3):
                    ppos[p, c] = bpos[s + 1, body[p], c]
                    pvel[p, c] = bvel[s + 1, body[p], c]
        dgs_record(r, v, x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N,
                   Nstar, faces, slack, pwork[4], start_force[s + 1], end_force[s + 1],
                   laid[s + 1])
        for p in range(P):
            for c in range(3):
                point_pos[s + 1, p, c] = ppos[p, c]
        steps[s + 1] = n_sub
        status = _check(r, v, q, x, u, sec, prm, kind, where)
        if status != _k.DG_OK:
            return status, s + 1
    return _k.DG_OK, n
