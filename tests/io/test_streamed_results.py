"""A run's results streamed to their file: the final file is the one the
whole-dataset writer made (``write_dataset``: xarray's netCDF-3 writer), but for ``time``
being the record dimension (stored first in the variables along it); the window the run
holds is bounded; the file is valid while the run goes and after it is killed."""

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
from floatmoor.io.netcdf import open_result, read_dataset, write_dataset
from floatmoor.simulation import forced, recorder as recorder_module
from floatmoor.simulation.coupled_run import run_coupled
from floatmoor.simulation.forced import output_times, run_forced_motion
from floatmoor.simulation.recorder import Recorder
from tests.conftest import CASES, LINDAHL_CASE, REPO

BUOY = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
SYSTEM = Path(__file__).parents[1] / "data" / "systems" / "clump_buoy.toml"
BODY_MOTION = CASES / "systems" / "three_line_clump_buoy.toml"
#: Attributes that differ between two runs of a case: when it was written, how long it took.
VOLATILE = ("created", "wall_time_s")


def _scipy(path: Path) -> xr.Dataset:
    with xr.open_dataset(path, engine="scipy") as ds:
        return ds.load()


def _without_volatile(ds: xr.Dataset) -> xr.Dataset:
    return ds.assign_attrs({k: None for k in VOLATILE})


def _small_windows(monkeypatch) -> None:
    """Windows of a few samples and a write at every chunk: many appends."""
    monkeypatch.setattr(recorder_module, "WINDOW_BYTES", 1)
    monkeypatch.setattr(forced, "CHUNK_SAMPLES", 37)


def _compare(streamed_path: Path, in_memory: xr.Dataset, tmp_path: Path) -> None:
    """The streamed file against the whole-dataset writer's file of the same results."""
    whole = tmp_path / "whole.nc"
    write_dataset(in_memory, whole)
    old, new = _scipy(whole), _scipy(streamed_path)
    assert new.encoding["unlimited_dims"] == {"time"}
    assert old.encoding["unlimited_dims"] == set()
    for name, var in new.variables.items():  # time first where it is a dimension
        assert "time" not in var.dims or var.dims[0] == "time", name
    assert set(new.attrs) == set(old.attrs)
    back = read_dataset(streamed_path)  # the usual order again
    xr.testing.assert_identical(_without_volatile(back), _without_volatile(old))
    for name, var in old.variables.items():
        assert back[name].dims == var.dims and back[name].dtype == var.dtype, name
        assert var.attrs["units"] and var.attrs["long_name"], name
    assert new.attrs["status"] == "complete" and new.attrs["floatmoor_version"]


@pytest.mark.parametrize("source, overrides", [
    (LINDAHL_CASE, ['lines.chain.model="quasi-static"', "simulation.duration=4.0",
                    "simulation.shape_output_interval=0.3"]),
    (SYSTEM, ['motion={kind = "harmonic", amplitude = [2.0, 0.0, 1.0], period = 10.0, '
              'ramp_duration = 1.0}',
              "simulation.duration=3.0", "simulation.shape_output_interval=0.5"]),
    (BODY_MOTION, ["simulation.duration=12.5"]),
], ids=["lindahl-shapes", "system-groups", "body-motion"])
def test_forced_run_file_equals_the_whole_dataset_writers(tmp_path, monkeypatch, source,
                                                          overrides):
    case = load_case(source, overrides)
    in_memory = run_forced_motion(case).dataset
    _small_windows(monkeypatch)
    out = tmp_path / "streamed.nc"
    result = run_forced_motion(case, output=out, flush_interval=0.0)
    _compare(out, in_memory, tmp_path)
    # the returned dataset is read from the file, lazily, in the in-memory run's order
    assert not result.dataset["fairlead_tension"].variable._in_memory
    xr.testing.assert_identical(_without_volatile(result.dataset.load()),
                                _without_volatile(in_memory))
    result.dataset.close()


def test_coupled_run_file_equals_the_whole_dataset_writers(tmp_path, monkeypatch):
    import floatmoor.simulation.coupled_run as cr

    case = load_case(BUOY, ['lines.*.model="quasi-static"', 'lines.line1.model="quasi-dynamic"',
                            "simulation.duration=2.0", "simulation.output_interval=0.02",
                            "simulation.time_step=0.01", "simulation.shape_output_interval=0.1",
                            'waves={kind = "regular", height = 0.04, period = 1.2}'])
    monkeypatch.setattr(cr, "CHUNK_STEPS", 14)  # in both: the chunks set the wave loads' blocks
    in_memory = run_coupled(case).dataset
    monkeypatch.setattr(recorder_module, "WINDOW_BYTES", 1)
    out = tmp_path / "streamed.nc"
    result = run_coupled(case, output=out, flush_interval=0.0)
    _compare(out, in_memory, tmp_path)
    xr.testing.assert_identical(_without_volatile(result.dataset.load()),
                                _without_volatile(in_memory))


