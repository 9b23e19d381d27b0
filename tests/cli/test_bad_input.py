"""Malformed case files and overrides: one message naming file, key, expectation and finding;
exit status 2; no traceback; no output file.

Each file in tests/data/bad_cases states in its header the key path, the fragment of the
expectation and of the finding its error message must contain.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from tests.conftest import LINDAHL_CASE

BAD_CASES = sorted((Path(__file__).parents[1] / "data" / "bad_cases").glob("*.toml"))


def _expectations(path: Path) -> dict[str, str]:
    out = {}
    for line in path.read_text().splitlines():
        if line.startswith("# expect-"):
            key, _, value = line[len("# expect-"):].partition(": ")
            out[key] = value
    return out


def test_there_are_at_least_15_bad_cases():
    assert len(BAD_CASES) >= 15


@pytest.mark.parametrize("path", BAD_CASES, ids=lambda p: p.stem)
def test_bad_case_error_names_file_key_expected_found(path: Path):
    expect = _expectations(path)
    with pytest.raises(CaseError) as info:
        load_case(path)
    err = info.value
    assert err.source == str(path)
    assert err.key == expect["key"]
    assert expect["expected"] in err.expected
    assert expect["found"] in err.found
    message = str(err)
    assert message.startswith(str(path))
    assert f"expected {err.expected}, found {err.found}" in message


@pytest.mark.parametrize("path", BAD_CASES, ids=lambda p: p.stem)
def test_cli_rejects_bad_case_with_status_2_and_no_output(path: Path, tmp_path, capsys):
    out = tmp_path / "out.nc"
    status = main(["run", str(path), "-o", str(out), "--quiet"])
    captured = capsys.readouterr()
    assert status == 2
    assert captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("floatmoor: error: " + str(path))
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("override, key, found", [
    ("motion.period=-1.0", "motion.period", "-1.0"),
    ("motion.period=fast", "motion.period", "'fast'"),
    ("lines.mooring.length=30.0", "lines.mooring", "'mooring'"),
    ("lines.chain.anchor=[0.0, 0.0]", "lines[0].anchor", "an array of 2"),
    ("lines.0.anchor=[0.0, 0.0, -3.0]", "lines.0", "'0'"),
    ("environment.water_depth=2.0", "lines[0].anchor", "z = -3.0"),
    ("simulation.duration", "", "'simulation.duration'"),
    ("motion.radius=1e3", "motion.radius", "fairlead"),
])
def test_bad_override_is_a_case_error(override, key, found):
    with pytest.raises(CaseError) as info:
        load_case(LINDAHL_CASE, [override])
    assert info.value.key == key
    assert found in info.value.found
    assert str(LINDAHL_CASE) in str(info.value)


def test_override_error_names_the_override():
    with pytest.raises(CaseError) as info:
        load_case(LINDAHL_CASE, ["motion.radius=-0.1"])
    assert "(--set motion.radius=-0.1)" in str(info.value)


@pytest.mark.parametrize("args", [
    ["run", "{bad}", "-o", "{tmp}/out.nc"],
    ["check", "{bad}"],
    ["run", "{case}", "--set", "motion.sense=clockwise", "-o", "{tmp}/out.nc"],
    ["run", "{case}", "-o", "{tmp}/no/such/folder/out.nc"],
    ["run", "{case}", "--plot", "{tmp}/plot.xyz", "-o", "{tmp}/out.nc"],
    ["run", "{tmp}/missing.toml", "-o", "{tmp}/out.nc"],
])
def test_console_command_bad_input_exits_2_without_traceback(args, tmp_path):
    """The real process: status 2, one line on stderr, no traceback, nothing written."""
    bad = BAD_CASES[0]
    argv = [a.format(bad=bad, tmp=tmp_path, case=LINDAHL_CASE) for a in args]
    proc = subprocess.run([sys.executable, "-m", "floatmoor", *argv], capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr
    assert proc.stderr.startswith("floatmoor: error: ")
    assert proc.stdout == ""
    assert list(tmp_path.iterdir()) == []


def test_an_override_of_a_tables_kind_says_how_to_replace_the_table(capsys):
    buoy = LINDAHL_CASE.parents[1] / "cylinder_buoy" / "buoy_regular_T1.20.toml"
    with pytest.raises(CaseError) as info:
        load_case(buoy, ['waves.kind="still"'])
    assert info.value.key == "waves.height"
    assert "--set waves.kind=\"still\" changed one key of [waves]" in info.value.expected
    assert "--set 'waves={kind = \"...\", ...}'" in info.value.expected
    # and the rule it gives works
    assert load_case(buoy, ['waves={kind = "still"}']).waves is not None
