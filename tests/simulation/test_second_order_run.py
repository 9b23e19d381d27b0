"""Coupled runs of the buoy with second-order wave loads (``[waves] second_order``): the
recorded force and its attributes, the mean drift in the start equilibrium, the ramp, the
warning for drift made for another mooring, and "none" unchanged bit for bit."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from floatmoor.case.coupling import CoupledCase
from floatmoor.case.load import load_case
from floatmoor.errors import FloatmoorWarning
from floatmoor.hydro.natural_periods import mooring_stiffness
from floatmoor.hydro.second_order import DriftLookup
from floatmoor.io.variables import VARIABLE_ATTRIBUTES
from floatmoor.simulation.assembly import assemble
from floatmoor.simulation.coupled_run import run_coupled, settings_from_case
from floatmoor.waves.second_order import NewmanForce
from floatmoor.waves.realisation import realise_sea
from tests.simulation import second_order_reference as reference
from tests.conftest import CASES

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
SHORT = ['lines.*.model="quasi-static"', "simulation.duration=2.0",
         "simulation.output_interval=0.02", "simulation.time_step=0.01"]
REGULAR = 'waves={kind = "regular", height = 0.04, period = 1.2, ramp_duration = 1.2, ' \
          'second_order = "%s"}'
#: The surge offset by the mean drift against the linear estimate (C + K_moor) x = F, K_moor
#: the lines' linearised stiffness at the case's position: the catenaries' K11 is 25.04 N/m
#: there, 24.74 N/m at the equilibrium without drift (3.6 mm lower) and 24.44 N/m at the
#: drifted one (measured by central differences of floatmoor.hydro.natural_periods.
#: mooring_force): 2.4 %, the nonlinearity the linear estimate leaves out (measured: 1.7 %).
LINEAR_OFFSET_RTOL = 0.03
#: The run with the mean drift against the run without, moved by the offset: the motion in
#: the waves about the moved position differs by the mooring's nonlinearity (measured: 0.27 %
#: of the offset over the 2 s).
MOVED_RTOL = 0.01
#: The recorded second-order force against the model evaluated again at the output times
#: (harmonic sums of the run's chunks against one sum: rounding).
ROUND_OFF = 1e-11


def _case(model: str, *extra: str):
    return load_case(BUOY_CASE, SHORT + [REGULAR % model, *extra])


def test_mean_drift_run_records_the_force_and_starts_at_the_drifted_equilibrium() -> None:
    """``mean`` on the shipped buoy: the recorded force is a^2 D of the database (far field
    for surge), constant from t = 0; the body starts at rest at an equilibrium moved by the
    drift, by the linearised mooring's offset (C + K_moor)^-1 F; the whole run is moved by it
    (the positions of the ``none`` run plus the offset); the attributes say what was used."""
    mean_case, none_case = _case("mean"), _case("none")
    ds = run_coupled(mean_case).dataset
    plain = run_coupled(none_case).dataset
    force = ds["second_order_force"]
    assert force.dims == ("time", "dof")
    assert force.attrs["units"] == "N (Surge, Sway, Heave), N m (Roll, Pitch, Yaw)"
    assert force.attrs["long_name"] == VARIABLE_ATTRIBUTES["second_order_force"]["long_name"]
    w = 2 * math.pi / 1.2
    with_db = assemble(mean_case, settings_from_case(mean_case))
    d = DriftLookup(with_db.database, "far_field").at(np.array([w]), 0.0)[0]
    expected = 0.02 ** 2 * d
    np.testing.assert_allclose(force.values, np.tile(expected, (force.sizes["time"], 1)),
                               rtol=0, atol=1e-15 * np.abs(expected).max())
    assert expected[0] > 0.05  # 0.068 N downwave
    assert ds.attrs["second_order"] == "mean" and ds.attrs["drift_source"] == "floatmoor"
    assert ds.attrs["drift_inputs_current"] == "yes"
    assert ds.attrs["second_order_coefficients"].startswith("mean_drift_far_field for Surge")
    assert ds["body_equilibrium"].attrs["mean_wave_drift"] == "included"
    assert "mean wave drift" in ds["body_equilibrium"].attrs["long_name"]
    # the offset of the equilibrium: the linearised mooring's
    offset = ds["body_equilibrium"].values - plain["body_equilibrium"].values
    stiffness = with_db.moored.body.stiffness + mooring_stiffness(mean_case)
    linear = np.linalg.solve(stiffness[np.ix_([0, 2, 4], [0, 2, 4])], expected[[0, 2, 4]])
    assert abs(offset[0] / linear[0] - 1.0) < LINEAR_OFFSET_RTOL
    # at rest there at t = 0; then the whole run moved by it
    assert np.all(ds["body_displacement"].values[0] == 0.0)
    moved = (ds["body_displacement"].values + ds["body_equilibrium"].values
             - plain["body_displacement"].values - plain["body_equilibrium"].values)
    assert np.abs(moved[:, 0] - offset[0]).max() < MOVED_RTOL * offset[0]
    # none: neither the force nor its attributes
    assert "second_order_force" not in plain and "second_order" not in plain.attrs
    assert "mean_wave_drift" not in plain["body_equilibrium"].attrs


def test_newman_run_applies_the_mean_unramped_and_the_rest_ramped_squared() -> None:
    """An irregular sea with ``newman``: the recorded force is the model's, its mean
    unramped and the rest times the square of the cosine ramp."""
    ramp = 0.6
    case = load_case(BUOY_CASE, SHORT + [
        'waves={kind = "jonswap", hs = 0.04, tp = 1.2, seed = 2, second_order = "newman", '
        f'ramp_duration = {ramp}}}', "simulation.duration=2.5"])
    ds = run_coupled(case).dataset
    settings = settings_from_case(case)
    sea = realise_sea(CoupledCase.of(case).waves.settings, 0.9, 9.81, case.simulation.duration)
    system = assemble(case, settings)
    lookup = DriftLookup(system.database, "far_field")
    inside = lookup.covers(sea.omega)
    assert not np.all(inside)  # the sea reaches above the database's 9.2 rad/s
    model = NewmanForce(sea, lookup.at(sea.omega, sea.direction), inside)
    t = ds["time"].values
    r = np.where(t < ramp, 0.5 - 0.5 * np.cos(np.pi * t / ramp), 1.0)
    expected = model.mean + r[:, None] ** 2 * (model.series(t) - model.mean)
    recorded = ds["second_order_force"].values
    np.testing.assert_allclose(recorded, expected, rtol=0,
                               atol=ROUND_OFF * np.abs(expected).max())
    assert np.ptp(recorded[t > ramp, 0]) > 0.5 * abs(model.mean[0])  # a slow drift, not a mean
    np.testing.assert_allclose(recorded[0], model.mean, rtol=1e-14)
    # the equilibrium holds the mean (the same as "mean"'s, to round-off)
    mean_case = load_case(BUOY_CASE, SHORT + [
        'waves={kind = "jonswap", hs = 0.04, tp = 1.2, seed = 2, second_order = "mean", '
        f'ramp_duration = {ramp}}}', "simulation.duration=2.5"])
    mean_system = assemble(mean_case, settings_from_case(mean_case))
    np.testing.assert_allclose(mean_system.loads.second_order.mean, model.mean, rtol=0,
                               atol=1e-14 * np.abs(model.mean).max())
    np.testing.assert_allclose(mean_system.equilibrium, system.equilibrium, rtol=0, atol=1e-12)


def test_drift_for_another_mooring_warns_once_and_is_recorded() -> None:
    """Longer lines change the mooring the drift's RAOs were computed with: the run goes on
    (a study varies the mooring) with one warning, and records it."""
    case = _case("mean", "lines.*.length=7.0", "simulation.duration=0.1")
    with pytest.warns(FloatmoorWarning, match="another mass or mooring") as caught:
        ds = run_coupled(case).dataset
    assert len([w for w in caught if "drift" in str(w.message)]) == 1
    assert ds.attrs["drift_inputs_current"] == "no"


def test_none_leaves_the_runs_as_they_were_bit_for_bit() -> None:
    """``second_order = "none"`` (the default) gives exactly the results of the code before
    second-order wave loads (tests/data/references/second_order_none.json)."""
    import dataclasses

    stored = json.loads(reference.REFERENCE.read_text())["runs"]
    # "none" given explicitly loads to the case the default gives (all but the title and the
    # list of overrides, which the runs do not read): one set of runs checks both
    for sea in reference.SEAS.values():
        base = reference.SHORT + [sea]
        default = load_case(reference.BUOY_CASE, base)
        explicit = load_case(reference.BUOY_CASE, base + ['waves.second_order="none"'])
        assert default.waves.second_order == "none"
        differ = [f.name for f in dataclasses.fields(default)
                  if getattr(default, f.name) != getattr(explicit, f.name)]
        assert differ == ["title", "overrides"], differ
    now = reference.results()
    for sea, variables in stored.items():
        for name, values in variables.items():
            assert np.array_equal(np.asarray(now[sea][name]), np.asarray(values)), (sea, name)


def test_interrupted_newman_run_resumes_to_identical_results(tmp_path, monkeypatch) -> None:
    """The second-order force is tabulated per chunk like the excitation: a run interrupted
    after a few chunks and resumed from its checkpoint records what an uninterrupted run
    does, bit for bit."""
    import floatmoor.simulation.coupled_run as cr
    from floatmoor.io.netcdf import read_dataset
    from tests.simulation.interrupted import interrupt_run

    monkeypatch.setattr(cr, "CHUNK_STEPS", 40)
    case = load_case(BUOY_CASE, SHORT + [
        'waves={kind = "jonswap", hs = 0.04, tp = 1.2, seed = 2, second_order = "newman", '
        'spacing = "random-in-bin", n_components = 30, ramp_duration = 0.5}',
        "simulation.duration=1.6"])
    whole = run_coupled(case, output=tmp_path / "whole.nc").dataset
    out = tmp_path / "cut.nc"
    interrupt_run(case, out)
    assert read_dataset(out).attrs["status"].startswith("interrupted")
    resumed = run_coupled(case, output=out, resume=True).dataset
    for name in ("second_order_force", "body_displacement", "body_equilibrium"):
        assert np.array_equal(resumed[name].values, whole[name].values), name
    assert resumed.attrs["second_order"] == "newman"
