"""Numba solvers of the quasi-static elastic catenary with seabed contact and friction.

This module holds the status codes (``CAT_*``), profile codes (``PROFILE_*``), the layouts of the
``out`` arrays, the tolerances and the solvers: :func:`catenary_solve` (2-D) and
:func:`catenary_solve_3d` find the fairlead tension components (HF, VF) given the fairlead
position relative to the anchor. The equations they solve, with their symbols, are stated and
evaluated in :mod:`floatmoor.mooring._catenary_equations`; the line profile of a solution is
computed by :mod:`floatmoor.mooring._catenary_profile`.

Numerical method (:func:`catenary_solve`): the degenerate limits (line entirely on the seabed,
slack line hanging vertically onto the seabed, exactly vertical line) are solved in closed form.
Otherwise a damped Newton iteration in (ln H, asinh((VF - W L/2)/H)) runs from the warm start,
with a step limit, VF kept positive on the touchdown branch and a backtracking line search on
the residual.
If it stalls, a bracketing solver takes over (outer safeguarded Newton/bisection on ln H along
the curve Z(H, VF) = ZF, inner one on VF; both functions are monotone), followed by a Newton
polish. The result is returned as ``CAT_OK`` only after the residual has been checked.

All kernels write into preallocated ``out`` arrays, allocate nothing, and report failure
through an integer status (``CAT_*``) instead of raising.

Size: one set of numba solvers that call each other's private helpers (the 3-D solve
runs the 2-D plane solve), with the codes and ``out`` layouts their callers read; the
equations are already apart, in :mod:`floatmoor.mooring._catenary_equations`.
"""

from __future__ import annotations

import math

from floatmoor._numba import jit
from floatmoor.mooring._catenary_equations import _asinh_diff, _eval, _eval_touchdown

# --------------------------------------------------------------------------- status codes
CAT_OK = 0
CAT_NOT_CONVERGED = 1
CAT_INVALID_INPUT = 2
CAT_BELOW_SEABED = 3
# 3-D only: both ends are off the seabed but the suspended line sags below it. U-shaped seabed
# contact is not modelled, so the forces would be wrong; the solution is still written to `out`.
CAT_SAG_BELOW_SEABED = 4

# --------------------------------------------------------------------------- profile types
PROFILE_SUSPENDED = 0  # free of the seabed, chord shorter than L
PROFILE_TAUT = 1  # free of the seabed, chord at least L (stretched beyond straight)
PROFILE_TOUCHDOWN = 2  # part of the line rests on the seabed, H > 0
PROFILE_ON_SEABED = 3  # the whole line rests on the seabed (ZF = 0)
PROFILE_SLACK = 4  # H = 0: hangs vertically from the fairlead, the rest lies slack on the seabed
PROFILE_VERTICAL = 5  # XF = 0 and no resting part: straight vertical, or folded (VA < 0 < VF)

# --------------------------------------------------------------------------- 2-D output layout
I_HF = 0
I_VF = 1
I_HA = 2
I_VA = 3
I_LB = 4
I_K11 = 5  # dHF/dXF
I_K12 = 6  # dHF/dZF
I_K21 = 7  # dVF/dXF
I_K22 = 8  # dVF/dZF
I_ITER = 9
I_RESID = 10
I_PROFILE = 11
N_OUT_2D = 12

# --------------------------------------------------------------------------- 3-D output layout
I3_FAIRLEAD_FORCE = 0  # 3 entries
I3_ANCHOR_FORCE = 3  # 3 entries
I3_HF = 6
I3_VF = 7
I3_HA = 8
I3_VA = 9
I3_LB = 10
I3_ITER = 11
I3_RESID = 12
I3_STIFFNESS = 13  # 9 entries, row-major
I3_PROFILE = 22
I3_SWAPPED = 23  # 1.0 when the `fairlead` argument is the lower end (roles swapped)
N_OUT_3D = 24

