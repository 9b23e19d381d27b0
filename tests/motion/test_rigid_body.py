"""Prescribed 6-DOF body motion (``[motion] kind = "body"``): large-angle
kinematics, exact velocities, table and harmonic input, and the translations of today's
motions reproduced bit for bit."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from floatmoor.case.load import load_case
from floatmoor.case.schema import BodyHarmonicMotion, BodyTableMotion
from floatmoor.errors import CaseError
from floatmoor.motion.fairlead import fairlead_state
from floatmoor.motion.rigid_body import (body_motion_state, body_points_state,
                                         prescribed_fairlead_state)
from floatmoor.rotations import angular_velocity, rotation_matrices, rotation_matrix
from tests.conftest import LINDAHL_CASE

#: Tolerance of the exactness checks [-]: a few hundred ulps of the arm length (the
#: requirement's "on its circle exactly (1e-12)").
EXACT = 1e-12
#: Rest points of a body (k = 4) spread around a reference point, arms of 5 to 40 m.
REST = np.array([[32.0, 0.0, -5.0], [-20.0, 17.0, -14.0], [3.0, -30.0, 2.0], [0.0, 0.0, -40.0]])
CENTRE = np.array([1.5, -2.0, -10.0])


def _case_text(motion: str) -> str:
    """The Lindahl case with ``motion`` as its [motion] table."""
    text = LINDAHL_CASE.read_text().replace(
        "circular motion r = {motion.radius:.2f} m, T = {motion.period:.2f} s", "body motion")
    start, end = text.index("[motion]"), text.index("[simulation]")
    return text[:start] + motion + "\n" + text[end:]


def _write_case(folder: Path, motion: str, csv: str | None = None) -> Path:
    case = folder / "body.toml"
    case.write_text(_case_text(motion))
    if csv is not None:
        (folder / "m.csv").write_text(csv)
    return case


def _rotation_table(ramp: float = 0.0) -> BodyTableMotion:
    """Only rotations, up to 70 degrees, changing sign, yaw over a half turn."""
    time = np.array([0.0, 1.0, 2.5, 4.0, 6.0])
    angles = np.radians([[0.0, 0.0, 0.0], [30.0, -20.0, 45.0], [-50.0, 70.0, 120.0],
                         [10.0, -60.0, -170.0], [0.0, 5.0, 0.0]])
    displacement = np.hstack([np.zeros((5, 3)), angles])
    return BodyTableMotion(reference_point=tuple(CENTRE), file="m.csv", time=time,
                           displacement=displacement, ramp_duration=ramp)


def _harmonic(amplitude, period=(7.0, 9.0, 11.0, 5.0, 6.5, 13.0),
              phase=(0.1, 0.7, -0.4, 1.1, 0.3, -0.9), ramp: float = 3.0) -> BodyHarmonicMotion:
    return BodyHarmonicMotion(reference_point=tuple(CENTRE), amplitude=tuple(amplitude),
                              period=tuple(period), phase=tuple(phase), ramp_duration=ramp)


# -- kinematics --------------------------------------------------------------------------------

def test_rotation_only_table_keeps_every_point_on_its_sphere():
    motion = _rotation_table()
    t = np.linspace(0.0, 6.0, 2401)
    positions, _ = body_points_state(motion, REST, t)
    arms = REST - CENTRE
    radius = np.linalg.norm(arms, axis=1)
    distance = np.linalg.norm(positions - CENTRE, axis=2)
    np.testing.assert_allclose(distance, np.broadcast_to(radius, distance.shape), rtol=EXACT,
                               atol=0.0)
    # the positions are R(angles(t)) applied to the rest arms, angles interpolated by the
    # not-a-knot cubic spline (scipy's, the oracle of floatmoor.motion.fairlead.table_state)
    spline = CubicSpline(motion.time, motion.displacement[:, 3:], bc_type="not-a-knot")
    for n in range(0, t.size, 37):
        angles = spline(t[n])
        expected = CENTRE + arms @ rotation_matrix(*angles).T
        np.testing.assert_allclose(positions[n], expected, rtol=0.0,
                                   atol=EXACT * radius.max())
    # it really turns: half a turn of yaw moves the points by tens of metres
    assert np.abs(positions - REST).max() > 30.0


def test_velocities_are_the_time_derivative_of_the_positions():
    # large angles in every DOF, ramped: the velocity of each point against central
    # differences of its position
    motion = _harmonic((1.5, 0.8, 0.6, math.radians(35), math.radians(50), math.radians(80)))
    t = np.linspace(0.2, 20.0, 97)
    h = 1e-5
    _, v = body_points_state(motion, REST, t)
    p_plus, _ = body_points_state(motion, REST, t + h)
    p_minus, _ = body_points_state(motion, REST, t - h)
    numerical = (p_plus - p_minus) / (2 * h)
    # central differences: O(h^2 |p'''|) ~ 1e-9 m/s, round-off ~ eps |p| / h ~ 1e-10 m/s
    np.testing.assert_allclose(v, numerical, rtol=0.0, atol=1e-7)
    assert np.abs(v).max() > 10.0  # not trivially small


def test_angular_velocity_is_the_exact_one_not_the_euler_rates():
    # omega x = R' R^T, R' by central differences of the rotation along a harmonic motion
    motion = _harmonic((0.0, 0.0, 0.0, math.radians(40), math.radians(60), math.radians(90)))
    t = np.linspace(3.5, 15.0, 41)
    h = 1e-6
    x, dx = body_motion_state(motion, t)
    omega = angular_velocity(x[:, 3:], dx[:, 3:])
    R_dot = (rotation_matrices(body_motion_state(motion, t + h)[0][:, 3:])
             - rotation_matrices(body_motion_state(motion, t - h)[0][:, 3:])) / (2 * h)
    W = R_dot @ np.transpose(rotation_matrices(x[:, 3:]), (0, 2, 1))
    np.testing.assert_allclose(W + np.transpose(W, (0, 2, 1)), 0.0, atol=1e-8)  # skew
    numerical = np.stack([W[:, 2, 1], W[:, 0, 2], W[:, 1, 0]], axis=1)
    np.testing.assert_allclose(omega, numerical, rtol=0.0, atol=1e-8)
    # at these angles the Euler rates are far from the angular velocity
    assert np.abs(omega - dx[:, 3:]).max() > 0.3


def test_the_rates_are_the_derivative_of_the_ramped_displacement():
    motion = _harmonic((1.0, 0.5, 0.3, 0.2, 0.4, 0.6), ramp=8.0)
    # off the ramp's ends, where its second derivative jumps (central differences across a
    # jump err by ~ h |jump| |x|)
    t = np.linspace(0.0, 12.0, 121) + 0.013
    h = 1e-6
    _, dx = body_motion_state(motion, t)
    numerical = (body_motion_state(motion, t + h)[0]
                 - body_motion_state(motion, t - h)[0]) / (2 * h)
    np.testing.assert_allclose(dx, numerical, rtol=0.0, atol=1e-8)
    x0, dx0 = body_motion_state(motion, np.array([0.0]))
    np.testing.assert_array_equal(x0, 0.0)  # the ramp starts from rest
    np.testing.assert_array_equal(dx0, 0.0)


# -- table and harmonic input --------------------------------------------------------------------

HARMONIC_BODY = """[motion]
kind = "body"
reference_point = [30.0, 0.0, -1.0]
ramp_duration = 0.0
[motion.surge]
amplitude = 0.15
period = 2.0
phase_deg = 30.0
[motion.pitch]
amplitude_deg = 4.0
period = 2.0
phase_deg = 90.0
[motion.yaw]
amplitude_deg = 10.0
period = 4.0
"""


def test_harmonic_and_table_of_the_same_motion_give_the_same_path(tmp_path):
    harmonic_case = load_case(_write_case(tmp_path, HARMONIC_BODY))
    motion = harmonic_case.motion
    assert isinstance(motion, BodyHarmonicMotion)
    assert motion.amplitude[4] == pytest.approx(math.radians(4.0), rel=1e-15)
    # the same motion sampled every 0.01 s into a table in degrees
    time = np.arange(0.0, 15.0 + 1e-9, 0.01)
    x, _ = body_motion_state(motion, time)
    rows = "\n".join(",".join(f"{v:.17g}" for v in (tk, *xk[:3], *np.degrees(xk[3:])))
                     for tk, xk in zip(time, x))
    table_motion = HARMONIC_BODY.split("[motion.surge]")[0].replace(
        'ramp_duration = 0.0', 'ramp_duration = 0.0\nfile = "m.csv"')
    (tmp_path / "t").mkdir()
    table_case = load_case(_write_case(
        tmp_path / "t", table_motion,
        "time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg\n" + rows + "\n"))
    assert isinstance(table_case.motion, BodyTableMotion)
    line = harmonic_case.lines[0]
    # at the table's times the paths agree to round-off (degrees to radians and back)
    on_nodes = time[::7]
    p_h, v_h = prescribed_fairlead_state(motion, line, on_nodes)
    p_t, _ = prescribed_fairlead_state(table_case.motion, line, on_nodes)
    np.testing.assert_allclose(p_t, p_h, rtol=0.0, atol=1e-12 * 30.0)
    # between them within the linear interpolation error, |x''| dt^2 / 8 (the spline's is
    # far smaller)
    between = time[:-1:7] + 0.005
    p_h, v_h = prescribed_fairlead_state(motion, line, between)
    p_t, v_t = prescribed_fairlead_state(table_case.motion, line, between)
    np.testing.assert_allclose(p_t, p_h, rtol=0.0, atol=5e-5)
    np.testing.assert_allclose(v_t, v_h, rtol=0.0, atol=5e-5 / 0.005)


def test_pure_translation_equals_todays_motions_bit_for_bit(tmp_path):
    today = load_case(LINDAHL_CASE, ['motion={kind="harmonic", amplitude=[0.1, 0.05, 0.2], '
                                     'period=[1.25, 2.0, 1.25], phase_deg=[0.0, 45.0, 90.0], '
                                     'ramp_duration=2.5}'])
    body = load_case(_write_case(tmp_path, """[motion]
