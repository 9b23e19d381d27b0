"""Numba kernels of the implicit (generalised-alpha) step of a DG mooring system
(docs/theory/dynamic_line.md#mooring-systems).

The sections' nodes and the free points advance together with the generalised-alpha method of
``_implicit_kernels`` (Chung & Hulbert 1993, force-interpolating form): the unknowns of a step
are the acceleration variables of every node and of every free point, the body points follow
their paths (cubic Hermite) and the fixed points stay. A free point of effective mass M_eff
(M + C_a rho_w V below z = 0) takes the residual

    M_eff ((1 - alpha_m) a1 + alpha_m a0) - (1 - alpha_f) F(t1) - alpha_f F(t0) = 0,

F the sum of its sections' end fluxes (N* at a start, -N* at an end, with the point's own
velocity in the Lax-Friedrichs penalty), its weight and buoyancy, drag, and seabed
spring-damper and friction (the nodes' forms of ``_system_kernels``, here inside the solve).
For a massless joint it is the limit M_eff -> 0: the force balance at the generalised
midpoint. The nodes' residual is the single line's (``_implicit_kernels._ga_step``).

Newton's matrix is bordered banded: every section's block is the single line's banded
Jacobian (``_implicit_kernels.dg_jacobian``, its ends held), coupled to the point unknowns
through the end conditions: the lift of an end position into the end element's gradient
(``_kernels._gradient``) and the penalty Z (v_end - u) at the end face (columns ``B`` of a
section, rows ``C`` of its end points' forces), and the points' own 3 x 3 blocks. It is solved
exactly by block elimination: each section's banded LU, W = J_s^-1 B_s, and the dense Schur
complement S = J_pp - sum_s C_s W_s on the free points' unknowns (3 per free point, LU with
partial pivoting). Factors are reused over iterations and steps while Newton contracts, as
the single line's.

The step size, error estimate (the end-force error of every section's end node from the
change of the acceleration variable) and halving / doubling per sample interval are the
single line's (``_implicit_kernels.dg_run_path_implicit``).

Size: one step's residual, bordered Jacobian, Schur solve and the path loop share the layout
of ``_system_kernels``; split, each part would need all of it.
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring.dg import _implicit_kernels as _ik
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg import _system_kernels as _s
from floatmoor.mooring.dg._banded_kernels import band_factor, band_solve

#: Newton's stopping test of a system step: the correction itself, throughout (a system has
#: one force tolerance and no snap window; ``_implicit_kernels.newton_converged``). Typed, not
#: the literal True, which would compile the test once more
#: (docs/development.md#numba-compile-time).
_STRICT = np.bool_(True)

__all__ = ["dgi_forces", "dgi_jacobian", "dgi_solve", "dgi_run_path", "dense_factor",
           "dense_solve"]


@jit
def _nodes4(a, sec, s):
    """Section s's slice of a (nodes, 3, 3) array as (K, Np, 3, 3)."""
    K, Np, o = sec[s, _s.S_K], sec[s, _s.S_NP], sec[s, _s.S_NODE]
    return a[o:o + K * Np].reshape((K, Np, 3, 3))


@jit
def _band(bands, boff, sec, s):
    """Section s's band matrix (3 K Np, 9 Np + 2)."""
    Np = sec[s, _s.S_NP]
    n = 3 * sec[s, _s.S_K] * Np
    return bands[boff[s]:boff[s + 1]].reshape((n, 9 * Np + 2))


@jit
def _border(a, sec, s):
    """Section s's border (3 K Np, 6) of a flat array (18 per node)."""
    n = 3 * sec[s, _s.S_K] * sec[s, _s.S_NP]
    o = 18 * sec[s, _s.S_NODE]
    return a[o:o + 6 * n].reshape((n, 6))


@jit
def _point_data(kind, body, x, u, t0s, t1s, bp0, bw0, bp1, bw1, t, ppos, pvel):
    """End data of every point at time t: fixed where they are at rest, body points on their
    path's Hermite cubic, free points their (iterated) state."""
    for p in range(kind.shape[0]):
        if kind[p] == _s.BODY:
            b = body[p]
            _k.hermite(t0s, t1s, bp0[b], bw0[b], bp1[b], bw1[b], t, ppos[p], pvel[p])
        else:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c] if kind[p] == _s.FREE else 0.0


@jit
def _effective_mass(x, pprm, env):
    """M + C_a rho_w V below z = 0, M above."""
    if x[2] < 0.0:
        return pprm[_s.PP_MASS] + pprm[_s.PP_CA] * env[_s.E_RHO_W] * pprm[_s.PP_VOLUME]
    return pprm[_s.PP_MASS]


