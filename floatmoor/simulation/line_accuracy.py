"""The a-posteriori check of a dynamic line whose numerics were chosen from its accuracy.

The rule of :mod:`floatmoor.mooring.dg.resolution` chooses a line's elements before the run
from its static shape and transverse wavelength, calibrated on three lines; on lines unlike
them it can miss ``accuracy`` (docs/theory/dynamic_line.md#a-posteriori-error-check). Before a
forced-motion run, every independent dynamic line whose element count the rule chose is run
over a probe window (the motion's ramp, then :data:`PROBE_CYCLES` cycles) twice, along the
fairlead path the run will take: at the chosen numerics and with :data:`REFINEMENT` times the
elements. Over the last :data:`JUDGED_CYCLES` cycles the fairlead tension's standard deviation
and mean per-cycle maximum of the two are compared; with a DG error falling as h^(p+1), the
chosen numerics' error is the difference over 1 - REFINEMENT^-(p+1) (Richardson). When the
larger of the two exceeds ``accuracy``, the elements are raised by (error / accuracy)^(1/(p+1))
with :data:`MARGIN` and the check repeats; a line still over it after
:data:`MAX_REFINEMENTS` raises, or at :data:`~floatmoor.mooring.dg.resolution.MAX_AUTO_ELEMENTS`,
stops the run with a :class:`LineAccuracyError` naming the line and its estimate.

A coupled run's fairlead path is known only as the run goes: its lines are probed
(:class:`RunProbe`) along the path recorded over :data:`PROBE_CYCLES` wave periods after the
wave ramp, or :data:`IRREGULAR_PROBE_CYCLES` peak periods in an irregular sea (two periods of a
sea are too short a sample of it). A line over its accuracy is raised by the same rule, and
the run starts again from t = 0 with it (:class:`LineRefinement`), where it is probed again.

A line over its accuracy is also probed at its own numerics on the path shifted by
:data:`NUDGE` of its length: a chain that goes slack and snaps can be so sensitive to its path
that this alone moves the statistics by more than :data:`SENSITIVE_SHARE` of the accuracy, and
then the difference of the two probes is not a discretisation error. Such a line is refined
by :data:`REFINEMENT` (an under-resolved chain can ring chaotically where a finer one does
not); one still that sensitive when the check gives up stops the run with a
:class:`LineSensitivityError` that says so, as does a coupled run's line at once (its run is
not started again for it).

A motion without a ramp starts the run's statistics with its start from rest in the
motion's first pose (docs/guide/running.md#what-a-run-writes-and-prints), which the probe
repeats: all its :data:`PROBE_CYCLES` cycles are then judged (on the OC4 r-test's 25 s
motion table, the start-up puts 9 x p3 2 % off in STD, which the last two cycles do not see).
A motion table that ends before the probe's window (:func:`probe_end`) would leave the probe
judging a fairlead held at the table's last row, whose quiet ring-down says nothing of the
run's error. The probe's cycles are then shortened to end with the table (a table has no
period: they are windows; :func:`probe_frequency`), so the probe judges the motion the run
follows (a case's table reaches past its ramp: it covers the run, which is longer than the
ramp).
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import Environment, Line, Seabed
from floatmoor.errors import SolverError
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.mooring.dg.resolution import MAX_AUTO_ELEMENTS
from floatmoor.motion.fairlead import ramp, ramp_rate, table_state

__all__ = ["LineAccuracy", "LineAccuracyError", "estimate_error", "checked_line", "describe",
           "estimate_error_along", "accuracy_error", "RunProbe", "NOT_YET_ESTIMATED",
           "PROBE_CYCLES", "JUDGED_CYCLES", "REFINEMENT", "MAX_REFINEMENTS",
           "LineSensitivityError", "NUDGE", "SENSITIVE_SHARE", "probe_end",
           "probe_frequency", "IRREGULAR_PROBE_CYCLES", "LineRefinement", "probe_cycles",
           "raised_elements", "recorded_cycles", "describe_raises"]

#: Cycles of the motion run after its ramp in a probe: the first lets the start from rest
#: pass through the line (its axial and transverse waves cross a chain in well under a
#: cycle), the others are judged.
PROBE_CYCLES = 3
#: Cycles at the end of the probe over which the statistics are compared.
JUDGED_CYCLES = 2
#: Peak periods of a coupled run's probe in an irregular sea (the first brings the probe onto
#: the recorded path, the others are judged): two periods of a sea are too short a sample.
#: Measured on DeepCwind LC34 (3 h, 8 x p3 lines, line 1 probed from 34 starts 300 s apart):
#: the estimate over 2 judged periods scatters from 0.02 to 2.1 % (median 0.75 %, over the 1 %
#: accuracy from 10 starts, 1.7 % from the end of the ramp) about the 0.37 % that longer
#: windows converge to (its STD after the ramp is within 0.21 % of 16 x p3's, 0.33 % of
#: 10 x p5's); over 10, 20 and 30
#: judged periods its largest is 1.6, 1.1 and 0.60 %
#: (docs/theory/dynamic_line.md#a-posteriori-error-check).
IRREGULAR_PROBE_CYCLES = 31
#: Samples per cycle at which the probe records the fairlead tension: the per-cycle maximum
#: of a snap load is caught to within (pi / 256)^2 / 2 ~ 1e-4 of a sinusoid's peak.
SAMPLES_PER_CYCLE = 256
#: Elements of the comparison line over the checked line's (same order): the estimate is the
#: difference over 1 - 2^-(p+1), 1.07 at p = 3.
REFINEMENT = 2
#: Raises of the element count before the check gives up.
MAX_REFINEMENTS = 3
#: Extra elements over what (error / accuracy)^(1/(p+1)) asks, so a raise lands under the
#: accuracy rather than on it.
MARGIN = 1.2
#: Shift of a probe's whole fairlead path, as a share of the line's length, that tells the
#: path sensitivity of a snapping chain from discretisation error. A line that answers linearly
#: moves its statistics by about its static stiffness times the shift (the shipped chains:
#: below 1e-4); a chaotic one by percents (the moored buoy's line 1 probed after the wave ramp:
#: STD 2.7 %, mean cycle maximum 1.2 %; 1e-10 of the length is too small to reach its snaps
#: within the probe, docs/theory/dynamic_line.md#a-posteriori-error-check).
NUDGE = 1e-8
#: Share of the accuracy that the nudge alone may move a statistic before the two probes'
#: difference is no longer taken for a discretisation error.
SENSITIVE_SHARE = 0.5
#: Smallest STD against which an STD error is judged, as a share of the mean tension: a line
#: whose tension varies by less than this has no STD worth a relative error.
STD_FLOOR = 0.01
#: Slack on the comparison of a motion table's end with the probe's [s]: round-off of the
#: table's times.
TIME_SLACK = 1e-9


class LineAccuracyError(SolverError):
    """A dynamic line's numerics miss its accuracy and the check cannot refine them further.

    A :class:`~floatmoor.errors.SolverError`: the run stops before its first sample and the
    command exits with status 1 naming the line."""


class LineSensitivityError(LineAccuracyError):
    """A dynamic line's tension statistics move under a nudge of its path as much as under a
    refinement (a chaotic slack-taut regime), so its discretisation error cannot be judged."""


@dataclass(frozen=True)
class LineAccuracy:
    """The outcome of the check of one line.

    Attributes
    ----------
    line
        The line's name.
    elements, order
        The numerics the run uses.
    std_error, maxima_error
        Estimated relative errors of the fairlead tension's STD and mean per-cycle maximum
        at those numerics [-].
    accuracy
        The line's ``accuracy`` [-].
    refinements
        How many times the check raised the element count.
    wall_time_s
        Wall time the check took [s].
    raised_from
        In a coupled run, each element count the probe found over the accuracy and raised
        (restarting the run), with its estimated errors: (elements, STD error, mean cycle
        maximum error), the rule's choice first.
    """

    line: str
    elements: int
    order: int
    std_error: float
    maxima_error: float
    accuracy: float
    refinements: int
    wall_time_s: float
    raised_from: tuple[tuple[int, float, float], ...] = ()

    @property
    def estimated_error(self) -> float:
        """The larger of the two estimates [-]."""
        return max(self.std_error, self.maxima_error)


PathState = Callable[[NDArray[np.float64]], tuple[NDArray[np.float64], NDArray[np.float64]]]


def _probe_tension(line: Line, environment: Environment, seabed: Seabed,
                   time: NDArray[np.float64], path: NDArray[np.float64],
                   velocity: NDArray[np.float64]) -> NDArray[np.float64]:
    """Fairlead tension [N] of ``line`` (numerics resolved) along the path, from rest."""
    model = DynamicLine.from_case(line, environment, seabed)
    n = time.size
    ff, af = np.zeros((n, 3)), np.zeros((n, 3))
    laid, steps = np.zeros(n), np.zeros(n)
    model.solve_path(time, path, velocity, ff, af, laid, steps)
    return np.linalg.norm(ff, axis=1)


def _statistics(tension: NDArray[np.float64], cycles: int) -> tuple[float, float, float]:
    """Mean, STD and mean per-cycle maximum over the last ``cycles`` cycles of a probe."""
    judged = tension[-cycles * SAMPLES_PER_CYCLE - 1:-1].reshape(cycles, SAMPLES_PER_CYCLE)
    return float(judged.mean()), float(judged.std()), float(judged.max(axis=1).mean())


def _judged_cycles(ramp: float) -> int:
    """Cycles of a forced run's probe that are judged: without a ramp the run's statistics
    start with its start from rest, judged too (module docstring)."""
    return JUDGED_CYCLES if ramp > 0.0 else PROBE_CYCLES


def _relative_differences(a: NDArray[np.float64], b: NDArray[np.float64],
                          cycles: int = JUDGED_CYCLES) -> tuple[float, float]:
    """Relative differences (STD, mean cycle maximum) of probe ``a``'s statistics from probe
    ``b``'s over their last ``cycles`` cycles."""
    a_stats = _statistics(a, cycles)
    mean, std, maxima = _statistics(b, cycles)
    return (abs(a_stats[1] - std) / max(std, STD_FLOOR * abs(mean), 1e-300),
            abs(a_stats[2] - maxima) / max(abs(maxima), 1e-300))


