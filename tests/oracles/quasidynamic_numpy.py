"""Plain NumPy/SciPy reference of the quasi-dynamic line model, independent of the numba kernels.

The quasi-dynamic paper's section 3 written literally, one array expression per equation:
the static positions of the Simpson stations from the literal closed-form profile of
:func:`tests.oracles.catenary_numpy.profile` (arcsinh, no reformulation), the backward
differences of eq. (4), the forces of eq. (3), eq. (2) integrated with
:func:`scipy.integrate.simpson`, and eq. (1). The static catenary solutions (H, V per sample) are
inputs: the catenary has its own oracle tests, and feeding both implementations the same ones
keeps this comparison free of solver noise, which eq. (4) would amplify by 1/dt^2.

Model choices (as in :mod:`floatmoor.mooring.quasidynamic`): fixed stations s_j = L - j h on
the suspended part, above the material points that lifted off since the step before last (an
even number of Simpson intervals, the lowest station dropped if need be), the rest of the
suspended part integrated with the quadratic through the three lowest stations; differences of
the material points at the stations on the two previous static lines; a = (v_n - v_{n-1}) / ((dt_n + dt_{n-1}) / 2), at rest before the
first step; normal components relative to the static tangent; material-area added mass; the
anchor force of the apparent-weight catenary. Restricted to lines whose fairlead is above the
anchor with H > 0 (no slack or vertical profiles). Units SI.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import simpson

from tests.oracles import catenary_numpy as cat


@dataclass(frozen=True)
class QDLine:
    """A line and its surroundings."""

    anchor: tuple[float, float, float]
    L: float  #: unstretched length [m]
    EA: float  #: [N]
    W: float  #: submerged weight per length [N/m]
    CB: float  #: seabed friction of the catenary [-]
    seabed: bool  #: the anchor rests on the seabed
    m: float  #: mass per length [kg/m]
    rho_w: float  #: [kg/m^3]
    Cdn: float  #: normal drag coefficient on d [-]
    d: float  #: drag diameter [m]
    Ca: float  #: normal added-mass coefficient on the material area m / rho_c [-]
    rho_c: float  #: material density [kg/m^3]
    spacing: float  #: station spacing h [m]: stations s_j = L - j h from the anchor


def positions(line: QDLine, fairlead: np.ndarray, H: float, V: float,
              s: np.ndarray) -> np.ndarray:
    """Global positions (n, 3) at unstretched arc lengths s from the anchor of the static line
    with upper-end tensions (H, V)."""
    anchor = np.asarray(line.anchor, dtype=float)
    span = np.asarray(fairlead, dtype=float) - anchor
    XF = float(np.hypot(span[0], span[1]))
    assert span[2] >= 0.0 and H > 0.0, "oracle: fairlead above the anchor and H > 0 only"
    u = np.array([span[0] / XF, span[1] / XF, 0.0])
    plane = cat.Line(XF=XF, ZF=float(span[2]), L=line.L, EA=line.EA, W=line.W, CB=line.CB,
                     seabed=line.seabed)
    laid = line.L - V / line.W if cat.touches_down(plane, V) else 0.0
    x, z, _ = cat.profile(plane, cat.Solution(HF=H, VF=V, HA=H, VA=V - line.W * line.L,
                                              LB=laid), s)
    return anchor[None, :] + x[:, None] * u[None, :] + z[:, None] * np.array([0.0, 0.0, 1.0])


def run(line: QDLine, time: np.ndarray, path: np.ndarray, H: np.ndarray, V: np.ndarray,
        fairlead_force: np.ndarray, anchor_force: np.ndarray) -> dict[str, np.ndarray]:
    """k_QD and the end forces at every sample of a path, starting at rest at sample 0.

    Parameters
    ----------
    line
        The line.
    time, path
        Sample times [s] (n,) and fairlead positions [m] (n, 3).
    H, V
        Static upper-end tension components at every sample [N] (n,).
    fairlead_force, anchor_force
        Static end forces at every sample [N] (n, 3).

    Returns
    -------
    dict
        ``factor`` (n,), ``fairlead_force`` and ``anchor_force`` (n, 3).
    """
    n = time.size
    anchor = np.asarray(line.anchor, dtype=float)
    area = line.m / line.rho_c
    k = np.ones(n)
    ff = np.array(fairlead_force, dtype=float)
    fa = np.array(anchor_force, dtype=float)
    h = line.spacing
    grid = line.L - np.arange(int(np.floor(line.L / h * (1 + 1e-9))) + 1) * h  # s_j = L - j h

    def laid_length(j: int) -> float:
        return line.L - V[j] / line.W if line.seabed and V[j] < line.W * line.L else 0.0

    for i in range(1, n):
        laid = laid_length(i)
        # stations on the suspended part, above the material points lifted off the seabed
        # since the step before last; an even number of Simpson intervals
        lift = max(laid, laid_length(i - 1), laid_length(max(i - 2, 0)))
        sigma = grid[grid >= lift - 1e-9 * h][::-1]  # ascending
        if (sigma.size - 1) % 2 == 1:
            sigma = sigma[1:]
        assert sigma.size >= 3, "oracle: at least three stations on the suspended part"
        # static positions of the material points at the stations: now, one and two steps ago
        r0 = positions(line, path[i], H[i], V[i], sigma)
        r1 = positions(line, path[i - 1], H[i - 1], V[i - 1], sigma)
        r2 = positions(line, path[max(i - 2, 0)], H[max(i - 2, 0)], V[max(i - 2, 0)], sigma)
        # eq. (4)
        dt = time[i] - time[i - 1]
        v = (r0 - r1) / dt
        if i >= 2:
            dtp = time[i - 1] - time[i - 2]
            a = (v - (r1 - r2) / dtp) / (0.5 * (dt + dtp))
        else:
            a = v / dt  # at rest before the first step
        # static unit tangent (H u, V(sigma)) / T
        span = path[i] - anchor
        u = np.array([span[0], span[1], 0.0]) / np.hypot(span[0], span[1])
        Vs = V[i] - line.W * (line.L - sigma)
        t = (H[i] * u[None, :] + Vs[:, None] * np.array([0.0, 0.0, 1.0])) \
            / np.hypot(H[i], Vs)[:, None]
        vn = v - np.sum(v * t, axis=1)[:, None] * t
        an = a - np.sum(a * t, axis=1)[:, None] * t
        # eq. (3): weight, Morison normal drag and added mass, inertia
        f_w = -line.W * np.ones(sigma.size)
        f_hd = (-0.5 * line.rho_w * line.Cdn * line.d * np.linalg.norm(vn, axis=1) * vn[:, 2]
                - line.Ca * line.rho_w * area * an[:, 2])
        f_i = line.m * a[:, 2]
        # eq. (2), clamped at zero: Simpson over the stations, and on [L_B, lowest station]
        # the quadratic through the three lowest stations' densities
        f = f_w + f_hd - f_i
        integral = simpson(f, x=sigma)
        quadratic = np.polyint(np.polyfit(sigma[:3], f[:3], 2))
        integral += np.polyval(quadratic, sigma[0]) - np.polyval(quadratic, laid)
        k[i] = max(integral / (-line.W * (line.L - laid)), 0.0)
        # eq. (1) at the fairlead; the apparent-weight catenary at the anchor
        ff[i] = k[i] * fairlead_force[i]
        if laid > 0.0:
            fa[i] = max(k[i] * H[i] - line.CB * line.W * laid, 0.0) * u
        else:
            fa[i] = k[i] * anchor_force[i]
    return {"factor": k, "fairlead_force": ff, "anchor_force": fa}