@jit
def _point_external(x, u, pprm, env, kc, cc, F, H):
    """F += the external force on a free point (weight, buoyancy, drag, seabed contact and
    friction, as ``_system_kernels``) [N]; H (3, 3) += -kc dF/dx - cc dF/du."""
    rho_w, g = env[_s.E_RHO_W], env[_s.E_G]
    sub = x[2] < 0.0
    M = pprm[_s.PP_MASS]
    F[2] += ((rho_w * pprm[_s.PP_VOLUME] if sub else 0.0) - M) * g
    if sub and pprm[_s.PP_DRAG_AREA] > 0.0:
        w0, w1, w2 = env[_s.E_U] - u[0], env[_s.E_U + 1] - u[1], env[_s.E_U + 2] - u[2]
        wv = (w0, w1, w2)
        wl = math.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
        cd = 0.5 * rho_w * pprm[_s.PP_DRAG_AREA]
        for a in range(3):
            F[a] += cd * wl * wv[a]
            # dF/du = -cd (|w| I + w w^T / |w|)
            H[a, a] += cc * cd * wl
            if wl > 0.0:
                for b in range(3):
                    H[a, b] += cc * cd * wv[a] * wv[b] / wl
    zb = env[_s.E_ZB]
    if x[2] < zb:
        kb, cb = pprm[_s.PP_KB], pprm[_s.PP_CB]
        if kb > 0.0:
            F[2] += -kb * (x[2] - zb) - cb * min(u[2], 0.0)
            H[2, 2] += kc * kb + (cc * cb if u[2] < 0.0 else 0.0)
        friction = pprm[_s.PP_FRICTION]
        if friction > 0.0:
            vc = env[_s.E_VC]
            vx, vy = u[0], u[1]
            speed = math.sqrt(vx * vx + vy * vy)
            if speed > 0.0:
                mag = friction * math.sin(0.5 * math.pi * speed / max(vc, speed))
                F[0] -= mag * vx / speed
                F[1] -= mag * vy / speed
            # -dF/du in the seabed plane, as _implicit_kernels._node_blocks
            if speed < vc:
                xs = 0.5 * math.pi / vc
                radial = friction * xs * math.cos(xs * speed)
                lateral = friction * (math.sin(xs * speed) / speed if speed > 0.0 else xs)
            else:
                radial = 0.0
                lateral = friction / speed
            ux, uy = (vx / speed, vy / speed) if speed > 0.0 else (0.0, 0.0)
            uv = (ux, uy)
            for a in range(2):
                for b in range(2):
                    pr = (1.0 if a == b else 0.0) - uv[a] * uv[b]
                    H[a, b] += cc * (lateral * pr + radial * uv[a] * uv[b])


@jit
def dgi_forces(r, v, x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, q, qt, N, Nstar, faces,
               slack, A, Fp, H):
    """The system's accelerations with everything in the right-hand side: A = M_eff^-1 F of
    every node (nodes, 3) and the force on every free point ``Fp`` (points, 3; zero for the
    others) [N]. ``ppos``/``pvel`` hold the fixed and body points' data (the free points'
    are set from x, u); ``prm`` the sections' implicit parameters (internal damping and
    seabed contact in the right-hand side); ``H`` (3, 3) scratch."""
    P = kind.shape[0]
    for p in range(P):
        for c in range(3):
            Fp[p, c] = 0.0
            if kind[p] == _s.FREE:
                ppos[p, c] = x[p, c]
                pvel[p, c] = u[p, c]
    for s in range(sec.shape[0]):
        K = sec[s, _s.S_K]
        ps = prm[s]
        D, LIFT, F, w = _s._ops(ops, sec, s)
        rs, vs = _s._nodes(r, sec, s), _s._nodes(v, sec, s)
        qs, Ns = _s._nodes(q, sec, s), _s._nodes(N, sec, s)
        fo, eo = sec[s, _s.S_FACE], sec[s, _s.S_ELEM]
        sp, ep = sec[s, _s.S_START], sec[s, _s.S_END]
        Nst = Nstar[fo:fo + K + 1]
        _k._tension_field(rs, vs, ppos[sp], pvel[sp], ppos[ep], pvel[ep], ps, D, LIFT, qs,
                          _s._nodes(qt, sec, s), Ns, Nst, faces[fo:fo + K + 1],
                          slack[eo:eo + K], ps[_k.P_CINT])
        _k._acceleration(rs, vs, ps, D, LIFT, qs, Ns, Nst, _s._nodes(A, sec, s), None)
        if kind[sp] == _s.FREE:
            for c in range(3):
                Fp[sp, c] += Nst[0, c]
        if kind[ep] == _s.FREE:
            for c in range(3):
                Fp[ep, c] -= Nst[K, c]
    for p in range(P):
        if kind[p] == _s.FREE:
            _point_external(x[p], u[p], pprm[p], env, 0.0, 0.0, Fp[p], H)


@jit
def _gcoef(K, Np, D, LIFT, jac, kk, jj, mm):
    """d q(kk, jj) / d r(kk, mm) of the DG gradient (``_kernels._gradient``)."""
    g = jac * D[jj, mm]
    if mm == 0:
        g += jac * LIFT[jj, 0]
    if mm == Np - 1 and kk == K - 1:
        g -= jac * LIFT[jj, 1]
    return g


@jit
def _add3(dst, ro, co, scale, blk):
    """dst[ro + a, co + b] += scale blk[a, b]."""
    for a in range(3):
        for b in range(3):
            dst[ro + a, co + b] += scale * blk[a, b]


