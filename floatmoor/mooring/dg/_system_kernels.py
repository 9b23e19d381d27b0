"""Numba kernels of a DG mooring system: sections joined at points (docs/theory/cable.md and docs/theory/dynamic_line.md).

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
point's position takes the explicit step x + dt u, like the nodes'. The implicit Kelvin-Voigt
damping after each step takes the free points' velocities with the sections' in one backward
Euler step, answered through the same impedances (:func:`_damping_phase`), so a massless
joint carries its sections' damping forces across.

Seabed contact of a free point: a point with a displaced volume V rests on the seabed through
a normal spring-damper of stiffness k_p = K_b A_p (K_b the case's seabed stiffness per unit
contact area, A_p = pi (3 V / 4 pi)^(2/3) the projected area of the sphere of volume V) and
damping 2 xi sqrt(M_eff k_p), taken like the nodes' contact as a backward-Euler step after each
SSP-RK3 step (unconditionally stable), and a Coulomb friction mu (M - rho_w V) g ramped in up
to the slip speed as the nodes' (docs/theory/cable.md), linearised about u in the substep like
the drag. A point without volume has no contact of its own: its sections' end nodes carry it,
which is all a point has in MoorDyn-C 2.x (its ``Point::doRHS`` has no seabed term; the line
end nodes' contact reaches the point through ``getEndStuff``).

Data layout (no allocation inside the time loop): the nodes of all sections in one (nodes, 3)
array, each section's slice reshaped to (K, Np, 3); ``sec`` holds per section K, Np, the node,
element, face, operator, Y and band offsets and the start and end point; ``ops`` the reference
element operators (D, LIFT, F, weights) of every section one after another.

Size: the numba stages of one system step (right-hand side, implicit damping phase,
free-point and end coupling) that call one another's private helpers within a step; the
implicit damping phase alone is ~180 lines.
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg._banded_kernels import band_solve

__all__ = ["FIXED", "FREE", "BODY", "S_K", "S_NP", "N_SEC", "PP_MASS", "PP_VOLUME",
           "PP_DRAG_AREA", "PP_CA", "PP_KB", "PP_CB", "PP_FRICTION", "N_PP", "E_RHO_W", "E_G", "E_U", "E_ZB", "E_VC",
           "N_ENV", "dgs_rhs",
           "dgs_run_path", "dgs_record", "dgs_record_shape"]

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
PP_KB = 4  #: seabed contact stiffness of the point [N/m] (0: no contact of its own)
PP_CB = 5  #: seabed contact damping of the point [N s/m]
PP_FRICTION = 6  #: full seabed friction force of the point [N]
N_PP = 7

# -- ``env`` ---------------------------------------------------------------------------------
E_RHO_W = 0  #: water density [kg/m^3]
E_G = 1  #: gravity [m/s^2]
E_U = 2  #: current velocity [m/s], 3 entries
E_RELAX = 5  #: relaxation rate of the free points [1/s] (settling only; 0)
E_ZB = 6  #: seabed elevation [m]
E_VC = 7  #: slip speed of the seabed friction [m/s]
N_ENV = 8

# -- typed constants for kernel arguments ----------------------------------------------------
# A Python literal passed to a kernel (``True``, ``0``) compiles that kernel once more for its
# value, beside the bool or int64 it gets elsewhere; these typed values keep one signature
# (docs/development.md#numba-compile-time).
_AT_START = np.bool_(True)  #: ``start`` of a section's start
_AT_END = np.bool_(False)  #: ``start`` of a section's end
_STAGES = (np.int64(0), np.int64(1), np.int64(2))  #: the SSP-RK3 stages
_I0 = np.int64(0)  #: a zero index or count
_I3 = np.int64(3)  #: the column offset of a section's end point in its border blocks

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
    the balance velocity of a massless one. Below the seabed a point with a contact of its
    own (``PP_KB`` > 0) feels the seabed friction, linearised about u like the drag."""
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
    cf = 0.0  # friction over the horizontal speed [N s/m]
    if x[2] < env[E_ZB] and pprm[PP_FRICTION] > 0.0:
        speed = math.sqrt(u[0] * u[0] + u[1] * u[1])
        vc = env[E_VC]
        if speed > 0.0:
            cf = pprm[PP_FRICTION] * math.sin(0.5 * math.pi * speed / max(vc, speed)) / speed
        else:  # the ramp's slope at rest
            cf = pprm[PP_FRICTION] * 0.5 * math.pi / vc
    for c in range(3):
        f = G[c] + cd * env[E_U + c] + (fz if c == 2 else 0.0)
        ch = cd + (cf if c < 2 else 0.0)
        if meff == 0.0:
            out[c] = f / (Zs + ch)
        else:
            out[c] = (meff * u[c] + dt * f) / (meff + dt * (Zs + ch + env[E_RELAX] * meff))


