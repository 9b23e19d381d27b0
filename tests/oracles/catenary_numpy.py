"""Plain NumPy/SciPy reference for the elastic catenary, independent of the numba kernels.

The equations are the closed forms of ``docs/theory/quasi_static.md`` (Irvine 1981; Jonkman 2007),
written literally (no reformulation against cancellation, so keep test lines away from the
extreme taut limit where that costs digits). The solver nests two :func:`scipy.optimize.brentq`
root finds: VF such that Z(H, VF) = ZF for fixed H, inside a root find on ln H for
X(H, VF(H)) = XF. Both functions are monotone, so the bracketing is reliable, if slow. The
Jacobian comes from complex-step differentiation of the same equations, so the stiffness is
checked against a derivative computed without any of the kernels' hand-derived partials.

Symbols as in :mod:`floatmoor.mooring.catenary`. Units SI.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq


@dataclass(frozen=True)
class Line:
    """One 2-D catenary problem: fairlead at (XF, ZF) from the anchor."""

    XF: float
    ZF: float
    L: float
    EA: float
    W: float
    CB: float = 0.0
    seabed: bool = False


def touches_down(line: Line, VF: complex) -> bool:
    """Profile type: part of the line rests on the seabed when VF < W L (LB = L - VF/W > 0)."""
    return line.seabed and float(np.real(VF)) < line.W * line.L


def end_point(line: Line, H: complex, VF: complex) -> tuple[complex, complex]:
    """(X, Z) of the fairlead for tensions (H, VF); complex-step safe."""
    L, EA, W, CB = line.L, line.EA, line.W, line.CB
    if not touches_down(line, VF):
        # fully suspended (docs/theory/quasi_static.md)
        X = (H / W) * (np.arcsinh(VF / H) - np.arcsinh((VF - W * L) / H)) + H * L / EA
        Z = ((H / W) * (np.sqrt(1 + (VF / H) ** 2) - np.sqrt(1 + ((VF - W * L) / H) ** 2))
             + (VF * L - W * L**2 / 2) / EA)
        return X, Z
    LB = L - VF / W
    X = LB + (H / W) * np.arcsinh(VF / H) + H * L / EA
    if CB > 0:
        # friction term, with max(.) decided on the real part
        xb = LB - H / (CB * W)
        X = X + (CB * W / (2 * EA)) * (-LB**2 + (xb * xb if np.real(xb) > 0 else 0.0))
    Z = (H / W) * (np.sqrt(1 + (VF / H) ** 2) - 1) + VF**2 / (2 * EA * W)
    return X, Z


def residual(line: Line, H: float, VF: float) -> tuple[float, float]:
    """(X - XF, Z - ZF) [m]."""
    X, Z = end_point(line, H, VF)
    return float(np.real(X)) - line.XF, float(np.real(Z)) - line.ZF


def jacobian(line: Line, H: float, VF: float) -> np.ndarray:
    """d(X, Z)/d(H, VF) by complex-step differentiation (exact to roundoff)."""
    J = np.empty((2, 2))
    for j, (dh, dv) in enumerate(((1.0, 0.0), (0.0, 1.0))):
        step = 1e-30 * max(abs(H), abs(VF), line.W * line.L)
        X, Z = end_point(line, H + 1j * step * dh, VF + 1j * step * dv)
        J[0, j] = np.imag(X) / step
        J[1, j] = np.imag(Z) / step
    return J


def hanging_length(line: Line) -> float:
    """Unstretched length hanging vertically onto the seabed: ZF = Ls + W Ls^2 / (2 EA)."""
    a = line.W / (2 * line.EA)
    return 2 * line.ZF / (1 + math.sqrt(1 + 4 * a * line.ZF))  # root of a Ls^2 + Ls - ZF


def _vf_for_z(line: Line, H: float) -> float:
    def f(v: float) -> float:
        return residual(line, H, v)[1]

    if line.seabed:
        lo, hi = 0.0, line.W * line.L
    else:
        lo, hi = -line.W * line.L, line.W * line.L
    while f(lo) > 0:
        lo = lo - 2 * (hi - lo)
    while f(hi) < 0:
        hi = hi + 2 * (hi - lo)
    if f(lo) == 0:
        return lo
    return brentq(f, lo, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500)


@dataclass(frozen=True)
class Solution:
    """Oracle solution of a :class:`Line`."""

    HF: float
    VF: float
    HA: float
    VA: float
    LB: float


def solve(line: Line) -> Solution:
    """Solve for (HF, VF) with nested brentq; closed form for the slack line on the seabed."""
    L, W, CB = line.L, line.W, line.CB
    if line.seabed:
        Ls = hanging_length(line)
        if Ls < L and line.XF <= L - Ls:  # slack: H = 0
            return Solution(0.0, W * Ls, 0.0, 0.0, L - Ls)

    def g(u: float) -> float:
        H = math.exp(u)
        return residual(line, H, _vf_for_z(line, H))[0]

    scale = math.log(W * L)
    lo, hi = scale - 5, scale + 5
    while g(lo) > 0:
        lo -= 5
    while g(hi) < 0:
        hi += 5
    u = brentq(g, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=500)
    H = math.exp(u)
    VF = _vf_for_z(line, H)
    if touches_down(line, VF):
        LB = L - VF / W
        return Solution(H, VF, max(H - CB * W * LB, 0.0), 0.0, LB)
    return Solution(H, VF, H, VF - W * L, 0.0)


def stiffness(line: Line, sol: Solution) -> np.ndarray:
    """d(HF, VF)/d(XF, ZF) = inverse of the complex-step Jacobian."""
    return np.linalg.inv(jacobian(line, sol.HF, sol.VF))


def profile(line: Line, sol: Solution, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """x, z (from the anchor) and effective tension at unstretched arc lengths s (H > 0)."""
    L, EA, W, CB = line.L, line.EA, line.W, line.CB
    H, VF = sol.HF, sol.VF
    s = np.asarray(s, dtype=float)
    x = np.empty_like(s)
    z = np.empty_like(s)
    T = np.empty_like(s)
    if not touches_down(line, VF):
        VA = VF - W * L
        V = VA + W * s
        x[:] = (H / W) * (np.arcsinh(V / H) - np.arcsinh(VA / H)) + H * s / EA
        z[:] = ((H / W) * (np.sqrt(1 + (V / H) ** 2) - np.sqrt(1 + (VA / H) ** 2))
                + (VA * s + W * s**2 / 2) / EA)
        T[:] = np.sqrt(H**2 + V**2)
        return x, z, T
    LB = L - VF / W
    xb = LB - H / (CB * W) if CB > 0 else -np.inf  # tension zero for s < xb
    for i, si in enumerate(s):
        if si <= LB:
            # tension along the bed T(s) = max(H - CB W (LB - s), 0); x = s + int T / EA
            if xb <= 0:
                stretch = (H - CB * W * LB) * si / EA + CB * W * si**2 / (2 * EA)
            else:
                stretch = CB * W * max(si - xb, 0.0) ** 2 / (2 * EA)
            x[i] = si + stretch
            z[i] = 0.0
            T[i] = max(H - CB * W * (LB - si), 0.0)
        else:
            sig = si - LB
            V = W * sig
            if xb <= 0:
                bed = LB + (H * LB - CB * W * LB**2 / 2) / EA
            else:
                bed = LB + H**2 / (2 * CB * W * EA)
            x[i] = bed + (H / W) * np.arcsinh(V / H) + H * sig / EA
            z[i] = (H / W) * (np.sqrt(1 + (V / H) ** 2) - 1) + W * sig**2 / (2 * EA)
            T[i] = np.sqrt(H**2 + V**2)
    return x, z, T