@jit
def _add_eye(dst, ro, co, value):
    for a in range(3):
        dst[ro + a, co + a] += value


@jit
def dgi_jacobian(r, v, x, u, sec, prm, ops, kind, pprm, env, fslot, q, qt, acoef, kc, cc, E,
                 Dg, bands, boff, B, C, Spp, H, F3):
    """Newton's bordered matrix of the system at its state (``q``, ``qt`` from
    :func:`dgi_forces` there): every section's band (``_implicit_kernels.dg_jacobian``),
    its border columns ``B`` (rows of its nodes, columns 3 x start point, 3 x end point) and
    rows ``C`` (3 x start point, 3 x end point; stored transposed, (3 K Np, 6)) for its free
    end points, and the free points' block ``Spp`` (3 x free points square, ``fslot`` the slot
    of every point). J = acoef M - kc dF/d(position) - cc dF/d(velocity). ``H`` (3, 3) and
    ``F3`` (3) scratch."""
    for a in range(Spp.shape[0]):
        for b in range(Spp.shape[1]):
            Spp[a, b] = 0.0
    for s in range(sec.shape[0]):
        K, Np = sec[s, _s.S_K], sec[s, _s.S_NP]
        ps = prm[s]
        D, LIFT, F, w = _s._ops(ops, sec, s)
        rs, vs = _s._nodes(r, sec, s), _s._nodes(v, sec, s)
        Es = _nodes4(E, sec, s)
        _ik.dg_jacobian(rs, vs, _s._nodes(q, sec, s), _s._nodes(qt, sec, s), ps, D, LIFT,
                        acoef, kc, cc, Es, _nodes4(Dg, sec, s), _band(bands, boff, sec, s),
                        None)  # fa as the single line passes it: one signature
        Bs, Cs = _border(B, sec, s), _border(C, sec, s)
        for i in range(Bs.shape[0]):
            for c in range(6):
                Bs[i, c] = 0.0
                Cs[i, c] = 0.0
        jac = 2.0 / ps[_k.P_H]
        sp, ep = sec[s, _s.S_START], sec[s, _s.S_END]
        free_s, free_e = kind[sp] == _s.FREE, kind[ep] == _s.FREE
        if not (free_s or free_e):
            continue
        zs = _s._end_impedance(rs, ps, _s._AT_START)
        ze = _s._end_impedance(rs, ps, _s._AT_END)
        # B: rows (k, i) through the divergence's nodes l = (kk, jj) whose gradient takes an
        # end position: -dcoef g_end E_l
        for k in range(K):
            for i in range(Np):
                row = 3 * (k * Np + i)
                for lj in range(Np + 1):
                    if lj < Np:
                        kk, jj = k, lj
                        dcoef = jac * D[i, lj]
                        if lj == Np - 1 and k < K - 1:
                            dcoef -= jac * LIFT[i, 1]
                    else:
                        if k == K - 1:
                            continue
                        kk, jj = k + 1, 0
                        dcoef = jac * LIFT[i, 1]
                    if dcoef == 0.0:
                        continue
                    if kk == 0 and free_s:
                        _add3(Bs, row, _s._I0, dcoef * jac * LIFT[jj, 0], Es[kk, jj])
                    if kk == K - 1 and free_e:
                        _add3(Bs, row, _s._I3, -dcoef * jac * LIFT[jj, 1], Es[kk, jj])
        for i in range(Np):  # the end faces' penalty Z (v_end - u)
            if free_s:
                _add_eye(Bs, 3 * i, _s._I0, -cc * jac * LIFT[i, 0] * zs)
            if free_e:
                _add_eye(Bs, 3 * ((K - 1) * Np + i), _s._I3, -cc * jac * LIFT[i, 1] * ze)
        # C (transposed) and Spp: the start point's force N*_0 = N(0, 0) + Z (v(0, 0) - u_s),
        # the end point's -N*_K = -N(K-1, Np-1) - Z (u_e - v(K-1, Np-1))
        if free_s:
            so = 3 * fslot[sp]
            E0 = Es[0, 0]
            for mm in range(Np):
                g = _gcoef(K, Np, D, LIFT, jac, _s._I0, _s._I0, mm)
                for a in range(3):
                    for b in range(3):
                        Cs[3 * mm + b, a] -= g * E0[a, b]
            _add_eye_t(Cs, _s._I0, _s._I0, -cc * zs)
            _add3(Spp, so, so, jac * LIFT[0, 0], E0)
            _add_eye(Spp, so, so, cc * zs)
            if K == 1 and free_e:
                _add3(Spp, so, 3 * fslot[ep], -jac * LIFT[0, 1], E0)
        if free_e:
            eo = 3 * fslot[ep]
            El = Es[K - 1, Np - 1]
            base = (K - 1) * Np
            for mm in range(Np):
                g = _gcoef(K, Np, D, LIFT, jac, K - 1, Np - 1, mm)
                for a in range(3):
                    for b in range(3):
                        Cs[3 * (base + mm) + b, 3 + a] += g * El[a, b]
            if K >= 2:
                g = -jac * LIFT[Np - 1, 0]
                for a in range(3):
                    for b in range(3):
                        Cs[3 * (base - 1) + b, 3 + a] += g * El[a, b]
            _add_eye_t(Cs, 3 * (base + Np - 1), _s._I3, -cc * ze)
            _add3(Spp, eo, eo, jac * LIFT[Np - 1, 1], El)
            _add_eye(Spp, eo, eo, cc * ze)
            if K == 1 and free_s:
                _add3(Spp, eo, 3 * fslot[sp], -jac * LIFT[Np - 1, 0], El)
    for p in range(kind.shape[0]):
        if kind[p] != _s.FREE:
            continue
        o = 3 * fslot[p]
        for a in range(3):
            for b in range(3):
                H[a, b] = 0.0
        _point_external(x[p], u[p], pprm[p], env, kc, cc, F3, H)
        _add3(Spp, o, o, 1.0, H)
        _add_eye(Spp, o, o, acoef * _effective_mass(x[p], pprm[p], env))


