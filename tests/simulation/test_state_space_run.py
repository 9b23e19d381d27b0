"""Coupled runs with ``[floater] radiation = "state-space"``: the case loads and runs, an
interrupted run resumes to bit-identical results (the radiation states are in the checkpoint),
and the bad-value and missing-realisation errors (exit status 2, nothing written)."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from floatmoor.hydro.database import read_database, write_database
from floatmoor.hydro.state_space import fit as state_space_fit
from floatmoor.hydro.state_space.storage import read_state_space, remove_from_dataset
from floatmoor.io.netcdf import read_dataset
from floatmoor.simulation.coupled_run import run_coupled
from tests.simulation.interrupted import interrupt_run
from tests.conftest import CASES, REPO

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
STATE_SPACE = 'floater.radiation="state-space"'


def test_state_space_case_runs_and_resumes_bit_identically(tmp_path, monkeypatch) -> None:
    """As tests/simulation/test_coupled_run.py::test_interrupted_run_resumes_to_identical_results,
    on the state-space path: a quasi-dynamic line and the radiation states both carry
    memory across the checkpoint."""
    import floatmoor.simulation.coupled_run as cr

    monkeypatch.setattr(cr, "CHUNK_STEPS", 40)
    overrides = [STATE_SPACE, 'lines.*.model="quasi-static"',
                 'lines.line1.model="quasi-dynamic"', "simulation.duration=3.0",
                 "simulation.output_interval=0.02", "simulation.time_step=0.01",
                 'waves={kind = "regular", height = 0.04, period = 1.2}']
    case = load_case(BUOY_CASE, overrides)
    assert case.floater.radiation == "state-space"
    whole = run_coupled(case, output=tmp_path / "whole.nc").dataset
    assert whole.attrs["status"] == "complete"
    heave = whole["body_displacement"].sel(dof="Heave").values
    assert np.all(np.isfinite(heave)) and np.ptp(heave[whole["time"].values > 2.0]) > 0.01
    out = tmp_path / "cut.nc"
    interrupt_run(case, out)
    assert cr.checkpoint_path(out).is_file()
    resumed = run_coupled(case, output=out, resume=True).dataset
    for name in ("body_displacement", "body_velocity", "fairlead_tension", "laid_length"):
        assert np.array_equal(resumed[name].values, whole[name].values), name
    # the same case on the convolution path moves the same way (regular waves, 3 s)
    conv = run_coupled(load_case(BUOY_CASE, overrides[1:])).dataset
    diff = np.abs(conv["body_displacement"].values - whole["body_displacement"].values).max()
    assert diff <= 0.01 * np.abs(conv["body_displacement"].values).max()


def test_bad_radiation_value_is_a_case_error() -> None:
    with pytest.raises(CaseError) as info:
        load_case(BUOY_CASE, ['floater.radiation="recursive"'])
    err = info.value
    assert err.key == "floater.radiation"
    assert err.expected == 'one of "convolution", "state-space"'
    assert err.found == 'the string "recursive"'
    assert "--set floater.radiation" in err.source
    with pytest.raises(CaseError, match="floater.radiation"):
        load_case(BUOY_CASE, ["floater.radiation=1"])


def test_state_space_without_a_realisation_exits_2_and_writes_nothing(tmp_path, capsys,
                                                                      monkeypatch) -> None:
    (tmp_path / "hydrodb").mkdir()
    (tmp_path / "cases").mkdir()
    ds = remove_from_dataset(read_database(REPO / "hydrodb" / "cylinder_buoy.nc"))
    ds.attrs.pop("path", None)
    write_database(ds, tmp_path / "hydrodb" / "cylinder_buoy.nc")
    case = tmp_path / "cases" / "buoy.toml"
    case.write_text(BUOY_CASE.read_text().replace(
        'reference_point = [0.0, 0.0, 0.0]     # m',
        'reference_point = [0.0, 0.0, 0.0]     # m\nradiation = "state-space"'))
    out = tmp_path / "run.nc"
    args = ["run", str(case), "-o", str(out), "--quiet", "--set", "simulation.duration=0.1"]
    args += ["--set", 'lines.*.model="quasi-static"']
    status = main(args)
    captured = capsys.readouterr()
    assert status == 2 and captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1
    message = lines[0]
    assert message.startswith(f"floatmoor: error: {case}: floater.radiation: expected ")
    assert "fit-state-space cylinder_buoy" in message and "holds none" in message
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["cases",
                                                                              "hydrodb"]
    # the same with the key given on the command line names the --set
    case.write_text(BUOY_CASE.read_text())
    assert main(args + ["--set", STATE_SPACE]) == 2
    assert f"(--set {STATE_SPACE})" in capsys.readouterr().err
    # once fitted, the run goes. The command's fit is the committed realisation here, which
    # spares a 15-35 s fit: the fit itself, and a run on a fresh one, are checked in
    # tests/hydro/state_space/test_state_space.py (its refit, its heave decay, the command's own fit)
    stored = read_state_space(read_database(REPO / "hydrodb" / "cylinder_buoy.nc"))
    fits = []
    monkeypatch.setattr(state_space_fit, "fit_state_space",
                        lambda *a, **k: fits.append(1) or stored)
    assert main(["hydro", "fit-state-space", str(tmp_path / "hydrodb" / "cylinder_buoy.nc")]) == 0
    assert fits == [1]
    capsys.readouterr()
    assert main(args + ["--set", STATE_SPACE]) == 0
    assert read_dataset(out).attrs["status"] == "complete"
