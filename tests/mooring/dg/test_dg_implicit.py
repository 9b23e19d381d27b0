"""The implicit (generalised-alpha) DG integration as a whole: its order in time, agreement
with the explicit integration of the same discretisation, bit-identical resume, the settled
state, and refinement where a snap needs it."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import xarray as xr

from floatmoor.case.load import load_case
from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg import _implicit_kernels as ik
from floatmoor.mooring.dg.line import CableProperties, DynamicLine
from floatmoor.motion.fairlead import fairlead_state
from tests.conftest import CASES, REPO


pytestmark = pytest.mark.verification

REFERENCES = REPO / "tests" / "data" / "references"
#: Second order: halving the step divides the error by 4; the measured ratios of the
#: fairlead-force error at the samples were 3.9 to 4.0. Bounds with room for the
#: reference's own error: 3.5 to 4.5.
ORDER_RATIO = (3.5, 4.5)
#: Implicit (accuracy 1 %) against explicit on the same elements, smooth motion: the implicit
#: local error share (0.25 %) accumulated over the run; measured 0.05 % of the force range.
SMOOTH_AGREEMENT = 0.005
#: DeepCwind lines on their recorded fairlead paths, 8 x p3, implicit against explicit: STD
#: and maximum after 60 s within 0.5 % (measured 0.2 %); the target is 1 % of the converged
#: tension of the whole run.
DEEPCWIND_AGREEMENT = 0.005
#: The settled end tensions of the two integrations: each settle stops at a 1e-6 relative
#: change per chunk, so they agree to a few times that.
SETTLE_RTOL = 1e-5
#: Lindahl snap case: implicit (accuracy 1 %) against explicit, mean cycle maximum: the
#: accuracy asked and the spread of a snap train's maxima under any change of the step pattern.
#: Newton's tolerance times 0.9, 1 and 1.1 gives +1.01, +1.11 and +1.04 % (and +1.04 % at
#: 0.5); the same on the steps before the smooth tolerance gave +1.11, +0.86 and +1.12 %
#: (+1.13 %), passing the earlier 1 % bound at 1 by chance. The explicit steps themselves move
#: by -0.3 % from cfl 0.8 to 0.4. (time_integration = "auto" steps this chain explicitly.)
SNAP_AGREEMENT = 0.015
#: A hanging line driven slack and snapped taut again on 50 ms steps: the snap peak of the
#: implicit steps (accuracy 1 %) against the explicit steps on the same elements, within the
#: accuracy asked (measured +0.73 %).
SLACK_SNAP_AGREEMENT = 0.01


def _taut_line(integration: str, max_step: float | None = None) -> DynamicLine:
    props = CableProperties(length=20.0, mass_per_length=1.5, axial_stiffness=2e4,
                            diameter=0.03, material_density=5000.0,
                            normal_drag_coefficient=1.2, tangential_drag_coefficient=0.3,
                            added_mass_coefficient=1.0)
    settings = DynamicSettings(elements=6, order=4, cfl=0.8, max_time_step=max_step,
                               slack_filter=True, seabed_contact="implicit",
                               time_integration=integration)
    line = DynamicLine(props, settings, np.array([0.0, 0.0, -15.0]),
                       np.array([16.2, 0.0, -3.0]))
    line.settle()
    return line


def _harmonic(n: int, end: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A periodic fairlead motion (period 2 s, 5 cm) starting from rest with zero acceleration
    and jerk, d = A sin^4(w t / 2), so that it excites no axial wave the steps cannot follow
    (an impulsive start rings the stiff modes, which the steps then damp differently)."""
    t = np.linspace(0.0, end, n)
    w = 2.0 * np.pi / 2.0
    f0 = np.array([16.2, 0.0, -3.0])
    s, c = np.sin(0.5 * w * t), np.cos(0.5 * w * t)
    path = f0 + 0.05 * np.outer(s ** 4, [1.0, 0.0, 0.5])
    vel = 0.05 * 2.0 * w * np.outer(s ** 3 * c, [1.0, 0.0, 0.5])
    return t, path, vel


def _run(line: DynamicLine, t, path, vel) -> np.ndarray:
    n = t.size
    ff = np.zeros((n, 3))
    line.solve_path(t, path, vel, ff, np.zeros((n, 3)), np.zeros(n), np.zeros(n))
    return ff