@jit
def _add_eye_t(Ct, ro, co, value):
    """The transposed store of C: Ct[ro + a, co + a] += value."""
    for a in range(3):
        Ct[ro + a, co + a] += value


@jit
def dense_factor(A, piv):
    """LU with partial pivoting of the small dense matrix A in place; False if singular."""
    n = A.shape[0]
    for k in range(n):
        best, arg = 0.0, k
        for i in range(k, n):
            if abs(A[i, k]) > best:
                best, arg = abs(A[i, k]), i
        piv[k] = arg
        if not (best > 0.0 and math.isfinite(best)):
            return False
        if arg != k:
            for j in range(n):
                A[k, j], A[arg, j] = A[arg, j], A[k, j]
        for i in range(k + 1, n):
            A[i, k] /= A[k, k]
            f = A[i, k]
            if f != 0.0:
                for j in range(k + 1, n):
                    A[i, j] -= f * A[k, j]
    return True


@jit
def dense_solve(A, piv, b):
    """Solve with the factors of :func:`dense_factor`, ``b`` overwritten."""
    n = A.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for i in range(n):
        acc = b[i]
        for j in range(i):
            acc -= A[i, j] * b[j]
        b[i] = acc
    for i in range(n - 1, -1, -1):
        acc = b[i]
        for j in range(i + 1, n):
            acc -= A[i, j] * b[j]
        b[i] = acc / A[i, i]


@jit
def dgi_factor(sec, kind, fslot, bands, boff, B, C, W, Spp, piv, col):
    """Factor the bordered matrix of :func:`dgi_jacobian` in place: every section's band,
    W = J_s^-1 B_s (stored like B) and the Schur complement Spp - sum C_s W_s (``col``:
    scratch of the largest section's 3 K Np). False when a pivot is zero or not finite."""
    for s in range(sec.shape[0]):
        K, Np = sec[s, _s.S_K], sec[s, _s.S_NP]
        n = 3 * K * Np
        band = _band(bands, boff, sec, s)
        if band_factor(band, n, 3 * Np + 2, 6 * Np - 1) >= 0:
            return False
        sp, ep = sec[s, _s.S_START], sec[s, _s.S_END]
        Bs, Cs, Ws = _border(B, sec, s), _border(C, sec, s), _border(W, sec, s)
        for end in range(2):
            p = sp if end == 0 else ep
            if kind[p] != _s.FREE:
                for i in range(n):
                    for c in range(3):
                        Ws[i, 3 * end + c] = 0.0
                continue
            for c in range(3):
                for i in range(n):
                    col[i] = Bs[i, 3 * end + c]
                band_solve(band, n, 3 * Np + 2, 6 * Np - 1, col)
                for i in range(n):
                    Ws[i, 3 * end + c] = col[i]
        for ea in range(2):
            pa = sp if ea == 0 else ep
            if kind[pa] != _s.FREE:
                continue
            for eb in range(2):
                pb = sp if eb == 0 else ep
                if kind[pb] != _s.FREE:
                    continue
                for a in range(3):
                    for b in range(3):
                        acc = 0.0
                        for i in range(n):
                            acc += Cs[i, 3 * ea + a] * Ws[i, 3 * eb + b]
                        Spp[3 * fslot[pa] + a, 3 * fslot[pb] + b] -= acc
    if Spp.shape[0] > 0:
        return dense_factor(Spp, piv)
    return True