@jit
def _point_contact(x, u, pprm, env, dt):
    """Backward-Euler seabed spring-damper of a free point below the seabed after a step,
    as ``_kernels._implicit_contact`` for the nodes (unconditionally stable)."""
    zb = env[E_ZB]
    kb = pprm[PP_KB]
    if kb <= 0.0 or x[2] >= zb:
        return
    mz = pprm[PP_MASS] + pprm[PP_CA] * env[E_RHO_W] * pprm[PP_VOLUME]
    cb = pprm[PP_CB]
    ws = u[2]
    num = mz * ws - dt * kb * (x[2] - dt * ws - zb)
    w1 = num / (mz + dt * cb + dt * dt * kb)
    if w1 >= 0.0:
        w1 = num / (mz + dt * dt * kb)
    x[2] = x[2] + dt * (w1 - ws)
    u[2] = w1


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
            Z = _end_impedance(rs, ps, _AT_START)
            Zs[sp] += Z
            for c in range(3):
                G[sp, c] += Ns[0, 0, c] + Z * vs[0, 0, c]
        if kind[ep] == FREE:
            Z = _end_impedance(rs, ps, _AT_END)
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
            Z = _end_impedance(rs, ps, _AT_START)
            for c in range(3):
                Nst[0, c] = Ns[0, 0, c] + Z * (vs[0, 0, c] - pvel[sp, c])
        if kind[ep] == FREE:
            Z = _end_impedance(rs, ps, _AT_END)
            for c in range(3):
                Nst[K, c] = Ns[K - 1, Np - 1, c] + Z * (pvel[ep, c] - vs[K - 1, Np - 1, c])
        _k._acceleration(rs, vs, ps, D, LIFT, _nodes(q, sec, s), Ns, Nst, _nodes(a, sec, s),
                         None)  # fa as the single line passes it: one signature


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
def _damping_rhs(v, avel, fvel, prm, D, LIFT, qt, faces, tng, cn, e):
    """Right-hand side C T^T Grad(v) of the damping system, the end values of Grad ``avel`` and
    ``fvel`` (as ``_kernels._damping_solve_ends``)."""
    K, Np = v.shape[0], v.shape[1]
    jac = 2.0 / prm[_k.P_H]
    _k._gradient(v, avel, fvel, D, LIFT, jac, faces, qt)
    for k in range(K):
        for i in range(Np):
            e[k * Np + i] = cn[k, i] * (tng[k, i, 0] * qt[k, i, 0] + tng[k, i, 1] * qt[k, i, 1]
                                        + tng[k, i, 2] * qt[k, i, 2])


