"""``floatmoor run`` on a floater case: a coupled run, its summary and output; ``--resume``."""

from __future__ import annotations

from floatmoor.cli import main
from floatmoor.io.netcdf import read_dataset
from tests.conftest import CASES, LINDAHL_CASE

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
SHORT = ["--set", "simulation.duration=1.0", "--set", "simulation.output_interval=0.02",
         "--set", 'lines.*.model="quasi-static"']


def test_run_floater_case_writes_body_motions(tmp_path, capsys) -> None:
    out = tmp_path / "buoy.nc"
    status = main(["run", str(BUOY_CASE), "-o", str(out), "--quiet", "--set",
                   'waves={kind = "regular", height = 0.04, period = 1.2}'] + SHORT)
    printed = capsys.readouterr().out
    assert status == 0
    assert "floater displacement" in printed and "Heave" in printed
    ds = read_dataset(out)
    assert ds.attrs["status"] == "complete" and "body_displacement" in ds


def test_resume_needs_a_checkpoint_and_a_floater(tmp_path, capsys) -> None:
    out = tmp_path / "buoy.nc"
    assert main(["run", str(BUOY_CASE), "-o", str(out), "--quiet", "--resume"] + SHORT) == 2
    err = capsys.readouterr().err
    assert "no checkpoint" in err and "partial results" not in err and not out.exists()
    assert main(["run", str(LINDAHL_CASE), "-o", str(tmp_path / "l.nc"), "--resume"]) == 2
    assert "--resume" in capsys.readouterr().err


def test_run_refuses_a_stale_database(tmp_path, capsys) -> None:
    """A floater case whose hydro inputs differ from the database's is bad input (status 2,
    one message naming what differs, nothing written)."""
    out = tmp_path / "stale.nc"
    status = main(["run", str(BUOY_CASE), "-o", str(out), "--quiet",
                   "--set", "hydro.panel_size=0.01"] + SHORT)
    err = capsys.readouterr().err
    assert status == 2 and "stale" in err and "Traceback" not in err
    assert not out.exists()


def test_run_refuses_a_database_failing_its_checks_unless_the_case_accepts(tmp_path, capsys
                                                                          ) -> None:
    """A database that fails ``hydro check`` is bad input for a run (status 2, one message
    naming the database, the check with its value and tolerance and how to accept it, nothing
    written); accepted by the case, the run goes on with one warning line."""
    from floatmoor.hydro.database import read_database, write_database

    (tmp_path / "hydrodb").mkdir()
    bad = read_database(CASES.parent / "hydrodb" / "cylinder_buoy.nc")
    bad["excitation_force"] = bad["excitation_force"] * 1.2
    bad.attrs.pop("path")
    database = tmp_path / "hydrodb" / "cylinder_buoy.nc"
    write_database(bad, database)
    case = tmp_path / "buoy.toml"
    case.write_text(BUOY_CASE.read_text())
    out = tmp_path / "run.nc"
    assert main(["run", str(case), "-o", str(out), "--quiet"] + SHORT) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(
        f"floatmoor: error: {database}: hydrodynamic database fails its checks: haskind "
        "(worst 0.441, tolerance 0.05)")
    assert 'accept_failed_checks = ["haskind"]' in err[0] and not out.exists()
    status = main(["run", str(case), "-o", str(out), "--quiet", "--set",
                   'hydro.accept_failed_checks=["haskind"]'] + SHORT)
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 0 and read_dataset(out).attrs["status"] == "complete"
    assert len(err) == 1 and err[0].startswith(f"floatmoor: warning: {database}: failed "
                                               "checks accepted by")


def test_interrupted_run_says_how_to_resume_and_the_command_does(tmp_path, capsys,
                                                                  monkeypatch) -> None:
    """Ctrl-C a second into a floater run: exit 130, a checkpoint, and a message giving the
    command that resumes it; that command completes the run to the uninterrupted results."""
    import shlex

    from tests.simulation.interrupted import interrupt_at_body_step

    waves = ["--set", 'waves={kind = "regular", height = 0.04, period = 1.2}']
    whole = tmp_path / "whole.nc"
    assert main(["run", str(BUOY_CASE), "-o", str(whole), "--quiet"] + waves + SHORT) == 0
    out = tmp_path / "cut.nc"
    with monkeypatch.context() as patch:
        interrupt_at_body_step(patch, 30)
        assert main(["run", str(BUOY_CASE), "-o", str(out)] + waves + SHORT) == 130
    err = capsys.readouterr().err
    assert f"checkpoint written to {out}.checkpoint" in err and "Traceback" not in err
    command = shlex.split(err.split("continue with: ", 1)[1].strip())
    assert command[:2] == ["floatmoor", "run"] and "--resume" in command
    assert main(command[1:] + ["--quiet"]) == 0
    resumed, reference = read_dataset(out), read_dataset(whole)
    assert resumed.attrs["status"] == "complete"
    for name in ("body_displacement", "fairlead_tension"):
        assert (resumed[name].values == reference[name].values).all(), name
