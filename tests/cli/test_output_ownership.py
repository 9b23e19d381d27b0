"""A command writes only files (and folders) of its own kind (docs/guide/safeguards.md#output-files):
``scale -o`` replaces only a case file, ``run -o`` only a run result, ``hydro build -o`` only
a database; a report, compare, uq, vtk or study folder is new, empty or the same command's;
a failure (too short runs, a disk that fills) leaves nothing of this invocation; lock files
and checkpoint temporaries are never followed through links; ``import``/``export moordyn``
make the same checks as the other commands."""

from __future__ import annotations

import errno
import json
import os
import shutil

import pytest

from floatmoor.cli import main
from floatmoor.io.output_files import OutputWriteError, lock_path
from floatmoor.io.output_folders import MANIFEST_NAME, OwnedFolder
from floatmoor.io.output_kinds import HYDRO_DATABASE, RUN_RESULT, netcdf_content
from tests.cli.test_output_files import QS, SHORT, tmpfs  # noqa: F401 (a fixture)
from tests.conftest import LINDAHL_CASE, REPO

#: A run whose window (ramp 2.5 s, then two periods of 1.25 s) a report can analyse.
REPORTABLE = ["--set", "simulation.duration=5.0", *QS]
DATABASE = REPO / "hydrodb" / "cylinder_buoy.nc"


@pytest.fixture
def case(tmp_path):
    path = tmp_path / "L.toml"
    shutil.copy(LINDAHL_CASE, path)
    return path


@pytest.fixture(scope="module")
def run_file(tmp_path_factory):
    """A short run's result file (read, never written, by the tests)."""
    folder = tmp_path_factory.mktemp("run")
    case = folder / "L.toml"
    shutil.copy(LINDAHL_CASE, case)
    out = folder / "r.nc"
    assert main(["run", str(case), *REPORTABLE, "-o", str(out), "--quiet"]) == 0
    return out


def _refused(capsys, *found: str) -> str:
    err = capsys.readouterr().err
    assert err.startswith("floatmoor: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err and all(f in err for f in found), err
    return err


# -- item 1: scale -o replaces only a case file ------------------------------------------------
def test_scale_replaces_only_a_case_file(case, tmp_path, run_file, capsys):
    notes, table = tmp_path / "notes.txt", tmp_path / "table.csv"
    notes.write_text("my notes\n")
    table.write_text("t,x\n0,1\n")
    study = tmp_path / "study.toml"
    shutil.copy(REPO / "cases" / "uq" / "lindahl_T1.25_cdn.toml", study)
    db = tmp_path / "cylinder_buoy.nc"
    shutil.copy(DATABASE, db)
    found = {notes: "which is not a TOML file", table: "which is not a TOML file",
             db: "which is not a TOML file", run_file: "which is not a TOML file",
             study: "a TOML file that is not a floatmoor case"}
    for target, what in found.items():
        before = target.read_bytes()
        assert main(["scale", str(case), "--length-scale", "2", "-o", str(target)]) == 2
        _refused(capsys, "expected a new file or a case file to replace", what)
        assert target.read_bytes() == before
    scaled = tmp_path / "L2.toml"
    shutil.copy(case, scaled)  # a case file: replaced, and said so
    assert main(["scale", str(case), "--length-scale", "2", "-o", str(scaled)]) == 0
    assert f"replacing the existing {scaled}" in capsys.readouterr().err
    assert scaled.read_text() != case.read_text()


# -- item 2: netCDF outputs replace only their own kind ------------------------------------
def test_run_and_hydro_build_replace_only_their_own_kind(case, tmp_path, run_file, capsys):
    from tests.hydro.test_cli_hydro import TINY_CASE

    db = tmp_path / "db.nc"
    shutil.copy(DATABASE, db)
    assert netcdf_content(db) == HYDRO_DATABASE and netcdf_content(run_file) == RUN_RESULT
    before = db.read_bytes()
    assert main(["run", str(case), *SHORT, "-o", str(db), "--quiet"]) == 2
    _refused(capsys, "expected a new file or a run result to replace",
             f"'{db}', a floatmoor hydrodynamic database")
    assert db.read_bytes() == before
    tiny = tmp_path / "tiny.toml"
    tiny.write_text(TINY_CASE)
    result = tmp_path / "run.nc"
    shutil.copy(run_file, result)
    before = result.read_bytes()
    assert main(["hydro", "build", str(tiny), "--force", "-o", str(result), "--quiet"]) == 2
    _refused(capsys, "expected a new file or a hydrodynamic database to replace",
             f"'{result}', a floatmoor run result")
    assert result.read_bytes() == before
    # a netCDF file floatmoor did not write is not replaced either
    from floatmoor.io.netcdf import write_dataset
    import xarray as xr

    foreign = tmp_path / "foreign.nc"
    write_dataset(xr.Dataset(attrs={"title": "someone else's"}), foreign)
    assert main(["run", str(case), *SHORT, "-o", str(foreign), "--quiet"]) == 2
    _refused(capsys, "a netCDF file floatmoor did not write")


# -- item 2: output folders are new, empty or the command's own ----------------------------
def test_report_writes_only_into_its_own_folder(run_file, tmp_path, capsys, monkeypatch):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "summary.md").write_text("my summary\n")
    (mine / "tension_psd.png").write_bytes(b"\x89PNG\r\n\x1a\n my figure")
    for out in (mine, tmp_path, REPO / "hydrodb"):
        assert main(["report", str(run_file), "-o", str(out)]) == 2
        _refused(capsys, "expected a new or empty folder, or one that floatmoor report wrote",
                 "did not write")
    assert (mine / "summary.md").read_text() == "my summary\n"
    assert (mine / "tension_psd.png").read_bytes() == b"\x89PNG\r\n\x1a\n my figure"
    monkeypatch.chdir(tmp_path)
    assert main(["report", str(run_file), "-o", "."]) == 2
    _refused(capsys, "found '.', which holds")
    # a new folder: written with its manifest; written again; refused once it holds another file
    out = tmp_path / "rep"
    assert main(["report", str(run_file), "-o", str(out)]) == 0
    manifest = json.loads((out / MANIFEST_NAME).read_text())
    assert manifest["command"] == "report" and "summary.md" in manifest["files"]
    assert main(["report", str(run_file), "-o", str(out)]) == 0
    (out / "notes.md").write_text("mine\n")
    assert main(["report", str(run_file), "-o", str(out)]) == 2
    _refused(capsys, "(e.g. 'notes.md')")
    # another command's folder is not the report's
    (out / "notes.md").unlink()
    assert main(["vtk", str(run_file), "-o", str(out)]) == 2
    _refused(capsys, "one that floatmoor vtk wrote")