def _nudged(path: NDArray[np.float64], length: float) -> NDArray[np.float64]:
    """The fairlead path shifted by :data:`NUDGE` of the line's length along x."""
    shifted = np.array(path, dtype=float)
    shifted[:, 0] += NUDGE * length
    return shifted


def sensitivity_error(line: str, sensitivity: tuple[float, float], accuracy: float,
                      length: float, cycles: int = JUDGED_CYCLES) -> LineSensitivityError:
    """The error stopping a run whose line's statistics move under a nudge of its path."""
    return LineSensitivityError(
        f"line '{line}' (dynamic): its fairlead tension is too sensitive to its path for the "
        f"accuracy check: shifting the path by {NUDGE * length:.2g} m moves the STD "
        f"{100 * sensitivity[0]:.3g} % and the mean cycle maximum {100 * sensitivity[1]:.3g} % "
        f"over {cycles} cycles, against an accuracy of {100 * accuracy:.3g} % (a chain "
        "snapping chaotically, docs/theory/dynamic_line.md#a-posteriori-error-check), so no "
        f"element count can be verified to it; set lines.{line}.dynamic.elements and order to "
        "run at numerics of your choice, and judge its statistics over many cycles or runs")


def _relative_errors(coarse: NDArray[np.float64], fine: NDArray[np.float64], order: int,
                     cycles: int = JUDGED_CYCLES) -> tuple[float, float]:
    """Estimated relative errors (STD, mean cycle maximum) of the coarse probe's tension from
    the two probes' last ``cycles`` cycles (module docstring)."""
    richardson = 1.0 - REFINEMENT ** -(order + 1.0)
    std_error, maxima_error = _relative_differences(coarse, fine, cycles)
    return std_error / richardson, maxima_error / richardson


