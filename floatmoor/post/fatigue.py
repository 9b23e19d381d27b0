"""Fatigue of mooring lines: S-N and T-N curves, Miner damage, damage equivalent loads.

Physics reference: docs/theory/post_processing.md (quasi-dynamic paper section 5.2). The tension history
is rainflow counted (ASTM E1049, :mod:`floatmoor.post.rainflow`); the stress range of a chain
is the tension range over the nominal area of its two legs, ``A = 2 pi d^2 / 4``; the number of
cycles to failure at a stress range S is ``n = a_D S^-m`` and the damage is Miner's sum

    D = sum_i n_i S_i^m / a_D.

Units. DNV-OS-E301 (Ch.2 Sec.2, fatigue limit state) gives ``a_D`` for S in MPa: studless chain
a_D = 6.0e10, m = 3; stud chain a_D = 1.2e11, m = 3. floatmoor works in Pa: an
:class:`SNCurve` stores the unit of S its ``a_D`` goes with (``stress_unit``, Pa per unit; 1e6
for MPa) and divides stress ranges in Pa by it before applying the curve, so
``DNV_STUDLESS_CHAIN.cycles_to_failure(100e6)`` is 6.0e10 / 100^3 = 6.0e4 cycles.

T-N curves (API RP 2SK): ``N R^M = K`` with R the tension range over the minimum breaking
strength (MBS). K, M and the MBS are parameters of :class:`TNCurve`; no preset values are given
here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Union

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from floatmoor.post.rainflow import rainflow_cycles
from floatmoor.post.statistics import time_window

__all__ = [
    "MPA",
    "SNCurve",
    "TNCurve",
    "DNV_STUDLESS_CHAIN",
    "DNV_STUDLINK_CHAIN",
    "chain_nominal_area",
    "miner_damage",
    "fatigue_damage",
    "damage_equivalent_load",
    "rayleigh_damage",
]

#: Pa per MPa: the stress unit of DNV-OS-E301's a_D.
MPA = 1.0e6


@dataclass(frozen=True)
class SNCurve:
    """S-N curve ``N = a_D S^-m`` on the nominal stress range S, optionally two-slope.

    Parameters
    ----------
    a_d
        Intercept a_D, for S in ``stress_unit``.
    m
        Inverse slope.
    stress_unit
        Pa per unit of S in the curve (``MPA`` = 1e6 for DNV's chain curves, 1.0 for Pa).
    knee_cycles
        Optional: cycle count beyond which the second slope ``m2`` applies (e.g. 1e7).
    m2
        Inverse slope beyond ``knee_cycles``; ``math.inf`` is an endurance limit (stress ranges
        below the knee do no damage). Ignored without ``knee_cycles``.
    name
        Label for reports.
    """

    a_d: float
    m: float
    stress_unit: float = MPA
    knee_cycles: float | None = None
    m2: float | None = None
    name: str = ""

    def cycles_to_failure(self, stress_range: ArrayLike) -> NDArray[np.float64]:
        """Cycles to failure N at stress ranges given in Pa (inf at zero range)."""
        s = np.asarray(stress_range, dtype=float) / self.stress_unit
        with np.errstate(divide="ignore"):
            n = self.a_d * np.power(s, -self.m)
        if self.knee_cycles is not None and self.m2 is not None:
            s_knee = (self.a_d / self.knee_cycles) ** (1.0 / self.m)
            below = s < s_knee
            if math.isinf(self.m2):
                n = np.where(below, np.inf, n)
            else:
                with np.errstate(divide="ignore"):
                    n2 = self.knee_cycles * np.power(s_knee / s, self.m2)
                n = np.where(below, n2, n)
        return n


@dataclass(frozen=True)
class TNCurve:
    """T-N curve ``N R^M = K`` with R = tension range / MBS (API RP 2SK form).

    Parameters
    ----------
    k
        Intercept K.
    m
        Exponent M.
    mbs
        Minimum breaking strength of the component [N].
    name
        Label for reports.
    """

    k: float
    m: float
    mbs: float
    name: str = ""

    def cycles_to_failure(self, tension_range: ArrayLike) -> NDArray[np.float64]:
        """Cycles to failure N at tension ranges given in N (inf at zero range)."""
        r = np.asarray(tension_range, dtype=float) / self.mbs
        with np.errstate(divide="ignore"):
            return self.k * np.power(r, -self.m)


FatigueCurve = Union[SNCurve, TNCurve]

#: DNV-OS-E301 Ch.2 Sec.2, S-N curve of studless chain: a_D = 6.0e10 (S in MPa), m = 3.
DNV_STUDLESS_CHAIN = SNCurve(a_d=6.0e10, m=3.0, stress_unit=MPA,
                             name="DNV-OS-E301 studless chain")
#: DNV-OS-E301 Ch.2 Sec.2, S-N curve of stud (studlink) chain: a_D = 1.2e11 (S in MPa), m = 3.
DNV_STUDLINK_CHAIN = SNCurve(a_d=1.2e11, m=3.0, stress_unit=MPA,
                             name="DNV-OS-E301 studlink chain")


def chain_nominal_area(diameter: float) -> float:
    """Nominal area of a chain link's two legs, ``2 pi d^2 / 4`` [m^2] (docs/theory/post_processing.md).

    Parameters
    ----------
    diameter
        Nominal (bar) diameter d [m].
    """
    return 2.0 * math.pi * diameter**2 / 4.0


def miner_damage(ranges: ArrayLike, counts: ArrayLike, curve: FatigueCurve) -> float:
    """Miner's sum ``sum_i n_i / N(range_i)``.

    Parameters
    ----------
    ranges
        Counted ranges, in the quantity the curve takes: stress range [Pa] for an
        :class:`SNCurve`, tension range [N] for a :class:`TNCurve`.
    counts
        Cycle counts of the ranges (0.5 for half cycles).
    curve
        The S-N or T-N curve.
    """
    n_fail = curve.cycles_to_failure(ranges)
    c = np.asarray(counts, dtype=float)
    return float(np.sum(c / n_fail))


def _over_time(func, data: xr.DataArray, start: float) -> xr.DataArray:
    window = time_window(data, start=start)
    return xr.apply_ufunc(func, window, input_core_dims=[["time"]], vectorize=True,
                          output_dtypes=[float])


def fatigue_damage(tension: xr.DataArray, curve: FatigueCurve, *, start: float,
                   nominal_area: float | None = None) -> xr.DataArray:
    """Miner damage of a tension record from ``start`` on, per series.

    Parameters
    ----------
    tension
        Tension [N] with a ``time`` dimension, e.g. ``ds["fairlead_tension"]`` (line, time);
        every other dimension is kept.
    curve
        :class:`SNCurve` (needs ``nominal_area``) or :class:`TNCurve`.
    start
        Samples before ``start`` [s] (the transient) are excluded.
    nominal_area
        Area [m^2] turning tension into stress for an S-N curve, e.g.
        ``chain_nominal_area(d)``.

    Returns
    -------
    DataArray
        Damage over the window (dimensionless), the record's other dimensions.
    """
    if isinstance(curve, SNCurve):
        if nominal_area is None or nominal_area <= 0.0:
            raise ValueError("fatigue_damage: an S-N curve needs nominal_area > 0 [m^2]")
        scale = 1.0 / nominal_area
    else:
        scale = 1.0

    def damage(values: NDArray[np.float64]) -> float:
        cycles = rainflow_cycles(values)
        return miner_damage(cycles.ranges * scale, cycles.counts, curve)

    out = _over_time(damage, tension, start).rename("fatigue_damage")
    out.attrs = {"long_name": f"Miner fatigue damage from t = {start:g} s"
                              + (f" ({curve.name})" if curve.name else ""),
                 "units": "1"}
    return out


def damage_equivalent_load(data: xr.DataArray, m: float, *, start: float,
                           n_eq: float | None = None,
                           reference_frequency: float = 1.0) -> xr.DataArray:
    """Damage equivalent load ``(sum_i n_i S_i^m / N_eq)^(1/m)`` from ``start`` on.

    The constant-amplitude range that does, in ``N_eq`` cycles, the damage of the rainflow
    counted record on a one-slope curve of inverse slope ``m`` (any a_D).

    Parameters
    ----------
    data
        Load record with a ``time`` dimension (e.g. fairlead tension [N]).
    m
        Inverse S-N slope (3 for chain per DNV-OS-E301).
    start
        Samples before ``start`` [s] are excluded.
    n_eq
        Reference number of cycles. None: ``reference_frequency`` times the window duration.
    reference_frequency
        Frequency of the equivalent cycles [Hz] when ``n_eq`` is None (1 Hz by convention).

    Returns
    -------
    DataArray
        The equivalent range, in the unit of ``data``.
    """
    window = time_window(data, start=start)
    time = window["time"].values
    if n_eq is None:
        n_eq = reference_frequency * float(time[-1] - time[0])
    if not n_eq > 0.0:
        raise ValueError(f"damage_equivalent_load: n_eq must be > 0, got {n_eq}")

    def equivalent(values: NDArray[np.float64]) -> float:
        c = rainflow_cycles(values)
        return float((np.sum(c.counts * c.ranges**m) / n_eq) ** (1.0 / m))

    out = xr.apply_ufunc(equivalent, window, input_core_dims=[["time"]], vectorize=True,
                         output_dtypes=[float]).rename("damage_equivalent_load")
    out.attrs = {"long_name": f"damage equivalent range (m = {m:g}, N_eq = {n_eq:g}) "
                              f"from t = {start:g} s",
                 "units": data.attrs.get("units", "")}
    return out


def rayleigh_damage(m0: float, m2: float, duration: float, curve: SNCurve) -> float:
    """Expected damage of a narrow-band Gaussian stress process (Rayleigh closed form).

    ``E[D] = (nu0 T / a_D) (2 sqrt(2 m0))^m Gamma(1 + m / 2)`` with the mean up-crossing rate
    ``nu0 = sqrt(m2 / m0)`` [Hz] (Rice), stress ranges twice the Rayleigh amplitudes (e.g.
    DNV-RP-C203 appendix on spectral fatigue; Wirsching & Light 1980). One-slope curves only.

    Parameters
    ----------
    m0
        Variance of the stress process [Pa^2].
    m2
        Second spectral moment in the Hz convention, integral of f^2 S(f) df [Pa^2 Hz^2].
    duration
        Exposure time T [s].
    curve
        One-slope S-N curve; stresses are converted to its ``stress_unit``.
    """
    if curve.knee_cycles is not None:
        raise ValueError("rayleigh_damage: one-slope S-N curves only")
    nu0 = math.sqrt(m2 / m0)
    sigma = math.sqrt(m0) / curve.stress_unit
    return (nu0 * duration / curve.a_d) * (2.0 * math.sqrt(2.0) * sigma) ** curve.m \
        * math.gamma(1.0 + curve.m / 2.0)
