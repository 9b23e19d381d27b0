"""Numba kernels of the quasi-dynamic line model (quasi-dynamic paper section 3; docs/theory/quasi_dynamic.md).

The line carries fixed stations ("nodes") at unstretched arc lengths s_j = L - j h from the
anchor, j = 0 .. M - 1, spaced h apart from the fairlead end (``Q_H``: the suspended length
at rest over ``integration_points - 1``, so that at rest the stations are the
``integration_points`` Simpson points of the suspended part). One step (:func:`qd_step`) for the
fairlead position at time t_n, a time step dt after t_{n-1}:

1. the static elastic catenary for the current fairlead position (warm-started Newton,
   :func:`~floatmoor.mooring._catenary_kernels.catenary_solve_3d`): upper-end tension (H, V),
   laid length L_B and the static end forces; this is the static tension T_S of eq. (1);
2. the suspended part [a, b] (in s: [L_B, L], or [0, L - L_B] when the fairlead is the lower
   end), and the stations inside it; the positions of those material points on this step's
   static line; their positions on the two previous steps' lines are those steps' own (kept
   in ``X``, ``Z``, a ring of three levels, in each line's vertical plane), or, for stations
   that were not evaluated then (they were resting, or not yet inside), evaluated now;
3. velocities and accelerations by the backward differences of eq. (4):
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
5. the quasi-dynamic factor of eq. (2), k_QD = int_a^b (f_w + f_HD - f_I).k ds / (-W (b - a)),
   clamped at k_QD >= 0 (slack): composite Simpson over the stations inside [a, b] that lie
   above the material points lifted off the seabed since the step before last (eq. (4)
   differences those across the kink of their history, a layer |dL_B/dt| dt wide; an even
   number of intervals, the lowest station left out if need be), and on the lower end panel,
   from the touchdown point to the lowest station used (narrower than 2 h plus the layer), the
   exact integral of the quadratic through the three lowest stations' densities: the smooth
   suspended-side density, so the rule keeps Simpson's order (observed 3.8) while the
   touchdown point moves; other end panels (the fairlead below the anchor, or fewer than three
   stations) take the trapezoidal rule with the panel end's material point;
6. eq. (1) at the upper end; the lower end gets the force of the same apparent-weight
   catenary: k_QD times the static force when no part rests on the seabed (a catenary of
   weight k_QD W has the same shape and k_QD times the forces); with a resting length L_B, the
   horizontal tension k_QD H at the touchdown point, reduced by the seabed friction C_B W L_B
   of the resting part (which does not move), floored at zero.

The current (steady) and the water line are ignored, like by the static catenary, which gives
the whole line its submerged weight: the hydrodynamic forces act along the whole suspended part.

Cost: one catenary solve and one static profile at the stations per step (the fixed stations
keep their earlier positions). The asinh term of the profile, sign(V) log q with
q = (|V| + hypot(H, V)) / H, is evaluated as log q = log q_r + log1p(q / q_r - 1) by a short
series from the same station's previous value (chained; directly every ``CHAIN_STEPS`` steps
and wherever the series does not apply): exact to round-off, and the loops over the stations
have no branches and write at most four arrays, none of which they read, so that they
vectorise; they run over whole vectors of stations with unsigned indices (contiguous vector
loads and stores, no scalar remainder: ``_vector_window``).

Everything is preallocated; the kernels allocate nothing and report failure by status.
Parameters travel in one float64 array ``prm`` indexed by the ``Q_*`` constants; the state of
the line is ``hist`` (the last two static solutions), ``cur`` (the ``C_*`` entries), ``X``
and ``Z`` (station positions on the last three static lines) and two buffers of the stations'
log references (``qa``, ``la``, ``qb``, ``lb``).

Size: one time step (:func:`qd_step`) and the private numba helpers it alone calls, with
the statement of the scheme above (this docstring, 60 lines).
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring._catenary_equations import _seabed_stretch
from floatmoor.mooring._catenary_kernels import (
    CAT_OK, I3_ANCHOR_FORCE, I3_FAIRLEAD_FORCE, I3_HF, I3_ITER, I3_LB, I3_VF,
    SEABED_CONTACT_TOL, catenary_solve_3d,
)
from floatmoor.mooring._catenary_profile import _profile_point
from floatmoor.mooring.dg._kernels import hermite

__all__ = [
    "Q_L", "Q_EA", "Q_W", "Q_CB", "Q_ZB", "Q_TOL", "Q_MAXIT", "Q_M", "Q_DRAG", "Q_MA",
    "Q_MAXDT", "Q_INV_W", "Q_INV_EA", "Q_H", "N_QPRM", "C_K", "C_FAIRLEAD_FORCE",
    "C_ANCHOR_FORCE", "C_LB", "C_DT", "C_CHAIN", "C_SLOT", "C_LO", "C_HI", "C_REF", "C_PLANE", "N_CUR",
    "H_FAIRLEAD", "H_HF", "H_VF", "H_LB", "N_HIST", "CHAIN_STEPS", "station_count",
    "qd_step", "quasi_dynamic_series",
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
Q_H = 13  #: station spacing h [m]
N_QPRM = 14

# -- layout of ``cur``: the outputs of the last step, and its bookkeeping ----------------------
C_K = 0  #: k_QD
C_FAIRLEAD_FORCE = 1  #: 3 entries [N]
C_ANCHOR_FORCE = 4  #: 3 entries [N]
C_LB = 7  #: laid length [m]
C_DT = 8  #: length of the last step [s]; 0 when the line was at rest before
C_CHAIN = 9  #: steps since the logs of the stations were last evaluated directly
C_SLOT = 10  #: level of ``X``, ``Z`` holding the last step
C_LO = 11  #: 3 entries: per level of ``X``, ``Z``, the first station evaluated (inclusive)
C_HI = 14  #: 3 entries: per level, the last station evaluated (inclusive; < C_LO: none)
C_REF = 17  #: 0: the latest log references are in (qa, la); 1: in (qb, lb)
C_PLANE = 18  #: 3 x 5 entries: per level, the vertical plane (lower end x, y, z; ux, uy)
N_CUR = 33

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
#: Stations per step of the vectorised loops' windows (8 float64: one AVX-512 vector, two
#: AVX2 ones): the windows are rounded up to a multiple of it (see ``_vector_window``).
_VECTOR_STATIONS = 8
#: Relative slack on station indices: a station within 1e-9 h of the touchdown point counts
#: as on it (the stations sit exactly on the suspended part's ends at rest).
_INDEX_SLACK = 1e-9


def station_count(L: float, h: float) -> int:
    """Number M of stations s_j = L - j h >= 0 (to round-off) on a line of length L."""
    return int(math.floor(L / h * (1.0 + _INDEX_SLACK))) + 1


@jit(error_model="numpy", inline="always")
def _log1p_small(e: float) -> float:
    """log(1 + e) for |e| <= ``_SERIES_LIMIT``: the alternating series to e^9 (Horner)."""
    return e * (1.0 - e * (0.5 - e * (1.0 / 3.0 - e * (0.25 - e * (0.2 - e * (
        1.0 / 6.0 - e * (1.0 / 7.0 - e * (0.125 - e * (1.0 / 9.0)))))))))


@jit(error_model="numpy", inline="always")
def _plane(anchor: np.ndarray, fx: float, fy: float, fz: float
           ) -> tuple[bool, float, float, float, float, float, float]:
    """The vertical plane of a static line: (swapped, lower end x, y, z, horizontal unit vector
    to the upper end x, y, horizontal span)."""
    swapped = fz < anchor[2]
    if swapped:
        lx, ly, lz = fx, fy, fz
        dx, dy = anchor[0] - lx, anchor[1] - ly
    else:
        lx, ly, lz = anchor[0], anchor[1], anchor[2]
        dx, dy = fx - lx, fy - ly
    XF = math.sqrt(dx * dx + dy * dy)
    ux = dx / XF if XF > 0.0 else 1.0
    uy = dy / XF if XF > 0.0 else 0.0
    return swapped, lx, ly, lz, ux, uy, XF


@jit(error_model="numpy")
def _material_point(anchor: np.ndarray, fx: float, fy: float, fz: float, prm: np.ndarray,
                    H: float, V: float, s: float) -> tuple[float, float, float]:
    """The material point at unstretched arc length ``s`` from the anchor on the static line of
    upper-end tension (H, V) with the fairlead at (fx, fy, fz): (x, z) in the line's vertical
    plane from its lower end, and the vertical tension component there (0 on the resting part;
    for the tangent). Any geometry: resting, suspended, slack or vertical profiles."""
    L = prm[Q_L]
    W = prm[Q_W]
    swapped, lx, ly, lz, ux, uy, XF = _plane(anchor, fx, fy, fz)
    seabed = 1 if abs(lz - prm[Q_ZB]) <= SEABED_CONTACT_TOL * L else 0
    sig = L - s if swapped else s
    x, z, _ = _profile_point(sig, XF, L, prm[Q_EA], W, prm[Q_CB], seabed, H, V)
    Vs = V - W * (L - sig)
    if seabed != 0 and V < W * L and Vs < 0.0:
        Vs = 0.0  # on the resting part
    return x, z, Vs


@jit(error_model="numpy", inline="always")
def _vertical_force(d01x: float, d01y: float, d01z: float, d12x: float, d12y: float,
                    d12z: float, tx: float, ty: float, tz: float, inv_dt: float, inv_dtp: float,
                    inv_den: float, W: float, m: float, drag: float, ma: float) -> float:
    """Eq. (3), vertical: weight + Morison drag + added mass - inertia per unstretched length,
    from the displacements r_n - r_{n-1} (d01) and r_{n-1} - r_{n-2} (d12) of a material point
    (eq. (4)) and the static tangent (tx, ty, tz), unnormalised (its squared length divides the
    projections)."""
    v0 = d01x * inv_dt
    v1 = d01y * inv_dt
    v2 = d01z * inv_dt
    a0 = (v0 - d12x * inv_dtp) * inv_den
    a1 = (v1 - d12y * inv_dtp) * inv_den
    a2 = (v2 - d12z * inv_dtp) * inv_den
    inv_tt = 1.0 / max(tx * tx + ty * ty + tz * tz, 1e-300)
    vt = (v0 * tx + v1 * ty + v2 * tz) * inv_tt
    n0 = v0 - vt * tx
    n1 = v1 - vt * ty
    n2 = v2 - vt * tz
    vn = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    at = (a0 * tx + a1 * ty + a2 * tz) * inv_tt
    return -W - drag * vn * n2 - ma * (a2 - at * tz) - m * a2


@jit(error_model="numpy", inline="always")
def _ensure_level(anchor: np.ndarray, prm: np.ndarray, hist: np.ndarray, row: int,
                  cur: np.ndarray, slot: int, X: np.ndarray, Z: np.ndarray, lo: int,
                  hi: int) -> None:
    """Make stations lo..hi of level ``slot`` (the static line of ``hist[row]``) available:
    those outside its evaluated range are evaluated now, and the range grows to cover them
    (gaps filled, so that it stays contiguous)."""
    L = prm[Q_L]
    h = prm[Q_H]
    have_lo = int(cur[C_LO + slot])
    have_hi = int(cur[C_HI + slot])
    if have_hi < have_lo:  # nothing evaluated at this level yet
        have_lo = hi + 1
        have_hi = hi
    fx, fy, fz = hist[row, 0], hist[row, 1], hist[row, 2]
    H, V = hist[row, H_HF], hist[row, H_VF]
    for j in range(lo, have_lo):
        X[slot, j], Z[slot, j], _ = _material_point(anchor, fx, fy, fz, prm, H, V, L - j * h)
    for j in range(have_hi + 1, hi + 1):
        X[slot, j], Z[slot, j], _ = _material_point(anchor, fx, fy, fz, prm, H, V, L - j * h)
    cur[C_LO + slot] = min(lo, have_lo)
    cur[C_HI + slot] = max(hi, have_hi)


@jit(error_model="numpy", inline="always")
def _vector_window(j_top: int, j_bot: int, M: int) -> tuple[np.uint64, np.uint64]:
    """Bounds of ``range`` for the vectorised loops over the stations j_top..j_bot
    (0 <= j_top; empty if j_bot < j_top): the window is widened below to a whole number of
    ``_VECTOR_STATIONS`` where the M stations allow it, and the bounds are unsigned.

    The stations added below j_bot (resting, or in the lift-off layer) are evaluated like the
    others and their results left unused: their positions stay outside the evaluated range
    of their level and their log references stay valid pairs; this spares the scalar
    remainder loop, which for ~30 stations costs as much as the vector part. Unsigned
    indices: numba wraps a negative signed index around (j + n), a select the compiler
    cannot drop here (it cannot prove j_top >= 0), so it vectorises with gathers and
    scatters, which costs about twice as much; unsigned indices load and store contiguous
    vectors."""
    if j_bot < j_top:
        return np.uint64(j_top), np.uint64(j_top)
    n = (j_bot - j_top + _VECTOR_STATIONS) // _VECTOR_STATIONS * _VECTOR_STATIONS
    return np.uint64(j_top), np.uint64(min(j_top + n, M))


@jit(error_model="numpy", inline="always")
def _station_profile(X: np.ndarray, Z: np.ndarray, s0: int, q_ref: np.ndarray, l_ref: np.ndarray,
                     q_new: np.ndarray, l_new: np.ndarray, jf: np.ndarray, j_top: int,
                     j_bot: int, refresh: bool, H: float, V: float, W: float, h: float,
                     Ls: float, base: float, aa: float, inv_H: float, inv_W: float,
                     inv_EA: float, V_low: float, h_low: float) -> None:
    """This step's in-plane positions of the suspended stations j_top..j_bot (H > 0, fairlead
    above the anchor) into ``X[s0]``, ``Z[s0]``, and their new log references; the asinh term
    by the series from the references (directly when ``refresh`` or too far from them)."""
    u_top, u_end = _vector_window(j_top, j_bot, jf.shape[0])
    if refresh:  # renew the references: every log directly
        for j in range(u_top, u_end):
            Vs = V - W * h * jf[j]
            qi = (abs(Vs) + math.sqrt(H * H + Vs * Vs)) * inv_H
            q_ref[j] = qi
            l_ref[j] = math.log(qi)
    for j in range(u_top, u_end):  # vectorised
        Vs = V - W * h * jf[j]  # V(sigma) = V - W (L - sigma), L - sigma = j h
        d = Ls - h * jf[j]  # sigma - s_low
        hs = math.sqrt(H * H + Vs * Vs)
        qi = (abs(Vs) + hs) * inv_H
        li = l_ref[j] + _log1p_small(qi / q_ref[j] - 1.0)
        X[s0, j] = base + aa * (li if Vs >= 0.0 else -li) + H * d * inv_EA
        Z[s0, j] = (hs - h_low) * inv_W + 0.5 * (V_low + Vs) * d * inv_EA
        q_new[j] = qi
        l_new[j] = li
    far = False  # |q / q_ref - 1| beyond the series' limit (or not finite)?
    for j in range(u_top, u_end):
        far = far or not (abs(q_new[j] - q_ref[j]) <= _SERIES_LIMIT * q_ref[j])
    if far:  # those stations: direct logs
        for j in range(u_top, u_end):
            if not (abs(q_new[j] - q_ref[j]) <= _SERIES_LIMIT * q_ref[j]):
                Vs = V - W * h * jf[j]
                d = Ls - h * jf[j]
                li = math.log(q_new[j])
                X[s0, j] = base + aa * (li if Vs >= 0.0 else -li) + H * d * inv_EA
                l_new[j] = li


@jit(error_model="numpy")
def _density_at(anchor: np.ndarray, fairlead: np.ndarray, prm: np.ndarray, hist: np.ndarray,
                H: float, V: float, se: float, inv_dt: float, inv_dtp: float,
                inv_den: float) -> float:
    """Eq. (3) at the material point at arc length ``se`` from the anchor, its positions on
    the three steps' static lines evaluated here."""
    fx, fy, fz = fairlead[0], fairlead[1], fairlead[2]
    x0, z0, Vs = _material_point(anchor, fx, fy, fz, prm, H, V, se)
    x1, z1, _ = _material_point(anchor, hist[0, 0], hist[0, 1], hist[0, 2], prm,
                                hist[0, H_HF], hist[0, H_VF], se)
    x2, z2, _ = _material_point(anchor, hist[1, 0], hist[1, 1], hist[1, 2], prm,
                                hist[1, H_HF], hist[1, H_VF], se)
    _, l0x, l0y, l0z, u0x, u0y, _ = _plane(anchor, fx, fy, fz)
    _, l1x, l1y, l1z, u1x, u1y, _ = _plane(anchor, hist[0, 0], hist[0, 1], hist[0, 2])
    _, l2x, l2y, l2z, u2x, u2y, _ = _plane(anchor, hist[1, 0], hist[1, 1], hist[1, 2])
    return _vertical_force((l0x + x0 * u0x) - (l1x + x1 * u1x), (l0y + x0 * u0y)
                           - (l1y + x1 * u1y), (l0z + z0) - (l1z + z1),
                           (l1x + x1 * u1x) - (l2x + x2 * u2x), (l1y + x1 * u1y)
                           - (l2y + x2 * u2y), (l1z + z1) - (l2z + z2),
                           H * u0x, H * u0y, Vs, inv_dt, inv_dtp, inv_den,
                           prm[Q_W], prm[Q_M], prm[Q_DRAG], prm[Q_MA])