@jit
def dgi_solve(sec, kind, fslot, bands, boff, C, W, Spp, piv, xs, xp):
    """Solve the factored bordered system for the right-hand sides ``xs`` (3 x nodes, the
    sections') and ``xp`` (3 x free points), both overwritten by the solution."""
    S = sec.shape[0]
    for s in range(S):
        K, Np = sec[s, _s.S_K], sec[s, _s.S_NP]
        n = 3 * K * Np
        o = 3 * sec[s, _s.S_NODE]
        band_solve(_band(bands, boff, sec, s), n, 3 * Np + 2, 6 * Np - 1, xs[o:o + n])
        Cs = _border(C, sec, s)
        for end in range(2):
            p = sec[s, _s.S_START] if end == 0 else sec[s, _s.S_END]
            if kind[p] != _s.FREE:
                continue
            for a in range(3):
                acc = 0.0
                for i in range(n):
                    acc += Cs[i, 3 * end + a] * xs[o + i]
                xp[3 * fslot[p] + a] -= acc
    if xp.shape[0] == 0:
        return
    dense_solve(Spp, piv, xp)
    for s in range(S):
        K, Np = sec[s, _s.S_K], sec[s, _s.S_NP]
        n = 3 * K * Np
        o = 3 * sec[s, _s.S_NODE]
        Ws = _border(W, sec, s)
        for end in range(2):
            p = sec[s, _s.S_START] if end == 0 else sec[s, _s.S_END]
            if kind[p] != _s.FREE:
                continue
            f = 3 * fslot[p]
            for i in range(n):
                xs[o + i] -= (Ws[i, 3 * end] * xp[f] + Ws[i, 3 * end + 1] * xp[f + 1]
                              + Ws[i, 3 * end + 2] * xp[f + 2])


@jit
def _copy2(src, dst):
    for i in range(src.shape[0]):
        for c in range(3):
            dst[i, c] = src[i, c]


@jit
def _gai_step(r, v, x, u, st, nw, pw, t0s, t1s, bp0, bw0, bp1, bw1, t, dt, sec, prm, ops, kind,
              body, pprm, env, fslot, ip, cs, fields, jw, bands, boff, flat, Spp, piv, H, F3):
    """One generalised-alpha step of the system from t to t + dt (``_implicit_kernels._ga_step``
    with the free points among the unknowns). ``st`` = (acc, An, pacc, Fn): the nodes' and
    free points' acceleration variables, the nodes' acceleration A and the points' force F of
    the state, updated to the end state on success; ``nw`` = (r0, v0, a0, An0, A1, MR, R) and
    ``pw`` = (x0, u0, pa0, Fn0, Fp1, ppos, pvel) node- and point-shaped work (a0, pa0, Fn0
    hold the start's acc, pacc, Fn); ``fields`` = (q, qt, N, Nstar, faces) and the slack
    flags in ``flat[6]``; ``jw`` = (E, Dg); ``flat`` = (B, C, W, xs, xp, col, slack).

    Returns
    -------
    (converged, iterations, fresh)
        As ``_implicit_kernels._ga_step``.
    """
    acc, An, pacc, Fn = st
    a0, A1, MR, R = nw[2], nw[4], nw[5], nw[6]
    pa0, Fn0, Fp1, ppos, pvel = pw[2], pw[3], pw[4], pw[5], pw[6]
    q, qt, N, Nstar, faces = fields
    E, Dg = jw
    B, C, W, xs, xp, col, slack = flat
    n = r.shape[0]
    P = kind.shape[0]
    am, af, beta, gamma = ip[_ik.IP_ALPHA_M], ip[_ik.IP_ALPHA_F], ip[_ik.IP_BETA], ip[_ik.IP_GAMMA]
    tol = ip[_ik.IP_NEWTON_TOL]
    max_iter = int(ip[_ik.IP_MAX_ITER])
    _point_data(kind, body, x, u, t0s, t1s, bp0, bw0, bp1, bw1, t + dt, ppos, pvel)
    cr = dt * dt * 0.5
    for i in range(n):
        for c in range(3):
            r[i, c] += dt * v[i, c] + cr * a0[i, c]
            v[i, c] += dt * a0[i, c]
    for p in range(P):
        if kind[p] == _s.FREE:
            for c in range(3):
                x[p, c] += dt * u[p, c] + cr * pa0[p, c]
                u[p, c] += dt * pa0[p, c]
    acoef = 1.0 - am
    bdt2, gdt = beta * dt * dt, gamma * dt
    kc = (1.0 - af) * bdt2
    cc = (1.0 - af) * gdt
    iterations = 0
    converged = False
    fresh = False
    previous = math.inf
    grew = False
    for it in range(max_iter):
        dgi_forces(r, v, x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, q, qt, N, Nstar,
                   faces, slack, A1, Fp1, H)
        if abs(cs[_ik.CS_FACTOR_DT] - dt) > _ik.SAME_STEP * dt or grew:
            dgi_jacobian(r, v, x, u, sec, prm, ops, kind, pprm, env, fslot, q, qt, acoef, kc,
                         cc, E, Dg, bands, boff, B, C, Spp, H, F3)
            cs[_ik.CS_FACTORISATIONS] += 1.0
            fresh = True
            if not dgi_factor(sec, kind, fslot, bands, boff, B, C, W, Spp, piv, col):
                cs[_ik.CS_FACTOR_DT] = 0.0
                return False, iterations, fresh
            cs[_ik.CS_FACTOR_DT] = dt
        for i in range(n):
            for c in range(3):
                R[i, c] = acoef * acc[i, c] + am * a0[i, c] - (1.0 - af) * A1[i, c] - af * An[i, c]
        for s in range(sec.shape[0]):
            _ik._mass_times(_s._nodes(r, sec, s), _s._nodes(q, sec, s), prm[s],
                            _s._nodes(R, sec, s), _s._nodes(MR, sec, s))
        for i in range(n):
            for c in range(3):
                xs[3 * i + c] = -MR[i, c]
        for p in range(P):
            if kind[p] == _s.FREE:
                meff = _effective_mass(x[p], pprm[p], env)
                for c in range(3):
                    xp[3 * fslot[p] + c] = -(meff * (acoef * pacc[p, c] + am * pa0[p, c])
                                             - (1.0 - af) * Fp1[p, c] - af * Fn0[p, c])
        dgi_solve(sec, kind, fslot, bands, boff, C, W, Spp, piv, xs, xp)
        iterations += 1
        big = 0.0
        total = 0.0
        for i in range(n):
            for c in range(3):
                da = xs[3 * i + c]
                acc[i, c] += da
                r[i, c] += bdt2 * da
                v[i, c] += gdt * da
                d = abs(bdt2 * da)
                total += d
                if d > big:
                    big = d
        for p in range(P):
            if kind[p] == _s.FREE:
                for c in range(3):
                    da = xp[3 * fslot[p] + c]
                    pacc[p, c] += da
                    x[p, c] += bdt2 * da
                    u[p, c] += gdt * da
                    d = abs(bdt2 * da)
                    total += d
                    if d > big:
                        big = d
        if not math.isfinite(total):
            return False, iterations, fresh
        converged = _ik.newton_converged(iterations, big, previous, tol, _STRICT)
        if converged:
            break
        grew = big > 0.5 * previous
        previous = big
    if not converged:
        return False, iterations, fresh
    # the end state's A and point forces from the step's equations, not evaluated again (as
    # ``_implicit_kernels._ga_step``)
    ci = 1.0 / (1.0 - af)
    for i in range(n):
        for c in range(3):
            An[i, c] = ci * (acoef * acc[i, c] + am * a0[i, c] - af * An[i, c])
    for p in range(P):
        if kind[p] == _s.FREE:
            meff = _effective_mass(x[p], pprm[p], env)
            for c in range(3):
                Fn[p, c] = ci * (meff * (acoef * pacc[p, c] + am * pa0[p, c]) - af * Fn0[p, c])
    return True, iterations, fresh


