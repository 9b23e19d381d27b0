"""The quasi-static elastic catenary with seabed contact and friction: the Python API.

A mooring line of unstretched length L hangs between an anchor and a fairlead under its own
submerged weight. Its shape and end forces follow the elastic catenary of Irvine (1981) with the
resting length and seabed friction of Jonkman (2007), as written in ``docs/theory/quasi_static.md``
(see :mod:`floatmoor.mooring._catenary_equations` for the equations and
:mod:`floatmoor.mooring._catenary_kernels` for the solver). This module wraps the compiled kernels
for use from Python: it validates shapes, raises :class:`~floatmoor.errors.SolverError` with the
reason on failure, and returns a :class:`CatenarySolution`. Time loops should call the kernels
directly.

Symbols
-------
======  ==========================================================================  ======
XF      horizontal distance from the anchor to the fairlead                         m
ZF      height of the fairlead above the anchor                                     m
L       unstretched line length                                                     m
EA      axial stiffness                                                             N
W       submerged weight per unstretched length                                     N/m
CB      seabed friction coefficient                                                 -
HF      horizontal tension at the fairlead                                          N
VF      vertical tension at the fairlead (positive when pulling the fairlead down)  N
HA      horizontal force on the anchor (towards the fairlead positive)              N
VA      vertical force on the anchor (upward positive)                              N
LB      unstretched length resting on the seabed                                    m
======  ==========================================================================  ======

References
----------
.. [1] H. M. Irvine, *Cable Structures*, MIT Press, 1981, chapter 2.
.. [2] J. M. Jonkman, *Dynamics Modeling and Loads Analysis of an Offshore Floating Wind
   Turbine*, NREL/TP-500-41958, 2007 (the FAST v7 quasi-static mooring line).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.errors import SolverError
from floatmoor.mooring import _catenary_kernels as _k
from floatmoor.mooring import _catenary_profile as _p

__all__ = [
    "DEFAULT_TOL", "DEFAULT_MAX_ITER", "STATUS_MESSAGES", "PROFILE_NAMES", "CatenarySolution",
    "solve_catenary", "catenary_profile", "describe_failure",
]

#: Convergence tolerance: |X - XF| + |Z - ZF| <= DEFAULT_TOL * L. Roundoff in the (cancellation
#: free) equations is a few 1e-16 L, so 1e-12 L is reached reliably and leaves the equations
#: holding far below the 1e-9 L of verification case 5.1.1
#: (``docs/development.md#case-511-elastic-catenary``).
DEFAULT_TOL = 1e-12
#: Newton iterations allowed per attempt (warm starts need 2 to 4, cold starts up to ~30).
DEFAULT_MAX_ITER = 100

#: One sentence per kernel status.
STATUS_MESSAGES: dict[int, str] = {
    _k.CAT_OK: "the catenary equations are satisfied to the requested tolerance",
    _k.CAT_NOT_CONVERGED: "the catenary solve did not reach the requested tolerance",
    _k.CAT_INVALID_INPUT: "invalid input: a value is not finite, or L, EA, W are not positive, "
                          "or XF, CB are negative, or the tolerance / iteration limit is invalid",
    _k.CAT_BELOW_SEABED: "an end of the line lies below the seabed",
    _k.CAT_SAG_BELOW_SEABED: "both ends are off the seabed but the suspended line sags below it "
                             "(U-shaped seabed contact is not modelled)",
}

#: Name of each kernel profile type.
PROFILE_NAMES: dict[int, str] = {
    _k.PROFILE_SUSPENDED: "suspended",
    _k.PROFILE_TAUT: "taut",
    _k.PROFILE_TOUCHDOWN: "touchdown",
    _k.PROFILE_ON_SEABED: "on_seabed",
    _k.PROFILE_SLACK: "slack",
    _k.PROFILE_VERTICAL: "vertical",
}


@dataclass(frozen=True)
class CatenarySolution:
    """Static solution of one line; forces act on the points given as fairlead and anchor.

    Attributes
    ----------
    fairlead_force
        Force the line exerts on the fairlead, global x, y, z [N]; shape (3,).
    anchor_force
        Force the line exerts on the anchor [N]; shape (3,).
    fairlead_tension, anchor_tension
        Tension magnitudes at the fairlead and the anchor [N].
    horizontal_tension
        Horizontal tension at the fairlead, HF [N].
    fairlead_vertical_tension
        Vertical tension at the fairlead, VF, positive when the line pulls it down [N].
    anchor_horizontal_tension
        Horizontal force on the anchor, HA, towards the fairlead positive [N].
    anchor_vertical_tension
        Vertical force on the anchor, VA, upward positive [N].
    laid_length
        Unstretched length resting on the seabed, LB [m].
    stiffness
        K = -d(fairlead_force)/d(fairlead position) [N/m]; shape (3, 3).
    iterations
        Newton (and fallback) iterations used.
    profile_type
        ``"suspended"``, ``"taut"`` (free, chord >= L), ``"touchdown"``, ``"on_seabed"``,
        ``"slack"`` (zero horizontal tension, part lying slack on the seabed) or
        ``"vertical"``.
    residual
        Final ``|X - XF| + |Z - ZF|`` relative to L [-].
    warm_start
        (HF, VF) of the upper end, the kernel's unknowns: pass the solution as
        ``initial_guess`` of the next solve [N].
    """

    fairlead_force: NDArray[np.float64]
    anchor_force: NDArray[np.float64]
    fairlead_tension: float
    anchor_tension: float
    horizontal_tension: float
    fairlead_vertical_tension: float
    anchor_horizontal_tension: float
    anchor_vertical_tension: float
    laid_length: float
    stiffness: NDArray[np.float64]
    iterations: int
    profile_type: str
    residual: float
    warm_start: tuple[float, float] = field(repr=False)


def _point(value: ArrayLike, name: str) -> NDArray[np.float64]:
    arr = np.array(value, dtype=np.float64)
    if arr.shape != (3,):
        raise ValueError(f"{name} must be a point (x, y, z) [m], got shape {arr.shape}")
    return arr


def _guess(initial_guess: CatenarySolution | tuple[float, float] | None) -> tuple[float, float]:
    if initial_guess is None:
        return math.nan, math.nan
    if isinstance(initial_guess, CatenarySolution):
        return initial_guess.warm_start
    h0, v0 = initial_guess
    return float(h0), float(v0)


def _readonly(arr: NDArray[np.float64]) -> NDArray[np.float64]:
    arr.setflags(write=False)
    return arr


def solve_catenary(
    anchor: ArrayLike,
    fairlead: ArrayLike,
    length: float,
    axial_stiffness: float,
    weight_per_length: float,
    friction_coefficient: float = 0.0,
    seabed_z: float = -math.inf,
    initial_guess: CatenarySolution | tuple[float, float] | None = None,
    tol: float = DEFAULT_TOL,
    max_iter: int = DEFAULT_MAX_ITER,
) -> CatenarySolution:
    """Static elastic catenary between two points, with seabed contact and friction.

    The line lies in the vertical plane through its ends. Its lower end may rest on the seabed
    (when within ``SEABED_CONTACT_TOL * length`` of ``seabed_z``); part of the line then lies
    on the seabed, with friction reducing the tension towards that end.

    Parameters
    ----------
    anchor, fairlead
        End positions, global x, y, z with z up [m]. Either may be the lower one.
    length
        Unstretched length L [m].
    axial_stiffness
        EA [N].
    weight_per_length
        Submerged weight per unstretched length W, > 0 [N/m].
    friction_coefficient
        Seabed friction coefficient CB [-].
    seabed_z
        Seabed elevation [m]; ``-inf`` (default) for a line that never touches it.
    initial_guess
        A previous solution of the same line (or its ``warm_start`` pair (HF, VF) [N]) to
        warm-start Newton; ``None`` for a cold start.
    tol
        Converged when ``|X - XF| + |Z - ZF| <= tol * L`` [-].
    max_iter
        Newton iterations per attempt.

    Returns
    -------
    CatenarySolution

    Raises
    ------
    SolverError
        With :func:`describe_failure`'s reason when there is no valid solution.
    ValueError
        When ``anchor`` or ``fairlead`` is not a 3-vector.
    """
    a = _point(anchor, "anchor")
    f = _point(fairlead, "fairlead")
    h0, v0 = _guess(initial_guess)
    out = np.empty(_k.N_OUT_3D)
    status = _k.catenary_solve_3d(
        a, f, float(length), float(axial_stiffness), float(weight_per_length),
        float(friction_coefficient), float(seabed_z), h0, v0, float(tol), int(max_iter), out,
    )
    if status != _k.CAT_OK:
        span = f - a
        reason = describe_failure(status, float(np.hypot(span[0], span[1])), float(span[2]),
                                  float(length), float(axial_stiffness),
                                  float(weight_per_length))
        raise SolverError(f"{reason} (anchor at {np.array2string(a, precision=6)} m, fairlead "
                          f"at {np.array2string(f, precision=6)} m, seabed at z = {seabed_z} m)")
    ff = out[_k.I3_FAIRLEAD_FORCE:_k.I3_FAIRLEAD_FORCE + 3].copy()
    fa = out[_k.I3_ANCHOR_FORCE:_k.I3_ANCHOR_FORCE + 3].copy()
    hf, vf, ha, va = out[_k.I3_HF], out[_k.I3_VF], out[_k.I3_HA], out[_k.I3_VA]
    if out[_k.I3_SWAPPED] != 0.0:  # the fairlead is the lower end (the kernel's end A)
        hf, vf, ha, va = ha, -va, hf, -vf
    return CatenarySolution(
        fairlead_force=_readonly(ff),
        anchor_force=_readonly(fa),
        fairlead_tension=float(np.linalg.norm(ff)),
        anchor_tension=float(np.linalg.norm(fa)),
        horizontal_tension=float(hf),
        fairlead_vertical_tension=float(vf),
        anchor_horizontal_tension=float(ha),
        anchor_vertical_tension=float(va),
        laid_length=float(out[_k.I3_LB]),
        stiffness=_readonly(out[_k.I3_STIFFNESS:_k.I3_STIFFNESS + 9].reshape(3, 3).copy()),
        iterations=int(out[_k.I3_ITER]),
        profile_type=PROFILE_NAMES[int(out[_k.I3_PROFILE])],
        residual=float(out[_k.I3_RESID]),
        warm_start=(float(out[_k.I3_HF]), float(out[_k.I3_VF])),
    )


def catenary_profile(
    anchor: ArrayLike,
    fairlead: ArrayLike,
    length: float,
    axial_stiffness: float,
    weight_per_length: float,
    friction_coefficient: float = 0.0,
    seabed_z: float = -math.inf,
    arc_lengths: ArrayLike | None = None,
    n_points: int = 21,
    solution: CatenarySolution | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Shape and effective tension of the static line.

    Parameters
    ----------
    anchor, fairlead, length, axial_stiffness, weight_per_length, friction_coefficient, seabed_z
        As :func:`solve_catenary`.
    arc_lengths
        Unstretched arc lengths from the anchor, in [0, L] [m]; default ``n_points`` evenly
        spaced.
    n_points
        Number of points when ``arc_lengths`` is not given.
    solution
        The solution for these inputs; solved here when ``None``.

    Returns
    -------
    positions : ndarray, shape (n, 3)
        Global positions of the points [m]. Where the line lies slack on the seabed its shape
        is not determined; the points are then spread evenly along the straight resting line.
    tensions : ndarray, shape (n,)
        Effective tension [N].
    """
    a = _point(anchor, "anchor")
    f = _point(fairlead, "fairlead")
    if solution is None:
        solution = solve_catenary(a, f, length, axial_stiffness, weight_per_length,
                                  friction_coefficient, seabed_z)
    if arc_lengths is None:
        s = np.linspace(0.0, float(length), int(n_points))
    else:
        s = np.ascontiguousarray(arc_lengths, dtype=np.float64).reshape(-1)
    positions = np.empty((s.size, 3))
    tensions = np.empty(s.size)
    hf, vf = solution.warm_start
    _p.catenary_profile_3d(a, f, float(length), float(axial_stiffness), float(weight_per_length),
                           float(friction_coefficient), float(seabed_z), hf, vf, s, positions,
                           tensions)
    return positions, tensions


