"""The characteristic frequency of a case's fairlead motion, from what the case declares.

The dynamic line's numerics are chosen before the run (mooring/dg/resolution.py) to resolve
the line's response at the frequency its fairlead is driven at: the prescribed motion's, or,
for a floater, the waves' (a floater follows the waves at their frequency; at its natural
periods it moves slower). A case that declares neither (a free decay, still water) gives 0:
the line is then resolved for its static shape only.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["fairlead_motion_frequency"]


def _table_frequency(time: np.ndarray, displacement: np.ndarray) -> float:
    """Mean zero-crossing frequency sqrt(m2 / m0) of a sampled displacement history [rad/s]
    (its moments from the samples: the velocity's mean square over the displacement's)."""
    x = np.asarray(displacement, dtype=float).reshape(len(time), -1)
    x = x - x.mean(axis=0)
    if len(time) < 3:
        return 0.0
    v = np.gradient(x, np.asarray(time, dtype=float), axis=0)
    # per column (metres and radians apart), the fastest of those that move
    return max((float(math.sqrt(np.sum(v[:, j] ** 2) / np.sum(x[:, j] ** 2)))
                for j in range(x.shape[1]) if np.any(x[:, j])), default=0.0)


def fairlead_motion_frequency(motion: Any, waves: Any) -> float:
    """Angular frequency the fairleads are driven at [rad/s], 0 when the case declares none.

    Parameters
    ----------
    motion
        The case's prescribed motion (``Case.motion``) or None.
    waves
        The case's waves (``Case.waves``, or its sea state) or None: regular waves give
        2 pi / T, a JONSWAP sea 2 pi / Tp (the peak, where the motion's energy is).

    Notes
    -----
    A harmonic motion with several periods gives the highest of its frequencies; a table the
    highest mean zero-crossing frequency of its columns.
    """
    if motion is not None:
        period = getattr(motion, "period", None)
        if period is not None and not hasattr(motion, "displacement"):
            amplitude = getattr(motion, "amplitude", None)
            if isinstance(period, tuple):
                moving = [p for a, p in zip(amplitude, period) if a != 0.0]
                return 2.0 * math.pi / min(moving) if moving else 0.0
            return 2.0 * math.pi / float(period)
        if hasattr(motion, "displacement"):
            return _table_frequency(motion.time, motion.displacement)
    waves = getattr(waves, "settings", waves)  # a WaveCase: its sea state
    if waves is not None:
        if hasattr(waves, "tp"):
            return 2.0 * math.pi / float(waves.tp)
        if hasattr(waves, "period"):
            return 2.0 * math.pi / float(waves.period)
    return 0.0
