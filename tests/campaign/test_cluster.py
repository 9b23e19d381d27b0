"""Campaigns on a real Dask cluster, whose scheduler and workers run as
processes of their own in a folder of their own (``dask scheduler``, ``dask worker``), so the
client's relative case path and case folder mean nothing to them: forced-motion and coupled
sweeps give numbers identical to a local run, workers of another floatmoor are refused, and a
worker killed mid-campaign loses no finished run (a resume completes the rest); a gPC study
runs on the cluster with the local numbers, several studies submitted together share the
workers with the numbers each gives alone, and a study survives a killed worker (every run,
the uninterrupted numbers) and a killed client (no finished run lost, the same command
resumes to the uninterrupted numbers)."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Iterator

import numpy as np
import pytest

from floatmoor.errors import ModelValidityWarning
from floatmoor.campaign import cluster
from floatmoor.campaign.bundle import BundleError, make_bundle, materialise
from floatmoor.campaign.design import design_from_options
from floatmoor.campaign.runner import run_campaign
from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.io.netcdf import read_attributes, read_dataset
from floatmoor.report.compare import model_design
from tests.campaign.test_coupled_campaign import BUOY_BASE, BUOY_ZIP
from tests.conftest import LINDAHL_CASE, REPO
from tests.uq.lindahl_studies import quick_study

distributed = pytest.importorskip("distributed")

#: Seconds a scheduler or worker process gets to start (imports of dask and numpy take
#: 2-4 s on the shared test machine); a cluster not up by then is a failure, not a hang.
START_TIMEOUT = 60.0
#: Seconds a whole campaign subprocess may take before the test gives up on it.
CAMPAIGN_TIMEOUT = 120.0
#: A motion table in the client's case folder, and a different one of the same name in the
#: workers' folder: a worker reading its own folder's would give other numbers.
TABLE = "time,x,y,z\n0,0,0,0\n5,0.1,0,0.05\n10,0,0,0\n20,0.1,0,0\n"
DECOY_TABLE = "time,x,y,z\n0,0,0,0\n10,0.3,0,0\n20,0,0,0\n"
#: Quasi-static forced runs of 5 s: milliseconds each.
FORCED_BASE = ['lines.chain.model="quasi-static"', "simulation.duration=5.0"]
#: 10 s of the Lindahl chain: six cycles after the ramp, for the comparison's figures.
COMPARE_BASE = ["simulation.duration=10.0"]
#: Two tables by name: each run reads its own file.
FORCED_GRID = ['motion.file="m.csv","n.csv"', "lines.chain.length=33.0,33.2"]
#: The coupled buoy by its path relative to the repository (the test's working folder).
BUOY_CASE = Path("cases") / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: Dynamic (10 x p5, explicit) forced runs of 12 s: ~1 s each once compiled, long enough to
#: kill a worker while it runs one (six runs: some still to run when the first finishes).
KILL_BASE = ["simulation.duration=12.0"]
KILL_GRID = ["lines.chain.length=33.0,33.05,33.1,33.15,33.2,33.25"]
#: Variables that hold a run's measured times, not its results.
TIMES = ("compute_time_s", "wall_time_s")


def _table_case(folder: Path) -> Path:
    """A Lindahl copy ``folder/case/T.toml`` moving its fairlead by the table ``m.csv``
    (and ``n.csv``, the same motion, for a second file)."""
    case_folder = folder / "case"
    case_folder.mkdir(parents=True)
    text = LINDAHL_CASE.read_text().replace(
        "circular motion r = {motion.radius:.2f} m, T = {motion.period:.2f} s", "table")
    start, end = text.index("[motion]"), text.index("[simulation]")
    case = case_folder / "T.toml"
    case.write_text(text[:start] + '[motion]\nkind = "table"\nfile = "m.csv"\n\n' + text[end:])
    (case_folder / "m.csv").write_text(TABLE)
    (case_folder / "n.csv").write_text(TABLE.replace("0.05", "0.02"))
    return case


class _Cluster:
    """A scheduler and workers as processes in ``folder`` (workers in ``folder/wN``) with
    decoys there: a motion table and a damaged database under the client's names."""

    def __init__(self, folder: Path, workers: int, allowed_failures: int | None = None):
        self.folder = folder
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "case").mkdir()
        for name in ("m.csv", "n.csv"):
            (folder / "case" / name).write_text(DECOY_TABLE)
        (folder / "hydrodb").mkdir()
        (folder / "hydrodb" / "cylinder_buoy.nc").write_bytes(b"not a database")
        env = {**os.environ, "PYTHONPATH": str(REPO), "MPLBACKEND": "Agg"}
        if allowed_failures is not None:
            env["DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES"] = str(allowed_failures)
        dask = str(Path(sys.executable).parent / "dask")
        file = folder / "scheduler.json"
        self.log = open(folder / "cluster.log", "w")
        self.scheduler = subprocess.Popen(
            [dask, "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
             "--scheduler-file", str(file)], cwd=folder, env=env, stdout=self.log,
            stderr=subprocess.STDOUT)
        self.workers: list[subprocess.Popen] = []
        self.address = self._wait(lambda: file.is_file() and json.loads(file.read_text())
                                  .get("address"))
        for k in range(workers):
            here = folder / f"w{k}"
            (here / "case").mkdir(parents=True)
            shutil.copy(folder / "case" / "m.csv", here / "case" / "m.csv")
            self.workers.append(subprocess.Popen(
                [dask, "worker", self.address, "--nthreads", "1", "--no-nanny",
                 "--no-dashboard", "--name", f"w{k}", "--local-directory", str(here / "tmp")],
                cwd=here, env=env, stdout=self.log, stderr=subprocess.STDOUT))
        if workers:
            with distributed.Client(self.address, timeout=START_TIMEOUT) as client:
                client.wait_for_workers(workers, timeout=START_TIMEOUT)

    def _wait(self, ready):
        end = time.monotonic() + START_TIMEOUT
        while time.monotonic() < end:
            with contextlib.suppress(ValueError, OSError):
                found = ready()
                if found:
                    return found
            time.sleep(0.1)
        raise AssertionError(f"the cluster did not start: {(self.folder / 'cluster.log')}")

    def close(self) -> None:
        """Kill the workers (a graceful shutdown takes ~10 s), then stop the scheduler."""
        for process in self.workers:
            process.kill()
        self.scheduler.terminate()
        for process in [*self.workers, self.scheduler]:
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        self.log.close()