kind = "body"
reference_point = [3.0, 1.0, -2.0]
ramp_duration = 2.5
[motion.surge]
amplitude = 0.1
period = 1.25
[motion.sway]
amplitude = 0.05
period = 2.0
phase_deg = 45.0
[motion.heave]
amplitude = 0.2
period = 1.25
phase_deg = 90.0
"""))
    t = np.arange(6001) * 0.0025
    line = today.lines[0]
    for a, b in zip(fairlead_state(today.motion, line, t),
                    prescribed_fairlead_state(body.motion, line, t)):
        assert a.tobytes() == b.tobytes()
    # a table with rotation columns of zeros: today's table, bit for bit
    table = "0,0,0,0\n1.5,0.1,-0.02,0.05\n4,-0.07,0.03,0.0\n20,0.01,0.0,-0.04\n"
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    today = load_case(_write_case(tmp_path / "a", '[motion]\nkind = "table"\nfile = "m.csv"\n'
                                  "ramp_duration = 1.0\n", "time,x,y,z\n" + table))
    rows = "".join(row + ",0,0,0\n" for row in table.splitlines())
    body = load_case(_write_case(tmp_path / "b", '[motion]\nkind = "body"\nfile = "m.csv"\n'
                                 "ramp_duration = 1.0\nreference_point = [5.0, 5.0, 5.0]\n",
                                 "time,surge,sway,heave,roll_rad,pitch_rad,yaw_rad\n" + rows))
    for a, b in zip(fairlead_state(today.motion, line, t),
                    prescribed_fairlead_state(body.motion, line, t)):
        assert a.tobytes() == b.tobytes()


def test_defaults_and_units(tmp_path):
    case = load_case(_write_case(tmp_path, '[motion]\nkind = "body"\n[motion.roll]\n'
                                 "amplitude_deg = 2.0\nperiod = 3.0\n[motion.heave]\n"
                                 "amplitude = 0.1\nperiod = 2.0\n"))
    motion = case.motion
    assert motion.reference_point == (0.0, 0.0, 0.0)  # the origin, as MoorDyn's coupled body
    assert motion.ramp_duration == 3.0  # the longest moving period, as kind = "harmonic"
    assert motion.amplitude == (0.0, 0.0, 0.1, math.radians(2.0), 0.0, 0.0)
    assert motion.cycle_period is None  # two periods
    # a table in degrees and one in radians are the same motion
    (tmp_path / "deg").mkdir()
    (tmp_path / "rad").mkdir()
    deg = load_case(_write_case(tmp_path / "deg", '[motion]\nkind = "body"\nfile = "m.csv"\n',
                                "time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg\n"
                                "0,0,0,0,0,0,0\n20,0.1,0,0,3,-2,45\n"))
    rad = load_case(_write_case(tmp_path / "rad", '[motion]\nkind = "body"\nfile = "m.csv"\n',
                                "time,surge,sway,heave,roll_rad,pitch_rad,yaw_rad\n"
                                f"0,0,0,0,0,0,0\n20,0.1,0,0,{math.radians(3)!r},"
                                f"{math.radians(-2)!r},{math.radians(45)!r}\n"))
    assert deg.motion.ramp_duration == 0.0
    np.testing.assert_allclose(deg.motion.displacement, rad.motion.displacement, rtol=1e-15)


# -- strict input ---------------------------------------------------------------------------------

BAD = {
    "bare_rotation_header": (
        '[motion]\nkind = "body"\nfile = "m.csv"\n',
        "time,surge,sway,heave,roll,pitch,yaw\n0,0,0,0,0,0,0\n20,0,0,0,0,0,0\n",
        "motion.file", "roll_deg,pitch_deg,yaw_deg", "column 5 is not roll_deg or roll_rad"),
    "mixed_units_header": (
        '[motion]\nkind = "body"\nfile = "m.csv"\n',
        "time,surge,sway,heave,roll_deg,pitch_rad,yaw_deg\n0,0,0,0,0,0,0\n20,0,0,0,0,0,0\n",
        "motion.file", "roll_rad,pitch_rad,yaw_rad", "a mix of the headers' columns"),
    "short_row": (
        '[motion]\nkind = "body"\nfile = "m.csv"\n',
        "time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg\n0,0,0,0,0,0,0\n20,0,0,0,0,0\n",
        "motion.file", "data row 3 with 7 comma-separated", "6 values in row 3"),
    "table_too_short": (
        '[motion]\nkind = "body"\nfile = "m.csv"\n',
        "time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg\n0,0,0,0,0,0,0\n10,0,0,0,0,0,0\n",
        "simulation.duration", "<= the end of the motion table m.csv (10 s)", "15.0"),
    "rotation_amplitude_in_radians": (
        '[motion]\nkind = "body"\n[motion.pitch]\namplitude = 0.1\nperiod = 2.0\n', None,
        "motion.pitch.amplitude", "amplitude_deg", "0.1"),
    "translation_in_degrees": (
        '[motion]\nkind = "body"\n[motion.surge]\namplitude_deg = 0.1\nperiod = 2.0\n', None,
        "motion.surge.amplitude_deg", "the surge amplitude in metres", "0.1"),
    "file_and_harmonic": (
        '[motion]\nkind = "body"\nfile = "m.csv"\n[motion.surge]\namplitude = 0.1\n'
        "period = 2.0\n",
        "time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg\n0,0,0,0,0,0,0\n20,0,0,0,0,0,0\n",
        "motion.surge", "not both", "a table"),
    "nothing_moves": ('[motion]\nkind = "body"\n', None, "motion.file",
                      "at least one harmonic DOF table", "nothing"),
    "zero_amplitudes": (
        '[motion]\nkind = "body"\n[motion.yaw]\namplitude_deg = 0.0\nperiod = 2.0\n', None,
        "motion.yaw", "a non-zero amplitude", "every amplitude 0"),
    "misspelt_dof": (
        '[motion]\nkind = "body"\n[motion.pich]\namplitude_deg = 1.0\nperiod = 2.0\n', None,
        "motion.pich", "one of the known keys", "the unknown key 'pich'"),
    "reference_point_of_two": (
        '[motion]\nkind = "body"\nreference_point = [1.0, 2.0]\n[motion.yaw]\n'
        "amplitude_deg = 1.0\nperiod = 2.0\n", None,
        "motion.reference_point", "an array of 3 finite numbers [m]", "an array of 2"),
    "rotation_into_the_seabed": (  # pitching 20 degrees about a point 30 m away
        '[motion]\nkind = "body"\nreference_point = [2.554, 0.0, 0.3]\n[motion.pitch]\n'
        "amplitude_deg = 20.0\nperiod = 2.0\n", None,
        "motion", "keeps the fairlead of line 'chain' above the seabed", "z = -"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_body_motions_are_clear_errors(tmp_path, name):
    motion, csv, key, expected, found = BAD[name]
    case = _write_case(tmp_path, motion, csv)
    with pytest.raises(CaseError) as info:
        load_case(case)
    err = info.value
    assert err.source == str(case)
    assert err.key == key, err
    assert expected in err.expected, err
    assert found in err.found, err


def test_every_body_point_is_checked_above_the_seabed(tmp_path):
    # a rope from a clump to the body point: no fixed-to-body line ends there, the body
    # point's own path is checked
    text = (Path(__file__).parents[1] / "data" / "systems" / "clump_buoy.toml").read_text()
    text = text[:text.index("[[lines]]")] + """[[lines]]
name = "lower"
start = "anchor"
end = "clump"
type = "chain"
length = 150.0
model = "quasi-static"

[[lines]]
name = "upper"
start = "clump"
end = "fairlead"
type = "chain"
length = 290.0
model = "quasi-static"

[motion]
kind = "body"
reference_point = [-150.0, 0.0, -10.0]
[motion.roll]
amplitude_deg = 1.0
period = 10.0
[motion.pitch]
amplitude_deg = {pitch}
period = 10.0

[simulation]
duration = 30.0
output_interval = 0.1
"""
    text = text.replace("[[points]]\nname = \"buoy\"", "[[unused]]\nname = \"buoy\"")
    head, _, rest = text.partition("[[unused]]")
    text = head + rest[rest.index("[[points]]"):]
    case = tmp_path / "system.toml"
    case.write_text(text.replace("{pitch}", "5.0"))
    motion = load_case(case).motion
    assert isinstance(motion, BodyHarmonicMotion)
    case.write_text(text.replace("{pitch}", "60.0"))  # swings the fairlead 130 m down
    with pytest.raises(CaseError) as info:
        load_case(case)
    assert info.value.key == "motion"
    assert "keeps body point 'fairlead' above the seabed" in info.value.expected
