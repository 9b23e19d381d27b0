"""Closed-form equations of the quasi-static elastic catenary with seabed contact and friction.

This module holds the numba kernels that evaluate the catenary equations and their derivatives
with respect to (HF, VF): the fully suspended line, the line partly resting on the seabed with
Coulomb friction, and the elastic stretch of the resting length. The solvers that use them are in
:mod:`floatmoor.mooring._catenary_kernels`.

The equations are the classic elastic catenary (Irvine 1981, *Cable Structures*) with the
resting length and Coulomb seabed friction of the FAST v7 catenary (Jonkman 2007,
NREL/TP-500-41958), exactly as written in ``docs/theory/quasi_static.md``, which this module
quotes below.

Symbols (SI units)
------------------
======  =============================================================================  ======
XF      horizontal distance from the anchor (end A) to the fairlead (end B)            m
ZF      height of the fairlead above the anchor                                        m
L       unstretched line length                                                        m
EA      axial stiffness                                                                N
W       submerged weight per unstretched length (> 0; buoyant lines are rejected)      N/m
CB      seabed (Coulomb) friction coefficient                                          -
H, HF   horizontal tension (constant along the suspended part)                         N
VF      vertical tension at the fairlead, > 0 when the line pulls the fairlead down    N
HA, VA  anchor force components: towards the fairlead / upward positive               N
LB      unstretched length resting on the seabed                                       m
s       unstretched arc length from the anchor                                         m
======  =============================================================================  ======

Equations (anchor at the origin, V(s) = VA + W s the vertical tension along a free span):

* fully suspended, VA = VF - W L (docs/theory/quasi_static.md, fully suspended line)::

      X = (H/W) [asinh(VF/H) - asinh(VA/H)] + H L / EA
      Z = (H/W) [sqrt(1 + (VF/H)^2) - sqrt(1 + (VA/H)^2)] + (VF L - W L^2 / 2) / EA

* touchdown (seabed at the anchor, VF < W L), LB = L - VF/W (docs/theory/quasi_static.md,
  line resting on the seabed, with its friction term)::

      X = LB + (H/W) asinh(VF/H) + H L / EA
          + (CB W / 2EA) [-LB^2 + (LB - H/(CB W)) max(LB - H/(CB W), 0)]
      Z = (H/W) [sqrt(1 + (VF/H)^2) - 1] + VF^2 / (2 EA W)
      HA = max(H - CB W LB, 0),  VA = 0

The kernels never evaluate these in the forms above: differences of nearly equal terms are
rewritten without cancellation (see :func:`_asinh_diff` and :func:`_eval_suspended`), which keeps
the equations exact to a few ulps of L for taut, nearly vertical and nearly slack lines alike.
"""

from __future__ import annotations

import math

from floatmoor._numba import jit


# =========================================================================== closed-form pieces
@jit(error_model="numpy")
def _asinh_diff(Vt, Vb, H, dV):
    """asinh(Vt/H) - asinh(Vb/H) with dV = Vt - Vb > 0 supplied exactly.

    For Vt, Vb of one sign the difference is asinh(D) with
    D = sinh(asinh(a) - asinh(b)) = a sqrt(1+b^2) - b sqrt(1+a^2) = dV (Vt+Vb) / (Vt hb + Vb ha),
    ha = hypot(H, Vt), hb = hypot(H, Vb): free of cancellation for taut lines. Of opposite signs
    the two terms add and the direct form is exact (it needs H > 0).
    """
    if Vt * Vb >= 0.0:
        ha = math.hypot(H, Vt)
        hb = math.hypot(H, Vb)
        den = Vt * hb + Vb * ha
        if den == 0.0:
            return 0.0
        return math.asinh(dV * (Vt + Vb) / den)
    return math.asinh(Vt / H) - math.asinh(Vb / H)


