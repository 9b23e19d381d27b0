"""The DG line's numerics chosen from the accuracy asked (``[lines.dynamic] accuracy``).

Before the run, the discretisation: order ``AUTO_ORDER`` and enough nodes to resolve the
line's static shape and the transverse wave its fairlead motion drives,

    nodes = (BASE_NODES + NODES_PER_WAVELENGTH L / lambda_t) (REFERENCE_ACCURACY / accuracy)^a,

a = 1 / (p + 1),

the transverse wavelength lambda_t = 2 pi c_t / omega at the motion frequency omega
(``DynamicSettings.motion_frequency``) and the transverse wave speed c_t = sqrt(H / (m + m_a))
on the horizontal tension H of the line at rest (its quasi-static catenary). The DG error of
a smooth solution falls as h^(p + 1), hence the exponent. The two constants are calibrated on
the three stored references at 1 % (explicit 10 x p5 the reference; tests/data/references):

- Lindahl chain, T = 1.25 s (L / lambda_t = 2.0, snaps): 40 to 48 nodes of order 3 or 4 keep
  the mean cycle maximum within 0.3 % of 10 x p5, 32 (8 x p3) move it by 0.9 %;
- DeepCwind LC34 lines (L / lambda_t = 0.6): 8 x p3 within 0.25 % of the converged tension,
  6 x p3 at 1.1 %;
- the moored buoy's chains (L / lambda_t = 1.4): 8 x p4 within 0.5 % (STD), 5 x p4 at 2.7 %.

Order 3: the explicit step falls as about 1 / p^2 (``reference.STABLE_STEP_FACTOR``), so at
equal accuracy order 3 cost the Lindahl chain 30 % of order 5's; the implicit step's banded
factorisation grows as p^3 per element.

During the run, the integration (``time_integration = "auto"``, :class:`AutoIntegration`): the
line starts implicit, whose step is bounded by the accuracy of the fairlead force
(implicit.py), and each window of the motion (a period) is stepped the way that costs less:
implicit windows whose steps' work, counted by the integrator and priced by operation costs
measured on the kernels, exceeds what the explicit steps over the same time would cost turn the
line explicit, and explicit windows are probed with implicit steps again, more rarely while the
probes come out dearer. When snaps or touchdown impacts hold the implicit step near the
explicit one (the Lindahl chain: implicit 2 to 4 times dearer at any period), explicit steps
are the cheaper way to the same accuracy; when the motion is smooth against the axial wave
(DeepCwind: implicit steps of 0.05 to 0.5 s against 4 ms explicit) the implicit steps stay;
a motion that turns from one to the other gets the other within ``MAX_PROBE_GAP`` windows.

Lines of several sections (line systems) keep the discretisation they had
(``SYSTEM_ELEMENTS`` of order ``SYSTEM_ORDER`` per section) and the time integration their
sections ask for (a system of "auto" sections chooses window by window as one:
``DynamicSystem``): the rule's 6 x p3 sections put the clump line 6.05 % of its
tension range from converged MoorDyn (10 x p5: 2.16 %) and the lazy wave's joint 0.21 m off
(tests/simulation/test_system_moordyn.py); the rule is not calibrated for joints, clumps and buoys.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg import _implicit_kernels as _ik

__all__ = ["AUTO_ORDER", "BASE_NODES", "NODES_PER_WAVELENGTH", "REFERENCE_ACCURACY",
           "MIN_ELEMENTS", "MAX_AUTO_ELEMENTS", "auto_nodes", "resolve_settings",
           "AutoIntegration", "implicit_work", "explicit_work"]

#: Polynomial order of an automatic discretisation (module docstring).
AUTO_ORDER = 3
#: Nodes a line's static shape (catenary, touchdown) needs at the reference accuracy: 6 x p3
#: (24 nodes) held the DeepCwind lines within 1.1 % (module docstring).
BASE_NODES = 24
#: Further nodes per transverse wavelength along the line at the reference accuracy: 10
#: puts the Lindahl chain at 44 nodes (measured: 40 to 48 within 0.3 % of 10 x p5).
NODES_PER_WAVELENGTH = 10
#: The accuracy the two constants above were calibrated at (the default, 1 %).
REFERENCE_ACCURACY = 0.01
#: Elements and order per section of a line of several sections (module docstring).
SYSTEM_ELEMENTS, SYSTEM_ORDER = 10, 5
#: Fewest elements of an automatic discretisation: one element cannot hold a touchdown.
MIN_ELEMENTS = 2
#: Most elements of an automatic discretisation per line: at 0.1 % the rule asks for about
#: twice its 1 % nodes; beyond 32 elements of order 3 ask for them explicitly.
MAX_AUTO_ELEMENTS = 32


def auto_nodes(length: float, transverse_speed: float, motion_frequency: float,
               accuracy: float, order: int = AUTO_ORDER) -> float:
    """Nodes the rule of the module docstring asks for (before rounding to elements).

    Parameters
    ----------
    length
        Unstretched line length L [m].
    transverse_speed
        c_t [m/s]; 0 for a line with no tension to carry transverse waves.
    motion_frequency
        omega [rad/s]; 0 when no motion is declared (the static shape only).
    accuracy
        Relative error of the fairlead tension accepted [-].
    order
        Polynomial order p.
    """
    waves = 0.0
    if motion_frequency > 0.0 and transverse_speed > 0.0:
        waves = length * motion_frequency / (2.0 * math.pi * transverse_speed)
    scale = (REFERENCE_ACCURACY / accuracy) ** (1.0 / (order + 1))
    return (BASE_NODES + NODES_PER_WAVELENGTH * waves) * scale


def resolve_settings(settings: DynamicSettings, length: float, transverse_speed: float, *,
                     several_sections: bool = False) -> DynamicSettings:
    """``settings`` with the elements and order chosen from its accuracy where the case left
    them out (a given ``elements`` or ``order`` is kept: it overrides the rule); on a line of
    several sections, ``SYSTEM_ELEMENTS`` x ``SYSTEM_ORDER`` (its time integration kept).

    Parameters
    ----------
    settings
        A line's or section's ``[lines.dynamic]``.
    length
        Length of what ``settings`` discretise (the line, or the section) [m].
    transverse_speed
        Transverse wave speed on the line at rest [m/s] (:func:`auto_nodes`).
    several_sections
        Whether the line has several sections (module docstring).
    """
    if several_sections:
        return replace(
            settings, elements=settings.elements if settings.elements is not None else SYSTEM_ELEMENTS,
            order=settings.order if settings.order is not None else SYSTEM_ORDER)
    order = settings.order if settings.order is not None else AUTO_ORDER
    elements = settings.elements
    if elements is None:
        nodes = auto_nodes(length, transverse_speed, settings.motion_frequency,
                           settings.accuracy, order)
        elements = min(max(math.ceil(nodes / (order + 1) - 1e-9), MIN_ELEMENTS),
                       MAX_AUTO_ELEMENTS)
    return replace(settings, elements=int(elements), order=int(order))


# -- the run-time choice of "auto" -------------------------------------------------------------
#: Work of the kernels' operations in units of one right-hand side evaluation (``A`` of the
#: implicit kernels), measured with numba loops of each kernel on DeepCwind line 2 (CPU time,
#: one process; rhs 3.2 us at 8 x p3, 5.4 us at 10 x p5):
#:
#: ========  ===========  ==============  =====  ==================================
#: K x p     explicit     Jacobian + LU   solve  implicit run: model / measured CPU
#: ========  ===========  ==============  =====  ==================================
#: 8 x p3    3.54         8.0             1.09   1.01 (120 s of LC34)
#: 12 x p3   3.50         8.9             1.19   0.94
#: 8 x p4    3.52         10.4            1.20   1.10
#: 10 x p5   3.45         16.2            1.63   1.04
#: ========  ===========  ==============  =====  ==================================
#:
#: An explicit step is the three SSP-RK3 stages with the slack filter and the backward-Euler
#: internal damping solve; an implicit Newton iteration one evaluation and one banded solve,
#: whose cost grows as the bandwidth (~ p + 1) against the evaluation's; a factorisation the
#: Jacobian and its LU, growing as (p + 1)^2 against it. (The constants before were guessed from
#: 10 x p5 and put the implicit steps of the p3 lines at 1.75 times their cost against the
#: explicit ones: DeepCwind line 2 went explicit although implicit was 3.3 times cheaper.)
EXPLICIT_STEP_WORK = 3.5
NEWTON_ITERATION_WORK = 1.0
SOLVE_WORK_PER_NODE = 0.27
FACTOR_WORK_PER_NODE_SQUARED = 0.5
#: An implicit attempt also copies the state, interpolates the fairlead and evaluates its
#: error estimate: the remainder of the measured runs' CPU time after the operations above is
#: 1.8 to 1.9 evaluations per attempt. Checked again after the end state's A came from the
#: step's equation and Newton's stopping test changed (DeepCwind lines 1 and 2 alone, 600 s,
#: best of 3): the model prices their implicit runs, against their explicit ones, at 0.96 and
#: 0.95 of the measured CPU ratio (a factorisation measures 9 evaluations where the model
#: counts 8; an attempt 2.1 where it counts 1.9).
IMPLICIT_STEP_WORK = 1.9
#: Shortest window of simulated time over which the two are compared [s]; the window is
#: otherwise one period of the motion, so that a snap per cycle counts in every window.
MIN_WINDOW = 1.0
#: Consecutive windows in which the implicit steps must cost more before the line goes
#: explicit: one steep wave group does not make a sea state snap, whereas a line that snaps
#: every cycle (the Lindahl chain, the buoy's chains) does so in every window.
OVER_BUDGET_WINDOWS = 2
#: A window whose implicit work exceeds the explicit steps' by this factor switches the line at
#: once: the Lindahl chain's implicit windows (12 x p3, T = 1.25 s) cost 5 to 9 times the
#: explicit steps' from the first on, whereas DeepCwind line 2's dearest window on its LC34
#: path (the steep wave group 188 s in) costs 2.0 times, between windows at 0.1 to 0.9.
CLEARLY_OVER_BUDGET = 3.0
#: Explicit windows are probed again with implicit steps (a window that started implicit
#: again), first after one explicit window, then after twice as many as before each time the
#: probe comes out dearer, at most this many: a motion that turns smooth (a storm that abates)
#: is back on implicit steps within this many windows, and a probe that fails costs about one
#: window's explicit work (below), 1 / 8 of the explicit run's at the longest gap.
MAX_PROBE_GAP = 8
#: A probe window (the first window of a run is one too) is checked this many times: as soon as
#: its implicit work exceeds what the explicit steps of the whole window cost, or
#: ``CLEARLY_OVER_BUDGET`` times what they cost up to the check, the rest of the window steps
#: explicitly. On the Lindahl chain (12 x p3, T = 1.25 s, implicit 5 to 9 times dearer) a probe
#: so fails at its first check and costs 0.2 to 0.3 of a window's explicit work beside the
#: explicit steps it replaces; with 8 checks (and a first window stepped implicitly through)
#: the 10 s snap benchmark's time loop cost 1.44 times the explicit steps', with 32 checks 1.03
#: (docs/validation/performance.md). The probes' results do not depend on the count: the
#: implicit steps span sample intervals, and a check only ends a kernel call at a sample.
PROBE_CHECKS = 32


def implicit_work(steps: float, iterations: float, factorisations: float, nodes: int) -> float:
    """Work of implicit steps (``steps`` attempts, accepted and rejected) in right-hand-side
    units (constants above); ``nodes`` per element, p + 1."""
    return (steps * IMPLICIT_STEP_WORK
            + iterations * (NEWTON_ITERATION_WORK + SOLVE_WORK_PER_NODE * nodes)
            + factorisations * FACTOR_WORK_PER_NODE_SQUARED * nodes * nodes)


def explicit_work(duration: float, explicit_step: float) -> float:
    """Work of the explicit steps over ``duration`` in right-hand-side units."""
    return math.ceil(duration / explicit_step - 1e-9) * EXPLICIT_STEP_WORK


@dataclass
class AutoIntegration:
    """The bookkeeping of ``time_integration = "auto"`` on one line, window by window of the
    motion: whether the window steps implicitly or explicitly, and when to try implicit again.

    A window stepped implicitly is compared, at its end, with the explicit steps over the same
    time (:func:`implicit_work` from the integrator's counters against :func:`explicit_work`);
    dearer in ``OVER_BUDGET_WINDOWS`` consecutive windows, or by ``CLEARLY_OVER_BUDGET`` in one,
    the line steps explicitly from the next window on. The first window, and while explicit
    every ``gap``-th window, is a probe: it starts implicit, stays implicit if its implicit
    work stays within the window's explicit work, and goes explicit for the rest of the window
    as soon as it does not or is clearly dearer so far (checked ``PROBE_CHECKS`` times per
    window), doubling the gap up to ``MAX_PROBE_GAP``. (A line that snaps from the start so
    pays for a few checks of implicit steps, not a whole window of them.)

    Deterministic (counters, not wall time), so a resumed run switches where the original
    did; :meth:`state` and :meth:`set_state` carry it in checkpoints.
    """

    window: float  #: [s]
    explicit_step: float  #: [s]
    nodes: int  #: nodes per element, p + 1
    window_start: float = 0.0  #: [s]
    counters: NDArray[np.float64] | None = None  #: ``CS_*`` counters at the window's start
    switched: bool = False  #: whether the line steps explicitly now
    switched_at: float = 0.0  #: when it last went explicit [s]
    over: int = 0  #: consecutive implicit windows whose work exceeded the explicit steps'
    probing: bool = False  #: whether the current window is a probe
    gap: int = 1  #: explicit windows between a probe that came out dearer and the next one
    wait: int = 0  #: explicit windows left before the next probe
    switches: int = 0  #: how many times the line went explicit
    explicit_windows: int = 0  #: windows that ended explicit (a failed probe among them)
    check_at: float = 0.0  #: a probe's next check [s]

    @classmethod
    def for_line(cls, motion_frequency: float, explicit_step: float,
                 nodes: int) -> "AutoIntegration":
        """The bookkeeping of a line driven at ``motion_frequency`` [rad/s]."""
        period = 2.0 * math.pi / motion_frequency if motion_frequency > 0.0 else 0.0
        return cls(max(MIN_WINDOW, period), explicit_step, nodes, probing=True)

    def restart(self, time: float, counters: NDArray[np.float64]) -> None:
        """Start a window at ``time`` with the integrator's ``counters``."""
        self.window_start = time
        self.counters = counters.copy()
        self.check_at = time + self.window / PROBE_CHECKS

    def next_check(self) -> float:
        """Simulated time of the next decision [s]: the window's end, or, in a probe still
        stepping implicitly, its next check."""
        end = self.window_start + self.window
        return min(end, self.check_at) if self.probing and not self.switched else end

    def segment_end(self, time: NDArray[np.float64], i0: int, shape_every: int,
                    counters: NDArray[np.float64]) -> int:
        """Last sample of a kernel call from sample ``i0`` of ``time``: the first sample at or
        after the next decision (:meth:`next_check`; a first call starts the first window at
        ``time[i0]`` with the integrator's ``counters``), on a shape sample when shapes are
        recorded every ``shape_every`` samples (so their records keep their slots)."""
        if self.counters is None:
            self.restart(float(time[i0]), counters)
        k = int(np.searchsorted(time, self.next_check(), side="left"))
        if shape_every > 0:
            k = -(-k // shape_every) * shape_every
        return min(max(k, i0 + 1), time.size - 1)

    def _spent(self, counters: NDArray[np.float64]) -> float:
        """Implicit work since the window's start."""
        def d(i: int) -> float:  # (the counters only: other slots hold states)
            return float(counters[i] - self.counters[i])
        return implicit_work(d(_ik.CS_STEPS) + d(_ik.CS_REJECTED), d(_ik.CS_ITERATIONS),
                             d(_ik.CS_FACTORISATIONS), self.nodes)

    def _go_explicit(self, time: float) -> None:
        self.switched, self.switched_at, self.switches = True, time, self.switches + 1

    def _probe_failed(self, time: float, rest: int) -> None:
        """A probe came out dearer: explicit, and the next probe ``gap`` windows later (plus
        ``rest``, this window's rest)."""
        self._go_explicit(time)
        self.probing = False
        self.gap = min(2 * self.gap, MAX_PROBE_GAP)
        self.wait = self.gap + rest

    def update(self, time: float, counters: NDArray[np.float64]) -> bool:
        """At ``time`` [s], with the integrator's ``counters``: end the window if it is over
        (choosing the next one's integration), or stop a probe already dearer than the whole
        window's explicit steps; whether the line changes between implicit and explicit steps
        now (the caller then switches). A first call starts the first window."""
        if self.counters is None:
            self.restart(time, counters)
            return False
        was = self.switched
        elapsed = time - self.window_start
        if elapsed < self.window * (1.0 - 1e-9):  # inside a window: only a probe is checked
            if not self.probing or self.switched or time < self.check_at:
                return False
            while self.check_at <= time:
                self.check_at += self.window / PROBE_CHECKS
            spent = self._spent(counters)
            if (spent > explicit_work(self.window, self.explicit_step)
                    or spent > CLEARLY_OVER_BUDGET * explicit_work(elapsed, self.explicit_step)):
                self._probe_failed(time, 1)  # (the rest of this window is explicit too)
            return self.switched != was
        spent = self._spent(counters)
        budget = explicit_work(elapsed, self.explicit_step)
        if self.switched:  # an explicit window (or a probe that went explicit)
            self.explicit_windows += 1
            self.probing = False
            self.wait -= 1
            if self.wait <= 0:
                self.switched, self.probing = False, True
        elif self.probing and spent > budget:
            self._probe_failed(time, 0)
        elif self.probing:  # within the explicit work to its end: implicit again
            self.probing, self.gap, self.over = False, 1, 0
        else:
            self.over = self.over + 1 if spent > budget else 0
            if self.over >= OVER_BUDGET_WINDOWS or spent > CLEARLY_OVER_BUDGET * budget:
                self._go_explicit(time)
                self.over, self.wait = 0, self.gap
        self.restart(time, counters)
        return self.switched != was

    def state(self) -> dict[str, NDArray[np.float64]]:
        """Checkpoint arrays."""
        started = self.counters is not None
        return {"auto_window": np.array([
                    self.window_start, float(started), float(self.switched), self.switched_at,
                    float(self.over), float(self.probing), float(self.gap), float(self.wait),
                    float(self.switches), float(self.explicit_windows), self.check_at]),
                "auto_counters": (self.counters.copy() if started else np.zeros(_ik.CS_N))}

    def set_state(self, arrays: dict[str, NDArray[np.float64]]) -> None:
        """Restore :meth:`state`."""
        (start, started, switched, at, over, probing, gap, wait, switches, windows,
         check) = (float(x) for x in arrays["auto_window"])
        self.window_start, self.switched, self.switched_at = start, switched != 0.0, at
        self.over, self.probing, self.gap, self.wait = int(over), probing != 0.0, int(gap), int(wait)
        self.switches, self.explicit_windows, self.check_at = int(switches), int(windows), check
        self.counters = (np.asarray(arrays["auto_counters"], dtype=float).copy()
                         if started != 0.0 else None)