@jit
def _save(r, v, x, u, st, nw, pw):
    """(r, v, acc, An) -> (r0, v0, a0, An0) and (x, u, pacc, Fn) -> (x0, u0, pa0, Fn0)."""
    _copy2(r, nw[0])
    _copy2(v, nw[1])
    _copy2(st[0], nw[2])
    _copy2(st[1], nw[3])
    _copy2(x, pw[0])
    _copy2(u, pw[1])
    _copy2(st[2], pw[2])
    _copy2(st[3], pw[3])


@jit
def _restore(r, v, x, u, st, nw, pw):
    """The inverse of :func:`_save`."""
    _copy2(nw[0], r)
    _copy2(nw[1], v)
    _copy2(nw[2], st[0])
    _copy2(nw[3], st[1])
    _copy2(pw[0], x)
    _copy2(pw[1], u)
    _copy2(pw[2], st[2])
    _copy2(pw[3], st[3])


@jit
def _step_error(sec, prm, ops, st, nw, fields, dt, err_coef):
    """Largest end-force error [N] over the sections' end nodes from the change of the
    acceleration variable (``_implicit_kernels._end_force_error``)."""
    acc, a0, R = st[0], nw[2], nw[6]
    q, N = fields[0], fields[2]
    c2 = err_coef * dt * dt
    for i in range(acc.shape[0]):
        for c in range(3):
            R[i, c] = c2 * (acc[i, c] - a0[i, c])
    worst = 0.0
    for s in range(sec.shape[0]):
        D, LIFT, F, w = _s._ops(ops, sec, s)
        e = _ik._end_force_error(_s._nodes(R, sec, s), _s._nodes(q, sec, s),
                                 _s._nodes(N, sec, s), prm[s], D, LIFT)
        worst = max(worst, e)
    return worst


@jit
def _end_strains(r, v, x, u, sec, prm, ops, kind, body, t0s, t1s, bp0, bw0, bp1, bw1, t, ppos,
                 pvel, out):
    """(eps, d eps/dt) of every section's end node at time t (``out`` (sections, 2)): the
    line kernel's fairlead strain (``_implicit_kernels._fairlead_strain``) with the section's
    start and end points as its anchor and fairlead (their data at t, ``_point_data``)."""
    _point_data(kind, body, x, u, t0s, t1s, bp0, bw0, bp1, bw1, t, ppos, pvel)
    for j in range(sec.shape[0]):
        D, LIFT, F, w = _s._ops(ops, sec, j)
        sp, ep = sec[j, _s.S_START], sec[j, _s.S_END]
        e, de = _ik._fairlead_strain(_s._nodes(r, sec, j), _s._nodes(v, sec, j), ppos[sp],
                                     ppos[ep], pvel[ep], prm[j], D, LIFT)
        out[j, 0] = e
        out[j, 1] = de


