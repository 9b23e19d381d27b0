"""Excitation force from transfer functions; the harmonic-sum kernel it runs on."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.waves.excitation_series import WaveExcitation, excitation_coefficients
from floatmoor.waves.realisation import WaveField
from floatmoor.waves.synthesis import harmonic_sum

G = 9.81
#: A closed form against a sum evaluated two ways: rounding of ~1e3 rad phases.
EXACT_RTOL = 1e-11


def test_single_component_against_closed_form():
    """f(t) = |X| a cos(omega t - phi - arg X): a phase lag phi of the wave and arg X of the
    transfer function both delay the force (e^{-i omega t} convention)."""
    a, period, phi = 1.5, 7.0, 0.4
    w = 2 * np.pi / period
    x = np.array([[2.0e5 * np.exp(0.9j), 3.0e4 * np.exp(-2.0j), 1e6 + 0j]])
    field = WaveField.regular(2 * a, period, phase=phi, depth=50.0, gravity=G)
    force = WaveExcitation(field, x)
    t = np.linspace(0.0, 100.0, 1001)
    closed = np.abs(x[0]) * a * np.cos(w * t[:, None] - phi - np.angle(x[0]))
    scale = np.abs(x[0]) * a
    np.testing.assert_allclose(force.series(t), closed, rtol=0, atol=EXACT_RTOL * scale.max())
    for ti in (0.0, 13.3, 99.0):
        np.testing.assert_allclose(force(ti), np.abs(x[0]) * a * np.cos(w * ti - phi
                                                                         - np.angle(x[0])),
                                   rtol=0, atol=EXACT_RTOL * scale.max())
    # a sign flip of the time dependence (e^{+i omega t}) would give cos(omega t + phi + arg X)
    wrong = np.abs(x[0]) * a * np.cos(w * t[:, None] + phi + np.angle(x[0]))
    assert np.abs(force.series(t) - wrong).max() > 0.1 * scale.max()


def test_series_matches_pointwise_on_any_grid():
    field = WaveField.jonswap(3.0, 9.0, seed=2, duration=600.0, omega_min=0.3, omega_max=2.5,
                              gravity=G)
    rng = np.random.default_rng(0)
    x = rng.normal(size=(field.n_components, 6)) + 1j * rng.normal(size=(field.n_components, 6))
    force = WaveExcitation(field, x)
    uniform = np.arange(0.0, 600.0, 0.1)  # block method
    scattered = np.sort(rng.uniform(0, 600, 300))  # direct chunks
    scale = np.abs(force.coefficients).sum(axis=0)
    for t in (uniform[::37], scattered):
        direct = np.array([force(ti) for ti in t])
        np.testing.assert_allclose(force.series(t), direct, rtol=0, atol=EXACT_RTOL * scale.max())
    full = force.series(uniform)
    np.testing.assert_allclose(full[::37], np.array([force(ti) for ti in uniform[::37]]),
                               rtol=0, atol=EXACT_RTOL * scale.max())


def test_harmonic_sum_blocks_and_shapes():
    rng = np.random.default_rng(1)
    omega = rng.uniform(0.1, 3.0, 50)
    c = rng.normal(size=50) + 1j * rng.normal(size=50)
    t = np.linspace(-5.0, 4000.0, 90001)  # 90001 x 50 > one 2**22 block: several blocks
    got = harmonic_sum(c, omega, t)
    pick = np.r_[0:5, 83880:83890, 90000]
    ref = (np.exp(-1j * np.outer(t[pick], omega)) @ c).real
    np.testing.assert_allclose(got[pick], ref, rtol=0, atol=EXACT_RTOL * np.abs(c).sum())
    assert harmonic_sum(c, omega, 2.0).shape == ()
    assert harmonic_sum(np.zeros((0, 6)), [], [0.0, 1.0]).shape == (2, 6)
    with pytest.raises(ValueError):
        harmonic_sum(c[:3], omega, t)


def test_transfer_shape_checked():
    field = WaveField.regular(1.0, 5.0, gravity=G)
    with pytest.raises(ValueError, match="shape"):
        excitation_coefficients(field, np.ones((2, 6)))
    with pytest.raises(ValueError, match="NaN"):
        excitation_coefficients(field, np.full((1, 6), np.nan))
    assert WaveExcitation(WaveField.still(gravity=G), np.zeros((0, 6))).series(
        [0.0, 1.0]).tolist() == [[0.0] * 6] * 2
    assert math.isinf(WaveField.still().repeat_period)
