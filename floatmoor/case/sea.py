"""The ``[waves]`` table: the settings of each sea kind, typed and declared once, their physical
checks, and the choices the wave models implement; the case's side of the sea, so that reading a
case imports no model (docs/theory/environment.md, docs/theory/hydrodynamics.md).

Each wave kind has a frozen dataclass whose field names are the case-file keys (angles as
``*_deg``; the sea built from them, :func:`floatmoor.waves.realisation.realise_sea`, takes radians).
``validate`` raises ValueError with a message that names the offending key; the case reader
turns it into the case error of ``[waves]``. The steepness check needs the wavelength, from the
dispersion relation of the base layer (:mod:`floatmoor.dispersion`).

Physical limits applied
-----------------------
* Regular waves: H > 0, T > 0; steepness H / lambda <= 1/7, the limiting steepness of a
  progressive wave in deep water (Michell 1893, 0.142); and H / h <= 0.78, the depth-limited
  breaking height of a solitary wave (McCowan 1894). Beyond either the wave breaks.
* JONSWAP: Hs > 0, Tp > 0, 1 <= gamma <= 10 (gamma = 1 is Pierson-Moskowitz; DNV-RP-C205
  3.5.5 uses 1 to 7 in its Hs-Tp rule, 10 is the accepted upper bound of fitted peaks);
  average steepness S_p = 2 pi Hs / (g Tp^2) <= 1/15, the steepest sea DNV-RP-C205 3.5.5
  admits (1/15 at short, 1/25 at long full-scale periods; only the Froude-invariant 1/15 is
  enforced so model-scale cases are judged like full scale); Hs / h <= 0.78 as above;
  0 < omega_min < omega_p < omega_max.

References
----------
DNV-RP-C205. Environmental conditions and environmental loads, section 3.5.5.
McCowan, J. (1894). On the highest wave of permanent type. Phil. Mag. 38, 351-358.
Michell, J. H. (1893). The highest waves in water. Phil. Mag. 36, 430-437.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from floatmoor.case.setting import setting
from floatmoor.dispersion import STANDARD_GRAVITY, wavelength

__all__ = ["SPACINGS", "SECOND_ORDER_MODELS", "DRIFT_ROUTES", "DEFAULT_GAMMA",
           "StillWaterSettings", "RegularWaveSettings", "JonswapSettings", "WaveSettings",
           "WaveCase", "MAX_STEEPNESS_REGULAR", "MAX_STEEPNESS_IRREGULAR",
           "MAX_HEIGHT_TO_DEPTH", "GAMMA_RANGE", "DEFAULT_OMEGA_RANGE_FACTORS"]

#: Frequency discretisations of irregular seas (floatmoor.waves.realisation).
SPACINGS = ("equal", "random-in-bin")
#: The case's ``[waves] second_order`` choices ("none": first-order forces only;
#: floatmoor.waves.second_order).
SECOND_ORDER_MODELS = ("none", "mean", "newman", "full")
#: The case's ``[waves] drift_coefficients`` choices (docs/theory/hydrodynamics.md).
DRIFT_ROUTES = ("far_field", "near_field")
#: Peak-enhancement factor when nothing else is known (DNV-RP-C205 3.5.5.5, North Sea average).
DEFAULT_GAMMA = 3.3
#: Limiting steepness H / lambda of a regular wave (Michell 1893: 0.142 ~ 1/7).
MAX_STEEPNESS_REGULAR = 1.0 / 7.0
#: Limiting average steepness 2 pi Hs / (g Tp^2) of a sea state (DNV-RP-C205 3.5.5).
MAX_STEEPNESS_IRREGULAR = 1.0 / 15.0
#: Depth-limited breaking, H / h (McCowan 1894).
MAX_HEIGHT_TO_DEPTH = 0.78
#: Admitted JONSWAP peak-enhancement factors.
GAMMA_RANGE = (1.0, 10.0)
#: Default realised band as multiples of omega_p: below 0.5 omega_p the spectrum holds
#: exp(-1.25 * 16) ~ 2e-9 of m0; above 4 omega_p the omega^-5 tail holds about 1.25/4^4 = 0.5 %.
DEFAULT_OMEGA_RANGE_FACTORS = (0.5, 4.0)
#: The description of ``[waves] direction_deg``, a key of both wave kinds.
DIRECTION_DOC = "Direction the waves travel in, from the x axis (`regular`, `jonswap`)."


def _positive(name: str, value: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
        raise ValueError(f"waves.{name} must be a finite number > 0, got {value!r}")


def _finite(name: str, value: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value)):
        raise ValueError(f"waves.{name} must be a finite number, got {value!r}")


@dataclass(frozen=True)
class StillWaterSettings:
    """No waves."""

    def validate(self, depth: float = math.inf, gravity: float = STANDARD_GRAVITY) -> None:
        """Nothing to check."""


@dataclass(frozen=True)
class RegularWaveSettings:
    """A regular (Airy) wave.

    Attributes
    ----------
    height
        H [m], crest to trough.
    period
        T [s].
    direction_deg
        Direction of travel [deg], 0 = towards +x, 90 = towards +y.
    phase_deg
        Phase [deg]: the crest passes x = y = 0 at t = phase_deg / 360 * T.
    """

    height: float = setting("number", unit="m", gt=0.0,
                            doc="Wave height, crest to trough (`regular`).")
    period: float = setting("number", unit="s", gt=0.0, doc="Wave period (`regular`).")
    direction_deg: float = setting("number", unit="deg", default=0.0, field_default=0.0,
                                   doc=DIRECTION_DOC)
    phase_deg: float = setting("number", unit="deg", default=0.0, field_default=0.0,
                               doc="Phase of the regular wave at the origin (`regular`).")

    def validate(self, depth: float = math.inf, gravity: float = STANDARD_GRAVITY) -> None:
        """Raise ValueError for unphysical or breaking waves (module docstring)."""
        _positive("height", self.height)
        _positive("period", self.period)
        _finite("direction_deg", self.direction_deg)
        _finite("phase_deg", self.phase_deg)
        length = float(wavelength(self.period, depth, gravity))
        steepness = self.height / length
        if steepness > MAX_STEEPNESS_REGULAR:
            raise ValueError(f"regular wave H = {self.height:g} m, T = {self.period:g} s is too "
                             f"steep: H/lambda = {steepness:.3f} > 1/7 (lambda = {length:g} m); "
                             "it would break")
        if math.isfinite(depth) and self.height > MAX_HEIGHT_TO_DEPTH * depth:
            raise ValueError(f"regular wave H = {self.height:g} m exceeds the depth-limited "
                             f"breaking height 0.78 h = {MAX_HEIGHT_TO_DEPTH * depth:g} m")


@dataclass(frozen=True)
class JonswapSettings:
    """An irregular, long-crested JONSWAP sea (see floatmoor.waves.realisation).

    Attributes
    ----------
    hs
        Significant wave height [m] (= 4 sqrt(m0) exactly).
    tp
        Peak period [s].
    seed
        Seed of the random phases (and frequencies for ``random-in-bin``); no default, so a
        case always says which sea it is.
    gamma
        Peak-enhancement factor, 1..10 (default 3.3, DNV-RP-C205).
    direction_deg
        Direction of travel [deg].
    spacing
        ``"equal"`` (default: d omega <= 2 pi / duration) or ``"random-in-bin"``.
    n_components
        Number of bins, ``random-in-bin`` only.
    frequency_step
        d omega [rad/s] for ``equal``; default 2 pi / duration, larger is an error.
    omega_min, omega_max
        Realised band [rad/s]; default 0.5 and 4 times omega_p.
    """

    hs: float = setting("number", unit="m", gt=0.0,
                        doc="Significant wave height, 4 sqrt(m0) (`jonswap`).")
    tp: float = setting("number", unit="s", gt=0.0, doc="Peak period (`jonswap`).")
    seed: int = setting("integer", ge=0, doc="Seed of the random phases, so a case always "
                        "names its sea (`jonswap`).")
    #: a case file's is read first, and checked against GAMMA_RANGE[1] with its own message
    gamma: float = setting("number", unit="-", ge=GAMMA_RANGE[0], default=DEFAULT_GAMMA,
                           field_default=DEFAULT_GAMMA,
                           doc="Peak-enhancement factor, 1 to 10 (`jonswap`).")
    direction_deg: float = setting("number", unit="deg", default=0.0, field_default=0.0,
                                   doc=DIRECTION_DOC)
    spacing: str = setting("string", choices=SPACINGS, default="equal", field_default="equal",
                           doc="Frequencies `equal`ly spaced or one `random-in-bin` "
                               "(`jonswap`).")
    n_components: int | None = setting(
        "integer", ge=1, default=None, field_default=None,
        doc="Number of frequency bins (`jonswap`, `random-in-bin` only).")
    frequency_step: float | None = setting(
        "number", unit="rad/s", gt=0.0, default=None, field_default=None,
        doc="Frequency step of an `equal` spacing; default 2 pi / duration, a larger one is "
            "an error as the sea would repeat (`jonswap`).")
    omega_min: float | None = setting(
        "number", unit="rad/s", gt=0.0, default=None, field_default=None,
        doc="Lowest realised frequency; default half the peak frequency (`jonswap`).")
    omega_max: float | None = setting(
        "number", unit="rad/s", gt=0.0, default=None, field_default=None,
        doc="Highest realised frequency; default four times the peak frequency (`jonswap`).")

    def band(self) -> tuple[float, float]:
        """(omega_min, omega_max) [rad/s] with the defaults filled in."""
        wp = 2.0 * math.pi / self.tp
        lo = self.omega_min if self.omega_min is not None else \
            DEFAULT_OMEGA_RANGE_FACTORS[0] * wp
        hi = self.omega_max if self.omega_max is not None else \
            DEFAULT_OMEGA_RANGE_FACTORS[1] * wp
        return lo, hi

    def validate(self, depth: float = math.inf, gravity: float = STANDARD_GRAVITY,
                 duration: float | None = None) -> None:
        """Raise ValueError for unphysical seas or discretisations (module docstring)."""
        _positive("hs", self.hs)
        _positive("tp", self.tp)
        _finite("direction_deg", self.direction_deg)
        if not (isinstance(self.gamma, (int, float)) and math.isfinite(self.gamma)
                and GAMMA_RANGE[0] <= self.gamma <= GAMMA_RANGE[1]):
            raise ValueError(f"waves.gamma must be in [1, 10] (1 = Pierson-Moskowitz), got "
                             f"{self.gamma!r}")
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0:
            raise ValueError(f"waves.seed must be an integer >= 0, got {self.seed!r}")
        steepness = 2.0 * math.pi * self.hs / (gravity * self.tp ** 2)
        if steepness > MAX_STEEPNESS_IRREGULAR:
            raise ValueError(f"sea state Hs = {self.hs:g} m, Tp = {self.tp:g} s is too steep: "
                             f"2 pi Hs/(g Tp^2) = {steepness:.4f} > 1/15 (DNV-RP-C205 3.5.5)")
        if math.isfinite(depth) and self.hs > MAX_HEIGHT_TO_DEPTH * depth:
            raise ValueError(f"Hs = {self.hs:g} m exceeds the depth-limited breaking height "
                             f"0.78 h = {MAX_HEIGHT_TO_DEPTH * depth:g} m")
        if self.spacing not in SPACINGS:
            raise ValueError(f"waves.spacing must be one of {SPACINGS}, got {self.spacing!r}")
        if self.spacing == "random-in-bin":
            if self.n_components is None or isinstance(self.n_components, bool) or \
                    not isinstance(self.n_components, int) or self.n_components < 1:
                raise ValueError("waves.n_components must be an integer >= 1 with spacing = "
                                 f"'random-in-bin', got {self.n_components!r}")
            if self.frequency_step is not None:
                raise ValueError("waves.frequency_step applies to spacing = 'equal' only")
        else:
            if self.n_components is not None:
                raise ValueError("waves.n_components applies to spacing = 'random-in-bin' only;"
                                 " with 'equal' the count follows from the frequency step")
            if self.frequency_step is not None:
                _positive("frequency_step", self.frequency_step)
                if duration is not None and \
                        self.frequency_step > 2.0 * math.pi / duration * (1.0 + 1e-12):
                    raise ValueError(f"waves.frequency_step = {self.frequency_step:g} rad/s "
                                     f"repeats the sea within the {duration:g} s run; use <= "
                                     f"2 pi / duration = {2.0 * math.pi / duration:g} rad/s")
        lo, hi = self.band()
        _positive("omega_min", lo)
        _positive("omega_max", hi)
        wp = 2.0 * math.pi / self.tp
        if not lo < wp < hi:
            raise ValueError(f"the band [omega_min, omega_max] = [{lo:g}, {hi:g}] rad/s must "
                             f"contain the spectral peak omega_p = {wp:g} rad/s")


WaveSettings = StillWaterSettings | RegularWaveSettings | JonswapSettings


@dataclass(frozen=True)
class WaveCase:
    """The sea of a coupled case, the ramp of its excitation and its second-order loads."""

    settings: WaveSettings
    ramp_duration: float = setting(  #: [s]
        "number", unit="s", ge=0.0, default_text="two (peak) periods",
        doc="Duration of the cosine ramp of the wave excitation.")
    #: second-order wave loads: "none", "mean", "newman" or "full"
    second_order: str = setting(
        "string", choices=SECOND_ORDER_MODELS, default="none", field_default="none",
        doc="Second-order wave loads: `none` (first order only), the constant `mean` drift, "
            "the slow drift by `newman`'s approximation, or the `full` difference-frequency "
            "QTF of the database (theory/hydrodynamics.md, guide/rao_and_drift.md).")
    #: mean drift route of "mean" and "newman": "far_field" or "near_field"
    drift_coefficients: str = setting(
        "string", choices=DRIFT_ROUTES, default="far_field", field_default="far_field",
        doc="Mean drift route of `mean` and `newman`: `far_field` (momentum: Surge, Sway, "
            "Yaw; Heave, Roll, Pitch from the near field) or `near_field` (pressure "
            "integration, all six DOFs).")