@jit
def _jumped_transitions(before, after, prm, dt, tol):
    """Whether any section's end crossed the slack-taut transition within the step with more
    than the force tolerance ``tol`` on its taut side (``_implicit_kernels._jumped_transition``
    per section)."""
    for j in range(before.shape[0]):
        if _ik._jumped_transition(before[j, 0], before[j, 1], after[j, 0], after[j, 1], dt,
                                  prm[j, _k.P_EA], tol):
            return True
    return False


@jit
def dgi_start(r, v, x, u, bpos, bvel, sec, prm, ops, kind, body, pprm, env, st, pw, fields,
              slack, H):
    """The state's accelerations: An, Fn (``st[1]``, ``st[3]``) and the acceleration
    variables (``st[0]``, ``st[2]``: the nodes' A, the free points' F / M_eff, 0 massless),
    the body points at (``bpos``, ``bvel``) (bodies, 3)."""
    acc, An, pacc, Fn = st
    ppos, pvel = pw[5], pw[6]
    for p in range(kind.shape[0]):
        if kind[p] == _s.BODY:
            for c in range(3):
                ppos[p, c] = bpos[body[p], c]
                pvel[p, c] = bvel[body[p], c]
        elif kind[p] == _s.FIXED:
            for c in range(3):
                ppos[p, c] = x[p, c]
                pvel[p, c] = 0.0
    q, qt, N, Nstar, faces = fields
    dgi_forces(r, v, x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, q, qt, N, Nstar, faces,
               slack, An, Fn, H)
    _copy2(An, acc)
    for p in range(kind.shape[0]):
        meff = _effective_mass(x[p], pprm[p], env)
        for c in range(3):
            pacc[p, c] = Fn[p, c] / meff if kind[p] == _s.FREE and meff > 0.0 else 0.0