def test_second_order_in_time() -> None:
    t, path, vel = _harmonic(41, 2.0)
    forces = {}
    for dt in (0.025, 0.0125, 0.00625, 0.05 / 128):
        line = _taut_line("implicit", dt)
        line.implicit.ip[ik.IP_FORCE_TOL] = np.inf  # fixed steps
        # Newton converged far below the finest step's time error (its own tolerance follows
        # the accuracy asked, which steps this fine exceed by far)
        line.implicit.ip[ik.IP_NEWTON_TOL] *= 1e-4
        forces[dt] = _run(line, t, path, vel)
    ref = forces[0.05 / 128]
    errors = [np.max(np.abs(forces[dt] - ref)) for dt in (0.025, 0.0125, 0.00625)]
    ratios = [errors[0] / errors[1], errors[1] / errors[2]]
    print("errors [N]", errors, "ratios", ratios)
    for ratio in ratios:
        assert ORDER_RATIO[0] <= ratio <= ORDER_RATIO[1]


def test_agrees_with_explicit_on_smooth_motion() -> None:
    t, path, vel = _harmonic(201, 4.0)
    explicit = _run(_taut_line("explicit"), t, path, vel)
    line = _taut_line("implicit")
    implicit = _run(line, t, path, vel)
    span = np.ptp(np.linalg.norm(explicit, axis=1))
    err = np.max(np.abs(implicit - explicit)) / span
    print(f"implicit - explicit: {err:.2e} of the range; steps {line.implicit.cs[ik.CS_STEPS]:.0f}")
    assert err <= SMOOTH_AGREEMENT


def test_resume_is_bit_identical() -> None:
    t, path, vel = _harmonic(81, 2.0)
    whole = _taut_line("implicit")
    full = _run(whole, t, path, vel)
    first = _taut_line("implicit")
    _run(first, t[:41], path[:41], vel[:41])
    saved = first.state_arrays()
    second = _taut_line("implicit")
    second.set_state_arrays(saved)
    rest = _run(second, t[40:], path[40:], vel[40:])
    assert rest.tobytes() == full[40:].tobytes()
    assert second.r.tobytes() == whole.r.tobytes()


def test_settles_to_the_explicit_equilibrium() -> None:
    """A sagging line hanging clear of the seabed has one equilibrium; both settles find it.
    (A chain resting on a frictionless seabed has none to find: its laid part creeps at
    any rate below the settle's stopping rule, and the two settles stop at different points.)"""
    props = CableProperties(length=20.0, mass_per_length=1.5, axial_stiffness=2e4,
                            diameter=0.03, material_density=5000.0,
                            normal_drag_coefficient=1.2, tangential_drag_coefficient=0.3,
                            added_mass_coefficient=1.0)
    ends = {}
    for integration in ("explicit", "implicit"):
        settings = DynamicSettings(elements=6, order=4, cfl=0.8, max_time_step=None,
                                   slack_filter=True, seabed_contact="implicit",
                                   time_integration=integration)
        dg = DynamicLine(props, settings, np.array([0.0, 0.0, -15.0]),
                         np.array([15.0, 0.0, -3.0]))
        report = dg.settle()
        assert report.converged, report
        ends[integration] = np.linalg.norm(dg.end_forces()[0])
    print(ends)
    assert abs(ends["implicit"] / ends["explicit"] - 1.0) <= SETTLE_RTOL


def test_deepcwind_lines_agree_with_explicit() -> None:
    case = load_case(REFERENCES / "deepcwind_lines_forced.toml",
                     ["lines.*.dynamic.elements=8", "lines.*.dynamic.order=3"])
    paths = xr.open_dataset(REFERENCES / "deepcwind_lc34_fairleads_600s.nc")
    keep = paths["time"].values <= 200.0
    t = paths["time"].values[keep]
    for ln in case.lines[:2]:  # line 3 mirrors line 1
        p = paths["fairlead_position"].sel(line=ln.name).values[keep]
        v = paths["fairlead_velocity"].sel(line=ln.name).values[keep]
        stats = {}
        for integration in ("explicit", "implicit"):
            line = dataclasses.replace(ln, fairlead=tuple(p[0]), dynamic=dataclasses.replace(
                ln.dynamic, time_integration=integration))
            dg = DynamicLine.from_case(line, case.environment, case.seabed)
            tension = np.linalg.norm(_run(dg, t, p, v), axis=1)[t >= 60.0]
            stats[integration] = np.array([tension.std(), tension.max()])
        rel = stats["implicit"] / stats["explicit"] - 1.0
        print(ln.name, stats, rel)
        assert np.all(np.abs(rel) <= DEEPCWIND_AGREEMENT)


