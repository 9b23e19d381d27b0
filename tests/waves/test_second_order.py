"""Second-order wave forces (floatmoor/waves/second_order.py), their kernels against the NumPy
oracle, and the database lookup (floatmoor/hydro/second_order.py) on the shipped buoy's drift
coefficients."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from floatmoor.hydro.second_order import DriftLookup, QTFLookup, missing_coefficients
from floatmoor.waves._second_order_kernels import band_amplitudes, hermitian_forms
from floatmoor.waves.realisation import WaveField
from floatmoor.waves.second_order import (
    MeanDriftForce, NewmanForce, QTFForce, hat_weights, newman_on_grid,
)
from tests.conftest import REPO
from tests.oracles import second_order_numpy as oracle


pytestmark = pytest.mark.oracle

BUOY_DATABASE = REPO / "hydrodb" / "cylinder_buoy.nc"
#: Sums evaluated two ways (harmonic sums of phases up to ~1e3 rad, the kernels' phase
#: recurrence resynchronised every 64 steps) agree to this fraction of the force's scale.
ROUND_OFF = 1e-11


@pytest.fixture(scope="module")
def buoy() -> xr.Dataset:
    with xr.open_dataset(BUOY_DATABASE) as ds:
        return ds.load()


def _by_hand(ds: xr.Dataset, index: int) -> np.ndarray:
    """The far-field route at database frequency ``index``, composed by hand: Surge, Sway, Yaw
    from the far field, Heave, Roll, Pitch from the near field."""
    far = ds["mean_drift_far_field"].isel(omega=index, wave_direction=0).values
    near = ds["mean_drift_near_field"].isel(omega=index, wave_direction=0).values
    return np.array([far[0], far[1], near[2], near[3], near[4], far[5]])


def test_regular_wave_force_is_a_squared_times_the_coefficient(buoy) -> None:
    """One wave of amplitude a at a database frequency: every model gives the constant
    a^2 D of the stored coefficients (the QTF's diagonal for "full")."""
    w = float(buoy["omega"].values[44])
    a = 0.02
    field = WaveField.regular(2 * a, 2 * math.pi / w, phase=0.7, depth=0.9)
    d = DriftLookup(buoy, "far_field").at(field.omega, field.direction)
    expected = a ** 2 * _by_hand(buoy, 44)
    np.testing.assert_array_equal(d[0], _by_hand(buoy, 44))
    t = np.linspace(0.0, 30.0, 301)
    scale = np.abs(expected).max()
    np.testing.assert_allclose(MeanDriftForce(field, d).series(t), np.tile(expected, (301, 1)),
                               rtol=0, atol=ROUND_OFF * scale)
    np.testing.assert_allclose(NewmanForce(field, d).series(t), np.tile(expected, (301, 1)),
                               rtol=0, atol=ROUND_OFF * scale)
    grid = buoy["omega"].values
    qtf = np.zeros((grid.size, grid.size, 6), dtype=complex)
    qtf[44, 44] = d[0]
    np.testing.assert_allclose(QTFForce(field, grid, qtf).series(t), np.tile(expected, (301, 1)),
                               rtol=0, atol=ROUND_OFF * scale)
    # the near-field route takes all six DOFs from the near field
    near = DriftLookup(buoy, "near_field").at(field.omega, field.direction)
    np.testing.assert_array_equal(near[0], buoy["mean_drift_near_field"].values[44, 0])


def test_lookup_interpolates_linearly_and_drops_components_outside_the_band(buoy) -> None:
    lookup = DriftLookup(buoy, "far_field")
    w = np.array([0.5, 2.05, 5.23, 9.3])  # below, inside, inside, above [0.8, 9.2] rad/s
    d = lookup.at(w, 0.0)
    grid = buoy["omega"].values
    full = np.array([_by_hand(buoy, i) for i in range(grid.size)])
    for k in (1, 2):
        np.testing.assert_allclose(d[k], [np.interp(w[k], grid, full[:, j]) for j in range(6)],
                                   rtol=1e-14, atol=0)
    assert np.all(d[[0, 3]] == 0.0)
    with pytest.raises(ValueError, match="outside the database directions"):
        lookup.at(w, math.radians(30.0))


def test_bichromatic_newman_is_newmans_formula_and_its_mean_the_two_drifts(buoy) -> None:
    """Two waves at database frequencies: F(t) = a1^2 D1 + a2^2 D2 + a1 a2 (D1 + D2)
    cos((w1 - w2) t - phi1 + phi2), written from the stored coefficients; its mean over the
    beat period is the sum of the two mean drifts."""
    i, j = 40, 46
    w = buoy["omega"].values[[i, j]]
    a, phi = np.array([0.015, 0.01]), np.array([0.3, 2.1])
    field = WaveField.from_components(w, a, phi, 0.0, depth=0.9)
    d = DriftLookup(buoy, "far_field").at(field.omega, field.direction)
    d1, d2 = _by_hand(buoy, i), _by_hand(buoy, j)
    beat = 2 * math.pi / (w[1] - w[0])
    t = np.linspace(0.0, beat, 2001)
    hand = (a[0] ** 2 * d1 + a[1] ** 2 * d2
            + a[0] * a[1] * (d1 + d2) * np.cos((w[0] - w[1]) * t - phi[0] + phi[1])[:, None])
    newman = NewmanForce(field, d)
    scale = np.abs(hand).max()
    np.testing.assert_allclose(newman.series(t), hand, rtol=0, atol=ROUND_OFF * scale)
    mean = a[0] ** 2 * d1 + a[1] ** 2 * d2
    np.testing.assert_allclose(newman.mean, mean, rtol=1e-14, atol=0)
    np.testing.assert_allclose(newman.series(t[:-1]).mean(axis=0), mean, rtol=0,
                               atol=ROUND_OFF * scale)
    np.testing.assert_allclose(MeanDriftForce(field, d).mean, mean, rtol=1e-14, atol=0)
    # pointwise calls equal the series
    np.testing.assert_allclose(newman(t[123]), hand[123], rtol=0, atol=ROUND_OFF * scale)


@pytest.mark.parametrize("spacing", ["equal", "random-in-bin"])
def test_full_qtf_of_newmans_off_diagonals_equals_newman(buoy, spacing) -> None:
    """A QTF built on the database's frequencies as (D_p + D_q) / 2 gives Newman's force to
    round-off, for equally spaced and random-in-bin seas (bilinear interpolation of it is
    Newman's form of the linearly interpolated D)."""
    grid = buoy["omega"].values
    d_grid = np.array([_by_hand(buoy, i) for i in range(grid.size)])
    qtf = 0.5 * (d_grid[:, None, :] + d_grid[None, :, :]).astype(complex)
    field = WaveField.jonswap(0.04, 1.2, seed=5, duration=60.0, omega_min=3.0, omega_max=9.0,
                              spacing=spacing, n_components=120 if spacing != "equal" else None,
                              depth=0.9)
    d = DriftLookup(buoy, "far_field").at(field.omega, field.direction)
    t = np.arange(0.0, 60.0, 0.005)
    newman = NewmanForce(field, d).series(t)
    full = QTFForce(field, grid, qtf)
    scale = np.abs(newman).max(axis=0).max()
    np.testing.assert_allclose(full.series(t), newman, rtol=0, atol=ROUND_OFF * scale)
    np.testing.assert_allclose(full.mean, NewmanForce(field, d).mean, rtol=0,
                               atol=ROUND_OFF * scale)


def test_newman_leaves_out_the_components_outside_the_band(buoy) -> None:
    """Components the drift coefficients do not cover take no part in S and S_D: the force
    is the in-band sea's (as the full QTF's pairs outside its grid are zero)."""
    w = np.array([0.5, 3.0, 4.0, 9.5])
    a, phi = np.array([0.05, 0.01, 0.02, 0.03]), np.array([0.1, 0.7, 2.0, 1.1])
    field = WaveField.from_components(w, a, phi, depth=0.9)
    lookup = DriftLookup(buoy, "far_field")
    inside = lookup.covers(w)
    assert list(inside) == [False, True, True, False]
    band = WaveField.from_components(w[1:3], a[1:3], phi[1:3], depth=0.9)
    t = np.linspace(0.0, 20.0, 401)
    expected = NewmanForce(band, lookup.at(band.omega, 0.0)).series(t)
    got = NewmanForce(field, lookup.at(w, 0.0), inside).series(t)
    np.testing.assert_allclose(got, expected, rtol=0, atol=ROUND_OFF * np.abs(expected).max())
    assert np.abs(NewmanForce(field, lookup.at(w, 0.0)).series(t) - expected).max() > \
        1e-3 * np.abs(expected).max()


@pytest.mark.parametrize("spacing", ["equal", "random-in-bin"])
def test_newman_from_the_band_amplitudes_equals_the_harmonic_sums(buoy, spacing) -> None:
    """The run's Newman force (D on the database's frequencies, from the grid's band
    amplitudes) against the harmonic sums of S and S_D, for seas reaching beyond the
    database's band at both ends."""
    field = WaveField.jonswap(0.04, 1.2, seed=8, duration=60.0, omega_min=0.5,
                              omega_max=12.0, spacing=spacing,
                              n_components=150 if spacing != "equal" else None, depth=0.9)
    lookup = DriftLookup(buoy, "far_field")
    inside = lookup.covers(field.omega)
    assert not inside[0] and not inside[-1]
    reference = NewmanForce(field, lookup.at(field.omega, 0.0), inside)
    fast = newman_on_grid(field, lookup.omega, lookup.column(0.0))
    t = np.arange(0.0, 60.0, 0.005)
    expected = reference.series(t)
    np.testing.assert_allclose(fast.series(t), expected, rtol=0,
                               atol=ROUND_OFF * np.abs(expected).max())
    np.testing.assert_allclose(fast.mean, reference.mean, rtol=1e-13)
    scattered = np.array([0.3, 17.1, 59.99])
    np.testing.assert_allclose(fast.series(scattered), reference.series(scattered), rtol=0,
                               atol=ROUND_OFF * np.abs(expected).max())


def test_qtf_with_a_known_phase_gives_the_hand_written_cosine() -> None:
    """Q12 = q e^{i theta} (Q21 its conjugate), Q11, Q22 real, two waves on grid nodes:
    F(t) = a1^2 Q11 + a2^2 Q22 + 2 a1 a2 q cos((w1 - w2) t - phi1 + phi2 - theta)."""
    grid = np.array([0.5, 0.6, 0.75, 0.9])
    q, theta = 2.0e4, 0.8
    qtf = np.zeros((4, 4, 6), dtype=complex)
    qtf[1, 1, 0], qtf[2, 2, 0], qtf[1, 1, 4] = 3.0e4, 5.0e4, -1.0e5
    qtf[1, 2, 0] = q * np.exp(1j * theta)
    qtf[2, 1, 0] = q * np.exp(-1j * theta)
    a, phi = np.array([1.5, 1.0]), np.array([0.4, 2.5])
    field = WaveField.from_components(grid[[1, 2]], a, phi, 0.0)
    t = np.linspace(0.0, 200.0, 4001)
    hand = np.zeros((t.size, 6))
    hand[:, 0] = (a[0] ** 2 * 3.0e4 + a[1] ** 2 * 5.0e4
                  + 2 * a[0] * a[1] * q * np.cos((grid[1] - grid[2]) * t - phi[0] + phi[1]
                                                 - theta))
    hand[:, 4] = a[0] ** 2 * -1.0e5
    force = QTFForce(field, grid, qtf)
    np.testing.assert_allclose(force.series(t), hand, rtol=0,
                               atol=ROUND_OFF * np.abs(hand).max())
    # a phase of the wrong sign (the e^{+i omega t} convention) is another force
    wrong = a[0] ** 2 * 3.0e4 + a[1] ** 2 * 5.0e4 + 2 * a[0] * a[1] * q * np.cos(
        (grid[1] - grid[2]) * t - phi[0] + phi[1] + theta)
    assert np.abs(force.series(t)[:, 0] - wrong).max() > 0.5 * q


def _random_qtf(rng: np.random.Generator, m: int) -> np.ndarray:
    """A Hermitian QTF with an arbitrary (non-Hermitian) part added, which the real force
    does not see."""
    raw = rng.normal(size=(m, m, 6)) + 1j * rng.normal(size=(m, m, 6))
    return raw * 1e3


def test_full_force_against_the_double_sum_oracle() -> None:
    """The hat-function kernels against the literal double sum over ordered pairs with the
    bilinearly interpolated QTF, on a random-in-bin sea whose band sticks out of the QTF grid
    at both ends (pairs with a frequency outside it contribute nothing), at uniform and at
    scattered times."""
    rng = np.random.default_rng(4)
    grid = np.array([0.3, 0.45, 0.5, 0.7, 0.8, 1.0, 1.3])
    qtf = _random_qtf(rng, grid.size)
    field = WaveField.jonswap(4.0, 9.0, seed=1, duration=400.0, omega_min=0.25, omega_max=1.5,
                              spacing="random-in-bin", n_components=40)
    assert field.omega.min() < grid[0] and field.omega.max() > grid[-1]
    force = QTFForce(field, grid, qtf)
    uniform = np.linspace(0.0, 400.0, 201)  # 200 steps: three phase resynchronisations
    scattered = np.sort(rng.uniform(0.0, 1e4, 25))
    for t in (uniform, scattered):
        expected = oracle.qtf_force(t, field.omega, field.complex_amplitude, grid, qtf)
        scale = np.abs(expected).max()
        np.testing.assert_allclose(force.series(t), expected, rtol=0, atol=ROUND_OFF * scale)
    # its constant part is the pairs' diagonal, the mean of the double sum
    diagonal = sum(abs(field.complex_amplitude[i]) ** 2
                   * oracle.bilinear(grid, qtf, field.omega[i], field.omega[i])
                   for i in range(field.n_components))
    herm = 0.5 * (qtf + np.conj(qtf.transpose(1, 0, 2)))
    diagonal_h = sum(abs(field.complex_amplitude[i]) ** 2
                     * oracle.bilinear(grid, herm, field.omega[i], field.omega[i])
                     for i in range(field.n_components))
    np.testing.assert_allclose(force.mean, diagonal.real, rtol=1e-12)
    np.testing.assert_allclose(force.mean, diagonal_h.real, rtol=1e-12)


def test_components_outside_the_qtf_grid_add_nothing() -> None:
    rng = np.random.default_rng(2)
    grid = np.array([0.4, 0.6, 0.8, 1.0])
    qtf = _random_qtf(rng, grid.size)
    inside = WaveField.from_components([0.5, 0.7, 0.95], [1.0, 0.5, 0.8], [0.1, 1.2, 2.0])
    more = WaveField.from_components([0.2, 0.5, 0.7, 0.95, 1.4], [2.0, 1.0, 0.5, 0.8, 3.0],
                                     [1.0, 0.1, 1.2, 2.0, 0.3])
    t = np.linspace(0.0, 100.0, 101)
    np.testing.assert_array_equal(QTFForce(inside, grid, qtf).series(t),
                                  QTFForce(more, grid, qtf).series(t))
    none = WaveField.from_components([0.2, 1.4], [1.0, 1.0], [0.0, 0.0])
    assert np.all(QTFForce(none, grid, qtf).series(t) == 0.0)


def test_kernels_against_their_oracles() -> None:
    rng = np.random.default_rng(7)
    m, n = 6, 150
    grid = np.linspace(0.3, 1.2, m)
    omega = np.sort(rng.uniform(0.3, 1.2, 50))
    amp = rng.normal(size=50) + 1j * rng.normal(size=50)
    cell, frac, inside = hat_weights(grid, omega)
    assert np.all(inside)
    low, high = amp * (1 - frac), amp * frac
    t0, h = 1234.5, 0.05
    p = np.empty((n, m), dtype=complex)
    band_amplitudes(t0, h, omega, low, high, cell, p)
    times = t0 + h * np.arange(n)
    expected = oracle.band_amplitudes(times, omega, low, high, cell, m)
    np.testing.assert_allclose(p, expected, rtol=0, atol=ROUND_OFF * np.abs(expected).max())
    raw = _random_qtf(rng, m)
    herm = np.ascontiguousarray(0.5 * (raw + np.conj(raw.transpose(1, 0, 2))))
    out = np.empty((n, 6))
    hermitian_forms(p, herm, out)
    forms = oracle.hermitian_forms(p, herm)
    np.testing.assert_allclose(out, forms, rtol=0, atol=1e-12 * np.abs(forms).max())


def test_missing_coefficients_are_named(buoy) -> None:
    assert missing_coefficients(buoy, "mean", "far_field") is None
    assert "qtf_difference" in missing_coefficients(buoy, "full", "far_field")
    only_near = buoy.drop_vars("mean_drift_far_field")
    assert "near field only" in missing_coefficients(only_near, "newman", "far_field")
    assert missing_coefficients(only_near, "newman", "near_field") is None
    # a far field alone (WAMIT .8): Heave, Roll, Pitch are zero
    only_far = buoy.drop_vars(["mean_drift_near_field", "mean_drift_near_field_terms"])
    d = DriftLookup(only_far, "far_field").at(np.array([5.0]), 0.0)
    assert np.all(d[0, 2:5] == 0.0) and d[0, 0] > 0.0


def test_qtf_lookup_takes_the_variable_in_either_complex_labelling() -> None:
    grid = np.array([0.4, 0.6, 0.8])
    rng = np.random.default_rng(3)
    q = rng.normal(size=(1, 3, 3, 6)) + 1j * rng.normal(size=(1, 3, 3, 6))
    for labels in (["re", "im"], ["real", "imag"]):
        ds = xr.Dataset(
            {"qtf_difference": (("complex", "qtf_direction", "qtf_omega_1", "qtf_omega_2",
                                 "influenced_dof"), np.stack([q.real, q.imag]))},
            coords={"complex": labels, "qtf_direction": [0.0], "qtf_omega_1": grid,
                    "qtf_omega_2": grid,
                    "influenced_dof": ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]})
        lookup = QTFLookup(ds)
        np.testing.assert_array_equal(lookup.at(0.0), q[0])
        np.testing.assert_array_equal(lookup.grid, grid)
        with pytest.raises(ValueError, match="outside the database directions"):
            lookup.at(0.3)