@jit
def _end_lift(v, prm, LIFT, dt, tng, minv, at_start, Z, du):
    """v += dt M_eff^-1 d(dN)/ds of the end-face flux change of a free point's velocity change
    ``du``: the penalty Z (v_end - u) of the end flux moves by Z du at either end (with the sign
    of the face), which the strong-form lift spreads over the end element."""
    K, Np = v.shape[0], v.shape[1]
    jac = 2.0 / prm[_k.P_H]
    k = 0 if at_start else K - 1
    col = 0 if at_start else 1
    for i in range(Np):
        f = dt * jac * LIFT[i, col] * Z
        fx, fy, fz = f * du[0], f * du[1], f * du[2]
        dot = minv[k, i, 1] * (tng[k, i, 0] * fx + tng[k, i, 1] * fy + tng[k, i, 2] * fz)
        v[k, i, 0] += minv[k, i, 0] * fx + dot * tng[k, i, 0]
        v[k, i, 1] += minv[k, i, 0] * fy + dot * tng[k, i, 1]
        v[k, i, 2] += minv[k, i, 0] * fz + dot * tng[k, i, 2]


@jit
def _end_masses(r, q, prm, tng, minv, K, Np):
    """Tangents and inverse Morison masses (as ``_kernels._damping_system``) of the end
    elements' nodes, from the tangent field q of the state r: for :func:`_end_lift` on a
    section without implicit damping."""
    m = prm[_k.P_M]
    for k in (0, K - 1):
        for i in range(Np):
            ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
            for c in range(3):
                tng[k, i, c] = q[k, i, c] / ql if ql > 0.0 else 0.0
            sub = r[k, i, 2] < 0.0
            mn = m + (prm[_k.P_MAN] if sub else 0.0)
            mt = m + (prm[_k.P_MAT] if sub else 0.0)
            minv[k, i, 0] = 1.0 / mn
            minv[k, i, 1] = 1.0 / mt - 1.0 / mn


@jit
def _dense_solve(A, b, n):
    """Solve A[:n, :n] x = b[:n] in place (Gaussian elimination, partial pivoting); x in b."""
    for col in range(n):
        piv = col
        big = abs(A[col, col])
        for rr in range(col + 1, n):
            if abs(A[rr, col]) > big:
                big = abs(A[rr, col])
                piv = rr
        if piv != col:
            for cc in range(n):
                A[col, cc], A[piv, cc] = A[piv, cc], A[col, cc]
            b[col], b[piv] = b[piv], b[col]
        for rr in range(col + 1, n):
            lf = A[rr, col] / A[col, col]
            if lf == 0.0:
                continue
            for cc in range(col, n):
                A[rr, cc] -= lf * A[col, cc]
            b[rr] -= lf * b[col]
    for rr in range(n - 1, -1, -1):
        acc = b[rr]
        for cc in range(rr + 1, n):
            acc -= A[rr, cc] * b[cc]
        b[rr] = acc / A[rr, rr]


