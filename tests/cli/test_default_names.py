"""Default output names carry the overrides (by the campaign's run-name rule), so a run with
``--set`` no longer overwrites the quick start's own file."""

from __future__ import annotations

import re

from floatmoor.campaign.design import design_from_options
from floatmoor.case.load import load_case
from floatmoor.case.naming import MAX_NAME_LENGTH, file_stem
from floatmoor.cli import main
from floatmoor.cli.run_case import default_stem as _default_stem
from floatmoor.io.netcdf import read_dataset
from tests.conftest import LINDAHL_CASE

#: A short, cheap run of the Lindahl case.
SHORT = ["--set", 'lines.*.model="quasi-static"', "--set", "simulation.duration=0.5",
         "--set", "motion.ramp_duration=0.2"]


def test_run_with_overrides_writes_a_name_that_carries_them(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    argv = ["run", str(LINDAHL_CASE), "--quiet", "--set", "motion.period=3.5",
            "--set", "motion.radius=0.15", *SHORT]
    assert main(argv) == 0, capsys.readouterr().err
    expected = ("lindahl_r0.20_T1.25_motion.period=3.5_motion.radius=0.15_lines.all.model="
                "quasi-static_simulation.duration=0.5_motion.ramp_duration=0.2.nc")
    assert [p.name for p in tmp_path.iterdir()] == [expected]
    out = capsys.readouterr().out
    assert expected in out
    # the title in the summary and in the file carries the new values, not the file's
    title = "Lindahl chain, circular motion r = 0.15 m, T = 3.50 s [lines.*.model=quasi-static"
    assert out.startswith(title)
    assert read_dataset(tmp_path / expected).attrs["title"].startswith(title)


def test_default_names_without_overrides_are_unchanged():
    assert _default_stem(load_case(LINDAHL_CASE)) == "lindahl_r0.20_T1.25"


def test_sweep_default_carries_the_base_overrides(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["sweep", str(LINDAHL_CASE), "--quiet", *SHORT,
                 "--grid", "motion.period=1.25,1.5"]) == 0, capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == [
        "lindahl_r0.20_T1.25_lines.all.model=quasi-static_simulation.duration=0.5_"
        "motion.ramp_duration=0.2_campaign.nc"]


def test_file_stems_are_safe_and_long_values_shortened_deterministically():
    assert file_stem([("motion.period", 3.5), ("lines.*.model", "quasi-static")]) == \
        "motion.period=3.5_lines.all.model=quasi-static"
    assert file_stem([("motion.file", "../a b/'c'.csv")]) == "motion.file=..-ab-c.csv"
    long_value = [float(i) for i in range(40)]
    stem = file_stem([("motion.amplitude", long_value)])
    assert stem == file_stem([("motion.amplitude", long_value)])  # deterministic
    assert stem != file_stem([("motion.amplitude", long_value[:-1] + [0.5])])
    assert re.fullmatch(r"motion\.amplitude=0\.0,1\.0,2\.0,3\.0,-[0-9a-f]{8}", stem), stem
    many = file_stem([(f"lines.line{i}.length", 30.0 + i) for i in range(20)])
    assert len(many) == MAX_NAME_LENGTH and re.fullmatch(r"[A-Za-z0-9._+,=-]+", many)


def test_campaign_run_names_use_the_same_rule():
    design = design_from_options(["motion.radius=0.1,0.15", "motion.period=1.25"])
    assert design.run_names() == [
        file_stem([("motion.radius", r), ("motion.period", 1.25)]) for r in (0.1, 0.15)]
    assert design.run_names()[0] == "motion.radius=0.1_motion.period=1.25"
