"""Prescribed fairlead motion: the translational motions of one fairlead (circular, harmonic,
table), with the ramp and the table spline every prescribed motion shares.

The fairlead position is the mean position given in the case plus a displacement
``R(t) d(t)``, where ``d`` is the motion (circular, harmonic or tabulated) and ``R`` the ramp
``R(t) = (1 - cos(pi t / t_r)) / 2`` for ``t < t_r``, 1 after. The ramp has zero slope at both
ends, so the velocity is continuous when the motion starts and when it reaches full amplitude.

A table is interpolated by the not-a-knot cubic spline through its rows, column by column
(:func:`table_state`), and the velocity is the spline's exact derivative: position, velocity
and acceleration are continuous at the rows, so a line model that differentiates the fairlead
path (the quasi-dynamic line's backward differences, the dynamic line's boundary velocity) sees
no jump there. Why this spline and not a linear or a monotone (PCHIP) interpolant:
docs/theory/mooring_systems.md#prescribed-motion-of-the-body-points.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import CircularMotion, HarmonicMotion, Line, Motion, TableMotion

__all__ = ["ramp", "ramp_rate", "harmonic_state", "ramped", "horizontal_direction", "motion_state", "displacement",
           "fairlead_path", "fairlead_state", "table_state"]

#: Tables whose spline coefficients are kept (:func:`table_state`): a run evaluates its table
#: once per chunk of samples and line, and building the spline of a long record (0.24 s for
#: 1e5 rows of 6 columns) must not repeat per chunk.
_SPLINE_CACHE_SIZE = 8
_SPLINES: dict[tuple[int, int], tuple[NDArray[np.float64], NDArray[np.float64],
                                      NDArray[np.float64]]] = {}


def _spline_coefficients(time: NDArray[np.float64], values: NDArray[np.float64]
                         ) -> NDArray[np.float64]:
    """Per-segment polynomial coefficients (4, rows - 1, columns) of the not-a-knot cubic
    spline of each column, highest power first, in the time since the segment's first row."""
    key = (id(time), id(values))
    hit = _SPLINES.get(key)
    # the cache holds the arrays themselves, so their ids cannot be reused while they are in
    # it; a case's arrays are never changed in place (a changed table is a new motion)
    if hit is not None and hit[0] is time and hit[1] is values:
        return hit[2]
    # here, not at import: scipy.interpolate (0.6 s to import) is needed by tables only, not
    # by the quick start's circular motion (docs/validation/performance.md#first-run)
    from scipy.interpolate import CubicSpline

    # one column at a time, so that a column's numbers do not depend on the others (a body
    # table without rotations gives a line table's path bit for bit)
    coefficients = np.empty((4, time.size - 1, values.shape[1]))
    for j in range(values.shape[1]):
        coefficients[:, :, j] = CubicSpline(time, values[:, j], bc_type="not-a-knot").c
    if len(_SPLINES) >= _SPLINE_CACHE_SIZE:
        _SPLINES.clear()  # (one step, safe should threads share the cache)
    _SPLINES[key] = (time, values, coefficients)
    return coefficients


