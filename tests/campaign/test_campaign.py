"""Campaigns: designs, results equal to individual runs, failures recorded, resume, local
processes and a Dask cluster giving the same numbers."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.campaign import runner as campaign_runner
from floatmoor.campaign import worker
from floatmoor.campaign.design import design_from_options
from floatmoor.campaign.runner import run_campaign
from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from floatmoor.io.netcdf import read_dataset
from floatmoor.post.summary import run_summary
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE

#: Quasi-static, 5 s: each run takes milliseconds.
BASE = ['lines.chain.model="quasi-static"', "simulation.duration=5.0"]
GRID = ["motion.radius=0.1,0.2", "motion.period=1.25,2.5"]


def test_design_product_zip_and_errors():
    design = design_from_options(GRID, ["motion.phase_deg=0.0,90.0,180.0",
                                        "motion.sense=\"away-from-anchor-at-top\",\"toward-anchor-at-top\",\"away-from-anchor-at-top\""])
    assert design.shape == (2, 2, 3) and design.size == 12
    index, overrides = design.runs()[5]
    assert index == (0, 1, 2)
    assert overrides == ["motion.radius=0.1", "motion.period=2.5", "motion.phase_deg=180.0",
                         'motion.sense="away-from-anchor-at-top"']
    with pytest.raises(CaseError, match="equally many"):
        design_from_options([], ["motion.radius=0.1,0.2", "motion.period=1.0"])
    with pytest.raises(CaseError, match="TOML values"):
        design_from_options(["motion.sense=away"])
    with pytest.raises(CaseError, match="swept once"):
        design_from_options(["motion.radius=0.1"], ["motion.radius=0.2"])


def test_campaign_equals_individual_runs(tmp_path):
    ds = run_campaign(LINDAHL_CASE, design_from_options(GRID), base_overrides=BASE,
                      output=tmp_path / "c.nc")
    assert (ds["status"].values == "complete").all()
    for i, r in enumerate((0.1, 0.2)):
        for j, T in enumerate((1.25, 2.5)):
            case = load_case(LINDAHL_CASE, [*BASE, f"motion.radius={r}", f"motion.period={T}"])
            expected = run_summary(case, run_forced_motion(case).dataset)
            stats = expected["lines"]["chain"]["fairlead_tension_N"]
            for key in ("mean", "std", "max", "mean_cycle_max"):
                assert ds[f"fairlead_tension_{key}"].values[i, j, 0] == pytest.approx(stats[key],
                                                                                     rel=1e-12)
    on_disk = read_dataset(tmp_path / "c.nc")
    for name in list(on_disk.data_vars) + list(on_disk.coords):
        assert on_disk[name].attrs["units"] and on_disk[name].attrs["long_name"], name
    assert on_disk.attrs["runs_complete"] == 4 and on_disk.attrs["case_overrides"]


def test_failed_run_is_recorded_and_the_campaign_completes(tmp_path, monkeypatch):
    original = worker.run_one

    def flaky(case_path, overrides, timeseries=False, run_file=None):
        if "motion.period=2.5" in overrides and "motion.radius=0.2" in overrides:
            return original(case_path, [*overrides, "lines.chain.quasi_static.max_iterations=1",
                                        "lines.chain.quasi_static.tolerance=1e-16"], timeseries,
                            run_file)
        return original(case_path, overrides, timeseries, run_file)

    monkeypatch.setattr(campaign_runner, "run_one", flaky)
    ds = run_campaign(LINDAHL_CASE, design_from_options(GRID), base_overrides=BASE,
                      output=tmp_path / "c.nc")
    status = ds["status"].values
    assert status[1, 1].startswith("failed: ") and "chain" in status[1, 1]
    assert (status[status != status[1, 1]] == "complete").all()
    assert np.isnan(ds["fairlead_tension_mean"].values[1, 1, 0])
    assert ds.attrs["runs_failed"] == 1


def test_time_left_is_not_estimated_from_runs_that_compiled(monkeypatch):
    """A first run of 20 s that compiled kernels, then runs of 1 s: no estimate after the
    first run (it was '~60 s left'), then one from the runs after it."""
    import types

    clock = {"now": 0.0}
    durations = iter([20.0, 1.0, 1.0, 1.0])
    original = worker.run_one

    def timed(case_path, overrides, timeseries=False, run_file=None):
        result = original(case_path, overrides, timeseries, run_file)
        seconds = next(durations)
        clock["now"] += seconds
        result["compile_time_s"] = 19.0 if seconds == 20.0 else 0.0
        return result

    monkeypatch.setattr(campaign_runner, "run_one", timed)
    monkeypatch.setattr(campaign_runner, "_time",
                        types.SimpleNamespace(perf_counter=lambda: clock["now"]))
    seen = []
    run_campaign(LINDAHL_CASE, design_from_options(GRID), base_overrides=BASE,
                 progress=lambda done, total, left: seen.append((done, left)))
    assert [done for done, _ in seen] == [0, 1, 2, 3, 4]
    assert np.isnan(seen[1][1]) and seen[2][1] == 2.0 and seen[3][1] == 1.0


def test_runs_report_their_compile_time():
    """A worker's result says how long its kernels compiled: 0 once they are cached."""
    first = worker.run_one(str(LINDAHL_CASE), BASE)  # compiles on a cold cache
    again = worker.run_one(str(LINDAHL_CASE), BASE)
    assert first["compile_time_s"] >= 0.0
    assert again["status"] == "complete" and again["compile_time_s"] == 0.0


