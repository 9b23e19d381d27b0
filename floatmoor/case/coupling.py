"""Case tables of coupled runs (a floater on its lines): ``[waves]``, ``[initial]``
and the body step ``[simulation] time_step`` (read in load.py).

``[waves]``: ``kind = "still"``; ``"regular"`` with ``height`` [m], ``period`` [s],
``direction_deg = 0``, ``phase_deg = 0``; ``"jonswap"`` with ``hs`` [m], ``tp`` [s],
``seed``, ``gamma = 3.3``, ``direction_deg = 0``, ``spacing = "equal"`` (or
``"random-in-bin"``), ``n_components``, ``frequency_step`` [rad/s], ``omega_min``,
``omega_max`` [rad/s]; all kinds: ``ramp_duration`` [s] (cosine ramp of the excitation;
default two periods, or two peak periods); ``second_order = "none"`` (or ``"mean"``,
``"newman"``, ``"full"``: second-order wave loads, floatmoor.waves.second_order) and
``drift_coefficients = "far_field"`` (or ``"near_field"``: the mean drift route of ``mean``
and ``newman``). ``[wind]`` (rotor thrust of the NREL 5 MW turbine,
floatmoor.wind): ``mean_speed`` [m/s] at ``reference_height = 90`` [m], ``spectrum = "npd"``
(or ``"steady"``), ``seed = 0``, ``direction_deg = 0``, ``relative_velocity = true``,
``cutoff_hz = 0.5``, ``hub_height = 90`` [m]. ``[initial]``: the body's displacement from its
static equilibrium at t = 0 (free decay): ``surge``, ``sway``, ``heave`` [m], ``roll_deg``,
``pitch_deg``, ``yaw_deg`` (all default 0); body and lines start at rest there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from floatmoor.case.reader import TableReader
from floatmoor.case.schema import Case, Environment
from floatmoor.case.sea import (GAMMA_RANGE, JonswapSettings, RegularWaveSettings,
                                StillWaterSettings, WaveCase, WaveSettings)
from floatmoor.case.setting import Setting, read_settings, setting, settings_of
from floatmoor.case.wind import WindSettings

__all__ = ["CoupledCase", "InitialOffset", "STILL_WATER", "read_waves", "read_initial",
           "read_wind", "WAVE_KINDS"]

WAVE_KINDS = ("still", "regular", "jonswap")
#: Default excitation ramp in (peak) wave periods.
RAMP_PERIODS = 2.0


#: ``[waves] kind``: which sea, hence which settings class the table's other keys fill.
WAVE_KIND = Setting("string", choices=WAVE_KINDS, doc="`still` water, `regular` (Airy) waves "
                    "or a `jonswap` irregular sea.")


def _offset(dof: str, unit: str, doc: str) -> float:
    """One DOF of :class:`InitialOffset` (an angle: given in degrees, ``*_deg``)."""
    angle = unit == "deg"
    return setting("number", key=f"{dof}_deg" if angle else None, radians=angle,
                   scale="same" if angle else "length", unit=unit, default=0.0,
                   field_default=0.0, doc=doc)


@dataclass(frozen=True)
class InitialOffset:
    """``[initial]``: the floater's displacement from its static equilibrium at t = 0 (a free
    decay) [m, rad]; :attr:`floatmoor.case.schema.Case.initial_offset` holds it as a tuple."""

    surge: float = _offset("surge", "m", "Initial surge offset.")
    sway: float = _offset("sway", "m", "Initial sway offset.")
    heave: float = _offset("heave", "m", "Initial heave offset.")
    roll: float = _offset("roll", "deg", "Initial roll angle.")
    pitch: float = _offset("pitch", "deg", "Initial pitch angle.")
    yaw: float = _offset("yaw", "deg", "Initial yaw angle.")


#: The sea of a case without ``[waves]``: still water, no ramp, no second-order loads.
STILL_WATER = WaveCase(StillWaterSettings(), 0.0)


@dataclass(frozen=True)
class CoupledCase:
    """What a coupled run takes from its case: a typed, read-only view built from a loaded
    case, whose reader checked it (``[simulation] time_step`` divides ``output_interval``
    within :data:`floatmoor.case.load.INTERVAL_RATIO_TOLERANCE`), so the time loop checks
    nothing again."""

    time_step: float  #: the body's step [s]: ``simulation.time_step``, or the output interval
    steps_per_output: int  #: body steps per output sample
    waves: WaveCase  #: the sea (:data:`STILL_WATER` without ``[waves]``)
    #: offset from the static equilibrium at t = 0 (Surge, Sway, Heave [m], Roll, Pitch,
    #: Yaw [rad])
    initial_offset: tuple[float, float, float, float, float, float]

    @classmethod
    def of(cls, case: Case) -> "CoupledCase":
        """The view of ``case`` (a case with a ``[floater]``)."""
        sim = case.simulation
        step = sim.time_step if sim.time_step is not None else sim.output_interval
        return cls(time_step=float(step),
                   steps_per_output=int(round(sim.output_interval / step)),
                   waves=case.waves if case.waves is not None else STILL_WATER,
                   initial_offset=tuple(case.initial_offset))  # type: ignore[arg-type]


def read_waves(t: TableReader, environment: Environment, duration: float) -> WaveCase:
    """``[waves]``, checked for physical values (steepness, breaking, gamma range)."""
    kind = WAVE_KIND.read(t, "kind")
    if kind == "still":
        settings: WaveSettings = StillWaterSettings()
        period = 0.0
    elif kind == "regular":
        settings = RegularWaveSettings(**read_settings(RegularWaveSettings, t))
        period = settings.period
    else:
        gamma = settings_of(JonswapSettings)["gamma"].read(t, "gamma")
        if gamma > GAMMA_RANGE[1]:
            raise t.error("gamma", f"a number in [{GAMMA_RANGE[0]:g}, {GAMMA_RANGE[1]:g}]",
                          gamma)
        settings = JonswapSettings(**read_settings(JonswapSettings, t, skip=("gamma",)),
                                   gamma=gamma)
        period = settings.tp
    read = read_settings(WaveCase, t, {"ramp_duration": RAMP_PERIODS * period})
    ramp, second_order, route = read["ramp_duration"], read["second_order"], \
        read["drift_coefficients"]
    if kind == "still" and second_order != "none":
        raise t.error("second_order", '"none" in still water (kind = "still": no waves to '
                      "drift the floater)", second_order)
    try:
        # an extreme period can defeat the dispersion relation's Newton iteration: that is a
        # period out of range, said in one message (no overflow warnings before it)
        with np.errstate(all="ignore"):
            if isinstance(settings, JonswapSettings):
                settings.validate(environment.water_depth, environment.gravity, duration)
            else:
                settings.validate(environment.water_depth, environment.gravity)
    except ValueError as err:
        raise t.error("kind", f"a physical sea ({err})", kind) from None
    except (RuntimeError, ArithmeticError) as err:
        key = "tp" if isinstance(settings, JonswapSettings) else "period"
        raise t.error(key, f"a wave period for which the dispersion relation has a solution "
                      f"({err}) [s]", period) from None
    t.finish()
    return WaveCase(settings, ramp, second_order, route)


def read_initial(t: TableReader) -> tuple[float, float, float, float, float, float]:
    """``[initial]``: the body's offset from its equilibrium (radians inside)."""
    out = tuple(read_settings(InitialOffset, t).values())
    t.finish()
    return out  # type: ignore[return-value]


def read_wind(t: TableReader, duration: float) -> WindSettings:
    """``[wind]``: the rotor thrust's wind (floatmoor.case.wind.WindSettings); a turbulent
    wind needs its cutoff above two frequency steps 1 / duration."""
    settings = WindSettings(**read_settings(WindSettings, t))
    if settings.spectrum != "steady" and not settings.cutoff_hz > 2.0 / duration:
        raise t.error("cutoff_hz", f"a frequency above 2 / simulation.duration = "
                      f"{2.0 / duration:.3g} Hz (a longer run, or spectrum = \"steady\")",
                      settings.cutoff_hz)
    t.finish()
    return settings