@jit(error_model="numpy")
def _end_panels(anchor: np.ndarray, fairlead: np.ndarray, prm: np.ndarray, hist: np.ndarray,
                H: float, V: float, a: float, b: float, j_top: int, j_bot: int, n_grid: int,
                lower_done: bool, F: np.ndarray, inv_dt: float, inv_dtp: float,
                inv_den: float) -> float:
    """Integral of the vertical force density over the end panels of the suspended part
    [a, b]: the trapezoidal rule on [a, s_bot] (unless ``lower_done``) and [s_top, b]
    (stations j_bot and j_top, whose densities are in ``F``; panels narrower than 2e-9 h are
    dropped), or Simpson on [a, (a + b) / 2, b] when no station lies inside."""
    L = prm[Q_L]
    h = prm[Q_H]
    if n_grid == 0:
        fa = _density_at(anchor, fairlead, prm, hist, H, V, a, inv_dt, inv_dtp, inv_den)
        fm = _density_at(anchor, fairlead, prm, hist, H, V, 0.5 * (a + b), inv_dt, inv_dtp,
                         inv_den)
        fb = _density_at(anchor, fairlead, prm, hist, H, V, b, inv_dt, inv_dtp, inv_den)
        return (fa + 4.0 * fm + fb) * (b - a) / 6.0
    tiny = 2.0 * _INDEX_SLACK * h
    total = 0.0
    wl = (L - j_bot * h) - a
    if wl > tiny and not lower_done:
        fa = _density_at(anchor, fairlead, prm, hist, H, V, a, inv_dt, inv_dtp, inv_den)
        total += 0.5 * (fa + F[j_bot]) * wl
    wu = b - (L - j_top * h)
    if wu > tiny:
        fb = _density_at(anchor, fairlead, prm, hist, H, V, b, inv_dt, inv_dtp, inv_den)
        total += 0.5 * (fb + F[j_top]) * wu
    return total


