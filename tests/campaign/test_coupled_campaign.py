"""Campaigns of floater (coupled) cases: motion statistics per DOF beside the line statistics,
histories, run files, a failing run, resume, two local workers giving the same numbers (on a
Dask cluster: tests/campaign/test_cluster.py); and the run-file resume rules (on fast
forced-motion runs)."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from floatmoor.campaign import runner as campaign_runner
from floatmoor.campaign import worker
from floatmoor.campaign.design import design_from_options
from floatmoor.campaign.runner import run_campaign
from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.io.dataset import DOFS
from floatmoor.io.netcdf import read_dataset, write_dataset
from floatmoor.post.summary import run_summary
from floatmoor.simulation.coupled_run import run_coupled
from tests.conftest import CASES, LINDAHL_CASE

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: Quasi-static lines, 2 s of simulated time: each run costs ~3 s (mostly building K(t)).
BUOY_BASE = ["simulation.duration=2.0", "simulation.output_interval=0.02",
             "simulation.time_step=0.02",
             'waves={kind = "regular", height = 0.04, period = 1.2, ramp_duration = 1.0}',
             'lines.*.model="quasi-static"']
#: Three wave periods; the last run fails (its catenary cannot meet 1e-16 in one iteration).
BUOY_ZIP = ["waves.period=1.0,1.4,1.2",
            "lines.line1.quasi_static.tolerance=1e-12,1e-12,1e-16",
            "lines.line1.quasi_static.max_iterations=100,100,1"]
#: Statistics stored by the campaign against those recomputed from the run file: the same
#: floating-point operations on the same numbers, up to summation order.
STATS_RTOL = 1e-12

#: The run files, named from the swept values (zipped keys by the first one).
BUOY_RUN_FILES = ["waves.period=1.0.nc", "waves.period=1.4.nc", "waves.period=1.2.nc"]

LINDAHL_BASE = ['lines.chain.model="quasi-static"', "simulation.duration=5.0"]


def _overrides(j: int) -> list[str]:
    design = design_from_options([], BUOY_ZIP)
    return [*BUOY_BASE, *design.runs()[j][1]]


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    """The buoy campaign run serially with histories and run files."""
    folder = tmp_path_factory.mktemp("coupled")
    ds = run_campaign(BUOY_CASE, design_from_options([], BUOY_ZIP), base_overrides=BUOY_BASE,
                      output=folder / "c.nc", runs_dir=folder / "runs", timeseries=True)
    return folder, ds


def test_coupled_campaign_keeps_motion_statistics_histories_and_run_files(serial) -> None:
    folder, ds = serial
    status = ds["status"].values
    assert list(status[:2]) == ["complete", "complete"]
    assert status[2].startswith("failed: SolverError: line 'line1'"), status[2]
    assert ds.attrs["runs_failed"] == 1
    assert list(ds["dof"].values) == list(DOFS)
    assert ds["body_displacement_std"].dims == ("waves.period", "dof")
    assert ds["body_displacement"].dims == ("waves.period", "time", "dof")
    assert np.isnan(ds["body_displacement_mean"].values[2]).all()
    assert np.isnan(ds["fairlead_tension_mean"].values[2]).all()
    for j in range(2):
        run_file = folder / "runs" / BUOY_RUN_FILES[j]
        assert ds["run_file"].values[j] == str(run_file)
        run = read_dataset(run_file)
        assert run.attrs["status"] == "complete"
        case = load_case(BUOY_CASE, _overrides(j))
        expected = run_summary(case, run)
        for line, entry in expected["lines"].items():
            for key in ("mean", "std", "min", "max"):
                assert ds[f"fairlead_tension_{key}"].sel(line=line).values[j] == pytest.approx(
                    entry["fairlead_tension_N"][key], rel=STATS_RTOL)
            assert np.isnan(ds["fairlead_tension_mean_cycle_max"].sel(line=line).values[j])
        for dof, stats in expected["body_displacement"].items():
            for key in ("mean", "std", "min", "max"):
                assert ds[f"body_displacement_{key}"].sel(dof=dof).values[j] == pytest.approx(
                    stats[key], rel=STATS_RTOL, abs=1e-300)
        np.testing.assert_array_equal(ds["body_displacement"].values[j],
                                      run["body_displacement"].values)
        np.testing.assert_array_equal(ds["fairlead_tension"].values[j],
                                      run["fairlead_tension"].values)
        # the waves move the buoy: surge, heave and pitch vary after the ramp
        assert (ds["body_displacement_std"].sel(dof=["Surge", "Heave", "Pitch"]).values[j]
                > 1e-3).all()
    # the failed run left its partial file, named in the dataset
    assert ds["run_file"].values[2] == str(folder / "runs" / BUOY_RUN_FILES[2])
    # a campaign run equals the run made alone
    alone = run_coupled(load_case(BUOY_CASE, _overrides(1))).dataset
    np.testing.assert_array_equal(ds["body_displacement"].values[1],
                                  alone["body_displacement"].values)
    on_disk = read_dataset(folder / "c.nc")
    for name in list(on_disk.data_vars) + list(on_disk.coords):
        assert on_disk[name].attrs["units"] and on_disk[name].attrs["long_name"], name


def test_coupled_campaign_resumes_and_retries_only_the_failed_run(serial, tmp_path,
                                                                  monkeypatch) -> None:
    folder, ds = serial
    out = tmp_path / "c.nc"
    shutil.copy(folder / "c.nc", out)
    shutil.copytree(folder / "runs", tmp_path / "runs")
    calls = []
    original = worker.run_one
    monkeypatch.setattr(campaign_runner, "run_one",
                        lambda *a: calls.append(a[1]) or original(*a))
    again = run_campaign(BUOY_CASE, design_from_options([], BUOY_ZIP),
                         base_overrides=BUOY_BASE, output=out, runs_dir=tmp_path / "runs",
                         timeseries=True)
    assert calls == [_overrides(2)]
    np.testing.assert_array_equal(again["body_displacement_std"].values[:2],
                                  ds["body_displacement_std"].values[:2])
    np.testing.assert_array_equal(again["body_displacement"].values[:2],
                                  ds["body_displacement"].values[:2])
    assert list(again["run_file"].values) == [str(tmp_path / "runs" / n) for n in BUOY_RUN_FILES]


def test_coupled_campaign_on_two_workers_gives_the_same_numbers(serial, tmp_path) -> None:
    _, ds = serial
    parallel = run_campaign(BUOY_CASE, design_from_options([], BUOY_ZIP),
                            base_overrides=BUOY_BASE, workers=2, timeseries=True,
                            runs_dir=tmp_path / "runs")
    np.testing.assert_array_equal(parallel["status"].values, ds["status"].values)
    for name in ("body_displacement_mean", "body_displacement_max", "fairlead_tension_std",
                 "body_displacement"):
        np.testing.assert_array_equal(parallel[name].values, ds[name].values)
    assert sorted(p.name for p in (tmp_path / "runs").iterdir()) == sorted(BUOY_RUN_FILES)


def test_stale_database_is_bad_input_before_anything_runs(tmp_path, capsys) -> None:
    out = tmp_path / "c.nc"
    status = main(["sweep", str(BUOY_CASE), "--grid", "hydro.panel_size=0.015,0.01", "-o",
                   str(out), "--runs-dir", str(tmp_path / "runs"), "--quiet"])
    err = capsys.readouterr().err
    assert status == 2 and "stale" in err and "Traceback" not in err
    assert not out.exists() and not (tmp_path / "runs").exists()


def test_run_files_are_redone_when_missing_incomplete_or_another_runs(tmp_path,
                                                                      monkeypatch) -> None:
    design = design_from_options(["motion.radius=0.1,0.15,0.2,0.25"])
    out, runs = tmp_path / "c.nc", tmp_path / "runs"
    first = run_campaign(LINDAHL_CASE, design, base_overrides=LINDAHL_BASE, output=out,
                         runs_dir=runs)
    names = [f"motion.radius={r}.nc" for r in ("0.1", "0.15", "0.2", "0.25")]
    assert sorted(p.name for p in runs.iterdir()) == sorted(names)
    for j, name in enumerate(names):
        assert first["run_file"].values[j] == str(runs / name)
        run = read_dataset(runs / name)
        case = load_case(LINDAHL_CASE, [*LINDAHL_BASE, f"motion.radius={name[14:-3]}"])
        stats = run_summary(case, run)["lines"]["chain"]["fairlead_tension_N"]
        assert first["fairlead_tension_max"].values[j, 0] == pytest.approx(stats["max"],
                                                                          rel=STATS_RTOL)
    calls = []
    original = worker.run_one
    monkeypatch.setattr(campaign_runner, "run_one",
                        lambda *a: calls.append(a[1][-1]) or original(*a))
    run_campaign(LINDAHL_CASE, design, base_overrides=LINDAHL_BASE, output=out, runs_dir=runs)
    assert calls == []  # everything complete, with its file
    (runs / names[0]).unlink()  # missing
    partial = read_dataset(runs / names[1])
    shutil.copy(runs / names[1], runs / names[2])  # another run's complete file
    partial.attrs["status"] = "interrupted: results up to t = 2 s"
    write_dataset(partial, runs / names[1])  # incomplete
    again = run_campaign(LINDAHL_CASE, design, base_overrides=LINDAHL_BASE, output=out,
                         runs_dir=runs)
    assert calls == ["motion.radius=0.1", "motion.radius=0.15", "motion.radius=0.2"]
    np.testing.assert_array_equal(again["fairlead_tension_max"], first["fairlead_tension_max"])
    assert read_dataset(runs / names[1]).attrs["status"] == "complete"
    # without a runs folder, the campaign file alone says what is done
    calls.clear()
    (runs / names[3]).unlink()
    run_campaign(LINDAHL_CASE, design, base_overrides=LINDAHL_BASE, output=out)
    assert calls == []


def test_sweep_command_with_runs_dir(tmp_path, capsys) -> None:
    out, runs = tmp_path / "sweep.nc", tmp_path / "runs"
    argv = ["sweep", str(LINDAHL_CASE), *sum((["--set", b] for b in LINDAHL_BASE), []),
            "--grid", "motion.period=1.25,2.5", "-o", str(out), "--quiet"]
    assert main([*argv, "--runs-dir", str(runs)]) == 0
    assert "2 of 2 runs complete" in capsys.readouterr().out
    assert sorted(p.name for p in runs.iterdir()) == ["motion.period=1.25.nc",
                                                      "motion.period=2.5.nc"]
    assert list(read_dataset(out)["run_file"].values) == [str(runs / "motion.period=1.25.nc"),
                                                          str(runs / "motion.period=2.5.nc")]
    # a runs folder that is a file, or in a missing folder, is bad input: nothing written
    a_file = tmp_path / "file.txt"
    a_file.write_text("x")
    for bad in (a_file, tmp_path / "missing" / "runs"):
        assert main([*argv[:-3], "-o", str(tmp_path / "b.nc"), "--quiet", "--runs-dir",
                     str(bad)]) == 2
        assert "--runs-dir" in capsys.readouterr().err
        assert not (tmp_path / "b.nc").exists()