@jit(error_model="numpy")
def _eval_suspended(H, V, L, EA, W):
    """X, Z and the Jacobian of the fully suspended line (elastic catenary, Irvine), H > 0.

    Returns (X, Z, dX/dH, dX/dV, dZ/dH, dZ/dV, LB=0).
    """
    WL = W * L
    VA = V - WL
    ha = math.hypot(H, V)
    hb = math.hypot(H, VA)
    asd = _asinh_diff(V, VA, H, WL)
    # g = a/sqrt(1+a^2) - b/sqrt(1+b^2) = V/ha - VA/hb, without cancellation when of one sign:
    # V hb - VA ha = H^2 (V^2 - VA^2) / (V hb + VA ha)
    if V * VA >= 0.0:
        den = V * hb + VA * ha
        g = H * H * WL * (V + VA) / (den * ha * hb) if den != 0.0 else 0.0
    else:
        g = V / ha - VA / hb
    X = H / W * asd + H * L / EA
    # (H/W)(sqrt(1+a^2) - sqrt(1+b^2)) = (ha - hb)/W = L (V + VA) / (ha + hb)
    Z = L * (V + VA) / (ha + hb) + L * (V + VA) / (2.0 * EA)
    XH = (asd - g) / W + L / EA
    # (H/W)(1/ha - 1/hb), with hb - ha = -W L (V + VA) / (ha + hb); symmetric: dX/dV = dZ/dH
    XV = -H * L * (V + VA) / (ha * hb * (ha + hb))
    ZV = g / W + L / EA
    return X, Z, XH, XV, XV, ZV, 0.0


@jit(error_model="numpy")
def _seabed_stretch(H, LB, EA, W, CB):
    """Elastic stretch of the resting length and its partials.

    The friction term of the resting line in docs/theory/quasi_static.md.

    Tension along the resting part drops from H at touchdown by CB W per unit length towards
    the anchor, floored at zero: T(s) = max(H - CB W (LB - s), 0).
    Returns (stretch, d/dH, d/dLB).
    """
    fr = CB * W * LB
    if fr <= H:  # anchor tension HA = H - CB W LB >= 0 (always so without friction)
        return (H - 0.5 * fr) * LB / EA, LB / EA, (H - fr) / EA
    # tension vanishes at xB = LB - H/(CB W) > 0: stretch = integral of the linear part
    return H * H / (2.0 * CB * W * EA), H / (CB * W * EA), 0.0


@jit(error_model="numpy")
def _eval_touchdown(H, V, L, EA, W, CB):
    """X, Z and Jacobian of the line partly resting on the seabed (touchdown, Jonkman 2007).

    0 <= V < W L, H > 0. Returns (X, Z, dX/dH, dX/dV, dZ/dH, dZ/dV, LB).
    """
    Ls = V / W  # suspended unstretched length
    LB = L - Ls
    ha = math.hypot(H, V)
    a = V / H
    asv = math.asinh(a)
    sb, sbH, sbLB = _seabed_stretch(H, LB, EA, W, CB)
    X = LB + sb + H / W * asv + H * Ls / EA
    # (H/W)(sqrt(1 + a^2) - 1) = (ha - H)/W = V^2 / (W (ha + H))
    c = V * V / (W * (ha + H))
    Z = c + V * Ls / (2.0 * EA)
    # (1/W)(asinh(a) - a/sqrt(1+a^2)) + Ls/EA + d(stretch)/dH
    XH = (asv - V / ha) / W + Ls / EA + sbH
    # dLB/dV = -1/W;  -1/W + (1/W)/sqrt(1+a^2) = -(ha - H)/(W ha) = -c/ha
    cz = c / ha
    XV = -cz + H / (W * EA) - sbLB / W
    ZH = -cz
    ZV = V / (W * ha) + V / (W * EA)
    return X, Z, XH, XV, ZH, ZV, LB


@jit(error_model="numpy")
def _eval(H, V, L, EA, W, CB, seabed):
    """Dispatch on the profile type: touchdown when the anchor rests on the seabed and VF < W L.

    Both branches agree in value and first derivatives at VF = W L (VA = 0, LB = 0), so the
    Newton iteration may cross between them.
    """
    if seabed != 0 and V < W * L:
        return _eval_touchdown(H, V, L, EA, W, CB)
    return _eval_suspended(H, V, L, EA, W)


__all__ = ["_asinh_diff", "_eval_suspended", "_seabed_stretch", "_eval_touchdown", "_eval"]