@jit
def _damping_phase(r, v, u, dt, sec, prm, ops, kind, pprm, env, x, ppos, pvel, q, qt, N, faces,
                   slack, tmp, tng, minv, cn, flags, Y, band, e, info, resp, coupling):
    """After the SSP-RK3 step: each section's implicit seabed contact, its backward-Euler
    Kelvin-Voigt step, and its slack filter, with the free points' velocities in the
    damping step (``ppos``/``pvel`` hold every point's data at t + dt).

    A section between fixed and body points takes ``_kernels._damping_solve_ends`` as a line.
    At a free point the sections' damping steps and the point's are one backward-Euler step:
    with the factored system frozen, each section's damping tension is affine in the velocity
    changes du of its free end points, s = s0 + W du (``resp`` caches W, three solves per free
    end, made again with the factors); each free point takes

        (M_eff + dt sum_j Z_j) du = dt sum_j (+-) t_j s_j,

    the damping fluxes t s of its sections' end nodes (+ at a section's start, - at its end)
    answered as the Riemann junction answers the elastic ones: the point's velocity change
    moves each section's end flux by Z_j du (``_end_lift``, which enters W), so every section
    sees the same flux, the point the reaction of what it exerts, and a massless joint carries
    its sections' damping forces across. The free points joined through sections (groups,
    ``coupling``) each solve one small dense system. ``units`` holds the unit velocities and a
    zero one, writable as ``pvel`` is: each helper compiles for one argument type. Without implicit damping at any free
    point this is the sections' own step (``du`` = 0), bit for bit."""
    sact, H, hrhs, du, gpts, goff, gidx, units = coupling
    S = sec.shape[0]
    coupled = False
    for s in range(S):
        ps = prm[s]
        if ps[_k.P_IMPLICIT_DAMPING] != 0.0 and ps[_k.P_CINT] > 0.0 and (
                kind[sec[s, S_START]] == FREE or kind[sec[s, S_END]] == FREE):
            coupled = True
    for s in range(S):
        K, Np = sec[s, S_K], sec[s, S_NP]
        ps = prm[s]
        D, LIFT, F, w = _ops(ops, sec, s)
        rs, vs = _nodes(r, sec, s), _nodes(v, sec, s)
        no, fo, eo = sec[s, S_NODE], sec[s, S_FACE], sec[s, S_ELEM]
        sp, ep = sec[s, S_START], sec[s, S_END]
        nn = K * Np
        deferred = coupled and (kind[sp] == FREE or kind[ep] == FREE)
        sact[s] = 0.0
        if ps[_k.P_IMPLICIT_CONTACT] != 0.0:
            _k._implicit_contact(rs, vs, ps, dt)
        tngs = _nodes(tng, sec, s)
        minvs = minv[no:no + nn].reshape((K, Np, 2))
        qs, qts, Ns = _nodes(q, sec, s), _nodes(qt, sec, s), _nodes(N, sec, s)
        fcs = faces[fo:fo + K + 1]
        if ps[_k.P_IMPLICIT_DAMPING] != 0.0 and ps[_k.P_CINT] > 0.0:
            yo, bo = sec[s, S_Y], sec[s, S_BAND]
            Ys = Y[yo:yo + nn * (Np + 1) * 3].reshape((K, Np, Np + 1, 3))
            bs = band[bo:bo + nn * 3 * Np].reshape((nn, 3 * Np))
            cns = cn[no:no + nn].reshape((K, Np))
            flg = flags[no:no + nn].reshape((K, Np))
            es = e[no:no + nn]
            if _k._damping_system(rs, ppos[sp], ppos[ep], ps, D, LIFT, dt, qs, fcs, tngs,
                                  minvs, cns, flg, Ys, bs, info[s]):
                if not deferred:
                    _k._damping_solve_ends(vs, pvel[sp], pvel[ep], ps, D, LIFT, dt, qts, Ns,
                                           fcs, tngs, minvs, cns, bs, es)
                else:
                    sact[s] = 1.0
                    kl, ku = 2 * Np - 1, Np
                    if info[s, 4] != info[s, 3]:  # responses of the new factors
                        for end in range(2):
                            pt = sp if end == 0 else ep
                            if kind[pt] != FREE:
                                continue
                            Z = _end_impedance(rs, ps, end == 0)
                            for c in range(3):
                                for k in range(K):
                                    for i in range(Np):
                                        for cc in range(3):
                                            Ns[k, i, cc] = 0.0
                                _end_lift(Ns, ps, LIFT, dt, tngs, minvs, end == 0, Z, units[c])
                                col = resp[end, c, no:no + nn]
                                if end == 0:
                                    _damping_rhs(Ns, units[c], units[3], ps, D, LIFT, qts, fcs,
                                                 tngs, cns, col)
                                else:
                                    _damping_rhs(Ns, units[3], units[c], ps, D, LIFT, qts, fcs,
                                                 tngs, cns, col)
                                band_solve(bs, nn, kl, ku, col)
                        info[s, 4] = info[s, 3]
                    _damping_rhs(vs, pvel[sp], pvel[ep], ps, D, LIFT, qts, fcs, tngs, cns, es)
                    band_solve(bs, nn, kl, ku, es)
        elif deferred:
            _k._gradient(rs, ppos[sp], ppos[ep], D, LIFT, 2.0 / ps[_k.P_H], fcs, qs)
            _end_masses(rs, qs, ps, tngs, minvs, K, Np)
        if not deferred and ps[_k.P_FILTER] != 0.0:
            _k._filter_slack(vs, F, slack[eo:eo + K], tmp)
    if not coupled:
        return
    # the free points' velocity changes, group by group
    P = kind.shape[0]
    rho_w = env[E_RHO_W]
    for g in range(goff.shape[0] - 1):
        m3 = 3 * (goff[g + 1] - goff[g])
        for i in range(m3):
            hrhs[i] = 0.0
            for j in range(m3):
                H[i, j] = 0.0
        for li in range(goff[g + 1] - goff[g]):
            p = gpts[goff[g] + li]
            meff = pprm[p, PP_MASS] + (pprm[p, PP_CA] * rho_w * pprm[p, PP_VOLUME]
                                       if x[p, 2] < 0.0 else 0.0)
            for a in range(3):
                H[3 * li + a, 3 * li + a] = meff
        for s in range(S):
            K, Np = sec[s, S_K], sec[s, S_NP]
            rs = _nodes(r, sec, s)
            no, nn = sec[s, S_NODE], K * Np
            for end in range(2):
                pt = sec[s, S_START] if end == 0 else sec[s, S_END]
                if kind[pt] != FREE or gidx[pt, 0] != g:
                    continue
                li = gidx[pt, 1]
                Z = _end_impedance(rs, prm[s], end == 0)
                for a in range(3):
                    H[3 * li + a, 3 * li + a] += dt * Z
                if sact[s] == 0.0:
                    continue
                node = no if end == 0 else no + nn - 1
                sigma = dt if end == 0 else -dt
                for a in range(3):
                    hrhs[3 * li + a] += sigma * tng[node, a] * e[node]
                for end2 in range(2):
                    pt2 = sec[s, S_START] if end2 == 0 else sec[s, S_END]
                    if kind[pt2] != FREE:
                        continue
                    lj = gidx[pt2, 1]
                    for a in range(3):
                        for c in range(3):
                            H[3 * li + a, 3 * lj + c] -= (sigma * tng[node, a]
                                                          * resp[end2, c, node])
        _dense_solve(H, hrhs, m3)
        for li in range(goff[g + 1] - goff[g]):
            p = gpts[goff[g] + li]
            for c in range(3):
                du[p, c] = hrhs[3 * li + c]
    # the sections at free points: damping tension s0 + W du, the penalty's share, filter
    for s in range(S):
        K, Np = sec[s, S_K], sec[s, S_NP]
        sp, ep = sec[s, S_START], sec[s, S_END]
        if kind[sp] != FREE and kind[ep] != FREE:
            continue
        ps = prm[s]
        D, LIFT, F, w = _ops(ops, sec, s)
        rs, vs = _nodes(r, sec, s), _nodes(v, sec, s)
        no, fo, eo = sec[s, S_NODE], sec[s, S_FACE], sec[s, S_ELEM]
        nn = K * Np
        tngs = _nodes(tng, sec, s)
        minvs = minv[no:no + nn].reshape((K, Np, 2))
        if sact[s] != 0.0:
            for end in range(2):
                pt = sp if end == 0 else ep
                if kind[pt] != FREE:
                    continue
                for i in range(nn):
                    e[no + i] += (resp[end, 0, no + i] * du[pt, 0]
                                  + resp[end, 1, no + i] * du[pt, 1]
                                  + resp[end, 2, no + i] * du[pt, 2])
            _k._damping_apply(vs, ps, D, LIFT, dt, _nodes(qt, sec, s), _nodes(N, sec, s),
                           faces[fo:fo + K + 1], tngs, minvs, e[no:no + nn])
        for end in range(2):
            pt = sp if end == 0 else ep
            if kind[pt] == FREE:
                _end_lift(vs, ps, LIFT, dt, tngs, minvs, end == 0,
                          _end_impedance(rs, ps, end == 0), du[pt])
        if ps[_k.P_FILTER] != 0.0:
            _k._filter_slack(vs, F, slack[eo:eo + K], tmp)
    for p in range(P):
        if kind[p] == FREE:
            for c in range(3):
                u[p, c] += du[p, c]


