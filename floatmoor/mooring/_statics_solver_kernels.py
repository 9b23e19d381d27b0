"""Numba kernels of the static equilibrium of a mooring system (points joined by catenary sections).

Unknowns are the coordinates of the free points (the ``dof`` table maps each point coordinate to
its unknown, -1 when it is given). Each section is the elastic catenary of
:mod:`floatmoor.mooring._catenary_kernels` between its two end points; a free point balances
its sections' end forces and its constant external force (weight and buoyancy).

Section end stiffness (6x6). The catenary kernel solves the line in the vertical plane through
its ends, with the lower end L (the catenary's end A, possibly on the seabed) and the upper end
U. With u the horizontal unit vector from L to U, XF the horizontal span, (HF, VF) and (HA, VA)
the tension components at U and L and k = d(HF, VF)/d(XF, ZF), h = d(HA, VA)/d(XF, ZF) the
kernel's in-plane stiffnesses (h = k on a line free of the seabed)::

    f_U = -HF u - VF e_z                   (force of the section on U)
    f_L =  HA u + VA e_z                   (force of the section on L)
    K_UU = -df_U/dp_U = [[k11 uu' + (HF/XF)(I - uu'), k12 u], [k21 u', k22]]
    M    =  df_L/dp_U = [[h11 uu' + (HA/XF)(I - uu'), h12 u], [h21 u', h22]]

The forces depend on p_U - p_L only (the contact state held), so K_UL = -K_UU, K_LL = M,
K_LU = -M. Free of the seabed the section is in equilibrium under its ends and its own
(constant) weight, so f_L = -f_U - W L e_z, M = K_UU and the 6x6 matrix is the symmetric
[[K, -K], [-K, K]]. With seabed contact the seabed carries the resting length and, with
friction, part of the horizontal load: the lower end sees only HA = max(HF - CB W LB, 0) and
VA = 0, so h = (k11 + CB k21, k12 + CB k22; 0, 0) while the anchor is loaded (zero once
friction takes the whole load), and the matrix is no longer symmetric. The rows of the lower
end are then one-sided derivatives (lifting that end off the seabed is a change of regime);
a free point resting on the seabed has its z held (below), so only its horizontal rows enter
the Newton matrix, and the one-sided z rows only a body point on the seabed would see.

Free points on the seabed (an active set). A free point whose equilibrium would lie below the
seabed rests on it: its z is pinned at the seabed (``pinned[p] = PIN_SEABED``; the unknowns
are its x and y) and the seabed carries the vertical force left over, R_z = -(its reaction).
A Newton step that would carry an unpinned free point through the seabed pins it there
(landing); once the equilibrium with the current pins has converged, a pinned point the
seabed would have to pull down (R_z > 0 beyond the force tolerance) is released (lift-off)
and the solve goes on. The point itself has no seabed friction: its horizontal force balance
is exact (its sections carry their own friction on their laid lengths).

All kernels write into preallocated arrays and allocate nothing.
"""

from __future__ import annotations

import math

from floatmoor._numba import jit
from floatmoor.mooring._catenary_kernels import (
    CAT_OK, CAT_SAG_BELOW_SEABED, SEABED_CONTACT_TOL, _lower_end_stiffness, _plane_setup,
    _solve_plane,
)

# --------------------------------------------------------------------------- section output
S_FA = 0  # force of the section on its start point (3)
S_FB = 3  # force on its end point (3)
S_KAA = 6  # -d f_start / d p_start (9, row-major)
S_KAB = 15  # -d f_start / d p_end
S_KBA = 24  # -d f_end / d p_start
S_KBB = 33  # -d f_end / d p_end
S_HF = 42  # horizontal tension at the upper end (warm start)
S_VF = 43  # vertical tension at the upper end (warm start)
S_LB = 44  # unstretched length on the seabed
S_ITER = 45
S_PROFILE = 46
S_RESID = 47
S_SWAPPED = 48  # 1.0 when the end point is the lower end
N_SECTION_OUT = 49

