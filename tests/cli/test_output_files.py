"""Output files of ``floatmoor run`` and ``sweep`` (docs/guide/safeguards.md#output-files): what
an output may not be, the checks made before any work (writable folder, free space), the lock
against a second writer, the kept file mode, atomic writes that leave no temporary file, and
the message saying whether partial results were written."""

from __future__ import annotations

import os
import shutil
import signal
import stat
import subprocess
import sys
import textwrap
import time

import pytest

from floatmoor.cli import main
from floatmoor.io import output_files
from floatmoor.io.netcdf import read_dataset
from floatmoor.io.output_files import OutputWriteError, atomic_target, lock_path, output_lock
from tests.conftest import LINDAHL_CASE, REPO

QS = ["--set", 'lines.chain.model="quasi-static"']
SHORT = ["--set", "simulation.duration=3.0", *QS]  # ramp 2.5 s: 1201 samples, about 136 kB


@pytest.fixture
def case(tmp_path):
    """A copy of the Lindahl case, as a user would run it."""
    path = tmp_path / "L.toml"
    shutil.copy(LINDAHL_CASE, path)
    return path


@pytest.fixture
def tmpfs(tmp_path):
    """Mount a tmpfs with the given options in ``tmp_path``; skips where mounting is not
    permitted (a read-only folder does not stop root, so only a read-only mount tests one)."""
    mounted = []

    def mount(name: str, options: str):
        folder = tmp_path / name
        folder.mkdir()
        done = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(folder)],
                              capture_output=True, text=True)
        if done.returncode != 0:
            pytest.skip(f"cannot mount a tmpfs here ({done.stderr.strip()}): the test needs a "
                        "read-only or full folder that also stops root")
        mounted.append(folder)
        return folder

    yield mount
    for folder in mounted:
        subprocess.run(["umount", str(folder)], check=False)


def _no_temporary_files(folder) -> bool:
    return not [p for p in os.listdir(folder) if p.endswith((".tmp", ".png")) and
                p.startswith(".")]


# -- item 1: what an output may not be -----------------------------------------------------
def test_case_file_is_not_an_output(case, capsys):
    text = case.read_bytes()
    link = case.parent / "link.nc"
    link.symlink_to(case.name)
    for target in (case, link):
        assert main(["run", str(case), *SHORT, "-o", str(target), "--quiet"]) == 2
        err = capsys.readouterr().err
        assert "expected a file other than the case file" in err and "Traceback" not in err
    assert case.read_bytes() == text and link.is_symlink()


def test_plot_and_result_must_differ(case, tmp_path, capsys):
    same = tmp_path / "same.png"
    assert main(["run", str(case), *SHORT, "-o", str(same), "--plot", str(same),
                 "--quiet"]) == 2
    assert "other than the result file" in capsys.readouterr().err
    assert not same.exists()


