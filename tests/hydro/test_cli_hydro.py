"""``floatmoor hydro build | check | info``: outputs and exit statuses."""

from __future__ import annotations

import json
import shutil
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


#: Every check the tiny database (3 frequencies) may fail: its K(t) cannot decay within the
#: truncation time, and its coarse mesh misses the checks' tolerances (kernel_decay inf,
#: kramers_kronig 25 %, hydrostatics 2.6 %, symmetry 1.5 %).
TINY_ACCEPTS = 'hydro.accept_failed_checks=["symmetry", "kramers_kronig", "kernel_decay", ' \
    '"haskind", "hydrostatics"]'


def test_build_writes_database_then_skips_when_up_to_date(tiny_case, capsys):
    """The tiny database fails its checks: written (failed checks recorded), exit 1; up
    to date on a re-run, checks reported again; accepted by the case: exit 0."""
    assert main(["hydro", "build", str(tiny_case)]) == 1
    out = capsys.readouterr()
    target = tiny_case.parent / "hydrodb" / "tiny.nc"
    assert target.is_file() and "hull" in out.out
    assert "3 / 4 frequencies" in out.err or "4 / 4 frequencies" in out.err
    ds = read_database(target)
    assert ds.sizes["omega"] == 3 and ds.attrs["geometry_kind"] == "cylinder"
    assert "kernel_decay" in ds.attrs["checks_failed"]
    mtime = target.stat().st_mtime_ns
    assert main(["hydro", "build", str(tiny_case)]) == 1
    out = capsys.readouterr()
    assert "up to date" in out.out and "kernel_decay    FAIL" in out.out
    assert target.stat().st_mtime_ns == mtime
    assert main(["hydro", "build", str(tiny_case), "--set", TINY_ACCEPTS]) == 0
    out = capsys.readouterr()
    assert "kernel_decay    FAIL*" in out.out and "accepted by the case" in out.out
    assert target.stat().st_mtime_ns == mtime
    assert main(["hydro", "build", str(tiny_case), "--force", "--quiet", "--set", TINY_ACCEPTS,
                 "-o", str(tiny_case.parent / "other.nc")]) == 0
    assert (tiny_case.parent / "other.nc").is_file()


def test_build_runs_the_checks_and_exits_1_when_one_fails(tmp_path, buoy_db, capsys,
                                                         monkeypatch):
    """``hydro build`` prints the table of ``hydro check`` for what it built; a failed check
    (here the Haskind relation of a database whose excitation is 20 % too large, built by a
    stand-in for the BEM) exits 1 naming it, the database written with the failure recorded
    for inspection."""
    import floatmoor.hydro.database as database

    from floatmoor.hydro.drift_build import DRIFT_VARIABLES

    # what a BEM build returns: the shipped database without its drift coefficients
    bad = buoy_db.drop_vars(list(DRIFT_VARIABLES) + ["drift_term"]).copy(deep=True)
    bad["excitation_force"] = bad["excitation_force"] * 1.2
    bad.attrs["build_seconds"] = 0.0
    monkeypatch.setattr(database, "build_database", lambda case, progress=None: bad)
    target = tmp_path / "built.nc"
    assert main(["hydro", "build", str(BUOY_CASE), "-o", str(target), "--quiet"]) == 1
    out = capsys.readouterr()
    assert "haskind         FAIL" in out.out and "symmetry        pass" in out.out
    assert out.out.strip().endswith("a check FAILED")
    err = out.err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"floatmoor: hydro build: {target} is written "
                                               "but fails its checks: haskind (worst 0.441")
    assert 'accept_failed_checks = ["haskind"]' in err[0]
    written = read_database(target)
    assert written.attrs["checks_failed"] == "haskind"
    recorded = {c["name"]: c["passed"] for c in json.loads(written.attrs["checks_json"])}
    assert recorded == {"symmetry": True, "damping_psd": True, "kramers_kronig": True,
                        "kernel_decay": True, "haskind": False, "hydrostatics": True}
    # a database passing every check builds with status 0
    monkeypatch.setattr(database, "build_database", lambda case, progress=None: buoy_db)
    assert main(["hydro", "build", str(BUOY_CASE), "-o", str(tmp_path / "good.nc"),
                 "--quiet", "--force"]) == 0
    assert "all checks pass" in capsys.readouterr().out


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


def test_check_stale_database_exits_2(tmp_path, buoy_db, capsys):
    """The recorded case file is found in the database's project (the folder above its
    hydrodb/), wherever the command runs."""
    stale = buoy_db.copy(deep=True)
    inputs = json.loads(stale.attrs["inputs_json"])
    inputs["panel_size"] = 0.05
    stale.attrs["inputs_json"] = json.dumps(inputs)
    stale.attrs["inputs_hash"] = "0" * 64
    case = tmp_path / stale.attrs["case_file"]
    case.parent.mkdir(parents=True)
    shutil.copy(REPO / stale.attrs["case_file"], case)
    path = tmp_path / "hydrodb" / "stale.nc"
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
    """omega = 0 is solved only in deep water (docs/theory/hydrodynamics.md, practical note 2); the heave added
    mass falls from omega = 0 to infinity for a floating cylinder."""
    out = tiny_case.parent / "deep.nc"
    assert main(["hydro", "build", str(tiny_case), "--quiet", "-o", str(out),
                 "--set", "hydro.infinite_depth=true", "--set", "hydro.lid=false",
                 "--set", TINY_ACCEPTS]) == 0
    ds = read_database(out)
    assert ds.attrs["bem_water_depth"] == "infinite"
    a0 = ds["added_mass_zero"].sel(radiating_dof="Heave", influenced_dof="Heave").item()
    a_inf = ds["added_mass_infinite"].sel(radiating_dof="Heave", influenced_dof="Heave").item()
    assert a0 > a_inf > 0.0


def test_floatmoor_check_shows_the_checks_a_case_accepts(capsys):
    case = str(REPO / "cases" / "deepcwind" / "deepcwind_free_decay.toml")
    assert main(["check", case, "--set", 'hydro.accept_failed_checks=["kernel_decay"]']) == 0
    assert "accepts failed checks: kernel_decay" in capsys.readouterr().out
    assert main(["check", case]) == 0
    assert "accepts failed checks" not in capsys.readouterr().out
