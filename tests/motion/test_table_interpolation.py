"""Motion tables are interpolated by the not-a-knot cubic spline through their rows, with its
exact derivative as the velocity
(docs/theory/mooring_systems.md#prescribed-motion-of-the-body-points): no velocity jump at the
rows, so a quasi-dynamic line driven by a sparse table has no tension spike there."""

from __future__ import annotations

import numpy as np
from scipy.interpolate import CubicSpline

from floatmoor.case.load import load_case
from floatmoor.case.schema import BodyTableMotion, TableMotion
from floatmoor.mooring.quasidynamic import QuasiDynamicLine
from floatmoor.motion.fairlead import fairlead_state, motion_state, ramp, table_state
from floatmoor.motion.rigid_body import body_motion_state
from tests.conftest import CASES

#: Against scipy's CubicSpline, the oracle: the same coefficients, evaluated by another
#: Horner form; round-off of values of order 1 (observed 2e-14 on values, 5e-14 on rates).
ORACLE_RTOL = 1e-12
#: Velocity jump across a row, relative to the largest speed: the spline's is round-off
#: (observed ~1e-12 with 1e-9 s either side); a linear table's is of order one.
ROW_JUMP = 1e-7
#: Sparse-table run: the harmonic motion of the quasi-dynamic verification case B tabulated
#: at this many rows per period (no row on an output sample but the first), against the
#: analytic motion: the largest fairlead-tension difference after the ramp relative to the
#: peak tension. Measured 0.50 % with the spline, 400 % with the linear interpolation of before
#: (its velocity jumps at the rows: acceleration spikes in the quasi-dynamic line), 28 % with
#: a monotone PCHIP (docs/theory/mooring_systems.md, table of schemes).
ROWS_PER_PERIOD = 12
SPIKE_MAX = 0.02
CASE_B = CASES / "qd_verification" / "s2_d2.toml"


def _table(rng: np.random.Generator, columns: int) -> tuple[np.ndarray, np.ndarray]:
    time = np.concatenate([[-0.3], np.cumsum(rng.uniform(0.2, 1.5, 24))])
    return time, rng.normal(size=(time.size, columns))


def test_the_spline_is_scipys_and_its_rate_the_exact_derivative():
    rng = np.random.default_rng(3)
    time, values = _table(rng, 3)
    t = np.linspace(0.0, time[-1], 2003)
    value, rate = table_state(time, values, t)
    oracle = CubicSpline(time, values, bc_type="not-a-knot")
    scale = np.abs(oracle(t)).max()
    np.testing.assert_allclose(value, oracle(t), rtol=0.0, atol=ORACLE_RTOL * scale)
    np.testing.assert_allclose(rate, oracle(t, 1), rtol=0.0,
                               atol=ORACLE_RTOL * np.abs(oracle(t, 1)).max())
    # the rows themselves are the table's numbers, exactly (but the last, to round-off)
    at_rows, _ = table_state(time, values, time[:-1])
    assert at_rows.tobytes() == values[:-1].tobytes()
    # after the end the last row holds, at rest
    after, after_rate = table_state(time, values, np.array([time[-1] + 1.0]))
    np.testing.assert_allclose(after[0], values[-1], rtol=1e-13)
    assert np.all(after_rate == 0.0)


def test_velocity_is_continuous_at_the_rows_for_line_and_body_tables():
    rng = np.random.default_rng(7)
    time, values = _table(rng, 6)
    rows = time[1:-1]
    h = 1e-9
    line = TableMotion(file="m.csv", time=time, displacement=values[:, :3])
    body = BodyTableMotion(reference_point=(0.0, 0.0, 0.0), file="m.csv", time=time,
                           displacement=0.1 * values)
    for state in (lambda t: motion_state(line, t, None), lambda t: body_motion_state(body, t)):
        _, before = state(rows - h)
        _, after = state(rows + h)
        _, everywhere = state(np.linspace(0.0, time[-1], 5001))
        speed = np.abs(everywhere).max()
        assert np.abs(after - before).max() < ROW_JUMP * speed


def test_the_ramped_rate_is_the_derivative_of_the_ramped_table():
    rng = np.random.default_rng(11)
    time, values = _table(rng, 3)
    motion = TableMotion(file="m.csv", time=time, displacement=values, ramp_duration=4.0)
    t = np.linspace(0.05, time[-1] - 0.05, 997)
    h = 1e-6
    d, dd = motion_state(motion, t, None)
    numerical = (motion_state(motion, t + h, None)[0] - motion_state(motion, t - h, None)[0]) \
        / (2.0 * h)
    np.testing.assert_allclose(dd, numerical, rtol=0.0, atol=1e-6 * np.abs(dd).max())
    np.testing.assert_allclose(d, ramp(t, 4.0)[:, None] * CubicSpline(time, values)(t),
                               rtol=0.0, atol=1e-13 * np.abs(values).max())


def _qd_tension(case, path, velocity, t):
    line = case.lines[0]
    model = QuasiDynamicLine.from_case(line, case.environment, case.seabed)
    n = t.size
    force = np.zeros((n, 3))
    model.solve_path(t, path, velocity, force, np.zeros((n, 3)), np.zeros(n), np.zeros(n))
    return np.linalg.norm(force, axis=1)


def test_a_sparse_table_drives_a_quasi_dynamic_line_without_spikes_at_its_rows():
    case = load_case(CASE_B)
    motion, line = case.motion, case.lines[0]
    dt = case.simulation.output_interval
    t = np.arange(int(round(case.simulation.duration / dt)) + 1) * dt
    amplitude, period = motion.amplitude[0], motion.period[0]
    rows = np.arange(0.0, case.simulation.duration + period, period / ROWS_PER_PERIOD)
    displacement = np.zeros((rows.size, 3))
    displacement[:, 0] = amplitude * np.sin(2.0 * np.pi * rows / period)
    table = TableMotion(file="sine.csv", time=rows, displacement=displacement,
                        ramp_duration=motion.ramp_duration)
    analytic = _qd_tension(case, *fairlead_state(motion, line, t), t)
    tabulated = _qd_tension(case, *fairlead_state(table, line, t), t)
    after = t >= motion.ramp_duration
    spike = np.abs(tabulated - analytic)[after].max() / analytic[after].max()
    assert spike < SPIKE_MAX, f"tension error {spike:.2%} of the peak"
