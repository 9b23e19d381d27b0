"""``floatmoor hydro import``: the OC4 WAMIT files in, a checked database out; provenance in
``hydro info``; broken files and bad options exit 2 with one line and write nothing."""

from __future__ import annotations

import json
import shutil

import pytest

from floatmoor.cli import main
from floatmoor.hydro.database import file_sha256, read_database
from tests.hydro.conftest import REPO

OC4 = REPO / "tests" / "data" / "wamit_oc4"
#: The options of the shipped hydrodb/deepcwind_wamit.nc (cases/deepcwind/
#: deepcwind_free_decay_wamit.toml's header).
OPTIONS = ["--water-density", "1025", "--gravity", "9.80665", "--water-depth", "200",
           "--reference-point", "0", "0", "0", "--displaced-volume", "13917",
           "--centre-of-buoyancy", "0", "0", "-13.17", "--yaw-deg", "180"]


@pytest.fixture
def oc4_copy(tmp_path):
    """The OC4 files copied to a project folder with a hydrodb/ folder."""
    (tmp_path / "hydrodb").mkdir()
    for name in ("marin_semi.1", "marin_semi.hst"):
        shutil.copy(OC4 / name, tmp_path / name)
    return tmp_path


def _import(folder, *extra, files=("marin_semi.1", "marin_semi.hst"), out="hydrodb/w.nc"):
    return main(["hydro", "import", *[str(folder / f) for f in files], "-o",
                 str(folder / out), *OPTIONS, *extra])


def test_import_checks_and_records_where_the_data_came_from(oc4_copy, capsys):
    assert _import(oc4_copy) == 0
    out = capsys.readouterr().out
    assert "498 frequencies" in out and "A_inf file (WAMIT .1, PER = 0)" in out
    assert "haskind         n/a" in out and "hydrostatics    n/a" in out
    assert "all checks pass (2 not applicable)" in out
    ds = read_database(oc4_copy / "hydrodb" / "w.nc")
    assert ds.attrs["source"] == "wamit" and ds.attrs["checks_failed"] == "none"
    files = json.loads(ds.attrs["source_files_json"])
    assert [f["path"] for f in files] == [str(oc4_copy / "marin_semi.1"),
                                          str(oc4_copy / "marin_semi.hst")]
    assert files[0]["sha256"] == file_sha256(OC4 / "marin_semi.1")
    assert files[0]["size"] == (OC4 / "marin_semi.1").stat().st_size
    options = json.loads(ds.attrs["import_options_json"])
    assert options["yaw_deg"] == 180.0 and options["water_depth"] == 200.0
    assert ds.attrs["import_command"].startswith("floatmoor hydro import ")
    assert "--displaced-volume 13917" in ds.attrs["import_command"]
    assert main(["hydro", "info", str(oc4_copy / "hydrodb" / "w.nc")]) == 0
    info = capsys.readouterr().out
    assert "source: wamit files, imported by floatmoor" in info
    assert f"marin_semi.1  494496 bytes  SHA-256 {files[0]['sha256']}" in info
    assert "A_inf: file (WAMIT .1, PER = 0)" in info
    assert "excitation: none" in info and "source files unchanged" in info
    assert "Turned by 180 deg" in info


def test_info_says_where_a_built_database_came_from(capsys):
    assert main(["hydro", "info", str(REPO / "hydrodb" / "deepcwind.nc")]) == 0
    info = capsys.readouterr().out
    assert "source: capytaine ('floatmoor hydro build'" in info
    assert "A_inf: capytaine (omega = infinity solved)" in info
    assert "excitation: excitation_force, Froude_Krylov_force, diffraction_force" in info


def test_existing_output_needs_force(oc4_copy, capsys):
    assert _import(oc4_copy) == 0
    target = oc4_copy / "hydrodb" / "w.nc"
    before = target.read_bytes()
    capsys.readouterr()
    assert _import(oc4_copy) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"floatmoor: error: -o/--output: expected a new file (--force "
                   f"overwrites), found the existing file '{target}'"]
    assert target.read_bytes() == before
    assert _import(oc4_copy, "--force") == 0


