"""The DG line's numerics chosen from the accuracy asked (``[lines.dynamic] accuracy``).

Before the run, the discretisation: order ``AUTO_ORDER`` and enough nodes to resolve the
line's static shape and the transverse wave its fairlead motion drives,

    nodes = (BASE_NODES + NODES_PER_WAVELENGTH L / lambda_t) (REFERENCE_ACCURACY / accuracy)^a,

a = 1 / (p + 1),

the transverse wavelength lambda_t = 2 pi c_t / omega at the motion frequency omega
(``DynamicSettings.motion_frequency``) and the transverse wave speed c_t = sqrt(H / (m + m_a))
on the horizontal tension H of the line at rest (its quasi-static catenary). The DG error of
a smooth solution falls as h^(p + 1), hence the exponent. The two constants are calibrated on
the three references of issue 17 at 1 % (explicit 10 x p5 the reference; tests/data/references):

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
(implicit.py), and is switched to the explicit steps for good when, over consecutive
windows of the motion, the implicit steps' work exceeds what the explicit steps over the same
time would cost: when snaps or touchdown impacts hold the implicit step near the explicit one (the
Lindahl chain: implicit 2 to 4 times slower at any period), explicit steps are the cheaper
way to the same accuracy; when the motion is smooth against the axial wave (DeepCwind:
implicit steps of 0.05 to 0.5 s against 4 ms explicit) the implicit steps stay.

Lines of several sections (line systems) stay explicit, the implicit step is not built for
their joints, and keep the discretisation they had (``SYSTEM_ELEMENTS`` of order
``SYSTEM_ORDER`` per section): the rule's 6 x p3 sections put the clump line 6.05 % of its
tension range from converged MoorDyn (10 x p5: 2.16 %) and the lazy wave's joint 0.21 m off
(tests/peer/test_system_moordyn.py); the rule is not calibrated for joints, clumps and buoys.
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
#: The accuracy the two constants above were calibrated at (issue 17's default, 1 %).
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
    several sections, ``SYSTEM_ELEMENTS`` x ``SYSTEM_ORDER`` and explicit steps.

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
        return replace(settings, time_integration=(
            "explicit" if settings.time_integration == "auto" else settings.time_integration),
            elements=settings.elements if settings.elements is not None else SYSTEM_ELEMENTS,
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
#: Work of the kernels' operations in units of one right-hand side evaluation, measured on
#: 10 x p5 lines (right-hand side 8 us, Jacobian 35 us, banded factorisation 100 us, banded
#: solve 17 us, one process): an explicit SSP-RK3 step is three evaluations; an implicit Newton
#: iteration one evaluation and one solve; a factorisation the Jacobian and its LU, whose cost
#: grows with the bandwidth (~ p + 1) against the evaluation's.
EXPLICIT_STEP_WORK = 3.0
NEWTON_ITERATION_WORK = 1.0 + 17.0 / 8.0
JACOBIAN_WORK = 35.0 / 8.0
FACTOR_WORK_PER_NODE = 100.0 / 8.0 / 6.0
#: An implicit step also evaluates its error estimate: about one evaluation.
IMPLICIT_STEP_WORK = 1.0
#: Shortest window of simulated time over which the two are compared [s]; the window is
#: otherwise one period of the motion, so that a snap per cycle counts in every window.
MIN_WINDOW = 1.0
#: Consecutive windows in which the implicit steps must cost more before the line goes
#: explicit: a line that snaps every cycle (the Lindahl chain, the buoy's chains) does so in
#: every window, whereas one steep wave group does not make a sea state snap (DeepCwind LC34
#: line 2: one window of 14.3 s at 1.03 times the explicit work, 71 s into the run, among
#: windows at 0.2 to 0.6).
OVER_BUDGET_WINDOWS = 2
#: A window whose implicit work exceeds the explicit steps' by this factor switches the line at
#: once: the Lindahl chain's implicit steps cost 2 to 4 times the explicit ones at every period,
#: whereas the one steep wave group of LC34 line 2 came to 1.03 times.
CLEARLY_OVER_BUDGET = 1.5


def implicit_work(steps: float, iterations: float, factorisations: float, nodes: int) -> float:
    """Work of implicit steps in right-hand-side units (constants above)."""
    return (steps * IMPLICIT_STEP_WORK + iterations * NEWTON_ITERATION_WORK
            + factorisations * (JACOBIAN_WORK + FACTOR_WORK_PER_NODE * nodes))


def explicit_work(duration: float, explicit_step: float) -> float:
    """Work of the explicit steps over ``duration`` in right-hand-side units."""
    return math.ceil(duration / explicit_step) * EXPLICIT_STEP_WORK


@dataclass
class AutoIntegration:
    """The bookkeeping of ``time_integration = "auto"`` on one line: the window's start and the
    implicit counters there, and whether (and when) the line went explicit.

    Deterministic (counters, not wall time), so a resumed run switches where the original
    did; :meth:`state` and :meth:`set_state` carry it in checkpoints (same arrays before and
    after the switch, all finite).
    """

    window: float  #: [s]
    explicit_step: float  #: [s]
    nodes: int  #: nodes per element, p + 1
    window_start: float = 0.0  #: [s]
    counters: NDArray[np.float64] | None = None  #: ``CS_*`` counters at the window's start
    switched: bool = False  #: whether the line steps explicitly now
    switched_at: float = 0.0  #: when it went explicit [s]
    over: int = 0  #: consecutive windows whose implicit work exceeded the explicit steps'


    @classmethod
    def for_line(cls, motion_frequency: float, explicit_step: float,
                 nodes: int) -> "AutoIntegration":
        """The bookkeeping of a line driven at ``motion_frequency`` [rad/s]."""
        period = 2.0 * math.pi / motion_frequency if motion_frequency > 0.0 else 0.0
        return cls(max(MIN_WINDOW, period), explicit_step, nodes)

    def restart(self, time: float, counters: NDArray[np.float64]) -> None:
        """Start a window at ``time`` with the integrator's ``counters``."""
        self.window_start = time
        self.counters = counters.copy()

    def should_switch(self, time: float, counters: NDArray[np.float64]) -> bool:
        """At the end of a window: whether its implicit work exceeded the explicit steps' in
        ``OVER_BUDGET_WINDOWS`` consecutive windows, or by ``CLEARLY_OVER_BUDGET`` in this one (then the line is marked explicit and the
        caller switches); a new window starts otherwise. False inside a window."""
        if self.counters is None:
            self.restart(time, counters)
            return False
        elapsed = time - self.window_start
        if elapsed < self.window:
            return False
        d = counters - self.counters
        spent = implicit_work(d[_ik.CS_STEPS] + d[_ik.CS_REJECTED], d[_ik.CS_ITERATIONS],
                              d[_ik.CS_FACTORISATIONS], self.nodes)
        budget = explicit_work(elapsed, self.explicit_step)
        self.over = self.over + 1 if spent > budget else 0
        if self.over >= OVER_BUDGET_WINDOWS or spent > CLEARLY_OVER_BUDGET * budget:
            self.switched, self.switched_at = True, time
            return True
        self.restart(time, counters)
        return False

    def state(self) -> dict[str, NDArray[np.float64]]:
        """Checkpoint arrays."""
        started = self.counters is not None
        return {"auto_window": np.array([self.window_start, float(started),
                                         float(self.switched), self.switched_at,
                                         float(self.over)]),
                "auto_counters": (self.counters.copy() if started else np.zeros(_ik.CS_N))}

    def set_state(self, arrays: dict[str, NDArray[np.float64]]) -> None:
        """Restore :meth:`state`."""
        start, started, switched, at, over = (float(x) for x in arrays["auto_window"])
        self.window_start, self.switched, self.switched_at = start, switched != 0.0, at
        self.over = int(over)
        self.counters = (np.asarray(arrays["auto_counters"], dtype=float).copy()
                         if started != 0.0 else None)