@pytest.mark.slow
def test_snap_refines_the_step() -> None:
    """Lindahl snap case: the error control halves the implicit step through each snap, and
    the mean cycle maximum stays within the accuracy of the explicit run's."""
    case = load_case(CASES / "lindahl" / "lindahl_r0.20_T1.25.toml")
    maxima = {}
    ln = case.lines[0]
    t = np.arange(0.0, 15.0 + 1e-9, case.simulation.output_interval)
    path, vel = fairlead_state(case.motion, ln, t)
    for integration in ("explicit", "implicit"):
        line = dataclasses.replace(ln, dynamic=dataclasses.replace(
            ln.dynamic, time_integration=integration))
        dg = DynamicLine.from_case(line, case.environment, case.seabed)
        n = t.size
        ff, steps = np.zeros((n, 3)), np.zeros(n)
        dg.solve_path(t, path, vel, ff, np.zeros((n, 3)), np.zeros(n), steps)
        tension = np.linalg.norm(ff, axis=1)
        period = case.motion.period
        cycles = [tension[(t >= k * period) & (t < (k + 1) * period)].max()
                  for k in range(2, int(t[-1] / period))]
        maxima[integration] = float(np.mean(cycles))
        if integration == "implicit":
            assert steps.max() >= 4 * max(np.median(steps[1:]), 1.0)
    print(maxima)
    assert abs(maxima["implicit"] / maxima["explicit"] - 1.0) <= SNAP_AGREEMENT


def test_jumped_transition() -> None:
    """The rejection test of a step over the fairlead's slack-taut transition: it fires when
    the end node's strain crosses zero with more than the force tolerance on the taut side,
    or, slack at both ends, its Hermite interpolant rises into tension inside the step."""
    EA, tol, dt = 1e4, 1.0, 0.01
    # strain rates consistent with the change over the step
    assert ik._jumped_transition(-1e-3, 0.6, 5e-3, 0.6, dt, EA, tol)  # snap onset: 50 N
    assert not ik._jumped_transition(-1e-3, 0.105, 5e-5, 0.105, dt, EA, tol)  # 0.5 N: located
    assert ik._jumped_transition(5e-3, -0.6, -1e-3, -0.6, dt, EA, tol)  # release from 50 N
    assert not ik._jumped_transition(5e-3, 0.0, 6e-3, 0.0, dt, EA, tol)  # taut throughout
    assert not ik._jumped_transition(-1e-3, 0.0, -1e-3, 0.0, dt, EA, tol)  # slack throughout
    # slack at both ends, a snap inside: strain rising at 2 /s, falling at 2 /s (peak ~4e-3)
    assert ik._jumped_transition(-1e-3, 2.0, -1e-3, -2.0, dt, EA, tol)
    assert not ik._jumped_transition(-1e-3, 0.02, -1e-3, -0.02, dt, EA, tol)


def test_snap_after_slack_on_large_steps() -> None:
    """A hanging line (vacuum, 224 N at rest) whose fairlead dips 0.5 m towards the anchor and
    comes back within 0.3 s, on 50 ms samples and steps of at most 50 ms, then 1 ms samples:
    the line goes slack at the fairlead and snaps taut again; the snap peak of the implicit
    steps within SLACK_SNAP_AGREEMENT of the explicit steps' on the same elements. (The error
    estimate alone already resolves this snap, measured +0.55 %: the end of the step into the
    snap is taut; the event test adds the steps that start or end slack.)"""
    props = CableProperties(length=10.0, mass_per_length=1.5, axial_stiffness=1.5e4,
                            diameter=0.03, material_density=5000.0, water_density=0.0)
    x0, dip, span = 9.95, 0.5, 0.3
    t = np.r_[np.arange(0.0, span - 1e-9, 0.05), np.arange(span, span + 0.3 + 1e-9, 1e-3)]
    s = np.clip(t / span, 0.0, 1.0)
    path = np.zeros((t.size, 3))
    vel = np.zeros((t.size, 3))
    path[:, 0] = x0 - dip * np.sin(np.pi * s) ** 2
    vel[:, 0] = -dip * np.pi / span * np.sin(2.0 * np.pi * s) * (t < span)
    peaks = {}
    for integration in ("explicit", "implicit"):
        settings = DynamicSettings(elements=6, order=4, cfl=0.8,
                                   max_time_step=0.05 if integration == "implicit" else None,
                                   slack_filter=True, seabed_contact="implicit",
                                   time_integration=integration)
        line = DynamicLine(props, settings, np.zeros(3), np.array([x0, 0.0, 0.0]))
        line.settle()
        peaks[integration] = float(np.max(np.linalg.norm(_run(line, t, path, vel), axis=1)))
    print(peaks)
    assert peaks["explicit"] > 4.0 * 224.0  # a snap
    assert abs(peaks["implicit"] / peaks["explicit"] - 1.0) <= SLACK_SNAP_AGREEMENT