# --------------------------------------------------------------------------- numerical constants
# An end counts as resting on the seabed when it lies within this fraction of L of seabed_z
# (above or below). Anchor positions come from case files (z = -depth) or from body transforms
# and sums of floats, which leave roundoff of ~1e-13 relative; 1e-6 L is far above that and far
# below any clearance that changes the forces measurably (MoorPy uses 1e-5 L for the same test).
SEABED_CONTACT_TOL = 1e-6
# Bounds on H relative to W L: below 1e-30 W L the horizontal extent of the catenary terms,
# about (H/W) ln(VF/H), is under 1e-27 L, far below any tolerance; the upper bound only keeps
# exp() finite.
H_MIN_REL = 1e-30
H_MAX_REL = 1e30
# Largest Newton step in ln H or psi (a factor of 100 in H): keeps a cold start from jumping
# across decades of tension in one step; warm starts rarely reach it.
MAX_LOG_STEP = 4.6
MAX_BACKTRACK = 40
MAX_BRACKET_ITER = 200
EPS = 2.220446049250313e-16


# =========================================================================== closed-form limits
@jit(error_model="numpy")
def _vertical(ZF, L, EA, W):
    """Exactly vertical line (XF = 0) free of the seabed, H = 0.

    With H -> 0 the suspended Z equation becomes
    Z = (|VF| - |VA|)/W + (VA + VF) L / (2 EA), VF = VA + W L, piecewise linear and increasing
    in VA. With c = 1 + W L / (2 EA): ZF >= L c straight and taut upwards (VA >= 0; the
    fixed-fixed line with ZF = L + W L^2/(2 EA) has VA = 0, VF = W L); ZF <= -L c taut downwards;
    in between folded, the lowest point at s0 = (L - ZF/c)/2 with VA = -W s0.
    Returns (VF, VA, dH/dXF, dVF/dZF). dH/dXF is the limit of H/XF as XF -> 0:
    1 / ((1/W) ln(VF/VA) + L/EA) when taut, 0 when folded (the asinh terms diverge).
    """
    c = 1.0 + W * L / (2.0 * EA)
    if ZF >= L * c:
        VA = EA * (ZF - L) / L - 0.5 * W * L
        VF = VA + W * L
        kh = 1.0 / (math.log1p(W * L / VA) / W + L / EA) if VA > 0.0 else 0.0
        return VF, VA, kh, EA / L
    if ZF <= -L * c:
        VA = EA * (ZF + L) / L - 0.5 * W * L
        VF = VA + W * L
        kh = 1.0 / (math.log1p(W * L / -VF) / W + L / EA) if VF < 0.0 else 0.0
        return VF, VA, kh, EA / L
    s0 = 0.5 * (L - ZF / c)
    VA = -W * s0
    VF = W * (L - s0)
    return VF, VA, 0.0, W / (2.0 * c)


@jit(error_model="numpy")
def _vertical_z(VF, VA, L, EA, W):
    """Z of the H = 0 line, for the residual of the vertical closed form."""
    return (abs(VF) - abs(VA)) / W + (VA + VF) * L / (2.0 * EA)


# =========================================================================== iterative solvers
@jit(error_model="numpy")
def _cold_start(XF, ZF, L, EA, W, seabed, h_min):
    """Starting (H, VF) without a previous solution.

    * Nearly vertical lines (XF < 0.1 L): the vertical closed form gives VF and VA (or the
      hanging length Ls when the anchor rests on the seabed), then H solves
      XF - x0 = H [(1/W)(asinh(VF/H) - asinh(VA/H)) + L/EA] by fixed-point iteration (the
      bracket depends on H only logarithmically). The slack-line guess below scales as XF^2
      instead of XF / ln(1/XF), and starts such lines decades away from the solution.
    * Taut lines (chord d >= L): the straight elastic bar, T = EA (d/L - 1), with the weight
      shared equally by the ends, but not below the Peyrot-Goulois value at lambda0 = 0.2.
    * Otherwise Peyrot & Goulois (1979, Computers & Structures 10) as in FAST v7 (Jonkman
      2007): lambda0 = sqrt(3 ((L^2 - ZF^2)/XF^2 - 1)), H = W XF / (2 lambda0),
      VF = (W/2)(ZF / tanh(lambda0) + L).
    """
    d = math.hypot(XF, ZF)
    if XF < 0.1 * L:
        x0 = 0.0
        VF = 0.0
        VA = 0.0
        Ls = L
        if seabed != 0:
            Ls = 2.0 * ZF / (1.0 + math.sqrt(1.0 + 2.0 * W * ZF / EA))
            if Ls < L:
                x0 = L - Ls
                VF = W * Ls
        if Ls >= L:
            Ls = L
            VF, VA, kh, kv = _vertical(ZF, L, EA, W)
        H = max(W * (XF - x0), h_min)
        for _ in range(6):
            g = _asinh_diff(VF, VA, H, VF - VA) / W + Ls / EA
            H = max((XF - x0) / g, h_min)
    elif d >= L:
        T = max(EA * (d / L - 1.0), W * d / 0.4)
        H = T * XF / d
        VF = T * ZF / d + 0.5 * W * L
    else:
        lam = math.sqrt(3.0 * ((L * L - ZF * ZF) / (XF * XF) - 1.0))
        H = W * XF / (2.0 * lam)
        VF = 0.5 * W * (ZF / math.tanh(lam) + L)
    if not (H > h_min):  # also catches NaN
        H = h_min
    if seabed != 0 and not (VF > 0.0):
        VF = 0.5 * W * min(ZF, L)
    return H, VF