def _broken(folder, name, edit):
    lines = (OC4 / name).read_text().splitlines(keepends=True)
    (folder / name).write_text("".join(edit(lines)))


def _replace(index, text):
    return lambda lines: lines[:index] + [text] + lines[index + 1:]


#: A .3 whose period (10 s) is none of the .1's.
FOREIGN_3 = "".join(f"  0.100000E+02   0.000000E+00 {i}  1.0 0.0 1.0 0.0\n"
                    for i in range(1, 7))


@pytest.mark.parametrize("name, edit, files, message", [
    ("marin_semi.1", _replace(40, "  0.628319E+03     3     3  NaN  1.805970E+02\n"), None,
     "marin_semi.1: line 41: expected a finite number"),
    ("marin_semi.1", _replace(40, "  0.628319E+03     3     3  1.499195E+04\n"), None,
     "marin_semi.1: line 41"),
    ("marin_semi.hst", _replace(14, "     3     3\n"), None, "marin_semi.hst: line 15"),
    (None, None, ("marin_semi.1", "marin_semi.hst", "missing.3"), "missing.3"),
    ("marin_semi.3", None, ("marin_semi.1", "marin_semi.hst", "marin_semi.3"),
     "marin_semi.3: wave periods: expected the finite periods of"),
], ids=["nan", "columns-1", "columns-hst", "missing-file", "inconsistent-frequencies"])
def test_broken_files_exit_2_with_one_line_and_nothing_written(oc4_copy, capsys, name, edit,
                                                              files, message):
    if name == "marin_semi.3":
        (oc4_copy / name).write_text(FOREIGN_3)
    elif name is not None:
        _broken(oc4_copy, name, edit)
    args = {} if files is None else {"files": files}
    assert _import(oc4_copy, **args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("floatmoor: error: ") and message in err[0]
    assert "Traceback" not in err[0]
    assert list((oc4_copy / "hydrodb").iterdir()) == []


@pytest.mark.parametrize("change, message", [
    (["--water-depth", "deep"], "--water-depth: expected a water depth > 0 [m] or "
     "'infinite', found 'deep'"),
    (["--water-density", "-1"], "--water-density: expected a number > 0 [kg/m^3], found '-1'"),
    (["--gravity", "nan"], "--gravity: expected a number > 0"),
    (["--body", "2"], "--body: expected no --body with WAMIT files"),
    (["--length-scale", "0"], "--length-scale: expected a number > 0 [m]"),
])
def test_bad_options_exit_2(oc4_copy, capsys, change, message):
    assert _import(oc4_copy, *change) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    assert list((oc4_copy / "hydrodb").iterdir()) == []


@pytest.mark.parametrize("drop, message", [
    ("--displaced-volume", "--displaced-volume: expected the displaced volume"),
    ("--centre-of-buoyancy", "--centre-of-buoyancy: expected the displaced volume"),
    ("--water-density", "--water-density: expected the water density"),
    ("--water-depth", "--water-depth: expected the water depth of the WAMIT run"),
])
def test_missing_options_are_named(oc4_copy, capsys, monkeypatch, drop, message):
    i = OPTIONS.index(drop)
    n = 3 if drop == "--centre-of-buoyancy" else 1
    monkeypatch.setattr(f"{__name__}.OPTIONS", OPTIONS[:i] + OPTIONS[i + 1 + n:])
    assert _import(oc4_copy) == 2
    err = capsys.readouterr().err
    assert message in err
    assert list((oc4_copy / "hydrodb").iterdir()) == []


@pytest.mark.parametrize("files", [("marin_semi.1", "marin_semi.h5"),
                                   ("marin_semi.1", "marin_semi.txt")])
def test_mixed_or_unknown_formats_exit_2(oc4_copy, capsys, files):
    assert _import(oc4_copy, files=files) == 2
    assert "expected WAMIT files" in capsys.readouterr().err
    assert list((oc4_copy / "hydrodb").iterdir()) == []


def test_output_must_be_a_database_file(oc4_copy, capsys):
    assert _import(oc4_copy, out="hydrodb/w.txt") == 2
    assert "a database file PATH.nc" in capsys.readouterr().err