def recorded_cycles(time: NDArray[np.float64]) -> int:
    """Cycles of a recorded path's probe whose times ``time`` hold :data:`SAMPLES_PER_CYCLE`
    samples a cycle after the first (:data:`PROBE_CYCLES`, or :data:`IRREGULAR_PROBE_CYCLES`
    in an irregular sea)."""
    return (np.asarray(time).size - 1) // SAMPLES_PER_CYCLE


def _onto_path(line: Line, time: NDArray[np.float64], path: NDArray[np.float64],
               velocity: NDArray[np.float64]) -> tuple[Line, NDArray[np.float64],
                                                        NDArray[np.float64], NDArray[np.float64]]:
    """A recorded path's probe (:func:`estimate_error_along`): ``line`` with its fairlead where
    the path starts, the probe's times from 0, and the path and velocity brought on over the
    first of the probe's cycles (:func:`recorded_cycles`) by the cosine ramp."""
    start = path[0]
    s = time - time[0]
    duration = (time[-1] - time[0]) / recorded_cycles(time)
    factor, rate = ramp(s, duration)[:, None], ramp_rate(s, duration)[:, None]
    at_start = replace(line, fairlead=(float(start[0]), float(start[1]), float(start[2])))
    return (at_start, s, start + factor * (path - start),
            factor * velocity + rate * (path - start))