#: Generous ceiling of the CPU time of a 3 h record's second-order force at the body's half
#: steps, tabulated per chunk as a run does (measured on the shared 2-core machine: full QTF
#: on 60 frequencies 3.9 s for 1000 random-in-bin components, 7.0 s for 2922 equally spaced;
#: Newman on 61 frequencies 3.1 s and 6.4 s).
MAX_RECORD_CPU_SECONDS = 40.0


@pytest.mark.benchmark
@pytest.mark.parametrize("spacing", ["equal", "random-in-bin"])
def test_three_hour_second_order_record_cost(spacing) -> None:
    import time

    field = WaveField.jonswap(6.0, 10.0, seed=1, duration=10800.0, omega_min=0.3,
                              omega_max=2.0, spacing=spacing,
                              n_components=1000 if spacing != "equal" else None)
    rng = np.random.default_rng(0)
    grid = np.linspace(0.25, 2.05, 60)
    forces = {"full": QTFForce(field, grid, _random_qtf(rng, 60)),
              "newman": newman_on_grid(field, grid, rng.normal(size=(60, 6)))}
    dt, steps = 0.1, 500  # chunks of 500 body steps, tabulated at the half steps
    for name, force in forces.items():
        force.series(np.arange(0.0, 1.0, 0.05))  # compiled before the clock starts
        start = time.process_time()
        for c in range(int(10800.0 / dt / steps)):
            force.series(c * steps * dt + 0.5 * dt * np.arange(2 * steps + 1))
        cpu = time.process_time() - start
        print(f"\n{name}, {field.n_components} components ({spacing}): {cpu:.1f} s CPU")
        assert cpu < MAX_RECORD_CPU_SECONDS
