"""The report's strength table: the largest tension against the minimum breaking load, beside
the fatigue tables, checked against the run's own numbers."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.io.netcdf import read_dataset, write_dataset
from floatmoor.report.build import write_report
from floatmoor.report.runs import load_run
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE
from tests.report.test_report import TABLE_RTOL, table_rows

KEY = "line_types.chain.minimum_breaking_load"
#: Quasi-static, 8 s: five cycles after the 2.5 s ramp (the exceedance figure needs extrema).
QS = ['lines.chain.model="quasi-static"', "simulation.duration=8.0"]
TITLE = "Largest tension against the minimum breaking load"


def test_report_shows_max_tension_mbl_ratio_and_safety_factor(tmp_path):
    with_mbl = tmp_path / "mbl.nc"
    without = tmp_path / "none.nc"
    run_forced_motion(load_case(LINDAHL_CASE, [*QS, f"{KEY}=40.0"]), output=with_mbl)
    run_forced_motion(load_case(LINDAHL_CASE, QS), output=without)
    # a file written before the variable existed: the MBL comes from the case in its attributes
    old = read_dataset(with_mbl).drop_vars("minimum_breaking_load")
    write_dataset(old, tmp_path / "old.nc")
    runs = [load_run(p) for p in (with_mbl, without, tmp_path / "old.nc")]
    files = write_report(runs, tmp_path / "report")
    md = files.summary.read_text()
    # beside the fatigue tables: after the damage table, before the floater or the end
    assert md.index(TITLE) > md.index("Fatigue damage (Miner) of the fairlead tension")
    rows = table_rows(md, TITLE)
    assert rows[0] == ["line", "run", "T_max [N]", "at", "t [s]", "MBL [N]", "T_max / MBL",
                       "safety factor"]
    by_run = {r[1]: r for r in rows[1:]}
    ds = read_dataset(with_mbl)
    after = ds["time"].values >= 2.5
    t_max = max(ds["fairlead_tension"].values[0][after].max(),
                ds["anchor_tension"].values[0][after].max())
    for label in ("mbl", "old"):
        row = by_run[label]
        assert float(row[2]) == pytest.approx(t_max, rel=TABLE_RTOL)
        assert row[3] == "fairlead" and float(row[5]) == 40.0
        assert float(row[6]) == pytest.approx(t_max / 40.0, rel=TABLE_RTOL)
        assert float(row[7]) == pytest.approx(40.0 / t_max, rel=TABLE_RTOL)
    assert by_run["none"][5:] == ["no MBL", "–", "–"]
    assert t_max > 40.0  # the MBL was chosen below the peak: the caution names the line
    assert "Caution: the tension reached the MBL on line chain of run mbl" in md
    assert np.isfinite(files.analyses[0].strength["chain"]["safety_factor"])
