"""``[motion] kind = "body"`` from the command line: shipped forced cases run
under a 6-DOF body motion and record it; bad body motions stop with one message, status 2 and
no output."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.io.netcdf import read_dataset
from floatmoor.io.variables import VARIABLE_ATTRIBUTES
from floatmoor.motion.rigid_body import body_motion_state, body_points_state
from tests.conftest import CASES, LINDAHL_CASE

QD_CASE = CASES / "qd_verification" / "s1_d1.toml"


def _with_motion(source, folder, motion: str, csv: str | None = None):
    """A copy of ``source`` in ``folder`` with ``motion`` as its [motion] table and a title
    without placeholders."""
    text = source.read_text()
    start, end = text.index("[motion]"), text.index("[simulation]")
    head = text[:start]
    title_start = head.index("title = ")
    head = head[:title_start] + 'title = "body motion"' + head[head.index("\n", title_start):]
    case = folder / f"{source.stem}_body.toml"
    case.write_text(head + motion + "\n" + text[end:])
    if csv is not None:
        (folder / "m.csv").write_text(csv)
    return case


def test_lindahl_under_a_body_table_records_the_motion(tmp_path, capsys):
    # surge, heave and large rotations about the sheave's foot, quasi-static for speed
    csv = ("time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg\n"
           "0,0,0,0,0,0,0\n0.5,0.1,0,0.05,5,-3,10\n1.0,-0.05,0.02,0,-4,4,25\n2.0,0,0,0,0,0,0\n")
    case = _with_motion(LINDAHL_CASE, tmp_path, '[motion]\nkind = "body"\nfile = "m.csv"\n'
                        "reference_point = [31.0, 0.0, -0.5]\nramp_duration = 0.2\n", csv)
    out = tmp_path / "run.nc"
    overrides = ["--set", "simulation.duration=2.0", "--set", 'lines.chain.model="quasi-static"']
    assert main(["run", str(case), *overrides, "-o", str(out), "--quiet"]) == 0
    capsys.readouterr()
    ds = read_dataset(out)
    assert ds.attrs["status"] == "complete"
    for name in ("prescribed_displacement", "prescribed_displacement_rate", "dof"):
        assert ds[name].attrs["units"] == VARIABLE_ATTRIBUTES[name]["units"]
        assert ds[name].attrs["long_name"] == VARIABLE_ATTRIBUTES[name]["long_name"]
    assert ds["prescribed_displacement"].dims == ("time", "dof")
    loaded = load_case(case, ["simulation.duration=2.0", 'lines.chain.model="quasi-static"'])
    t = ds["time"].values
    x, dx = body_motion_state(loaded.motion, t)
    np.testing.assert_array_equal(ds["prescribed_displacement"].values, x)
    np.testing.assert_array_equal(ds["prescribed_displacement_rate"].values, dx)
    # 25 degrees of yaw at t = 1 s, in radians
    assert ds["prescribed_displacement"].sel(dof="Yaw").values[t == 1.0] == \
        pytest.approx(np.radians(25.0), rel=1e-12)
    # the fairlead followed the rigid-body motion, and the line answered it
    positions, _ = body_points_state(loaded.motion, np.array([loaded.lines[0].fairlead]), t)
    np.testing.assert_array_equal(ds["fairlead_position"].sel(line="chain").values,
                                  positions[:, 0])
    tension = ds["fairlead_tension"].sel(line="chain").values
    assert np.all(np.isfinite(tension)) and tension.max() > 1.2 * tension[0]


def test_qd_study_case_under_a_harmonic_pitch_and_surge(tmp_path, capsys):
    # the quasi-dynamic model takes the fairlead's velocity: the exact rigid-body one
    case = _with_motion(QD_CASE, tmp_path, '[motion]\nkind = "body"\n'
                        "reference_point = [0.0, 0.0, -0.2]\nramp_duration = 1.0\n"
                        "[motion.surge]\namplitude = 0.01\nperiod = 1.061511\n"
                        "[motion.pitch]\namplitude_deg = 5.0\nperiod = 1.061511\n"
                        "phase_deg = 90.0\n")
    out = tmp_path / "qd.nc"
    assert main(["run", str(case), "--set", "simulation.duration=1.5", "-o", str(out),
                 "--quiet"]) == 0
    capsys.readouterr()
    ds = read_dataset(out)
    assert ds.attrs["status"] == "complete" and str(ds["model"].values[0]) == "quasi-dynamic"
    path = ds["fairlead_position"].sel(line="chain").values
    # the fairlead 0.2 m above the pitch centre swings on its circle: x = 0.2 sin(pitch) + surge
    pitch = ds["prescribed_displacement"].sel(dof="Pitch").values
    surge = ds["prescribed_displacement"].sel(dof="Surge").values
    np.testing.assert_allclose(path[:, 0], surge + 0.2 * np.sin(pitch), rtol=0.0, atol=1e-15)
    np.testing.assert_allclose(path[:, 2], -0.2 + 0.2 * np.cos(pitch), rtol=0.0, atol=1e-15)
    assert np.all(np.isfinite(ds["fairlead_tension"].values))


@pytest.mark.parametrize("motion, csv, key", [
    ('[motion]\nkind = "body"\nfile = "m.csv"\n',
     "time,surge,sway,heave,roll,pitch,yaw\n0,0,0,0,0,0,0\n20,0,0,0,0,0,0\n", "motion.file"),
    ('[motion]\nkind = "body"\n[motion.roll]\namplitude = 0.1\nperiod = 2.0\n', None,
     "motion.roll.amplitude"),
    ('[motion]\nkind = "body"\n[motion.rol]\namplitude_deg = 1.0\nperiod = 2.0\n', None,
     "motion.rol"),
    ('[motion]\nkind = "body"\n[motion.heave]\namplitude = 4.0\nperiod = 2.0\n', None,
     "motion"),
], ids=["bare-rotation-header", "rotation-amplitude-in-radians", "misspelt-dof",
        "heave-into-the-seabed"])
def test_bad_body_motion_stops_with_status_2_one_message_no_output(tmp_path, capsys, motion,
                                                                   csv, key):
    case = _with_motion(LINDAHL_CASE, tmp_path, motion, csv)
    out = tmp_path / "out.nc"
    status = main(["run", str(case), "-o", str(out), "--quiet"])
    captured = capsys.readouterr()
    assert status == 2 and captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"floatmoor: error: {case}: {key}: expected")
    assert "Traceback" not in captured.err
    assert not out.exists()
