"""Numba kernels of the quasi-dynamic line model (quasi-dynamic paper section 3; physics.md 4).

One step (:func:`qd_step`) for the fairlead position at time t_n, a time step dt after t_{n-1}:

1. the static elastic catenary for the current fairlead position (warm-started Newton,
   :func:`~floatmoor.mooring._catenary_kernels.catenary_solve_3d`): upper-end tension (H, V),
   laid length L_B and the static end forces; this is the static tension T_S of eq. (1);
2. ``N`` Simpson stations sigma_j = L_B + j (L - L_B) / (N - 1), j = 0..N-1, spread over the
   suspended part [s_0, l] of eq. (2) (unstretched arc length from the lower end, s_0 = L_B the
   touchdown point of this step);
3. the positions of the *material* points at these stations on the static catenaries of steps
   n, n-1 and n-2, evaluated exactly at the same unstretched arc length (points that were on
   the seabed at an earlier step sit on its resting part there), and their velocities and
   accelerations by the backward differences of eq. (4):
   v_n = (r_n - r_{n-1}) / dt_n, v_{n-1} = (r_{n-1} - r_{n-2}) / dt_{n-1},
   a_n = (v_n - v_{n-1}) / ((dt_n + dt_{n-1}) / 2), which is eq. (4) for equal steps and keeps
   first-order accuracy for unequal ones; before the first step the line is at rest
   (v_{n-1} = 0, a_n = v_n / dt_n);
4. the vertical component of the distributed forces per unstretched length of eq. (3):
   weight f_w = -W k, inertia f_I = m a, and the Morison normal drag and added mass
   f_HD = -1/2 rho_w C_dn d |v_n| v_n - C_a rho_w A_c a_n, with v_n, a_n the components normal
   to the static tangent t (v - (v.t) t; for a line in its vertical plane this is eq. (3)'s
   (v.n) n), A_c = m / rho_c the material area (floatmoor's added-mass convention, also the
   dynamic model's);
5. the quasi-dynamic factor of eq. (2), composite Simpson over the stations,
   k_QD = int (f_w + f_HD - f_I).k ds / int f_w.k ds, clamped at k_QD >= 0 (slack);
6. eq. (1): the upper-end force is k_QD times the static one. The lower end gets the force of
   the same apparent-weight catenary: k_QD times the static force when no part rests on the
   seabed (a catenary of weight k_QD W has the same shape and k_QD times the forces); with a
   resting length L_B, the horizontal tension k_QD H at the touchdown point, reduced by the
   seabed friction C_B W L_B of the resting part (which does not move), floored at zero.

The current (steady) and the water line are ignored, like by the static catenary, which gives
the whole line its submerged weight: the hydrodynamic forces act along the whole suspended part.

Cost: one catenary solve and 3 N profile points per step (eq. 4 needs three static lines at the
same material points). To keep it near the quasi-static model's, the log in the catenary's
asinh term is not evaluated 3 N times: log q = log q_r + log1p(q / q_r - 1), by a short series,
from a reference q_r at the same station index, the previous step's for the current line
(chained, and evaluated directly every ``CHAIN_STEPS`` steps) and the current line's for the
two earlier ones; exact to round-off, with direct logs wherever the series does not apply. The
loops over the stations have no branches, so that they vectorise.

Everything is preallocated; the kernels allocate nothing and report failure by status.
Parameters travel in one float64 array ``prm`` indexed by the ``Q_*`` constants; the state of
the line is ``hist`` (the last two static solutions), ``cur`` (the ``C_*`` entries) and
``chain`` (the log references of the stations).
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring._catenary_equations import _seabed_stretch
from floatmoor.mooring._catenary_kernels import (
    CAT_OK, I3_ANCHOR_FORCE, I3_FAIRLEAD_FORCE, I3_HF, I3_ITER, I3_LB, I3_SWAPPED, I3_VF,
    SEABED_CONTACT_TOL, _plane_setup, catenary_solve_3d,
)
from floatmoor.mooring._catenary_profile import _profile_point
from floatmoor.mooring.dg._kernels import hermite

__all__ = [
    "Q_L", "Q_EA", "Q_W", "Q_CB", "Q_ZB", "Q_TOL", "Q_MAXIT", "Q_M", "Q_DRAG", "Q_MA",
    "Q_MAXDT", "Q_INV_W", "Q_INV_EA", "N_QPRM", "C_K", "C_FAIRLEAD_FORCE", "C_ANCHOR_FORCE",
    "C_LB", "C_DT", "C_CHAIN", "N_CUR", "H_FAIRLEAD", "H_HF", "H_VF", "H_LB", "N_HIST",
    "CHAIN_STEPS", "qd_step", "quasi_dynamic_series",
]

# -- parameter layout -----------------------------------------------------------------------
Q_L = 0  #: unstretched length [m]
Q_EA = 1  #: axial stiffness [N]
Q_W = 2  #: submerged weight per length [N/m]
Q_CB = 3  #: seabed friction coefficient of the catenary [-]
Q_ZB = 4  #: seabed elevation [m] (-inf: none)
Q_TOL = 5  #: catenary tolerance [-]
Q_MAXIT = 6  #: catenary Newton iterations
Q_M = 7  #: mass per length, rho_m A of eq. (3) [kg/m]
Q_DRAG = 8  #: 1/2 rho_w C_dn d [kg/m^2]
Q_MA = 9  #: normal added mass per length C_a rho_w A_c [kg/m]
Q_MAXDT = 10  #: largest step of the backward differences [s]; 0: one step per sample
Q_INV_W = 11  #: 1 / W [m/N]
Q_INV_EA = 12  #: 1 / EA [1/N]
N_QPRM = 13

# -- layout of ``cur``: the outputs of the last step, and its time step ----------------------
C_K = 0  #: k_QD
C_FAIRLEAD_FORCE = 1  #: 3 entries [N]
C_ANCHOR_FORCE = 4  #: 3 entries [N]
C_LB = 7  #: laid length [m]
C_DT = 8  #: length of the last step [s]; 0 when the line was at rest before
C_CHAIN = 9  #: steps since the logs of the stations were last evaluated directly
N_CUR = 10

# -- layout of a row of ``hist`` (row 0: the last step, row 1: the one before) ---------------
H_FAIRLEAD = 0  #: 3 entries [m]
H_HF = 3  #: upper-end horizontal tension [N]
H_VF = 4  #: upper-end vertical tension [N]
H_LB = 5  #: laid length [m]
N_HIST = 6

#: |q'/q - 1| up to which log q' = log q + log1p(q'/q - 1) takes the series below: its 9 terms
#: leave a truncation error below |e|^10 / 10 = 1e-21, under the round-off of the log itself.
_SERIES_LIMIT = 1e-2
#: Steps after which the chained logs of the stations are evaluated directly again: each link
#: adds about an ulp, so the chain stays within ~sqrt(1024) = 32 ulps of log q (and this
#: round-off is common to the three steps of a backward difference).
CHAIN_STEPS = 1024


@jit(error_model="numpy", inline="always")
def _log1p_small(e: float) -> float:
    """log(1 + e) for |e| <= ``_SERIES_LIMIT``: the alternating series to e^9 (Horner)."""
    return e * (1.0 - e * (0.5 - e * (1.0 / 3.0 - e * (0.25 - e * (0.2 - e * (
        1.0 / 6.0 - e * (1.0 / 7.0 - e * (0.125 - e / 9.0))))))))


@jit(error_model="numpy", inline="always")
def _level_xz(anchor: np.ndarray, fx: float, fy: float, fz: float, prm: np.ndarray, H: float,
              V: float, LB: float, s0: float, ds: float, jf: np.ndarray, mode: int,
              ref: np.ndarray, sc: np.ndarray, x: np.ndarray, z: np.ndarray, row: int
              ) -> tuple[float, float, float, float, float]:
    """Positions at the unstretched arc lengths s0 + ds j from the anchor (j = ``jf`` = 0.0, 1.0,
    ..., n - 1) on the static line solved with upper-end tension (H, V) and laid length L_B for
    the fairlead at (fx, fy, fz), in its vertical plane: x along the plane and z up from its
    lower end (written to ``x[row]``, ``z[row]``).

    The equations are those of :func:`~floatmoor.mooring._catenary_profile._profile_point`,
    with the vertical coordinate of the suspended part as (hypot(H, V(s)) - hypot(H, V_low)) / W
    (plus stretch) instead of its cancellation-free quotient: its absolute error, a few ulps of
    T / W, is that of the positions themselves. The catenary's asinh(V(s) / H) is
    sign(V) log q, q = (|V| + hypot(H, V)) / H, and log q comes from a reference pair
    (1/q_r, log q_r) per station in ``ref`` as log q = log q_r + log1p(q / q_r - 1), by series
    when |q / q_r - 1| <= ``_SERIES_LIMIT`` and directly otherwise (an identity: any reference
    whose log is right will do):

    * ``mode`` 0 / 1: the current step, whose stations are all on the suspended part; its
      (1/q, log q) replace the reference. Mode 0 evaluates every log directly, mode 1 chains
      them from the reference left by the previous step (at its stations, close to these);
    * ``mode`` 2: an earlier step, against the current one's reference, in a branch-free loop
      that the compiler vectorises, then exact fix-ups of the stations that rest on the seabed
      at that step or are too far from the reference.

    ``sc[0]`` is scratch (the series arguments). Inlined (numba ``inline="always"``), and without
    array views: a call with a dozen array arguments, or a view's reference counting, costs as
    much as a short profile. The station index comes as floats (``jf``): AVX2 has no packed
    conversion of the int64 loop index, which would stop the vectorisation.

    Returns
    -------
    tuple
        (lx, ly, lz, ux, uy): the lower end, and the horizontal unit vector from it to the
        upper end; the global position is (lx + x ux, ly + x uy, lz + z).
    """
    L = prm[Q_L]
    EA = prm[Q_EA]
    W = prm[Q_W]
    CB = prm[Q_CB]
    n = jf.shape[0]
    # the vertical plane (as _plane_setup, for a solved, hence valid, geometry)
    swapped = fz < anchor[2]
    if swapped:
        lx, ly, lz = fx, fy, fz
        dx, dy = anchor[0] - lx, anchor[1] - ly
    else:
        lx, ly, lz = anchor[0], anchor[1], anchor[2]
        dx, dy = fx - lx, fy - ly
    XF = math.sqrt(dx * dx + dy * dy)
    inv_XF = 1.0 / XF if XF > 0.0 else 0.0
    ux = dx * inv_XF if XF > 0.0 else 1.0
    uy = dy * inv_XF
    # arc length of station i from this line's lower end: A + B i
    A = L - s0 if swapped else s0
    B = -ds if swapped else ds
    if not (H > 0.0):  # slack or vertical profile: the general point evaluator
        seabed = 1 if abs(lz - prm[Q_ZB]) <= SEABED_CONTACT_TOL * L else 0
        for i in range(n):
            xi, zi, T = _profile_point(A + B * jf[i], XF, L, EA, W, CB, seabed, H, V)
            x[row, i] = xi
            z[row, i] = zi
            if mode != 2:
                ref[0, i] = 1.0
                ref[1, i] = 0.0
        return lx, ly, lz, ux, uy
    inv_H = 1.0 / H
    inv_W = prm[Q_INV_W]
    inv_EA = prm[Q_INV_EA]
    a = H * inv_W
    # the suspended part starts at s_low (touchdown point or lower end) with tension
    # (H, V_low): V(s) = V_low + W (s - s_low)
    if LB > 0.0:
        s_low = LB
        V_low = 0.0
        h_low = H
        base = s_low + _seabed_stretch(H, s_low, EA, W, CB)[0]
    else:
        s_low = 0.0
        V_low = V - W * L
        h_low = math.sqrt(H * H + V_low * V_low)
        base = -a * math.asinh(V_low * inv_H)
    if mode == 0:
        for i in range(n):
            d = A + B * jf[i] - s_low
            Vs = V_low + W * d
            hs = math.sqrt(H * H + Vs * Vs)
            qi = (abs(Vs) + hs) * inv_H
            li = math.log(qi)
            ref[0, i] = 1.0 / qi
            ref[1, i] = li
            x[row, i] = base + a * (li if Vs >= 0.0 else -li) + H * d * inv_EA
            z[row, i] = (hs - h_low) * inv_W + 0.5 * (V_low + Vs) * d * inv_EA
        return lx, ly, lz, ux, uy
    for i in range(n):  # every station as suspended, log by the series (vectorised)
        d = A + B * jf[i] - s_low
        Vs = V_low + W * d
        hs = math.sqrt(H * H + Vs * Vs)
        qi = (abs(Vs) + hs) * inv_H
        ei = qi * ref[0, i] - 1.0
        li = ref[1, i] + _log1p_small(ei)
        x[row, i] = base + a * (li if Vs >= 0.0 else -li) + H * d * inv_EA
        z[row, i] = (hs - h_low) * inv_W + 0.5 * (V_low + Vs) * d * inv_EA
        sc[0, i] = ei
        if mode == 1:
            ref[0, i] = 1.0 / qi
            ref[1, i] = li
    fr = CB * W * s_low
    for i in range(n):  # fix-ups (a separate loop: a count of them in the one above, or any
        # reduction, would stop its vectorisation and cost twice as much)
        sig = A + B * jf[i]
        d = sig - s_low
        if d < 0.0 and mode == 2:  # resting on the seabed at this step (friction)
            if fr <= H:
                x[row, i] = sig + ((H - fr) * sig + 0.5 * CB * W * sig * sig) * inv_EA
            else:
                xB = s_low - H / (CB * W)
                x[row, i] = sig if sig <= xB else \
                    sig + 0.5 * CB * W * (sig - xB) * (sig - xB) * inv_EA
            z[row, i] = 0.0
        elif not (abs(sc[0, i]) <= _SERIES_LIMIT):
            Vs = V_low + W * d
            li = math.log((abs(Vs) + math.sqrt(H * H + Vs * Vs)) * inv_H)
            x[row, i] = base + a * (li if Vs >= 0.0 else -li) + H * d * inv_EA
            if mode == 1:
                ref[1, i] = li
    return lx, ly, lz, ux, uy


@jit(error_model="numpy")
def qd_step(anchor: np.ndarray, fairlead: np.ndarray, dt: float, prm: np.ndarray,
            hist: np.ndarray, cur: np.ndarray, chain: np.ndarray, x: np.ndarray, z: np.ndarray,
            scratch: np.ndarray, jf: np.ndarray, work: np.ndarray) -> int:
    """One quasi-dynamic step to the fairlead position ``fairlead``, ``dt`` after the last.

    Parameters
    ----------
    anchor, fairlead : float64[3]
        End positions [m].
    dt : float
        Time since the last step [s], > 0.
    prm : float64[N_QPRM]
        Parameters (``Q_*``).
    hist : float64[2, N_HIST]
        The static solutions of the last two steps (updated).
    cur : float64[N_CUR]
        Outputs of the last step (``C_*``), overwritten with this step's.
    chain : float64[2, N]
        1/q and log q of the N stations of the last step (the reference of the logs; any pair
        with log q right is valid, e.g. (1, 0)), overwritten with this step's.
    x, z : float64[3, N]
        Scratch: station positions in the planes of steps n, n-1, n-2 [m].
    scratch : float64[2, N]
        Scratch: series arguments, force densities.
    jf : float64[N]
        The station indices 0.0, 1.0, ..., N - 1 (constant).
    work : float64[N_OUT_3D]
        Output of the catenary solve of this step.

    Returns
    -------
    int
        ``CAT_OK``, or the catenary's failure status (the state is then unchanged).
    """
    L = prm[Q_L]
    W = prm[Q_W]
    CB = prm[Q_CB]
    status = catenary_solve_3d(anchor, fairlead, L, prm[Q_EA], W, CB, prm[Q_ZB],
                               hist[0, H_HF], hist[0, H_VF], prm[Q_TOL], int(prm[Q_MAXIT]), work)
    if status != CAT_OK:
        return status
    H = work[I3_HF]
    V = work[I3_VF]
    LB = work[I3_LB]
    swapped = work[I3_SWAPPED] != 0.0
    n = chain.shape[1]
    Ls = L - LB
    k = 1.0
    if not (Ls > 0.0):  # the whole line rests on the seabed: no suspended part, k_QD = 1
        ux, uy = _plane_setup(anchor, fairlead, L, prm[Q_ZB])[5:7]
    else:
        # stations sigma_j = L_B + h j from the lower end; s0 + ds j from the anchor
        h = Ls / (n - 1)
        s0 = L - LB if swapped else LB
        ds = -h if swapped else h
        # the logs of this step: directly every CHAIN_STEPS steps, else chained
        mode = 0 if cur[C_CHAIN] >= CHAIN_STEPS else 1
        cur[C_CHAIN] = 0.0 if mode == 0 else cur[C_CHAIN] + 1.0
        lx, ly, lz, ux, uy = _level_xz(anchor, fairlead[0], fairlead[1], fairlead[2], prm, H,
                                       V, LB, s0, ds, jf, mode, chain, scratch, x, z, 0)
        lx1, ly1, lz1, ux1, uy1 = _level_xz(anchor, hist[0, 0], hist[0, 1], hist[0, 2], prm,
                                            hist[0, H_HF], hist[0, H_VF], hist[0, H_LB], s0,
                                            ds, jf, 2, chain, scratch, x, z, 1)
        lx2, ly2, lz2, ux2, uy2 = _level_xz(anchor, hist[1, 0], hist[1, 1], hist[1, 2], prm,
                                            hist[1, H_HF], hist[1, H_VF], hist[1, H_LB], s0,
                                            ds, jf, 2, chain, scratch, x, z, 2)
        dtp = cur[C_DT]
        rest = not (dtp > 0.0)
        # inverses of the step lengths: the same quotients to an ulp, without divisions
        inv_dt = 1.0 / dt
        inv_dtp = 0.0 if rest else 1.0 / dtp
        inv_den = inv_dt if rest else 2.0 / (dt + dtp)
        V0 = V - W * Ls  # V(sigma) = V0 + W h j at the stations
        Wh = W * h
        m = prm[Q_M]
        drag = prm[Q_DRAG]
        ma = prm[Q_MA]
        for j in range(n):  # branch-free: vectorised
            # eq. (4): backward differences of the material point's static positions
            d01x = (lx - lx1) + x[0, j] * ux - x[1, j] * ux1
            d01y = (ly - ly1) + x[0, j] * uy - x[1, j] * uy1
            d01z = (lz - lz1) + z[0, j] - z[1, j]
            d12x = (lx1 - lx2) + x[1, j] * ux1 - x[2, j] * ux2
            d12y = (ly1 - ly2) + x[1, j] * uy1 - x[2, j] * uy2
            d12z = (lz1 - lz2) + z[1, j] - z[2, j]
            v0 = d01x * inv_dt
            v1 = d01y * inv_dt
            v2 = d01z * inv_dt
            a0 = (v0 - d12x * inv_dtp) * inv_den
            a1 = (v1 - d12y * inv_dtp) * inv_den
            a2 = (v2 - d12z * inv_dtp) * inv_den
            # static unit tangent (H u, V(sigma)) / T, V(sigma) = V - W (L - sigma)
            Vs = V0 + Wh * jf[j]
            hs = math.sqrt(H * H + Vs * Vs)
            inv_hs = 1.0 / hs if hs > 0.0 else 0.0
            t0 = H * ux * inv_hs
            t1 = H * uy * inv_hs
            t2 = Vs * inv_hs if hs > 0.0 else 1.0
            vt = v0 * t0 + v1 * t1 + v2 * t2
            n0 = v0 - vt * t0
            n1 = v1 - vt * t1
            n2 = v2 - vt * t2
            vn = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
            at = a0 * t0 + a1 * t1 + a2 * t2
            # eq. (3), vertical: weight + drag + added mass - inertia
            scratch[1, j] = -W - drag * vn * n2 - ma * (a2 - at * t2) - m * a2
        # eq. (2): composite Simpson over the suspended length (weights 1 4 2 ... 2 4 1)
        total = scratch[1, 0] + scratch[1, n - 1]
        for j in range(1, n - 1, 2):
            total += 4.0 * scratch[1, j]
        for j in range(2, n - 1, 2):
            total += 2.0 * scratch[1, j]
        k = total * h / (-3.0 * W * Ls)
        if k < 0.0:  # slack
            k = 0.0
    # eq. (1) at the upper end; the apparent-weight catenary at the lower end
    up = I3_ANCHOR_FORCE if swapped else I3_FAIRLEAD_FORCE
    low = I3_FAIRLEAD_FORCE if swapped else I3_ANCHOR_FORCE
    c_up = C_ANCHOR_FORCE if swapped else C_FAIRLEAD_FORCE
    c_low = C_FAIRLEAD_FORCE if swapped else C_ANCHOR_FORCE
    for c in range(3):
        cur[c_up + c] = k * work[up + c]
    if LB > 0.0:
        ha = max(k * H - CB * W * LB, 0.0)
        cur[c_low] = ha * ux
        cur[c_low + 1] = ha * uy
        cur[c_low + 2] = 0.0
    else:
        for c in range(3):
            cur[c_low + c] = k * work[low + c]
    cur[C_K] = k
    cur[C_LB] = LB
    cur[C_DT] = dt
    for c in range(N_HIST):
        hist[1, c] = hist[0, c]
    for c in range(3):
        hist[0, H_FAIRLEAD + c] = fairlead[c]
    hist[0, H_HF] = H
    hist[0, H_VF] = V
    hist[0, H_LB] = LB
    return CAT_OK


@jit(error_model="numpy")
def quasi_dynamic_series(anchor: np.ndarray, t_now: float, p_now: np.ndarray, v_now: np.ndarray,
                         time: np.ndarray, path: np.ndarray, velocity: np.ndarray,
                         prm: np.ndarray, hist: np.ndarray, cur: np.ndarray, chain: np.ndarray,
                         x: np.ndarray, z: np.ndarray, scratch: np.ndarray, jf: np.ndarray,
                         work: np.ndarray, fpos: np.ndarray, fvel: np.ndarray,
                         fairlead_force: np.ndarray, anchor_force: np.ndarray,
                         laid_length: np.ndarray, iterations: np.ndarray, factor: np.ndarray,
                         failure: np.ndarray) -> int:
    """Quasi-dynamic steps along a fairlead path, from the current state.

    Parameters
    ----------
    anchor : float64[3]
        Anchor position [m].
    t_now : float
        Time of the current state [s].
    p_now, v_now : float64[3]
        Fairlead position [m] and velocity [m/s] of the current state.
    time : float64[n]
        Sample times [s], increasing from ``time[0] >= t_now``; a sample at ``t_now`` is the
        current state.
    path, velocity : float64[n, 3]
        Fairlead positions [m] and velocities [m/s] at the samples.
    prm, hist, cur, chain, x, z, scratch, jf, work
        As :func:`qd_step`.
    fpos, fvel : float64[3]
        Scratch for the fairlead inside a sample interval.
    fairlead_force, anchor_force : float64[n, 3]
        Forces exerted by the line on its fairlead and anchor [N] (written).
    laid_length, iterations, factor : float64[n]
        Laid length [m], Newton iterations and k_QD per sample (written).
    failure : int64[2]
        Written on failure: (sample index, catenary status).

    Returns
    -------
    int
        -1 if every sample was solved, else the index of the first failure.

    Notes
    -----
    Each sample interval takes one step, or with ``prm[Q_MAXDT] > 0`` the fewest equal steps
    no longer than it, the fairlead moving on the cubic Hermite curve of its positions and
    velocities at both ends (as the dynamic model's fairlead does).
    """
    n = time.shape[0]
    max_dt = prm[Q_MAXDT]
    for k in range(n):
        iters = 0.0
        t0 = time[k - 1] if k > 0 else t_now
        span = time[k] - t0
        if span > 0.0:
            m = 1
            if max_dt > 0.0 and span > max_dt:
                m = int(math.ceil(span / max_dt * (1.0 - 1e-12)))
            dt = span / m
            for i in range(1, m + 1):
                if i < m:
                    if k > 0:
                        hermite(t0, time[k], path[k - 1], velocity[k - 1], path[k],
                                velocity[k], t0 + i * dt, fpos, fvel)
                    else:
                        hermite(t0, time[k], p_now, v_now, path[k], velocity[k], t0 + i * dt,
                                fpos, fvel)
                    status = qd_step(anchor, fpos, dt, prm, hist, cur, chain, x, z, scratch,
                                     jf, work)
                else:
                    status = qd_step(anchor, path[k], dt, prm, hist, cur, chain, x, z,
                                     scratch, jf, work)
                if status != CAT_OK:
                    failure[0] = k
                    failure[1] = status
                    return k
                iters += work[I3_ITER]
        for c in range(3):
            fairlead_force[k, c] = cur[C_FAIRLEAD_FORCE + c]
            anchor_force[k, c] = cur[C_ANCHOR_FORCE + c]
        laid_length[k] = cur[C_LB]
        iterations[k] = iters
        factor[k] = cur[C_K]
    return -1