@jit(error_model="numpy")
def _newton(XF, ZF, L, EA, W, CB, seabed, H, V, tol, max_iter, h_min, h_max):
    """Damped Newton with backtracking on |residual|^2, in the unknowns
    u = ln H and psi = asinh((VF - W L / 2) / H).

    psi is the inclination of the tension at mid-span (tan = (VF - W L/2)/H), so a taut line
    moves along u at nearly constant psi: in (H, VF) that path is a thin curved valley in
    which Newton crawls; in (u, psi) it is straight. Both unknowns stay well scaled as
    H -> 0 (vertical lines). Returns (converged, H, V, iterations, |rX| + |rZ|, XH, XV, ZH,
    ZV, LB) at the last point.
    """
    c = 0.5 * W * L
    X, Z, XH, XV, ZH, ZV, LB = _eval(H, V, L, EA, W, CB, seabed)
    rX = X - XF
    rZ = Z - ZF
    res = abs(rX) + abs(rZ)
    it = 0
    target = tol * L
    while True:
        if res <= target:
            return True, H, V, it, res, XH, XV, ZH, ZV, LB
        if it >= max_iter or not math.isfinite(res):
            break
        # chain rule: d/du = H d/dH + (V - c) d/dV,  d/dpsi = hypot(H, V - c) d/dV
        Vm = V - c
        R = math.hypot(H, Vm)
        a11 = H * XH + Vm * XV
        a12 = R * XV
        a21 = H * ZH + Vm * ZV
        a22 = R * ZV
        det = a11 * a22 - a12 * a21
        if not (math.isfinite(det) and det != 0.0):
            break
        du = -(a22 * rX - a12 * rZ) / det
        dp = -(a11 * rZ - a21 * rX) / det
        psi = math.asinh(Vm / H)
        alpha = 1.0
        big = max(abs(du), abs(dp))
        if big > MAX_LOG_STEP:
            alpha = MAX_LOG_STEP / big
        phi = rX * rX + rZ * rZ
        accepted = False
        for _ in range(MAX_BACKTRACK):
            Hn = H * math.exp(alpha * du)
            if Hn < h_min:
                Hn = h_min
            elif Hn > h_max:
                Hn = h_max
            Vn = c + Hn * math.sinh(psi + alpha * dp)
            if seabed != 0 and not (Vn > 0.0):
                # stay on the physical side of the touchdown branch (VF > 0 when ZF > 0)
                alpha *= 0.5
                continue
            Xn, Zn, XHn, XVn, ZHn, ZVn, LBn = _eval(Hn, Vn, L, EA, W, CB, seabed)
            rXn = Xn - XF
            rZn = Zn - ZF
            phin = rXn * rXn + rZn * rZn
            if phin < phi:
                accepted = True
                break
            alpha *= 0.5
        if not accepted:
            break
        H = Hn
        V = Vn
        X, Z, XH, XV, ZH, ZV, LB = Xn, Zn, XHn, XVn, ZHn, ZVn, LBn
        rX = rXn
        rZ = rZn
        res = abs(rX) + abs(rZ)
        it += 1
    return False, H, V, it, res, XH, XV, ZH, ZV, LB


