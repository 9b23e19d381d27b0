"""A realised sea: a finite sum of linear (Airy) wave components.

Data structure
--------------
:class:`WaveField` holds N long-crested components as arrays of shape (N,): angular frequency
``omega`` [rad/s], amplitude ``amplitude`` a_j [m], phase ``phase`` phi_j [rad], direction
``direction`` beta_j [rad] (the direction the component travels *towards*, from +x towards +y,
capytaine's ``wave_direction``) and ``wavenumber`` k_j [rad/m] from the dispersion relation at
the field's ``depth``.

Phase convention (capytaine's, the project's)
---------------------------------------------
Complex amplitudes multiply e^{-i omega t}: a complex amplitude Z stands for Re{Z e^{-i omega t}}
(capytaine docs, user_manual/conventions.rst, "x(t) = Re(X e^{-i omega t})"). Component j has
the complex elevation amplitude A_j = a_j e^{i phi_j} at the origin and

.. math::
    \\eta_j(x, y, t) = \\Re\\{A_j e^{i k_j (x\\cos\\beta_j + y\\sin\\beta_j)} e^{-i\\omega_j t}\\}
                    = a_j \\cos(k_j (x\\cos\\beta_j + y\\sin\\beta_j) - \\omega_j t + \\phi_j).

This is capytaine's incident wave of unit amplitude times A_j: capytaine 3 defines
Phi_0 = -i g/omega cosh(k(z+h))/cosh(kh) e^{ik(x cos beta + y sin beta)} and the elevation
i omega/g Phi_0(z=0) = e^{ik(x cos beta + y sin beta)} (capytaine/bem/airy_waves.py), so its
excitation force X(omega, beta) per unit amplitude gives the force of component j as
Re{X_j A_j e^{-i omega_j t}}. With phi = 0 the crest is at the origin at t = 0 and a crest
passes x = lambda/4 a quarter period later (the wave travels towards +x for beta = 0);
tests/waves/test_conventions.py checks both against capytaine's own functions.

Programs in the WAMIT-style e^{+i omega t} convention (docs/conventions.md) write the same
sum as Re{X_W a_j e^{+i(omega_j t + phi_j)}}, where X_W = conj(X) (capytaine docs: "F_e = conj(F_e,W)"). Since
Re{conj(Z)} = Re{Z}, Re{X_W a e^{i(omega t + phi)}} = Re{X a e^{-i(omega t + phi)}}: the same
real signal as ours with phi_j -> -phi_j. Phases are uniform on [0, 2 pi), so both describe the
same random sea; what matters is that X from capytaine is only ever paired with e^{-i omega t}
(using capytaine's X in that formula would put the force a phase 2 arg X off the wave).

Irregular seas: frequency discretisation
----------------------------------------
a_j = sqrt(2 S(omega_j) d omega_j) with S the one-sided spectrum, phases uniform from
``numpy.random.default_rng(seed)`` (deterministic amplitudes, random phases). Two choices:

``"equal"`` (default)
    omega_j = j d omega, integer multiples of d omega <= 2 pi / duration. The record is exactly
    periodic with ``repeat_period`` 2 pi / d omega >= duration, so it never repeats within the
    run, and over one repeat period the periodogram returns S(omega_j) exactly and the variance
    is sum a_j^2/2 exactly. Cost: N = (omega_max - omega_min) duration / (2 pi) components;
    a 3 h full-scale record over 0.2-2.0 rad/s needs 3094.
``"random-in-bin"``
    ``n_components`` equal bins of width d omega over [omega_min, omega_max], one component per
    bin at a uniformly random frequency inside it (drawn after the phases from the same
    generator). No common period exists: at the would-be repeat lag 2 pi / d omega each
    component's phase has moved by a uniform random amount, so the record does not repeat
    (tests/waves/test_realisation.py measures the correlation there). Fewer components for
    a long run, at the price of a realised spectrum made of randomly placed lines.

The equal spacing is the default because it guarantees non-repetition by construction for any
seed and reproduces the target spectrum exactly over the repeat period; the measured cost of
3094 components over 3 h is a few seconds (docs/validation/notes.md).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from floatmoor.case.sea import (SPACINGS,  # frequency discretisations (module docstring)
                                JonswapSettings, RegularWaveSettings, StillWaterSettings,
                                WaveSettings)
from floatmoor.dispersion import STANDARD_GRAVITY, wavenumber
from floatmoor.waves.spectra import DEFAULT_GAMMA, jonswap, jonswap_moment
from floatmoor.waves.synthesis import harmonic_sum

__all__ = ["WaveField", "SPACINGS", "wave_elevation", "realise_sea"]

log = logging.getLogger(__name__)



def _frozen(a: ArrayLike, dtype: type = float) -> NDArray[Any]:
    out = np.array(a, dtype=dtype, copy=True).reshape(-1)
    out.setflags(write=False)
    return out


@dataclass(frozen=True, eq=False)
class WaveField:
    """A sea state realised as N linear wave components (see the module docstring).

    Build it with :meth:`still`, :meth:`regular`, :meth:`jonswap` or :meth:`from_components`
    rather than directly; the arrays are read-only.

    Attributes
    ----------
    omega, amplitude, phase, direction, wavenumber
        Component arrays of shape (N,) [rad/s, m, rad, rad, rad/m].
    depth
        Water depth [m] (``math.inf`` for deep water).
    gravity
        g [m/s^2].
    repeat_period
        Smallest lag at which the record repeats exactly [s] (``math.inf`` if it never does).
    info
        Provenance: how the field was built (kind, Hs, Tp, gamma, seed, spacing, ...).
    """

    omega: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    phase: NDArray[np.float64]
    direction: NDArray[np.float64]
    wavenumber: NDArray[np.float64]
    depth: float
    gravity: float
    repeat_period: float = math.inf
    info: dict[str, Any] = field(default_factory=dict)

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_components(cls, omega: ArrayLike, amplitude: ArrayLike, phase: ArrayLike,
                        direction: ArrayLike | float = 0.0, depth: float = math.inf,
                        gravity: float = STANDARD_GRAVITY, repeat_period: float = math.inf,
                        info: dict[str, Any] | None = None) -> WaveField:
        """A field from explicit components (angles in radians); wavenumbers are computed."""
        w = _frozen(omega)
        n = w.size
        a = _frozen(np.broadcast_to(np.asarray(amplitude, float), (n,)))
        p = _frozen(np.broadcast_to(np.asarray(phase, float), (n,)))
        d = _frozen(np.broadcast_to(np.asarray(direction, float), (n,)))
        if np.any(a < 0.0) or not np.all(np.isfinite(a)):
            raise ValueError("component amplitudes must be finite and >= 0")
        if not (np.all(np.isfinite(p)) and np.all(np.isfinite(d))):
            raise ValueError("component phases and directions must be finite")
        k = _frozen(wavenumber(w, depth, gravity)) if n else _frozen([])
        return cls(w, a, p, d, k, float(depth), float(gravity), float(repeat_period),
                   dict(info or {"kind": "components"}))

    @classmethod
    def still(cls, depth: float = math.inf, gravity: float = STANDARD_GRAVITY) -> WaveField:
        """Still water: no components (elevation, kinematics and excitation are zero)."""
        return cls.from_components([], [], [], [], depth, gravity, math.inf,
                                   {"kind": "still"})

    @classmethod
    def regular(cls, height: float, period: float, direction: float = 0.0,
                phase: float = 0.0, depth: float = math.inf,
                gravity: float = STANDARD_GRAVITY) -> WaveField:
        """One Airy component: eta(0, 0, t) = H/2 cos(2 pi t / T - phase).

        Parameters
        ----------
        height
            Wave height H [m] (crest to trough), amplitude H/2.
        period
            T [s].
        direction
            Direction the wave travels towards [rad], 0 = +x.
        phase
            phi [rad]: the crest passes the origin at t = phi T / (2 pi).
        depth, gravity
            Water depth [m] and g [m/s^2].
        """
        if not (height > 0.0 and math.isfinite(height)):
            raise ValueError(f"regular wave height must be finite and > 0 m, got {height!r}")
        if not (period > 0.0 and math.isfinite(period)):
            raise ValueError(f"regular wave period must be finite and > 0 s, got {period!r}")
        return cls.from_components([2.0 * math.pi / period], [0.5 * height], [phase],
                                   [direction], depth, gravity, float(period),
                                   {"kind": "regular", "height": height, "period": period,
                                    "direction": direction, "phase": phase})

    @classmethod
    def jonswap(cls, hs: float, tp: float, *, gamma: float = DEFAULT_GAMMA,
                direction: float = 0.0, seed: int, duration: float, omega_min: float,
                omega_max: float, spacing: str = "equal", n_components: int | None = None,
                frequency_step: float | None = None, depth: float = math.inf,
                gravity: float = STANDARD_GRAVITY) -> WaveField:
        """A seeded random-phase realisation of a JONSWAP sea (long-crested).

        Parameters
        ----------
        hs, tp, gamma
            Spectrum (see :func:`floatmoor.waves.spectra.jonswap`).
        direction
            Direction the waves travel towards [rad].
        seed
            Seed of ``numpy.random.default_rng``; the same seed gives the same sea.
        duration
            Run length [s]; the record must not repeat within it.
        omega_min, omega_max
            Frequency band [rad/s] that is realised; the variance outside it is dropped
            (``info["variance_fraction"]`` says how much is kept).
        spacing
            ``"equal"`` or ``"random-in-bin"`` (module docstring).
        n_components
            Number of bins for ``"random-in-bin"`` (required there, ignored for ``"equal"``).
        frequency_step
            d omega [rad/s] for ``"equal"``; default and maximum 2 pi / duration.
        depth, gravity
            Water depth [m] and g [m/s^2].
        """
        if spacing not in SPACINGS:
            raise ValueError(f"spacing must be one of {SPACINGS}, got {spacing!r}")
        if not (duration > 0.0 and math.isfinite(duration)):
            raise ValueError(f"duration must be finite and > 0 s, got {duration!r}")
        if not 0.0 < omega_min < omega_max < math.inf:
            raise ValueError(f"need 0 < omega_min < omega_max < inf, got {omega_min!r}, "
                             f"{omega_max!r}")
        rng = np.random.default_rng(seed)
        if spacing == "equal":
            max_step = 2.0 * math.pi / duration
            step = max_step if frequency_step is None else float(frequency_step)
            if not 0.0 < step <= max_step * (1.0 + 1e-12):
                raise ValueError(f"frequency_step {step:g} rad/s would repeat the record "
                                 f"within the {duration:g} s run: use <= 2 pi / duration = "
                                 f"{max_step:g} rad/s")
            j = np.arange(math.ceil(omega_min / step - 1e-9), math.floor(omega_max / step
                                                                        + 1e-9) + 1)
            j = j[j > 0]
            omega = j * step
            width = np.full(omega.shape, step)
            phase = rng.uniform(0.0, 2.0 * math.pi, omega.size)
            repeat = 2.0 * math.pi / step
        else:
            if n_components is None or int(n_components) < 1:
                raise ValueError("random-in-bin spacing needs n_components >= 1")
            n = int(n_components)
            step = (omega_max - omega_min) / n
            phase = rng.uniform(0.0, 2.0 * math.pi, n)
            offset = rng.uniform(0.0, 1.0, n)
            omega = omega_min + (np.arange(n) + offset) * step
            width = np.full(n, step)
            repeat = math.inf
        if omega.size == 0:
            raise ValueError("no wave component falls in [omega_min, omega_max]")
        density = jonswap(omega, hs, tp, gamma, gravity)
        amplitude = np.sqrt(2.0 * density * width)
        m0 = jonswap_moment(0, hs, tp, gamma, gravity)
        fraction = float(np.sum(density * width) / m0)
        log.info("JONSWAP Hs=%g m Tp=%g s gamma=%g: %d components (%s), %.4f of m0 in "
                 "[%g, %g] rad/s", hs, tp, gamma, omega.size, spacing, fraction,
                 omega_min, omega_max)
        info = {"kind": "jonswap", "hs": hs, "tp": tp, "gamma": gamma,
                "direction": direction, "seed": seed, "duration": duration,
                "spacing": spacing, "frequency_step": step, "omega_min": omega_min,
                "omega_max": omega_max, "n_components": int(omega.size),
                "variance_fraction": fraction}
        return cls.from_components(omega, amplitude, phase, direction, depth, gravity,
                                   repeat, info)

    # ------------------------------------------------------------------ properties
    @property
    def n_components(self) -> int:
        """Number of components N."""
        return int(self.omega.size)

    @property
    def complex_amplitude(self) -> NDArray[np.complex128]:
        """A_j = a_j e^{i phi_j} [m]: complex elevation amplitudes at the origin, shape (N,)."""
        return self.amplitude * np.exp(1j * self.phase)

    @property
    def variance(self) -> float:
        """Variance of the elevation, sum a_j^2 / 2 [m^2] (the realised m0)."""
        return float(0.5 * np.sum(self.amplitude ** 2))

    def complex_elevation(self, x: ArrayLike = 0.0, y: ArrayLike = 0.0
                          ) -> NDArray[np.complex128]:
        """A_j e^{i k_j (x cos beta_j + y sin beta_j)}, shape x.shape + (N,)."""
        xx = np.asarray(x, dtype=float)[..., None]
        yy = np.asarray(y, dtype=float)[..., None]
        travel = xx * np.cos(self.direction) + yy * np.sin(self.direction)
        return self.complex_amplitude * np.exp(1j * self.wavenumber * travel)

    # ------------------------------------------------------------------ evaluation
    def elevation(self, t: ArrayLike, x: float = 0.0, y: float = 0.0) -> NDArray[np.float64]:
        """Undisturbed incident elevation eta(x, y, t) [m] at one point, shape of ``t``."""
        return harmonic_sum(self.complex_elevation(x, y), self.omega, t)


def wave_elevation(field: WaveField, times: ArrayLike,
                   reference_xy: tuple[float, float] = (0.0, 0.0)) -> xr.DataArray:
    """The incident wave elevation at the body's reference point as a labelled time series.

    Parameters
    ----------
    field
        The sea.
    times
        Times [s], 1-D.
    reference_xy
        Horizontal position [m] of the body's reference point in the wave frame; the hydro
        database's transfer functions are relative to x = y = 0, the default.

    Returns
    -------
    xarray.DataArray
        ``wave_elevation`` [m] over ``time`` [s], with the field's provenance in attrs.
    """
    t = np.asarray(times, dtype=float)
    if t.ndim != 1:
        raise ValueError("times must be 1-D")
    eta = field.elevation(t, *reference_xy)
    attrs = {"long_name": "undisturbed incident wave elevation at the body reference point",
             "units": "m", "x": float(reference_xy[0]), "y": float(reference_xy[1])}
    attrs.update({f"waves_{k}": v for k, v in field.info.items()})
    return xr.DataArray(eta, dims=("time",),
                        coords={"time": ("time", t, {"units": "s"})},
                        name="wave_elevation", attrs=attrs)


def realise_sea(settings: WaveSettings, depth: float, gravity: float,
                duration: float) -> WaveField:
    """Validate a case's ``[waves]`` settings and realise the sea they describe.

    The settings, their keys and physical limits are :mod:`floatmoor.case.sea` (angles in
    degrees there, radians here).

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