def table_state(time: NDArray[np.float64], values: NDArray[np.float64],
                t: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The not-a-knot cubic spline through the rows of a table, and its exact derivative.

    Parameters
    ----------
    time
        The table's times [s], (rows,), strictly increasing.
    values
        Its columns, (rows, columns).
    t
        Times [s], (n,). Outside the table the end rows hold, at rest.

    Returns
    -------
    (ndarray, ndarray)
        Values and their time derivatives [1/s], (n, columns) each. At the rows the values
        are the table's own; two rows give the straight line, three the parabola.
    """
    t = np.asarray(t, dtype=float)
    c = _spline_coefficients(time, values)
    inside = (t >= time[0]) & (t <= time[-1])
    tc = np.clip(t, time[0], time[-1])
    index = np.clip(np.searchsorted(time, tc, side="right") - 1, 0, time.size - 2)
    s = (tc - time[index])[:, None]
    a, b, g, d = c[0, index], c[1, index], c[2, index], c[3, index]
    value = ((a * s + b) * s + g) * s + d
    rate = (3.0 * a * s + 2.0 * b) * s + g
    rate[~inside] = 0.0
    return value, rate


def ramp(t: NDArray[np.float64], duration: float) -> NDArray[np.float64]:
    """Cosine ramp from 0 at t = 0 to 1 at t = ``duration`` [-]."""
    t = np.asarray(t, dtype=float)
    if duration <= 0.0:
        return np.ones_like(t)
    x = np.clip(t / duration, 0.0, 1.0)
    return 0.5 * (1.0 - np.cos(np.pi * x))


def horizontal_direction(line: Line) -> NDArray[np.float64] | None:
    """Unit horizontal vector from the anchor towards the fairlead, or None for a vertical line."""
    d = np.subtract(line.fairlead, line.anchor)[:2]
    norm = float(np.hypot(d[0], d[1]))
    if norm <= 1e-12 * max(line.length, 1.0):
        return None
    return np.array([d[0] / norm, d[1] / norm, 0.0])


def ramp_rate(t: NDArray[np.float64], duration: float) -> NDArray[np.float64]:
    """Time derivative of :func:`ramp` [1/s]."""
    t = np.asarray(t, dtype=float)
    if duration <= 0.0:
        return np.zeros_like(t)
    inside = (t > 0.0) & (t < duration)
    return np.where(inside, 0.5 * np.pi / duration * np.sin(np.pi * t / duration), 0.0)


def motion_state(motion: Motion, t: NDArray[np.float64], direction: NDArray[np.float64] | None
                 ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Ramped displacement and its time derivative at times ``t``.

    Parameters
    ----------
    motion
        The prescribed motion.
    t
        Times [s], shape (n,).
    direction
        The line's horizontal unit vector away from the anchor (needed by circular motion).

    Returns
    -------
    (ndarray, ndarray)
        Displacements [m] and velocities [m/s], shape (n, 3) each.
    """
    t = np.asarray(t, dtype=float)
    d = np.zeros((t.size, 3))
    dd = np.zeros((t.size, 3))
    if isinstance(motion, CircularMotion):
        if direction is None:
            raise ValueError("circular motion needs a line with a horizontal span")
        omega = 2.0 * np.pi / motion.period
        phi = omega * t + motion.phase
        sense = 1.0 if motion.sense == "away-from-anchor-at-top" else -1.0
        d[:, :] = (sense * motion.radius * np.sin(phi))[:, None] * direction[None, :]
        d[:, 2] += motion.radius * np.cos(phi)
        dd[:, :] = (sense * motion.radius * omega * np.cos(phi))[:, None] * direction[None, :]
        dd[:, 2] -= motion.radius * omega * np.sin(phi)
    elif isinstance(motion, HarmonicMotion):
        harmonic_state(motion.amplitude, motion.period, motion.phase, t, d, dd)
    elif isinstance(motion, TableMotion):
        d, dd = table_state(motion.time, motion.displacement, t)
    else:  # pragma: no cover - the loader admits no other kind
        raise TypeError(f"unknown motion {motion!r}")
    return ramped(t, motion.ramp_duration, d, dd)


def harmonic_state(amplitude: tuple[float, ...], period: tuple[float, ...],
                   phase: tuple[float, ...], t: NDArray[np.float64], d: NDArray[np.float64],
                   dd: NDArray[np.float64]) -> None:
    """Fill column i of ``d`` and ``dd`` with a_i sin(2 pi t / T_i + phase_i) and its rate,
    for each of the given DOFs (a fairlead's axes, a body's six DOFs: the same expressions,
    so that a body's translations are bit-identical to a fairlead's)."""
    for axis in range(len(amplitude)):
        omega = 2.0 * np.pi / period[axis]
        angle = omega * t + phase[axis]
        d[:, axis] = amplitude[axis] * np.sin(angle)
        dd[:, axis] = amplitude[axis] * omega * np.cos(angle)


def ramped(t: NDArray[np.float64], ramp_duration: float, d: NDArray[np.float64],
           dd: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A displacement ``d`` and its rate ``dd`` (time along the first axis) brought in from
    rest by the cosine ramp: r d and r dd + r' d."""
    r = ramp(t, ramp_duration)[:, None]
    dr = ramp_rate(t, ramp_duration)[:, None]
    return r * d, r * dd + dr * d


def displacement(motion: Motion, t: NDArray[np.float64],
                 direction: NDArray[np.float64] | None) -> NDArray[np.float64]:
    """Ramped displacement of a fairlead at times ``t`` [m], shape (n, 3)."""
    return motion_state(motion, t, direction)[0]


def fairlead_state(motion: Motion | None, line: Line, t: NDArray[np.float64]
                   ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Fairlead positions [m] and velocities [m/s] of ``line`` at times ``t``, (n, 3) each."""
    base = np.broadcast_to(np.asarray(line.fairlead, dtype=float), (np.size(t), 3)).copy()
    if motion is None:
        return base, np.zeros_like(base)
    d, dd = motion_state(motion, t, horizontal_direction(line))
    return base + d, dd


def fairlead_path(motion: Motion | None, line: Line, t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Fairlead positions of ``line`` at times ``t`` [m], shape (n, 3)."""
    return fairlead_state(motion, line, t)[0]
