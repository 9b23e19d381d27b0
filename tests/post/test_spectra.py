"""Welch PSD of a synthetic JONSWAP realisation: its integral is the signal variance and its
moments are the target spectrum's
(docs/development.md#case-532-spectra)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from floatmoor.post.spectra import (
    DEFAULT_SEGMENT_DURATION,
    mean_period,
    peak_period,
    sampling_interval,
    spectral_moment,
    spectral_moments,
    welch_psd,
    zero_upcrossing_period,
)
from tests.post.synthetic import jonswap, realisation

#: Integral of the PSD against the record's variance (the acceptance criterion) [-].
VARIANCE_RTOL = 0.01
#: Moments m0, m1, m2 and Tz of the estimate against the target JONSWAP. Sources of error:
#: the Hann window's leakage over 0.005 Hz bins and the random-phase estimate's scatter
#: (~100 segments); measured worst 0.7 % (m2, seed 0) [-].
MOMENT_RTOL = 0.02
#: Energy of the spectral peak band (0.8 to 1.2 w_p, 5 bins of ~190 degrees of freedom each):
#: random scatter ~3 % per realisation; measured worst 1.0 % [-].
PEAK_BAND_RTOL = 0.05
#: Peak period: the estimate's peak lies within one 0.005 Hz bin of the target's [Hz].
PEAK_FREQUENCY_ATOL = 1.0 / DEFAULT_SEGMENT_DURATION

#: LC34 sea state (docs/cases/deepcwind.md): Hs 10.5 m, Tp 14.3 s; gamma 3.3 (the standard JONSWAP value).
HS, TP, GAMMA = 10.5, 14.3, 3.3
#: 3-hour full-scale record at 4 Hz.
DT, DURATION = 0.25, 10800.0


@pytest.fixture(scope="module")
def elevation() -> xr.DataArray:
    n = int(DURATION / DT)
    rng = np.random.default_rng(7)
    # two independent realisations, to check the vectorisation over a second dimension
    records = []
    for _ in range(2):
        time, x, _ = realisation(lambda f: 2 * np.pi * jonswap(2 * np.pi * f, HS, TP, GAMMA),
                                 n, DT, rng)
        records.append(x)
    return xr.DataArray(np.array(records), dims=("seed", "time"),
                        coords={"seed": [0, 1], "time": time}, name="elevation",
                        attrs={"long_name": "wave elevation", "units": "m"})


def _target_moment(order: int, f_max: float) -> float:
    f = np.linspace(0.0, f_max, 200_001)
    s_f = 2 * np.pi * jonswap(2 * np.pi * f, HS, TP, GAMMA)
    return float(np.trapezoid(f**order * s_f, f))


def test_welch_integrates_to_the_variance(elevation):
    psd = welch_psd(elevation, start=0.0)
    m0 = spectral_moment(psd, 0)
    np.testing.assert_allclose(m0.values, elevation.var("time").values, rtol=VARIANCE_RTOL)
    assert psd.dims == ("seed", "frequency")
    assert psd.attrs["units"] == "m^2/Hz" and psd["frequency"].attrs["units"] == "Hz"
    df = float(psd["frequency"][1] - psd["frequency"][0])
    assert df == pytest.approx(1.0 / DEFAULT_SEGMENT_DURATION, rel=1e-9)
    # a target of 4 sqrt(m0) = Hs
    np.testing.assert_allclose(4 * np.sqrt(m0.values), HS, rtol=VARIANCE_RTOL)


def test_welch_moments_match_the_target_spectrum(elevation):
    psd = welch_psd(elevation, start=0.0)
    f_max = float(psd["frequency"][-1])
    moments = spectral_moments(psd, orders=(0, 1, 2))
    for k in (0, 1, 2):
        np.testing.assert_allclose(moments[f"m{k}"].values, _target_moment(k, f_max),
                                   rtol=MOMENT_RTOL, err_msg=f"m{k}")
    tz_target = np.sqrt(_target_moment(0, f_max) / _target_moment(2, f_max))
    np.testing.assert_allclose(zero_upcrossing_period(psd).values, tz_target, rtol=MOMENT_RTOL)
    tm_target = _target_moment(0, f_max) / _target_moment(1, f_max)
    np.testing.assert_allclose(mean_period(psd).values, tm_target, rtol=MOMENT_RTOL)
    np.testing.assert_allclose(1.0 / peak_period(psd).values, 1.0 / TP,
                               atol=PEAK_FREQUENCY_ATOL)


def test_angular_convention_is_the_same_spectrum(elevation):
    hz = welch_psd(elevation, start=0.0)
    rad = welch_psd(elevation, start=0.0, angular=True)
    assert rad.dims == ("seed", "angular_frequency") and rad.attrs["units"] == "m^2 s/rad"
    np.testing.assert_allclose(rad.values, hz.values / (2 * np.pi), rtol=1e-14)
    np.testing.assert_allclose(spectral_moment(rad, 0), spectral_moment(hz, 0), rtol=1e-12)
    np.testing.assert_allclose(zero_upcrossing_period(rad), zero_upcrossing_period(hz),
                               rtol=1e-12)
    np.testing.assert_allclose(peak_period(rad), peak_period(hz), rtol=1e-12)
    # the wave spectrum S(w) of docs/theory/environment.md is recovered around its peak: the energy
    # in the bins within 0.8 to 1.2 w_p against the target integrated over the same bins
    wp = 2 * np.pi / TP
    dw = float(rad["angular_frequency"][1] - rad["angular_frequency"][0])
    band = rad.sel(angular_frequency=slice(0.8 * wp, 1.2 * wp))
    w = band["angular_frequency"].values
    fine = np.linspace(w[0] - dw / 2, w[-1] + dw / 2, 20_001)
    target = np.trapezoid(jonswap(fine, HS, TP, GAMMA), fine)
    np.testing.assert_allclose(band.sum("angular_frequency").values * dw, target,
                               rtol=PEAK_BAND_RTOL)


def test_start_excludes_the_transient_and_vectorisation(elevation):
    spoiled = elevation.copy()
    spoiled[:, :400] += 50.0  # a 100 s transient
    clean = welch_psd(elevation.isel(time=slice(400, None)), start=0.0)
    cut = welch_psd(spoiled, start=100.0)
    np.testing.assert_allclose(cut.values, clean.values, rtol=1e-12)
    one = welch_psd(elevation.sel(seed=1), start=0.0)
    both = welch_psd(elevation, start=0.0)
    np.testing.assert_allclose(both.sel(seed=1).values, one.values, rtol=1e-12)


def test_non_uniform_sampling_is_refused():
    assert sampling_interval(np.arange(10) * 0.1) == pytest.approx(0.1)
    with pytest.raises(ValueError, match="uniformly"):
        sampling_interval(np.array([0.0, 0.1, 0.3, 0.4]))
