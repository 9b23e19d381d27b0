"""The DG numerics chosen from the accuracy (floatmoor.mooring.dg.resolution) and
the fairlead motion frequency a case declares (floatmoor.motion.frequency)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from floatmoor.case import limits
from floatmoor.case.load import load_case
from floatmoor.case.schema import DynamicSettings, TableMotion
from floatmoor.mooring.dg import resolution as rs
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.motion.frequency import fairlead_motion_frequency
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
    # a section of a line system: the systems' numerics unless given, its integration kept
    # (the system chooses its steps as one: DynamicSystem)
    st = rs.resolve_settings(_settings(), 50.0, 0.0, several_sections=True)
    assert (st.elements, st.order, st.time_integration) == (
        rs.SYSTEM_ELEMENTS, rs.SYSTEM_ORDER, _settings().time_integration)
    st = rs.resolve_settings(_settings(elements=4), 50.0, 0.0, several_sections=True)
    assert (st.elements, st.order) == (4, rs.SYSTEM_ORDER)


def test_the_reference_cases_choices() -> None:
    """What the rule gives on the stored references at the default 1 % (module docstring of
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
    """The auto choice compares like with like, in right-hand-side evaluations: an explicit
    step is EXPLICIT_STEP_WORK, an implicit attempt its overhead, a Newton iteration one
    evaluation and a banded solve growing with p + 1, a factorisation with (p + 1)^2."""
    assert rs.explicit_work(1.0, 0.25) == 4 * rs.EXPLICIT_STEP_WORK
    assert rs.implicit_work(2, 3, 0, 4) == pytest.approx(
        2 * rs.IMPLICIT_STEP_WORK + 3 * (rs.NEWTON_ITERATION_WORK + 4 * rs.SOLVE_WORK_PER_NODE))
    assert rs.implicit_work(0, 0, 1, 6) > rs.implicit_work(0, 0, 1, 4)


def test_work_model_prices_deepcwind_line2_as_measured() -> None:
    """DeepCwind line 2 (8 x p3) on its LC34 path, 600 s, measured on main: implicit 10857
    steps, 725 rejected, 31503 iterations, 5981 factorisations in 0.47 s of CPU against 1.57 s
    explicit (11.2 us per step of 4.3 ms): the model must see implicit as cheaper by about
    as much (the old constants priced it at 0.6 of explicit, and windows near 1 switched it)."""
    implicit = rs.implicit_work(10857 + 725, 31503, 5981, 4)
    explicit = rs.explicit_work(540.0, 540.0 / 140000)  # 1.57 s / 11.2 us = 1.4e5 steps
    assert implicit / explicit == pytest.approx(0.47 / 1.57, rel=0.2)


def _counters(steps: float) -> np.ndarray:
    """Integrator counters after ``steps`` accepted steps of one Newton iteration each."""
    from floatmoor.mooring.dg import _implicit_kernels as ik
    c = np.zeros(ik.CS_N)
    c[ik.CS_STEPS] = c[ik.CS_ITERATIONS] = steps
    return c


def _window_steps(ratio: float, auto: rs.AutoIntegration, fraction: float = 1.0) -> float:
    """Implicit steps (one iteration each) whose work over ``fraction`` of a window is
    ``ratio`` times the explicit steps' over it."""
    per_step = rs.IMPLICIT_STEP_WORK + rs.NEWTON_ITERATION_WORK + auto.nodes * rs.SOLVE_WORK_PER_NODE
    return ratio * rs.explicit_work(fraction * auto.window, auto.explicit_step) / per_step


@pytest.mark.parametrize("ratio, windows", [(0.9, None), (1.1, 2), (2.0, 2), (3.5, 1)])
def test_switch_rule(ratio: float, windows: int | None) -> None:
    """Implicit steps dearer than the explicit ones in two consecutive windows switch the line;
    clearly dearer (CLEARLY_OVER_BUDGET) in one window switch it at once; cheaper never."""
    auto = rs.AutoIntegration.for_line(2.0 * math.pi / 1.25, 1e-4, 4)
    assert auto.window == 1.25
    assert not auto.update(0.0, _counters(0.0))
    steps, switched = _window_steps(0.5, auto), None  # a first window (a probe) that passes
    assert not auto.update(auto.window, _counters(steps)) and not auto.probing
    for k in range(1, 5):
        steps += _window_steps(ratio, auto)
        if auto.update((k + 1) * auto.window, _counters(steps)):
            switched = k
            break
    assert switched == windows
    assert auto.switched == (windows is not None)


def _explicit_until_probe(auto: rs.AutoIntegration, time: float, steps: float) -> float:
    """Explicit windows (no implicit work) until the next probe starts; its start time."""
    while auto.switched:
        time += auto.window
        changed = auto.update(time, _counters(steps))
        assert changed == (not auto.switched)
    assert auto.probing
    return time


def test_probes_bring_implicit_back_and_back_off_while_dearer() -> None:
    """Explicit windows are probed with implicit steps: a probe dearer than the whole window's
    explicit steps, or CLEARLY_OVER_BUDGET times those up to a check, goes explicit at that
    check (the rest of the window explicit) and doubles the gap to the next probe, up to
    MAX_PROBE_GAP; a probe within them keeps the line implicit (never a permanent switch)."""
    auto = rs.AutoIntegration.for_line(2.0 * math.pi / 1.25, 1e-4, 4)
    auto.update(0.0, _counters(0.0))
    steps = _window_steps(0.5, auto)  # the first window, a probe, passes
    assert not auto.update(auto.window, _counters(steps)) and not auto.probing
    steps += _window_steps(4.0, auto)
    assert auto.update(2 * auto.window, _counters(steps)) and auto.switched
    part = auto.window / rs.PROBE_CHECKS
    time, gaps = 2 * auto.window, []
    for k in range(5):  # snapping: every probe dearer
        start = _explicit_until_probe(auto, time, steps)
        gaps.append(round((start - time) / auto.window))
        assert auto.next_check() == pytest.approx(start + part)
        if k % 2 == 0:  # dearer than the whole window's explicit steps at the second check
            steps += _window_steps(0.5 * rs.CLEARLY_OVER_BUDGET / rs.PROBE_CHECKS, auto)
            assert not auto.update(start + part, _counters(steps))
            assert auto.next_check() == pytest.approx(start + 2 * part)
            steps += _window_steps(1.0, auto)
            assert auto.update(start + 2 * part, _counters(steps))
        else:  # clearly dearer so far at the first check
            steps += _window_steps(1.5 * rs.CLEARLY_OVER_BUDGET / rs.PROBE_CHECKS, auto)
            assert auto.update(start + part, _counters(steps))
        assert auto.switched and not auto.probing
        assert auto.next_check() == pytest.approx(start + auto.window)
        time = start + auto.window
        assert not auto.update(time, _counters(steps))
    assert gaps == [1, 2, 4, 8, 8]
    assert rs.MAX_PROBE_GAP == 8
    start = _explicit_until_probe(auto, time, steps)  # smooth again: a probe at half the work
    for q in range(1, rs.PROBE_CHECKS + 1):
        steps += _window_steps(0.5, auto, 1.0 / rs.PROBE_CHECKS)
        assert not auto.update(start + q * part, _counters(steps))
    assert not auto.switched and not auto.probing and auto.gap == 1
    assert auto.switches == 6 and auto.explicit_windows >= 5 + sum(gaps)


def test_auto_state_round_trip() -> None:
    """A checkpoint carries every field of the choice."""
    auto = rs.AutoIntegration.for_line(2.0 * math.pi / 1.25, 1e-4, 4)
    auto.update(0.0, _counters(0.0))
    auto.update(auto.window, _counters(_window_steps(0.5, auto)))
    auto.update(2 * auto.window, _counters(_window_steps(4.5, auto)))
    auto.update(3 * auto.window, _counters(_window_steps(4.5, auto)))
    other = rs.AutoIntegration.for_line(2.0 * math.pi / 1.25, 1e-4, 4)
    other.set_state(auto.state())
    assert auto.probing and auto.switches == 1
    for f in dataclasses.fields(auto):
        assert np.all(getattr(other, f.name) == getattr(auto, f.name)), f.name