@jit
def dgs_damping_step(r, v, x, u, dt, sec, prm, ops, kind, pprm, env, ppos, pvel, q, qt, N,
                     faces, slack, tmp, tng, minv, cn, flags, Y, band, e, info, resp, coupling):
    """The step after SSP-RK3 alone (:func:`_damping_phase`) at the state (r, v, x, u):
    ``ppos``/``pvel`` give the body points; fixed and free points take their state. For the
    tests against the NumPy reference (``system_damping_step``)."""
    for p in range(kind.shape[0]):
        if kind[p] != BODY:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c] if kind[p] == FREE else 0.0
    _damping_phase(r, v, u, dt, sec, prm, ops, kind, pprm, env, x, ppos, pvel, q, qt, N, faces,
                   slack, tmp, tng, minv, cn, flags, Y, band, e, info, resp, coupling)


@jit
def _system_step(r, v, x, u, t, dt, t0, t1, bp0, bw0, bp1, bw1, sec, prm, ops, kind, body,
                 pprm, env, work, pwork, q, qt, N, Nstar, faces, slack, ppos, pvel, G, Zs, tmp,
                 bcd, tng, minv, cn, flags, Y, band, e, info, resp, coupling):
    """One SSP-RK3 step of every section and free point from t to t + dt, then each
    section's implicit contact, the implicit internal damping (with the free points,
    :func:`_damping_phase`) and slack filter."""
    r1, v1, r2, v2, a = work[0], work[1], work[2], work[3], work[4]
    x1, u1, x2, u2, ue = pwork[0], pwork[1], pwork[2], pwork[3], pwork[4]
    n = r.shape[0]
    P = kind.shape[0]
    for b in range(bp0.shape[0]):
        _k._hermite_derivatives(t0, t1, bp0[b], bw0[b], bp1[b], bw1[b], t, bcd[b])
    # stage 1
    _prescribed(kind, body, bcd, _STAGES[0], dt, x, u, ppos, pvel)
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
    _prescribed(kind, body, bcd, _STAGES[1], dt, x1, u1, ppos, pvel)
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
    _prescribed(kind, body, bcd, _STAGES[2], dt, x2, u2, ppos, pvel)
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
            _point_contact(x[p], u[p], pprm[p], env, dt)
    # the end data at t + dt for the damping step
    for p in range(P):
        if kind[p] == BODY:
            b = body[p]
            _k.hermite(t0, t1, bp0[b], bw0[b], bp1[b], bw1[b], t + dt, ppos[p], pvel[p])
        else:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c] if kind[p] == FREE else 0.0
    _damping_phase(r, v, u, dt, sec, prm, ops, kind, pprm, env, x, ppos, pvel, q, qt, N, faces,
                   slack, tmp, tng, minv, cn, flags, Y, band, e, info, resp, coupling)


