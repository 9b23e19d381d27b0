"""Several studies submitted together (``floatmoor uq A.toml B.toml C.toml -o A -o B -o C``,
docs/guide/uncertainty.md#several-studies-on-the-same-workers): their runs are one pool of
jobs taken in turn from each study, so no worker waits for a study to end while another has
runs left; each study keeps its own folder (runs.nc, uq.nc, surrogates, report) with the
numbers it gives alone, bit for bit; one count and one estimate for all, and a line per study
when its runs are done; a failed run fails its study only (exit 1 naming the study and the
run) and the other studies' results are written; Ctrl-C keeps every study's finished runs
and a killed submission leaves folders the same command resumes.

The studies are quick: the Lindahl chain on quasi-static lines, 4 runs of 5 s each
(milliseconds); the report's figures (a second of CPU per study, tested with single
studies) are left out: each report is its summary alone."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

import floatmoor.campaign.runner as runner
import floatmoor.uq.run as uq_run
from floatmoor.cli import main
from floatmoor.io.netcdf import read_dataset
from tests.conftest import LINDAHL_CASE
from tests.uq.lindahl_studies import quick_study

#: (name, chain length range) of the three studies: apart, so a run's length names its study.
RANGES = {"a": (32.9, 33.0), "b": (33.1, 33.2), "c": (32.7, 32.8)}
#: Runs of each study (2 x 2 Gauss nodes).
RUNS = 4
#: Variables of runs.nc that hold a run's measured times, not its results.
TIMES = ("compute_time_s", "wall_time_s")


def _summary_only(result, folder: Path) -> Path:
    """The study's report without its figures: ``summary.md`` naming its title."""
    folder.mkdir(exist_ok=True)
    (folder / "summary.md").write_text(result.study.title, encoding="utf-8")
    return folder / "summary.md"