# --------------------------------------------------------------------------- system status
SYS_OK = 0
SYS_NOT_CONVERGED = 1  # the Newton iteration stalled or ran out of iterations
SYS_SECTION_FAILED = 2  # a section has no catenary solution at the given (not trial) positions
SYS_ABOVE_SURFACE = 3  # converged, but a free point lies above the water surface (z > 0)
SYS_SAG_BELOW_SEABED = 4  # converged, but a section free of the seabed sags below it
SYS_CONTACT_CYCLING = 5  # the free points kept landing on and lifting off the seabed

# --------------------------------------------------------------------------- pins of a point's z
PIN_NONE = 0  # z is an unknown (free points) or given (fixed, body points)
PIN_SEABED = 1  # a free point resting on the seabed: z = seabed, released when pulled up
PIN_HELD = 2  # a free point's z held where it is (never released; for diagnostics)

# --------------------------------------------------------------------------- info layout
INFO_ITER = 0  # Newton iterations
INFO_RESIDUAL = 1  # max over dofs of |R| / (force scale of its point)
INFO_WORST_POINT = 2  # point with the largest relative residual
INFO_SECTION = 3  # failing section (SYS_SECTION_FAILED, SYS_SAG_BELOW_SEABED)
INFO_CAT_STATUS = 4  # its catenary status
INFO_POINT = 5  # the point above the surface (SYS_ABOVE_SURFACE)
INFO_CATENARY_ITER = 6  # catenary iterations summed over sections and Newton evaluations
INFO_CONTACT_CHANGES = 7  # landings and lift-offs of free points during the solve
N_INFO = 8

# --------------------------------------------------------------------------- numerics
#: Armijo constant of the backtracking line search on |R|^2 (the usual 1e-4: accept any step
#: that achieves a small fraction of the decrease the linear model predicts).
ARMIJO = 1e-4
#: Halvings of a step before the Levenberg-Marquardt shift is raised.
MAX_BACKTRACK = 30
#: First Levenberg-Marquardt shift relative to the largest diagonal stiffness, and the factor
#: it grows by after each failed line search; after MAX_SHIFTS raises the solve gives up.
LM_SHIFT0 = 1e-8
LM_GROWTH = 10.0
MAX_SHIFTS = 12
#: Landings and lift-offs of free points allowed in one equilibrium, per free point, beyond
#: one each: a point's contact settles after one landing and at most one lift-off unless the
#: iteration cycles between the two (a point balanced within the tolerance of the seabed).
MAX_CONTACT_CHANGES_PER_POINT = 4


@jit(error_model="numpy")
def _block(out, k, kh, khz, kzh, kz, kt, ux, uy, sign):
    """Write sign * [[kh uu' + kt (I - uu'), khz u], [kzh u', kz]] row-major at out[k:k+9]."""
    out[k + 0] = sign * (kh * ux * ux + kt * (1.0 - ux * ux))
    out[k + 1] = sign * ((kh - kt) * ux * uy)
    out[k + 2] = sign * (khz * ux)
    out[k + 3] = sign * ((kh - kt) * ux * uy)
    out[k + 4] = sign * (kh * uy * uy + kt * (1.0 - uy * uy))
    out[k + 5] = sign * (khz * uy)
    out[k + 6] = sign * (kzh * ux)
    out[k + 7] = sign * (kzh * uy)
    out[k + 8] = sign * kz