def estimate_error_along(line: Line, environment: Environment, seabed: Seabed,
                         time: NDArray[np.float64], path: NDArray[np.float64],
                         velocity: NDArray[np.float64]) -> tuple[float, float]:
    """Estimated relative errors (STD, mean per-cycle maximum) of the fairlead tension of
    ``line`` at its resolved numerics along a fairlead path known only as a run goes (a coupled
    run's): two probes, at its elements and at :data:`REFINEMENT` times as many, each settled at
    rest with its fairlead where the path starts and brought onto the path over the first of
    the cycles ``time`` holds (:data:`SAMPLES_PER_CYCLE` samples each after its first; the
    others are judged) by the cosine ramp of the prescribed motions (docs/conventions.md). A
    probe cannot start from the run's own state instead: refined, its DG boundary and interface
    jumps would pull with twice the force (their lifting scales as 1 / h), a jolt of many times
    the tension on a stiff chain.
    """
    settings = line.dynamic
    at_start, s, ramped, ramped_velocity = _onto_path(line, time, path, velocity)
    tensions = []
    for k in (1, REFINEMENT):
        probe = replace(at_start, dynamic=replace(settings, elements=settings.elements * k))
        tensions.append(_probe_tension(probe, environment, seabed, s, ramped, ramped_velocity))
    return _relative_errors(tensions[0], tensions[1], settings.order, recorded_cycles(time) - 1)


def path_sensitivity_along(line: Line, environment: Environment, seabed: Seabed,
                           time: NDArray[np.float64], path: NDArray[np.float64],
                           velocity: NDArray[np.float64]) -> tuple[float, float]:
    """Relative changes (STD, mean per-cycle maximum) of the fairlead tension of ``line`` at its
    resolved numerics when the probe's path of :func:`estimate_error_along` is shifted by
    :data:`NUDGE` of the line's length (module docstring)."""
    tensions = []
    for shifted in (path, _nudged(path, line.length)):
        at_start, s, ramped, ramped_velocity = _onto_path(line, time, shifted, velocity)
        tensions.append(_probe_tension(at_start, environment, seabed, s, ramped,
                                       ramped_velocity))
    return _relative_differences(tensions[1], tensions[0], recorded_cycles(time) - 1)