#: Passes of the recorded balance of a massless joint whose sections' damping tensions depend
#: on its velocity (``dgs_record``): the balance is affine in it but for the clip of a tension
#: at zero and a one-element section's other end, so the second pass normally confirms it.
RECORD_PASSES = 6
#: The balance velocity has converged when a pass changes it by less than this [m/s] (far
#: below anything the end forces can resolve: Z du is then ~1e-10 N for a chain).
RECORD_VELOCITY_TOL = 1e-14


@jit
def _damped_balance(p, x, u, sec, prm, ops, kind, pprm, env, pvel, G, Zs, q, qt):
    """Balance velocity of the massless free point p (sum of its end fluxes zero) with the
    damping tensions of its sections' end nodes linearised in it: an end node's strain rate
    moves with the end velocity w by jac L (L the lift entry of the end node, L > 0), so its
    flux on p by -(Z I + c_int jac L t t^T) w. Linearised about ``pvel[p]`` (G, Zs and the
    fields q, qt from a pass with it); returns the change of ``pvel[p]``, or -1.0 when p has
    mass or no damped section end (then ``pvel[p]`` is left to ``_free_velocity``)."""
    rho_w, g = env[E_RHO_W], env[E_G]
    sub = x[p, 2] < 0.0
    M = pprm[p, PP_MASS]
    if M + (pprm[p, PP_CA] * rho_w * pprm[p, PP_VOLUME] if sub else 0.0) != 0.0:
        return -1.0
    dxx, dyy, dzz, dxy, dxz, dyz = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    damped = False
    for s in range(sec.shape[0]):
        ps = prm[s]
        cint = ps[_k.P_CINT]
        if cint <= 0.0:
            continue
        K, Np = sec[s, S_K], sec[s, S_NP]
        D, LIFT, F, w = _ops(ops, sec, s)
        qs, qts = _nodes(q, sec, s), _nodes(qt, sec, s)
        jac = 2.0 / ps[_k.P_H]
        for end in range(2):
            if (sec[s, S_START] if end == 0 else sec[s, S_END]) != p:
                continue
            k, i = (0, 0) if end == 0 else (K - 1, Np - 1)
            L = LIFT[0, 0] if end == 0 else LIFT[Np - 1, 1]
            ql = math.sqrt(qs[k, i, 0] ** 2 + qs[k, i, 1] ** 2 + qs[k, i, 2] ** 2)
            if ql <= 1.0:
                continue
            deps = (qs[k, i, 0] * qts[k, i, 0] + qs[k, i, 1] * qts[k, i, 1]
                    + qs[k, i, 2] * qts[k, i, 2]) / ql
            if ps[_k.P_EA] * (ql - 1.0) + cint * deps <= 0.0:
                continue  # clipped at zero: the tension does not move with w
            damped = True
            d = cint * jac * L
            tx, ty, tz = qs[k, i, 0] / ql, qs[k, i, 1] / ql, qs[k, i, 2] / ql
            dxx += d * tx * tx
            dyy += d * ty * ty
            dzz += d * tz * tz
            dxy += d * tx * ty
            dxz += d * tx * tz
            dyz += d * ty * tz
    if not damped:
        return -1.0
    # the other forces as _free_velocity's (drag and friction linearised about the state u)
    fz = ((rho_w * pprm[p, PP_VOLUME] if sub else 0.0) - M) * g
    cd = 0.0
    if sub and pprm[p, PP_DRAG_AREA] > 0.0:
        w2 = 0.0
        for c in range(3):
            w2 += (env[E_U + c] - u[p, c]) ** 2
        cd = 0.5 * rho_w * pprm[p, PP_DRAG_AREA] * math.sqrt(w2)
    cf = 0.0
    if x[p, 2] < env[E_ZB] and pprm[p, PP_FRICTION] > 0.0:
        speed = math.sqrt(u[p, 0] ** 2 + u[p, 1] ** 2)
        vc = env[E_VC]
        if speed > 0.0:
            cf = pprm[p, PP_FRICTION] * math.sin(0.5 * math.pi * speed / max(vc, speed)) / speed
        else:
            cf = pprm[p, PP_FRICTION] * 0.5 * math.pi / vc
    w0x, w0y, w0z = pvel[p, 0], pvel[p, 1], pvel[p, 2]
    bx = G[p, 0] + cd * env[E_U] + dxx * w0x + dxy * w0y + dxz * w0z
    by = G[p, 1] + cd * env[E_U + 1] + dxy * w0x + dyy * w0y + dyz * w0z
    bz = G[p, 2] + cd * env[E_U + 2] + fz + dxz * w0x + dyz * w0y + dzz * w0z
    axx = Zs[p] + cd + cf + dxx
    ayy = Zs[p] + cd + cf + dyy
    azz = Zs[p] + cd + dzz
    # Cramer's rule of the symmetric 3x3 system
    c00 = ayy * azz - dyz * dyz
    c01 = dxz * dyz - dxy * azz
    c02 = dxy * dyz - dxz * ayy
    det = axx * c00 + dxy * c01 + dxz * c02
    c11 = axx * azz - dxz * dxz
    c12 = dxy * dxz - axx * dyz
    c22 = axx * ayy - dxy * dxy
    wx = (c00 * bx + c01 * by + c02 * bz) / det
    wy = (c01 * bx + c11 * by + c12 * bz) / det
    wz = (c02 * bx + c12 * by + c22 * bz) / det
    change = max(abs(wx - w0x), abs(wy - w0y), abs(wz - w0z))
    pvel[p, 0], pvel[p, 1], pvel[p, 2] = wx, wy, wz
    return change


