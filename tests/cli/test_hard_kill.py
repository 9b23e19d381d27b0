"""Nothing lost to a hard kill (docs/guide/running.md#checkpoints): a floater run checkpoints
at its start and every ``--checkpoint-every`` seconds of wall time, after the samples the
checkpoint covers are in its file and on disk, so that a SIGKILL (or an out-of-memory kill, or
a power cut), which no handler sees, leaves a checkpoint and a file that ``--resume``
continues to the uninterrupted run's file, bit for bit.

The subprocess test kills a real ``floatmoor run`` (quasi-static lines: seconds of wall time)
once its checkpoint shows it half way. SIGKILL can be neither handled nor ignored, so unlike
the SIGINT tests (tests/cli/test_signals.py) it does not depend on the SIGINT disposition the
test process inherited and needs no ``python_sigint`` fixture; the child runs in its own
session, so a Ctrl-C of the test run does not reach it. The in-process tests stop a run with
an exception no part of floatmoor catches: like a kill, nothing is written on the way out."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.simulation import checkpoint as ck
from floatmoor.simulation import coupled_run as cr
from floatmoor.simulation import recorder as recorder_module
from floatmoor.simulation.coupled_run import checkpoint_path, run_coupled
from tests.conftest import CASES, REPO

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: 30 s of the buoy on quasi-static lines: 3000 body steps, 6 chunks, 1 to 3 s of wall time
#: (killed once its checkpoint covers 3 chunks, the other 3 still to run).
RUN = ["--set", 'lines.*.model="quasi-static"', "--set", "simulation.duration=30.0",
       "--quiet"]
#: Seconds the killed run may take to get half way (its start-up included) before the test
#: calls it hung.
PROGRESS_TIMEOUT_S = 180.0
#: Attributes that differ between two runs of a case (when written, how long it took).
VOLATILE = ("created", "wall_time_s")

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


def _scipy(path: Path) -> xr.Dataset:
    with xr.open_dataset(path, engine="scipy") as ds:
        return ds.load()


def _assert_same_file_data(resumed: Path, whole: Path) -> None:
    """Every variable (values, dtype, dimensions, attributes) and every attribute but when
    the file was written and how long it took the same, bit for bit."""
    a, b = _scipy(resumed), _scipy(whole)
    assert set(a.variables) == set(b.variables)
    for name, var in b.variables.items():
        assert a[name].dtype == var.dtype and a[name].dims == var.dims, name
        assert np.array_equal(a[name].values, var.values,
                              equal_nan=var.dtype.kind == "f"), name
        if var.dtype.kind == "f":  # -0.0 and NaN payloads too
            assert a[name].values.tobytes() == var.values.tobytes(), name
    assert a.attrs["status"] == "complete"
    assert a.assign_attrs({k: None for k in VOLATILE}).identical(
        b.assign_attrs({k: None for k in VOLATILE}))


def _checkpoint_samples(path: Path) -> int | None:
    """The output samples the checkpoint ``path`` covers (None: none there yet)."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            return int(npz["progress/n_done"])
    except FileNotFoundError:
        return None


def test_sigkill_half_way_then_resume_gives_the_uninterrupted_file(tmp_path) -> None:
    whole = tmp_path / "whole.nc"
    assert main(["run", str(BUOY_CASE), "-o", str(whole)] + RUN) == 0
    n_total = _scipy(whole).sizes["time"]
    out = tmp_path / "killed.nc"
    ckpt = checkpoint_path(out)
    child = subprocess.Popen(
        [sys.executable, "-m", "floatmoor", "run", str(BUOY_CASE), "-o", str(out),
         "--checkpoint-every", "0"] + RUN,
        cwd=REPO, env=dict(os.environ, PYTHONPATH=str(REPO)), stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE, start_new_session=True)
    try:
        deadline = time.monotonic() + PROGRESS_TIMEOUT_S
        while time.monotonic() < deadline and child.poll() is None:
            saved = _checkpoint_samples(ckpt)
            if saved is not None and saved >= n_total // 2:
                break
            time.sleep(0.01)
        assert child.poll() is None, "the run ended before it could be killed: " + (
            child.stderr.read().decode())
        os.kill(child.pid, signal.SIGKILL)
        child.wait(timeout=60)
    finally:
        if child.poll() is None:
            child.kill()
        child.wait()
        child.stderr.close()
    assert child.returncode == -signal.SIGKILL
    saved = _checkpoint_samples(ckpt)
    # about half way (the checkpoint may have moved on before the kill took effect)
    assert n_total // 2 <= saved < n_total, (saved, n_total)
    partial = _scipy(out)
    assert partial.attrs["status"].startswith("running: ")
    assert partial.sizes["time"] >= saved  # the file covers the checkpoint
    assert main(["run", str(BUOY_CASE), "-o", str(out), "--resume"] + RUN) == 0
    assert not ckpt.exists()
    assert not list(tmp_path.glob(".*.tmp"))  # no temporary file left behind
    _assert_same_file_data(out, whole)