def describe_failure(status: int, XF: float, ZF: float, L: float, EA: float, W: float) -> str:
    """Why the catenary kernel returned ``status``, with the numbers.

    Parameters
    ----------
    status
        A ``CAT_*`` code of :mod:`floatmoor.mooring._catenary_kernels`.
    XF, ZF
        Horizontal distance and height of the fairlead relative to the anchor [m].
    L, EA, W
        Unstretched length [m], axial stiffness [N], submerged weight per length [N/m].

    Returns
    -------
    str
        One sentence, naming the offending quantities.
    """
    values = (f"XF = {XF:.6g} m, ZF = {ZF:.6g} m, L = {L:.6g} m, EA = {EA:.6g} N, "
              f"W = {W:.6g} N/m")
    if status == _k.CAT_OK:
        return f"{STATUS_MESSAGES[status]} ({values})"
    if status == _k.CAT_INVALID_INPUT:
        named = {"XF": XF, "ZF": ZF, "L": L, "EA": EA, "W": W}
        bad = [f"{k} = {v!r} is not finite" for k, v in named.items() if not math.isfinite(v)]
        if math.isfinite(XF) and XF < 0.0:
            bad.append(f"XF = {XF:.6g} m is negative")
        if math.isfinite(L) and L <= 0.0:
            bad.append(f"the length L = {L:.6g} m is not positive")
        if math.isfinite(EA) and EA <= 0.0:
            bad.append(f"the axial stiffness EA = {EA:.6g} N is not positive")
        if math.isfinite(W) and W <= 0.0:
            bad.append(f"the submerged weight W = {W:.6g} N/m is not positive (buoyant or "
                       "neutrally buoyant lines are not supported by the catenary)")
        if not bad:
            bad.append("a position is not finite, or the friction coefficient is negative, or "
                       f"the tolerance is not positive, or the iteration limit is below 1 "
                       f"({values})")
        return "invalid catenary input: " + "; ".join(bad)
    if status == _k.CAT_BELOW_SEABED:
        where = (f"the fairlead lies {-ZF:.6g} m below the anchor" if ZF < 0.0
                 else "an end lies below the seabed")
        return (f"{where}, beyond the contact tolerance of {_k.SEABED_CONTACT_TOL:g} L = "
                f"{_k.SEABED_CONTACT_TOL * L:.3g} m: the seabed cannot be penetrated "
                f"({values})")
    if status == _k.CAT_SAG_BELOW_SEABED:
        return f"{STATUS_MESSAGES[status]} ({values})"
    if status == _k.CAT_NOT_CONVERGED:
        chord = math.hypot(XF, ZF)
        ratio = chord / L if L > 0.0 else math.inf
        hint = ""
        if ratio > 1.0:
            hint = (f"; the line is stretched to chord/L = {ratio:.6g}, a mean strain of "
                    f"{ratio - 1.0:.3g} (tension about {(ratio - 1.0) * EA:.3g} N)")
        return (f"the elastic catenary did not converge to the tolerance "
                f"(chord/L = {ratio:.6g}{hint}; {values})")
    return f"unknown catenary status {status} ({values})"
