"""The NPD (Froya) spectrum and profile (DNV-RP-C205 2.3.4)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from floatmoor.wind.spectrum import (npd_band_variance, npd_fraction_below, npd_profile,
                                     npd_spectrum, npd_variance, speed_at_10m)

#: quad's attained accuracy on a smooth integrand, well above its error estimate.
QUAD_RTOL = 1e-7


@pytest.mark.parametrize("u0, z", [(10.0, 10.0), (10.85, 90.0), (25.0, 50.0)])
def test_variance_closed_form_equals_integral_of_spectrum(u0, z):
    # the Beta-function closed form (substitution y = f~^n) against direct quadrature
    a = 172.0 * (z / 10) ** (2 / 3) * (u0 / 10) ** -0.75
    integral = quad(lambda x: npd_spectrum(x / a, u0, z) / a, 0.0, np.inf, limit=400)[0]
    assert npd_variance(u0, z) == pytest.approx(integral, rel=QUAD_RTOL)
    band = quad(lambda f: npd_spectrum(f, u0, z), 1e-3, 0.5, limit=400)[0]
    assert npd_band_variance(1e-3, 0.5, u0, z) == pytest.approx(band, rel=QUAD_RTOL)


def test_spectrum_definition_values():
    # S(0) = 320 (U0/10)^2 (z/10)^0.45; at f~ = 1, S = S(0) 2^(-5/(3n)) (DNV-RP-C205 2.3.4)
    u0, z = 20.0, 40.0
    s0 = 320.0 * 4.0 * 4.0 ** 0.45
    f1 = 1.0 / (172.0 * 4.0 ** (2 / 3) * 2.0 ** -0.75)
    assert npd_spectrum(0.0, u0, z) == pytest.approx(s0, rel=1e-14)
    assert npd_spectrum(f1, u0, z) == pytest.approx(s0 * 2.0 ** (-5 / (3 * 0.468)), rel=1e-12)


def test_inertial_subrange_slope():
    # Kolmogorov: S ~ f^(-5/3) at high frequency; at f~ ~ 1e4 the log slope is within 1 %
    f = np.array([20.0, 40.0])
    s = npd_spectrum(f, 10.0, 90.0)
    slope = math.log(s[1] / s[0]) / math.log(2.0)
    assert slope == pytest.approx(-5 / 3, rel=0.01)


def test_fraction_below_is_a_distribution():
    fr = npd_fraction_below(np.array([0.0, 1e-3, 1e-2, np.inf]), 10.85, 90.0)
    assert fr[0] == 0.0 and fr[-1] == pytest.approx(1.0, abs=1e-15)
    assert np.all(np.diff(fr) > 0.0)


def test_profile_and_its_inverse():
    # U(z) = U0 (1 + C ln(z/10)), C = 0.0573 sqrt(1 + 0.148 U0)
    u0 = 10.0
    c = 5.73e-2 * math.sqrt(1 + 1.48)
    assert npd_profile(u0, 90.0) == pytest.approx(u0 * (1 + c * math.log(9.0)), rel=1e-14)
    assert npd_profile(u0, 10.0) == u0
    u10 = speed_at_10m(13.05, 90.0)
    assert npd_profile(u10, 90.0) == pytest.approx(13.05, rel=1e-12)
    assert u10 == pytest.approx(10.846, abs=1e-3)


def test_rejects_bad_inputs():
    with pytest.raises(ValueError, match="10 m mean wind speed"):
        npd_spectrum(0.1, 0.0, 90.0)
    with pytest.raises(ValueError, match="height"):
        npd_variance(10.0, -1.0)
