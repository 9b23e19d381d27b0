"""Numba kernels of the implicit time integration of the DG cable
(docs/theory/dynamic_line.md#time-integration).

The semi-discrete cable of ``_kernels`` (the same tension field, fluxes, external forces and
mass), dr/dt = v, M_eff(r) dv/dt = F(r, v, t), is advanced with the generalised-alpha method of
Chung & Hulbert (1993, J. Appl. Mech. 60, 371-375), the implicit scheme of structural codes
(OrcaFlex's implicit integration among them): second order, unconditionally stable for linear
problems, with numerical dissipation of the unresolved high frequencies set by the spectral
radius at infinity rho_inf. With alpha_m = (2 rho - 1) / (rho + 1), alpha_f = rho / (rho + 1),
gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4, a step solves

    (1 - alpha_m) a1 + alpha_m a0 = (1 - alpha_f) A(r1, v1, t1) + alpha_f A(r0, v0, t0),
    r1 = r0 + dt v0 + dt^2 ((1/2 - beta) a0 + beta a1),  v1 = v0 + dt ((1 - gamma) a0 + gamma a1)

for the acceleration variable a1, A = M_eff^-1 F the acceleration of the semi-discrete cable
(the force-interpolating form, second order for nonlinear problems: Erlicher, Bonaventura &
Bursi 2002, Comput. Mech. 28, 83-104). Everything stiff is inside the solve: the axial
elasticity EA, the Kelvin-Voigt damping, the Lax-Friedrichs penalty (Z = m c), the seabed
spring-damper and friction, the drag. Newton's method uses the banded Jacobian
(1 - alpha_m) M - (1 - alpha_f) (beta dt^2 dF/dr + gamma dt dF/dv), built from the exact
derivatives of the DG operators (:func:`_jacobian`), LU-factored without pivoting
(``_banded_kernels``) and reused over steps and iterations while Newton converges quickly
(a modified Newton method); it is rebuilt when dt changes or convergence slows. Away from
slack Newton stops when the error left in its iterate, estimated from the contraction of its
corrections as eta |dx| with eta = theta / (1 - theta) (Hairer & Wanner 1996, Solving
Ordinary Differential Equations II, 2nd ed., section IV.8), is below its tolerance. The end
state's A, which the next step's equation needs, is taken from the step's equation,
(1 - alpha_f) A1 = (1 - alpha_m) a1 + alpha_m a0 - alpha_f A0, not evaluated again at the
converged state (one evaluation a step less; the two differ by Newton's residual).

Step size: each interval between two path samples is cut into 2^L equal steps. The local error
of a step is estimated from the change of the acceleration variable,
e_r = dt^2 |beta - 1/6| (a1 - a0) (Zienkiewicz & Xie 1991, Earthq. Eng. Struct. Dyn. 20,
871-887), mapped to the fairlead force through the end node's tangent stiffness
(|dN/dq . de/ds|). Its tolerance is the tight one of snaps while the fairlead end node is
near slack or was within the last ``IP_SNAP_WINDOW`` (a snap's peak follows the local errors
of the steps through it directly), the looser one of smooth motion otherwise (its local
errors are damped out by the line's drag before they add up;
docs/theory/dynamic_line.md#time-integration). A step whose force error exceeds the tolerance
is redone at half the step (L + 1), and after ``GOOD_STEPS`` steps well inside it the step
doubles again (L - 1). Snap loads, whose axial waves carry the force, so get the small steps
they need and the rest of the run the steps its fairlead motion needs.

Slack elements are filtered after each step as in the explicit scheme (``_kernels``).

Size: the generalised-alpha step, its Jacobian and its step control share the private
operators of one DG cable; splitting them would pass a dozen work arrays across modules.
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg._banded_kernels import band_factor
from floatmoor.mooring.dg._friction_kernels import return_map, stick_tangent

__all__ = ["IP_N", "CS_N", "dg_acceleration", "dg_jacobian", "dg_run_path_implicit",
           "generalised_alpha", "newton_converged"]

# -- integrator parameters ``ip`` ------------------------------------------------------------
IP_ALPHA_M = 0
IP_ALPHA_F = 1
IP_BETA = 2
IP_GAMMA = 3
IP_NEWTON_TOL = 4  #: Newton converged when the largest position correction is below [m]
IP_FORCE_TOL = 5  #: local error of the end force allowed per step [N]
IP_MAX_ITER = 6  #: Newton iterations before the Jacobian is rebuilt or the step halved
IP_DT_MAX = 7  #: largest step [s]
IP_LEVEL_MAX = 8  #: most halvings of a sample interval (2^LEVEL_MAX steps)
IP_GROW = 9  #: error ratio below which a step counts as "well inside" the tolerance
#: 1: rebuild the Jacobian when a node changes state (else on slow contraction only)
IP_FLAG_REFACTOR = 10
#: 1: reject a step that jumps a slack-taut transition of the fairlead (:func:`_jumped_transition`;
#: the lines' default), 0: the error estimate alone decides (as the systems' implicit step does)
IP_FLAG_EVENTS = 11
#: local error of the end force allowed per step away from slack [N]: a step that starts more
#: than ``IP_SNAP_WINDOW`` after the fairlead end node was last near slack (its strain at or
#: below ``IP_SLACK_STRAIN``) is held to the larger of this and ``IP_FORCE_TOL``, and its
#: Newton iteration stops on its error estimate (:func:`newton_converged`)
IP_SMOOTH_TOL = 12
IP_SNAP_WINDOW = 13  #: [s]
#: the fairlead end node's strain at or below which it counts as near slack
IP_SLACK_STRAIN = 14
IP_N = 15

# -- integrator state ``cs`` (carried between calls and checkpointed) ------------------------
CS_LEVEL = 0  #: current halving level L of a sample interval
CS_GOOD = 1  #: consecutive steps well inside the tolerance
CS_FACTOR_DT = 2  #: dt of the factored Jacobian; 0: no valid factors
CS_ACC_VALID = 3  #: 1 when ``acc`` and ``An`` belong to the state
CS_FACTORISATIONS = 4  #: counters (diagnostics)
CS_STEPS = 5
CS_REJECTED = 6
CS_ITERATIONS = 7
#: when the fairlead end node was last seen near slack [s]; ``SLACK_UNKNOWN``: not known (a
#: new state, taken as near slack at its first step)
CS_SLACK_TIME = 8
CS_N = 9

#: ``cs[CS_SLACK_TIME]`` of a state whose history is not known [s] (finite: checkpoints hold
#: finite values only)
SLACK_UNKNOWN = -1e300

#: statuses beyond ``_kernels``' DG_*
DG_NEWTON = 4  #: Newton did not converge at the smallest step allowed


def generalised_alpha(rho_inf: float) -> tuple[float, float, float, float]:
    """(alpha_m, alpha_f, beta, gamma) of Chung & Hulbert for the spectral radius rho_inf."""
    am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0)
    af = rho_inf / (rho_inf + 1.0)
    gamma = 0.5 - am + af
    beta = 0.25 * (1.0 - am + af) ** 2
    return am, af, beta, gamma


@jit
def dg_acceleration(r, v, anchor, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces, slack, out,
                    fa=None):
    """A = M_eff^-1 F of the semi-discrete cable with every term in the right-hand side: the
    Kelvin-Voigt damping always, the seabed spring-damper when ``prm[P_IMPLICIT_CONTACT]`` is 0
    (the implicit integrator's parameter vector has it 0); the stick-spring friction on the
    anchors ``fa`` when given and ``prm[P_KS]`` > 0."""
    _k._tension_field(r, v, anchor, _k._ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                      slack, prm[_k.P_CINT])
    _k._acceleration(r, v, prm, D, LIFT, q, N, Nstar, out, fa)


@jit
def _mass_times(r, q, prm, x, out):
    """out = M_eff x per node, M_eff = m_n (I - t t^T) + m_t t t^T (Morison added mass below
    z = 0), t from the tangent field q."""
    K, Np = r.shape[0], r.shape[1]
    m = prm[_k.P_M]
    for k in range(K):
        for i in range(Np):
            sub = r[k, i, 2] < 0.0
            mn = m + (prm[_k.P_MAN] if sub else 0.0)
            mt = m + (prm[_k.P_MAT] if sub else 0.0)
            ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
            tx, ty, tz = 0.0, 0.0, 0.0
            if ql > 0.0:
                tx, ty, tz = q[k, i, 0] / ql, q[k, i, 1] / ql, q[k, i, 2] / ql
            xt = x[k, i, 0] * tx + x[k, i, 1] * ty + x[k, i, 2] * tz
            out[k, i, 0] = mn * x[k, i, 0] + (mt - mn) * xt * tx
            out[k, i, 1] = mn * x[k, i, 1] + (mt - mn) * xt * ty
            out[k, i, 2] = mn * x[k, i, 2] + (mt - mn) * xt * tz


@jit
def _node_blocks(r, v, q, qt, prm, kc, cc, acoef, E, Dg, fa=None):
    """Per node: ``E`` = kc dN/dq + cc dN/dq_t (the tension's tangent blocks, 3 x 3) and
    ``Dg`` = acoef M_eff - kc df/dr - cc df/dv (the local blocks: mass, seabed, drag,
    friction, relaxation); the stick-spring friction's exact tangent on the anchors ``fa``
    when given and ``prm[P_KS]`` > 0."""
    K, Np = r.shape[0], r.shape[1]
    EA = prm[_k.P_EA]
    cint = prm[_k.P_CINT]
    m = prm[_k.P_M]
    rho_w = prm[_k.P_RHO_W]
    drag = 0.5 * rho_w * prm[_k.P_D]
    cdn, cdt = prm[_k.P_CDN], prm[_k.P_CDT]
    zb = prm[_k.P_ZB]
    friction = prm[_k.P_MU] * prm[_k.P_WSUB]
    vc = prm[_k.P_VC]
    relax = prm[_k.P_RELAX]
    ks = prm[_k.P_KS]
    mu_kb = prm[_k.P_MU] * prm[_k.P_KB]
    stick = False
    if fa is not None:
        stick = ks > 0.0
    for k in range(K):
        for i in range(Np):
            ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
            t0, t1, t2 = 0.0, 0.0, 0.0
            if ql > 0.0:
                t0, t1, t2 = q[k, i, 0] / ql, q[k, i, 1] / ql, q[k, i, 2] / ql
            tv = (t0, t1, t2)
            eps = ql - 1.0
            T = 0.0
            if eps > 0.0:
                T = EA * eps
                if cint > 0.0:
                    T += cint * (q[k, i, 0] * qt[k, i, 0] + q[k, i, 1] * qt[k, i, 1]
                                 + q[k, i, 2] * qt[k, i, 2]) / ql
            taut = eps > 0.0 and T > 0.0
            for a in range(3):
                for b in range(3):
                    E[k, i, a, b] = 0.0
                    Dg[k, i, a, b] = 0.0
            if taut:
                geo = T / ql
                for a in range(3):
                    E[k, i, a, a] += kc * geo
                    for b in range(3):
                        E[k, i, a, b] += (kc * (EA - geo) + cc * cint) * tv[a] * tv[b]
            sub = r[k, i, 2] < 0.0
            mn = m + (prm[_k.P_MAN] if sub else 0.0)
            mt = m + (prm[_k.P_MAT] if sub else 0.0)
            for a in range(3):
                Dg[k, i, a, a] += acoef * mn + cc * relax * mn
                for b in range(3):
                    Dg[k, i, a, b] += (acoef + cc * relax) * (mt - mn) * tv[a] * tv[b]
            if sub and (cdn > 0.0 or cdt > 0.0):
                vr0 = prm[_k.P_UX] - v[k, i, 0]
                vr1 = prm[_k.P_UX + 1] - v[k, i, 1]
                vr2 = prm[_k.P_UX + 2] - v[k, i, 2]
                vt = vr0 * t0 + vr1 * t1 + vr2 * t2
                vn0, vn1, vn2 = vr0 - vt * t0, vr1 - vt * t1, vr2 - vt * t2
                vn = math.sqrt(vn0 * vn0 + vn1 * vn1 + vn2 * vn2)
                vnv = (vn0, vn1, vn2)
                s = drag * math.sqrt(ql)
                # -df/dv = s (2 cdt |vt| t t^T + cdn (|vn| P + vn vn^T / |vn|)), P = I - t t^T
                for a in range(3):
                    for b in range(3):
                        p = (1.0 if a == b else 0.0) - tv[a] * tv[b]
                        val = 2.0 * cdt * abs(vt) * tv[a] * tv[b] + cdn * vn * p
                        if vn > 0.0:
                            val += cdn * vnv[a] * vnv[b] / vn
                        Dg[k, i, a, b] += cc * s * val
            if r[k, i, 2] < zb:
                Dg[k, i, 2, 2] += kc * prm[_k.P_KB]
                if v[k, i, 2] < 0.0:
                    Dg[k, i, 2, 2] += cc * prm[_k.P_CB]
                if stick and mu_kb > 0.0:  # -df/dr of the stick spring, exact
                    txx, txy, tyx, tyy, txz, tyz = stick_tangent(
                        fa[k, i, 0] - r[k, i, 0], fa[k, i, 1] - r[k, i, 1],
                        mu_kb * (zb - r[k, i, 2]), ks, mu_kb)
                    Dg[k, i, 0, 0] += kc * txx
                    Dg[k, i, 0, 1] += kc * txy
                    Dg[k, i, 1, 0] += kc * tyx
                    Dg[k, i, 1, 1] += kc * tyy
                    Dg[k, i, 0, 2] += kc * txz
                    Dg[k, i, 1, 2] += kc * tyz
                elif friction > 0.0 and not stick:
                    vx, vy = v[k, i, 0], v[k, i, 1]
                    speed = math.sqrt(vx * vx + vy * vy)
                    # -df/dv of f = -mu W sin(pi s / (2 max(vc, s))) v / s in the seabed plane
                    if speed < vc:
                        x = 0.5 * math.pi / vc
                        radial = friction * x * math.cos(x * speed)
                        lateral = friction * (math.sin(x * speed) / speed if speed > 0.0 else x)
                    else:
                        radial = 0.0
                        lateral = friction / speed
                    ux, uy = (vx / speed, vy / speed) if speed > 0.0 else (0.0, 0.0)
                    uv = (ux, uy)
                    for a in range(2):
                        for b in range(2):
                            p = (1.0 if a == b else 0.0) - uv[a] * uv[b]
                            Dg[k, i, a, b] += cc * (lateral * p + radial * uv[a] * uv[b])


@jit
def _add_block(band, kl, row_node, col_node, scale, blk):
    """band[3 row_node + a, 3 col_node + b] += scale blk[a, b]."""
    for a in range(3):
        row = 3 * row_node + a
        for b in range(3):
            band[row, kl + 3 * col_node + b - row] += scale * blk[a, b]


@jit
def _add_diagonal(band, kl, row_node, col_node, value):
    """band[3 row_node + a, 3 col_node + a] += value (an isotropic block)."""
    for a in range(3):
        row = 3 * row_node + a
        band[row, kl + 3 * col_node + a - row] += value


@jit
def dg_jacobian(r, v, q, qt, prm, D, LIFT, acoef, kc, cc, E, Dg, band, fa=None):
    """The Newton matrix J = acoef M_eff - kc dF/dr - cc dF/dv of the DG cable in band storage
    (``_banded_kernels``), node-major with the three components interleaved:
    kl = 3 Np + 2 sub- and ku = 6 Np - 1 super-diagonals.

    dF/dr = Div_N (dN/dq) Grad + df/dr and dF/dv = Div_N (dN/dq_t) Grad + Div_Z + df/dv, with
    Grad the DG gradient (traces from the anchor side, end values prescribed), Div_N the
    divergence of the nodal force (traces from the fairlead side), Div_Z the Lax-Friedrichs
    penalty and f the external forces. ``q`` and ``qt`` must hold the state's tangent and its
    rate (:func:`dg_acceleration` leaves them). The dependence of the mass, buoyancy and drag
    on the tangent and of the damping tension on the direction is left out (Newton converges
    with it, a little more slowly). ``fa``: the stick-spring friction's anchors, or None.
    """
    K, Np = r.shape[0], r.shape[1]
    n = 3 * K * Np
    kl = 3 * Np + 2
    jac = 2.0 / prm[_k.P_H]
    for row in range(n):
        for col in range(band.shape[1]):
            band[row, col] = 0.0
    _node_blocks(r, v, q, qt, prm, kc, cc, acoef, E, Dg, fa)
    for k in range(K):
        for i in range(Np):
            node = k * Np + i
            _add_block(band, kl, node, node, 1.0, Dg[k, i])
    # elastic and damping part: - Div_N E Grad, row (k, i), through node l, to column c
    for k in range(K):
        for i in range(Np):
            row = k * Np + i
            # nodes l of the divergence of row (k, i): (k, j) and, through the right face,
            # (k + 1, 0)
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
                # gradient at node (kk, jj): columns (kk, m) and (kk - 1, Np - 1)
                for mm in range(Np):
                    gcoef = jac * D[jj, mm]
                    if mm == 0:
                        gcoef += jac * LIFT[jj, 0]
                    if mm == Np - 1 and kk == K - 1:
                        gcoef -= jac * LIFT[jj, 1]
                    if gcoef != 0.0:
                        _add_block(band, kl, row, kk * Np + mm, -dcoef * gcoef, E[kk, jj])
                if kk >= 1:
                    _add_block(band, kl, row, (kk - 1) * Np + Np - 1,
                               dcoef * jac * LIFT[jj, 0], E[kk, jj])
    # Lax-Friedrichs penalty: - cc Div_Z
    m = prm[_k.P_M]
    c_wave = prm[_k.P_C]
    for k in range(K):
        # left face k
        if k == 0:
            sub = 1.0 if r[0, 0, 2] < 0.0 else 0.0
            Z = (m + sub * prm[_k.P_MAT]) * c_wave
            for i in range(Np):
                _add_diagonal(band, kl, i, 0, cc * jac * LIFT[i, 0] * Z)
        else:
            sub = 1.0 if r[k, 0, 2] + r[k - 1, Np - 1, 2] < 0.0 else 0.0
            Z = (m + sub * prm[_k.P_MAT]) * c_wave
            for i in range(Np):
                row = k * Np + i
                _add_diagonal(band, kl, row, k * Np, cc * jac * LIFT[i, 0] * 0.5 * Z)
                _add_diagonal(band, kl, row, (k - 1) * Np + Np - 1,
                              -cc * jac * LIFT[i, 0] * 0.5 * Z)
        # right face k + 1
        if k == K - 1:
            sub = 1.0 if r[K - 1, Np - 1, 2] < 0.0 else 0.0
            Z = (m + sub * prm[_k.P_MAT]) * c_wave
            for i in range(Np):
                _add_diagonal(band, kl, k * Np + i, k * Np + Np - 1, cc * jac * LIFT[i, 1] * Z)
        else:
            sub = 1.0 if r[k + 1, 0, 2] + r[k, Np - 1, 2] < 0.0 else 0.0
            Z = (m + sub * prm[_k.P_MAT]) * c_wave
            for i in range(Np):
                row = k * Np + i
                _add_diagonal(band, kl, row, (k + 1) * Np, -cc * jac * LIFT[i, 1] * 0.5 * Z)
                _add_diagonal(band, kl, row, k * Np + Np - 1, cc * jac * LIFT[i, 1] * 0.5 * Z)


@jit
def _dg_band_solve(band, n, kl, ku, Np, x):
    """``band_solve`` with the factors of a :func:`dg_jacobian` (Np nodes per element), the
    products with the band's structural zeros left out (the same bits): row (k, i) of the
    matrix, and so of its LU factors, spans the columns of nodes (k, 0) - 1 to (k + 2, 0) - 1,
    up to 3 Np scalars fewer than the band."""
    for row in range(n):  # forward substitution (unit lower factor)
        first = 3 * ((row // (3 * Np)) * Np - 1)
        acc = x[row]
        for cc in range(max(0, first, row - kl), row):
            acc -= band[row, kl + cc - row] * x[cc]
        x[row] = acc
    for row in range(n - 1, -1, -1):
        last = 3 * ((row // (3 * Np) + 2) * Np) - 1
        acc = x[row]
        for cc in range(row + 1, min(n, last + 1, row + ku + 1)):
            acc -= band[row, kl + cc - row] * x[cc]
        x[row] = acc / band[row, kl]


@jit
def _end_gradient(e, D, LIFT, jac, c):
    """Component c of the DG gradient of the field ``e`` at the fairlead end node, its ends
    held at zero: ``_kernels._gradient``'s value at that node, the same bits, without the
    rest of the line."""
    K, Np = e.shape[0], e.shape[1]
    k, i = K - 1, Np - 1
    left = e[k - 1, Np - 1, c] if K > 1 else 0.0  # the trace from the anchor side
    jl = left - e[k, 0, c]
    jr = 0.0 - e[k, i, c]
    acc = 0.0
    for j in range(Np):
        acc += D[i, j] * e[k, j, c]
    return jac * (acc - LIFT[i, 0] * jl + LIFT[i, 1] * jr)


@jit
def _end_force_error(e, q, N, prm, D, LIFT):
    """|dN/dq . de/ds| at the fairlead end node [N]: the end tension's error from a position
    error field ``e`` (the end positions exact)."""
    K, Np = e.shape[0], e.shape[1]
    k, i = K - 1, Np - 1
    ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
    if ql <= 1.0:
        return 0.0
    jac = 2.0 / prm[_k.P_H]
    T = math.sqrt(N[k, i, 0] ** 2 + N[k, i, 1] ** 2 + N[k, i, 2] ** 2)
    t0, t1, t2 = q[k, i, 0] / ql, q[k, i, 1] / ql, q[k, i, 2] / ql
    g0 = _end_gradient(e, D, LIFT, jac, 0)
    g1 = _end_gradient(e, D, LIFT, jac, 1)
    g2 = _end_gradient(e, D, LIFT, jac, 2)
    gt = g0 * t0 + g1 * t1 + g2 * t2
    p0, p1, p2 = g0 - gt * t0, g1 - gt * t1, g2 - gt * t2
    axial = prm[_k.P_EA] * gt
    lateral = T / ql * math.sqrt(p0 * p0 + p1 * p1 + p2 * p2)
    return math.sqrt(axial * axial + lateral * lateral)


@jit
def _node_flag(r, q, N, prm, k, i):
    """1 taut + 2 below the seabed + 4 submerged: the states the Jacobian depends on."""
    ql2 = q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2
    taut = N[k, i, 0] ** 2 + N[k, i, 1] ** 2 + N[k, i, 2] ** 2 > 0.0 and ql2 > 1.0
    return ((1.0 if taut else 0.0) + (2.0 if r[k, i, 2] < prm[_k.P_ZB] else 0.0)
            + (4.0 if r[k, i, 2] < 0.0 else 0.0))


@jit
def _flags_changed(r, q, N, prm, flags):
    for k in range(r.shape[0]):
        for i in range(r.shape[1]):
            if _node_flag(r, q, N, prm, k, i) != flags[k, i]:
                return True
    return False


@jit
def _set_flags(r, q, N, prm, flags):
    for k in range(r.shape[0]):
        for i in range(r.shape[1]):
            flags[k, i] = _node_flag(r, q, N, prm, k, i)


#: Steps whose sizes differ by less than this fraction share factors: sample times that are
#: sums of a body step differ in their last bits (a coupled run's intervals, the probes'
#: recorded paths), and a Newton matrix of dt (1 + 1e-9) converges as one of dt.
SAME_STEP = 1e-9


@jit
def newton_converged(iterations, big, previous, tol, strict):
    """Whether Newton has converged after its iteration ``iterations`` (1, 2, ...), whose
    largest position correction was ``big`` after ``previous`` [m]: the correction is within
    ``tol``, or, from the second iteration on and unless ``strict``, the error left in the
    iterate, eta |dx| with eta = theta / (1 - theta) and theta = big / previous the measured
    contraction (Hairer & Wanner 1996, section IV.8). ``strict``: the correction only (near a
    snap, whose peak moves by several per cent with the error the estimate lets through).
    The first iteration is never ended on an estimate: the last step's eta, which RADAU5
    trusts there, lets two mirror-image lines take different steps
    (docs/validation/performance.md)."""
    if big <= tol:
        return True
    if strict or iterations < 2 or not big < previous:
        return False
    theta = big / previous
    return theta / (1.0 - theta) * big <= tol


@jit
def _ga_step(r, v, acc, a0, An, t0s, t1s, p0, w0, p1, w1, t, dt, anchor, prm, D, LIFT, ip, cs,
             q, qt, N, Nstar, faces, slack, fpos, fvel, A1, R, MR, E, Dg, band, x, flags,
             strict, fa=None):
    """One generalised-alpha step of (r, v, acc) from t to t + dt; ``a0`` holds ``acc`` at the
    start and ``An`` the acceleration A of the start state. On success ``An`` holds A of the
    end state. The stick-spring friction's anchors ``fa`` stay where the last committed step
    left them (the caller commits them).

    The Jacobian is reused while Newton contracts (and, with ``ip[IP_FLAG_REFACTOR]``, while
    the nodes keep the taut / seabed / submerged states it was built with, ``flags``); a
    correction above :data:`STALE_CONTRACTION` (near slack, ``strict``) or
    :data:`SMOOTH_STALE_CONTRACTION` times the previous has it rebuilt at the iterate (a
    semismooth Newton step: the tension's kink at zero strain and the seabed's at contact are
    where a stale Jacobian diverges).

    Returns
    -------
    (converged, iterations, fresh)
        Whether Newton converged within ``ip[IP_MAX_ITER]`` iterations, how many it took, and
        whether the Jacobian was factored in this step (at its predictor or an iterate).
    """
    K, Np = r.shape[0], r.shape[1]
    n = 3 * K * Np
    kl, ku = 3 * Np + 2, 6 * Np - 1
    am, af, beta, gamma = ip[IP_ALPHA_M], ip[IP_ALPHA_F], ip[IP_BETA], ip[IP_GAMMA]
    tol = ip[IP_NEWTON_TOL]
    max_iter = int(ip[IP_MAX_ITER])
    _k.hermite(t0s, t1s, p0, w0, p1, w1, t + dt, fpos, fvel)
    # predictor: the acceleration variable held (a1 = a0), r and v from the Newmark formulas
    cr = dt * dt * 0.5
    cv = dt
    for k in range(K):
        for i in range(Np):
            for c in range(3):
                r[k, i, c] += dt * v[k, i, c] + cr * a0[k, i, c]
                v[k, i, c] += cv * a0[k, i, c]
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
        dg_acceleration(r, v, anchor, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces, slack,
                        A1, fa)
        if abs(cs[CS_FACTOR_DT] - dt) > SAME_STEP * dt or grew or (ip[IP_FLAG_REFACTOR] != 0.0
                                               and _flags_changed(r, q, N, prm, flags)):
            _set_flags(r, q, N, prm, flags)
            dg_jacobian(r, v, q, qt, prm, D, LIFT, acoef, kc, cc, E, Dg, band, fa)
            cs[CS_FACTORISATIONS] += 1.0
            fresh = True
            if band_factor(band, n, kl, ku) >= 0:
                cs[CS_FACTOR_DT] = 0.0
                return False, iterations, fresh
            cs[CS_FACTOR_DT] = dt
        for k in range(K):
            for i in range(Np):
                for c in range(3):
                    R[k, i, c] = (acoef * acc[k, i, c] + am * a0[k, i, c]
                                  - (1.0 - af) * A1[k, i, c] - af * An[k, i, c])
        _mass_times(r, q, prm, R, MR)
        for k in range(K):
            for i in range(Np):
                for c in range(3):
                    x[3 * (k * Np + i) + c] = -MR[k, i, c]
        _dg_band_solve(band, n, kl, ku, Np, x)
        iterations += 1
        big = 0.0
        total = 0.0
        for k in range(K):
            for i in range(Np):
                for c in range(3):
                    da = x[3 * (k * Np + i) + c]
                    acc[k, i, c] += da
                    r[k, i, c] += bdt2 * da
                    v[k, i, c] += gdt * da
                    d = abs(bdt2 * da)
                    total += d
                    if d > big:
                        big = d
        if not math.isfinite(total):
            return False, iterations, fresh
        converged = newton_converged(iterations, big, previous, tol, strict)
        if converged:
            break
        grew = big > (STALE_CONTRACTION if strict else SMOOTH_STALE_CONTRACTION) * previous
        previous = big
    if not converged:
        return False, iterations, fresh
    # A of the end state from the step's equation, (1 - alpha_f) A1 = (1 - alpha_m) a1 +
    # alpha_m a0 - alpha_f An, instead of one more evaluation at the converged iterate (the
    # two differ by the residual Newton leaves; docs/theory/dynamic_line.md#time-integration)
    ci = 1.0 / (1.0 - af)
    for k in range(K):
        for i in range(Np):
            for c in range(3):
                An[k, i, c] = ci * (acoef * acc[k, i, c] + am * a0[k, i, c] - af * An[k, i, c])
    return True, iterations, fresh


#: Newton iterations above which the factored Jacobian counts as stale and is rebuilt at the
#: next step (a fresh one converges in 2 to 3 on the cases of the verification tests).
SLOW_ITERATIONS = 4
#: Consecutive steps well inside the tolerance before the step doubles (implicit.GROW_RATIO).
GOOD_STEPS = 4
#: A Newton correction above this fraction of the previous one has the Jacobian rebuilt at the
#: iterate (near slack: a snap's kink at zero strain is where a stale Jacobian diverges).
STALE_CONTRACTION = 0.5
#: The same away from slack (the step's smooth tolerance): an iteration on the stale factors
#: (about 7 us on DeepCwind line 2, 8 x p3) costs a third of a rebuild (Jacobian 7.7 us,
#: factors 15 us), so a contraction up to 0.95 is cheaper to ride out. DeepCwind LC34 with
#: dynamic lines, 1200 s: loop 7.55 -> 7.29 s, tension STD and maximum within 0.02 %. 1.0
#: (rebuild only when a correction grows): 654 rejected steps of line 2 on its 600 s
#: recorded path against 500, 5 % more CPU. Not near slack: 0.8 there moved the mean cycle
#: maximum of the Lindahl chain stepped implicitly to +1.70 % of the explicit steps' (0.5:
#: +1.11 %).
SMOOTH_STALE_CONTRACTION = 0.95


@jit
def _fairlead_strain(r, v, anchor, fpos, fvel, prm, D, LIFT):
    """(eps, d eps/dt) of the fairlead end node: its strain |q| - 1 and the strain's rate
    q . q_t / |q|, from the DG gradient of r and v on the last element (traces from the anchor
    side, the fairlead's position and velocity at the end)."""
    K, Np = r.shape[0], r.shape[1]
    jac = 2.0 / prm[_k.P_H]
    k, i = K - 1, Np - 1
    qx, qy, qz, wx, wy, wz = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    for j in range(Np):
        qx += D[i, j] * r[k, j, 0]
        qy += D[i, j] * r[k, j, 1]
        qz += D[i, j] * r[k, j, 2]
        wx += D[i, j] * v[k, j, 0]
        wy += D[i, j] * v[k, j, 1]
        wz += D[i, j] * v[k, j, 2]
    lx, ly, lz = anchor[0], anchor[1], anchor[2]
    ux, uy, uz = 0.0, 0.0, 0.0
    if K > 1:
        lx, ly, lz = r[k - 1, Np - 1, 0], r[k - 1, Np - 1, 1], r[k - 1, Np - 1, 2]
        ux, uy, uz = v[k - 1, Np - 1, 0], v[k - 1, Np - 1, 1], v[k - 1, Np - 1, 2]
    l0, l1 = LIFT[i, 0], LIFT[i, 1]
    qx = jac * (qx - l0 * (lx - r[k, 0, 0]) + l1 * (fpos[0] - r[k, i, 0]))
    qy = jac * (qy - l0 * (ly - r[k, 0, 1]) + l1 * (fpos[1] - r[k, i, 1]))
    qz = jac * (qz - l0 * (lz - r[k, 0, 2]) + l1 * (fpos[2] - r[k, i, 2]))
    wx = jac * (wx - l0 * (ux - v[k, 0, 0]) + l1 * (fvel[0] - v[k, i, 0]))
    wy = jac * (wy - l0 * (uy - v[k, 0, 1]) + l1 * (fvel[1] - v[k, i, 1]))
    wz = jac * (wz - l0 * (uz - v[k, 0, 2]) + l1 * (fvel[2] - v[k, i, 2]))
    ql = math.sqrt(qx * qx + qy * qy + qz * qz)
    if ql <= 0.0:
        return -1.0, 0.0
    return ql - 1.0, (qx * wx + qy * wy + qz * wz) / ql


#: Halvings of the largest step (the sample interval or ``IP_DT_MAX``) a slack-taut transition
#: of the fairlead is located to at most: an end node chattering about zero strain crosses it
#: at every step, and each crossing may cost this many rejected steps, no more; below 2^-8 of
#: the largest step the error estimate alone decides.
EVENT_LEVELS = 8
#: Points of the step (fractions) where the cubic Hermite interpolant of the fairlead strain is
#: checked for an excursion into tension that both ends of the step miss (a snap jumped over).
EVENT_SAMPLES = 8


@jit
def _jumped_transition(e0, s0, e1, s1, dt, EA, tol):
    """Whether a step from fairlead strain (e0, rate s0) to (e1, s1) crosses the slack-taut
    transition with more than the force tolerance ``tol`` on its taut side: the step's largest
    tension EA max(e0, e1, the strain's cubic Hermite interpolant inside the step) exceeds
    ``tol`` while the end node is slack at either end or both
    (docs/theory/dynamic_line.md#slack-taut-events-and-seabed-friction)."""
    if e0 > 0.0 and e1 > 0.0:
        return False
    peak = max(e0, e1)
    for m in range(1, EVENT_SAMPLES):
        x = m / EVENT_SAMPLES
        x2 = x * x
        x3 = x2 * x
        e = ((2.0 * x3 - 3.0 * x2 + 1.0) * e0 + (x3 - 2.0 * x2 + x) * dt * s0
             + (-2.0 * x3 + 3.0 * x2) * e1 + (x3 - x2) * dt * s1)
        if e > peak:
            peak = e
    return EA * peak > tol


@jit
def _copy(src, dst):
    K, Np = src.shape[0], src.shape[1]
    for k in range(K):
        for i in range(Np):
            for c in range(3):
                dst[k, i, c] = src[k, i, c]


@jit
def dg_run_path_implicit(r, v, acc, An, time, path, velocity, anchor, prm, D, LIFT, F, weights,
                         ip, cs, fair_force, anch_force, laid, steps, shape_every, shape_r,
                         shape_t, q, qt, N, Nstar, faces, slack, fpos, fvel, tmp, where, r0, v0,
                         a0, An0, A1, R, MR, E, Dg, band, x, flags, record_first, fa=None):
    """Advance the line along a fairlead path with the generalised-alpha method, recording its
    end forces at every sample (the implicit counterpart of ``_kernels.dg_run_path``, same
    outputs; ``steps`` gets the number of steps taken in each interval); at the first sample
    (the current state) only with ``record_first`` or shapes to record (a caller that has them
    already: the coupled runs' batch kernel).

    ``acc`` is the acceleration variable of the method and ``An`` the acceleration A of the
    state; both are computed from the state first when ``cs[CS_ACC_VALID]`` is 0. ``prm`` must
    have ``P_IMPLICIT_CONTACT`` and ``P_IMPLICIT_DAMPING`` 0 (contact and damping in the
    right-hand side, inside the implicit solve). ``fa``: the stick-spring friction's anchors
    (K, Np, 2), moved by return mapping after every accepted step only, or None.

    A step is accepted when Newton converged, its error estimate is inside the tolerance and
    it does not jump a slack-taut transition of the fairlead end node with a tension above the
    force tolerance (:func:`_jumped_transition`); otherwise it is redone at half the step
    (until ``ip[IP_LEVEL_MAX]``), so a snap's onset is located to within the time its tension
    takes to reach the force tolerance.

    Returns
    -------
    (status, index)
        ``DG_OK`` and n, or the first failing status (``_kernels``' DG_*, or ``DG_NEWTON``) and
        the sample where it occurred (``where`` holds the element and node).
    """
    n = time.shape[0]
    K, Np = r.shape[0], r.shape[1]
    for c in range(3):
        fpos[c] = path[0, c]
        fvel[c] = velocity[0, c]
    if cs[CS_ACC_VALID] == 0.0:
        dg_acceleration(r, v, anchor, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces, slack,
                        An, fa)
        _copy(An, acc)
        cs[CS_ACC_VALID] = 1.0
    if record_first or shape_every > 0:  # (a shape takes the tension field of the record)
        laid[0] = _k._record(r, v, anchor, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                             slack, weights, fair_force[0], anch_force[0])
    steps[0] = 0.0
    err_coef = abs(ip[IP_BETA] - 1.0 / 6.0)
    dt_max = ip[IP_DT_MAX]
    level_max = int(ip[IP_LEVEL_MAX])
    EA = prm[_k.P_EA]
    e_start, s_start = _fairlead_strain(r, v, anchor, fpos, fvel, prm, D, LIFT)
    if e_start <= ip[IP_SLACK_STRAIN] or cs[CS_SLACK_TIME] <= SLACK_UNKNOWN:
        cs[CS_SLACK_TIME] = time[0]  # (a state of unknown history: near slack for a window)
    smooth_tol = max(ip[IP_FORCE_TOL], ip[IP_SMOOTH_TOL])
    n_shape = 0
    for s in range(n):
        if shape_every > 0 and s % shape_every == 0:
            _k._record_shape(r, N, shape_r, shape_t, n_shape)
            n_shape += 1
        if s == n - 1:
            break
        t0, t1 = time[s], time[s + 1]
        span = t1 - t0
        level_min = 0
        if span > dt_max:
            level_min = int(math.ceil(math.log2(span / dt_max) - 1e-12))
        L = max(int(cs[CS_LEVEL]), level_min)
        m = 0
        taken = 0
        while m < (1 << L):
            dt = span / (1 << L)
            t = t0 + m * dt
            _copy(r, r0)
            _copy(v, v0)
            _copy(acc, a0)
            _copy(An, An0)
            near_slack = t - cs[CS_SLACK_TIME] <= ip[IP_SNAP_WINDOW]
            ok, its, fresh = _ga_step(r, v, acc, a0, An, t0, t1, path[s], velocity[s],
                                      path[s + 1], velocity[s + 1], t, dt, anchor, prm, D, LIFT,
                                      ip, cs, q, qt, N, Nstar, faces, slack, fpos, fvel, A1, R,
                                      MR, E, Dg, band, x, flags, near_slack, fa)
            if not ok and not fresh:  # factors of an older state: rebuild them and retry
                _copy(r0, r)
                _copy(v0, v)
                _copy(a0, acc)
                _copy(An0, An)
                cs[CS_FACTOR_DT] = 0.0
                ok, its, fresh = _ga_step(r, v, acc, a0, An, t0, t1, path[s], velocity[s],
                                          path[s + 1], velocity[s + 1], t, dt, anchor, prm, D,
                                          LIFT, ip, cs, q, qt, N, Nstar, faces, slack, fpos,
                                          fvel, A1, R, MR, E, Dg, band, x, flags, near_slack,
                                          fa)
            cs[CS_ITERATIONS] += its
            err = 0.0
            if ok:
                c2 = err_coef * dt * dt
                for k in range(K):
                    for i in range(Np):
                        for c in range(3):
                            R[k, i, c] = c2 * (acc[k, i, c] - a0[k, i, c])
                tol = ip[IP_FORCE_TOL] if near_slack else smooth_tol
                err = _end_force_error(R, q, N, prm, D, LIFT) / tol
            jumped = False
            strain_known = False
            if (ok and err <= 1.0 and ip[IP_FLAG_EVENTS] != 0.0
                    and L < min(level_max, level_min + EVENT_LEVELS)):
                e_end, s_end = _fairlead_strain(r, v, anchor, fpos, fvel, prm, D, LIFT)
                strain_known = True
                jumped = _jumped_transition(e_start, s_start, e_end, s_end, dt, EA,
                                            ip[IP_FORCE_TOL])
            if not ok or jumped or (err > 1.0 and L < level_max):
                _copy(r0, r)
                _copy(v0, v)
                _copy(a0, acc)
                _copy(An0, An)
                cs[CS_REJECTED] += 1.0
                cs[CS_GOOD] = 0.0
                if L >= level_max:
                    where[0], where[1] = K - 1, Np - 1
                    cs[CS_LEVEL] = L
                    return DG_NEWTON, s + 1
                L += 1
                m *= 2
                continue
            m += 1
            taken += 1
            cs[CS_STEPS] += 1.0
            if its > SLOW_ITERATIONS:
                cs[CS_FACTOR_DT] = 0.0
            filtered = False
            if prm[_k.P_FILTER] != 0.0:
                for k in range(K):
                    if slack[k] != 0.0:
                        filtered = True
                if filtered:
                    _k._filter_slack(v, F, slack, tmp)
                    dg_acceleration(r, v, anchor, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar,
                                    faces, slack, An, fa)
            if fa is not None:  # (the force at the committed state, so An, stays the same)
                return_map(r, fa, prm[_k.P_KS], prm[_k.P_MU] * prm[_k.P_KB], prm[_k.P_ZB])
            if strain_known and not filtered:  # (the same state: the events' values)
                e_start, s_start = e_end, s_end
            else:
                e_start, s_start = _fairlead_strain(r, v, anchor, fpos, fvel, prm, D, LIFT)
            if e_start <= ip[IP_SLACK_STRAIN]:
                cs[CS_SLACK_TIME] = t + dt
            cs[CS_GOOD] = cs[CS_GOOD] + 1.0 if err < ip[IP_GROW] else 0.0
            if cs[CS_GOOD] >= GOOD_STEPS and L > level_min and m % 2 == 0:
                L -= 1
                m //= 2
                cs[CS_GOOD] = 0.0
        cs[CS_LEVEL] = L
        for c in range(3):
            fpos[c] = path[s + 1, c]
            fvel[c] = velocity[s + 1, c]
        laid[s + 1] = _k._record(r, v, anchor, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                                 slack, weights, fair_force[s + 1], anch_force[s + 1])
        steps[s + 1] = taken
        status = _k._check(r, v, q, prm, where)
        if status != _k.DG_OK:
            return status, s + 1
    return _k.DG_OK, n