@jit(error_model="numpy")
def section_solve(pa, pb, L, EA, W, CB, seabed_z, HF0, VF0, tol, max_iter, out):
    """Catenary section from ``pa`` (start) to ``pb`` (end): end forces and 6x6 stiffness.

    Results in ``out`` (``N_SECTION_OUT``, layout ``S_*``). The forces are computed exactly as
    :func:`~floatmoor.mooring._catenary_kernels.catenary_solve_3d` computes them with
    anchor = ``pa`` and fairlead = ``pb``. Returns the catenary status (``CAT_*``);
    ``CAT_SAG_BELOW_SEABED`` still writes every output.
    """
    st, swapped, seabed, XF, ZF, ux, uy, lx, ly, lz = _plane_setup(pa, pb, L, seabed_z)
    out[S_SWAPPED] = 1.0 if swapped else 0.0
    out[S_ITER] = 0.0
    if st != CAT_OK:
        return st
    st, H, V, HA, VA, LB, k11, k12, k21, k22, it, res, prof = _solve_plane(
        XF, ZF, L, EA, W, CB, seabed, HF0, VF0, tol, max_iter
    )
    out[S_ITER] = it
    out[S_RESID] = res
    if st != CAT_OK:
        return st
    out[S_HF] = H
    out[S_VF] = V
    out[S_LB] = LB
    out[S_PROFILE] = prof
    h11, h12, h21, h22 = _lower_end_stiffness(prof, H, HA, k11, k12, k21, k22, CB)
    kt_u = H / XF if XF > 0.0 else k11
    kt_l = HA / XF if XF > 0.0 else h11
    if swapped:  # the end point is the lower one
        fu = S_FA
        fl = S_FB
        kuu, kul, klu, kll = S_KAA, S_KAB, S_KBA, S_KBB
    else:
        fu = S_FB
        fl = S_FA
        kuu, kul, klu, kll = S_KBB, S_KBA, S_KAB, S_KAA
    out[fu] = -H * ux
    out[fu + 1] = -H * uy
    out[fu + 2] = -V
    out[fl] = HA * ux
    out[fl + 1] = HA * uy
    out[fl + 2] = VA
    _block(out, kuu, k11, k12, k21, k22, kt_u, ux, uy, 1.0)
    _block(out, kul, k11, k12, k21, k22, kt_u, ux, uy, -1.0)
    _block(out, kll, h11, h12, h21, h22, kt_l, ux, uy, 1.0)
    _block(out, klu, h11, h12, h21, h22, kt_l, ux, uy, -1.0)
    if seabed == 0 and seabed_z > -math.inf and VA < 0.0:
        hb = math.hypot(H, VA)
        zs = -VA * VA / (W * (hb + H)) - VA * VA / (2.0 * W * EA)
        if lz + zs < seabed_z - SEABED_CONTACT_TOL * L:
            return CAT_SAG_BELOW_SEABED
    return CAT_OK


@jit(error_model="numpy")
def assemble(pos, sec_start, sec_end, sec_L, sec_EA, sec_W, sec_CB, seabed_z, sec_tol,
             sec_maxit, warm, dof, n_dof, ext, sec_out, R, K, scale, with_k):
    """Evaluate every section at ``pos`` and assemble the free-point residual and stiffness.

    R[i] is the net force on unknown i < ``n_dof`` (sections + ``ext``); K = -dR/dx over the
    unknowns (filled when ``with_k``); ``scale[p]`` = |ext_p| + the sum over the sections at
    p of their larger end tension.
    Returns (index of the first section without a solution or -1, its status, index of a
    section sagging below the seabed or -1, catenary iterations).
    """
    n_pts = pos.shape[0]
    for i in range(n_dof):
        R[i] = 0.0
        if with_k:
            for j in range(n_dof):
                K[i, j] = 0.0
    for p in range(n_pts):
        scale[p] = math.sqrt(ext[p, 0] ** 2 + ext[p, 1] ** 2 + ext[p, 2] ** 2)
        for c in range(3):
            i = dof[p, c]
            if i >= 0:
                R[i] += ext[p, c]
    sag = -1
    cat_iter = 0.0
    n_sec = sec_L.shape[0]
    for s in range(n_sec):
        a = sec_start[s]
        b = sec_end[s]
        o = sec_out[s]
        st = section_solve(pos[a], pos[b], sec_L[s], sec_EA[s], sec_W[s], sec_CB[s], seabed_z,
                           warm[s, 0], warm[s, 1], sec_tol[s], sec_maxit[s], o)
        cat_iter += o[S_ITER]
        if st == CAT_SAG_BELOW_SEABED:
            if sag < 0:
                sag = s
        elif st != CAT_OK:
            return s, st, sag, cat_iter
        # a section's force error is relative to its largest tension (at its upper end), also
        # at an end that carries little: a joint beyond which seabed friction has taken
        # nearly all the tension
        t = max(math.sqrt(o[S_FA] ** 2 + o[S_FA + 1] ** 2 + o[S_FA + 2] ** 2),
                math.sqrt(o[S_FB] ** 2 + o[S_FB + 1] ** 2 + o[S_FB + 2] ** 2))
        scale[a] += t
        scale[b] += t
        for c in range(3):
            ia = dof[a, c]
            ib = dof[b, c]
            if ia >= 0:
                R[ia] += o[S_FA + c]
            if ib >= 0:
                R[ib] += o[S_FB + c]
            if with_k:
                for d in range(3):
                    ja = dof[a, d]
                    jb = dof[b, d]
                    if ia >= 0 and ja >= 0:
                        K[ia, ja] += o[S_KAA + 3 * c + d]
                    if ia >= 0 and jb >= 0:
                        K[ia, jb] += o[S_KAB + 3 * c + d]
                    if ib >= 0 and ja >= 0:
                        K[ib, ja] += o[S_KBA + 3 * c + d]
                    if ib >= 0 and jb >= 0:
                        K[ib, jb] += o[S_KBB + 3 * c + d]
    return -1, CAT_OK, sag, cat_iter


