"""``floatmoor run`` and ``check`` end to end: output file, attributes, summary, plot,
progress, and the partial file left by an interrupted or failed run."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest

import floatmoor
from floatmoor.cli import main
from floatmoor.errors import SolverError
from floatmoor.io.netcdf import read_dataset
from floatmoor.io.variables import VARIABLE_ATTRIBUTES
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.simulation import forced
from floatmoor.cli.progress import ProgressReporter
from tests.conftest import LINDAHL_CASE

QS = ["--set", 'lines.chain.model="quasi-static"']
SHORT = ["--set", "simulation.duration=5.0", *QS]  # ramp 2.5 s + 2 cycles of 1.25 s


def test_run_writes_labelled_dataset_summary_and_plot(tmp_path, capsys):
    out, png = tmp_path / "lindahl.nc", tmp_path / "lindahl.png"
    status = main(["run", str(LINDAHL_CASE), *SHORT, "-o", str(out), "--plot", str(png),
                   "--json", "--quiet"])
    assert status == 0
    summary = json.loads(capsys.readouterr().out)
    stats = summary["lines"]["chain"]["fairlead_tension_N"]
    assert stats["n_cycles"] == 2 and stats["window_start"] == 2.5
    assert stats["min"] <= stats["mean"] <= stats["max"]
    assert stats["mean_cycle_max"] == pytest.approx(stats["max"], rel=1e-3)  # periodic QS
    assert summary["simulated_time_s"] == pytest.approx(5.0)
    assert summary["wall_time_s"] > 0.0

    ds = read_dataset(out)
    assert ds.sizes["time"] == 2001 and list(ds["line"].values) == ["chain"]
    for name in list(ds.data_vars) + list(ds.coords):
        assert ds[name].attrs["units"] == VARIABLE_ATTRIBUTES[name]["units"], name
        assert ds[name].attrs["long_name"], name
    assert ds.attrs["case_toml"] == LINDAHL_CASE.read_text()
    assert ds.attrs["case_overrides"] == 'simulation.duration=5.0\nlines.chain.model="quasi-static"'
    assert ds.attrs["floatmoor_version"] == floatmoor.__version__
    assert ds.attrs["created"].endswith("+00:00") and ds.attrs["status"] == "complete"
    np.testing.assert_allclose(ds["fairlead_tension"],
                               np.linalg.norm(ds["fairlead_force"].values, axis=-1))
    for name in ds.data_vars:
        assert np.all(np.isfinite(ds[name].values))
    assert png.stat().st_size > 10_000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_text_summary_and_check(tmp_path, capsys):
    assert main(["run", str(LINDAHL_CASE), *SHORT, "-o", str(tmp_path / "a.nc"), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "chain" in text and "quasi-static" in text and "cycle max" in text
    assert main(["check", str(LINDAHL_CASE)]) == 0
    text = capsys.readouterr().out
    assert "valid case" in text and "chain" in text


def test_interrupted_run_leaves_valid_partial_file(tmp_path, capsys, monkeypatch):
    calls = []

    def interrupt(self, simulated):
        calls.append(simulated)
        if len(calls) == 2:
            raise KeyboardInterrupt

    monkeypatch.setattr(ProgressReporter, "__call__", interrupt)
    out = tmp_path / "partial.nc"
    assert main(["run", str(LINDAHL_CASE), "-o", str(out), *QS]) == 130
    assert "interrupted" in capsys.readouterr().err
    ds = read_dataset(out)
    assert ds.attrs["status"].startswith("interrupted")
    assert ds.sizes["time"] == 2 * forced.CHUNK_SAMPLES
    assert all(np.all(np.isfinite(ds[v].values)) for v in ds.data_vars)


def test_failed_run_names_line_time_quantity_and_keeps_partial(tmp_path, capsys, monkeypatch):
    original = QuasiStaticLine.solve_path

    def failing(self, time, path, *arrays):
        stop = int(np.searchsorted(time, 7.0))
        if stop < time.size:
            original(self, time[:stop], path[:stop], *(a[:stop] for a in arrays))
            for a in arrays:
                a[stop:] = np.nan  # what a diverging model would leave behind
            self.failed_index = stop
            raise SolverError(f"line '{self.name}' (quasi-static): fairlead force at "
                              f"t = {time[stop]:.6g} s: no solution")
        original(self, time, path, *arrays)

    monkeypatch.setattr(QuasiStaticLine, "solve_path", failing)
    out = tmp_path / "failed.nc"
    assert main(["run", str(LINDAHL_CASE), "-o", str(out), "--quiet", *QS]) == 1
    err = capsys.readouterr().err
    assert "line 'chain'" in err and "t = 7 s" in err and "fairlead force" in err
    ds = read_dataset(out)
    assert ds.attrs["status"].startswith("failed")
    assert ds["time"].values[-1] < 7.0
    assert all(np.all(np.isfinite(ds[v].values)) for v in ds.data_vars)


def test_progress_reports_on_long_runs():
    stream = io.StringIO()
    reporter = ProgressReporter(10.0, stream=stream, delay=0.0, interval=0.0)
    reporter(2.5)
    reporter(5.0)
    lines = stream.getvalue().splitlines()
    assert len(lines) == 2 and "t = 5 / 10 s (50%)" in lines[1]
    quiet = io.StringIO()
    ProgressReporter(10.0, stream=quiet, delay=60.0)(5.0)  # short runs stay silent
    assert quiet.getvalue() == ""


def test_results_are_written_as_the_run_goes(tmp_path):
    """With a zero flush interval the file on disk holds every completed chunk mid-run."""
    from floatmoor.case.load import load_case

    out = tmp_path / "growing.nc"
    seen = []

    def look(simulated):
        ds = read_dataset(out)
        seen.append((ds.sizes["time"], ds.attrs["status"]))

    case = load_case(LINDAHL_CASE, [QS[1]])
    result = forced.run_forced_motion(case, output=out, progress=look, flush_interval=0.0)
    assert [n for n, _ in seen] == [forced.CHUNK_SAMPLES * (i + 1) for i in range(len(seen) - 1)] \
        + [result.dataset.sizes["time"]]
    assert all(status.startswith("running") for _, status in seen)
    assert read_dataset(out).attrs["status"] == "complete"


def test_dynamic_run_with_line_shapes(tmp_path, capsys):
    """The case's default dynamic model, with shapes every 0.05 s on the DG nodes."""
    out = tmp_path / "dyn.nc"
    status = main(["run", str(LINDAHL_CASE), "--set", "simulation.duration=5.0", "--set",
                   "simulation.shape_output_interval=0.05", "-o", str(out), "--json", "--quiet"])
    assert status == 0
    summary = json.loads(capsys.readouterr().out)
    stats = summary["lines"]["chain"]["fairlead_tension_N"]
    assert summary["lines"]["chain"]["model"] == "dynamic" and stats["n_cycles"] == 2
    ds = read_dataset(out)
    assert ds.sizes["shape_time"] == 101 and ds.sizes["node"] == 60  # 10 elements of order 5
    np.testing.assert_allclose(ds["shape_time"].values, np.arange(101) * 0.05, atol=1e-12)
    arc = ds["arc_length"].sel(line="chain").values
    assert arc[0] == 0.0 and arc[-1] == pytest.approx(33.0) and np.all(np.diff(arc) >= 0.0)
    for name in ("shape_time", "arc_length", "shape_position", "shape_tension"):
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"]
    shape = ds["shape_position"].sel(line="chain")
    # The end nodes follow the anchor and the fairlead: the DG imposes them weakly (through the
    # traces and the flux), and while the chain is slack next to the fairlead nothing but the
    # flux's velocity penalty holds the end node, which then strays by up to 8.5 mm (0.3 mm at
    # the anchor); imposing it strongly cost the end forces an order of convergence.
    END_NODE_ATOL = 0.01
    np.testing.assert_allclose(shape.isel(node=0).values, np.tile([0.0, 0.0, -3.0], (101, 1)),
                               atol=END_NODE_ATOL)
    fair = ds["fairlead_position"].sel(line="chain").values[::20]
    np.testing.assert_allclose(shape.isel(node=-1).values, fair, atol=END_NODE_ATOL)
    # where the line is taut the last node's tension is the fairlead tension (in slack and
    # snap phases the fairlead force is the flux, which adds the velocity penalty)
    node_tension = ds["shape_tension"].sel(line="chain").isel(node=-1).values
    fairlead_tension = ds["fairlead_tension"].sel(line="chain").values[::20]
    taut = fairlead_tension > 20.0
    assert taut.sum() > 30
    np.testing.assert_allclose(node_tension[taut], fairlead_tension[taut], rtol=0.02)
    assert all(np.all(np.isfinite(ds[v].values)) for v in ds.data_vars)


@pytest.mark.parametrize("quiet", [True, False])
def test_the_final_line_says_how_much_of_the_wall_time_compiled_kernels(tmp_path, capsys,
                                                                        monkeypatch, quiet):
    # the first run after an install compiles its kernels: its wall time says so (a fake
    # compilation of 12.5 s, since the test's kernels are cached)
    from contextlib import contextmanager

    import floatmoor._numba

    @contextmanager
    def one_compilation(on_start, on_end):
        on_start()
        on_end(12.5)
        yield

    monkeypatch.setattr(floatmoor._numba, "watch_compilation", one_compilation)
    out = tmp_path / "run.nc"
    argv = ["run", str(LINDAHL_CASE), "-o", str(out), "--set", 'lines.*.model="quasi-static"',
            "--set", "simulation.duration=3.0"]
    assert main(argv + (["--quiet"] if quiet else [])) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert "s of wall time (12.5 s of it compiling the numerical kernels, which later runs " \
           "load from their cache)" in last
    assert main(argv + ["--quiet", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["compile_time_s"] == 12.5