@jit(error_model="numpy")
def _v_for_z(H, ZF, L, EA, W, CB, seabed, V, ztol):
    """VF such that Z(H, VF) = ZF at fixed H (Z increases monotonically with VF).

    Safeguarded Newton inside a bracket. Returns (VF, iterations).
    """
    step = max(W * L, abs(V), 1e-3 * H)
    if seabed != 0:
        lo = 0.0  # Z(H, 0) = 0 <= ZF
        if ZF == 0.0:
            return 0.0, 0
        hi = max(V, step)
        for _ in range(2000):
            if _eval(H, hi, L, EA, W, CB, seabed)[1] >= ZF:
                break
            lo = hi
            hi *= 2.0
    else:
        lo = V - step
        hi = V + step
        for _ in range(2000):
            if _eval(H, lo, L, EA, W, CB, seabed)[1] <= ZF:
                break
            hi = lo
            step *= 2.0
            lo -= step
        for _ in range(2000):
            if _eval(H, hi, L, EA, W, CB, seabed)[1] >= ZF:
                break
            lo = hi
            step *= 2.0
            hi += step
    if not (lo < V < hi):
        V = 0.5 * (lo + hi)
    last = math.inf
    for k in range(MAX_BRACKET_ITER):
        r = _eval(H, V, L, EA, W, CB, seabed)
        f = r[1] - ZF
        if abs(f) <= ztol:
            return V, k
        if f < 0.0:
            lo = V
        else:
            hi = V
        if hi - lo <= 4.0 * EPS * max(abs(lo), abs(hi)):
            return V, k
        Vn = V - f / r[5]
        if not (lo < Vn < hi) or abs(f) > 0.5 * last:
            Vn = 0.5 * (lo + hi)
        last = abs(f)
        V = Vn
    return V, MAX_BRACKET_ITER


@jit(error_model="numpy")
def _bracketed(XF, ZF, L, EA, W, CB, seabed, H, V, tol, h_min, h_max):
    """Fallback: solve X(H, VF(H)) = XF on ln H, VF(H) from Z(H, VF) = ZF.

    X(H, VF(H)) tends to the slack limit (< XF, the slack cases are handled in closed form)
    as H -> 0 and grows without bound with H (H L / EA), so a bracket always exists.
    Returns (H, V, iterations).
    """
    ztol = 0.05 * tol * L
    xtol = 0.5 * tol * L
    its = 0
    u = math.log(min(max(H, h_min), h_max))
    u_min = math.log(h_min)
    u_max = math.log(h_max)
    # bracket [ulo, uhi] with X(ulo) <= XF <= X(uhi)
    V, k = _v_for_z(math.exp(u), ZF, L, EA, W, CB, seabed, V, ztol)
    its += k
    X = _eval(math.exp(u), V, L, EA, W, CB, seabed)[0]
    ulo = u
    uhi = u
    Vlo = V
    Vhi = V
    if X < XF:
        while X < XF and uhi < u_max:
            ulo = uhi
            Vlo = V
            uhi = min(uhi + 2.3, u_max)
            V, k = _v_for_z(math.exp(uhi), ZF, L, EA, W, CB, seabed, V, ztol)
            its += k + 1
            X = _eval(math.exp(uhi), V, L, EA, W, CB, seabed)[0]
        Vhi = V
    else:
        while X > XF and ulo > u_min:
            uhi = ulo
            Vhi = V
            ulo = max(ulo - 2.3, u_min)
            V, k = _v_for_z(math.exp(ulo), ZF, L, EA, W, CB, seabed, V, ztol)
            its += k + 1
            X = _eval(math.exp(ulo), V, L, EA, W, CB, seabed)[0]
        Vlo = V
        if X > XF:  # root below h_min: the line is slack to within 1e-27 L
            return h_min, V, its
    u = 0.5 * (ulo + uhi)
    V = 0.5 * (Vlo + Vhi)
    last = math.inf
    for _ in range(MAX_BRACKET_ITER):
        Hc = math.exp(u)
        V, k = _v_for_z(Hc, ZF, L, EA, W, CB, seabed, V, ztol)
        its += k + 1
        X, Z, XH, XV, ZH, ZV, LB = _eval(Hc, V, L, EA, W, CB, seabed)
        f = X - XF
        if abs(f) <= xtol or uhi - ulo <= 1e-15:
            return Hc, V, its
        if f < 0.0:
            ulo = u
        else:
            uhi = u
        # dX/du along Z = ZF: H (dX/dH - dX/dV dZ/dH / dZ/dV)
        dfdu = Hc * (XH - XV * ZH / ZV) if ZV > 0.0 else 0.0
        un = u - f / dfdu if dfdu > 0.0 else math.nan
        if not (ulo < un < uhi) or abs(f) > 0.5 * last:
            un = 0.5 * (ulo + uhi)
        last = abs(f)
        u = un
    return math.exp(u), V, its