@jit(error_model="numpy")
def qd_step(anchor: np.ndarray, fairlead: np.ndarray, dt: float, prm: np.ndarray,
            hist: np.ndarray, cur: np.ndarray, X: np.ndarray, Z: np.ndarray, qa: np.ndarray,
            la: np.ndarray, qb: np.ndarray, lb: np.ndarray, F: np.ndarray, jf: np.ndarray,
            work: np.ndarray) -> int:
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
        Outputs and bookkeeping of the last step (``C_*``), overwritten with this step's.
    X, Z : float64[3, M]
        Positions of the M stations in the vertical plane of the static lines of the last
        three steps, from their lower ends (a ring of levels: ``cur[C_SLOT]`` is the last
        step's, ``cur[C_LO/C_HI + level]`` the stations evaluated there).
    qa, la, qb, lb : float64[M]
        Two buffers of q and log q per station (the references of the logs; any pair with
        log q right is valid, e.g. (1, 0)); ``cur[C_REF]`` tells which holds the latest.
    F : float64[M]
        Scratch: force densities.
    jf : float64[M]
        The station indices 0.0, 1.0, ..., M - 1 (constant).
    work : float64[N_OUT_3D]
        Output of the catenary solve of this step.

    Returns
    -------
    int
        ``CAT_OK``, or the catenary's failure status (the state is then unchanged).

    Notes
    -----
    The hot loops write at most four arrays and none they read: the compiler then vectorises
    them (with updates in place it does not, and the step costs about twice as much).
    """
    L = prm[Q_L]
    W = prm[Q_W]
    CB = prm[Q_CB]
    h = prm[Q_H]
    status = catenary_solve_3d(anchor, fairlead, L, prm[Q_EA], W, CB, prm[Q_ZB],
                               hist[0, H_HF], hist[0, H_VF], prm[Q_TOL], int(prm[Q_MAXIT]), work)
    if status != CAT_OK:
        return status
    H = work[I3_HF]
    V = work[I3_VF]
    LB = work[I3_LB]
    M = jf.shape[0]
    last = int(cur[C_SLOT])
    s0 = (last + 1) % 3  # this step's level
    s1 = last  # the last step's
    s2 = (last + 2) % 3  # the one before
    cur[C_LO + s0] = 1.0  # nothing evaluated at this level yet
    cur[C_HI + s0] = 0.0
    fx, fy, fz = fairlead[0], fairlead[1], fairlead[2]
    swapped, lx, ly, lz, ux, uy, _ = _plane(anchor, fx, fy, fz)
    Ls = L - LB
    k = 1.0
    if Ls > 0.0:
        # the suspended part [a, b] in arc length from the anchor
        a = 0.0 if swapped else LB
        b = Ls if swapped else L
        # material points that lifted off the seabed since the step before last (between
        # this touchdown point and the highest of the last two) were accelerated by eq. (4)
        # across the kink of their history: the stations keep above that layer
        lift = a if swapped else max(a, hist[0, H_LB], hist[1, H_LB])
        j_top = max(int(math.ceil((L - b) / h - _INDEX_SLACK)), 0)
        j_bot = min(int(math.floor((L - lift) / h + _INDEX_SLACK)), M - 1)
        if j_bot > j_top and (j_bot - j_top) % 2 == 1:
            j_bot -= 1  # an even number of Simpson intervals; the rest joins the end panel
        n_grid = j_bot - j_top + 1 if j_bot >= j_top else 0
        # -- this step's static positions of the stations j_top..j_bot ----------------------
        if n_grid > 0 and H > 0.0 and not swapped:
            inv_H = 1.0 / H
            inv_W = prm[Q_INV_W]
            inv_EA = prm[Q_INV_EA]
            aa = H * inv_W
            if LB > 0.0:
                V_low = 0.0
                h_low = H
                base = LB + _seabed_stretch(H, LB, prm[Q_EA], W, CB)[0]
            else:
                V_low = V - W * L
                h_low = math.sqrt(H * H + V_low * V_low)
                base = -aa * math.asinh(V_low * inv_H)
            # references: the latest buffer in, the other out (two calls rather than a
            # tuple of arrays: no reference counting of array views in the step)
            new_in_b = cur[C_REF] == 0.0
            refresh = cur[C_CHAIN] >= CHAIN_STEPS
            cur[C_CHAIN] = 0.0 if refresh else cur[C_CHAIN] + 1.0
            if new_in_b:
                _station_profile(X, Z, s0, qa, la, qb, lb, jf, j_top, j_bot, refresh, H, V, W,
                                 h, Ls, base, aa, inv_H, inv_W, inv_EA, V_low, h_low)
            else:
                _station_profile(X, Z, s0, qb, lb, qa, la, jf, j_top, j_bot, refresh, H, V, W,
                                 h, Ls, base, aa, inv_H, inv_W, inv_EA, V_low, h_low)
            cur[C_REF] = 1.0 if new_in_b else 0.0
        else:  # slack or vertical profiles, or the fairlead below the anchor: general points
            for j in range(j_top, j_bot + 1):
                X[s0, j], Z[s0, j], _ = _material_point(anchor, fx, fy, fz, prm, H, V,
                                                        L - j * h)
        if n_grid > 0:
            cur[C_LO + s0] = j_top
            cur[C_HI + s0] = j_bot
            _ensure_level(anchor, prm, hist, 0, cur, s1, X, Z, j_top, j_bot)
            _ensure_level(anchor, prm, hist, 1, cur, s2, X, Z, j_top, j_bot)
        # -- eq. (4) and eq. (3) at the stations ---------------------------------------------
        dtp = cur[C_DT]
        rest = not (dtp > 0.0)
        # inverses of the step lengths: the same quotients to an ulp, without divisions
        inv_dt = 1.0 / dt
        inv_dtp = 0.0 if rest else 1.0 / dtp
        inv_den = inv_dt if rest else 2.0 / (dt + dtp)
        m = prm[Q_M]
        drag = prm[Q_DRAG]
        ma = prm[Q_MA]
        c1 = C_PLANE + 5 * s1  # the earlier lines' planes, kept from their steps
        c2 = C_PLANE + 5 * s2
        l1x, l1y, l1z, u1x, u1y = cur[c1], cur[c1 + 1], cur[c1 + 2], cur[c1 + 3], cur[c1 + 4]
        l2x, l2y, l2z, u2x, u2y = cur[c2], cur[c2 + 1], cur[c2 + 2], cur[c2 + 3], cur[c2 + 4]
        Hx = H * ux
        Hy = H * uy
        # V(sigma) at station j: V - W j h, or with the fairlead below, V - W (L - j h)
        Vt0 = V - W * L if swapped else V
        Vt1 = W * h if swapped else -W * h
        u_top, u_end = _vector_window(j_top, j_bot, M)
        for j in range(u_top, u_end):  # vectorised
            x0, x1, x2 = X[s0, j], X[s1, j], X[s2, j]
            z0, z1, z2 = Z[s0, j], Z[s1, j], Z[s2, j]
            F[j] = _vertical_force(
                (lx - l1x) + x0 * ux - x1 * u1x, (ly - l1y) + x0 * uy - x1 * u1y,
                (lz - l1z) + z0 - z1, (l1x - l2x) + x1 * u1x - x2 * u2x,
                (l1y - l2y) + x1 * u1y - x2 * u2y, (l1z - l2z) + z1 - z2,
                Hx, Hy, Vt0 + Vt1 * jf[j], inv_dt, inv_dtp, inv_den, W, m, drag, ma)
        # -- eq. (2): Simpson over the stations (weights 1 4 2 ... 2 4 1) --------------------
        total = 0.0
        if n_grid >= 3:
            odd = 0.0
            even = 0.0
            for j in range(j_top + 1, j_bot, 2):  # pairs (odd j, even j + 1)
                odd += F[j]
                even += F[j + 1]
            total = (F[j_top] - F[j_bot] + 4.0 * odd + 2.0 * even) * h / 3.0
        # -- the lower end panel [a, s_bot]: the quadratic through the three lowest stations
        # (the smooth suspended-side density, exact for quadratics), integrated exactly ------
        lower = n_grid >= 3
        if lower:
            w = ((L - j_bot * h) - a) / h  # panel width in stations
            if w > 2.0 * _INDEX_SLACK:
                w2 = w * w
                w3 = w2 * w
                total += h * (F[j_bot] * (w3 / 6.0 + 0.75 * w2 + w)
                              - F[j_bot - 1] * (w3 / 3.0 + w2)
                              + F[j_bot - 2] * (w3 / 6.0 + 0.25 * w2))
        # -- other end panels: the trapezoidal rule with the panel end's material point -------
        if swapped or not lower:  # (the upper end b = L is station 0 otherwise)
            total += _end_panels(anchor, fairlead, prm, hist, H, V, a, b, j_top, j_bot,
                                 n_grid, lower, F, inv_dt, inv_dtp, inv_den)
        k = total / (-W * Ls)
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
    cur[C_SLOT] = s0
    c0 = C_PLANE + 5 * s0
    cur[c0], cur[c0 + 1], cur[c0 + 2], cur[c0 + 3], cur[c0 + 4] = lx, ly, lz, ux, uy
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
                         prm: np.ndarray, hist: np.ndarray, cur: np.ndarray, X: np.ndarray,
                         Z: np.ndarray, qa: np.ndarray, la: np.ndarray, qb: np.ndarray,
                         lb: np.ndarray, F: np.ndarray, jf: np.ndarray,
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
    prm, hist, cur, X, Z, qa, la, qb, lb, F, jf, work
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
                    status = qd_step(anchor, fpos, dt, prm, hist, cur, X, Z, qa, la, qb,
                                     lb, F, jf, work)
                else:
                    status = qd_step(anchor, path[k], dt, prm, hist, cur, X, Z, qa, la,
                                     qb, lb, F, jf, work)
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
