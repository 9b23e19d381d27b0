"""An existing campaign output file is validated before it is resumed: an
empty, truncated, non-netCDF or foreign file, a run's output, another campaign or a damaged
variable is one message (status 2) naming the file and what is wrong, saying how to start
over, with nothing run and the file untouched; ``sweep --restart`` moves it aside to
``NAME.bak-N`` (never deleting it) and runs the campaign afresh."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from floatmoor.campaign import runner as campaign_runner
from floatmoor.campaign.design import design_from_options
from floatmoor.campaign.runner import run_campaign
from floatmoor.cli import main
from floatmoor.io.netcdf import read_dataset, write_dataset
from tests.conftest import LINDAHL_CASE, REPO

#: Quasi-static, 3 s (the ramp is 2.5 s): each run takes milliseconds.
BASE = ["--set", 'lines.chain.model="quasi-static"', "--set", "simulation.duration=3.0"]
GRID = ["--grid", "motion.radius=0.1,0.2"]


def _sweep(out: Path, capsys, *extra: str) -> tuple[int, str]:
    status = main(["sweep", str(LINDAHL_CASE), "-o", str(out), "--quiet"] + BASE + GRID
                  + list(extra))
    return status, capsys.readouterr().err


@pytest.fixture(scope="module")
def campaign_bytes(tmp_path_factory) -> bytes:
    """The bytes of a complete campaign file of this module's sweep."""
    out = tmp_path_factory.mktemp("campaign") / "c.nc"
    assert main(["sweep", str(LINDAHL_CASE), "-o", str(out), "--quiet"] + BASE + GRID) == 0
    return out.read_bytes()


@pytest.fixture
def no_runs(monkeypatch) -> list:
    """Records every run the campaign starts."""
    calls: list = []
    original = campaign_runner.run_one
    monkeypatch.setattr(campaign_runner, "run_one",
                        lambda *a: calls.append(a[1]) or original(*a))
    return calls


def _damaged_variable(data: bytes, folder: Path) -> bytes:
    path = folder / "full.nc"
    path.write_bytes(data)
    ds = read_dataset(path)
    write_dataset(ds.drop_vars("fairlead_tension_max"), path)
    return path.read_bytes()


def _misshapen(data: bytes, folder: Path) -> bytes:
    path = folder / "full.nc"
    path.write_bytes(data)
    ds = read_dataset(path)
    write_dataset(ds.assign(wall_time_s=ds["wall_time_s"].expand_dims(extra=2)), path)
    return path.read_bytes()


def _run_output(data: bytes, folder: Path) -> bytes:
    out = folder / "run.nc"
    assert main(["run", str(LINDAHL_CASE), "-o", str(out), "--quiet"] + BASE) == 0
    return out.read_bytes()


@pytest.mark.parametrize("make, message", [
    (lambda data, folder: b"", "an empty file"),
    (lambda data, folder: b"not a netCDF file\n", "not a readable netCDF dataset"),
    (lambda data, folder: data[:len(data) // 2], "not a readable netCDF dataset"),
    (lambda data, folder: data[:200], "not a readable netCDF dataset"),
    (_run_output, "not a floatmoor campaign file"),
    (_damaged_variable, "without the variable 'fairlead_tension_max'"),
    (_misshapen, "variable 'wall_time_s'"),
], ids=["empty", "text", "half", "header-only", "run-output", "missing-variable",
        "misshapen"])
def test_bad_campaign_file_is_refused_then_restart_moves_it_aside(
        tmp_path, capsys, campaign_bytes, no_runs, make, message) -> None:
    out = tmp_path / "c.nc"
    bad = make(campaign_bytes, tmp_path)
    out.write_bytes(bad)
    status, err = _sweep(out, capsys)
    lines = err.strip().splitlines()
    assert status == 2 and len(lines) == 1, err
    assert lines[0].startswith(f"floatmoor: error: {out}: ") and message in err
    assert "--restart" in err and "Traceback" not in err
    assert out.read_bytes() == bad and not no_runs
    # the start-over path: moved aside, never deleted; the campaign runs afresh
    status, err = _sweep(out, capsys, "--restart")
    assert status == 0, err
    assert f"moved the existing {out} aside to {out}.bak-1" in err
    assert Path(f"{out}.bak-1").read_bytes() == bad and len(no_runs) == 2
    assert read_dataset(out).attrs["runs_complete"] == 2


def test_restart_keeps_every_earlier_backup(tmp_path, capsys, campaign_bytes, no_runs) -> None:
    """A good campaign file resumes (nothing run); --restart twice leaves .bak-1 and .bak-2
    as they were."""
    out = tmp_path / "c.nc"
    out.write_bytes(campaign_bytes)
    assert _sweep(out, capsys)[0] == 0 and not no_runs
    Path(f"{out}.bak-1").write_bytes(b"an earlier backup")
    resumed = out.read_bytes()
    assert _sweep(out, capsys, "--restart")[0] == 0
    assert Path(f"{out}.bak-1").read_bytes() == b"an earlier backup"
    assert Path(f"{out}.bak-2").read_bytes() == resumed
    assert len(no_runs) == 2


def test_another_campaign_names_what_differs(tmp_path, capsys, campaign_bytes,
                                             no_runs) -> None:
    out = tmp_path / "c.nc"
    out.write_bytes(campaign_bytes)
    status = main(["sweep", str(LINDAHL_CASE), "-o", str(out), "--quiet"] + BASE
                  + ["--grid", "motion.radius=0.1,0.3"])
    err = capsys.readouterr().err
    assert status == 2 and "another campaign: its campaign design differs" in err
    assert "--restart" in err and out.read_bytes() == campaign_bytes and not no_runs


def test_replacing_another_campaign_moves_it_aside(tmp_path, campaign_bytes) -> None:
    """``replace_other`` (the comparison's own campaign file) keeps the file it replaces."""
    out = tmp_path / "c.nc"
    out.write_bytes(b"damaged")
    moved = []
    ds = run_campaign(LINDAHL_CASE, design_from_options(["motion.radius=0.1,0.2"]),
                      base_overrides=BASE[1::2], output=out, replace_other=True,
                      moved_aside=lambda *paths: moved.append(paths))
    assert moved == [(out, Path(f"{out}.bak-1"))]
    assert Path(f"{out}.bak-1").read_bytes() == b"damaged"
    assert ds.attrs["runs_complete"] == 2


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")
def test_fifo_campaign_file_is_refused_without_hanging(tmp_path) -> None:
    """A FIFO in the output's place would block a reader forever: refused from its type (in
    a separate process, so that a hang fails the test instead of blocking it)."""
    out = tmp_path / "c.nc"
    os.mkfifo(out)
    proc = subprocess.run([sys.executable, "-m", "floatmoor.cli", "sweep", str(LINDAHL_CASE),
                           "-o", str(out), "--quiet"] + BASE + GRID, capture_output=True,
                          text=True, timeout=120, env=dict(os.environ, PYTHONPATH=str(REPO)))
    assert proc.returncode == 2, proc.stderr
    assert "a FIFO" in proc.stderr and "Traceback" not in proc.stderr