@jit(error_model="numpy")
def _solve_plane(XF, ZF, L, EA, W, CB, seabed, HF0, VF0, tol, max_iter):
    """The 2-D solve. Returns a tuple
    (status, HF, VF, HA, VA, LB, K11, K12, K21, K22, iterations, residual/L, profile).
    """
    nan = math.nan
    if not (
        math.isfinite(XF) and math.isfinite(ZF) and math.isfinite(L) and math.isfinite(EA)
        and math.isfinite(W) and math.isfinite(CB) and math.isfinite(tol)
        and XF >= 0.0 and L > 0.0 and EA > 0.0 and W > 0.0 and CB >= 0.0 and tol > 0.0
        and max_iter >= 1
    ):
        return CAT_INVALID_INPUT, nan, nan, nan, nan, nan, nan, nan, nan, nan, 0.0, nan, -1
    if seabed != 0 and ZF < 0.0:
        return CAT_BELOW_SEABED, nan, nan, nan, nan, nan, nan, nan, nan, nan, 0.0, nan, -1
    WL = W * L
    h_min = H_MIN_REL * WL
    h_max = H_MAX_REL * (WL + EA)

    if seabed != 0:
        if ZF == 0.0:
            # whole line on the seabed (MoorPy profile type 0)
            if XF <= L:  # slack: no tension, no stretch
                return CAT_OK, 0.0, 0.0, 0.0, 0.0, L, 0.0, 0.0, 0.0, W, 0.0, 0.0, PROFILE_ON_SEABED
            e = XF - L
            fr = CB * WL
            if EA * e / L >= 0.5 * fr:
                # tension everywhere: XF - L = (H L - CB W L^2 / 2) / EA
                H = EA * e / L + 0.5 * fr
                k11 = EA / L
            else:
                # anchor end unloaded: XF - L = H^2 / (2 CB W EA)
                H = math.sqrt(2.0 * EA * CB * W * e)
                k11 = EA * CB * W / H
            r = _eval_touchdown(H, 0.0, L, EA, W, CB)
            res = abs(r[0] - XF) / L
            # dVF/dZF is unbounded at ZF = 0 (VF ~ sqrt(2 H W ZF)); report W, the slack-line
            # value, as MoorPy does, so that a system Jacobian stays finite.
            status = CAT_OK if res <= tol else CAT_NOT_CONVERGED
            return (status, H, 0.0, max(H - fr, 0.0), 0.0, L, k11, 0.0, 0.0, W, 0.0, res,
                    PROFILE_ON_SEABED)
        # unstretched length hanging vertically from the fairlead onto the seabed:
        # ZF = Ls + W Ls^2 / (2 EA)  ->  Ls = 2 ZF / (1 + sqrt(1 + 2 W ZF / EA))
        Ls = 2.0 * ZF / (1.0 + math.sqrt(1.0 + 2.0 * W * ZF / EA))
        if Ls < L and XF <= L - Ls:
            # slack: H = 0, the resting part has room to spare (MoorPy profile type 4)
            VF = W * Ls
            res = abs(Ls + W * Ls * Ls / (2.0 * EA) - ZF) / L
            status = CAT_OK if res <= tol else CAT_NOT_CONVERGED
            return (status, 0.0, VF, 0.0, 0.0, L - Ls, 0.0, 0.0, 0.0, W / (1.0 + W * Ls / EA),
                    0.0, res, PROFILE_SLACK)
    if XF == 0.0:
        VF, VA, kh, kv = _vertical(ZF, L, EA, W)
        res = abs(_vertical_z(VF, VA, L, EA, W) - ZF) / L
        status = CAT_OK if res <= tol else CAT_NOT_CONVERGED
        return status, 0.0, VF, 0.0, VA, 0.0, kh, 0.0, 0.0, kv, 0.0, res, PROFILE_VERTICAL

    # ---- general case: Newton from the warm start, bracketing fallback
    H = HF0
    V = VF0
    if not (math.isfinite(H) and math.isfinite(V) and H > 0.0) or (seabed != 0 and not V > 0.0):
        H, V = _cold_start(XF, ZF, L, EA, W, seabed, h_min)
    H = min(max(H, h_min), h_max)
    ok, H, V, it, res, XH, XV, ZH, ZV, LB = _newton(
        XF, ZF, L, EA, W, CB, seabed, H, V, tol, max_iter, h_min, h_max
    )
    iters = it
    if not ok:
        H, V, k = _bracketed(XF, ZF, L, EA, W, CB, seabed, H, V, tol, h_min, h_max)
        iters += k
        ok, H, V, it, res, XH, XV, ZH, ZV, LB = _newton(
            XF, ZF, L, EA, W, CB, seabed, H, V, tol, max_iter, h_min, h_max
        )
        iters += it
    det = XH * ZV - XV * ZH
    if not ok or not (math.isfinite(det) and det != 0.0):
        return (CAT_NOT_CONVERGED, H, V, nan, nan, nan, nan, nan, nan, nan, float(iters), res / L,
                -1)
    # stiffness d(HF, VF)/d(XF, ZF) = inverse of the Jacobian d(X, Z)/d(HF, VF)
    k11 = ZV / det
    k12 = -XV / det
    k21 = -ZH / det
    k22 = XH / det
    if seabed != 0 and V < WL:
        HA = max(H - CB * W * LB, 0.0)
        VA = 0.0
        profile = PROFILE_TOUCHDOWN
    else:
        HA = H
        VA = V - WL
        LB = 0.0
        profile = PROFILE_TAUT if math.hypot(XF, ZF) >= L else PROFILE_SUSPENDED
    return CAT_OK, H, V, HA, VA, LB, k11, k12, k21, k22, float(iters), res / L, profile


