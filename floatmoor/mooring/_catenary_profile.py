"""Numba kernels of the profile of a solved quasi-static elastic catenary.

Positions and effective tension along the line at given unstretched arc lengths, in the plane
of the line (:func:`catenary_profile`) or in 3-D (:func:`catenary_profile_3d`), from a solution
(HF, VF) of the solvers in :mod:`floatmoor.mooring._catenary_kernels`; the equations are those
of :mod:`floatmoor.mooring._catenary_equations`, evaluated at arc length s.
"""

from __future__ import annotations

import math

from floatmoor._numba import jit
from floatmoor.mooring._catenary_equations import _asinh_diff, _seabed_stretch
from floatmoor.mooring._catenary_kernels import CAT_OK, _plane_setup


# =========================================================================== profiles
@jit(error_model="numpy")
def _profile_point(s, XF, L, EA, W, CB, seabed, H, V):
    """Position (x, z) relative to end A and effective tension at unstretched arc length s."""
    WL = W * L
    if seabed != 0 and V < WL:
        LB = L - V / W
        if not (H > 0.0):
            # slack: the resting part is not straight; spread it evenly up to below the fairlead
            if s <= LB:
                return (XF * s / LB if LB > 0.0 else 0.0), 0.0, 0.0
            sig = s - LB
            return XF, sig + W * sig * sig / (2.0 * EA), W * sig
        if s <= LB:
            fr = CB * W * LB
            if fr <= H:
                T = H - CB * W * (LB - s)
                x = s + ((H - fr) * s + 0.5 * CB * W * s * s) / EA
            else:
                xB = LB - H / (CB * W)
                if s <= xB:
                    T = 0.0
                    x = s
                else:
                    T = CB * W * (s - xB)
                    x = s + 0.5 * CB * W * (s - xB) * (s - xB) / EA
            return x, 0.0, T
        sig = s - LB
        Vs = W * sig
        hs = math.hypot(H, Vs)
        sb = _seabed_stretch(H, LB, EA, W, CB)[0]
        x = LB + sb + H / W * math.asinh(Vs / H) + H * sig / EA
        z = Vs * Vs / (W * (hs + H)) + Vs * sig / (2.0 * EA)
        return x, z, hs
    # free span from A: V(s) = VA + W s (the suspended equations at arc length s)
    VA = V - WL
    Vs = VA + W * s
    ha = math.hypot(H, Vs)
    hb = math.hypot(H, VA)
    x = H / W * _asinh_diff(Vs, VA, H, W * s) + H * s / EA if H > 0.0 else 0.0
    den = ha + hb
    zg = s * (Vs + VA) / den if den > 0.0 else 0.0
    z = zg + (VA * s + 0.5 * W * s * s) / EA
    return x, z, ha


@jit(error_model="numpy")
def catenary_profile(XF, ZF, L, EA, W, CB, seabed, HF, VF, s, x_out, z_out, T_out):
    """Positions (x from A, z relative to A) and effective tension at arc lengths ``s``.

    ``HF``, ``VF``: a solution of :func:`catenary_solve` for the same inputs.
    """
    for i in range(s.shape[0]):
        x, z, T = _profile_point(s[i], XF, L, EA, W, CB, seabed, HF, VF)
        x_out[i] = x
        z_out[i] = z
        T_out[i] = T


@jit(error_model="numpy")
def catenary_profile_3d(anchor, fairlead, L, EA, W, CB, seabed_z, HF, VF, s, pos_out, T_out):
    """Global positions (n, 3) and effective tension at arc lengths ``s`` from ``anchor``.

    ``HF``, ``VF``: ``out[I3_HF]``, ``out[I3_VF]`` of :func:`catenary_solve_3d` (upper end).
    NaN when the geometry is invalid.
    """
    st, swapped, seabed, XF, ZF, ux, uy, lx, ly, lz = _plane_setup(anchor, fairlead, L, seabed_z)
    for i in range(s.shape[0]):
        if st != CAT_OK:
            pos_out[i, 0] = math.nan
            pos_out[i, 1] = math.nan
            pos_out[i, 2] = math.nan
            T_out[i] = math.nan
            continue
        si = L - s[i] if swapped else s[i]
        x, z, T = _profile_point(si, XF, L, EA, W, CB, seabed, HF, VF)
        pos_out[i, 0] = lx + x * ux
        pos_out[i, 1] = ly + x * uy
        pos_out[i, 2] = lz + z
        T_out[i] = T


__all__ = ["catenary_profile", "catenary_profile_3d"]