def test_a_long_runs_window_is_bounded(tmp_path):
    """The recorder of a long run holds its window, not the run: ~WINDOW_BYTES of buffers,
    whatever the duration; without an output file, the whole run."""
    short = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"'])
    long = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"',
                                    "simulation.duration=20000.0"])

    def held(rec: Recorder) -> int:
        arrays = [*rec.series.values(), *(rec.system or {}).values()]
        return sum(a.nbytes for a in arrays)

    a = Recorder(short, output_times(short.simulation), tmp_path / "a.nc", chunk=2000)
    b = Recorder(long, output_times(long.simulation), tmp_path / "b.nc", chunk=2000)
    assert b.capacity < output_times(long.simulation).size // 20
    assert held(b) <= 1.05 * recorder_module.WINDOW_BYTES
    assert held(a) <= held(b)
    c = Recorder(short, output_times(short.simulation), None, chunk=2000)
    assert c.capacity == output_times(short.simulation).size


def test_partial_file_is_readable_during_the_run(tmp_path, monkeypatch):
    _small_windows(monkeypatch)
    case = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"', "simulation.duration=4.0"])
    out = tmp_path / "r.nc"
    seen = []

    def look(t: float) -> None:
        if out.exists():
            ds = _scipy(out)
            seen.append((ds.sizes["time"], ds.attrs["status"], ds.attrs["simulated_time_s"]))

    run_forced_motion(case, output=out, progress=look, flush_interval=0.0)
    sizes = [s for s, _, _ in seen]
    assert len(seen) > 10 and sizes == sorted(sizes) and sizes[0] < sizes[-1]
    assert all(status.startswith("running: partial results up to t = ") for _, status, _ in seen)
    assert all(t == pytest.approx((n - 1) * case.simulation.output_interval) for n, _, t in seen)
    assert _scipy(out).attrs["status"] == "complete"


def test_returned_dataset_reads_the_file_it_was_written_to(tmp_path):
    """The lazily read result keeps its own file: a later run replacing it does not change
    what the first result reads."""
    out = tmp_path / "r.nc"
    first = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"',
                                     "simulation.duration=3.0"])
    second = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"',
                                      "simulation.duration=3.0", "motion.radius=0.1"])
    a = run_forced_motion(first, output=out).dataset
    b = run_forced_motion(second, output=out).dataset
    assert not np.array_equal(a["fairlead_tension"].values, b["fairlead_tension"].values)
    np.testing.assert_array_equal(a["fairlead_tension"].values,
                                  run_forced_motion(first).dataset["fairlead_tension"].values)
    a.close(), b.close()
    reopened = open_result(out)
    np.testing.assert_array_equal(reopened["fairlead_tension"].values,
                                  b["fairlead_tension"].values)
    reopened.close()


def test_run_killed_by_sigkill_leaves_a_valid_file(tmp_path):
    """``floatmoor run`` killed with SIGKILL while it appends: the file is readable and holds
    the samples of its last write, in order, with a 'running' status."""
    out = tmp_path / "killed.nc"
    command = [sys.executable, "-m", "floatmoor", "run", str(LINDAHL_CASE), "-o", str(out),
               "--set", 'lines.chain.model="quasi-static"', "--set",
               "simulation.duration=20000", "--quiet"]
    child = subprocess.Popen(command, cwd=REPO, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and child.poll() is None:
            if out.exists() and out.stat().st_size > 2_000_000:  # written at least twice
                break
            time.sleep(0.05)
        assert child.poll() is None, "the run ended before it could be killed"
        os.kill(child.pid, signal.SIGKILL)
    finally:
        child.kill()
        child.wait()
    ds = read_dataset(out)
    n = ds.sizes["time"]
    status = ds.attrs["status"]
    assert n > 1 and status.startswith("running: partial results up to t = "), (n, status)
    np.testing.assert_allclose(ds["time"].values, np.arange(n) * 0.0025, rtol=1e-12)
    assert np.all(np.isfinite(ds["fairlead_tension"].values))
    # the attributes are updated after the records are counted: never ahead of them
    last = float(ds["time"].values[-1])
    # (the status prints 6 significant digits: compare with the last time printed so)
    assert float(status.split("t = ")[1].split()[0]) <= float(f"{last:.6g}"), (n, status)
    assert ds.attrs["simulated_time_s"] <= last