@jit(error_model="numpy")
def catenary_solve(XF, ZF, L, EA, W, CB, seabed, HF0, VF0, tol, max_iter, out):
    """Solve the 2-D elastic catenary; results in ``out`` (length ``N_OUT_2D``).

    End A (anchor) at the origin, the fairlead at (XF >= 0, ZF). ``seabed`` = 1 when A rests on
    a flat seabed at its own height (touchdown allowed, needs ZF >= 0), 0 when the line is free
    of the seabed. ``HF0``, ``VF0``: warm start (a cold start is used when either is not
    finite or HF0 <= 0). Converged when |X - XF| + |Z - ZF| <= tol L. Returns a ``CAT_*``
    status; on failure the force entries of ``out`` are NaN.
    """
    st, H, V, HA, VA, LB, k11, k12, k21, k22, it, res, prof = _solve_plane(
        XF, ZF, L, EA, W, CB, seabed, HF0, VF0, tol, max_iter
    )
    ok = st == CAT_OK
    nan = math.nan
    out[I_HF] = H if ok else nan
    out[I_VF] = V if ok else nan
    out[I_HA] = HA if ok else nan
    out[I_VA] = VA if ok else nan
    out[I_LB] = LB if ok else nan
    out[I_K11] = k11 if ok else nan
    out[I_K12] = k12 if ok else nan
    out[I_K21] = k21 if ok else nan
    out[I_K22] = k22 if ok else nan
    out[I_ITER] = it
    out[I_RESID] = res
    out[I_PROFILE] = prof
    return st


