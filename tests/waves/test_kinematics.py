"""Airy kinematics: Laplace, free-surface condition, d/dt, deep-water decay, stretching."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.waves.kinematics import (PointKinematics, airy_kinematics,
                                        elevation_at_points)
from floatmoor.waves.realisation import WaveField

G = 9.81
#: Central differences with step d have O(d^2) truncation; with d = 1e-3 / k (or 1e-4 T) the
#: relative error is ~1e-7, round-off (eps / d^2 relative) ~1e-9: 1e-6 of the field's scale.
FD_RTOL = 1e-6
#: Closed-form identities evaluated two ways: rounding only.
EXACT_RTOL = 1e-12


def _multi(depth: float) -> WaveField:
    """Five components of mixed frequencies and directions."""
    rng = np.random.default_rng(4)
    return WaveField.from_components(omega=[0.4, 0.7, 0.9, 1.3, 2.1],
                                     amplitude=[0.5, 1.0, 0.7, 0.3, 0.1],
                                     phase=rng.uniform(0, 2 * np.pi, 5),
                                     direction=[0.0, 0.4, -1.0, 2.5, 3.5],
                                     depth=depth, gravity=G)


def _scale(field: WaveField) -> float:
    return float(np.sum(field.amplitude * field.omega * field.wavenumber))


@pytest.mark.parametrize("depth", [30.0, math.inf])
def test_velocity_is_divergence_free_and_irrotational(depth):
    field = _multi(depth)
    d = 1e-3 / field.wavenumber.max()
    base = np.array([[3.0, -2.0, -5.0], [-10.0, 7.0, -12.0]])
    for t in (0.0, 3.7):
        grad = np.empty((2, 3, 3))  # point, d/dx_i, velocity component
        for i in range(3):
            step = np.zeros(3)
            step[i] = d
            up = airy_kinematics(field, base + step, t, "none").velocity
            down = airy_kinematics(field, base - step, t, "none").velocity
            grad[:, i, :] = (up - down) / (2 * d)
        div = np.trace(grad, axis1=1, axis2=2)
        curl = grad - np.transpose(grad, (0, 2, 1))
        assert np.abs(div).max() < FD_RTOL * _scale(field)
        assert np.abs(curl).max() < FD_RTOL * _scale(field)


def test_seabed_no_flux():
    field = _multi(30.0)
    r = airy_kinematics(field, [[1.0, 2.0, -30.0]], 1.0, "none")
    assert abs(r.velocity[0, 2]) < EXACT_RTOL * _scale(field) / field.wavenumber.min()
    assert abs(r.velocity[0, 0]) > 0.01


@pytest.mark.parametrize("depth", [30.0, math.inf])
def test_kinematic_free_surface_condition_and_acceleration(depth):
    """Linear kinematic condition w(z=0) = d eta / dt, and acceleration = d u / dt."""
    field = _multi(depth)
    dt = 1e-4 * 2 * np.pi / field.omega.max()
    x, y = 4.0, -1.0
    times = np.linspace(0.0, 20.0, 41)
    eta = field.elevation(times, x, y)
    checked = 0
    for t, e in zip(times, eta):
        deta = (field.elevation(t + dt, x, y) - field.elevation(t - dt, x, y)) / (2 * dt)
        if e >= 0.0:  # z = 0 is wet
            r = airy_kinematics(field, [[x, y, 0.0]], t, "none")
            assert r.velocity[0, 2] == pytest.approx(
                deta, abs=FD_RTOL * float(np.sum(field.amplitude * field.omega)))
            checked += 1
        p = [[x, y, -3.0]]
        du = (airy_kinematics(field, p, t + dt, "none").velocity
              - airy_kinematics(field, p, t - dt, "none").velocity) / (2 * dt)
        acc = airy_kinematics(field, p, t, "none").acceleration
        np.testing.assert_allclose(acc, du, atol=FD_RTOL * _scale(field) * field.omega.max())
    assert checked > 5


def test_deep_water_decay_and_orbital_speed():
    field = WaveField.regular(2.0, 9.0, direction=0.7, depth=math.inf, gravity=G)
    k, w, a = field.wavenumber[0], field.omega[0], 1.0
    z = np.array([0.0, -2.0, -10.0, -40.0])
    points = np.column_stack([np.zeros(4), np.zeros(4), z])
    for t in (0.0, 1.1, 2.9):
        r = airy_kinematics(field, points, t, "none")
        wet = r.wet
        speed = np.linalg.norm(r.velocity, axis=1)
        np.testing.assert_allclose(speed[wet], a * w * np.exp(k * z[wet]), rtol=EXACT_RTOL)
        acc = np.linalg.norm(r.acceleration, axis=1)
        np.testing.assert_allclose(acc[wet], a * w ** 2 * np.exp(k * z[wet]), rtol=EXACT_RTOL)
    # direction: horizontal velocity along (cos beta, sin beta) under the crest at t = 0
    r = airy_kinematics(field, [[0.0, 0.0, -1.0]], 0.0, "none")
    np.testing.assert_allclose(r.velocity[0, :2] / np.linalg.norm(r.velocity[0, :2]),
                               [math.cos(0.7), math.sin(0.7)], rtol=EXACT_RTOL)


@pytest.mark.parametrize("depth", [20.0, math.inf])
def test_wheeler_at_crest_equals_unstretched_at_still_water_line(depth):
    field = WaveField.regular(3.0, 8.0, depth=depth, gravity=G)
    crest = airy_kinematics(field, [[0.0, 0.0, 1.5]], 0.0, "wheeler")
    still_line = airy_kinematics(field, [[0.0, 0.0, 0.0]], 0.0, "none")
    np.testing.assert_allclose(crest.velocity, still_line.velocity, rtol=EXACT_RTOL)
    np.testing.assert_allclose(crest.acceleration, still_line.acceleration, rtol=EXACT_RTOL,
                               atol=1e-15)
    # below a crest Wheeler gives less than the exponentially extrapolated profile
    mid_w = airy_kinematics(field, [[0.0, 0.0, 0.5]], 0.0, "wheeler").velocity[0, 0]
    mid_n = airy_kinematics(field, [[0.0, 0.0, 0.5]], 0.0, "none").velocity[0, 0]
    mid_v = airy_kinematics(field, [[0.0, 0.0, 0.5]], 0.0, "vertical").velocity[0, 0]
    assert mid_w < mid_v < mid_n
    assert mid_v == pytest.approx(still_line.velocity[0, 0], rel=EXACT_RTOL)
    if math.isfinite(depth):  # the seabed maps to itself
        bed_w = airy_kinematics(field, [[0.0, 0.0, -depth]], 0.0, "wheeler").velocity
        bed_n = airy_kinematics(field, [[0.0, 0.0, -depth]], 0.0, "none").velocity
        np.testing.assert_allclose(bed_w, bed_n, rtol=EXACT_RTOL)


def test_dry_points_and_seabed():
    field = WaveField.regular(2.0, 8.0, depth=20.0, gravity=G)
    # trough at the origin at t = T/2: z = -0.5 is above the surface
    r = airy_kinematics(field, [[0.0, 0.0, -0.5], [0.0, 0.0, -1.5]], 4.0, "wheeler")
    assert r.wet.tolist() == [False, True]
    np.testing.assert_array_equal(r.velocity[0], 0.0)
    np.testing.assert_array_equal(r.acceleration[0], 0.0)
    assert np.abs(r.velocity[1]).max() > 0.1
    with pytest.raises(ValueError, match="seabed"):
        airy_kinematics(field, [[0.0, 0.0, -20.5]], 0.0)
    with pytest.raises(ValueError, match="stretching"):
        airy_kinematics(field, [[0.0, 0.0, -1.0]], 0.0, "linear")


def test_vectorised_equals_pointwise_and_cached():
    field = _multi(40.0)
    rng = np.random.default_rng(2)
    points = np.column_stack([rng.uniform(-50, 50, 20), rng.uniform(-50, 50, 20),
                              rng.uniform(-40, 2, 20)])
    fixed = PointKinematics(field, points, "wheeler")
    for t in (0.0, 5.5):
        together = fixed(t)
        for i, p in enumerate(points):
            one = airy_kinematics(field, p[None], t, "wheeler")
            np.testing.assert_allclose(together.velocity[i], one.velocity[0], rtol=1e-13,
                                       atol=1e-15)
            np.testing.assert_allclose(together.acceleration[i], one.acceleration[0],
                                       rtol=1e-13, atol=1e-15)
            assert together.elevation[i] == pytest.approx(
                float(field.elevation(t, p[0], p[1])), abs=1e-14)
        np.testing.assert_allclose(elevation_at_points(field, points[:, 0], points[:, 1], t),
                                   together.elevation, atol=1e-14)
        np.testing.assert_allclose(fixed.elevation(t), together.elevation, atol=1e-14)
