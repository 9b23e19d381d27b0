"""Reports of a sweep: every run labelled and titled by what makes it different, legends whole."""

from __future__ import annotations

from pathlib import Path

import matplotlib.image
import xarray as xr

from floatmoor.cli import main
from floatmoor.report.figures import DPI
from floatmoor.report.runs import RunData, run_labels
from tests.conftest import LINDAHL_CASE
from tests.report.test_report import table_rows

#: Short quasi-static runs with a few tension extrema after the ramp (about 0.5 s each).
SHORT = ["--set", 'lines.*.model="quasi-static"', "--set", "simulation.duration=2.0",
         "--set", "motion.ramp_duration=0.5"]
#: Width of the report's figures before any widening for legends [inch] (figures._panels).
PANEL_WIDTH = 9.0


def test_report_of_a_small_sweep_labels_and_titles_runs_apart(tmp_path, capsys) -> None:
    runs = tmp_path / "runs"
    assert main(["sweep", str(LINDAHL_CASE), "--quiet", *SHORT, "-o", str(tmp_path / "c.nc"),
                 "--grid", "motion.radius=0.15,0.2", "--grid", "motion.period=1.25,1.5",
                 "--runs-dir", str(runs)]) == 0, capsys.readouterr().err
    files = sorted(str(p) for p in runs.glob("*.nc"))
    assert main(["report", *files, "-o", str(tmp_path / "rep")]) == 0, capsys.readouterr().err
    summary = (tmp_path / "rep" / "summary.md").read_text()
    header = table_rows(summary, "Fairlead tension statistics, line chain")[0][2:]
    # the swept values, not what all runs share (the base overrides), label the columns
    assert header == ["motion.radius=0.15, motion.period=1.25",
                      "motion.radius=0.15, motion.period=1.5",
                      "motion.radius=0.2, motion.period=1.25", "motion.radius=0.2, motion.period=1.5"]
    titles = [row[2] for row in table_rows(summary, "Runs")[1:]]
    assert len(set(titles)) == 4
    assert titles[1].startswith("Lindahl chain, circular motion r = 0.15 m, T = 1.50 s [")
    # the report's title is what the runs share, not the first run's
    assert summary.startswith("# Lindahl chain (4 runs)\n")
    # the legend beside the axes is not cut at the figure's edge: the figure grows for it
    image = matplotlib.image.imread(tmp_path / "rep" / "tension_timeseries.png")
    assert image.shape[1] > PANEL_WIDTH * DPI + 10


def _run(name: str, case_file: str, overrides: list[str], toml: str = "") -> RunData:
    dataset = xr.Dataset(attrs={"case_file": case_file, "case_toml": toml,
                                "case_overrides": "\n".join(overrides) or "none"})
    return RunData(label=name, dataset=dataset, start=0.0, start_source="test",
                   path=Path(f"{name}.nc"))


def test_a_run_without_the_override_shows_its_case_file_value() -> None:
    toml = "[motion]\nperiod = 1.25\n"
    runs = [_run("a", "case.toml", ["simulation.duration=5.0"], toml),
            _run("b", "case.toml", ["simulation.duration=5.0", "motion.period=3.5"], toml)]
    assert run_labels(runs) == ["motion.period=1.25", "motion.period=3.5"]


def test_runs_of_different_case_files_lead_with_the_file() -> None:
    """Overrides are compared between runs of the same case file only."""
    runs = [_run("T1.00", "buoy_T1.00.toml", ['lines.*.model="dynamic"']),
            _run("T1.20", "buoy_T1.20.toml", ['lines.*.model="quasi-static"']),
            _run("T1.20-qd", "buoy_T1.20.toml", ['lines.*.model="quasi-dynamic"'])]
    assert run_labels(runs) == ["T1.00", "T1.20 [lines.*.model=quasi-static]",
                                "T1.20-qd [lines.*.model=quasi-dynamic]"]


def test_alike_runs_are_numbered() -> None:
    same = [_run("x", "case.toml", []), _run("x", "case.toml", [])]
    assert run_labels(same) == ["x", "x #2"]