@jit(error_model="numpy")
def _residual_measure(R, dof, scale):
    """(max over unknowns of |R_i| / scale of its point, that point, sum of R_i^2)."""
    worst = 0.0
    worst_p = -1
    phi = 0.0
    for p in range(dof.shape[0]):
        for c in range(3):
            i = dof[p, c]
            if i >= 0:
                r = abs(R[i])
                phi += r * r
                ratio = r / scale[p] if scale[p] > 0.0 else (math.inf if r > 0.0 else 0.0)
                if ratio > worst or worst_p < 0:
                    worst = ratio
                    worst_p = p
    return worst, worst_p, phi


@jit(error_model="numpy")
def lu_solve(A, b, x, n):
    """Solve A x = b over the leading ``n`` unknowns by Gaussian elimination with partial
    pivoting, in place (A, b overwritten).

    Returns False when a pivot is zero or the result is not finite.
    """
    for k in range(n):
        piv = k
        big = abs(A[k, k])
        for i in range(k + 1, n):
            if abs(A[i, k]) > big:
                big = abs(A[i, k])
                piv = i
        if not (big > 0.0) or not math.isfinite(big):
            return False
        if piv != k:
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[piv, j]
                A[piv, j] = tmp
            tmp = b[k]
            b[k] = b[piv]
            b[piv] = tmp
        for i in range(k + 1, n):
            f = A[i, k] / A[k, k]
            if f != 0.0:
                for j in range(k, n):
                    A[i, j] -= f * A[k, j]
                b[i] -= f * b[k]
    for k in range(n - 1, -1, -1):
        acc = b[k]
        for j in range(k + 1, n):
            acc -= A[k, j] * x[j]
        x[k] = acc / A[k, k]
        if not math.isfinite(x[k]):
            return False
    return True


@jit(error_model="numpy")
def build_dof(free, pinned, dof):
    """Number the unknowns: x, y, z of each free point (``free[p]``), z left out while
    ``pinned[p]``. Writes ``dof`` (n_points, 3; -1 for a given coordinate), returns the count."""
    n = 0
    for p in range(dof.shape[0]):
        for c in range(3):
            if free[p] and not (c == 2 and pinned[p] != PIN_NONE):
                dof[p, c] = n
                n += 1
            else:
                dof[p, c] = -1
    return n


@jit(error_model="numpy")
def vertical_force(p, ext, sec_start, sec_end, sec_out):
    """Net vertical force of ``ext`` and the sections on point ``p`` [N]; on a point resting on
    the seabed, minus the seabed's reaction."""
    fz = ext[p, 2]
    for s in range(sec_start.shape[0]):
        if sec_start[s] == p:
            fz += sec_out[s, S_FA + 2]
        if sec_end[s] == p:
            fz += sec_out[s, S_FB + 2]
    return fz


# results of _newton
_CONVERGED = 0
_STALLED = 1
_SECTION_FAILED = 2
_LANDED = 3