class _HardKill(BaseException):
    """Stops a run the way a kill does: no floatmoor handler catches it, nothing more is
    written."""


def _kill_at_body_step(patch: pytest.MonkeyPatch, step: int) -> None:
    from floatmoor.simulation.coupled import MooredBody

    original, calls = MooredBody.step, []

    def stepped(self) -> None:
        calls.append(1)
        if len(calls) == step:
            raise _HardKill
        original(self)

    patch.setattr(MooredBody, "step", stepped)


#: A short run of 3 chunks of 40 body steps, with line shapes.
SHORT = ['lines.*.model="quasi-static"', "simulation.duration=1.2",
         "simulation.shape_output_interval=0.2"]


@pytest.fixture(scope="module")
def whole_short(tmp_path_factory) -> Path:
    """The uninterrupted run of ``SHORT`` in chunks of 40 steps: its file."""
    whole = tmp_path_factory.mktemp("whole") / "whole.nc"
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(cr, "CHUNK_STEPS", 40)
        run_coupled(load_case(BUOY_CASE, SHORT), output=whole).dataset.close()
    return whole


@pytest.mark.parametrize("small_windows", [False, True], ids=["default", "appends-ahead"])
def test_a_run_killed_before_its_first_periodic_checkpoint_resumes(tmp_path, monkeypatch,
                                                                   whole_short,
                                                                   small_windows) -> None:
    """Killed in its third chunk, seconds before the default checkpoint interval, a run has
    the checkpoint of its start (before, it had none: ``--resume`` said "no checkpoint" and
    the run was lost); with small windows its file holds samples beyond the checkpoint,
    which the resumed run replaces. Either way the result is the uninterrupted one."""
    monkeypatch.setattr(cr, "CHUNK_STEPS", 40)
    if small_windows:  # every chunk appended to the file when the next one is reserved
        monkeypatch.setattr(recorder_module, "WINDOW_BYTES", 1)
    case = load_case(BUOY_CASE, SHORT)
    out = tmp_path / "cut.nc"
    with monkeypatch.context() as patch:
        _kill_at_body_step(patch, 2 * 40 + 7)
        with pytest.raises(_HardKill):
            run_coupled(case, output=out)
    assert _checkpoint_samples(checkpoint_path(out)) == 1  # the start
    partial = _scipy(out)
    assert partial.sizes["time"] == (2 * 40 + 1 if small_windows else 1)
    run_coupled(case, output=out, resume=True).dataset.close()
    assert not checkpoint_path(out).exists()
    _assert_same_file_data(out, whole_short)