@pytest.fixture
def studies(tmp_path, monkeypatch) -> dict[str, str]:
    """The three study files by name, in ``tmp_path/study`` with their case (the working
    folder ``tmp_path``); reports without figures."""
    monkeypatch.setattr(uq_run, "write_study_report", _summary_only)
    folder = tmp_path / "study"
    folder.mkdir()
    shutil.copy(LINDAHL_CASE, folder / "L.toml")
    for name, (lower, upper) in RANGES.items():
        (folder / f"{name}.toml").write_text(quick_study(lower, upper),
                                             encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return {name: f"study/{name}.toml" for name in RANGES}


def _together(studies: dict[str, str], *rest: str) -> list[str]:
    outputs = sum((["-o", f"together_{name}"] for name in studies), [])
    return ["uq", *studies.values(), *outputs, *rest]


def _assert_same_study(alone: Path, together: Path) -> None:
    """uq.nc bit for bit, and every run's results in runs.nc (not its measured times)."""
    a, b = read_dataset(alone / "uq.nc"), read_dataset(together / "uq.nc")
    assert sorted(a.data_vars) == sorted(b.data_vars)
    for name in a.data_vars:
        np.testing.assert_array_equal(b[name].values, a[name].values, err_msg=name)
    a, b = read_dataset(alone / "runs.nc"), read_dataset(together / "runs.nc")
    assert sorted(a.data_vars) == sorted(b.data_vars)
    for name in a.data_vars:
        if name not in TIMES:
            np.testing.assert_array_equal(b[name].values, a[name].values, err_msg=name)
    assert sorted(os.listdir(alone)) == sorted(os.listdir(together))


def test_studies_share_one_pool_and_give_their_numbers_alone(studies, capsys,
                                                              monkeypatch) -> None:
    calls: list[str] = []
    original = runner.run_one

    def run_one(case_path, overrides, timeseries=False, run_file=None):
        length = float(next(o for o in overrides if o.startswith("lines.chain.length="))
                       .split("=")[1])
        calls.extend(n for n, (lower, upper) in RANGES.items() if lower < length < upper)
        return original(case_path, overrides, timeseries, run_file)

    monkeypatch.setattr(runner, "run_one", run_one)
    assert main(_together(studies)) == 0
    err = capsys.readouterr().err.splitlines()
    assert calls == ["a", "b", "c"] * RUNS  # one pool taken in turn
    # one count and one estimate for all, then each study when its runs are done
    assert err[0] == ("floatmoor: 12 runs of 3 studies on 1 local worker; the wall-time "
                      "estimate follows the first finished run")
    assert sum("estimated wall time to finish" in line for line in err) == 1
    ends = [k for k, line in enumerate(err) if "runs done, 0 failed" in line]
    assert [err[k] for k in ends] == [f"floatmoor: study {studies[n]}: all {RUNS} runs done, "
                                      "0 failed" for n in "abc"]
    assert [err[k - 1].split(",")[0] for k in ends] == [
        f"floatmoor: {n} / 12 runs done" for n in (10, 11, 12)]
    for name, study in studies.items():
        assert main(["uq", study, "-o", f"alone_{name}", "--quiet"]) == 0
        _assert_same_study(Path(f"alone_{name}"), Path(f"together_{name}"))
    a, b = read_dataset(Path("together_a/uq.nc")), read_dataset(Path("together_b/uq.nc"))
    assert float(a["tension_max_mean"]) != float(b["tension_max_mean"])  # not one study


@pytest.mark.slow  # ~7 s of CPU, 15 s of wall time: two worker processes start and import
def test_local_workers_take_the_studies_runs_from_one_pool(studies, capsys) -> None:
    """On two local workers the jobs start in turn (a, b, c, a, ...): study a's last run is
    the 10th of 12, started once 8 others finished, so a ends with at least 9 runs done
    in all (4 if the studies ran one after the other), b with at least 10."""
    assert main(_together(studies, "--workers", "2")) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("floatmoor: 12 runs of 3 studies on 2 local workers;")
    done_at = {}
    for k, line in enumerate(err):
        for name, study in studies.items():
            if line == f"floatmoor: study {study}: all {RUNS} runs done, 0 failed":
                counts = [int(e.split()[1]) for e in err[:k] if " / 12 runs done" in e]
                done_at[name] = counts[-1]
    assert done_at["a"] >= 9 and done_at["b"] >= 10 and done_at["c"] == 12, err
    for name, study in studies.items():
        assert main(["uq", study, "-o", f"alone_{name}", "--quiet"]) == 0
        _assert_same_study(Path(f"alone_{name}"), Path(f"together_{name}"))


def test_a_failed_run_fails_its_study_only(studies, capsys, monkeypatch) -> None:
    original = runner.run_one
    failing: list[list[str]] = []

    def run_one(case_path, overrides, timeseries=False, run_file=None):
        if any(o.startswith("lines.chain.length=33.17") for o in overrides) and not failing:
            failing.append(list(overrides))  # b's upper node, once
            return {"status": "failed: SolverError: diverged (test)", "statistics": {},
                    "compute_time_s": 0.0, "wall_time_s": 0.0, "compile_time_s": 0.0}
        return original(case_path, overrides, timeseries, run_file)

    monkeypatch.setattr(runner, "run_one", run_one)
    assert main(_together(studies, "--quiet")) == 1
    captured = capsys.readouterr()
    (bad,) = [o for o in failing[0] if o.startswith("lines.chain.length=")]
    assert f"floatmoor: uq {studies['b']} failed: 1 of 4 runs failed (" in captured.err
    assert bad in captured.err and "diverged (test)" in captured.err
    assert studies["a"] not in captured.err and studies["c"] not in captured.err
    assert f"{studies['b']}: 3 of 4 runs complete" in captured.out
    for name in "ac":  # the other studies are written whole
        assert (Path(f"together_{name}") / "uq.nc").is_file()
        assert (Path(f"together_{name}") / "report" / "summary.md").is_file()
    b = Path("together_b")
    assert (b / "runs.nc").is_file() and not (b / "uq.nc").exists()
    status = read_dataset(b / "runs.nc")["status"].values
    assert list(status).count("complete") == 3
    # re-running resumes: only b's failed run is run again, and b is written
    monkeypatch.setattr(runner, "run_one", original)
    calls: list[list[str]] = []
    monkeypatch.setattr(runner, "run_one", lambda *a, **k: calls.append(a[1]) or original(
        *a, **k))
    assert main(_together(studies, "--quiet")) == 0
    assert calls == [failing[0]] and (b / "uq.nc").is_file()


class _Killed(BaseException):
    """Stops the command as SIGKILL does: nothing catches it."""


def test_a_killed_submission_keeps_its_runs_and_resumes(studies, monkeypatch) -> None:
    """Killed after 5 of its 12 runs (no clean-up: the folders are left as a SIGKILL leaves
    them), the studies' folders hold those runs and are still the command's: the same
    command resumes them, running the 7 others only."""
    from floatmoor.io.output_folders import OwnedFolder

    original = runner.run_one
    calls: list[list[str]] = []

    def run_one(case_path, overrides, timeseries=False, run_file=None):
        if len(calls) == 5:
            raise _Killed
        calls.append(overrides)
        return original(case_path, overrides, timeseries, run_file)

    with monkeypatch.context() as killed:
        killed.setattr(runner, "run_one", run_one)
        killed.setattr(OwnedFolder, "__exit__", lambda self, *exc: None)  # no clean-up
        with pytest.raises(_Killed):
            main(_together(studies, "--quiet"))
    held = sum(int(read_dataset(Path(f"together_{name}") / "runs.nc").attrs["runs_complete"])
               for name in studies)
    assert held == 5
    monkeypatch.setattr(runner, "run_one", lambda *a, **k: calls.append(a[1]) or original(
        *a, **k))
    assert main(_together(studies, "--quiet")) == 0
    assert len(calls) == 12 and len({tuple(c) for c in calls}) == 12  # none run twice
    for name in studies:
        assert (Path(f"together_{name}") / "uq.nc").is_file()


def test_ctrl_c_says_where_every_studys_finished_runs_are(studies, capsys,
                                                          monkeypatch) -> None:
    original = runner.run_one
    calls: list[list[str]] = []

    def run_one(case_path, overrides, timeseries=False, run_file=None):
        if len(calls) == 4:  # a, b, c and a's second run done
            raise KeyboardInterrupt
        calls.append(overrides)
        return original(case_path, overrides, timeseries, run_file)

    monkeypatch.setattr(runner, "run_one", run_one)
    assert main(_together(studies, "--quiet")) == 130
    err = capsys.readouterr().err
    assert err == ("floatmoor: interrupted; the finished runs are in together_a/runs.nc, "
                   "together_b/runs.nc, together_c/runs.nc (re-run the same command to "
                   "resume)\n")
    held = [int(read_dataset(Path(f"together_{n}") / "runs.nc").attrs["runs_complete"])
            for n in studies]
    assert held == [2, 1, 1]


@pytest.mark.parametrize("outputs, expected", [
    (["-o", "x"], "one output folder per study (3, in the order of the study files), found 1"),
    (["-o", "x", "-o", "y", "-o", "x"], "a folder of its own for each study"),
    (["-o", "x", "-o", "x/y", "-o", "z"], "a folder of its own for each study"),
])
def test_output_folders_are_one_per_study(studies, capsys, outputs, expected) -> None:
    Path("x").mkdir()
    assert main(["uq", *studies.values(), *outputs, "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("floatmoor: error: ") and "-o/--output" in err and expected in err
    assert err.count("\n") == 1 and not os.listdir("x")
    assert not any(Path(p).exists() for p in ("y", "z"))
