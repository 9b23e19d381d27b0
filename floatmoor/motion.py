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

__all__ = ["ramp", "horizontal_direction", "displacement", "fairlead_path"]


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


def displacement(motion: Motion, t: NDArray[np.float64],
                 direction: NDArray[np.float64] | None) -> NDArray[np.float64]:
    """Ramped displacement of a fairlead at times ``t``.

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
    ndarray
        Displacements [m], shape (n, 3).
    """
    t = np.asarray(t, dtype=float)
    out = np.zeros((t.size, 3))
    if isinstance(motion, CircularMotion):
        if direction is None:
            raise ValueError("circular motion needs a line with a horizontal span")
        phi = 2.0 * np.pi * t / motion.period + motion.phase
        sense = 1.0 if motion.sense == "away-from-anchor-at-top" else -1.0
        horizontal = sense * motion.radius * np.sin(phi)
        out[:, :] = horizontal[:, None] * direction[None, :]
        out[:, 2] += motion.radius * np.cos(phi)
    elif isinstance(motion, HarmonicMotion):
        for axis in range(3):
            out[:, axis] = motion.amplitude[axis] * np.sin(
                2.0 * np.pi * t / motion.period[axis] + motion.phase[axis])
    elif isinstance(motion, TableMotion):
        for axis in range(3):
            out[:, axis] = np.interp(t, motion.time, motion.displacement[:, axis])
    else:  # pragma: no cover - the loader admits no other kind
        raise TypeError(f"unknown motion {motion!r}")
    out *= ramp(t, motion.ramp_duration)[:, None]
    return out


def fairlead_path(motion: Motion | None, line: Line, t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Fairlead positions of ``line`` at times ``t`` [m], shape (n, 3)."""
    base = np.broadcast_to(np.asarray(line.fairlead, dtype=float), (np.size(t), 3)).copy()
    if motion is None:
        return base
    return base + displacement(motion, t, horizontal_direction(line))