@jit(error_model="numpy")
def _newton(pos, sec_start, sec_end, sec_L, sec_EA, sec_W, sec_CB, seabed_z, sec_tol,
            sec_maxit, dof, n_dof, pinned, ext, step_cap, force_rtol, max_iter, it, warm,
            sec_out, trial_out, trial_pos, R, Rt, K, Kt, A, rhs, dx, scale, info):
    """Newton iteration with the pins held. Returns (``_CONVERGED`` | ``_STALLED`` |
    ``_SECTION_FAILED`` | ``_LANDED``, iterations so far, a section sagging below the seabed or
    -1). ``_LANDED``: a step would have carried free points through the seabed; they are
    pinned there (``pinned``, ``pos`` updated) and the caller starts again."""
    n_sec = sec_L.shape[0]
    n_pts = pos.shape[0]
    fail, fst, sag, ci = assemble(pos, sec_start, sec_end, sec_L, sec_EA, sec_W, sec_CB,
                                  seabed_z, sec_tol, sec_maxit, warm, dof, n_dof, ext, sec_out,
                                  R, K, scale, True)
    info[INFO_CATENARY_ITER] += ci
    if fail >= 0:
        info[INFO_SECTION] = fail
        info[INFO_CAT_STATUS] = fst
        return _SECTION_FAILED, it, sag
    for s in range(n_sec):
        warm[s, 0] = sec_out[s, S_HF]
        warm[s, 1] = sec_out[s, S_VF]
    worst, worst_p, phi = _residual_measure(R, dof, scale)
    mu = 0.0
    shifts = 0
    result = _STALLED
    while True:
        if worst <= force_rtol:
            result = _CONVERGED
            break
        if it >= max_iter or not math.isfinite(phi):
            break
        kmax = 0.0
        for i in range(n_dof):
            kmax = max(kmax, abs(K[i, i]))
        if kmax == 0.0:
            kmax = 1.0
        accepted = False
        landed = False
        while not accepted:
            for i in range(n_dof):
                rhs[i] = R[i]
                for j in range(n_dof):
                    A[i, j] = K[i, j]
                A[i, i] += mu * kmax
            ok = lu_solve(A, rhs, dx, n_dof)
            if ok:
                # step limit per point
                alpha = 1.0
                tsag = -1
                for p in range(n_pts):
                    d2 = 0.0
                    for c in range(3):
                        i = dof[p, c]
                        if i >= 0:
                            d2 += dx[i] * dx[i]
                    d = math.sqrt(d2)
                    if d * alpha > step_cap[p]:
                        alpha = step_cap[p] / d
                # landing: the step would carry a free point through the seabed
                for p in range(n_pts):
                    i = dof[p, 2]
                    if i >= 0 and pos[p, 2] + alpha * dx[i] < seabed_z:
                        pinned[p] = PIN_SEABED
                        pos[p, 2] = seabed_z
                        landed = True
                if landed:
                    break
                for _ in range(MAX_BACKTRACK):
                    for p in range(n_pts):
                        for c in range(3):
                            i = dof[p, c]
                            trial_pos[p, c] = pos[p, c] + alpha * dx[i] if i >= 0 else pos[p, c]
                    tf, tst, tsag, ci = assemble(trial_pos, sec_start, sec_end, sec_L, sec_EA,
                                                 sec_W, sec_CB, seabed_z, sec_tol, sec_maxit,
                                                 warm, dof, n_dof, ext, trial_out, Rt, Kt,
                                                 scale, True)
                    info[INFO_CATENARY_ITER] += ci
                    if tf < 0:
                        phit = 0.0
                        for i in range(n_dof):
                            phit += Rt[i] * Rt[i]
                        if phit <= (1.0 - ARMIJO * alpha) * phi:
                            accepted = True
                            break
                    alpha *= 0.5
            if not accepted:
                if shifts >= MAX_SHIFTS:
                    break
                shifts += 1
                mu = LM_SHIFT0 if mu == 0.0 else mu * LM_GROWTH
        if landed:
            result = _LANDED
            break
        if not accepted:
            break
        # accept: the trial evaluation becomes the current state
        for p in range(n_pts):
            for c in range(3):
                pos[p, c] = trial_pos[p, c]
        for i in range(n_dof):
            R[i] = Rt[i]
            for j in range(n_dof):
                K[i, j] = Kt[i, j]
        for s in range(n_sec):
            for j in range(N_SECTION_OUT):
                sec_out[s, j] = trial_out[s, j]
            warm[s, 0] = sec_out[s, S_HF]
            warm[s, 1] = sec_out[s, S_VF]
        sag = tsag
        worst, worst_p, phi = _residual_measure(R, dof, scale)
        mu = mu / LM_GROWTH if mu > LM_SHIFT0 else 0.0
        it += 1
    info[INFO_ITER] = it
    info[INFO_RESIDUAL] = worst
    info[INFO_WORST_POINT] = worst_p
    return result, it, sag


