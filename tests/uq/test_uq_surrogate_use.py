"""Using a surrogate: file round trip, confidence bands, densities, sampling."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from floatmoor import uq
from floatmoor.uq.taut_string import taut_string

INPUTS = [uq.UncertainInput("T", "uniform", {"lower": 100.0, "upper": 116.0}),
          uq.UncertainInput("m", "uniform", {"lower": 1.0, "upper": 5.0})]
#: Positions along the string [m]: a vector output (the whole string, as the paper's Fig. 2b).
X = np.linspace(0.25, 2.75, 11)


@pytest.fixture(scope="module")
def string_surrogate() -> uq.Surrogate:
    return uq.propagate(lambda z: taut_string(T=z[0], m=z[1], x=X), INPUTS,
                        uq.QuadratureMethod(7))


def test_save_load_round_trip(tmp_path, string_surrogate):
    path = tmp_path / "string.nc"
    string_surrogate.save(path, {"study": "case E"}, output_units="m")
    loaded = uq.Surrogate.load(path)
    x = uq.designs.lhs_design(INPUTS, 200, seed=5)
    np.testing.assert_array_equal(loaded.evaluate(x), string_surrogate.evaluate(x))
    for name in ("mean", "variance", "sobol_first", "sobol_total", "validation_error",
                 "coefficients", "multi_indices"):
        np.testing.assert_array_equal(getattr(loaded, name), getattr(string_surrogate, name))
    assert loaded.inputs == string_surrogate.inputs
    assert (loaded.method, loaded.order, loaded.n_runs) == ("quadrature", 7, 64)
    with xr.open_dataset(path, engine="scipy") as ds:
        for name, var in ds.variables.items():
            assert "units" in var.attrs and "long_name" in var.attrs, name
        assert ds["mean"].attrs["units"] == "m" and ds["variance"].attrs["units"] == "(m)^2"
        assert {"floatmoor_version", "created", "study"} <= set(ds.attrs)


#: A band holds its level of new model outputs within 4 binomial standard errors.
STANDARD_ERRORS = 4.0


def test_bands_hold_their_level_of_model_outputs(string_surrogate):
    level, n = 0.9, 4000
    lower, upper = string_surrogate.bands(level, n=20000, seed=1)
    assert np.all(lower < string_surrogate.mean) and np.all(string_surrogate.mean < upper)
    rng = np.random.default_rng(3)
    t, m = rng.uniform(100, 116, n), rng.uniform(1, 5, n)
    y = taut_string(T=t[:, None], m=m[:, None], x=X)
    inside = np.mean((y >= lower) & (y <= upper), axis=0)
    assert np.all(abs(inside - level) < STANDARD_ERRORS * np.sqrt(level * (1 - level) / n))


#: The kernel density integrates to 1 over a grid wide enough for its tails; the trapezoid
#: rule on 4001 points of a smooth density errs by far less.
UNIT_MASS = 1e-3


def test_density_integrates_to_one_and_follows_the_model(string_surrogate):
    middle = 5                                    # x = 1.5 m, the paper's point
    grid = np.linspace(-2.0, 2.0, 4001)
    density = string_surrogate.density(middle, grid, n=3000, seed=2)
    assert np.all(density >= 0.0)
    assert np.trapezoid(density, grid) == pytest.approx(1.0, abs=UNIT_MASS)
    # its mean is the surrogate's mean (Gaussian kernels keep the sample mean) within 4
    # standard errors of a mean of 3000 samples
    mean = np.trapezoid(grid * density, grid)
    assert mean == pytest.approx(string_surrogate.mean[middle],
                                 abs=4 * string_surrogate.std[middle] / np.sqrt(3000))


def test_samples_are_reproducible(string_surrogate):
    a = string_surrogate.sample(100, seed=9)
    np.testing.assert_array_equal(a, string_surrogate.sample(100, seed=9))
    assert a.shape == (100, X.size)
    assert not np.array_equal(a, string_surrogate.sample(100, seed=10))
    np.testing.assert_array_equal(uq.designs.lhs_design(INPUTS, 30, 4),
                                  uq.designs.lhs_design(INPUTS, 30, 4))


def test_density_of_a_constant_output_is_refused():
    nodes, weights = uq.designs.quadrature_design(INPUTS, 1)
    s = uq.Surrogate.fit_quadrature(INPUTS, 1, nodes, weights, np.ones(len(nodes)))
    with pytest.raises(ValueError, match="does not vary"):
        s.density(0, np.linspace(0, 2, 5))
