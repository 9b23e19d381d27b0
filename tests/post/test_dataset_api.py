"""The analysis functions on a dataset shaped as floatmoor writes it: ``fairlead_tension``
(line, time) with a ``model`` coordinate on ``line``; results keep the other dimensions and
coordinates and carry ``units`` and ``long_name``."""

from __future__ import annotations

import numpy as np
import xarray as xr

from floatmoor.io.variables import attributes
from floatmoor.post.extremes import exceedance_probability, extrema
from floatmoor.post.fatigue import (
    DNV_STUDLESS_CHAIN,
    chain_nominal_area,
    damage_equivalent_load,
    fatigue_damage,
)
from floatmoor.post.spectra import spectral_moments, welch_psd, zero_upcrossing_period
from floatmoor.post.statistics import time_statistics

#: White-noise PSD level and Tz against their closed forms; measured within 0.8 % [-].
WHITE_NOISE_RTOL = 0.02


def _dataset(rng: np.random.Generator) -> xr.Dataset:
    time = np.arange(0.0, 1200.0, 0.1)
    tension = 1.0e6 + 1.0e5 * rng.standard_normal((3, time.size))
    return xr.Dataset(
        {"fairlead_tension": (("line", "time"), tension, attributes("fairlead_tension"))},
        coords={"time": ("time", time, attributes("time")),
                "line": ("line", ["1", "2", "3"], attributes("line")),
                "model": ("line", ["quasi-static", "quasi-dynamic", "dynamic"])})


def test_every_function_keeps_line_and_model_and_labels_its_result(rng):
    tension = _dataset(rng)["fairlead_tension"]
    area = chain_nominal_area(0.0779)
    psd = welch_psd(tension, start=100.0)
    results = [
        *time_statistics(tension, start=100.0).data_vars.values(),
        psd, zero_upcrossing_period(psd), *spectral_moments(psd).data_vars.values(),
        extrema(tension, start=100.0),
        *exceedance_probability(tension, start=100.0).data_vars.values(),
        fatigue_damage(tension, DNV_STUDLESS_CHAIN, start=100.0, nominal_area=area),
        damage_equivalent_load(tension, 3.0, start=100.0),
    ]
    for result in results:
        assert result.dims[0] == "line" and "time" not in result.dims, result.name
        assert list(result["model"].values) == ["quasi-static", "quasi-dynamic", "dynamic"]
        assert result.attrs["units"] and result.attrs["long_name"], result.name
    assert psd.attrs["units"] == "N^2/Hz"
    # White noise sampled at dt: a flat one-sided PSD 2 sigma^2 dt (sigma^2 the record's own
    # variance) up to the Nyquist frequency f_N, so Tz = sqrt(m0 / m2) = sqrt(3) / f_N.
    f_nyquist = 0.5 / 0.1
    np.testing.assert_allclose(zero_upcrossing_period(psd).values, np.sqrt(3) / f_nyquist,
                               rtol=WHITE_NOISE_RTOL)
    variance = tension.sel(time=slice(100.0, None)).var("time").values
    np.testing.assert_allclose(psd.mean("frequency").values, 2 * variance * 0.1,
                               rtol=WHITE_NOISE_RTOL)
