"""Wave settings dataclasses: validation messages and the sea they realise (realise_sea)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.case.sea import JonswapSettings, RegularWaveSettings, StillWaterSettings
from floatmoor.waves.realisation import realise_sea

G = 9.81


def test_build_regular_converts_degrees():
    field = realise_sea(RegularWaveSettings(height=2.0, period=8.0, direction_deg=30.0,
                                      phase_deg=90.0), 100.0, G, 600.0)
    assert field.n_components == 1
    assert field.direction[0] == pytest.approx(math.radians(30.0))
    assert field.phase[0] == pytest.approx(math.pi / 2)
    assert field.amplitude[0] == 1.0
    # crest at the origin a quarter period after t = 0
    t = np.linspace(0, 8, 8001)
    assert t[np.argmax(field.elevation(t))] == pytest.approx(2.0, abs=1e-3)


def test_build_jonswap_defaults_and_variants():
    s = JonswapSettings(hs=4.0, tp=10.0, seed=3)
    field = realise_sea(s, 200.0, G, 10800.0)
    lo, hi = s.band()
    assert (lo, hi) == pytest.approx((0.5 * 2 * np.pi / 10, 4 * 2 * np.pi / 10))
    assert field.info["spacing"] == "equal" and field.repeat_period >= 10800.0
    assert field.info["variance_fraction"] > 0.99
    r = realise_sea(JonswapSettings(hs=4.0, tp=10.0, seed=3, spacing="random-in-bin",
                              n_components=200, omega_min=0.3, omega_max=2.0), 200.0, G, 10800)
    assert r.n_components == 200 and math.isinf(r.repeat_period)
    assert realise_sea(StillWaterSettings(), 200.0, G, 10.0).n_components == 0


@pytest.mark.parametrize("settings, depth, message", [
    (RegularWaveSettings(height=0.0, period=8.0), math.inf, "height"),
    (RegularWaveSettings(height=1.0, period=-1.0), math.inf, "period"),
    (RegularWaveSettings(height=1.0, period=float("nan")), math.inf, "period"),
    (RegularWaveSettings(height=20.0, period=8.0), math.inf, "1/7"),   # H/lambda = 0.2
    (RegularWaveSettings(height=4.0, period=20.0), 5.0, "0.78"),
    (JonswapSettings(hs=-1.0, tp=10.0, seed=1), math.inf, "hs"),
    (JonswapSettings(hs=1.0, tp=0.0, seed=1), math.inf, "tp"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=1, gamma=0.9), math.inf, "gamma"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=1, gamma=11.0), math.inf, "gamma"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=-3), math.inf, "seed"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=1.5), math.inf, "seed"),
    (JonswapSettings(hs=12.0, tp=8.0, seed=1), math.inf, "1/15"),
    (JonswapSettings(hs=5.0, tp=14.0, seed=1), 6.0, "0.78"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=1, spacing="fft"), math.inf, "spacing"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=1, spacing="random-in-bin"), math.inf,
     "n_components"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=1, n_components=100), math.inf, "n_components"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=1, frequency_step=0.01), math.inf, "repeats"),
    (JonswapSettings(hs=1.0, tp=10.0, seed=1, omega_min=0.8, omega_max=2.0), math.inf,
     "peak"),
])
def test_unphysical_settings_raise_clear_errors(settings, depth, message):
    with pytest.raises(ValueError, match=message):
        realise_sea(settings, depth, G, 3600.0)


def test_steep_but_admissible_waves_pass():
    RegularWaveSettings(height=12.0, period=8.0).validate(math.inf, G)  # H/lambda = 0.12
    JonswapSettings(hs=9.0, tp=10.0, seed=0).validate(math.inf, G)      # S_p = 0.058