def test_uq_study_vtk_and_run_vtk_refuse_folders_they_did_not_write(case, tmp_path, capsys):
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "uq.nc").write_bytes(b"CDF\x02 a user's results")
    study = REPO / "cases" / "uq" / "lindahl_T1.25_cdn.toml"
    commands = {"uq": ["uq", str(study), "--quiet"],
                "study qd-verification": ["study", "qd-verification", "--quick", "--quiet"],
                "vtk": ["vtk", str(tmp_path / "missing.nc")]}
    for name, command in commands.items():
        assert main([*command, "-o", str(folder)]) == 2, name
        _refused(capsys, f"one that floatmoor {name} wrote", "(e.g. 'uq.nc')")
    assert main(["run", str(case), *SHORT, "--set", "simulation.shape_output_interval=0.5",
                 "-o", str(tmp_path / "r.nc"), "--vtk", str(folder), "--quiet"]) == 2
    _refused(capsys, "--vtk: expected a new or empty folder")
    assert os.listdir(folder) == ["uq.nc"] and not (tmp_path / "r.nc").exists()


# -- item 3: nothing left by a failure -------------------------------------------------------
def test_compare_of_runs_too_short_for_the_report_is_refused_before_running(case, tmp_path,
                                                                          capsys, monkeypatch):
    import floatmoor.report.compare as compare

    monkeypatch.setattr(compare, "run_campaign", lambda *a, **k: pytest.fail("ran"))
    out = tmp_path / "cmp"
    assert main(["compare", str(case), "--models", "quasi-static", "--set",
                 "simulation.duration=3.0", "-o", str(out), "--quiet"]) == 2
    _refused(capsys, "simulation.duration: expected runs of at least 5 s for the report "
             "(2 periods of 1.25 s after the window start 2.5 s (motion ramp)), found 3 s")
    assert not out.exists()
    assert main(["compare", str(case), "--models", "quasi-static", "--start", "4", "--set",
                 "simulation.duration=5.0", "-o", str(out), "--quiet"]) == 2
    _refused(capsys, "at least 6.5 s", "(--start)")