@contextlib.contextmanager
def _cluster(folder: Path, workers: int = 2, **kwargs) -> Iterator[_Cluster]:
    started = _Cluster(folder, workers, **kwargs)
    try:
        yield started
    finally:
        started.close()


@pytest.fixture(scope="module")
def dask_cluster(tmp_path_factory) -> Iterator[_Cluster]:
    with _cluster(tmp_path_factory.mktemp("cluster")) as started:
        yield started


def _sweep_args(case: str, base: list[str], grid: list[str], *rest: str) -> list[str]:
    return ["sweep", case, *sum((["--set", b] for b in base), []),
            *sum((["--grid", g] for g in grid), []), "--quiet", *rest]


def _assert_same_results(local, remote) -> None:
    """Every variable but the measured times bit-identical."""
    assert sorted(set(local.data_vars) - {"run_file"}) == sorted(set(remote.data_vars) -
                                                                  {"run_file"})
    for name in local.data_vars:
        if name not in TIMES and name != "run_file":
            np.testing.assert_array_equal(remote[name].values, local[name].values, err_msg=name)


def _assert_same_run_files(local: Path, remote: Path, names: list[str]) -> None:
    for name in names:
        a, b = read_dataset(local / name), read_dataset(remote / name)
        for key in ("case_file", "case_toml", "case_overrides", "status"):
            assert a.attrs[key] == b.attrs[key], (name, key)
        _assert_same_results(a, b)


def test_forced_sweep_on_workers_of_their_own_folder(dask_cluster, tmp_path,
                                                     monkeypatch) -> None:
    client = tmp_path / "client"
    _table_case(client)
    monkeypatch.chdir(client)
    design = design_from_options(FORCED_GRID)
    local = run_campaign("case/T.toml", design, base_overrides=FORCED_BASE,
                         output="local.nc", runs_dir="local_runs", timeseries=True)
    assert main(_sweep_args("case/T.toml", FORCED_BASE, FORCED_GRID, "-o", "remote.nc",
                            "--runs-dir", "runs", "--timeseries",
                            "--scheduler", dask_cluster.address)) == 0
    remote = read_dataset(client / "remote.nc")
    assert (remote["status"].values == "complete").all()
    _assert_same_results(local, remote)
    names = sorted(p.name for p in (client / "local_runs").iterdir())
    assert sorted(p.name for p in (client / "runs").iterdir()) == names
    _assert_same_run_files(client / "local_runs", client / "runs", names)
    # the runs folder is the client's: the paths are the client's, the workers wrote none
    assert all(str(p).startswith("runs/") for p in remote["run_file"].values.ravel())
    assert not list(dask_cluster.folder.rglob("*.nc.tmp"))
    assert not [p for p in dask_cluster.folder.rglob("runs") if any(p.iterdir())]