def test_links_devices_fifos_folders_and_other_files_are_not_replaced(case, tmp_path, capsys):
    other = tmp_path / "other.nc"
    other.write_bytes(b"CDF\x02 someone else's data")
    link = tmp_path / "link.nc"
    link.symlink_to(other)
    fifo = tmp_path / "fifo.nc"
    os.mkfifo(fifo)
    device = tmp_path / "null"
    os.mknod(device, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    notes = tmp_path / "notes.txt"
    notes.write_text("my notes\n")
    cases = {link: "a symbolic link", fifo: "a FIFO", device: "a character device",
             notes: "which is not a run result file", tmp_path: "a file name (not a folder)"}
    for target, found in cases.items():
        assert main(["run", str(case), *SHORT, "-o", str(target), "--quiet"]) == 2, target
        err = capsys.readouterr().err
        assert found in err and "Traceback" not in err, err
    assert link.is_symlink() and other.read_bytes() == b"CDF\x02 someone else's data"
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and stat.S_ISCHR(os.lstat(device).st_mode)
    assert notes.read_text() == "my notes\n"


def test_output_naming_a_new_folder_is_refused(case, tmp_path, capsys, monkeypatch):
    # item 14: ``-o newdir/`` wrote a file named ``newdir``
    monkeypatch.chdir(tmp_path)
    assert main(["run", str(case), *SHORT, "-o", "newdir/", "--quiet"]) == 2
    assert "expected a file name (not a folder), found 'newdir/'" in capsys.readouterr().err
    assert not (tmp_path / "newdir").exists()


def test_replacing_a_result_is_announced_and_keeps_its_mode(case, tmp_path, capsys):
    out, png = tmp_path / "r.nc", tmp_path / "r.png"
    old_umask = os.umask(0o022)
    try:
        assert main(["run", str(case), *SHORT, "-o", str(out), "--quiet"]) == 0
        assert stat.S_IMODE(out.stat().st_mode) == 0o644  # a new file: 0o666 less the umask
        assert "replacing" not in capsys.readouterr().err
        out.chmod(0o640)
        png.write_bytes(b"\x89PNG\r\n\x1a\n old plot")
        png.chmod(0o600)
        assert main(["run", str(case), *SHORT, "-o", str(out), "--plot", str(png),
                     "--quiet"]) == 0
    finally:
        os.umask(old_umask)
    err = capsys.readouterr().err
    assert f"replacing the existing {out}" in err and f"replacing the existing {png}" in err
    assert stat.S_IMODE(out.stat().st_mode) == 0o640
    assert stat.S_IMODE(png.stat().st_mode) == 0o600 and png.stat().st_size > 10_000
    assert read_dataset(out).attrs["status"] == "complete"
    assert _no_temporary_files(tmp_path) and not lock_path(out).exists()


# -- item 2: a second writer ---------------------------------------------------------------
def test_second_writer_of_a_run_or_campaign_is_refused_before_any_work(case, tmp_path,
                                                                      capsys):
    out, campaign = tmp_path / "same.nc", tmp_path / "campaign.nc"
    with output_lock(out), output_lock(campaign):
        assert main(["run", str(case), *SHORT, "-o", str(out), "--quiet"]) == 2
        err = capsys.readouterr().err
        assert f"expected a file no other floatmoor process is writing, found '{out}', " \
               f"being written by process {os.getpid()}" in err
        assert main(["sweep", str(case), *SHORT, "--grid", "motion.period=1.25,1.5", "-o",
                     str(campaign), "--quiet"]) == 2
        assert "being written by process" in capsys.readouterr().err
    assert not out.exists() and not campaign.exists()
    assert not lock_path(out).exists() and not lock_path(campaign).exists()


def test_lock_of_a_killed_process_does_not_block(case, tmp_path, capsys):
    out = tmp_path / "same.nc"
    holder = subprocess.Popen(
        [sys.executable, "-c", textwrap.dedent(f"""
            import time
            from floatmoor.io.output_files import output_lock
            with output_lock({str(out)!r}):
                print("locked", flush=True)
                time.sleep(60)
            """)],
        stdout=subprocess.PIPE, text=True, env={**os.environ, "PYTHONPATH": str(REPO)})
    try:
        assert holder.stdout.readline().strip() == "locked"
        assert main(["run", str(case), *SHORT, "-o", str(out), "--quiet"]) == 2
        assert f"being written by process {holder.pid}" in capsys.readouterr().err
    finally:
        holder.kill()  # SIGKILL: no clean-up runs, the lock file stays
        holder.wait(timeout=10)
    assert lock_path(out).exists()
    assert main(["run", str(case), *SHORT, "-o", str(out), "--quiet"]) == 0
    assert read_dataset(out).attrs["status"] == "complete"


@pytest.mark.slow  # about 12 s: two processes importing floatmoor, one running a dynamic line
def test_two_concurrent_runs_leave_the_first_ones_results(case, tmp_path):
    """Two ``floatmoor run`` processes on one output: the second stops at once (status 2)
    without touching the file; the first, interrupted, leaves its partial results."""
    out = tmp_path / "same.nc"
    command = [sys.executable, "-m", "floatmoor", "run", str(case), "-o", str(out),
               "--quiet"]
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    # the dynamic line over 200 s: minutes, far longer than the second needs
    first = subprocess.Popen([*command, "--set", "simulation.duration=200.0"], env=env,
                             stderr=subprocess.PIPE, text=True)
    try:
        for _ in range(600):  # the first holds the lock once its checks have passed
            if lock_path(out).exists() or first.poll() is not None:
                break
            time.sleep(0.05)
        second = subprocess.run([*command, *SHORT], env=env,
                                capture_output=True, text=True, timeout=60)
        assert first.poll() is None, "the first run ended before the second started"
        assert second.returncode == 2, second.stderr
        assert "being written by process" in second.stderr
        first.send_signal(signal.SIGINT)
        assert first.wait(timeout=60) == 130, first.stderr.read()
    finally:
        first.kill()
        first.wait()
    ds = read_dataset(out)
    assert ds.attrs["status"].startswith("interrupted")
    assert "simulation.duration=200.0" in ds.attrs["case_overrides"]


# -- item 3 and 11: read-only folder, full disk -------------------------------------------
def test_read_only_folder_is_refused_before_the_run(case, tmp_path, tmpfs, capsys):
    folder = tmpfs("ro", "ro,size=1m")
    assert main(["run", str(case), *SHORT, "-o", str(folder / "r.nc"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "expected a file in a folder floatmoor can write to" in err
    assert "Read-only file system" in err and "Traceback" not in err
    # item 11: a plot into a read-only folder failed after the run; now before it
    out = tmp_path / "r.nc"
    assert main(["run", str(case), *SHORT, "-o", str(out), "--plot", str(folder / "r.png"),
                 "--quiet"]) == 2
    assert "--plot: expected a file in a folder floatmoor can write to" in \
        capsys.readouterr().err
    assert not out.exists()


def test_folder_without_room_for_the_output_is_refused_before_the_run(case, tmpfs, capsys):
    folder = tmpfs("small", "size=64k")
    assert main(["run", str(case), *SHORT, "-o", str(folder / "r.nc"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "expected a folder with room for the output (about 1.31" in err
    assert "free in" in err and os.listdir(folder) == []


def test_disk_full_during_the_run_is_a_failure_with_no_temporary_file(case, tmpfs, capsys,
                                                                      monkeypatch):
    # the free space was there at the start and went during the run: no space margin, and
    # an estimate the folder holds
    monkeypatch.setattr(output_files, "SPACE_MARGIN", 0)
    monkeypatch.setattr("floatmoor.simulation.recorder.estimated_output_bytes", lambda c: 0)
    folder = tmpfs("full", "size=64k")
    out = folder / "r.nc"
    assert main(["run", str(case), *SHORT, "-o", str(out), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert f"run failed: cannot write {out}: No space left on device" in err
    assert "nothing written: its writes failed" in err and "Traceback" not in err
    assert os.listdir(folder) == []  # no temporary file, no lock file


def test_plot_failing_after_the_run_keeps_the_results(case, tmp_path, tmpfs, capsys,
                                                      monkeypatch):
    monkeypatch.setattr(output_files, "SPACE_MARGIN", 0)
    folder = tmpfs("plots", "size=16k")  # a plot is about 50 kB
    out = tmp_path / "r.nc"
    assert main(["run", str(case), *SHORT, "-o", str(out), "--plot", str(folder / "r.png"),
                 "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "the plot failed: cannot write" in err and "No space left on device" in err
    assert f"the run completed; results in {out}" in err and "Traceback" not in err
    assert read_dataset(out).attrs["status"] == "complete"
    assert os.listdir(folder) == []


def test_interrupted_write_keeps_the_old_file_and_no_temporary(tmp_path):
    target = tmp_path / "r.nc"
    target.write_bytes(b"CDF\x02 old")
    with pytest.raises(KeyboardInterrupt):
        with atomic_target(target) as tmp:
            tmp.write_bytes(b"CDF\x02 half")
            raise KeyboardInterrupt
    assert target.read_bytes() == b"CDF\x02 old" and os.listdir(tmp_path) == ["r.nc"]
    target.unlink()
    target.symlink_to(tmp_path / "elsewhere.nc")
    with pytest.raises(OutputWriteError, match="it is a symbolic link"):
        with atomic_target(target):
            pass


# -- item 13: "partial results written" only when they were ---------------------------------
def test_failure_before_recording_says_no_results_were_written(case, tmp_path, capsys):
    out = tmp_path / "d.nc"
    assert main(["run", str(case), "--set", "simulation.duration=0.5", "--set",
                 "motion.ramp_duration=0.2", "--set",
                 "line_types.chain.normal_drag_coefficient=1e308", "-o", str(out),
                 "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "run failed" in err and "nothing written: the run stopped before recording" in err
    assert "partial results written" not in err and not out.exists()


# -- the other commands that write ---------------------------------------------------------
def test_sweep_outputs_are_checked_before_any_run(case, tmp_path, tmpfs, capsys):
    text = case.read_text()
    grid = ["--grid", "motion.period=1.25,1.5"]
    assert main(["sweep", str(case), *SHORT, *grid, "-o", str(case), "--quiet"]) == 2
    assert "expected a file other than the case file" in capsys.readouterr().err
    assert case.read_text() == text
    folder = tmpfs("ro", "ro,size=1m")
    assert main(["sweep", str(case), *SHORT, *grid, "-o", str(folder / "c.nc"),
                 "--quiet"]) == 2
    assert "folder floatmoor can write to" in capsys.readouterr().err
    out = tmp_path / "c.nc"
    assert main(["sweep", str(case), *SHORT, *grid, "-o", str(out), "--runs-dir",
                 str(folder / "runs"), "--quiet"]) == 2
    assert "--runs-dir: expected a file in a folder floatmoor can write to" in \
        capsys.readouterr().err
    assert not out.exists()


def test_hydro_build_output_is_checked_and_locked(tmp_path, capsys):
    from tests.hydro.test_cli_hydro import TINY_CASE

    (tmp_path / "hydrodb").mkdir()
    case = tmp_path / "tiny.toml"
    case.write_text(TINY_CASE)
    assert main(["hydro", "build", str(case), "-o", str(case), "--quiet"]) == 2
    assert "expected a file other than the case file" in capsys.readouterr().err
    assert case.read_text() == TINY_CASE
    target = tmp_path / "hydrodb" / "tiny.nc"
    with output_lock(target):
        assert main(["hydro", "build", str(case), "--quiet"]) == 2
        assert "being written by process" in capsys.readouterr().err
    assert not target.exists()


def test_study_and_report_folders_are_checked_and_locked(tmp_path, tmpfs, capsys):
    folder = tmpfs("ro", "ro,size=1m")
    for command in (["study", "qd-verification", "--quick", "--quiet"], ["report", "x.nc"]):
        assert main([*command, "-o", str(folder / "out")]) == 2
        err = capsys.readouterr().err
        assert "folder floatmoor can write to" in err and "Read-only file system" in err
    out = tmp_path / "study"
    with output_lock(out.resolve()):
        assert main(["study", "qd-verification", "--quick", "-o", str(out), "--quiet"]) == 2
        assert "being written by process" in capsys.readouterr().err
    assert not out.exists()