@jit
def dgs_record_shape(r, N, shape_r, shape_t, n_shape):
    """The system's shape record ``n_shape``: every node's position and tension |N|."""
    for i in range(r.shape[0]):
        shape_t[n_shape, i] = math.sqrt(N[i, 0] ** 2 + N[i, 1] ** 2 + N[i, 2] ** 2)
        for c in range(3):
            shape_r[n_shape, i, c] = r[i, c]


@jit
def dgs_record(r, v, x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N, Nstar,
               faces, slack, ue, start_out, end_out, laid_out):
    """End forces of every section on its start and end point [N] (``start_out``,
    ``end_out``: (sections, 3)) and laid lengths [m] at the current state, with the internal
    damping in the tension. ``ppos``/``pvel`` hold the body points' data; fixed points take
    their position at rest, free points their state, massless ones their balance velocity:
    the sum of their end fluxes is zero, the damping tensions included (``_damped_balance``,
    up to ``RECORD_PASSES`` passes)."""
    S = sec.shape[0]
    P = kind.shape[0]
    for p in range(P):
        if kind[p] != BODY:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c] if kind[p] == FREE else 0.0
    for it in range(RECORD_PASSES):
        for p in range(P):
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
                Z = _end_impedance(rs, ps, _AT_START)
                Zs[sp] += Z
                for c in range(3):
                    G[sp, c] += Ns[0, 0, c] + Z * vs[0, 0, c]
            if kind[ep] == FREE:
                Z = _end_impedance(rs, ps, _AT_END)
                Zs[ep] += Z
                for c in range(3):
                    G[ep, c] += -Ns[K - 1, Np - 1, c] + Z * vs[K - 1, Np - 1, c]
        change = 0.0
        for p in range(P):
            if kind[p] != FREE:
                continue
            dp = _damped_balance(p, x, u, sec, prm, ops, kind, pprm, env, pvel, G, Zs, q, qt)
            if dp < 0.0:
                if it == 0:  # mass, or no damped end: the state's or the elastic balance
                    _free_velocity(x[p], u[p], pprm[p], env, G[p], Zs[p], 0.0, ue[p])
                    for c in range(3):
                        pvel[p, c] = ue[p, c]
            else:
                change = max(change, dp)
        if change <= RECORD_VELOCITY_TOL:
            break
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
                 minv, cn, flags, Y, band, e, info, resp, coupling, where):
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
    n_shape = _I0  # (an int64 from the start: one signature of dgs_record_shape)
    for s in range(n):
        if shape_every > 0 and s % shape_every == 0:
            dgs_record_shape(r, N, shape_r, shape_t, n_shape)
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
                         flags, Y, band, e, info, resp, coupling)
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
