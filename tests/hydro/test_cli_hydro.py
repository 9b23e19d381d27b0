"""``floatmoor hydro build | check | info``: outputs and exit statuses."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from floatmoor.cli import main
from floatmoor.hydro.database import read_database, write_database
from tests.hydro.conftest import BUOY_DB, BUOY_CASE, REPO

TINY_CASE = """
title = "tiny floating cylinder"
[environment]
water_density = 1000.0
water_depth = 2.0
gravity = 9.81
[seabed]
stiffness = 1.0e6
damping_ratio = 1.0
friction_coefficient = 0.0
slip_speed = 0.01
[floater]
name = "tiny"
mass = 50.0
centre_of_mass = [0.0, 0.0, -0.1]
inertia = [2.0, 2.0, 1.5]
reference_point = [0.0, 0.0, 0.0]
[floater.geometry]
kind = "cylinder"
diameter = 0.5
height = 0.6
[hydro]
database = "tiny"
frequencies = [2.0, 4.0, 6.0]
directions_deg = [0.0]
panel_size = 0.1
[simulation]
duration = 1.0
output_interval = 0.1
"""


@pytest.fixture
def tiny_case(tmp_path) -> Path:
    (tmp_path / "hydrodb").mkdir()
    path = tmp_path / "tiny.toml"
    path.write_text(TINY_CASE)
    return path


def test_build_writes_database_then_skips_when_up_to_date(tiny_case, capsys):
    assert main(["hydro", "build", str(tiny_case)]) == 0
    out = capsys.readouterr()
    target = tiny_case.parent / "hydrodb" / "tiny.nc"
    assert target.is_file() and "hull" in out.out
    assert "3 / 4 frequencies" in out.err or "4 / 4 frequencies" in out.err
    ds = read_database(target)
    assert ds.sizes["omega"] == 3 and ds.attrs["geometry_kind"] == "cylinder"
    mtime = target.stat().st_mtime_ns
    assert main(["hydro", "build", str(tiny_case)]) == 0
    assert "up to date" in capsys.readouterr().out
    assert target.stat().st_mtime_ns == mtime
    assert main(["hydro", "build", str(tiny_case), "--force", "--quiet",
                 "-o", str(tiny_case.parent / "other.nc")]) == 0
    assert (tiny_case.parent / "other.nc").is_file()


def test_build_bad_case_exits_2_without_output(tiny_case, capsys):
    status = main(["hydro", "build", str(tiny_case), "--set", "floater.mass=-1.0"])
    err = capsys.readouterr().err
    assert status == 2 and err.startswith("floatmoor: error: ") and "floater.mass" in err
    assert len(err.strip().splitlines()) == 1
    assert list((tiny_case.parent / "hydrodb").iterdir()) == []


def test_build_case_without_floater_exits_2(capsys):
    status = main(["hydro", "build", str(REPO / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml")])
    assert status == 2 and "[floater]" in capsys.readouterr().err


def test_check_shipped_database_exits_0(capsys, monkeypatch):
    monkeypatch.chdir(REPO)
    assert main(["hydro", "check", "cylinder_buoy", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["passed"] and report["staleness"].startswith("up to date")
    assert {c["name"] for c in report["checks"]} >= {"symmetry", "haskind", "kramers_kronig"}


def test_check_failing_database_exits_1(tmp_path, buoy_db, capsys, monkeypatch):
    monkeypatch.chdir(REPO)
    bad = buoy_db.copy(deep=True)
    bad["excitation_force"] *= 1.2
    path = tmp_path / "bad.nc"
    write_database(bad, path)
    assert main(["hydro", "check", str(path)]) == 1
    assert "FAIL" in capsys.readouterr().out


def test_check_damaged_or_missing_database_exits_2(tmp_path, capsys):
    path = tmp_path / "cut.nc"
    path.write_bytes(BUOY_DB.read_bytes()[:1000])
    assert main(["hydro", "check", str(path)]) == 2
    assert "damaged" in capsys.readouterr().err
    assert main(["hydro", "check", str(tmp_path / "absent.nc")]) == 2


def test_check_stale_database_exits_2(tmp_path, buoy_db, capsys, monkeypatch):
    monkeypatch.chdir(REPO)
    stale = buoy_db.copy(deep=True)
    inputs = json.loads(stale.attrs["inputs_json"])
    inputs["panel_size"] = 0.05
    stale.attrs["inputs_json"] = json.dumps(inputs)
    stale.attrs["inputs_hash"] = "0" * 64
    path = tmp_path / "stale.nc"
    write_database(stale, path)
    assert main(["hydro", "check", str(path)]) == 2
    assert "stale" in capsys.readouterr().err
    assert main(["hydro", "info", str(path)]) == 2


def test_info_describes_database(capsys, monkeypatch):
    monkeypatch.chdir(REPO)
    assert main(["hydro", "info", str(BUOY_DB)]) == 0
    out = capsys.readouterr().out
    assert "hull" in out and "capytaine" in out and str(BUOY_CASE.relative_to(REPO)) in out


@pytest.mark.parametrize("case", [
    "deepcwind/deepcwind_free_decay.toml",
    # the buoy's dynamic lines build their DG discretisation: ~10 s
    pytest.param("cylinder_buoy/buoy_regular_T1.20.toml", marks=pytest.mark.slow),
])
def test_floatmoor_check_prints_floater_cases(capsys, case):
    assert main(["check", str(REPO / "cases" / case)]) == 0
    assert "floater:" in capsys.readouterr().out


def test_infinite_depth_build_adds_zero_frequency_added_mass(tiny_case, capsys):
    """omega = 0 is solved only in deep water (capytaine_notes.md pitfall 2); the heave added
    mass falls from omega = 0 to infinity for a floating cylinder."""
    out = tiny_case.parent / "deep.nc"
    assert main(["hydro", "build", str(tiny_case), "--quiet", "-o", str(out),
                 "--set", "hydro.infinite_depth=true", "--set", "hydro.lid=false"]) == 0
    ds = read_database(out)
    assert ds.attrs["bem_water_depth"] == "infinite"
    a0 = ds["added_mass_zero"].sel(radiating_dof="Heave", influenced_dof="Heave").item()
    a_inf = ds["added_mass_infinite"].sel(radiating_dof="Heave", influenced_dof="Heave").item()
    assert a0 > a_inf > 0.0
