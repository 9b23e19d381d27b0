"""``floatmoor report``: figures and tables of real short runs, checked against floatmoor.post."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import matplotlib.image
import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.io.netcdf import read_dataset, write_dataset
from floatmoor.post.fatigue import DNV_STUDLESS_CHAIN, chain_nominal_area, fatigue_damage
from floatmoor.post.statistics import time_statistics
from floatmoor.report.build import write_report
from floatmoor.cli.report import report_command
from floatmoor.report.figures import FigureDataError, check_series, decay_fit
from floatmoor.report.runs import LineChain, load_run
from floatmoor.simulation.coupled_run import run_coupled
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import CASES, LINDAHL_CASE

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
QS_LINES = ['lines.*.model="quasi-static"']
BUOY_WAVES = ["simulation.duration=3.0", "simulation.output_interval=0.02",
              'waves={kind = "regular", height = 0.04, period = 1.2, ramp_duration = 1.2}',
              *QS_LINES]
BUOY_DECAY = ["simulation.duration=3.0", "simulation.output_interval=0.02",
              'waves={kind = "still"}', "initial={heave = 0.02}", *QS_LINES]

#: A figure file smaller than this [bytes] is taken as empty (a blank 990 px wide PNG
#: with axes only is ~20 kB; the report's figures are 50-200 kB).
MIN_PNG_BYTES = 20_000
#: Variance of the grey levels (0..1) of a figure below which it counts as blank: a white
#: page with a few thin lines has ~1e-3, the report's plots 1e-2 or more.
MIN_PIXEL_VARIANCE = 5e-3
#: Relative agreement of a number printed in a table (4 significant digits: half a unit of
#: the 4th digit is at most 5e-4 relative) with its direct computation.
TABLE_RTOL = 5e-4


def _namespace(**kwargs) -> argparse.Namespace:
    base = dict(start=None, reference=None, nominal_diameter=[], html=False)
    base.update(kwargs)
    return argparse.Namespace(**base)


def table_rows(markdown: str, title: str) -> list[list[str]]:
    """The rows (header first) of the table headed ``**title**`` in a summary."""
    lines = markdown.splitlines()
    i = lines.index(f"**{title}**") + 2
    rows = []
    while i < len(lines) and lines[i].startswith("|"):
        if not lines[i].startswith("| ---") and not lines[i].startswith("|---"):
            rows.append([c.strip() for c in lines[i].strip("|").split(" | ")])
        i += 1
    return rows


def cell(rows: list[list[str]], row: str, column: str) -> str:
    col = rows[0].index(column)
    return next(r for r in rows[1:] if r[0] == row)[col]


def assert_png_not_blank(path: Path) -> None:
    assert path.is_file(), path
    assert path.stat().st_size > MIN_PNG_BYTES, (path, path.stat().st_size)
    image = matplotlib.image.imread(path)
    grey = image[..., :3].mean(axis=-1)
    assert float(grey.var()) > MIN_PIXEL_VARIANCE, (path, float(grey.var()))


@pytest.fixture(scope="module")
def runs_dir(tmp_path_factory) -> Path:
    """A Lindahl forced-motion run, a coupled buoy run in waves and a buoy heave decay."""
    folder = tmp_path_factory.mktemp("runs")
    run_forced_motion(load_case(LINDAHL_CASE), output=folder / "lindahl.nc")
    run_coupled(load_case(BUOY_CASE, BUOY_WAVES), output=folder / "buoy.nc")
    run_coupled(load_case(BUOY_CASE, BUOY_DECAY), output=folder / "decay.nc")
    return folder


def test_report_of_two_runs_side_by_side(runs_dir, tmp_path, capsys) -> None:
    out = tmp_path / "report"
    status = report_command(_namespace(runs=[str(runs_dir / "lindahl.nc"),
                                             str(runs_dir / "buoy.nc")], output=str(out),
                                       html=True))
    assert status == 0, capsys.readouterr().err
    expected = ["tension_timeseries.png", "tension_psd.png", "tension_exceedance.png",
                "rainflow_histogram.png", "motion_timeseries.png", "motion_psd.png"]
    for name in expected:
        assert_png_not_blank(out / name)
    md = (out / "summary.md").read_text()
    assert (out / "summary.html").is_file()
    for name in expected:
        assert f"]({name})" in md
    # side by side: both runs are columns of the tension and damage tables
    rows = table_rows(md, "Fairlead tension statistics, line chain")
    assert rows[0][2:4] == ["lindahl", "buoy"]
    damage_rows = table_rows(md, "Fatigue damage (Miner) of the fairlead tension")
    assert damage_rows[0] == ["line", "lindahl", "buoy"]

    # numbers cross-checked against floatmoor.post, over the window after the ramps
    lindahl = read_dataset(runs_dir / "lindahl.nc")
    ramp = load_case(LINDAHL_CASE).motion.ramp_duration
    mean = float(time_statistics(lindahl["fairlead_tension"], start=ramp)["mean"]
                 .sel(line="chain"))
    assert float(cell(rows, "mean", "lindahl")) == pytest.approx(mean, rel=TABLE_RTOL)
    area = chain_nominal_area(load_case(LINDAHL_CASE).line_types["chain"].diameter)
    damage = float(fatigue_damage(lindahl["fairlead_tension"].sel(line="chain"),
                                  DNV_STUDLESS_CHAIN, start=ramp, nominal_area=area))
    assert damage > 0.0
    assert float(cell(damage_rows, "chain", "lindahl")) == pytest.approx(damage, rel=TABLE_RTOL)
    buoy = read_dataset(runs_dir / "buoy.nc")
    buoy_ramp = load_case(BUOY_CASE, BUOY_WAVES).waves.ramp_duration
    std = float(time_statistics(buoy["fairlead_tension"], start=buoy_ramp)["std"]
                .sel(line="line3"))
    rows3 = table_rows(md, "Fairlead tension statistics, line line3")
    assert float(cell(rows3, "std", "buoy")) == pytest.approx(std, rel=TABLE_RTOL)
    assert cell(rows3, "std", "lindahl") == "–"  # the line is not in that run
    # the window start is the ramp of each case, and is reported
    assert "2.5 s (motion ramp)" in md and f"{buoy_ramp:g} s (wave ramp)" in md


def test_start_option_and_nominal_diameter_change_the_numbers(runs_dir, tmp_path) -> None:
    out = tmp_path / "r"
    assert report_command(_namespace(runs=[str(runs_dir / "lindahl.nc")], output=str(out),
                                     start="5", nominal_diameter=["chain=0.004"])) == 0
    md = (out / "summary.md").read_text()
    lindahl = read_dataset(runs_dir / "lindahl.nc")
    damage = float(fatigue_damage(lindahl["fairlead_tension"].sel(line="chain"),
                                  DNV_STUDLESS_CHAIN, start=5.0,
                                  nominal_area=chain_nominal_area(0.004)))
    rows = table_rows(md, "Fatigue damage (Miner) of the fairlead tension")
    assert float(cell(rows, "chain", "lindahl")) == pytest.approx(damage, rel=TABLE_RTOL)
    d_rows = table_rows(md, "Chain nominal diameters used for the damage")
    assert d_rows[1] == ["chain", "lindahl", "0.004", "--nominal-diameter"]
    assert "5 s (--start)" in md


def test_free_decay_figure_and_fit(runs_dir, tmp_path) -> None:
    files = write_report([load_run(runs_dir / "decay.nc")], tmp_path / "d")
    decay_png = tmp_path / "d" / "free_decay_1_heave.png"
    assert decay_png in files.figures
    assert_png_not_blank(decay_png)
    fit = files.analyses[0].decay["Heave"]
    assert fit is not None and fit.period > 0.0 and 0.0 < fit.damping_ratio < 1.0
    assert "**Free decay**" in files.summary.read_text()


#: A fit of a sampled damped cosine (200 samples per period) recovers zeta and T_d to this
#: relative accuracy; extrema are located to one sample, dt / T_d = 0.5 %.
DECAY_RTOL = 1e-2


@pytest.mark.parametrize("zeta", [0.02, 0.1])
def test_decay_fit_recovers_a_damped_oscillator(zeta: float) -> None:
    period_n, offset = 10.0, 0.3
    wn = 2.0 * math.pi / period_n
    wd = wn * math.sqrt(1.0 - zeta**2)
    t = np.arange(0.0, 60.0, 2.0 * math.pi / wd / 200.0)
    x = offset + 2.0 * np.exp(-zeta * wn * t) * np.cos(wd * t)
    fit = decay_fit(t, x)
    assert fit.damping_ratio == pytest.approx(zeta, rel=DECAY_RTOL)
    assert fit.period == pytest.approx(2.0 * math.pi / wd, rel=DECAY_RTOL)
    assert fit.level == pytest.approx(offset, abs=DECAY_RTOL)


def test_check_series_rejects_empty_and_nan() -> None:
    with pytest.raises(FigureDataError, match="no samples"):
        check_series([], "tension")
    with pytest.raises(FigureDataError, match="1 NaN"):
        check_series([1.0, np.nan, 2.0], "tension")
    assert check_series([1.0, 2.0], "ok").tolist() == [1.0, 2.0]


def test_a_nan_series_fails_the_report_and_writes_nothing(runs_dir, tmp_path, capsys) -> None:
    ds = read_dataset(runs_dir / "lindahl.nc")
    values = ds["fairlead_tension"].values.copy()
    values[0, -10] = np.nan
    ds["fairlead_tension"].values = values
    bad = tmp_path / "nan.nc"
    write_dataset(ds, bad)
    out = tmp_path / "report"
    assert report_command(_namespace(runs=[str(bad)], output=str(out))) == 2
    err = capsys.readouterr().err
    assert "NaN" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".floatmoor-report")]


def test_volume_equivalent_diameter_is_flagged() -> None:
    # docs/cases/deepcwind.md: 125.6 kg/m; volume-equivalent 0.1393 m, nominal 0.0779 m
    assert LineChain("line1", "chain", 0.1393, 125.6).looks_volume_equivalent
    assert not LineChain("line1", "chain", 0.0779, 125.6).looks_volume_equivalent
    # Lindahl's chain: 0.0818 kg/m at its nominal 2.2 mm
    assert not LineChain("chain", "chain", 2.2e-3, 0.0818).looks_volume_equivalent


def test_runs_outside_their_models_validity_are_flagged(runs_dir, tmp_path, capsys) -> None:
    """A run whose file records validity warnings (floatmoor.simulation.validity) is named
    under the Runs table with them: the report does not show its numbers as if valid."""
    ds = read_dataset(runs_dir / "lindahl.nc").load()
    ds.attrs["validity_warnings"] = ("line 'chain' (quasi-dynamic): dimensionless "
                                     "acceleration 1.36 at t = 5.2275 s")
    flagged = tmp_path / "flagged.nc"
    write_dataset(ds, flagged)
    out = tmp_path / "report"
    status = report_command(_namespace(runs=[str(flagged), str(runs_dir / "buoy.nc")],
                                       output=str(out), html=False))
    assert status == 0, capsys.readouterr().err
    md = (out / "summary.md").read_text()
    assert "**Run flagged is outside its model's validity**: line 'chain' (quasi-dynamic): " \
        "dimensionless acceleration 1.36" in md
    assert "Run buoy is outside" not in md
