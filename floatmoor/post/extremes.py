"""Local maxima and minima of time series and their empirical probability of exceedance.

Physics reference: docs/theory/post_processing.md (quasi-dynamic paper section 5.2, its Figure 14 plots
the probability of exceedance of the local maxima and minima of fairlead tension).

Two definitions of the extrema, chosen by ``method``:

* ``"local"`` (default, as the paper's Figure 14): every sample larger (smaller) than its
  neighbours, a plateau counting once; the record's end samples are not extrema;
* ``"crossing"``: one maximum and one minimum per interval between successive up-crossings
  of the window's mean (the crest and trough of each zero up-crossing wave); parts before the
  first and after the last up-crossing are dropped.

Probability of exceedance by the Weibull plotting position: with the n maxima sorted in
decreasing order, the i-th (i = 1..n) is exceeded with probability ``i / (n + 1)``. For minima
the probability is that of falling below: sorted in increasing order, the i-th has
``P[X < x_i] = i / (n + 1)``.

For a narrow-band Gaussian process of standard deviation sigma, the maxima above the mean are
Rayleigh distributed, ``P[A > a] = exp(-a^2 / (2 sigma^2))`` (Longuet-Higgins 1952):
:func:`rayleigh_exceedance`.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from floatmoor.post.statistics import time_window

__all__ = ["local_extrema", "extrema", "exceedance_probability", "rayleigh_exceedance"]

Kind = Literal["maxima", "minima"]
Method = Literal["local", "crossing"]


def local_extrema(values: ArrayLike, kind: Kind = "maxima",
                  method: Method = "local") -> NDArray[np.float64]:
    """Local maxima or minima of one record, in time order.

    Parameters
    ----------
    values
        Samples, shape (n,).
    kind
        ``"maxima"`` or ``"minima"``.
    method
        ``"local"`` (every local extremum) or ``"crossing"`` (one per mean up-crossing
        interval); see the module docstring.

    Returns
    -------
    ndarray
        The extreme values.
    """
    x = np.asarray(values, dtype=float)
    if kind not in ("maxima", "minima"):
        raise ValueError(f"kind must be 'maxima' or 'minima', got {kind!r}")
    if method == "local":
        keep = np.concatenate(([True], np.diff(x) != 0.0))
        y = x[keep]  # plateaus collapse to one sample
        if y.size < 3:
            return np.empty(0)
        left, mid, right = y[:-2], y[1:-1], y[2:]
        mask = (mid > left) & (mid > right) if kind == "maxima" else \
            (mid < left) & (mid < right)
        return mid[mask]
    if method == "crossing":
        above = x >= x.mean()
        up = np.flatnonzero(~above[:-1] & above[1:]) + 1
        if up.size < 2:
            return np.empty(0)
        reduce = np.maximum if kind == "maxima" else np.minimum
        return reduce.reduceat(x[: up[-1]], up[:-1])
    raise ValueError(f"method must be 'local' or 'crossing', got {method!r}")


def extrema(data: xr.DataArray, *, start: float, kind: Kind = "maxima",
            method: Method = "local") -> xr.DataArray:
    """Local maxima or minima of every series of ``data`` from ``start`` on.

    Parameters
    ----------
    data
        DataArray with a ``time`` dimension, e.g. ``ds["fairlead_tension"]``.
    start
        Samples before ``start`` [s] are excluded.
    kind, method
        As :func:`local_extrema`.

    Returns
    -------
    DataArray
        Dims (other dims..., ``peak``): the extrema in time order, NaN-padded to the longest
        series.
    """
    window = time_window(data, start=start)
    other = [d for d in window.dims if d != "time"]
    values = window.transpose(*other, "time").values
    flat = values.reshape(-1, values.shape[-1])
    found = [local_extrema(row, kind, method) for row in flat]
    n_max = max((f.size for f in found), default=0)
    out = np.full((flat.shape[0], n_max), np.nan)
    for i, f in enumerate(found):
        out[i, : f.size] = f
    out = out.reshape(*values.shape[:-1], n_max)
    coords = {k: v for k, v in window.coords.items() if "time" not in v.dims}
    label = data.attrs.get("long_name", data.name or "series")
    return xr.DataArray(out, dims=(*other, "peak"), coords=coords, attrs={
        "long_name": f"local {kind} ({method}) of {label} from t = {start:g} s",
        "units": data.attrs.get("units", "")})


def exceedance_probability(data: xr.DataArray, *, start: float, kind: Kind = "maxima",
                           method: Method = "local") -> xr.Dataset:
    """Empirical probability of exceedance of the local maxima (or minima) from ``start`` on.

    Parameters
    ----------
    data
        DataArray with a ``time`` dimension, e.g. ``ds["fairlead_tension"]``.
    start
        Samples before ``start`` [s] are excluded.
    kind, method
        As :func:`local_extrema`.

    Returns
    -------
    Dataset
        Over (other dims..., ``rank``): ``value``, the extrema sorted from the most extreme
        (decreasing maxima, increasing minima), and ``probability``, ``i / (n + 1)`` for rank
        i = 1..n of each series (the probability of exceeding, or for minima of falling below,
        ``value``); NaN-padded past each series' count.
    """
    peaks = extrema(data, start=start, kind=kind, method=method)
    values = peaks.values
    ordered = np.sort(values, axis=-1)  # NaNs last
    if kind == "maxima":
        ordered = -np.sort(-values, axis=-1)
    count = np.sum(np.isfinite(values), axis=-1, keepdims=True)
    rank = np.arange(1, values.shape[-1] + 1)
    probability = np.where(rank <= count, rank / (count + 1.0), np.nan)
    dims = peaks.dims[:-1] + ("rank",)
    coords = dict(peaks.coords)
    coords["rank"] = ("rank", rank, {"long_name": "rank from the most extreme", "units": "1"})
    side = "exceedance" if kind == "maxima" else "non-exceedance"
    return xr.Dataset({
        "value": (dims, ordered, {"long_name": peaks.attrs["long_name"] + ", sorted",
                                  "units": peaks.attrs["units"]}),
        "probability": (dims, probability,
                        {"long_name": f"probability of {side} (Weibull plotting position "
                                      "i / (n + 1))", "units": "1"}),
    }, coords=coords)


def rayleigh_exceedance(amplitude: ArrayLike, std: ArrayLike) -> NDArray[np.float64]:
    """Rayleigh probability of exceedance ``exp(-a^2 / (2 sigma^2))`` of amplitudes a >= 0.

    Parameters
    ----------
    amplitude
        Maxima measured from the mean of the process.
    std
        Standard deviation sigma of the (narrow-band Gaussian) process.
    """
    a = np.clip(np.asarray(amplitude, dtype=float), 0.0, None)
    s = np.asarray(std, dtype=float)
    return np.exp(-(a**2) / (2.0 * s**2))
