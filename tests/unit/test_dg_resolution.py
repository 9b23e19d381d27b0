"""Issue 17: the DG numerics chosen from the accuracy (floatmoor.mooring.dg.resolution) and
the fairlead motion frequency a case declares (floatmoor.case.motion_frequency)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from floatmoor.case import limits
from floatmoor.case.load import load_case
from floatmoor.case.motion_frequency import fairlead_motion_frequency
from floatmoor.case.schema import DynamicSettings, TableMotion
from floatmoor.mooring.dg import resolution as rs
from floatmoor.mooring.dg.line import DynamicLine
from tests.conftest import CASES, LINDAHL_CASE

BUOY = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
LC34 = CASES / "deepcwind" / "deepcwind_lc34.toml"


def _settings(**kw) -> DynamicSettings:
    base = dict(elements=None, order=None, cfl=0.8, max_time_step=None, slack_filter=True,
                seabed_contact="implicit", time_integration="auto")
    base.update(kw)
    return DynamicSettings(**base)


def test_nodes_scale_with_the_dg_error_order() -> None:
    """h^(p + 1) error: 16 times the accuracy asks 16^(1 / 4) = 2 times fewer nodes at p = 3."""
    fine = rs.auto_nodes(100.0, 10.0, 1.0, 0.01 / 16.0)
    coarse = rs.auto_nodes(100.0, 10.0, 1.0, 0.01)
    assert fine / coarse == pytest.approx(2.0, rel=1e-12)
    # at the reference accuracy: the base and 10 nodes per transverse wavelength
    wavelength = 2.0 * math.pi * 10.0 / 1.0
    assert coarse == pytest.approx(rs.BASE_NODES + rs.NODES_PER_WAVELENGTH * 100.0 / wavelength)
    # no motion declared, or no tension: the static shape only
    assert rs.auto_nodes(100.0, 10.0, 0.0, 0.01) == rs.BASE_NODES
    assert rs.auto_nodes(100.0, 0.0, 1.0, 0.01) == rs.BASE_NODES


def test_given_keys_override_the_choice() -> None:
    st = rs.resolve_settings(_settings(elements=7), 100.0, 10.0)
    assert (st.elements, st.order, st.time_integration) == (7, rs.AUTO_ORDER, "auto")
    st = rs.resolve_settings(_settings(order=5, time_integration="explicit"), 100.0, 0.0)
    assert st.order == 5 and st.time_integration == "explicit"
    assert st.elements == math.ceil(rs.BASE_NODES / 6)
    # bounds: at least MIN_ELEMENTS, at most MAX_AUTO_ELEMENTS
    assert rs.resolve_settings(_settings(accuracy=0.2), 1.0, 0.0).elements >= rs.MIN_ELEMENTS
    st = rs.resolve_settings(_settings(accuracy=1e-3, motion_frequency=50.0), 1000.0, 1.0)
    assert st.elements == rs.MAX_AUTO_ELEMENTS
    # a section of a line system: explicit, the systems' numerics unless given
    st = rs.resolve_settings(_settings(), 50.0, 0.0, several_sections=True)
    assert (st.elements, st.order, st.time_integration) == (
        rs.SYSTEM_ELEMENTS, rs.SYSTEM_ORDER, "explicit")
    st = rs.resolve_settings(_settings(elements=4), 50.0, 0.0, several_sections=True)
    assert (st.elements, st.order) == (4, rs.SYSTEM_ORDER)


def test_the_reference_cases_choices() -> None:
    """What the rule gives on issue 17's references at the default 1 % (module docstring of
    resolution.py: 40 to 48 nodes on the Lindahl chain and the buoy chains, 32 on the
    DeepCwind lines), their files' reference numerics taken out; numerics a case gives stay
    as given (the QD study's 10 x p5)."""
    def chosen(path, overrides=()):
        case = load_case(path, list(overrides))
        ln = case.lines[0]
        ln = dataclasses.replace(ln, dynamic=dataclasses.replace(
            ln.dynamic, elements=None, order=None, time_integration="auto"))
        return DynamicLine.from_case(ln, case.environment, case.seabed).settings

    lindahl = chosen(LINDAHL_CASE)
    assert (lindahl.elements, lindahl.order, lindahl.time_integration) == (12, 3, "auto")
    assert (chosen(BUOY).elements, chosen(BUOY).order) == (11, 3)
    deep = chosen(LC34, ['lines.*.model="dynamic"'])
    assert (deep.elements, deep.order) == (8, 3)
    qd = load_case(CASES / "qd_verification" / "s1_d1.toml").lines[0].dynamic
    assert (qd.elements, qd.order, qd.time_integration) == (10, 5, "explicit")


def test_motion_frequencies() -> None:
    assert load_case(LINDAHL_CASE).lines[0].dynamic.motion_frequency == pytest.approx(
        2.0 * math.pi / 1.25)
    assert load_case(BUOY).lines[0].dynamic.motion_frequency == pytest.approx(
        2.0 * math.pi / 1.2)
    assert load_case(LC34).lines[0].dynamic.motion_frequency == pytest.approx(
        2.0 * math.pi / 14.3)
    # a table: the mean zero-crossing frequency of each column, the fastest; a sine's is its own
    t = np.linspace(0.0, 20.0 * np.pi, 40001)  # whole periods of both
    x = np.column_stack([0.3 * np.sin(0.7 * t), 0.1 * np.sin(2.0 * t), np.zeros_like(t)])
    table = TableMotion(file="x.csv", time=t, displacement=x)
    assert fairlead_motion_frequency(table, None) == pytest.approx(2.0, rel=1e-3)
    assert fairlead_motion_frequency(None, None) == 0.0


def test_layers_agree_on_the_largest_choice() -> None:
    """case.limits bounds an automatic line's nodes (for the input limits and the recorder's
    size estimate) without importing the models' rule: the same figure."""
    assert (limits.AUTO_MAX_ELEMENTS, limits.AUTO_ORDER) == (rs.MAX_AUTO_ELEMENTS, rs.AUTO_ORDER)
    assert limits.dynamic_nodes_bound(_settings()) == rs.MAX_AUTO_ELEMENTS * (rs.AUTO_ORDER + 1)
    assert limits.dynamic_nodes_bound(_settings(elements=3, order=2)) == 9


def test_work_model() -> None:
    """The auto switch compares like with like: an explicit step is three right-hand sides,
    a Newton iteration one and a banded solve."""
    assert rs.explicit_work(1.0, 0.25) == 4 * rs.EXPLICIT_STEP_WORK
    assert rs.implicit_work(2, 3, 0, 4) == pytest.approx(2 * rs.IMPLICIT_STEP_WORK
                                                        + 3 * rs.NEWTON_ITERATION_WORK)
    assert rs.implicit_work(0, 0, 1, 6) > rs.implicit_work(0, 0, 1, 4)


def _counters(steps: float) -> np.ndarray:
    """Integrator counters after ``steps`` accepted steps of one Newton iteration each."""
    from floatmoor.mooring.dg import _implicit_kernels as ik
    c = np.zeros(ik.CS_N)
    c[ik.CS_STEPS] = c[ik.CS_ITERATIONS] = steps
    return c


def _window_steps(ratio: float, auto: rs.AutoIntegration) -> float:
    """Implicit steps (one iteration each) whose work over one window is ``ratio`` times the
    explicit steps'."""
    per_step = rs.IMPLICIT_STEP_WORK + rs.NEWTON_ITERATION_WORK
    return ratio * rs.explicit_work(auto.window, auto.explicit_step) / per_step


@pytest.mark.parametrize("ratio, windows", [(0.9, None), (1.1, 2), (1.6, 1), (3.0, 1)])
def test_switch_rule(ratio: float, windows: int | None) -> None:
    """Implicit steps dearer than the explicit ones in two consecutive windows switch the line;
    clearly dearer (CLEARLY_OVER_BUDGET) in one window switch it at once; cheaper never."""
    auto = rs.AutoIntegration.for_line(2.0 * math.pi / 1.25, 1e-4, 4)
    assert auto.window == 1.25
    assert not auto.should_switch(0.0, _counters(0.0))
    steps, switched = 0.0, None
    for k in range(1, 5):
        steps += _window_steps(ratio, auto)
        if auto.should_switch(k * auto.window, _counters(steps)):
            switched = k
            break
    assert switched == windows
    assert auto.switched == (windows is not None)