# =========================================================================== 3-D wrapper
@jit(error_model="numpy")
def _plane_setup(anchor, fairlead, L, seabed_z):
    """Vertical plane of the line: which end is lower, seabed contact, XF, ZF, unit vector.

    The lower end plays the catenary's end A (ties keep ``anchor``), so ZF >= 0.
    Returns (status, swapped, seabed, XF, ZF, ux, uy, x_low, y_low, z_low).
    """
    ax = anchor[0]
    ay = anchor[1]
    az = anchor[2]
    fx = fairlead[0]
    fy = fairlead[1]
    fz = fairlead[2]
    if not (
        math.isfinite(ax) and math.isfinite(ay) and math.isfinite(az) and math.isfinite(fx)
        and math.isfinite(fy) and math.isfinite(fz) and math.isfinite(L) and L > 0.0
        and not math.isnan(seabed_z) and seabed_z < math.inf
    ):
        return CAT_INVALID_INPUT, False, 0, math.nan, math.nan, 1.0, 0.0, 0.0, 0.0, 0.0
    swapped = fz < az
    if swapped:
        lx, ly, lz, hx, hy, hz = fx, fy, fz, ax, ay, az
    else:
        lx, ly, lz, hx, hy, hz = ax, ay, az, fx, fy, fz
    dx = hx - lx
    dy = hy - ly
    XF = math.hypot(dx, dy)
    ZF = hz - lz
    if XF > 0.0:
        ux = dx / XF
        uy = dy / XF
    else:  # vertical line: the horizontal force is zero, any direction will do
        ux = 1.0
        uy = 0.0
    seabed = 0
    if seabed_z > -math.inf:
        gap = lz - seabed_z
        ctol = SEABED_CONTACT_TOL * L
        if gap < -ctol:
            return CAT_BELOW_SEABED, swapped, 0, XF, ZF, ux, uy, lx, ly, lz
        if gap <= ctol:
            seabed = 1
    return CAT_OK, swapped, seabed, XF, ZF, ux, uy, lx, ly, lz


@jit(error_model="numpy")
def _lower_end_stiffness(prof, H, HA, k11, k12, k21, k22, CB):
    """d(HA, VA)/d(XF, ZF): the stiffness seen at the lower end (end A)."""
    if prof == PROFILE_TOUCHDOWN:
        # VA = 0; HA = H - CB W (L - VF/W) = H - CB W L + CB VF while positive
        if HA > 0.0:
            return k11 + CB * k21, k12 + CB * k22, 0.0, 0.0
        return 0.0, 0.0, 0.0, 0.0
    if prof == PROFILE_ON_SEABED:
        return (k11 if HA > 0.0 else 0.0), 0.0, 0.0, 0.0
    if prof == PROFILE_SLACK:
        return 0.0, 0.0, 0.0, 0.0
    # free of the seabed: HA = HF, VA = VF - W L
    return k11, k12, k21, k22


