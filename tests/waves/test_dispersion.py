"""Linear dispersion relation omega^2 = g k tanh(kh): residual, limits, a tabulated root."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.dispersion import (angular_frequency, group_velocity, wavelength,
                                        wavenumber)

G = 9.81
#: Residual of the dispersion relation; docs/development.md#case-531-dispersion-relation
#: asks 1e-10 (WEC-Sim bemioTest), the
#: Newton iteration stops at a few ulps so 1e-13 is the honest bound.
RESIDUAL_RTOL = 1e-13
#: x tanh x = 1 has the root 1.19967864025773383391636984864 (published to 30 digits, e.g. as
#: the fold of the catenoid / C_CFP constant); compared to double precision.
ROOT_X_TANH_X_EQ_1 = 1.1996786402577338339
TABULATED_RTOL = 1e-14


def test_residual_over_six_decades_of_kh():
    omega = np.logspace(-3, 2, 400)
    for depth in (0.9, 50.0, 200.0, 4000.0):
        k = wavenumber(omega, depth, G)
        rel = np.abs(G * k * np.tanh(k * depth) - omega ** 2) / omega ** 2
        assert rel.max() < RESIDUAL_RTOL, (depth, rel.max())


def test_tabulated_root():
    # omega^2 h / g = 1  <=>  kh tanh(kh) = 1
    k = wavenumber(1.0, 1.0, 1.0)
    assert abs(float(k) - ROOT_X_TANH_X_EQ_1) < TABULATED_RTOL * ROOT_X_TANH_X_EQ_1


def test_deep_water_limit():
    omega = np.linspace(0.1, 5.0, 50)
    np.testing.assert_allclose(wavenumber(omega, math.inf, G), omega ** 2 / G, rtol=0, atol=0)
    # kh > 20: tanh(kh) = 1 to double precision, so k = omega^2 / g
    depth = 25.0 * G / omega[0] ** 2
    np.testing.assert_allclose(wavenumber(omega, depth, G), omega ** 2 / G, rtol=1e-15)


def test_shallow_water_limit():
    # kh -> 0: omega = k sqrt(gh) (1 - (kh)^2/6 + O((kh)^4)), so the relative deviation from the
    # series is O((kh)^4) ~ 1e-12 at kh ~ 1e-3.
    depth = 10.0
    omega = np.array([1e-4, 3e-4, 1e-3])
    k = wavenumber(omega, depth, G)
    kh = k * depth
    assert kh.max() < 2e-3
    series = omega / math.sqrt(G * depth) * (1.0 + kh ** 2 / 6.0)
    np.testing.assert_allclose(k, series, rtol=1e-11)
    # and the leading term alone is off by (kh)^2/6, which the test above would catch
    assert np.all(np.abs(k * math.sqrt(G * depth) / omega - 1.0) > 0.1 * kh ** 2 / 6.0)


def test_inverse_and_wavelength():
    omega = np.linspace(0.05, 4.0, 30)
    k = wavenumber(omega, 35.0, G)
    np.testing.assert_allclose(angular_frequency(k, 35.0, G), omega, rtol=1e-14)
    np.testing.assert_allclose(wavelength(2 * np.pi / omega, 35.0, G), 2 * np.pi / k,
                               rtol=1e-14)
    assert float(wavelength(10.0, math.inf, G)) == pytest.approx(G * 100 / (2 * np.pi),
                                                                   rel=1e-15)


def test_group_velocity_limits_and_derivative():
    assert float(group_velocity(1.0, math.inf, G)) == pytest.approx(G / 2.0, rel=1e-15)
    assert float(group_velocity(1e-4, 10.0, G)) == pytest.approx(math.sqrt(G * 10.0), rel=1e-8)
    omega = np.array([0.3, 0.8, 1.5])
    dw = 1e-6 * omega
    dk = wavenumber(omega + dw, 30.0, G) - wavenumber(omega - dw, 30.0, G)
    np.testing.assert_allclose(group_velocity(omega, 30.0, G), 2 * dw / dk, rtol=1e-7)


@pytest.mark.parametrize("omega, depth, g", [(0.0, 10.0, G), (-1.0, 10.0, G),
                                             (np.nan, 10.0, G), (1.0, 0.0, G),
                                             (1.0, -5.0, G), (1.0, 10.0, 0.0)])
def test_bad_input_raises(omega, depth, g):
    with pytest.raises(ValueError):
        wavenumber(omega, depth, g)