@jit
def dgi_run_path(r, v, x, u, time, bpos, bvel, sec, prm, rprm, ops, kind, body, pprm, env,
                 fslot, ip, cs, st, nw, pw, fields, jw, bands, boff, flat, Spp, piv, H, F3,
                 tmp, G, Zs, start_force, end_force, laid, point_pos, steps, shape_every,
                 shape_r, shape_t, where):
    """Advance the system along its body points' paths with the generalised-alpha method,
    recording at every sample (the implicit counterpart of ``_system_kernels.dgs_run_path``,
    same outputs, ``steps`` the steps taken per interval). ``prm`` the sections' implicit
    parameters, ``rprm`` their parameters for the records (``dgs_record``). The state's
    accelerations (``st``) are computed first when ``cs[CS_ACC_VALID]`` is 0.

    Returns
    -------
    (status, index)
        As ``dgs_run_path``, or ``_implicit_kernels.DG_NEWTON`` (``where``: section, last
        element and node) when Newton fails at the smallest step.
    """
    n = time.shape[0]
    nodes = r.shape[0]
    P = kind.shape[0]
    ppos, pvel = pw[5], pw[6]
    q, qt, N, Nstar, faces = fields
    slack = flat[6]
    if cs[_ik.CS_ACC_VALID] == 0.0:
        dgi_start(r, v, x, u, bpos[0], bvel[0], sec, prm, ops, kind, body, pprm, env, st, pw,
                  fields, slack, H)
        cs[_ik.CS_ACC_VALID] = 1.0
    for p in range(P):
        if kind[p] == _s.BODY:
            for c in range(3):
                ppos[p, c] = bpos[0, body[p], c]
                pvel[p, c] = bvel[0, body[p], c]
    _s.dgs_record(r, v, x, u, sec, rprm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N,
                  Nstar, faces, slack, pw[4], start_force[0], end_force[0], laid[0])
    for p in range(P):
        for c in range(3):
            point_pos[0, p, c] = ppos[p, c]
    steps[0] = 0.0
    err_coef = abs(ip[_ik.IP_BETA] - 1.0 / 6.0)
    dt_max = ip[_ik.IP_DT_MAX]
    level_max = int(ip[_ik.IP_LEVEL_MAX])
    events = ip[_ik.IP_FLAG_EVENTS] != 0.0
    strain0 = np.zeros((sec.shape[0], 2))  # (the sections' end strains at the step's start)
    strain1 = np.zeros((sec.shape[0], 2))
    if events and n > 1:
        _end_strains(r, v, x, u, sec, prm, ops, kind, body, time[0], time[1], bpos[0], bvel[0],
                     bpos[1], bvel[1], time[0], ppos, pvel, strain0)
    n_shape = _s._I0  # (an int64 from the start: one signature of dgs_record_shape)
    for s in range(n):
        if shape_every > 0 and s % shape_every == 0:
            _s.dgs_record_shape(r, N, shape_r, shape_t, n_shape)
            n_shape += 1
        if s == n - 1:
            break
        t0, t1 = time[s], time[s + 1]
        span = t1 - t0
        level_min = 0
        if span > dt_max:
            level_min = int(math.ceil(math.log2(span / dt_max) - 1e-12))
        L = max(int(cs[_ik.CS_LEVEL]), level_min)
        m = 0
        taken = 0
        while m < (1 << L):
            dt = span / (1 << L)
            t = t0 + m * dt
            _save(r, v, x, u, st, nw, pw)
            ok, its, fresh = _gai_step(r, v, x, u, st, nw, pw, t0, t1, bpos[s], bvel[s],
                                       bpos[s + 1], bvel[s + 1], t, dt, sec, prm, ops, kind,
                                       body, pprm, env, fslot, ip, cs, fields, jw, bands, boff,
                                       flat, Spp, piv, H, F3)
            if not ok and not fresh:  # factors of an older state: rebuild them and retry
                _restore(r, v, x, u, st, nw, pw)
                cs[_ik.CS_FACTOR_DT] = 0.0
                ok, its, fresh = _gai_step(r, v, x, u, st, nw, pw, t0, t1, bpos[s], bvel[s],
                                           bpos[s + 1], bvel[s + 1], t, dt, sec, prm, ops,
                                           kind, body, pprm, env, fslot, ip, cs, fields, jw,
                                           bands, boff, flat, Spp, piv, H, F3)
            cs[_ik.CS_ITERATIONS] += its
            err = 0.0
            if ok:
                err = _step_error(sec, prm, ops, st, nw, fields, dt,
                                  err_coef) / ip[_ik.IP_FORCE_TOL]
            jumped = False
            if (ok and err <= 1.0 and events
                    and L < min(level_max, level_min + _ik.EVENT_LEVELS)):
                _end_strains(r, v, x, u, sec, prm, ops, kind, body, t0, t1, bpos[s], bvel[s],
                             bpos[s + 1], bvel[s + 1], t + dt, ppos, pvel, strain1)
                jumped = _jumped_transitions(strain0, strain1, prm, dt, ip[_ik.IP_FORCE_TOL])
            if not ok or jumped or (err > 1.0 and L < level_max):
                _restore(r, v, x, u, st, nw, pw)
                cs[_ik.CS_REJECTED] += 1.0
                cs[_ik.CS_GOOD] = 0.0
                if L >= level_max:
                    where[0], where[1], where[2] = 0, sec[0, _s.S_K] - 1, sec[0, _s.S_NP] - 1
                    cs[_ik.CS_LEVEL] = L
                    return _ik.DG_NEWTON, s + 1
                L += 1
                m *= 2
                continue
            m += 1
            taken += 1
            cs[_ik.CS_STEPS] += 1.0
            if its > _ik.SLOW_ITERATIONS:
                cs[_ik.CS_FACTOR_DT] = 0.0
            filtered = False
            for j in range(sec.shape[0]):
                if prm[j, _k.P_FILTER] == 0.0:
                    continue
                K, Np = sec[j, _s.S_K], sec[j, _s.S_NP]
                eo = sec[j, _s.S_ELEM]
                sl = slack[eo:eo + K]
                any_slack = False
                for k in range(K):
                    if sl[k] != 0.0:
                        any_slack = True
                if any_slack:
                    D, LIFT, F, w = _s._ops(ops, sec, j)
                    _k._filter_slack(_s._nodes(v, sec, j), F, sl, tmp)
                    filtered = True
            if filtered:
                dgi_forces(r, v, x, u, sec, prm, ops, kind, pprm, env, ppos, pvel, q, qt, N,
                           Nstar, faces, slack, st[1], st[3], H)
            if events:
                _end_strains(r, v, x, u, sec, prm, ops, kind, body, t0, t1, bpos[s], bvel[s],
                             bpos[s + 1], bvel[s + 1], t + dt, ppos, pvel, strain0)
            if err < ip[_ik.IP_GROW]:
                cs[_ik.CS_GOOD] += 1.0
            else:
                cs[_ik.CS_GOOD] = 0.0
            if cs[_ik.CS_GOOD] >= _ik.GOOD_STEPS and L > level_min and m % 2 == 0:
                L -= 1
                m //= 2
                cs[_ik.CS_GOOD] = 0.0
        cs[_ik.CS_LEVEL] = L
        for p in range(P):
            if kind[p] == _s.BODY:
                for c in range(3):
                    ppos[p, c] = bpos[s + 1, body[p], c]
                    pvel[p, c] = bvel[s + 1, body[p], c]
        _s.dgs_record(r, v, x, u, sec, rprm, ops, kind, pprm, env, ppos, pvel, G, Zs, q, qt, N,
                      Nstar, faces, slack, pw[4], start_force[s + 1], end_force[s + 1],
                      laid[s + 1])
        for p in range(P):
            for c in range(3):
                point_pos[s + 1, p, c] = ppos[p, c]
        steps[s + 1] = taken
        status = _s._check(r, v, q, x, u, sec, prm, kind, where)
        if status != _k.DG_OK:
            return status, s + 1
    return _k.DG_OK, n
