"""Histories of a ``--timeseries`` campaign share one time axis: runs of
different output times are refused before any run, and a campaign file is resumed only with
the same choice of histories, so no run is ever marked complete with NaN histories."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.campaign.design import design_from_options
from floatmoor.campaign.store import CampaignStore
from floatmoor.cli import main
from floatmoor.errors import CaseError
from floatmoor.io.netcdf import read_dataset
from tests.conftest import LINDAHL_CASE

QS = ["--set", 'lines.chain.model="quasi-static"']


@pytest.mark.parametrize("grid", ["simulation.duration=3,4",
                                  "simulation.output_interval=0.0025,0.005"])
def test_timeseries_of_different_output_times_refused_before_any_run(tmp_path, capsys,
                                                                     monkeypatch, grid):
    from floatmoor.campaign import runner

    def no_run(*args, **kwargs):
        raise AssertionError("a run started")

    monkeypatch.setattr(runner, "run_one", no_run)
    out = tmp_path / "ts.nc"
    status = main(["sweep", str(LINDAHL_CASE), *QS, "--set", "simulation.duration=3",
                   "--grid", grid, "--timeseries", "-o", str(out), "--quiet"])
    assert status == 2
    err = capsys.readouterr().err
    assert "--timeseries: expected runs with the same output times" in err
    assert not out.exists()


def test_record_of_other_output_times_stores_nothing():
    design = design_from_options(["motion.period=1.25,2.5"])
    store = CampaignStore(design, "case.toml", "text", [], ["chain"])
    result = {"status": "complete", "compute_time_s": 1.0, "wall_time_s": 1.0,
              "statistics": {}, "time": np.arange(3.0), "fairlead_tension": np.ones((1, 3))}
    store.record((0,), result)
    with pytest.raises(CaseError):
        store.record((1,), {**result, "time": np.arange(4.0),
                            "fairlead_tension": np.ones((1, 4))})
    assert store.status[1] == "pending"  # not "complete" with NaN histories


@pytest.mark.parametrize("first, then", [([], ["--timeseries"]), (["--timeseries"], [])])
def test_resume_with_the_other_timeseries_choice_refused(tmp_path, capsys, first, then):
    out = tmp_path / "c.nc"
    sweep = ["sweep", str(LINDAHL_CASE), *QS, "--set", "simulation.duration=3",
             "--grid", "motion.period=1.25,1.5", "-o", str(out), "--quiet"]
    assert main([*sweep, *first]) == 0
    before = out.read_bytes()
    assert main([*sweep, *then]) == 2
    assert "time series" in capsys.readouterr().err
    assert out.read_bytes() == before
    assert list(read_dataset(out)["status"].values) == ["complete", "complete"]