def test_coupled_sweep_with_a_relative_case_path(dask_cluster, tmp_path, monkeypatch) -> None:
    """Two runs and one failing (its catenary cannot converge): the same numbers and the
    same failure message, the database found though the workers' folder has none (a damaged
    decoy under its name)."""
    monkeypatch.chdir(REPO)  # the case's relative path and hydrodb/ are the repository's
    design = design_from_options([], BUOY_ZIP)
    local = run_campaign(BUOY_CASE, design, base_overrides=BUOY_BASE, timeseries=True,
                         runs_dir=tmp_path / "local")
    remote = run_campaign(BUOY_CASE, design, base_overrides=BUOY_BASE, timeseries=True,
                          runs_dir=tmp_path / "remote", output=tmp_path / "c.nc",
                          scheduler=dask_cluster.address)
    assert list(remote["status"].values[:2]) == ["complete"] * 2  # statuses compared below
    _assert_same_results(local, remote)
    names = sorted(p.name for p in (tmp_path / "local").iterdir())
    _assert_same_run_files(tmp_path / "local", tmp_path / "remote", names)


def test_workers_of_another_floatmoor_are_refused_before_anything_runs(
        dask_cluster, tmp_path, monkeypatch) -> None:
    real_version = cluster.__version__  # the workers', as they import this tree
    monkeypatch.setattr(cluster, "__version__", "0.0.0+other")
    out = tmp_path / "c.nc"
    with pytest.raises(cluster.WorkerVersionError) as info:
        run_campaign(LINDAHL_CASE, design_from_options(["motion.radius=0.1,0.2"]),
                     base_overrides=FORCED_BASE, output=out, runs_dir=tmp_path / "runs",
                     scheduler=dask_cluster.address)
    message = str(info.value)
    with distributed.Client(dask_cluster.address) as client:
        workers = list(client.scheduler_info()["workers"])
    assert all(w in message for w in workers)
    assert "0.0.0+other" in message and f"floatmoor {real_version}" in message, message
    assert not out.exists() and not list((tmp_path / "runs").glob("*.nc"))


def test_a_task_on_a_worker_of_another_version_refuses_to_run(tmp_path) -> None:
    case = load_case(LINDAHL_CASE, FORCED_BASE)
    bundle, blobs = make_bundle([case])
    result = cluster.run_bundled(bundle, blobs, FORCED_BASE, False, False,
                                 {"floatmoor": "0.0.0+other", "bundle_format": 1},
                                 root=tmp_path)
    assert result["status"].startswith("failed: WorkerVersionError")
    assert "0.0.0+other" in result["status"] and not list(tmp_path.iterdir())
    good = cluster.run_bundled(bundle, blobs, FORCED_BASE, False, True,
                               cluster.worker_identity(), root=tmp_path)
    assert good["status"] == "complete" and good["run_file_bytes"][:3] == b"CDF"


def test_bundle_files_are_checked_against_their_hash(tmp_path) -> None:
    case = _table_case(tmp_path / "client")
    bundle, blobs = make_bundle([load_case(case, FORCED_BASE)])
    assert list(bundle.files) == ["case/m.csv"]
    digest = bundle.files["case/m.csv"]
    with pytest.raises(BundleError, match="SHA-256"):
        materialise(bundle, {digest: DECOY_TABLE.encode()}, tmp_path / "worker")
    folder = materialise(bundle, blobs, tmp_path / "worker")
    assert (folder / "case" / "m.csv").read_text() == TABLE