def test_compare_failing_after_its_runs_leaves_nothing(case, tmp_path, capsys, monkeypatch):
    import floatmoor.report.compare as compare
    from floatmoor.report.figures import FigureDataError

    def unplottable(*args, **kwargs):
        raise FigureDataError("tension maxima exceedance: expected a non-empty series")

    monkeypatch.setattr(compare, "write_report", unplottable)
    out = tmp_path / "cmp"
    assert main(["compare", str(case), "--models", "quasi-static", "--set",
                 "simulation.duration=5.0", "-o", str(out), "--quiet"]) == 2
    _refused(capsys, "expected a non-empty series")
    assert not out.exists()  # status 2: the runs it made are gone too


def _disk_full(monkeypatch):
    import matplotlib.figure

    def full(self, path, *args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", full)


def test_report_and_compare_on_a_full_disk_fail_in_one_line_leaving_nothing(
        case, run_file, tmp_path, capsys, monkeypatch):
    _disk_full(monkeypatch)
    out = tmp_path / "rep"
    assert main(["report", str(run_file), "-o", str(out)]) == 1
    err = capsys.readouterr().err
    assert err == (f"floatmoor: report failed: cannot write {out / 'tension_timeseries.png'}: "
                   "No space left on device; nothing written\n")
    assert not out.exists() and os.listdir(tmp_path) == ["L.toml"]
    cmp = tmp_path / "cmp"
    assert main(["compare", str(case), "--models", "quasi-static", "--set",
                 "simulation.duration=5.0", "-o", str(cmp), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "No space left on device" in err and "Traceback" not in err
    assert not cmp.exists()


def test_uq_and_vtk_on_a_full_disk_remove_what_they_wrote(tmp_path, capsys, monkeypatch):
    import floatmoor.cli.plots as plots_cli
    import floatmoor.uq.run as uq_run

    folder = tmp_path / "uq"

    def prepared(study, folder, **kwargs):  # no case checked, no runs.nc resumed
        folder.mkdir(exist_ok=True)
        return uq_run.PreparedStudy(study, folder, None, None, None)

    def runs_done(studies, **kwargs):
        (studies[0].folder / "runs.nc").write_bytes(b"CDF\x02 runs")

    def full_study(prepared):
        (prepared.folder / "report").mkdir()
        (prepared.folder / "report" / "summary.md").write_text("half")
        raise OutputWriteError(f"cannot write {folder / 'uq.nc'}: No space left on device")

    monkeypatch.setattr(uq_run, "prepare_study", prepared)
    monkeypatch.setattr(uq_run, "run_studies", runs_done)
    monkeypatch.setattr(uq_run, "finish_study", full_study)
    study = REPO / "cases" / "uq" / "lindahl_T1.25_cdn.toml"
    assert main(["uq", str(study), "-o", str(folder), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "uq failed: cannot write" in err and "the finished runs are in" in err
    assert sorted(os.listdir(folder)) == [MANIFEST_NAME, "runs.nc"]  # resumable runs kept
    assert main(["uq", str(study), "-o", str(folder), "--quiet"]) == 1  # its own: accepted
    capsys.readouterr()

    def full_vtk(dataset, folder, samples, quiet):
        folder.mkdir(exist_ok=True)
        (folder / "line_shapes_000000.vtu").write_text("<VTKFile/>")
        raise OutputWriteError(f"cannot write {folder / 'x.vtu'}: No space left on device")

    monkeypatch.setattr(plots_cli, "_window", lambda args: (None, [0]))
    monkeypatch.setattr(plots_cli, "write_vtk", full_vtk)
    out = tmp_path / "vtk"
    assert main(["vtk", "run.nc", "-o", str(out)]) == 1
    assert "the files it wrote were removed" in capsys.readouterr().err
    assert not out.exists()


def test_owned_folder_keeps_files_it_did_not_write(tmp_path):
    folder = tmp_path / "out"
    with OwnedFolder(folder, "report"):
        folder.mkdir()
        (folder / "a.png").write_text("a")
    (folder / "moved").write_text("old")
    inode = (folder / "moved").stat().st_ino
    with pytest.raises(OutputWriteError):
        with OwnedFolder(folder, "report"):
            (folder / "a.png").write_text("a again")  # replaced: kept, whole
            os.rename(folder / "moved", folder / "moved.bak-1")  # moved aside: not new
            (folder / "b.png").write_text("b")
            raise OutputWriteError("disk full")
    assert sorted(os.listdir(folder)) == [MANIFEST_NAME, "a.png", "moved.bak-1"]
    assert (folder / "moved.bak-1").stat().st_ino == inode
    empty = tmp_path / "empty"  # a user's empty folder stays empty after a failure
    empty.mkdir()
    with pytest.raises(OutputWriteError):
        with OwnedFolder(empty, "vtk"):
            (empty / "x.vtu").write_text("x")
            raise OutputWriteError("disk full")
    assert os.listdir(empty) == []


# -- item 6: lock files and checkpoint temporaries are not followed --------------------------
def test_a_link_at_the_lock_path_is_not_followed(case, tmp_path, capsys):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    out = tmp_path / "r.nc"
    lock_path(out).symlink_to(victim)
    assert main(["run", str(case), *SHORT, "-o", str(out), "--quiet"]) == 2
    _refused(capsys, "a symbolic link")
    lock_path(out).unlink()
    os.link(victim, lock_path(out))  # a second name of the victim
    assert main(["run", str(case), *SHORT, "-o", str(out), "--quiet"]) == 2
    _refused(capsys, "a file with 2 names (hard links)")
    assert victim.read_text() == "precious\n" and not out.exists()
    lock_path(out).unlink()
    os.mkfifo(lock_path(out))
    assert main(["run", str(case), *SHORT, "-o", str(out), "--quiet"]) == 2
    _refused(capsys, "a FIFO")


def test_checkpoint_write_does_not_follow_a_link_beside_it(tmp_path):
    import numpy as np

    from floatmoor.simulation import checkpoint as ck

    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    path = tmp_path / "r.nc.checkpoint"
    (tmp_path / "r.nc.checkpoint.tmp").symlink_to(victim)
    identity = ck.RunIdentity.of("title = 'a'\n", [], "settings", "case.toml")
    ck.write_checkpoint(path, {"state/x": np.zeros(3)}, identity)
    assert victim.read_text() == "precious\n" and path.is_file()


def test_a_floater_run_replaces_only_a_checkpoint_beside_its_output(tmp_path, capsys):
    buoy = REPO / "cases" / "cylinder_buoy" / "buoy_regular_T1.00.toml"
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    out = tmp_path / "r.nc"
    ckpt = tmp_path / "r.nc.checkpoint"
    ckpt.symlink_to(victim)
    assert main(["run", str(buoy), "-o", str(out), "--quiet"]) == 2
    _refused(capsys, f"'{ckpt}', a symbolic link")
    ckpt.unlink()
    shutil.copy(victim, ckpt)
    assert main(["run", str(buoy), "-o", str(out), "--quiet"]) == 2
    _refused(capsys, "which is not a checkpoint file")
    assert victim.read_text() == "precious\n" and not out.exists()


# -- item 16: import / export moordyn make the common output checks --------------------------
def test_moordyn_outputs_get_the_common_checks(tmp_path, tmpfs, capsys):  # noqa: F811
    deck = REPO / "tests" / "data" / "moordyn" / "wd0050_chain.txt"
    read_only = tmpfs("ro", "ro,size=1m")
    small = tmpfs("small", "size=16k")
    for folder, found in ((read_only, "Read-only file system"), (small, "free in")):
        for command in (["import", "moordyn", str(deck), "-o", str(folder / "c.toml")],
                        ["export", "moordyn", str(LINDAHL_CASE), "-o", str(folder / "d.dat")]):
            assert main(command) == 2, command
            _refused(capsys, "-o/--output: expected", found)
        assert os.listdir(folder) == []


def test_sweep_runs_dir_replaces_only_run_results(case, tmp_path, capsys, monkeypatch):
    import floatmoor.campaign.runner as runner

    runs = tmp_path / "runs"
    runs.mkdir()
    mine = runs / "motion.period=1.5.nc"
    mine.write_bytes(b"CDF\x02 a user's file of the same name")
    monkeypatch.setattr(runner, "run_one", lambda *a: pytest.fail("ran"))
    assert main(["sweep", str(case), *SHORT, "--grid", "motion.period=1.25,1.5", "-o",
                 str(tmp_path / "c.nc"), "--runs-dir", str(runs), "--quiet"]) == 2
    _refused(capsys, "--runs-dir: expected a new file or a run result to replace",
             "a netCDF file floatmoor cannot read")
    assert mine.read_bytes() == b"CDF\x02 a user's file of the same name"
    assert not (tmp_path / "c.nc").exists()
