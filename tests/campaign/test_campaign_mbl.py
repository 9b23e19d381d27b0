"""Campaign datasets keep the largest line tension and its ratio to the MBL per run and line,
equal to the run summary's, NaN without an MBL, and carry them over on resume."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.campaign.design import design_from_options
from floatmoor.campaign.runner import run_campaign
from floatmoor.case.load import load_case
from floatmoor.io.netcdf import read_dataset
from floatmoor.post.summary import run_summary
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE

BASE = ['lines.chain.model="quasi-static"', "simulation.duration=4.0"]
#: A far-off MBL and one below the peak tension.
GRID = ["line_types.chain.minimum_breaking_load=1e9,40.0"]


def test_campaign_keeps_max_tension_and_mbl_ratio(tmp_path):
    out = tmp_path / "c.nc"
    run_campaign(LINDAHL_CASE, design_from_options(GRID), base_overrides=BASE, output=out)
    ds = read_dataset(out)
    assert ds["max_tension_over_mbl"].attrs["units"] == "1"
    assert ds["max_line_tension"].attrs["units"] == "N"
    case = load_case(LINDAHL_CASE, [*BASE, "line_types.chain.minimum_breaking_load=40.0"])
    expected = run_summary(case, run_forced_motion(case).dataset)["lines"]["chain"]["strength"]
    assert ds["max_line_tension"].values[1, 0] == pytest.approx(expected["max_tension_N"],
                                                                rel=1e-12)
    assert ds["max_tension_over_mbl"].values[1, 0] == pytest.approx(
        expected["max_tension_over_mbl"], rel=1e-12)
    assert ds["max_tension_over_mbl"].values[0, 0] == pytest.approx(
        expected["max_tension_N"] / 1e9, rel=1e-12)
    # resuming keeps them
    again = run_campaign(LINDAHL_CASE, design_from_options(GRID), base_overrides=BASE,
                         output=out)
    np.testing.assert_array_equal(again["max_tension_over_mbl"].values,
                                  ds["max_tension_over_mbl"].values)


def test_campaign_without_mbl_stores_nan(tmp_path):
    ds = run_campaign(LINDAHL_CASE, design_from_options(["motion.radius=0.1,0.2"]),
                      base_overrides=BASE, output=tmp_path / "c.nc")
    assert np.all(np.isnan(ds["max_tension_over_mbl"].values))
    assert np.all(ds["max_line_tension"].values > 0.0)


def test_a_run_whose_line_breaks_at_rest_fails_and_the_campaign_goes_on(tmp_path):
    # the Lindahl chain holds ~23 N at rest: an MBL of 10 N breaks it before it moves
    ds = run_campaign(LINDAHL_CASE, design_from_options(
        ["line_types.chain.minimum_breaking_load=10.0,100.0"]), base_overrides=BASE,
        output=tmp_path / "c.nc")
    status = ds["status"].values
    assert status[0].startswith("failed: CaseError") and "line 'chain'" in status[0]
    assert status[1] == "complete"
    assert np.isnan(ds["max_tension_over_mbl"].values[0, 0])
    assert 0.0 < ds["max_tension_over_mbl"].values[1, 0] < 1.0