@pytest.mark.slow  # ~35 s: its own cluster, two campaigns of dynamic runs and a local one
def test_killed_worker_loses_no_finished_run_and_a_resume_completes(tmp_path,
                                                                    monkeypatch) -> None:
    client = tmp_path / "client"
    _table_case(client)
    args = _sweep_args("case/T.toml", KILL_BASE, KILL_GRID, "-o", "c.nc", "--runs-dir", "runs")
    env = {**os.environ, "PYTHONPATH": str(REPO), "MPLBACKEND": "Agg"}
    # no retry of a run whose worker died: it is recorded as failed, for the resume to run
    with _cluster(tmp_path / "cluster", allowed_failures=0) as started:
        command = [sys.executable, "-m", "floatmoor", *args, "--scheduler", started.address]
        sweep = subprocess.Popen(command, cwd=client, env=env, stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True)
        end = time.monotonic() + CAMPAIGN_TIMEOUT
        attrs = None
        while time.monotonic() < end and sweep.poll() is None:
            attrs = read_attributes(client / "c.nc")
            if attrs is not None and int(attrs["runs_complete"]) >= 1:
                break
            time.sleep(0.05)
        assert attrs is not None and sweep.poll() is None, "no run finished before the end"
        started.workers[0].send_signal(signal.SIGKILL)
        before = read_dataset(client / "c.nc")
        out, err = sweep.communicate(timeout=CAMPAIGN_TIMEOUT)
        after = read_dataset(client / "c.nc")
        done = before["status"].values == "complete"
        assert done.any() and (after["status"].values[done] == "complete").all()
        np.testing.assert_array_equal(after["fairlead_tension_max"].values[done],
                                      before["fairlead_tension_max"].values[done])
        lost = after["status"].values != "complete"
        assert sweep.returncode == (1 if lost.any() else 0), (out, err)
        for status in after["status"].values[lost]:
            assert "lost on the cluster" in status and "KilledWorker" in status
        resumed = subprocess.run(command, cwd=client, env=env, capture_output=True, text=True,
                                 timeout=CAMPAIGN_TIMEOUT)
    assert resumed.returncode == 0, resumed.stderr
    final = read_dataset(client / "c.nc")
    assert (final["status"].values == "complete").all()
    np.testing.assert_array_equal(final["compute_time_s"].values[done],
                                  before["compute_time_s"].values[done])  # not run again
    monkeypatch.chdir(client)
    local = run_campaign("case/T.toml", design_from_options(KILL_GRID), base_overrides=KILL_BASE)
    _assert_same_results(local, final)


def test_a_scheduler_without_workers_fails_before_anything_runs(tmp_path) -> None:
    out = tmp_path / "c.nc"
    with _cluster(tmp_path / "cluster", workers=0) as started:
        with pytest.raises(cluster.SchedulerError, match="has no workers"):
            run_campaign(LINDAHL_CASE, design_from_options(["motion.radius=0.1,0.2"]),
                         base_overrides=FORCED_BASE, output=out, scheduler=started.address)
    assert not out.exists()


@pytest.mark.slow  # ~15 s; compare's resume locally and the sweeps on the cluster stay default
def test_compare_runs_its_models_on_the_cluster(dask_cluster, tmp_path, monkeypatch) -> None:
    """``compare`` goes the same way: the model runs come back into the client's folder."""
    (tmp_path / "case").mkdir()
    shutil.copy(LINDAHL_CASE, tmp_path / "case" / "L.toml")
    monkeypatch.chdir(tmp_path)
    models = ["quasi-static", "quasi-dynamic"]
    # T = 1.25 s: the quasi-dynamic run is outside its model's range, warned in the client
    with pytest.warns(ModelValidityWarning, match="run quasi-dynamic"):
        assert main(["compare", "case/L.toml", "--models", ",".join(models),
                     *sum((["--set", b] for b in COMPARE_BASE), []), "-o", "report",
                     "--scheduler", dask_cluster.address, "--quiet"]) == 0
    with pytest.warns(ModelValidityWarning, match="run quasi-dynamic"):
        local = run_campaign("case/L.toml", model_design(models), base_overrides=COMPARE_BASE,
                             runs_dir="local", run_names=models)
    assert (local["status"].values == "complete").all()
    _assert_same_run_files(Path("local"), Path("report/runs"), [f"{m}.nc" for m in models])




