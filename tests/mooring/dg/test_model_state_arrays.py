"""The line models' ``state_arrays`` (what a checkpoint stores): restored into a model built
afresh from the case, the model continues exactly as the original does."""

from __future__ import annotations

import numpy as np

from floatmoor.case.load import load_case
from floatmoor.mooring.dg.line import DynamicLine
from tests.conftest import CASES

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"


def _path(line, t):
    amplitude = np.array([0.01, 0.0, 0.004])
    return (np.asarray(line.fairlead) + np.outer(np.sin(2.0 * t), amplitude),
            2.0 * np.outer(np.cos(2.0 * t), amplitude))


def _run(model, t, path, velocity):
    n = t.size
    ff, af, lb, st = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n), np.zeros(n)
    model.solve_path(t, path, velocity, ff, af, lb, st)
    return ff, af


def test_dynamic_line_with_frozen_damping_factors_continues_bit_identically() -> None:
    """Sample intervals of exactly equal length keep the implicit internal damping's factors
    frozen over many steps; restored without them, the continuation would refactor and
    differ in the last bits."""
    case = load_case(BUOY_CASE, ['lines.*.model="dynamic"', "lines.*.dynamic.elements=4",
                                 "lines.*.dynamic.order=3",
                                 'lines.*.dynamic.time_integration="explicit"',
                                 "line_types.chain.internal_damping_ratio=0.2"])
    line = case.lines[0]
    t = np.arange(0, 17) * 2.0 ** -8  # exact binary steps: every interval the same dt
    path, velocity = _path(line, t)
    original = DynamicLine.from_case(line, case.environment, case.seabed)
    _run(original, t[:9], path[:9], velocity[:9])
    saved = original.state_arrays()
    assert saved["damping_info"][0] == 1.0
    factorisations = saved["damping_info"][3]
    expected = _run(original, t[8:], path[8:], velocity[8:])
    # reused over many steps, rebuilt a few times
    assert original.state_arrays()["damping_info"][3] - factorisations < 8
    fresh = DynamicLine.from_case(line, case.environment, case.seabed)
    fresh.set_state_arrays({k: np.array(v) for k, v in saved.items()})
    got = _run(fresh, t[8:], path[8:], velocity[8:])
    for a, b in zip(got, expected):
        assert np.array_equal(a, b)
