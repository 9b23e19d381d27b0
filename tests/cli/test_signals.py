"""Interrupts and signals: SIGINT, a second SIGINT and SIGTERM leave a
valid partial file or none and say which; a sweep's workers die with their parent, even when it
is killed; finished runs reach the campaign file before the workers are stopped.

The subprocess tests fork real runs (quasi-static lines: seconds each) and signal them once
their progress report shows that recording has started."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.io.netcdf import read_dataset
from floatmoor.simulation import assembly, forced, recorder
from floatmoor.cli.progress import ProgressReporter
from tests.conftest import LINDAHL_CASE, REPO

QS = ["--set", 'lines.chain.model="quasi-static"']
#: Long enough to be signalled (the dynamic line: minutes of wall time; quasi-static lines
#: run 2000 s in under a second) and stopped after its first progress report.
LONG = ["--set", "simulation.duration=2000"]
#: Seconds a signalled command may take to write and exit before the test calls it hung.
EXIT_TIMEOUT_S = 60.0

#: POSIX signals, and Python's SIGINT handler whatever the test process inherited
#: (tests/conftest.py).
pytestmark = [pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals"),
              pytest.mark.usefixtures("python_sigint")]


def _start(*args: str) -> subprocess.Popen[str]:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    return subprocess.Popen([sys.executable, "-m", "floatmoor", *args], env=env, text=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            start_new_session=True)


def _wait_for(proc: subprocess.Popen[str], prefix: str) -> list[str]:
    """The standard-error lines up to the first starting with ``prefix`` (the process is
    killed, and the test fails, if none comes within the timeout)."""
    watchdog = threading.Timer(EXIT_TIMEOUT_S, proc.kill)
    watchdog.start()
    lines = []
    try:
        for line in proc.stderr:
            lines.append(line)
            if line.startswith(prefix):
                return lines
    finally:
        watchdog.cancel()
    pytest.fail(f"no line starting {prefix!r}: {''.join(lines)}")


def _finish(proc: subprocess.Popen[str]) -> tuple[int, str]:
    """Exit status and the rest of standard error (failing on a hang)."""
    try:
        rest = proc.communicate(timeout=EXIT_TIMEOUT_S)[1]
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("the signalled command did not exit")
    return proc.returncode, rest


def _assert_valid_partial(path, status_start: str, message: str) -> None:
    ds = read_dataset(path)
    assert ds.attrs["status"].startswith(status_start)
    t_end = float(ds["time"].values[-1])
    assert 0.0 < t_end < 2000.0
    assert f"partial results up to t = {t_end:.6g} s written to {path}" in message
    assert all(np.all(np.isfinite(ds[v].values)) for v in ds.data_vars)


@pytest.mark.parametrize("signals, status, text, code", [
    ((signal.SIGINT,), "interrupted", "floatmoor: interrupted;", 130),
    ((signal.SIGTERM,), "terminated (SIGTERM)", "floatmoor: terminated (SIGTERM);", 143),
    # a second Ctrl-C during the partial write: the next test, which delivers it there
    # deterministically (a second one sent 0.15 s after the first landed there or not)
])
def test_signalled_run_leaves_valid_partial_file_and_says_so(tmp_path, signals, status, text,
                                                             code):
    out = tmp_path / "run.nc"
    proc = _start("run", str(LINDAHL_CASE), *LONG, "-o", str(out))
    _wait_for(proc, "floatmoor: t =")
    for number in signals:
        proc.send_signal(number)
        time.sleep(0.15)
    status_code, err = _finish(proc)
    assert status_code == code, err
    assert text in err and "Traceback" not in err
    _assert_valid_partial(out, status, err)
    assert not list(tmp_path.glob(".*.tmp"))  # no temporary file left behind


def test_second_interrupt_during_the_partial_write_keeps_the_file(tmp_path, capfd,
                                                                  monkeypatch):
    """Deterministic: the first SIGINT arrives while a chunk is solved, the second inside the
    write of the partial results."""
    calls = []

    def first_interrupt(self, simulated):
        calls.append(simulated)
        if len(calls) == 2:
            os.kill(os.getpid(), signal.SIGINT)

    real_write = recorder.Recorder._write

    def interrupted_write(self, status):
        if status.startswith("interrupted"):
            os.kill(os.getpid(), signal.SIGINT)  # handled before the write below
        real_write(self, status)

    monkeypatch.setattr(ProgressReporter, "__call__", first_interrupt)
    monkeypatch.setattr(recorder.Recorder, "_write", interrupted_write)
    out = tmp_path / "partial.nc"
    assert main(["run", str(LINDAHL_CASE), "-o", str(out), *QS]) == 130
    err = capfd.readouterr().err  # the handler writes to the file descriptor
    assert "still writing" in err
    ds = read_dataset(out)
    assert ds.attrs["status"].startswith("interrupted")
    assert ds.sizes["time"] == 2 * forced.CHUNK_SAMPLES
    assert f"partial results up to t = {ds['time'].values[-1]:.6g} s written" in err
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # restored


@pytest.mark.parametrize("existing", [False, True])
def test_interrupt_before_recording_says_nothing_written(tmp_path, capsys, monkeypatch,
                                                         existing):
    def interrupted_build(case):
        os.kill(os.getpid(), signal.SIGTERM)

    monkeypatch.setattr(assembly, "build_line_models", interrupted_build)
    out = tmp_path / "none.nc"
    if existing:  # an earlier result (run -o replaces run results only)
        import xarray as xr

        from floatmoor.io.netcdf import write_dataset

        write_dataset(xr.Dataset({"x": ("a", [1.0])}, attrs={
            "floatmoor_version": "0", "case_toml": "", "status": "complete"}), out)
        earlier = out.read_bytes()
    assert main(["run", str(LINDAHL_CASE), "-o", str(out), *QS, "--quiet"]) == 143
    err = capsys.readouterr().err
    assert "terminated (SIGTERM); nothing written" in err
    assert "partial results" not in err
    if existing:
        assert f"{out} is unchanged" in err and out.read_bytes() == earlier
    else:
        assert not out.exists()


def test_interrupt_before_the_first_sample_writes_no_file(tmp_path, capsys, monkeypatch):
    """A file of no samples cannot be read back: a run stopped in its first chunk leaves
    none, and says so."""
    def interrupted_chunk(*args):
        os.kill(os.getpid(), signal.SIGINT)

    monkeypatch.setattr(forced, "_solve_chunk", interrupted_chunk)
    out = tmp_path / "none.nc"
    assert main(["run", str(LINDAHL_CASE), "-o", str(out), *QS, "--quiet"]) == 130
    assert "interrupted; nothing written" in capsys.readouterr().err
    assert not out.exists()


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, dead but not yet reaped, does not)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def _workers(pid: int) -> list[int]:
    with open(f"/proc/{pid}/task/{pid}/children") as fh:
        return [int(p) for p in fh.read().split()]


SWEEP = ["sweep", str(LINDAHL_CASE), "--grid", "simulation.duration=5,5.5,2000,2000",
         "--workers", "2"]


@pytest.mark.slow  # about 10 s on a loaded machine: two workers start and run
@pytest.mark.skipif(not os.path.exists("/proc/self/task"), reason="needs Linux /proc")
def test_killed_sweep_parent_leaves_no_worker_and_keeps_finished_runs(tmp_path):
    out = tmp_path / "campaign.nc"
    proc = _start(*SWEEP, "-o", str(out))
    _wait_for(proc, "floatmoor: 2 / 4 runs done")  # reported once written
    workers = _workers(proc.pid)
    assert len(workers) == 2 and all(_alive(p) for p in workers)
    proc.kill()
    _finish(proc)
    deadline = time.monotonic() + 5.0
    while any(_alive(p) for p in workers) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(_alive(p) for p in workers), "a worker outlived its killed parent"
    status = read_dataset(out)["status"].values
    assert list(status[:2]) == ["complete", "complete"]


@pytest.mark.slow  # about 10 s each on a loaded machine: two workers start and run
@pytest.mark.skipif(not os.path.exists("/proc/self/task"), reason="needs Linux /proc")
@pytest.mark.parametrize("number, code, text", [
    (signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated (SIGTERM)")])
def test_signalled_sweep_writes_finished_runs_then_stops_workers(tmp_path, number, code, text):
    out = tmp_path / "campaign.nc"
    proc = _start(*SWEEP, "-o", str(out))
    _wait_for(proc, "floatmoor: 2 / 4 runs done")
    workers = _workers(proc.pid)
    if number == signal.SIGINT:
        os.killpg(proc.pid, number)  # Ctrl-C: the whole foreground group
    else:
        proc.send_signal(number)
    status_code, err = _finish(proc)
    assert status_code == code, err
    assert f"floatmoor: {text}; 2 finished runs are in {out}" in err
    assert "Traceback" not in err
    assert not any(_alive(p) for p in workers)
    ds = read_dataset(out)
    assert list(ds["status"].values) == ["complete", "complete", "pending", "pending"]
    assert ds.attrs["runs_complete"] == 2