def test_uq_study_on_the_cluster_gives_the_local_numbers(dask_cluster, tmp_path,
                                                         monkeypatch) -> None:
    """``floatmoor uq`` runs its design through the same campaign path: the study's
    statistics, Sobol indices and bands are those of a local run, bit for bit."""
    (tmp_path / "study").mkdir()
    shutil.copy(LINDAHL_CASE, tmp_path / "study" / "L.toml")
    (tmp_path / "study" / "s.toml").write_text(quick_study(), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert main(["uq", "study/s.toml", "-o", "local", "--quiet"]) == 0
    assert main(["uq", "study/s.toml", "-o", "remote", "--quiet",
                 "--scheduler", dask_cluster.address]) == 0
    local, remote = read_dataset(tmp_path / "local" / "uq.nc"), \
        read_dataset(tmp_path / "remote" / "uq.nc")
    assert float(local["tension_max_variance"]) > 0.0  # the inputs move the result
    assert sorted(local.data_vars) == sorted(remote.data_vars)
    for name in local.data_vars:
        np.testing.assert_array_equal(remote[name].values, local[name].values, err_msg=name)


def _summary_only(result, folder: Path) -> Path:
    """A study's report without its figures (a second of CPU each, drawn by the test above):
    ``summary.md`` naming its title."""
    folder.mkdir(exist_ok=True)
    (folder / "summary.md").write_text(result.study.title, encoding="utf-8")
    return folder / "summary.md"


def _assert_same_study(alone: Path, other: Path) -> None:
    """uq.nc bit for bit, and every run's results in runs.nc (not its measured times)."""
    a, b = read_dataset(alone / "uq.nc"), read_dataset(other / "uq.nc")
    assert sorted(a.data_vars) == sorted(b.data_vars)
    for name in a.data_vars:
        np.testing.assert_array_equal(b[name].values, a[name].values, err_msg=name)
    _assert_same_results(read_dataset(alone / "runs.nc"), read_dataset(other / "runs.nc"))


def test_uq_studies_together_share_the_cluster(dask_cluster, tmp_path, monkeypatch) -> None:
    """Two studies submitted together run their runs on the same workers, each into its
    own folder, with the numbers each gives alone on this machine."""
    import floatmoor.uq.run as uq_run

    monkeypatch.setattr(uq_run, "write_study_report", _summary_only)
    (tmp_path / "study").mkdir()
    shutil.copy(LINDAHL_CASE, tmp_path / "study" / "L.toml")
    (tmp_path / "study" / "s.toml").write_text(quick_study(), encoding="utf-8")
    (tmp_path / "study" / "t.toml").write_text(quick_study(33.3, 33.5), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert main(["uq", "study/s.toml", "study/t.toml", "-o", "rs", "-o", "rt", "--quiet",
                 "--scheduler", dask_cluster.address]) == 0
    for name in "st":
        assert main(["uq", f"study/{name}.toml", "-o", f"local_{name}", "--quiet"]) == 0
        _assert_same_study(tmp_path / f"local_{name}", tmp_path / f"r{name}")
    assert float(read_dataset(tmp_path / "rs" / "uq.nc")["tension_max_mean"]) != float(
        read_dataset(tmp_path / "rt" / "uq.nc")["tension_max_mean"])


#: A gPC study of dynamic runs long enough to kill a worker or the client while runs are
#: left (6 runs of ~1 s each once compiled, as KILL_BASE's), one input at order 5.
KILL_STUDY = """
title = "Lindahl chain, dynamic: uncertain length {lower} to {upper} m"
case = "L.toml"
base_overrides = ["simulation.duration=12.0"]

[[inputs]]
key = "lines.chain.length"
distribution = "uniform"
lower = {lower}
upper = {upper}

[method]
kind = "quadrature"
order = 5

[[quantities]]
name = "tension_max"
line = "chain"
statistic = "max"

[[quantities]]
name = "tension"
line = "chain"
statistic = "history"
window = [10.0, 12.0]
"""


def _kill_studies(client: Path, names: str) -> list[str]:
    """Study files ``client/study/N.toml`` of KILL_STUDY (apart in length), by name."""
    (client / "study").mkdir(parents=True)
    shutil.copy(LINDAHL_CASE, client / "study" / "L.toml")
    for k, name in enumerate(names):
        lower = 33.0 + 0.3 * k
        (client / "study" / f"{name}.toml").write_text(
            KILL_STUDY.format(lower=lower, upper=round(lower + 0.25, 2)), encoding="utf-8")
    return [f"study/{name}.toml" for name in names]


def _complete_runs(folders: list[Path]) -> int:
    """Complete runs in the runs.nc of ``folders`` (as their attributes say)."""
    found = 0
    for folder in folders:
        attrs = read_attributes(folder / "runs.nc")
        found += int(attrs["runs_complete"]) if attrs is not None else 0
    return found


def _wait_for_a_run(process: subprocess.Popen, folders: list[Path]) -> None:
    end = time.monotonic() + CAMPAIGN_TIMEOUT
    while time.monotonic() < end and process.poll() is None:
        if _complete_runs(folders) >= 1:
            break
        time.sleep(0.05)
    assert _complete_runs(folders) >= 1 and process.poll() is None, \
        "no run finished before the end"


@pytest.mark.slow  # ~25 s of CPU (85 s of wall time on the shared machine): its own
# cluster, a study of dynamic runs there and one here
def test_uq_study_survives_a_killed_worker(tmp_path, monkeypatch) -> None:
    """A worker killed mid-study: Dask runs its run again on the other worker, the study
    ends with every run and the numbers of a study run here uninterrupted."""
    client = tmp_path / "client"
    (study,) = _kill_studies(client, "k")
    env = {**os.environ, "PYTHONPATH": str(REPO), "MPLBACKEND": "Agg"}
    with _cluster(tmp_path / "cluster") as started:
        command = [sys.executable, "-m", "floatmoor", "uq", study, "-o", "remote", "--quiet",
                   "--scheduler", started.address]
        process = subprocess.Popen(command, cwd=client, env=env, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True)
        _wait_for_a_run(process, [client / "remote"])
        before = read_dataset(client / "remote" / "runs.nc")
        started.workers[0].send_signal(signal.SIGKILL)
        out, err = process.communicate(timeout=CAMPAIGN_TIMEOUT)
    assert process.returncode == 0, (out, err)
    after = read_dataset(client / "remote" / "runs.nc")
    assert (after["status"].values == "complete").all()
    done = before["status"].values == "complete"
    assert not done.all(), "the worker was killed after the last run"
    np.testing.assert_array_equal(after["compute_time_s"].values[done],
                                  before["compute_time_s"].values[done])  # kept, not rerun
    monkeypatch.chdir(client)
    assert main(["uq", study, "-o", "local", "--quiet"]) == 0
    _assert_same_study(client / "local", client / "remote")


@pytest.mark.slow  # ~40 s of CPU (165 s of wall time on the shared machine): its own
# cluster, two studies of dynamic runs there and here
def test_killed_uq_client_loses_no_finished_run_and_a_rerun_resumes(tmp_path,
                                                                   monkeypatch) -> None:
    """``floatmoor uq`` of two studies killed (SIGKILL) while their runs go on the cluster:
    the runs that finished are in the studies' runs.nc, their folders stay the command's,
    and the same command resumes them (running only the others) to the numbers of studies
    run here uninterrupted."""
    client = tmp_path / "client"
    studies = _kill_studies(client, "pq")
    outputs = [client / "rp", client / "rq"]
    env = {**os.environ, "PYTHONPATH": str(REPO), "MPLBACKEND": "Agg"}
    with _cluster(tmp_path / "cluster") as started:
        command = [sys.executable, "-m", "floatmoor", "uq", *studies, "-o", "rp", "-o", "rq",
                   "--quiet", "--scheduler", started.address]
        process = subprocess.Popen(command, cwd=client, env=env, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True)
        _wait_for_a_run(process, outputs)
        process.kill()
        process.communicate(timeout=CAMPAIGN_TIMEOUT)
        before = {o.name: read_dataset(o / "runs.nc") for o in outputs
                  if (o / "runs.nc").is_file()}
        held = sum(int((ds["status"].values == "complete").sum()) for ds in before.values())
        assert 1 <= held < 12, held  # some finished runs kept, some left to run
        resumed = subprocess.run(command, cwd=client, env=env, capture_output=True,
                                 text=True, timeout=CAMPAIGN_TIMEOUT)
    assert resumed.returncode == 0, resumed.stderr
    for name, ds in before.items():
        done = ds["status"].values == "complete"
        after = read_dataset(client / name / "runs.nc")
        np.testing.assert_array_equal(after["compute_time_s"].values[done],
                                      ds["compute_time_s"].values[done])  # not run again
    monkeypatch.chdir(client)
    for study, output in zip(studies, outputs):
        local = client / f"local_{output.name}"
        assert main(["uq", study, "-o", local.name, "--quiet"]) == 0
        _assert_same_study(local, output)