def test_periodic_checkpoints_follow_the_interval(tmp_path, monkeypatch) -> None:
    """With ``checkpoint_interval=0`` every chunk's end is checkpointed, each after its
    samples are flushed to disk (an endless interval: tests/simulation/test_coupled_run.py); an
    interval that is not a number >= 0 is refused before the run is set up."""
    monkeypatch.setattr(cr, "CHUNK_STEPS", 40)
    case = load_case(BUOY_CASE, ['lines.*.model="quasi-static"', "simulation.duration=1.2"])
    events: list[tuple[str, int]] = []
    real_sync, real_write = recorder_module.Recorder.sync, cr.write_checkpoint

    def sync(self) -> None:
        events.append(("sync", self.written))
        real_sync(self)

    def write(path, arrays, identity) -> None:
        events.append(("checkpoint", int(arrays["progress/n_done"])))
        real_write(path, arrays, identity)

    monkeypatch.setattr(recorder_module.Recorder, "sync", sync)
    monkeypatch.setattr(cr, "write_checkpoint", write)
    run_coupled(case, output=tmp_path / "every.nc", checkpoint_interval=0.0).dataset.close()
    # the start, then the end of each of the three chunks
    assert events == [("sync", 1), ("checkpoint", 1), ("sync", 41), ("checkpoint", 41),
                      ("sync", 81), ("checkpoint", 81), ("sync", 121), ("checkpoint", 121)]
    for bad in (float("nan"), -1.0):
        with pytest.raises(ValueError, match="checkpoint_interval"):
            run_coupled(case, output=tmp_path / "bad.nc", checkpoint_interval=bad)
    assert not (tmp_path / "bad.nc").exists()


@pytest.mark.parametrize("value", ["-1", "nan", "inf", "soon"])
def test_checkpoint_every_must_be_seconds(tmp_path, capsys, value) -> None:
    out = tmp_path / "run.nc"
    status = main(["run", str(BUOY_CASE), "-o", str(out), "--checkpoint-every", value] + RUN)
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and len(err) == 1, err
    assert err[0] == ("floatmoor: error: --checkpoint-every: expected seconds of wall time, "
                      f"a number >= 0, found '{value}'")
    assert not out.exists() and not checkpoint_path(out).exists()


def test_checkpoint_every_needs_a_floater(tmp_path, capsys) -> None:
    from tests.conftest import LINDAHL_CASE

    out = tmp_path / "forced.nc"
    assert main(["run", str(LINDAHL_CASE), "-o", str(out), "--checkpoint-every", "5"]) == 2
    err = capsys.readouterr().err
    assert "--checkpoint-every" in err and "[floater]" in err and not out.exists()


def test_the_temporary_file_is_new_and_never_followed(tmp_path) -> None:
    """A file or a symbolic link already at the temporary name (a killed write's, or a
    planted one) is never written through; the victim stays as it was."""
    path = tmp_path / "run.nc.checkpoint"
    victim = tmp_path / "victim"
    victim.write_bytes(b"keep")
    os.symlink(victim, ck.temporary_path(path))
    ck.write_checkpoint(path, {"state/x": np.arange(3.0)}, ck.RunIdentity.of("a", [], "s"))
    assert victim.read_bytes() == b"keep"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.nc.checkpoint", "victim"]


def test_stale_temporaries_of_dead_processes_are_removed(tmp_path) -> None:
    path = tmp_path / "run.nc.checkpoint"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True)
    stale = ck.temporary_path(path, int(dead.stdout))
    live = ck.temporary_path(path, os.getppid())  # a process that runs: its write may be
    other = tmp_path / ".other.nc.checkpoint.1.tmp"
    for p in (stale, live, other):
        p.write_bytes(b"partial")
    assert ck.remove_stale_temporaries(path) == [stale]
    assert not stale.exists() and live.exists() and other.exists()


def test_the_help_gives_the_default_interval(capsys) -> None:
    """``run --help`` states the interval the run uses when none is given (the CLI does not
    import the simulation to say it)."""
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert f"default {cr.CHECKPOINT_INTERVAL_S:g}, 0: every chunk" in help_text


def test_a_folder_that_cannot_be_flushed_is_skipped_but_an_io_error_is_not(tmp_path,
                                                                            monkeypatch
                                                                            ) -> None:
    """File systems without a folder fsync (EINVAL) still run; a failing disk (EIO) is an
    error, as for the files themselves."""
    import errno

    from floatmoor.io.output_files import sync_folder

    code = {"n": errno.EINVAL}

    def fsync(fd: int) -> None:
        raise OSError(code["n"], os.strerror(code["n"]))

    monkeypatch.setattr(os, "fsync", fsync)
    sync_folder(tmp_path)
    code["n"] = errno.EIO
    with pytest.raises(OSError):
        sync_folder(tmp_path)
