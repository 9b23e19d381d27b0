"""Motion tables are confined to the case folder, regular,
bounded and strictly parsed; errors never quote the file (nor say "times nan to nan")."""

from __future__ import annotations

import os
import stat
import subprocess
import sys

import pytest

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError
from tests.conftest import LINDAHL_CASE, REPO

SECRET = "root:x:0:0:secret-first-line"


@pytest.fixture
def table_case(tmp_path):
    """A Lindahl copy in tmp_path/case moving its fairlead by a table case/m.csv, and a
    'secret' file beside the case folder."""
    folder = tmp_path / "case"
    folder.mkdir()
    (tmp_path / "secret.txt").write_text(SECRET + "\n")
    text = LINDAHL_CASE.read_text().replace(
        "circular motion r = {motion.radius:.2f} m, T = {motion.period:.2f} s", "table")
    start, end = text.index("[motion]"), text.index("[simulation]")
    case = folder / "T.toml"
    case.write_text(text[:start] + '[motion]\nkind = "table"\nfile = "m.csv"\n\n' + text[end:])
    (folder / "m.csv").write_text("time,x,y,z\n0,0,0,0\n10,0.1,0,0\n20,0,0,0\n")
    return case


def _error(case, *overrides) -> CaseError:
    with pytest.raises(CaseError) as info:
        load_case(case, list(overrides))
    assert SECRET not in str(info.value) and "nan" not in str(info.value)
    return info.value


def test_table_inside_the_case_folder_loads(table_case):
    assert load_case(table_case).motion.time[-1] == 20.0


@pytest.mark.parametrize("name", ["/etc/passwd", "../secret.txt", "../../../../etc/passwd"])
def test_paths_out_of_the_case_folder_are_refused(table_case, name):
    err = _error(table_case, f'motion.file="{name}"')
    assert err.key == "motion.file" and "inside the case file's folder" in err.expected


def test_symlink_out_of_the_case_folder_is_refused(table_case):
    os.symlink(table_case.parent.parent / "secret.txt", table_case.parent / "link.csv")
    err = _error(table_case, 'motion.file="link.csv"')
    assert "leads out of" in err.found


def test_device_and_folder_are_refused_before_reading(table_case):
    os.symlink("/dev/zero", table_case.parent / "zero.csv")
    assert "leads out of" in _error(table_case, 'motion.file="zero.csv"').found
    (table_case.parent / "sub").mkdir()
    assert "a folder" in _error(table_case, 'motion.file="sub"').found
    try:  # a /dev/zero inside the folder (root may create it; others cannot)
        os.mknod(table_case.parent / "dev.csv", stat.S_IFCHR | 0o600, os.makedev(1, 5))
    except PermissionError:
        pytest.skip("creating a device node needs privileges this user lacks")
    assert "a character device" in _error(table_case, 'motion.file="dev.csv"').found


def test_fifo_is_refused_without_hanging(table_case):
    os.mkfifo(table_case.parent / "pipe.csv")
    # in a subprocess: the fault was a read that never returns
    result = subprocess.run([sys.executable, "-m", "floatmoor.cli", "check", str(table_case),
                             "--set", 'motion.file="pipe.csv"'], capture_output=True,
                            text=True, timeout=60, cwd=REPO,
                            env={**os.environ, "PYTHONPATH": str(REPO)})
    assert result.returncode == 2
    assert "a FIFO" in result.stderr and "Traceback" not in result.stderr


def test_case_file_that_is_a_fifo_is_refused(tmp_path):
    os.mkfifo(tmp_path / "case.toml")
    with pytest.raises(CaseError, match="a FIFO"):
        load_case(tmp_path / "case.toml")


def test_non_utf8_table_is_a_case_error(table_case):
    (table_case.parent / "m.csv").write_bytes(b"time,x,y,z\n0,0,0,0\n\xff\xfe,0,0,0\n")
    err = _error(table_case)
    assert "UTF-8" in err.expected and "offset" in err.found


def test_file_contents_are_not_echoed(table_case):
    (table_case.parent / "m.csv").write_text(SECRET + "\n0,0,0,0\n")
    err = _error(table_case)
    assert "header" in err.expected and "row 1" in err.found


@pytest.mark.parametrize("cell", ["1_0", "nan", "inf", "0x10", "1e999"])
def test_only_plain_decimals_are_numbers(table_case, cell):
    (table_case.parent / "m.csv").write_text(f"time,x,y,z\n0,0,0,0\n{cell},0,0,0\n20,0,0,0\n")
    err = _error(table_case)
    assert "row 3" in err.expected


@pytest.mark.parametrize("body, found", [
    ("", "0 data rows"),
    ("0,0,0,0\n", "1 data row"),
    ("0,0,0,0\n5,0,0,0\n5,0,0,0\n", "time 5 s in row 4 after 5 s"),
    ("1,0,0,0\n20,0,0,0\n", "a first time of 1 s"),
])
def test_time_errors_say_what_is_wrong(table_case, body, found):
    (table_case.parent / "m.csv").write_text("time,x,y,z\n" + body)
    err = _error(table_case)
    assert found in err.found and "increasing time" in err.expected
