"""The ``[wind]`` table: the wind on the rotor of a coupled case, one declaration per key.

The rotor thrust that uses it is :class:`floatmoor.wind.force.RotorThrust`
(docs/theory/environment.md); the settings live here, beside the case schema, so that
reading a case needs no model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from floatmoor.case.setting import setting

__all__ = ["WindSettings", "SPECTRA", "DEFAULT_CUTOFF_HZ", "HUB_HEIGHT"]

#: Wind spectra: "npd" (turbulent, DNV-RP-C205 2.3.4) and "steady" (constant wind).
SPECTRA = ("npd", "steady")
#: Upper end of the realised wind band [Hz]: above it the NPD spectrum at 90 m for 13.05 m/s
#: holds 4.7 % of its variance, gusts shorter than 2 s that a 126 m rotor largely averages out
#: (the averaging itself is not modelled).
DEFAULT_CUTOFF_HZ = 0.5
#: NREL 5 MW hub height above the still water line [m] (Jonkman et al. 2009, Table 1-1).
HUB_HEIGHT = 90.0


@dataclass(frozen=True)
class WindSettings:
    """Wind on the rotor, the case's ``[wind]`` keys (LC43 of OC5 Phase II: 13.05 m/s at the
    hub, direction 0).

    The mean speed at 10 m and at the hub follow from the NPD profile
    (:func:`floatmoor.wind.force.speed_10m`, :func:`floatmoor.wind.force.hub_mean_speed`).
    """

    mean_speed: float = setting(  #: 1-hour mean at ``reference_height`` [m/s]
        "number", unit="m/s", gt=0.0,
        doc="One-hour mean wind speed at `reference_height`.")
    reference_height: float = setting(  #: height of ``mean_speed`` [m]
        "number", unit="m", gt=0.0, default=HUB_HEIGHT, field_default=HUB_HEIGHT,
        doc="Height of `mean_speed` above the still water line.")
    spectrum: str = setting(  #: "npd" or "steady"
        "string", choices=SPECTRA, default="npd", field_default="npd",
        doc="`npd` (turbulent, the NPD spectrum of DNV-RP-C205) or `steady` (constant wind).")
    seed: int = setting(  #: seed of the random phases and frequencies
        "integer", ge=0, default=0, field_default=0,
        doc="Seed of the turbulent wind's random phases.")
    direction_deg: float = setting(  #: blows towards, from +x towards +y [deg]
        "number", unit="deg", default=0.0, field_default=0.0,
        doc="Direction the wind blows towards, from +x towards +y.")
    relative_velocity: bool = setting(  #: thrust from the wind relative to the moving hub
        "boolean", default=True, field_default=True,
        doc="Thrust on the wind relative to the moving rotor (quasi-steady; gives the "
            "negative aerodynamic damping above rated speed).")
    cutoff_hz: float = setting(  #: upper end of the realised band [Hz]
        "number", unit="Hz", gt=0.0, default=DEFAULT_CUTOFF_HZ, field_default=DEFAULT_CUTOFF_HZ,
        doc="Highest frequency of the turbulent wind; above 2 / duration.")
    hub_height: float = setting(  #: hub height above the reference point [m]
        "number", unit="m", gt=0.0, default=HUB_HEIGHT, field_default=HUB_HEIGHT,
        doc="Height of the rotor hub.")

    def validate(self) -> None:
        """Raise ValueError naming the offending key (for settings built in code; a case's
        are checked as they are read)."""
        def positive(name: str) -> None:
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value) or value <= 0.0:
                raise ValueError(f"wind.{name} must be a finite number > 0, got {value!r}")

        for name in ("mean_speed", "reference_height", "cutoff_hz", "hub_height"):
            positive(name)
        if self.spectrum not in SPECTRA:
            raise ValueError(f"wind.spectrum must be one of {', '.join(SPECTRA)}, "
                             f"got {self.spectrum!r}")
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)) \
                or self.seed < 0:
            raise ValueError(f"wind.seed must be an integer >= 0, got {self.seed!r}")
        d = self.direction_deg
        if isinstance(d, bool) or not isinstance(d, (int, float)) or not math.isfinite(d):
            raise ValueError(f"wind.direction_deg must be a finite number, got {d!r}")
        if not isinstance(self.relative_velocity, bool):
            raise ValueError(f"wind.relative_velocity must be true or false, "
                             f"got {self.relative_velocity!r}")
