"""Power spectral densities of time series (Welch) and their moments and periods.

Welch's method (scipy.signal.welch) with these defaults, chosen for long offshore records:

* segments of ``segment_duration`` = 200 s, so a frequency resolution of 1 / 200 s = 0.005 Hz,
  and about 100 averaged segments for a 3-hour full-scale record (configurable: a longer
  segment resolves slow-drift surge better at the cost of a noisier estimate);
* Hann window, 50 % overlap, linear detrend of each segment;
* one-sided density: ``S(f)`` in unit^2/Hz over ``frequency`` [Hz], with
  ``integral S(f) df = variance``; or, with ``angular=True``, ``S(w) = S(f) / (2 pi)`` in
  unit^2 s/rad over ``angular_frequency`` w = 2 pi f [rad/s], the convention of the wave
  spectra in docs/theory/environment.md, with ``integral S(w) dw = variance``.

Spectral moments ``m_n = integral x^n S(x) dx`` (x = f or w, the PSD's own coordinate) are sums
over the PSD's uniform frequency grid times its spacing (the rectangle rule, which is the
discrete Parseval identity of the Welch estimate). Periods from moments: the mean zero
up-crossing period ``Tz = sqrt(m0 / m2)`` in the Hz convention (``2 pi sqrt(m0 / m2)`` in the
rad/s one), the mean period ``Tm01`` likewise from m0 / m1, the peak period ``Tp`` at the
maximum of the PSD.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from scipy.signal import welch

from floatmoor.post.statistics import time_window

__all__ = [
    "DEFAULT_SEGMENT_DURATION",
    "sampling_interval",
    "welch_psd",
    "spectral_moment",
    "spectral_moments",
    "zero_upcrossing_period",
    "mean_period",
    "peak_period",
]

#: Default Welch segment length [s]: 0.005 Hz resolution, ~100 segments in 3 h at 50 % overlap.
DEFAULT_SEGMENT_DURATION = 200.0

#: Relative spread of sampling intervals accepted as uniform (output times are k * dt, so
#: only round-off of t = k * dt is expected) [-].
_UNIFORM_RTOL = 1e-6

_COORDS = {
    False: ("frequency", {"long_name": "frequency", "units": "Hz"}),
    True: ("angular_frequency", {"long_name": "angular frequency", "units": "rad/s"}),
}


def sampling_interval(time: np.ndarray) -> float:
    """The uniform sampling interval of ``time`` [s]; ValueError if not uniform."""
    t = np.asarray(time, dtype=float)
    if t.size < 2:
        raise ValueError("sampling_interval: fewer than two samples")
    steps = np.diff(t)
    dt = float(np.mean(steps))
    if not dt > 0.0 or np.max(np.abs(steps - dt)) > _UNIFORM_RTOL * dt:
        raise ValueError("Welch PSD needs uniformly sampled time series; the time steps range "
                         f"from {steps.min():.6g} to {steps.max():.6g} s")
    return dt


def _squared(units: str) -> str:
    if not units:
        return "1"
    return f"{units}^2" if units.isalnum() else f"({units})^2"


def welch_psd(data: xr.DataArray, *, start: float,
              segment_duration: float = DEFAULT_SEGMENT_DURATION, overlap: float = 0.5,
              window: str = "hann", detrend: str | bool = "linear",
              angular: bool = False) -> xr.DataArray:
    """One-sided power spectral density by Welch's method, from ``start`` on.

    Parameters
    ----------
    data
        Uniformly sampled DataArray with a ``time`` dimension; the PSD is taken along time for
        every element of the other dimensions.
    start
        Samples before ``start`` [s] (the transient) are excluded.
    segment_duration
        Segment length [s]; the resolution is 1 / segment_duration [Hz]. Cut to the window's
        length if longer.
    overlap
        Fraction of a segment shared with the next, in [0, 1).
    window
        Window name passed to scipy.signal.welch (Hann by default).
    detrend
        ``"linear"``, ``"constant"`` or False, per segment.
    angular
        False: S(f) [unit^2/Hz] over ``frequency`` [Hz]. True: S(w) = S(f) / (2 pi)
        [unit^2 s/rad] over ``angular_frequency`` [rad/s].

    Returns
    -------
    DataArray
        The PSD, the time dimension replaced by the frequency one; attributes
        ``segment_duration``, ``overlap``, ``window``, ``detrend``, ``window_start``.
    """
    if not 0.0 <= overlap < 1.0:
        raise ValueError(f"welch_psd: overlap must be in [0, 1), got {overlap}")
    if not segment_duration > 0.0:
        raise ValueError(f"welch_psd: segment_duration must be > 0, got {segment_duration}")
    series = time_window(data, start=start)
    dt = sampling_interval(series["time"].values)
    n = series.sizes["time"]
    nperseg = int(min(n, max(2, round(segment_duration / dt))))
    noverlap = int(round(overlap * nperseg))
    other = [d for d in series.dims if d != "time"]
    values = series.transpose(*other, "time").values
    freq, psd = welch(values, fs=1.0 / dt, window=window, nperseg=nperseg, noverlap=noverlap,
                      detrend=detrend, return_onesided=True, scaling="density", axis=-1)
    if angular:
        freq, psd = 2.0 * math.pi * freq, psd / (2.0 * math.pi)
    name, coord_attrs = _COORDS[angular]
    coords = {k: v for k, v in series.coords.items() if "time" not in v.dims}
    coords[name] = (name, freq, coord_attrs)
    units = data.attrs.get("units", "")
    label = data.attrs.get("long_name", data.name or "series")
    attrs = {
        "long_name": f"power spectral density of {label}",
        "units": f"{_squared(units)}/Hz" if not angular else f"{_squared(units)} s/rad",
        "segment_duration": nperseg * dt,
        "overlap": noverlap / nperseg,
        "window": window,
        "detrend": str(detrend),
        "window_start": float(start),
    }
    return xr.DataArray(psd, dims=(*other, name), coords=coords, attrs=attrs,
                        name=f"{data.name}_psd" if data.name else "psd")


def _axis(psd: xr.DataArray) -> tuple[str, bool]:
    for angular, (name, _) in _COORDS.items():
        if name in psd.dims:
            return name, angular
    raise ValueError(f"expected a PSD over 'frequency' or 'angular_frequency', got {psd.dims}")


def spectral_moment(psd: xr.DataArray, order: int) -> xr.DataArray:
    """Spectral moment ``m_n = integral x^n S(x) dx`` over the PSD's own frequency axis.

    Parameters
    ----------
    psd
        A PSD from :func:`welch_psd` (or any density over a uniform ``frequency`` [Hz] or
        ``angular_frequency`` [rad/s] grid).
    order
        n >= 0.

    Returns
    -------
    DataArray
        m_n per element of the other dimensions, in the convention of the PSD's axis.
    """
    name, angular = _axis(psd)
    x = np.asarray(psd[name].values, dtype=float)
    step = float(np.mean(np.diff(x)))
    moment = (psd * psd[name] ** order).sum(name) * step
    axis_units = "(rad/s)" if angular else "Hz"
    base = psd.attrs.get("units", "").rsplit("/Hz", 1)[0].rsplit(" s/rad", 1)[0]
    units = base if order == 0 else f"{base} {axis_units}^{order}"
    return moment.assign_attrs(long_name=f"spectral moment m{order}", units=units)


def spectral_moments(psd: xr.DataArray, orders: tuple[int, ...] = (0, 1, 2, 4)) -> xr.Dataset:
    """Spectral moments ``m0, m1, m2, m4`` (or ``orders``) as a Dataset of ``m<n>``.

    Parameters
    ----------
    psd
        A one-sided power spectral density along ``frequency`` [Hz] (:func:`welch_psd`).
    orders
        The moments' orders n.

    Returns
    -------
    xarray.Dataset
        ``m<n>`` = integral of f^n S(f) df, one variable per order."""
    return xr.Dataset({f"m{k}": spectral_moment(psd, k) for k in orders})


def zero_upcrossing_period(psd: xr.DataArray) -> xr.DataArray:
    """Mean zero up-crossing period ``Tz`` [s] from m0 and m2 (Rice)."""
    _, angular = _axis(psd)
    factor = 2.0 * math.pi if angular else 1.0
    tz = factor * np.sqrt(spectral_moment(psd, 0) / spectral_moment(psd, 2))
    return tz.assign_attrs(long_name="mean zero up-crossing period Tz", units="s")


def mean_period(psd: xr.DataArray) -> xr.DataArray:
    """Mean period ``Tm01`` = m0 / m1 [s] (times 2 pi in the rad/s convention)."""
    _, angular = _axis(psd)
    factor = 2.0 * math.pi if angular else 1.0
    tm = factor * spectral_moment(psd, 0) / spectral_moment(psd, 1)
    return tm.assign_attrs(long_name="mean period Tm01", units="s")


def peak_period(psd: xr.DataArray) -> xr.DataArray:
    """Peak period ``Tp`` [s]: the period of the PSD's largest ordinate (grid resolution)."""
    name, angular = _axis(psd)
    peak = psd[name].isel({name: psd.argmax(name)}).drop_vars(name)
    factor = 2.0 * math.pi if angular else 1.0
    tp = factor / peak
    return tp.assign_attrs(long_name="peak period Tp", units="s")