@jit(error_model="numpy")
def catenary_solve_3d(anchor, fairlead, L, EA, W, CB, seabed_z, HF0, VF0, tol, max_iter, out):
    """Solve the catenary between two 3-D points (z up); results in ``out`` (``N_OUT_3D``).

    ``seabed_z``: seabed elevation, ``-inf`` for none. The lower end is the catenary's end A
    (roles swap when ``fairlead`` is lower); it may rest on the seabed when within
    ``SEABED_CONTACT_TOL * L`` of it. ``I3_HF, I3_VF`` (and the warm start ``HF0, VF0``) are
    the tension components at the upper end, ``I3_HA, I3_VA`` at the lower end, whatever the
    argument names; the forces ``I3_FAIRLEAD_FORCE`` / ``I3_ANCHOR_FORCE`` act on the points
    passed as ``fairlead`` / ``anchor``. ``I3_STIFFNESS`` is K = -d(fairlead force)/d(fairlead
    position), 3x3 row-major, including the transverse term HF/XF (its XF -> 0 limit on a
    vertical line). Returns a ``CAT_*`` status.
    """
    for i in range(N_OUT_3D):
        out[i] = math.nan
    st, swapped, seabed, XF, ZF, ux, uy, lx, ly, lz = _plane_setup(anchor, fairlead, L, seabed_z)
    out[I3_ITER] = 0.0
    out[I3_SWAPPED] = 1.0 if swapped else 0.0
    if st != CAT_OK:
        return st
    st, H, V, HA, VA, LB, k11, k12, k21, k22, it, res, prof = _solve_plane(
        XF, ZF, L, EA, W, CB, seabed, HF0, VF0, tol, max_iter
    )
    out[I3_ITER] = it
    out[I3_RESID] = res
    if st != CAT_OK:
        return st
    out[I3_HF] = H
    out[I3_VF] = V
    out[I3_HA] = HA
    out[I3_VA] = VA
    out[I3_LB] = LB
    out[I3_PROFILE] = prof
    # forces: on the upper end (-H u, -VF), on the lower end (HA u, VA); u from lower to upper
    if swapped:
        f0 = I3_ANCHOR_FORCE
        f1 = I3_FAIRLEAD_FORCE
        # stiffness of the fairlead argument = the lower end
        kh, khz, kzh, kz = _lower_end_stiffness(prof, H, HA, k11, k12, k21, k22, CB)
        ht = HA
    else:
        f0 = I3_FAIRLEAD_FORCE
        f1 = I3_ANCHOR_FORCE
        kh, khz, kzh, kz = k11, k12, k21, k22
        ht = H
    out[f0] = -H * ux
    out[f0 + 1] = -H * uy
    out[f0 + 2] = -V
    out[f1] = HA * ux
    out[f1 + 1] = HA * uy
    out[f1 + 2] = VA
    # K = [[kh u u^T + kt (I - u u^T), khz u], [kzh u^T, kz]], kt = (horizontal tension)/XF:
    # the pendulum-like stiffness of the direction change (d u / d p = (I - u u^T) / XF).
    # On a vertical line kt -> dH/dXF, the same limit as kh.
    kt = ht / XF if XF > 0.0 else kh
    k = I3_STIFFNESS
    out[k + 0] = kh * ux * ux + kt * (1.0 - ux * ux)
    out[k + 1] = (kh - kt) * ux * uy
    out[k + 2] = khz * ux
    out[k + 3] = (kh - kt) * ux * uy
    out[k + 4] = kh * uy * uy + kt * (1.0 - uy * uy)
    out[k + 5] = khz * uy
    out[k + 6] = kzh * ux
    out[k + 7] = kzh * uy
    out[k + 8] = kz
    # a free line whose sag reaches below the seabed (U-shaped contact is not modelled)
    if seabed == 0 and seabed_z > -math.inf and VA < 0.0:
        # lowest point at s* = -VA/W: z* = -(hypot(H, VA) - H)/W - VA^2/(2 W EA)
        hb = math.hypot(H, VA)
        zs = -VA * VA / (W * (hb + H)) - VA * VA / (2.0 * W * EA)
        if lz + zs < seabed_z - SEABED_CONTACT_TOL * L:
            return CAT_SAG_BELOW_SEABED
    return CAT_OK


__all__ = [
    "CAT_OK", "CAT_NOT_CONVERGED", "CAT_INVALID_INPUT", "CAT_BELOW_SEABED",
    "CAT_SAG_BELOW_SEABED",
    "PROFILE_SUSPENDED", "PROFILE_TAUT", "PROFILE_TOUCHDOWN", "PROFILE_ON_SEABED",
    "PROFILE_SLACK", "PROFILE_VERTICAL",
    "I_HF", "I_VF", "I_HA", "I_VA", "I_LB", "I_K11", "I_K12", "I_K21", "I_K22", "I_ITER",
    "I_RESID", "I_PROFILE", "N_OUT_2D",
    "I3_FAIRLEAD_FORCE", "I3_ANCHOR_FORCE", "I3_HF", "I3_VF", "I3_HA", "I3_VA", "I3_LB",
    "I3_ITER", "I3_RESID", "I3_STIFFNESS", "I3_PROFILE", "I3_SWAPPED", "N_OUT_3D",
    "SEABED_CONTACT_TOL",
    "catenary_solve", "catenary_solve_3d",
]
