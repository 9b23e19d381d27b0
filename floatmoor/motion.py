"""Prescribed fairlead motion for forced-motion runs.

The fairlead position is the mean position given in the case plus a displacement
``R(t) d(t)``, where ``d`` is the motion (circular, harmonic or tabulated) and ``R`` the ramp
``R(t) = (1 - cos(pi t / t_r)) / 2`` for ``t < t_r``, 1 after. The ramp has zero slope at both
ends, so the velocity is continuous when the motion starts and when it reaches full amplitude.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import CircularMotion, HarmonicMotion, Line, Motion, TableMotion

__all__ = ["ramp", "ramp_rate", "horizontal_direction", "motion_state", "displacement",
           "fairlead_path", "fairlead_state"]


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
        for axis in range(3):
            omega = 2.0 * np.pi / motion.period[axis]
            phase = omega * t + motion.phase[axis]
            d[:, axis] = motion.amplitude[axis] * np.sin(phase)
            dd[:, axis] = motion.amplitude[axis] * omega * np.cos(phase)
    elif isinstance(motion, TableMotion):
        slopes = np.diff(motion.displacement, axis=0) / np.diff(motion.time)[:, None]
        index = np.clip(np.searchsorted(motion.time, t, side="right") - 1, 0, len(slopes) - 1)
        for axis in range(3):
            d[:, axis] = np.interp(t, motion.time, motion.displacement[:, axis])
            dd[:, axis] = slopes[index, axis]
    else:  # pragma: no cover - the loader admits no other kind
        raise TypeError(f"unknown motion {motion!r}")
    r = ramp(t, motion.ramp_duration)[:, None]
    dr = ramp_rate(t, motion.ramp_duration)[:, None]
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
