"""RotorThrust: direction, pitch-moment sign, relative wind (aerodynamic damping), settings."""

import math

import numpy as np
import pytest

from floatmoor.body.kinematics import generalised_force
from floatmoor.wind.force import RotorThrust, WindSettings, hub_mean_speed, speed_10m
from floatmoor.wind.thrust import NREL_5MW

HUB = 90.0
REST = np.zeros(6)
#: finite-difference step on the hub velocity [m/s], inside one 1 m/s row of the table
DV = 0.01


def _steady(speed=13.05, **kw):
    return RotorThrust(WindSettings(speed, spectrum="steady", **kw), duration=600.0)


def test_force_along_wind_and_bow_down_pitch_moment():
    rotor = _steady()
    rotor.prepare(0.0, 3, 0.05)
    f = rotor.force(1, REST, REST)
    t = NREL_5MW(13.05)
    assert f[0] == pytest.approx(t, rel=1e-12) and f[0] > 0.0
    assert np.allclose(f[[1, 2, 3, 5]], 0.0, atol=1e-9 * t)
    # r x F with r = (0, 0, 90), F = (T, 0, 0): M_y = +90 T
    assert f[4] == pytest.approx(HUB * t, rel=1e-12)
    same = generalised_force(REST, np.array([[t, 0.0, 0.0]]), np.array([[0.0, 0.0, HUB]]))
    assert np.allclose(f, same, rtol=1e-14)


def test_direction_rotates_the_force():
    rotor = _steady(direction_deg=90.0)
    f = rotor.force_at(0.0, REST, REST)
    t = NREL_5MW(13.05)
    assert f[1] == pytest.approx(t, rel=1e-12) and abs(f[0]) < 1e-9 * t
    assert f[3] == pytest.approx(-HUB * t, rel=1e-12)  # (0,0,90) x (0,T,0) = (-90 T, 0, 0)


@pytest.mark.parametrize("speed, sign", [(8.0, -1.0), (13.05, +1.0)])
def test_relative_wind_damping_sign(speed, sign):
    """Moving downwind lowers the relative wind: thrust falls below rated (damping) and rises
    above rated (negative damping, dT/dU < 0 under pitch control)."""
    rotor = _steady(speed)
    f0 = rotor.force_at(0.0, REST, REST)[0]
    v = np.zeros(6)
    v[0] = DV
    dsurge = (rotor.force_at(0.0, REST, v)[0] - f0) / DV
    assert math.copysign(1.0, dsurge) == sign
    assert dsurge == pytest.approx(-NREL_5MW.slope(speed - DV / 2), rel=1e-9)
    # pitch rate q moves the hub downwind at q * 90 m/s
    w = np.zeros(6)
    w[4] = DV / HUB
    assert rotor.force_at(0.0, REST, w)[0] == pytest.approx(rotor.force_at(0.0, REST, v)[0],
                                                             rel=1e-12)


def test_relative_velocity_off_ignores_body_motion():
    rotor = _steady(relative_velocity=False)
    v = np.array([2.0, 0.0, 0.0, 0.0, 0.01, 0.0])
    assert np.array_equal(rotor.force_at(0.0, REST, v), rotor.force_at(0.0, REST, REST))


def test_prepared_grid_matches_the_wind_series():
    rotor = RotorThrust(WindSettings(13.05, seed=5), duration=3600.0)
    dt = 0.1
    rotor.prepare(100.0, 2 * 20 + 1, dt / 2)
    for k in (0, 7, 40):
        t = 100.0 + k * dt / 2
        u = rotor.wind.speeds(np.array([t]))[0]
        assert rotor.wind_speed(k) == pytest.approx(u, abs=1e-9)
        assert rotor.force(k, REST, REST)[0] == pytest.approx(NREL_5MW(u), rel=1e-9)
        assert np.array_equal(rotor.force_at(t, REST, REST), rotor.force(k, REST, REST))
    # off the grid: evaluated directly
    t = 100.013
    u = rotor.wind.speeds(np.array([t]))[0]
    assert rotor.force_at(t, REST, REST)[0] == pytest.approx(NREL_5MW(u), rel=1e-12)


def test_hub_reference_height_reads_mean_at_hub():
    hub = WindSettings(13.05)
    ten = WindSettings(13.05, reference_height=10.0)
    assert hub_mean_speed(hub) == 13.05
    assert speed_10m(hub) == pytest.approx(10.846, abs=1e-3)
    assert speed_10m(ten) == 13.05 and hub_mean_speed(ten) > 13.05


def test_steady_force_is_mean_thrust_at_hub():
    rotor = RotorThrust(WindSettings(13.05, seed=1), duration=600.0)
    f = rotor.steady_force()
    assert f[0] == pytest.approx(NREL_5MW(13.05)) and f[4] == pytest.approx(HUB * f[0])


@pytest.mark.parametrize("kw, key", [
    ({"mean_speed": 0.0}, "mean_speed"), ({"mean_speed": 10.0, "reference_height": -1},
                                          "reference_height"),
    ({"mean_speed": 10.0, "spectrum": "kaimal"}, "spectrum"),
    ({"mean_speed": 10.0, "seed": -1}, "seed"), ({"mean_speed": 10.0, "seed": 1.5}, "seed"),
    ({"mean_speed": 10.0, "direction_deg": math.nan}, "direction_deg"),
    ({"mean_speed": 10.0, "relative_velocity": "yes"}, "relative_velocity"),
    ({"mean_speed": 10.0, "cutoff_hz": 0.0}, "cutoff_hz"),
    ({"mean_speed": True}, "mean_speed"),
])
def test_settings_validation_names_the_key(kw, key):
    with pytest.raises(ValueError, match=f"wind.{key}"):
        WindSettings(**kw).validate()
