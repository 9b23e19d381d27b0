"""K(t) and the Kramers-Kronig rebuild against closed-form pairs.

Pair (B(0) = 0 as for any radiating body): B(omega) = omega^2 / (1 + omega^2)^2 has
K(t) = (2/pi) int B cos = (1 - t) exp(-t) / 2 and
A(omega) - A_inf = -(1/omega) int_0^inf K sin(omega t) dt = -(omega^2 - 1) / (2 (1 + omega^2)^2).
Its tail is omega^-2, so with tail exponent 2 the truncated-band transform must reproduce K
closely; without a tail it must not (the test can fail).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import floatmoor.hydro.radiation as radiation
from floatmoor.hydro.radiation import (
    added_mass_from_kernel, cosine_transform_operator, impulse_response,
    piecewise_linear_cosine_transform, sine_moments,
)

#: The piecewise-linear interpolant's error is h^2 B''/8 ~ 1e-4 for h = 0.05 near omega = 0;
#: the transform must hold to that order.
PAIR_TOLERANCE = 2e-3
#: Blocked and whole transforms differ only in the order of the sums: a few ulps of
#: their largest value.
BLOCKED_RTOL = 1e-13
#: Most memory building a kernel may take at once, as a fraction of its whole tail operator
#: (times x tail nodes): K itself and its copies (36 values per time against 601), and the
#: operator blocks (radiation._BLOCK_VALUES floats, 4 MB) with their temporaries. Building the
#: whole operator took about seven times its size.
KERNEL_MEMORY_FRACTION = 0.5


def test_piecewise_linear_transform_is_exact_for_linear_data():
    w = np.array([0.5, 1.0, 2.5])
    f = 3.0 + 2.0 * w
    t = np.array([0.0, 0.7, 3.0])
    expected = [(3 * w[-1] + w[-1] ** 2) - (3 * w[0] + w[0] ** 2)]
    for ti in t[1:]:
        # int (3 + 2 w) cos(w t) = (3 + 2w) sin(wt)/t + 2 cos(wt)/t^2
        g = lambda x: (3 + 2 * x) * math.sin(x * ti) / ti + 2 * math.cos(x * ti) / ti ** 2
        expected.append(g(w[-1]) - g(w[0]))
    out = piecewise_linear_cosine_transform(w, f, t)
    assert out == pytest.approx(expected, rel=1e-12, abs=1e-12)


def _pair_b(omega):
    return omega ** 2 / (1.0 + omega ** 2) ** 2


def _pair_k(t):
    return 0.5 * (1.0 - t) * np.exp(-t)


def _pair_a(omega, a_inf):
    return a_inf - (omega ** 2 - 1.0) / (2.0 * (1.0 + omega ** 2) ** 2)


def test_impulse_response_of_the_analytic_pair():
    omega = np.arange(0.05, 20.0 + 1e-9, 0.05)
    t = np.linspace(0.0, 8.0, 161)
    k = impulse_response(omega, _pair_b(omega), t, tail_exponent=2.0)
    assert np.max(np.abs(k - _pair_k(t))) < PAIR_TOLERANCE * 0.5
    # without the tail the truncation at 20 rad/s shows: K(0) misses (2/pi) int_20^inf w^-2
    k_cut = impulse_response(omega, _pair_b(omega), t, tail_exponent=None)
    assert abs(k_cut[0] - 0.5) > 10 * PAIR_TOLERANCE


def test_kramers_kronig_rebuild_of_the_analytic_pair():
    omega = np.arange(0.05, 20.0 + 1e-9, 0.05)
    t = np.linspace(0.0, 30.0, 6001)  # |K(30)| = 4e-13: truncation negligible
    k = impulse_response(omega, _pair_b(omega), t, tail_exponent=2.0)
    rebuilt = added_mass_from_kernel(t, k, 2.0, omega[::20])
    assert np.max(np.abs(rebuilt - _pair_a(omega[::20], 2.0))) < PAIR_TOLERANCE


def test_truncation_too_early_is_visible():
    omega = np.arange(0.05, 20.0 + 1e-9, 0.05)
    t = np.linspace(0.0, 1.0, 201)
    k = impulse_response(omega, _pair_b(omega), t, tail_exponent=2.0)
    rebuilt = added_mass_from_kernel(t, k, 0.0, np.array([0.5]))
    assert abs(rebuilt[0] - _pair_a(np.array([0.5]), 0.0)[0]) > 0.05


def test_database_kernel_matches_damping_transform(buoy_db):
    """K(t) of a database inverted back with a cosine transform returns B (Fourier pair)."""
    from floatmoor.hydro.radiation import radiation_kernel

    kernel = radiation_kernel(buoy_db, t_max=20.0)
    omega = buoy_db["omega"].values
    t = kernel.time
    k33 = kernel.kernel[:, 2, 2]
    w = np.array([4.0, 6.0, 8.0])
    from scipy.integrate import simpson
    b_back = [simpson(k33 * np.cos(wi * t), x=t) for wi in w]
    b33 = np.interp(w, omega, buoy_db["radiation_damping"].sel(
        radiating_dof="Heave", influenced_dof="Heave").values)
    assert b_back == pytest.approx(b33, rel=0.02)


def test_cosine_transform_of_one_node_is_zero():
    assert np.array_equal(cosine_transform_operator(np.array([2.0]), np.array([0.0, 1.5])),
                          [[0.0], [0.0]])


def test_blocked_transforms_match_the_whole_operator(monkeypatch):
    """The operator is built a few times (or nodes) at a time: the same transforms."""
    omega = np.concatenate([[0.0], np.geomspace(0.3, 40.0, 57)])
    values = np.stack([_pair_b(omega), np.sqrt(omega)], axis=1)
    t = np.linspace(0.0, 12.0, 301)  # even intervals, for Simpson
    whole = cosine_transform_operator(omega, t)
    sine = np.sin(omega[-1] * t)
    from scipy.integrate import simpson
    moments = simpson(whole * sine[:, None], x=t, axis=0)
    monkeypatch.setattr(radiation, "_BLOCK_VALUES", 7 * len(omega))  # 7 times, 1 node at most
    blocked = piecewise_linear_cosine_transform(omega, values, t)
    expected = whole @ values
    assert np.abs(blocked - expected).max() <= BLOCKED_RTOL * np.abs(expected).max()
    monkeypatch.setattr(radiation, "_BLOCK_VALUES", 3 * len(t))  # 3 nodes a block
    scale = np.abs(moments).max()
    assert np.abs(sine_moments(omega, t, omega[-1]) - moments).max() <= BLOCKED_RTOL * scale


def test_kernel_memory_does_not_grow_with_its_length(buoy_db, monkeypatch):
    """The buoy's kernel at a 0.02 s body step (10 samples per step over 31 s: 15709 times)
    is built with a fraction of the memory of its whole tail operator, which is never built
    (the 0.01 s step of the shipped case doubles both; its run peaked at 1.1 GB)."""
    import tracemalloc

    from floatmoor.body.model import KERNEL_SUBSTEPS
    from floatmoor.hydro.radiation import radiation_kernel

    monkeypatch.setattr(radiation, "_FITTED_EXPONENTS", {})  # fitted here too
    tracemalloc.start()
    try:
        kernel = radiation_kernel(buoy_db, dt=0.02 / KERNEL_SUBSTEPS)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    nodes = radiation._tail_grid(float(buoy_db["omega"].values[-1]), 1.0)[0].size  # 601
    whole_tail_operator = kernel.time.size * nodes * 8  # bytes
    assert peak <= KERNEL_MEMORY_FRACTION * whole_tail_operator


def test_tail_exponents_of_the_same_inputs_are_fitted_once(buoy_db, monkeypatch):
    """A process's next kernel of the same database and step takes the exponents fitted for
    the last; other inputs are fitted again."""
    from floatmoor.hydro.radiation import radiation_kernel

    fits = []
    monkeypatch.setattr(radiation, "_FITTED_EXPONENTS", {})
    monkeypatch.setattr(radiation, "fit_tail_exponents",
                        lambda *args: fits.append(args) or np.full((6, 6), 2.5))
    first = radiation_kernel(buoy_db, dt=0.02)
    again = radiation_kernel(buoy_db.copy(deep=True), dt=0.02)
    assert len(fits) == 1 and np.array_equal(again.kernel, first.kernel)
    radiation_kernel(buoy_db, dt=0.01)
    changed = buoy_db.copy(deep=True)
    changed["added_mass"] = changed["added_mass"] * 1.01
    radiation_kernel(changed, dt=0.02)
    assert len(fits) == 3