@jit(error_model="numpy")
def solve_equilibrium(pos, sec_start, sec_end, sec_L, sec_EA, sec_W, sec_CB, seabed_z, sec_tol,
                      sec_maxit, free, pinned, dof, ext, step_cap, check_surface, force_rtol,
                      max_iter, warm, sec_out, trial_out, trial_pos, R, Rt, K, Kt, A, rhs, dx,
                      scale, info):
    """Equilibrium of the free points (``free[p]``); ``pos`` holds the guess and the result,
    ``pinned`` the seabed contacts (``PIN_*``, updated: the active set).

    Newton's method, globalised by a step limit (no point moves more than ``step_cap[p]`` in
    one step, the direction kept), a backtracking line search on |R|^2 that also rejects trial
    positions where a section has no catenary solution, and a Levenberg-Marquardt shift
    K + mu I raised whenever the line search fails (singular K of slack sections, points far
    off). Converged when every unknown's force residual is at most ``force_rtol`` times its
    point's force scale (|ext| + its sections' larger end tensions). Free points on the seabed
    form an active set (module docstring): a free point starting at or below the seabed, or
    that a step would carry through it, rests on it; after convergence the pinned point the
    seabed would pull down the most (beyond ``force_rtol`` of its force scale) lifts off and
    the iteration goes on; ``max_iter`` bounds the Newton iterations of the whole solve.

    ``warm`` (n_sections, 2) holds the sections' warm starts (updated); ``sec_out`` the
    section outputs at the result; ``dof`` (n_points, 3) receives the unknowns' numbering; the
    others are workspaces sized to 3 x the free points (``R, Rt, rhs, dx``; ``K, Kt, A``
    square), the sections (``trial_out``) and the points (``trial_pos``, ``scale``).
    ``check_surface[p]``: fail when free point p ends above z = 0. Returns a ``SYS_*`` status;
    ``info`` (``N_INFO``) says more.
    """
    n_pts = pos.shape[0]
    for k in range(N_INFO):
        info[k] = -1.0
    info[INFO_ITER] = 0.0
    info[INFO_RESIDUAL] = math.nan
    info[INFO_CATENARY_ITER] = 0.0
    info[INFO_CONTACT_CHANGES] = 0.0
    n_free = 0
    for p in range(n_pts):
        if free[p]:
            n_free += 1
            if pinned[p] == PIN_NONE and pos[p, 2] <= seabed_z:
                pinned[p] = PIN_SEABED
            if pinned[p] == PIN_SEABED:
                pos[p, 2] = seabed_z
    max_changes = MAX_CONTACT_CHANGES_PER_POINT * n_free
    changes = 0
    # 0 as an int64 variable: a literal 0 made numba compile _newton a second time, for
    # Literal[int](0) beside int64 (docs/validation/performance.md#first-run)
    it = int(info[INFO_ITER])
    sag = -1
    lift = -1
    while True:
        n_dof = build_dof(free, pinned, dof)
        result, it, sag = _newton(pos, sec_start, sec_end, sec_L, sec_EA, sec_W, sec_CB,
                                  seabed_z, sec_tol, sec_maxit, dof, n_dof, pinned, ext,
                                  step_cap, force_rtol, max_iter, it, warm, sec_out, trial_out,
                                  trial_pos, R, Rt, K, Kt, A, rhs, dx, scale, info)
        if result == _SECTION_FAILED:
            return SYS_SECTION_FAILED
        if result == _STALLED:
            return SYS_NOT_CONVERGED
        if result == _CONVERGED:
            # lift-off: the point the seabed would have to pull down the most
            lift = -1
            worst = 0.0
            for p in range(n_pts):
                if pinned[p] == PIN_SEABED:
                    fz = vertical_force(p, ext, sec_start, sec_end, sec_out)
                    if fz > force_rtol * scale[p] and fz > worst * scale[p]:
                        worst = fz / scale[p]
                        lift = p
            if lift < 0:
                break
            pinned[lift] = PIN_NONE
        changes += 1
        info[INFO_CONTACT_CHANGES] = changes
        if changes > max_changes:
            if lift >= 0:
                info[INFO_WORST_POINT] = lift
            return SYS_CONTACT_CYCLING
    for p in range(n_pts):
        if check_surface[p] and pos[p, 2] > 0.0:
            info[INFO_POINT] = p
            return SYS_ABOVE_SURFACE
    if sag >= 0:
        info[INFO_SECTION] = sag
        info[INFO_CAT_STATUS] = CAT_SAG_BELOW_SEABED
        return SYS_SAG_BELOW_SEABED
    return SYS_OK


