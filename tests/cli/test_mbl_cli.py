"""The minimum breaking load on the command line: ``check`` prints the static strain, T / MBL
and the safety factor and refuses a static tension at the MBL; ``run`` refuses it too, and its
summary (text and --json) and output file carry the largest tension over the MBL."""

from __future__ import annotations

import json

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.io.netcdf import read_dataset
from floatmoor.mooring.static_strength import static_line_loads
from tests.conftest import CASES, LINDAHL_CASE

KEY = "line_types.chain.minimum_breaking_load"
QS = ["--set", 'lines.chain.model="quasi-static"', "--set", "simulation.duration=4.0"]
DEEPCWIND = CASES / "deepcwind" / "deepcwind_lc34.toml"
BUOY = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"


def _row(text: str, line: str) -> list[str]:
    """The row of ``line`` in check's strength block (the one with the strain column)."""
    return next(r.split() for r in text.splitlines() if r.split()[:1] == [line] and "%" in r)


def test_check_prints_strain_ratio_and_safety_factor(capsys):
    assert main(["check", str(LINDAHL_CASE), "--set", f"{KEY}=50.0"]) == 0
    text = capsys.readouterr().out
    (load,) = static_line_loads(load_case(LINDAHL_CASE, [f"{KEY}=50.0"]))
    row = _row(text, "chain")
    assert float(row[1]) == pytest.approx(load.fairlead_tension, rel=1e-4)
    assert float(row[2]) == pytest.approx(100.0 * load.fairlead_tension / 1.0e4, rel=1e-2)
    assert row[3] == "%" and float(row[4]) == 50.0
    assert float(row[5]) == pytest.approx(load.fairlead_tension / 50.0, rel=1e-3)
    assert float(row[6]) == pytest.approx(50.0 / load.fairlead_tension, rel=1e-3)
    # without an MBL the row says so
    assert main(["check", str(LINDAHL_CASE)]) == 0
    assert _row(capsys.readouterr().out, "chain")[4:] == ["no", "MBL", "-", "-"]


def test_check_and_run_refuse_a_static_tension_above_the_mbl(tmp_path, capsys):
    (load,) = static_line_loads(load_case(LINDAHL_CASE))
    mbl = 0.9 * load.fairlead_tension
    assert main(["check", str(LINDAHL_CASE), "--set", f"{KEY}={mbl!r}"]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    (message,) = captured.err.strip().splitlines()
    assert message.startswith(f"floatmoor: error: {LINDAHL_CASE}: {KEY}: expected")
    assert "line 'chain'" in message and f"{load.fairlead_tension:.6g} N" in message
    assert f"found {mbl!r} N" in message
    out = tmp_path / "a.nc"
    assert main(["run", str(LINDAHL_CASE), *QS, "--set", f"{KEY}={mbl!r}", "-o", str(out),
                 "--quiet"]) == 2
    assert "line 'chain'" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_check_of_the_issue_case_strain_is_visible_and_refused(capsys):
    # a line shortened until the static strain is ~20 %
    short = ["--set", "lines.line1.length=680.0"]
    assert main(["check", str(DEEPCWIND), *short]) == 0
    text = capsys.readouterr().out
    strain = float(_row(text, "line1")[2])
    assert strain > 15.0
    assert "warning: line 'line1' is stretched" in text and KEY in text
    assert "warning: line 'line2'" not in text
    # with an MBL (DNV-OS-E302 studless R3 at 77.9 mm, see the case file) it is an error
    assert main(["check", str(DEEPCWIND), *short, "--set", f"{KEY}=5.111e6"]) == 2
    captured = capsys.readouterr()
    assert "valid case" not in captured.out and "line 'line1'" in captured.err


def test_run_summary_json_and_dataset_carry_the_mbl_ratio(tmp_path, capsys):
    out = tmp_path / "a.nc"
    assert main(["run", str(LINDAHL_CASE), *QS, "--set", f"{KEY}=60.0", "-o", str(out),
                 "--quiet", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    ds = read_dataset(out)
    assert float(ds["minimum_breaking_load"].sel(line="chain")) == 60.0
    assert ds["minimum_breaking_load"].attrs["units"] == "N"
    assert ds["minimum_breaking_load"].attrs["long_name"]
    s = summary["lines"]["chain"]["strength"]
    start = summary["lines"]["chain"]["fairlead_tension_N"]["window_start"]
    after = ds["time"].values >= start
    both = np.maximum(ds["fairlead_tension"].values[0], ds["anchor_tension"].values[0])
    assert s["max_tension_N"] == pytest.approx(both[after].max(), rel=1e-15)
    assert s["whole_run_max_tension_N"] == pytest.approx(both.max(), rel=1e-15)
    assert s["minimum_breaking_load_N"] == 60.0
    assert s["max_tension_over_mbl"] == pytest.approx(s["max_tension_N"] / 60.0, rel=1e-15)
    assert s["safety_factor"] == pytest.approx(60.0 / s["max_tension_N"], rel=1e-15)
    assert s["max_tension_end"] == "fairlead"  # a static chain with a resting length

    # the text summary prints the same numbers; an MBL below T_max warns that the line breaks
    assert main(["run", str(LINDAHL_CASE), *QS, "--set", f"{KEY}=30.0", "-o",
                 str(tmp_path / "b.nc"), "--quiet"]) == 0
    text = capsys.readouterr().out
    row = next(r.split() for r in text.splitlines() if r.split()[:2] == ["chain", "%.4g" % (
        s["max_tension_N"])])
    assert float(row[4]) == 30.0
    assert float(row[5]) == pytest.approx(s["max_tension_N"] / 30.0, rel=1e-3)
    assert float(row[6]) == pytest.approx(30.0 / s["max_tension_N"], rel=1e-2)
    assert "warning: line 'chain' reached its MBL" in text


def test_run_summary_without_mbl_says_so(tmp_path, capsys):
    assert main(["run", str(LINDAHL_CASE), *QS, "-o", str(tmp_path / "a.nc"), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "no MBL" in text and "reached its MBL" not in text
    assert "minimum_breaking_load" not in read_dataset(tmp_path / "a.nc")


def test_coupled_run_summary_carries_the_mbl_ratio(tmp_path, capsys):
    qs = ['lines.*.model="quasi-static"']
    sets = [x for o in [*qs, "simulation.duration=1.0", "simulation.output_interval=0.02",
                        'waves={kind = "regular", height = 0.04, period = 1.2, '
                        'ramp_duration = 0.4}', f"{KEY}=20.0"] for x in ("--set", o)]
    out = tmp_path / "buoy.nc"
    assert main(["run", str(BUOY), *sets, "-o", str(out), "--quiet", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    ds = read_dataset(out)
    for line in ("line1", "line2", "line3"):
        s = summary["lines"][line]["strength"]
        both = np.maximum(ds["fairlead_tension"].sel(line=line).values,
                          ds["anchor_tension"].sel(line=line).values)
        assert s["whole_run_max_tension_N"] == pytest.approx(both.max(), rel=1e-15)
        assert s["max_tension_over_mbl"] == pytest.approx(s["max_tension_N"] / 20.0)
        assert 0.1 < s["max_tension_over_mbl"] < 1.0
