"""Fatigue damage (docs/theory/post_processing.md): units of the DNV curves, constant-amplitude closed
form, the Rayleigh closed form of a narrow-band Gaussian process, damage equivalent loads."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from floatmoor.post.fatigue import (
    DNV_STUDLESS_CHAIN,
    DNV_STUDLINK_CHAIN,
    MPA,
    SNCurve,
    TNCurve,
    chain_nominal_area,
    damage_equivalent_load,
    fatigue_damage,
    miner_damage,
    rayleigh_damage,
)
from floatmoor.post.rainflow import rainflow_cycles
from tests.post.synthetic import gaussian_band, realisation

#: Closed-form comparisons of exact counts: only round-off of sums of ~1e3 terms [-].
CLOSED_FORM_RTOL = 1e-12
#: Narrow-band damage against the Rayleigh closed form (the acceptance criterion) [-].
RAYLEIGH_DAMAGE_RTOL = 0.05

#: DeepCwind chain nominal diameter (docs/cases/deepcwind.md, quasi-dynamic paper Table 7) [m].
DEEPCWIND_CHAIN_D = 0.0779


def _tension(time: np.ndarray, values: np.ndarray) -> xr.DataArray:
    return xr.DataArray(values, dims=("line", "time"),
                        coords={"line": ["1", "2"][: values.shape[0]], "time": time},
                        name="fairlead_tension",
                        attrs={"long_name": "line tension at the fairlead", "units": "N"})


def test_dnv_curves_take_stress_in_mpa():
    # DNV-OS-E301: N = a_D S^-m with S in MPa; floatmoor passes S in Pa.
    assert DNV_STUDLESS_CHAIN.cycles_to_failure(100.0 * MPA) == pytest.approx(6.0e4, rel=1e-15)
    assert DNV_STUDLINK_CHAIN.cycles_to_failure(100.0 * MPA) == pytest.approx(1.2e5, rel=1e-15)
    # the same curve written for S in Pa gives the same damage
    in_pa = SNCurve(a_d=6.0e10 * MPA**3, m=3.0, stress_unit=1.0)
    ranges, counts = np.array([30e6, 80e6]), np.array([10.0, 0.5])
    assert miner_damage(ranges, counts, in_pa) == pytest.approx(
        miner_damage(ranges, counts, DNV_STUDLESS_CHAIN), rel=CLOSED_FORM_RTOL)


def test_chain_nominal_area_has_two_legs():
    assert chain_nominal_area(DEEPCWIND_CHAIN_D) == pytest.approx(
        2.0 * math.pi * DEEPCWIND_CHAIN_D**2 / 4.0, rel=1e-15)


def test_constant_amplitude_damage_matches_the_closed_form():
    # n cycles of tension range R on top of a mean, after a violent transient that `start`
    # must exclude. Troughs and peaks fall on samples (40 per cycle).
    n_cycles, per_cycle, period = 500, 40, 8.0
    dt = period / per_cycle
    k = np.arange(n_cycles * per_cycle + 1)
    ranges = np.array([[200e3], [350e3]])  # [N], one per line
    steady = 1.0e6 - 0.5 * ranges * np.cos(2.0 * np.pi * k / per_cycle)
    transient = 1.0e6 + 2.0e6 * np.sin(np.linspace(0.0, 30.0, 300))[None, :] * [[1.0], [1.0]]
    t_transient = -dt * np.arange(300, 0, -1)
    time = np.concatenate((t_transient, k * dt))
    tension = _tension(time, np.concatenate((transient, steady), axis=1))

    area = chain_nominal_area(DEEPCWIND_CHAIN_D)
    damage = fatigue_damage(tension, DNV_STUDLESS_CHAIN, start=0.0, nominal_area=area)
    stress_mpa = ranges[:, 0] / area / MPA
    expected = n_cycles * stress_mpa**3 / 6.0e10
    np.testing.assert_allclose(damage.values, expected, rtol=CLOSED_FORM_RTOL)
    assert damage.dims == ("line",) and damage.attrs["units"] == "1"
    # the transient is counted when not excluded
    assert np.all(fatigue_damage(tension, DNV_STUDLESS_CHAIN, start=time[0],
                                 nominal_area=area).values > 10 * expected)

    # DEL with N_eq = n is the range itself; with the 1 Hz default it scales as (n/N_eq)^(1/m)
    del_n = damage_equivalent_load(tension, 3.0, start=0.0, n_eq=n_cycles)
    np.testing.assert_allclose(del_n.values, ranges[:, 0], rtol=CLOSED_FORM_RTOL)
    assert del_n.attrs["units"] == "N"
    del_1hz = damage_equivalent_load(tension, 3.0, start=0.0)
    duration = n_cycles * period
    np.testing.assert_allclose(del_1hz.values, ranges[:, 0] * (n_cycles / duration) ** (1 / 3),
                               rtol=CLOSED_FORM_RTOL)

    # T-N curve: N = K R^-M with R = range / MBS
    tn = TNCurve(k=316.0, m=3.36, mbs=6.0e6)
    d_tn = fatigue_damage(tension, tn, start=0.0)
    np.testing.assert_allclose(d_tn.values, n_cycles * (ranges[:, 0] / 6.0e6) ** 3.36 / 316.0,
                               rtol=CLOSED_FORM_RTOL)
    with pytest.raises(ValueError, match="nominal_area"):
        fatigue_damage(tension, DNV_STUDLESS_CHAIN, start=0.0)


def test_two_slope_and_endurance_limit():
    knee = 1e7
    s_knee_pa = (6.0e10 / knee) ** (1 / 3) * MPA  # ~18.2 MPa
    endurance = SNCurve(a_d=6.0e10, m=3.0, knee_cycles=knee, m2=math.inf)
    two_slope = SNCurve(a_d=6.0e10, m=3.0, knee_cycles=knee, m2=5.0)
    assert endurance.cycles_to_failure(0.9 * s_knee_pa) == math.inf
    assert two_slope.cycles_to_failure(0.5 * s_knee_pa) == pytest.approx(knee * 2.0**5,
                                                                         rel=1e-12)
    above = 2.0 * s_knee_pa
    assert endurance.cycles_to_failure(above) == pytest.approx(
        DNV_STUDLESS_CHAIN.cycles_to_failure(above), rel=1e-15)


def test_narrow_band_gaussian_damage_matches_the_rayleigh_closed_form():
    # A narrow Gaussian band (relative width 2 %, f0 = 0.1 Hz, stress std 20 MPa), 2^21
    # samples at 32 per mean cycle: ~65 000 cycles, seeded. The closed form uses the moments
    # of the synthesised spectrum.
    f0, delta, sigma = 0.1, 0.02, 20.0 * MPA
    n, dt = 2**21, 1.0 / (32 * f0)
    rng = np.random.default_rng(20261122)
    time, stress, amplitude = realisation(lambda f: gaussian_band(f, f0, delta, sigma**2),
                                          n, dt, rng)
    f = np.arange(amplitude.size) / (n * dt)
    m0, m2 = np.sum(amplitude**2 / 2), np.sum(f**2 * amplitude**2 / 2)
    expected = rayleigh_damage(m0, m2, n * dt, DNV_STUDLESS_CHAIN)

    area = chain_nominal_area(DEEPCWIND_CHAIN_D)
    tension = _tension(time, (1.0e6 + stress * area)[None, :])
    damage = float(fatigue_damage(tension, DNV_STUDLESS_CHAIN, start=0.0,
                                  nominal_area=area).values[0])
    assert damage == pytest.approx(expected, rel=RAYLEIGH_DAMAGE_RTOL)
    # and the direct sum on the same stress record
    cycles = rainflow_cycles(stress)
    assert miner_damage(cycles.ranges, cycles.counts, DNV_STUDLESS_CHAIN) == pytest.approx(
        damage, rel=1e-9)