def test_interrupted_campaign_resumes_without_redoing_runs(tmp_path, monkeypatch):
    out = tmp_path / "c.nc"
    calls = []

    def interrupt(done, total, left):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_campaign(LINDAHL_CASE, design_from_options(GRID), base_overrides=BASE, output=out,
                     progress=interrupt)
    assert read_dataset(out).attrs["runs_complete"] == 2
    original = worker.run_one
    monkeypatch.setattr(campaign_runner, "run_one",
                        lambda *a: calls.append(a[1]) or original(*a))
    ds = run_campaign(LINDAHL_CASE, design_from_options(GRID), base_overrides=BASE, output=out)
    assert len(calls) == 2 and (ds["status"].values == "complete").all()
    # another campaign in the same file is refused
    with pytest.raises(CaseError, match="same campaign"):
        run_campaign(LINDAHL_CASE, design_from_options(["motion.radius=0.1,0.3"]),
                     base_overrides=BASE, output=out)


def test_two_local_workers_and_timeseries_give_the_same_numbers(tmp_path):
    design = design_from_options(GRID)
    serial = run_campaign(LINDAHL_CASE, design, base_overrides=BASE, timeseries=True)
    parallel = run_campaign(LINDAHL_CASE, design, base_overrides=BASE, workers=2,
                            timeseries=True)
    np.testing.assert_array_equal(serial["fairlead_tension"], parallel["fairlead_tension"])
    np.testing.assert_array_equal(serial["fairlead_tension_max"],
                                  parallel["fairlead_tension_max"])
    assert serial["fairlead_tension"].dims == ("motion.radius", "motion.period", "line", "time")


@pytest.mark.slow  # ~9 s; the cluster's sweeps and uq study against local numbers stay default
def test_dask_cluster_gives_the_same_numbers():
    distributed = pytest.importorskip("distributed")
    design = design_from_options(["motion.radius=0.1,0.2"])
    local = run_campaign(LINDAHL_CASE, design, base_overrides=BASE)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        remote = run_campaign(LINDAHL_CASE, design, base_overrides=BASE,
                              scheduler=cluster.scheduler_address)
    np.testing.assert_array_equal(local["fairlead_tension_mean"], remote["fairlead_tension_mean"])
    assert (remote["status"].values == "complete").all()


def test_sweep_command(tmp_path, capsys):
    out = tmp_path / "sweep.nc"
    assert main(["sweep", str(LINDAHL_CASE), *sum((["--set", b] for b in BASE), []),
                 "--grid", "motion.radius=0.1,0.2", "-o", str(out), "--quiet"]) == 0
    assert "2 of 2 runs complete" in capsys.readouterr().out
    assert read_dataset(out).sizes["motion.radius"] == 2
    # a bad swept value is bad input: status 2, nothing written
    bad = tmp_path / "bad.nc"
    assert main(["sweep", str(LINDAHL_CASE), "--grid", "motion.radius=0.1,-1.0", "-o",
                 str(bad), "--quiet"]) == 2
    assert "motion.radius" in capsys.readouterr().err and not bad.exists()