def accuracy_error(line: str, elements: int, order: int, std_error: float,
                   maxima_error: float, accuracy: float, refinements: int) -> LineAccuracyError:
    """The error stopping a run whose line misses its accuracy, with what to set."""
    error = max(std_error, maxima_error)
    factor = MARGIN * (error / accuracy) ** (1.0 / (order + 1))
    advised = max(math.ceil(elements * factor), elements + 1)
    return LineAccuracyError(
        f"line '{line}' (dynamic): the fairlead tension's estimated error at {elements} "
        f"elements of order {order} is {100 * error:.3g} % (STD {100 * std_error:.3g} %, mean "
        f"cycle maximum {100 * maxima_error:.3g} %), over its accuracy of {100 * accuracy:.3g} "
        f"%, after {refinements} refinements of the rule's choice; set lines.{line}.dynamic."
        f"elements (about {advised} for order {order}, by the convergence rate) or a larger "
        "accuracy")


def _probe_path(line: Line, path_state: PathState, ramp: float
                ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Times, fairlead positions and velocities of a forced run's probe window: the ramp,
    then :data:`PROBE_CYCLES` cycles of :data:`SAMPLES_PER_CYCLE` samples."""
    period = 2.0 * math.pi / line.dynamic.motion_frequency
    n = int(math.ceil(ramp / period * SAMPLES_PER_CYCLE)) + PROBE_CYCLES * SAMPLES_PER_CYCLE
    time = np.arange(n + 1) * (period / SAMPLES_PER_CYCLE)
    path, velocity = path_state(time)
    return time, np.asarray(path, dtype=float), np.asarray(velocity, dtype=float)


def estimate_error(line: Line, environment: Environment, seabed: Seabed,
                   path_state: PathState, ramp: float) -> tuple[float, float]:
    """Estimated relative errors (STD, mean per-cycle maximum) of the fairlead tension of
    ``line`` at its resolved numerics, from a probe against :data:`REFINEMENT` times its
    elements (module docstring).

    Parameters
    ----------
    line
        A line of one section, its ``dynamic`` settings resolved (elements and order set) and
        ``motion_frequency`` > 0.
    environment, seabed
        The case's.
    path_state
        The fairlead's positions and velocities (n, 3) at times (n,) [m, m/s].
    ramp
        Duration of the motion's ramp [s].
    """
    settings = line.dynamic
    time, path, velocity = _probe_path(line, path_state, ramp)
    fine = replace(line, dynamic=replace(settings, elements=settings.elements * REFINEMENT))
    return _relative_errors(_probe_tension(line, environment, seabed, time, path, velocity),
                            _probe_tension(fine, environment, seabed, time, path, velocity),
                            settings.order, _judged_cycles(ramp))


def path_sensitivity(line: Line, environment: Environment, seabed: Seabed,
                     path_state: PathState, ramp: float) -> tuple[float, float]:
    """Relative changes (STD, mean per-cycle maximum) of the fairlead tension of ``line`` at its
    resolved numerics over the probe window of :func:`estimate_error` when its fairlead path is
    shifted by :data:`NUDGE` of the line's length (module docstring)."""
    time, path, velocity = _probe_path(line, path_state, ramp)
    shifted = _nudged(path, line.length)
    at_start = replace(line, fairlead=tuple(float(c) for c in shifted[0]))
    return _relative_differences(
        _probe_tension(at_start, environment, seabed, time, shifted, velocity),
        _probe_tension(line, environment, seabed, time, path, velocity), _judged_cycles(ramp))


def checked_line(line: Line, environment: Environment, seabed: Seabed,
                 path_state: PathState, ramp: float) -> tuple[Line, LineAccuracy]:
    """``line`` with numerics that meet its accuracy by the probe, and the check's outcome.

    ``line.dynamic`` must be resolved, with ``motion_frequency`` > 0; its element count is
    raised as the module docstring says.

    Raises
    ------
    LineAccuracyError
        When the estimate stays over the accuracy after :data:`MAX_REFINEMENTS` raises or at
        ``MAX_AUTO_ELEMENTS`` elements.
    """
    start = _time.perf_counter()
    settings = line.dynamic
    accuracy, order = settings.accuracy, settings.order
    refinements = 0
    while True:
        std_error, maxima_error = estimate_error(line, environment, seabed, path_state, ramp)
        error = max(std_error, maxima_error)
        elements = line.dynamic.elements
        if error <= accuracy:
            break
        sensitivity = path_sensitivity(line, environment, seabed, path_state, ramp)
        sensitive = max(sensitivity) > SENSITIVE_SHARE * accuracy
        if refinements == MAX_REFINEMENTS or elements >= MAX_AUTO_ELEMENTS:
            if sensitive:
                raise sensitivity_error(line.name, sensitivity, accuracy, line.length)
            raise accuracy_error(line.name, elements, order, std_error, maxima_error,
                                 accuracy, refinements)
        # a sensitive line's estimate is no convergence rate: refinement alone may calm it
        # (an under-resolved chain rings chaotically; S3 at 8 x p3, not at 13)
        raised = (min(elements * REFINEMENT, MAX_AUTO_ELEMENTS) if sensitive
                  else raised_elements(elements, order, error, accuracy))
        line = replace(line, dynamic=replace(line.dynamic, elements=raised))
        refinements += 1
    return line, LineAccuracy(line.name, elements, order, std_error, maxima_error, accuracy,
                              refinements, _time.perf_counter() - start)


def probe_end(ramp: float, motion_frequency: float) -> float:
    """When the probe of a forced run's line ends [s]: the motion's ramp and
    :data:`PROBE_CYCLES` cycles of 2 pi / ``motion_frequency`` (:func:`estimate_error`)."""
    return ramp + PROBE_CYCLES * 2.0 * math.pi / motion_frequency


def probe_frequency(line: Line, motion_end: float | None, ramp: float) -> float:
    """The frequency [rad/s] whose :data:`PROBE_CYCLES` cycles after the ramp the probe of
    ``line`` (settings resolved, ``motion_frequency`` > 0) runs along a motion ending at
    ``motion_end`` [s] (a table's last row, after ``ramp``; None for a motion without an end):
    the line's ``motion_frequency``, or for a table ending before those cycles, the frequency
    whose cycles end with it (module docstring)."""
    omega = line.dynamic.motion_frequency
    if motion_end is None or motion_end >= probe_end(ramp, omega) - TIME_SLACK:
        return omega
    return PROBE_CYCLES * 2.0 * math.pi / (motion_end - ramp)


def describe_raises(raised_from: tuple[tuple[int, float, float], ...]) -> str:
    """The earlier element counts of a coupled run's line and their estimates, as text."""
    return ", then ".join(f"{k} elements (estimated {100 * max(e_std, e_max):.2g} %: STD "
                          f"{100 * e_std:.2g} %, mean cycle maximum {100 * e_max:.2g} %)"
                          for k, e_std, e_max in raised_from)


def describe(result: LineAccuracy) -> str:
    """One line of text: the line's numerics and its estimated errors (and, in a coupled run,
    the element counts the probe raised and restarted the run from)."""
    raised = (f", raised {result.refinements} time{'s' if result.refinements > 1 else ''} "
              "from the rule's choice") if result.refinements else ""
    if result.raised_from:
        raised += (f" (from {describe_raises(result.raised_from)}, the run starting again "
                   "from t = 0 each time)")
    return (f"{result.line}: {result.elements} x p{result.order}{raised}; estimated error "
            f"{100 * result.estimated_error:.2g} % (STD {100 * result.std_error:.2g} %, mean "
            f"cycle maximum {100 * result.maxima_error:.2g} %) against {100 * result.accuracy:g} "
            f"% asked; checked in {result.wall_time_s:.2g} s")


#: The ``line_accuracy`` attribute of a coupled run's file until its lines are checked.
NOT_YET_ESTIMATED = ("not estimated yet: the lines whose elements the accuracy chose are "
                     "checked after the wave ramp and three wave periods (an irregular sea's: "
                     f"{IRREGULAR_PROBE_CYCLES} peak periods)")


def probe_cycles(irregular: bool) -> int:
    """Cycles of a coupled run's probe (the first brings the probe onto the recorded path, the
    others are judged): :data:`PROBE_CYCLES` wave periods in regular waves,
    :data:`IRREGULAR_PROBE_CYCLES` peak periods in an irregular sea."""
    return IRREGULAR_PROBE_CYCLES if irregular else PROBE_CYCLES


class LineRefinement(Exception):
    """A coupled run's probe found lines over their accuracy that can be refined: the run
    starts again from t = 0 with their raised element counts (not an error of the run).

    Attributes
    ----------
    elements
        Line index -> raised element count.
    raised_from
        Line index -> the earlier element counts and their estimates
        (:attr:`LineAccuracy.raised_from`), the one just rejected last.
    """

    def __init__(self, elements: dict[int, int],
                 raised_from: dict[int, tuple[tuple[int, float, float], ...]],
                 names: dict[int, str]) -> None:
        self.elements = elements
        self.raised_from = raised_from
        #: wall time of the stopped pass's time loop [s] (set by the run)
        self.loop_wall_s = 0.0
        super().__init__("; ".join(
            f"line '{names[i]}' raised from {raised_from[i][-1][0]} to {k} elements (estimated "
            f"{100 * max(raised_from[i][-1][1:]):.2g} % at {raised_from[i][-1][0]})"
            for i, k in elements.items()))


def raised_elements(elements: int, order: int, error: float, accuracy: float) -> int:
    """The element count a line over its accuracy is raised to: by (error / accuracy)^(1/(p+1))
    with :data:`MARGIN`, at least one more, at most
    :data:`~floatmoor.mooring.dg.resolution.MAX_AUTO_ELEMENTS`."""
    factor = MARGIN * (error / accuracy) ** (1.0 / (order + 1))
    return min(max(math.ceil(elements * factor), elements + 1), MAX_AUTO_ELEMENTS)


class RunProbe:
    """The check of a coupled run's lines whose element count the accuracy chose, as the
    run goes (their fairlead path is known only then): from the first recorded sample after
    the wave ramp their fairlead positions are recorded for ``cycles`` periods
    (:func:`probe_cycles`); then each is probed along the spline through them
    (:func:`estimate_error_along`). Lines over their accuracy are raised as a forced run's
    are (:func:`raised_elements`) and the run starts again from t = 0 with them
    (:class:`LineRefinement`), where they are probed again; a line still over it after
    :data:`MAX_REFINEMENTS` raises or at ``MAX_AUTO_ELEMENTS`` stops the run
    (:func:`accuracy_error`), as does a line sensitive to its path
    (:func:`sensitivity_error`).

    Parameters
    ----------
    lines
        (index, line with its resolved settings) of the lines to check.
    environment, seabed
        The case's.
    start
        When the probe starts [s]: the end of the wave ramp.
    cycles
        Periods recorded and probed (the first brings the probe onto the path).
    raised_from
        Line index -> the element counts earlier passes of the run raised, with their
        estimates (:attr:`LineAccuracy.raised_from`).
    """

    def __init__(self, lines: list[tuple[int, Line]], environment: Environment, seabed: Seabed,
                 start: float, cycles: int = PROBE_CYCLES,
                 raised_from: dict[int, tuple[tuple[int, float, float], ...]] | None = None
                 ) -> None:
        self.lines = lines
        self.environment = environment
        self.seabed = seabed
        omega = lines[0][1].dynamic.motion_frequency
        self.period = 2.0 * math.pi / omega
        self.start = float(start)
        self.cycles = int(cycles)
        self.end = self.start + self.cycles * self.period
        self.raised_from = dict(raised_from or {})
        self._time: list[float] = []
        self._positions: list[NDArray[np.float64]] = []
        #: the outcome per line, once checked
        self.results: tuple[LineAccuracy, ...] | None = None

    @classmethod
    def for_run(cls, lines: list[Line], models: list, environment: Environment,
                seabed: Seabed, ramp: float, *, irregular: bool = False,
                raised_from: dict[int, tuple[tuple[int, float, float], ...]] | None = None
                ) -> "RunProbe | None":
        """The probe of a run's dynamic lines whose elements the accuracy chose (None when
        there are none, or no wave frequency to judge cycles by). ``lines`` are the case's
        (their ``elements`` unset where the rule chose them), ``models`` the run's (their
        settings what the run uses, raised by earlier passes' probes)."""
        chosen = [(i, replace(line, dynamic=models[i].settings))
                  for i, (line, model) in enumerate(zip(lines, models))
                  if model is not None and model.accuracy_checked
                  and line.dynamic.elements is None]
        return (cls(chosen, environment, seabed, ramp, probe_cycles(irregular), raised_from)
                if chosen else None)

    @property
    def done(self) -> bool:
        """Whether the lines have been checked."""
        return self.results is not None

    def sample(self, time: float, fairleads: NDArray[np.float64]) -> None:
        """Take the run's recorded sample at ``time`` (fairlead positions (lines, 3) [m]);
        check the lines once the probe's window is recorded.

        Raises
        ------
        LineRefinement
            When lines exceed their accuracy and can be raised: the run starts again.
        LineAccuracyError
            For the first line whose estimated error exceeds its accuracy and that cannot be
            raised further (LineSensitivityError: that is too sensitive to its path).
        """
        if self.done or time < self.start - 1e-9 * max(1.0, self.start):
            return
        self._time.append(time)
        self._positions.append(np.array([fairleads[i] for i, _ in self.lines]))
        if time >= self.end:
            self._check()

    def _check(self) -> None:
        started = _time.perf_counter()
        recorded_t = np.asarray(self._time)
        recorded = np.asarray(self._positions)  # (samples, lines, 3)
        t0 = recorded_t[0]
        time = t0 + np.arange(self.cycles * SAMPLES_PER_CYCLE + 1) * (
            self.period / SAMPLES_PER_CYCLE)
        results, raised = [], {}
        for k, (i, line) in enumerate(self.lines):
            path, velocity = table_state(recorded_t, recorded[:, k], time)
            std_error, maxima_error = estimate_error_along(
                line, self.environment, self.seabed, time, path, velocity)
            settings = line.dynamic
            earlier = self.raised_from.get(i, ())
            error = max(std_error, maxima_error)
            if error > settings.accuracy:
                sensitivity = path_sensitivity_along(line, self.environment, self.seabed, time,
                                                     path, velocity)
                if max(sensitivity) > SENSITIVE_SHARE * settings.accuracy:
                    raise sensitivity_error(line.name, sensitivity, settings.accuracy,
                                            line.length, self.cycles - 1)
                if len(earlier) >= MAX_REFINEMENTS or settings.elements >= MAX_AUTO_ELEMENTS:
                    raise accuracy_error(line.name, settings.elements, settings.order,
                                         std_error, maxima_error, settings.accuracy,
                                         len(earlier))
                raised[i] = raised_elements(settings.elements, settings.order, error,
                                            settings.accuracy)
                self.raised_from[i] = (*earlier, (settings.elements, std_error, maxima_error))
            results.append(LineAccuracy(line.name, settings.elements, settings.order,
                                        std_error, maxima_error, settings.accuracy,
                                        len(earlier), _time.perf_counter() - started, earlier))
        if raised:
            raise LineRefinement(raised, {i: self.raised_from[i] for i in raised},
                                 {i: line.name for i, line in self.lines})
        self.results = tuple(results)
