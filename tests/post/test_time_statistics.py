"""Channel statistics on DataArrays (mean, STD, min, max, skewness, Pearson kurtosis)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from scipy import stats

from floatmoor.post.statistics import channel_statistics, time_statistics, time_window

#: Agreement with scipy.stats and channel_statistics on the same samples: round-off only [-].
ROUNDOFF_RTOL = 1e-10
#: Sample skewness / kurtosis of 2e5 independent Gaussian samples: their standard errors are
#: sqrt(6 / n) = 0.0055 and sqrt(24 / n) = 0.011; the bound is about 4 standard errors [-].
GAUSSIAN_SKEW_ATOL = 0.025
GAUSSIAN_KURT_ATOL = 0.045


def _record(rng: np.random.Generator) -> xr.DataArray:
    t = np.arange(0.0, 100.0, 0.01)
    sine = 5.0 + 2.0 * np.sin(2 * np.pi * t)  # 100 whole periods after t = 0
    skewed = rng.gamma(2.0, 1.0, t.size)
    values = np.stack((sine, skewed))
    values[:, t < 10.0] = 1e3  # a transient before start = 10 s
    return xr.DataArray(values, dims=("line", "time"), coords={"line": ["1", "2"], "time": t},
                        name="fairlead_tension",
                        attrs={"long_name": "line tension at the fairlead", "units": "N"})


def test_moments_against_closed_forms_and_scipy(rng):
    da = _record(rng)
    s = time_statistics(da, start=10.0)
    assert s.attrs["window_start"] == 10.0
    # a sine of amplitude A: std A / sqrt(2), skewness 0, kurtosis m4 / m2^2 = 3/2
    sine = s.sel(line="1")
    assert float(sine["mean"]) == pytest.approx(5.0, rel=1e-12)
    assert float(sine["std"]) == pytest.approx(2.0 / np.sqrt(2.0), rel=1e-12)
    assert float(sine["skewness"]) == pytest.approx(0.0, abs=1e-10)
    assert float(sine["kurtosis"]) == pytest.approx(1.5, rel=1e-10)
    # scipy's biased skewness and Pearson kurtosis, and channel_statistics, on each line
    for line in ("1", "2"):
        window = da.sel(line=line).values[da["time"].values >= 10.0]
        assert float(s["skewness"].sel(line=line)) == pytest.approx(
            stats.skew(window, bias=True), rel=ROUNDOFF_RTOL, abs=1e-12)
        assert float(s["kurtosis"].sel(line=line)) == pytest.approx(
            stats.kurtosis(window, fisher=False, bias=True), rel=ROUNDOFF_RTOL)
        reference = channel_statistics(da["time"].values, da.sel(line=line).values, start=10.0)
        for key in ("mean", "std", "min", "max"):
            assert float(s[key].sel(line=line)) == pytest.approx(reference[key],
                                                                 rel=ROUNDOFF_RTOL)
    assert s["std"].attrs["units"] == "N" and s["kurtosis"].attrs["units"] == "1"
    assert "Pearson" in s["kurtosis"].attrs["long_name"]


def test_gaussian_samples_have_skewness_0_and_kurtosis_3(rng):
    t = np.arange(200_000) * 0.1
    da = xr.DataArray(rng.normal(3.0, 2.0, t.size), dims="time", coords={"time": t})
    s = time_statistics(da, start=0.0)
    assert float(s["skewness"]) == pytest.approx(0.0, abs=GAUSSIAN_SKEW_ATOL)
    assert float(s["kurtosis"]) == pytest.approx(3.0, abs=GAUSSIAN_KURT_ATOL)


def test_constant_record_and_bad_windows():
    t = np.arange(10.0)
    s = time_statistics(xr.DataArray(np.ones(10), dims="time", coords={"time": t}), start=0.0)
    assert float(s["std"]) == 0.0 and np.isnan(float(s["skewness"]))
    assert np.isnan(float(s["kurtosis"]))
    with pytest.raises(ValueError, match="fewer than two samples"):
        time_window(xr.DataArray(np.ones(10), dims="time", coords={"time": t}), start=9.5)
    with pytest.raises(ValueError, match="'time' dimension"):
        time_window(xr.DataArray(np.ones(3), dims="x"), start=0.0)
