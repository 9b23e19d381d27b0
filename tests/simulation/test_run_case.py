"""The Python runners refuse a case they cannot run as asked: a forced-motion run
of a case with a floater would ignore the floater and hold the fairleads fixed; a coupled run
of a case without one has no body. ``run_case`` picks the runner a case needs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import floatmoor as fm
from floatmoor.case.schema import HarmonicMotion
from tests.conftest import CASES, LINDAHL_CASE

DECAY_CASE = CASES / "deepcwind" / "deepcwind_free_decay.toml"
#: Quasi-static, 3 s: a forced-motion run of milliseconds.
QUICK = ['lines.chain.model="quasi-static"', "simulation.duration=3.0",
         "motion.ramp_duration=1.0"]


def test_forced_motion_refuses_a_floater_case_and_names_run_coupled(tmp_path):
    out = tmp_path / "decay.nc"
    with pytest.raises(fm.CaseError) as info:
        fm.run_forced_motion(fm.load_case(DECAY_CASE), output=out)
    err = info.value
    assert err.source == str(DECAY_CASE) and err.key == "floater"
    assert "run_coupled" in err.expected and "run_case" in err.expected
    assert err.found == "a [floater] table"
    assert not out.exists()


@pytest.mark.parametrize("key, change", [
    ("initial", lambda case: {"initial_offset": (1.0, 0.0, 0.0, 0.0, 0.0, 0.0)}),
    ("waves", lambda case: {"waves": object()}),
    ("simulation.time_step",
     lambda case: {"simulation": dataclasses.replace(case.simulation, time_step=0.0025)}),
])
def test_forced_motion_refuses_other_floater_parts(key, change):
    """A Case built in Python (load_case refuses these) with a part only a coupled run uses."""
    case = fm.load_case(LINDAHL_CASE, QUICK)
    with pytest.raises(fm.CaseError) as info:
        fm.run_forced_motion(dataclasses.replace(case, **change(case)))
    assert info.value.key == key and "run_coupled" in info.value.expected


def test_coupled_run_refuses_a_case_without_floater_or_with_a_motion():
    forced = fm.load_case(LINDAHL_CASE, QUICK)
    with pytest.raises(fm.CaseError) as info:
        fm.run_coupled(forced)
    assert info.value.key == "floater" and "run_forced_motion" in info.value.expected
    decay = fm.load_case(DECAY_CASE)
    moved = dataclasses.replace(decay, motion=HarmonicMotion(
        amplitude=(1.0, 0.0, 0.0), period=(10.0, 10.0, 10.0), phase=(0.0, 0.0, 0.0),
        ramp_duration=5.0))
    with pytest.raises(fm.CaseError) as info:
        fm.run_coupled(moved)
    assert info.value.key == "motion" and info.value.found == "a [motion] table"


def test_run_case_runs_a_forced_case_in_forced_motion():
    case = fm.load_case(LINDAHL_CASE, QUICK)
    picked = fm.run_case(case).dataset["fairlead_tension"].values
    forced = fm.run_forced_motion(case).dataset["fairlead_tension"].values
    np.testing.assert_array_equal(picked, forced)
