"""The sea a case's ``[waves]`` settings describe: :func:`build` validates them and realises
the :class:`~floatmoor.waves.realisation.WaveField` (the settings, their keys and physical
limits: :mod:`floatmoor.case.sea`; angles in degrees there, radians here).
"""

from __future__ import annotations

import math

from floatmoor.case.sea import (JonswapSettings, RegularWaveSettings, StillWaterSettings,
                                WaveSettings)
from floatmoor.waves.realisation import WaveField

__all__ = ["build"]


def build(settings: WaveSettings, depth: float, gravity: float,
          duration: float) -> WaveField:
    """Validate ``settings`` and realise the sea.

    Parameters
    ----------
    settings
        One of the settings dataclasses.
    depth
        Water depth [m] (``math.inf`` for deep water).
    gravity
        g [m/s^2].
    duration
        Run length [s] (irregular seas must not repeat within it).

    Returns
    -------
    WaveField
    """
    if isinstance(settings, StillWaterSettings):
        return WaveField.still(depth, gravity)
    if isinstance(settings, RegularWaveSettings):
        settings.validate(depth, gravity)
        return WaveField.regular(settings.height, settings.period,
                                 math.radians(settings.direction_deg),
                                 math.radians(settings.phase_deg), depth, gravity)
    if isinstance(settings, JonswapSettings):
        settings.validate(depth, gravity, duration)
        lo, hi = settings.band()
        return WaveField.jonswap(settings.hs, settings.tp, gamma=float(settings.gamma),
                                 direction=math.radians(settings.direction_deg),
                                 seed=settings.seed, duration=duration, omega_min=lo,
                                 omega_max=hi, spacing=settings.spacing,
                                 n_components=settings.n_components,
                                 frequency_step=settings.frequency_step, depth=depth,
                                 gravity=gravity)
    raise TypeError(f"unknown wave settings {type(settings).__name__}")