def test_campaign_table_in_the_case_file(tmp_path, capsys):
    case = tmp_path / "lindahl_campaign.toml"
    case.write_text(LINDAHL_CASE.read_text() + '\n[campaign.grid]\n"motion.radius" = [0.1, 0.2]\n'
                    '\n[campaign.zip]\n"motion.period" = [1.25, 2.5]\n'
                    '"motion.ramp_duration" = [2.5, 5.0]\n')
    out = tmp_path / "table.nc"
    argv = ["sweep", str(case), "--set", BASE[0], "--set", "simulation.duration=7.5", "-o",
            str(out), "--quiet"]
    assert main(argv) == 0
    ds = read_dataset(out)
    assert ds.sizes["motion.radius"] == 2 and ds.sizes["motion.period"] == 2
    np.testing.assert_array_equal(ds["motion.ramp_duration"].values, [2.5, 5.0])
    # a --grid on the command line replaces the table's axis of the same key
    assert main([*argv[:-3], "--grid", "motion.radius=0.15", "-o", str(tmp_path / "b.nc"),
                 "--quiet"]) == 0
    assert read_dataset(tmp_path / "b.nc").sizes["motion.radius"] == 1


def test_sweep_with_failed_runs_exits_1_naming_them(tmp_path, capsys):
    """A sweep whose runs fail at run time (one iteration cannot reach 1e-16; the values
    validate) keeps its dataset but exits 1 with a one-line summary naming the failed runs by
    their swept values, then their messages; 0 only when every run completes."""
    out = tmp_path / "sweep.nc"
    argv = ["sweep", str(LINDAHL_CASE), *sum((["--set", b] for b in BASE), []),
            "--set", "lines.chain.quasi_static.max_iterations=1",
            "--grid", "lines.chain.quasi_static.tolerance=1e-16,1e-6", "--grid",
            "motion.radius=0.1,0.2", "-o", str(out), "--quiet"]
    assert main(argv) == 1
    captured = capsys.readouterr()
    assert "2 of 4 runs complete, 2 failed" in captured.out
    lines = captured.err.strip().splitlines()
    assert lines[0] == ("floatmoor: sweep failed: 2 of 4 runs failed "
                        "(lines.chain.quasi_static.tolerance=1e-16, motion.radius=0.1; "
                        "lines.chain.quasi_static.tolerance=1e-16, motion.radius=0.2)")
    assert lines[1].startswith("  lines.chain.quasi_static.tolerance=1e-16, motion.radius=0.1: "
                               "failed: SolverError: line 'chain'")
    assert len(lines) == 3
    ds = read_dataset(out)
    assert ds.attrs["runs_failed"] == 2 and ds.attrs["runs_complete"] == 2
    # every run failing (the probe's case) is a failure too, not "0 of 2 ... exit 0"
    assert main([*argv[:-7], "--grid", "lines.chain.quasi_static.tolerance=1e-16", "--grid",
                 "motion.radius=0.1,0.2", "-o", str(tmp_path / "all.nc"), "--quiet"]) == 1
    assert "2 of 2 runs failed" in capsys.readouterr().err


def test_sweep_whose_workers_cannot_read_the_case_exits_1(tmp_path, capsys, monkeypatch):
    """The probe: every worker fails to load the case (here a path the workers do not
    see); the sweep said "0 of 4 runs complete, 4 failed" and exited 0."""
    original = worker.run_one

    def elsewhere(case_path, overrides, timeseries=False, run_file=None):
        return original(str(tmp_path / "not_on_this_worker.toml"), overrides, timeseries,
                        run_file)

    monkeypatch.setattr(campaign_runner, "run_one", elsewhere)
    out = tmp_path / "lost.nc"
    assert main(["sweep", str(LINDAHL_CASE), *sum((["--set", b] for b in BASE), []),
                 "--grid", GRID[0], "--grid", GRID[1], "-o", str(out), "--quiet"]) == 1
    captured = capsys.readouterr()
    assert "0 of 4 runs complete, 4 failed" in captured.out
    err = captured.err.strip().splitlines()
    assert err[0].startswith("floatmoor: sweep failed: 4 of 4 runs failed (motion.radius=0.1, "
                             "motion.period=1.25; ")
    assert "failed: CaseError: " in err[1] and "not_on_this_worker.toml" in err[1]
    assert read_dataset(out).attrs["runs_failed"] == 4