def test_newton_stopping_test() -> None:
    """Newton's stopping test: the correction within the tolerance, or, from the second
    iteration on, the error left in the iterate, eta |dx| with eta = theta / (1 - theta);
    near slack (strict) the correction only."""
    assert ik.newton_converged(1, 1.0, np.inf, 1.0, False)
    assert not ik.newton_converged(1, 1.5, np.inf, 1.0, False)  # the first: no estimate
    # theta = 0.01: eta = 1 / 99; 3.0 / 99 <= 1 ends the step, strict needs 3.0 <= 1
    assert ik.newton_converged(2, 3.0, 300.0, 1.0, False)
    assert not ik.newton_converged(2, 3.0, 300.0, 1.0, True)
    # theta = 0.5: eta = 1; 1.5 > 1
    assert not ik.newton_converged(2, 1.5, 3.0, 1.0, False)
    assert not ik.newton_converged(3, 0.9, 0.5, 0.5, False)  # growing: the correction only


#: The recorded paths' motion frequency (LC34's peak period 14.3 s) [rad/s].
LC34_FREQUENCY = 2.0 * np.pi / 14.3


def _deepcwind_line(name: str, near_slack: bool, end: float = 150.0):
    """DeepCwind line ``name`` at 8 x p3 on its recorded LC34 path up to ``end``, its snap
    window one period of the path's motion; ``near_slack``: every step counts as near slack
    (the snap tolerances and the strict Newton test throughout). The fairlead tension and the
    integrator's counters."""
    case = load_case(REFERENCES / "deepcwind_lines_forced.toml",
                     ["lines.*.dynamic.elements=8", "lines.*.dynamic.order=3",
                      'lines.*.dynamic.time_integration="implicit"'])
    with xr.open_dataset(REFERENCES / "deepcwind_lc34_fairleads_600s.nc") as paths:
        keep = paths["time"].values <= end
        t = paths["time"].values[keep]
        p = paths["fairlead_position"].sel(line=name).values[keep]
        v = paths["fairlead_velocity"].sel(line=name).values[keep]
    ln = next(x for x in case.lines if x.name == name)
    dg = DynamicLine.from_case(dataclasses.replace(ln, fairlead=tuple(p[0])), case.environment,
                               case.seabed)
    dg.implicit.ip[ik.IP_SNAP_WINDOW] = 2.0 * np.pi / LC34_FREQUENCY
    if near_slack:
        dg.implicit.ip[ik.IP_SLACK_STRAIN] = np.inf
    tension = np.linalg.norm(_run(dg, t, p, v), axis=1)[t >= 60.0]
    return tension, dg.implicit.cs.copy()


#: The step's smooth tolerance and Newton's estimate against the snap tolerances and the
#: strict test throughout, DeepCwind line 1 over 150 s (its ramp, one window at the snap
#: tolerances, then smooth): STD and maximum within 0.3 % (measured +0.10 % and +0.01 %),
#: a third of the accuracy; at most 0.8 times the steps and the Newton iterations (measured
#: 0.70 and 0.74).
SMOOTH_AGREEMENT_DEEPCWIND = 3e-3
SMOOTH_WORK_RATIO = 0.8


def test_smooth_motion_takes_the_smooth_tolerance() -> None:
    """Away from slack (DeepCwind line 1, never below 30 % of its pretension) the steps take
    the whole accuracy and Newton stops on its estimate: far fewer steps and iterations than
    with the snap tolerances throughout, and the same tension statistics."""
    smooth, cs = _deepcwind_line("line1", False)
    strict, cs_strict = _deepcwind_line("line1", True)
    for a, b in ((smooth.std(), strict.std()), (smooth.max(), strict.max())):
        assert abs(a / b - 1.0) <= SMOOTH_AGREEMENT_DEEPCWIND
    assert cs[ik.CS_STEPS] <= SMOOTH_WORK_RATIO * cs_strict[ik.CS_STEPS]
    assert cs[ik.CS_ITERATIONS] <= SMOOTH_WORK_RATIO * cs_strict[ik.CS_ITERATIONS]


def test_steps_equal_to_round_off_share_their_factors() -> None:
    """Sample times that are running sums of 50 ms differ in their last bits: the steps
    between them share one factored Newton matrix (a taut line on a smooth path: a handful of
    factorisations, where each new bit pattern of the step cost one)."""
    line = _taut_line("implicit", 0.05)
    t = np.concatenate(([0.0], np.cumsum(np.full(80, 0.05))))
    spans = np.diff(t)
    assert np.unique(spans).size > 3  # (the sums' round-off: several bit patterns)
    _, path, vel = _harmonic(t.size, t[-1])
    _run(line, t, path, vel)
    cs = line.implicit.cs
    assert cs[ik.CS_FACTORISATIONS] <= 0.1 * cs[ik.CS_STEPS]


def test_integrator_state_is_finite() -> None:
    """The integrator's state (checkpointed; a checkpoint holds finite values only) is finite
    when new and when forgotten, its unknown slack time included."""
    line = _taut_line("implicit")
    line.implicit.invalidate()
    assert np.all(np.isfinite(line.implicit.cs))
    assert line.implicit.cs[ik.CS_SLACK_TIME] == ik.SLACK_UNKNOWN
