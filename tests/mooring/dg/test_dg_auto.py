"""``time_integration = "auto"`` (floatmoor.mooring.dg.resolution.AutoIntegration): each window
of the motion stepped implicitly or explicitly, whichever its measured work says is cheaper;
explicit windows probed with implicit steps again (docs/theory/dynamic_line.md)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import xarray as xr

from floatmoor.case.load import load_case
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.motion.fairlead import fairlead_state
from tests.conftest import LINDAHL_CASE, REPO


pytestmark = pytest.mark.verification

REFERENCES = REPO / "tests" / "data" / "references"
#: Lindahl snap case, auto against explicit on the same elements: mean of the cycle maxima
#: after the ramp. The snaps scatter ~1 % from cycle to cycle (any change of the state
#: reshuffles them: test_unchanged_dynamic.py), and auto's first period is implicit (its
#: accuracy 1 %): within 1 %.
SNAP_AGREEMENT = 0.01


def _run(dg: DynamicLine, t, path, vel) -> np.ndarray:
    n = t.size
    ff = np.zeros((n, 3))
    dg.solve_path(t, path, vel, ff, np.zeros((n, 3)), np.zeros(n), np.zeros(n))
    return ff


def _lindahl(integration: str, duration: float = 10.0):
    case = load_case(LINDAHL_CASE)
    ln = case.lines[0]
    line = dataclasses.replace(ln, dynamic=dataclasses.replace(  # the accuracy's 12 x p3
        ln.dynamic, elements=None, order=None, time_integration=integration))
    t = np.arange(0.0, duration + 1e-9, case.simulation.output_interval)
    path, vel = fairlead_state(case.motion, ln, t)
    return DynamicLine.from_case(line, case.environment, case.seabed), t, path, vel, case


def test_snapping_line_goes_explicit() -> None:
    """The Lindahl chain at T = 1.25 s snaps every cycle: the implicit steps shrink to near the
    explicit ones through each snap, so auto switches at the first check of its first window
    (a probe), its later probes come out dearer, and it matches the explicit run."""
    maxima = {}
    for integration in ("auto", "explicit"):
        dg, t, path, vel, case = _lindahl(integration)
        tension = np.linalg.norm(_run(dg, t, path, vel), axis=1)
        period = case.motion.period
        start = case.motion.ramp_duration + period
        maxima[integration] = np.mean([tension[(t >= s) & (t < s + period)].max()
                                       for s in np.arange(start, t[-1] - period + 1e-9, period)])
        if integration == "auto":  # 8 windows: the first a probe, then probes 2 and 4 on
            assert dg.auto.switches >= 2 and dg.auto.explicit_windows >= 6, dg.auto
    print(maxima)
    assert abs(maxima["auto"] / maxima["explicit"] - 1.0) <= SNAP_AGREEMENT


def test_resume_across_the_switches_is_bit_identical() -> None:
    """The choice follows the integrator's counters, not the wall clock: a line restored from
    a state saved in its first window (a probe gone explicit), in an explicit window, in a
    probe, or in a later explicit window goes on to the same bits as the uninterrupted one."""
    whole, t, path, vel, _ = _lindahl("auto", 6.0)
    full = _run(whole, t, path, vel)
    assert whole.auto.switches >= 2
    for cut in (1.0, 2.0, 2.7, 4.4):
        k = int(np.searchsorted(t, cut))
        first, *_ = _lindahl("auto", 6.0)
        _run(first, t[:k + 1], path[:k + 1], vel[:k + 1])
        second, *_ = _lindahl("auto", 6.0)
        second.set_state_arrays(first.state_arrays())
        rest = _run(second, t[k:], path[k:], vel[k:])
        assert rest.tobytes() == full[k:].tobytes(), cut
        assert second.auto.state()["auto_window"].tobytes() == whole.auto.state()[
            "auto_window"].tobytes()


def _deepcwind_line2(integration: str, frequency: float):
    case = load_case(REFERENCES / "deepcwind_lines_forced.toml")
    ln = case.lines[1]
    return case, dataclasses.replace(ln, dynamic=dataclasses.replace(
        ln.dynamic, time_integration=integration, motion_frequency=frequency))


def test_smooth_lines_stay_implicit() -> None:
    """DeepCwind line 2 on its recorded LC34 fairlead path (600 s): implicit steps of tens of
    explicit ones, 3.3 times cheaper in CPU time, so auto never switches (with the work
    priced by guessed constants it went explicit 180 s in), and its windows (separate kernel
    calls) change no bit of the implicit run."""
    with xr.open_dataset(REFERENCES / "deepcwind_lc34_fairleads_600s.nc") as paths:
        t = paths["time"].values
        p = paths["fairlead_position"].sel(line="line2").values
        v = paths["fairlead_velocity"].sel(line="line2").values
    out, settled = {}, None
    for integration in ("auto", "implicit"):
        case, line = _deepcwind_line2(integration, 2 * np.pi / 14.3)
        dg = DynamicLine.from_case(dataclasses.replace(line, fairlead=tuple(p[0])),
                                   case.environment, case.seabed)
        if settled is None:  # auto settles explicitly: the implicit run starts there too
            settled = dg.r.copy()
        dg.r[:] = settled
        out[integration] = _run(dg, t, p, v)
        if integration == "auto":
            assert not dg.auto.switched and dg.auto.switches == 0
    assert out["auto"].tobytes() == out["implicit"].tobytes()


def test_snapping_then_smooth_goes_back_to_implicit() -> None:
    """DeepCwind line 2 surging 20 m at T = 10 s (it goes slack and snaps at 7.5 times its
    pretension; implicit 2.6 times dearer than explicit there) for 60 s, then 2 m: auto steps
    the snaps explicitly (its first window, a probe like the later ones, goes explicit when
    the snaps start in the ramp, 6.5 s in; the probe at 30 s is found dearer within its
    first check) and, probing again at 80 s, is back on implicit steps for the smooth
    motion."""
    period, split, end = 10.0, 60.0, 130.0
    omega = 2.0 * np.pi / period
    case, line = _deepcwind_line2("auto", omega)
    t = np.arange(0.0, end + 1e-9, 0.5)
    x = np.clip((t - split) / period, 0.0, 1.0)  # 20 m to 2 m over one period, C1
    amp, damp = 20.0 - 18.0 * (3 * x**2 - 2 * x**3), -18.0 * (6 * x - 6 * x**2) / period
    y = np.clip(t / period, 0.0, 1.0)  # and a C1 ramp from rest
    ramp, dramp = 3 * y**2 - 2 * y**3, (6 * y - 6 * y**2) / period
    surge = ramp * amp * np.sin(omega * t)
    speed = (ramp * (amp * omega * np.cos(omega * t) + damp * np.sin(omega * t))
             + dramp * amp * np.sin(omega * t))
    fair, anchor = np.array(line.fairlead), np.array(line.anchor)
    d = np.array([fair[0] - anchor[0], fair[1] - anchor[1], 0.0])
    d /= np.linalg.norm(d)
    dg = DynamicLine.from_case(line, case.environment, case.seabed)
    n = t.size
    ff, steps = np.zeros((n, 3)), np.zeros(n)
    dg.solve_path(t, fair + surge[:, None] * d, speed[:, None] * d, ff, np.zeros((n, 3)),
                  np.zeros(n), steps)
    explicit_per_sample = 0.5 / dg.auto.explicit_step
    assert dg.auto.switches >= 1 and not dg.auto.switched, dg.auto
    for a, b in ((7.0, 30.0), (31.0, 80.0)):  # explicit
        assert steps[(t > a) & (t <= b)].min() >= 0.99 * explicit_per_sample, (a, b)
    # implicit (8 to 29 steps; the first sample, 36, starts from the smallest step)
    assert steps[t > 80.5].max() < 0.25 * explicit_per_sample
    assert dg.auto.switches == 2 and dg.auto.explicit_windows == 8


def test_coupled_advance_stops_at_an_explicit_windows_end() -> None:
    """A coupled run's one-call advance (``DynamicLine.plain_steps_until``) must hand a window's
    end to ``solve_path`` in explicit windows too: a probe may start implicit steps there (it
    used to run explicit windows through, so a coupled line never came back to implicit)."""
    dg, t, path, vel, case = _lindahl("auto", duration=0.1)
    auto = dg.auto
    auto.restart(0.0, dg.implicit.cs)
    auto.switched = True  # an explicit window [0, window)
    assert dg.plain_steps_until(0.5 * auto.window) is False
    assert dg.plain_steps_until(auto.window) is None
    auto.switched, auto.probing = False, True  # a probe: checked at each eighth
    assert dg.plain_steps_until(0.5 * auto.next_check()) is True
    assert dg.plain_steps_until(auto.next_check()) is None
