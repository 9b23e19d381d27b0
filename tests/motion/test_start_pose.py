"""A motion table whose first row is not the rest pose, run without a ramp, starts the lines in
that pose (docs/theory/mooring_systems.md#prescribed-motion-of-the-body-points): no jump of
the fairleads at t = 0, and the summary says that its statistics include t = 0."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import ModelValidityWarning
from floatmoor.io.run_case import default_start
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.motion.rigid_body import prescribed_fairlead_state, start_line
from floatmoor.post.summary import format_summary, run_summary
from floatmoor.simulation.assembly import assemble, start_positions
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE, REPO

#: A constant pose held from t = 0, away from rest (a record's first row: surge and pitch, the
#: fairlead 1.08 m above its rest position), as a body table and as a line table.
BODY_POSE = ("time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg\n0,0.1,0,0,0,-1.9,0\n"
             "2,0.1,0,0,0,-1.9,0\n")
LINE_POSE = "time,x,y,z\n0,0.1,0,0.5\n2,0.1,0,0.5\n"
#: A quasi-dynamic line at rest stays at its static tension: round-off of the backward
#: differences (observed 4e-11 relative; before, the jump at t = 0 read 2e7 N against 49 N).
AT_REST_RTOL = 1e-9
#: A dynamic line settled in the pose: its tension drifts by the settle tolerance only
#: (observed 1.3e-6 relative over the run; before, the run failed at the first step: a node
#: faster than the axial wave).
SETTLED_RTOL = 1e-4
#: The dynamic line's own discretised equilibrium against the exact catenary (10 elements of
#: order 5 on the Lindahl chain: observed 0.68 %).
DISCRETISATION_RTOL = 0.02


def _case(folder: Path, kind: str, csv: str, model: str, ramp: float = 0.0,
          duration: float = 0.25) -> Path:
    text = LINDAHL_CASE.read_text().replace(
        "circular motion r = {motion.radius:.2f} m, T = {motion.period:.2f} s", "a pose")
    i, j = text.index("[motion]"), text.index("[simulation]")
    text = (text[:i] + f'[motion]\nkind = "{kind}"\nfile = "pose.csv"\nramp_duration = {ramp}\n\n'
            + text[j:]).replace("duration = 15.0", f"duration = {duration}")
    text = text.replace('model = "dynamic"', f'model = "{model}"')
    (folder / "pose.csv").write_text(csv)
    (folder / "case.toml").write_text(text)
    return folder / "case.toml"


def _static_tension(case) -> float:
    line = case.lines[0]
    pose = prescribed_fairlead_state(case.motion, line, np.zeros(1))[0][0]
    model = QuasiStaticLine.from_case(line, case.environment, case.seabed)
    return float(np.linalg.norm(model.solve(pose).fairlead_force))


@pytest.mark.parametrize("kind, csv", [("body", BODY_POSE), ("table", LINE_POSE)])
def test_a_quasi_dynamic_line_starts_at_rest_in_the_first_pose(tmp_path, kind, csv):
    case = load_case(_case(tmp_path, kind, csv, "quasi-dynamic"))
    tension = run_forced_motion(case).dataset["fairlead_tension"].values[0]
    np.testing.assert_allclose(tension, _static_tension(case), rtol=AT_REST_RTOL)


def test_a_dynamic_line_is_settled_in_the_first_pose(tmp_path):
    case = load_case(_case(tmp_path, "body", BODY_POSE, "dynamic"))
    tension = run_forced_motion(case).dataset["fairlead_tension"].values[0]
    np.testing.assert_allclose(tension, tension[0], rtol=SETTLED_RTOL)
    assert tension[0] == pytest.approx(_static_tension(case), rel=DISCRETISATION_RTOL)


def test_with_a_ramp_or_a_zero_first_row_the_lines_start_at_rest(tmp_path):
    ramped = load_case(_case(tmp_path, "body", BODY_POSE, "quasi-dynamic", ramp=0.1))
    line = ramped.lines[0]
    assert start_line(ramped.motion, line) is line  # the ramp starts from zero displacement
    (tmp_path / "b").mkdir()
    zero = load_case(_case(tmp_path / "b", "table", "time,x,y,z\n0,0,0,0\n2,0.1,0,0.5\n",
                           "quasi-dynamic"))
    assert start_line(zero.motion, zero.lines[0]) is zero.lines[0]  # the same model, bit for bit
    held = load_case(_case(tmp_path, "body", BODY_POSE, "quasi-dynamic"))
    moved = start_line(held.motion, held.lines[0])
    np.testing.assert_array_equal(
        moved.fairlead, prescribed_fairlead_state(held.motion, held.lines[0], np.zeros(1))[0][0])


def test_lines_solved_as_a_system_start_in_the_first_pose(tmp_path):
    text = (REPO / "tests" / "data" / "systems" / "clump_buoy.toml").read_text()
    text = text.replace("[simulation]", '[motion]\nkind = "table"\nfile = "pose.csv"\n\n'
                        "[simulation]")
    (tmp_path / "pose.csv").write_text("time,x,y,z\n0,3.0,0,1.0\n20,3.0,0,1.0\n")
    (tmp_path / "case.toml").write_text(text)
    case = load_case(tmp_path / "case.toml")
    moved = start_positions(case)
    np.testing.assert_array_equal(moved["fairlead"], [3.0, 0.0, -9.0])
    (group,) = assemble(case).groups
    k = [case.points[i].name for i in group.points].index("fairlead")
    np.testing.assert_array_equal(group.last_positions[k], [3.0, 0.0, -9.0])


def test_the_summary_and_check_say_where_the_statistics_start(tmp_path, capsys):
    path = _case(tmp_path, "body", BODY_POSE, "quasi-dynamic")
    case = load_case(path)
    summary = run_summary(case, run_forced_motion(case).dataset)
    assert "no motion ramp" in summary["window_start_reason"]
    assert "from t = 0 s (no motion ramp: the whole record" in format_summary(summary)
    assert default_start(case) == (0.0, "record start (no motion ramp)")  # report, plots
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "the lines start, settled, at its pose at t = 0, fairleads up to 1.082 m" in out
    ramped = load_case(_case(tmp_path, "body", BODY_POSE, "quasi-dynamic", ramp=0.1))
    # (a ramp of 1 m in 0.1 s: far beyond the quasi-dynamic model's accelerations, as the
    # run says)
    with pytest.warns(ModelValidityWarning, match="dimensionless acceleration"):
        result = run_forced_motion(ramped)
    assert run_summary(ramped, result.dataset)["window_start_reason"] == "end of the motion ramp"