@jit(error_model="numpy")
def statics_series(body_path, body_index, pos, sec_start, sec_end, sec_L, sec_EA, sec_W,
                   sec_CB, seabed_z, sec_tol, sec_maxit, free, pinned, dof, ext, step_cap,
                   check_surface, force_rtol, max_iter, warm, sec_out, trial_out, trial_pos, R,
                   Rt, K, Kt, A, rhs, dx, scale, info, out_pos, out_fa, out_fb, out_lb,
                   out_pinned, out_iter, out_resid):
    """Equilibrium at every sample of a path of body-point positions, warm-started.

    ``body_path`` (n, n_body, 3) gives the positions of the points ``body_index`` at each
    sample; the free points start from ``pos`` and the seabed contacts from ``pinned``, and
    each solve starts from the previous solution (its contacts too: points land and lift off
    as the path goes). Writes ``out_pos`` (n, n_points, 3), the sections' forces on their
    start and end points ``out_fa``, ``out_fb`` (n, n_sections, 3), laid lengths ``out_lb``
    (n, n_sections), the pins ``out_pinned`` (n, n_points), Newton iterations and residuals.
    The other arguments are those of :func:`solve_equilibrium`. Returns -1 when every sample
    solved, else the index of the first failure (its status and ``info`` left as
    :func:`solve_equilibrium` wrote them; the earlier samples are valid).
    """
    n = body_path.shape[0]
    n_body = body_index.shape[0]
    n_pts = pos.shape[0]
    n_sec = sec_L.shape[0]
    for k in range(n):
        for j in range(n_body):
            p = body_index[j]
            for c in range(3):
                pos[p, c] = body_path[k, j, c]
        st = solve_equilibrium(pos, sec_start, sec_end, sec_L, sec_EA, sec_W, sec_CB, seabed_z,
                               sec_tol, sec_maxit, free, pinned, dof, ext, step_cap,
                               check_surface, force_rtol, max_iter, warm, sec_out, trial_out,
                               trial_pos, R, Rt, K, Kt, A, rhs, dx, scale, info)
        if st != SYS_OK:
            return k
        for p in range(n_pts):
            for c in range(3):
                out_pos[k, p, c] = pos[p, c]
            out_pinned[k, p] = pinned[p]
        for s in range(n_sec):
            for c in range(3):
                out_fa[k, s, c] = sec_out[s, S_FA + c]
                out_fb[k, s, c] = sec_out[s, S_FB + c]
            out_lb[k, s] = sec_out[s, S_LB]
        out_iter[k] = info[INFO_ITER]
        out_resid[k] = info[INFO_RESIDUAL]
    return -1


__all__ = [
    "S_FA", "S_FB", "S_KAA", "S_KAB", "S_KBA", "S_KBB", "S_HF", "S_VF", "S_LB", "S_ITER",
    "S_PROFILE", "S_RESID", "S_SWAPPED", "N_SECTION_OUT",
    "SYS_OK", "SYS_NOT_CONVERGED", "SYS_SECTION_FAILED", "SYS_ABOVE_SURFACE",
    "SYS_SAG_BELOW_SEABED", "SYS_CONTACT_CYCLING", "PIN_NONE", "PIN_SEABED", "PIN_HELD",
    "INFO_ITER", "INFO_RESIDUAL", "INFO_WORST_POINT", "INFO_SECTION", "INFO_CAT_STATUS",
    "INFO_POINT", "INFO_CATENARY_ITER", "INFO_CONTACT_CHANGES", "N_INFO",
    "section_solve", "assemble", "lu_solve", "build_dof", "vertical_force",
    "solve_equilibrium", "statics_series",
]
