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

A line over its accuracy is also probed at its own numerics on the path shifted by
:data:`NUDGE` of its length: a chain that goes slack and snaps can be so sensitive to its path
that this alone moves the statistics by more than :data:`SENSITIVE_SHARE` of the accuracy, and
then the difference of the two probes is not a discretisation error. Such a line is refined
by :data:`REFINEMENT` (an under-resolved chain can ring chaotically where a finer one does
not); one still that sensitive when the check gives up stops the run with a
:class:`LineSensitivityError` that says so, as does a coupled run's line (whose numerics are
not changed as the run goes).

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
from floatmoor.motion import ramp, ramp_rate, table_state

__all__ = ["LineAccuracy", "LineAccuracyError", "estimate_error", "checked_line", "describe",
           "estimate_error_along", "accuracy_error", "RunProbe", "NOT_YET_ESTIMATED",
           "PROBE_CYCLES", "JUDGED_CYCLES", "REFINEMENT", "MAX_REFINEMENTS",
           "LineSensitivityError", "NUDGE", "SENSITIVE_SHARE", "probe_end",
           "probe_frequency"]

#: Cycles of the motion run after its ramp in a probe: the first lets the start from rest
#: pass through the line (its axial and transverse waves cross a chain in well under a
#: cycle), the others are judged.
PROBE_CYCLES = 3
#: Cycles at the end of the probe over which the statistics are compared.
JUDGED_CYCLES = 2
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
    """

    line: str
    elements: int
    order: int
    std_error: float
    maxima_error: float
    accuracy: float
    refinements: int
    wall_time_s: float

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
                      length: float) -> LineSensitivityError:
    """The error stopping a run whose line's statistics move under a nudge of its path."""
    return LineSensitivityError(
        f"line '{line}' (dynamic): its fairlead tension is too sensitive to its path for the "
        f"accuracy check: shifting the path by {NUDGE * length:.2g} m moves the STD "
        f"{100 * sensitivity[0]:.3g} % and the mean cycle maximum {100 * sensitivity[1]:.3g} % "
        f"over {JUDGED_CYCLES} cycles, against an accuracy of {100 * accuracy:.3g} % (a chain "
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


def _onto_path(line: Line, time: NDArray[np.float64], path: NDArray[np.float64],
               velocity: NDArray[np.float64]) -> tuple[Line, NDArray[np.float64],
                                                        NDArray[np.float64], NDArray[np.float64]]:
    """A recorded path's probe (:func:`estimate_error_along`): ``line`` with its fairlead where
    the path starts, the probe's times from 0, and the path and velocity brought on over the
    first of the :data:`PROBE_CYCLES` cycles by the cosine ramp."""
    start = path[0]
    s = time - time[0]
    duration = (time[-1] - time[0]) / PROBE_CYCLES
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
    the :data:`PROBE_CYCLES` cycles ``time`` holds (:data:`SAMPLES_PER_CYCLE` samples each
    after its first) by the cosine ramp of the prescribed motions (docs/conventions.md). A
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
    return _relative_errors(tensions[0], tensions[1], settings.order)


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
    return _relative_differences(tensions[1], tensions[0])


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
        factor = (REFINEMENT if sensitive
                  else MARGIN * (error / accuracy) ** (1.0 / (order + 1)))
        raised = min(max(math.ceil(elements * factor), elements + 1), MAX_AUTO_ELEMENTS)
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


def describe(result: LineAccuracy) -> str:
    """One line of text: the line's numerics and its estimated errors."""
    raised = (f", raised {result.refinements} time{'s' if result.refinements > 1 else ''} "
              "from the rule's choice") if result.refinements else ""
    return (f"{result.line}: {result.elements} x p{result.order}{raised}; estimated error "
            f"{100 * result.estimated_error:.2g} % (STD {100 * result.std_error:.2g} %, mean "
            f"cycle maximum {100 * result.maxima_error:.2g} %) against {100 * result.accuracy:g} "
            f"% asked; checked in {result.wall_time_s:.2g} s")


#: The ``line_accuracy`` attribute of a coupled run's file until its lines are checked.
NOT_YET_ESTIMATED = ("not estimated yet: the lines whose elements the accuracy chose are "
                     "checked after the wave ramp and three wave periods")


class RunProbe:
    """The check of a coupled run's lines whose element count the accuracy chose, as the
    run goes (their fairlead path is known only then): from the first recorded sample after
    the wave ramp their fairlead positions are recorded for :data:`PROBE_CYCLES` periods; then
    each is probed along the spline through them (:func:`estimate_error_along`). A line over
    its accuracy stops the run (:func:`accuracy_error`); the run's numerics are not changed
    as it goes.

    Parameters
    ----------
    lines
        (index, line with its resolved settings) of the lines to check.
    environment, seabed
        The case's.
    start
        When the probe starts [s]: the end of the wave ramp.
    """

    def __init__(self, lines: list[tuple[int, Line]], environment: Environment, seabed: Seabed,
                 start: float) -> None:
        self.lines = lines
        self.environment = environment
        self.seabed = seabed
        omega = lines[0][1].dynamic.motion_frequency
        self.period = 2.0 * math.pi / omega
        self.start = float(start)
        self.end = self.start + PROBE_CYCLES * self.period
        self._time: list[float] = []
        self._positions: list[NDArray[np.float64]] = []
        #: the outcome per line, once checked
        self.results: tuple[LineAccuracy, ...] | None = None

    @classmethod
    def for_run(cls, lines: list[Line], models: list, environment: Environment,
                seabed: Seabed, ramp: float) -> "RunProbe | None":
        """The probe of a run's dynamic lines whose elements the accuracy chose (None when
        there are none, or no wave frequency to judge cycles by)."""
        chosen = [(i, replace(line, dynamic=models[i].settings))
                  for i, (line, model) in enumerate(zip(lines, models))
                  if isinstance(model, DynamicLine) and line.dynamic.elements is None
                  and model.settings.motion_frequency > 0.0]
        return cls(chosen, environment, seabed, ramp) if chosen else None

    @property
    def done(self) -> bool:
        """Whether the lines have been checked."""
        return self.results is not None

    def sample(self, time: float, fairleads: NDArray[np.float64]) -> None:
        """Take the run's recorded sample at ``time`` (fairlead positions (lines, 3) [m]);
        check the lines once the probe's window is recorded.

        Raises
        ------
        LineAccuracyError
            For the first line whose estimated error exceeds its accuracy.
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
        time = t0 + np.arange(PROBE_CYCLES * SAMPLES_PER_CYCLE + 1) * (
            self.period / SAMPLES_PER_CYCLE)
        results = []
        for k, (i, line) in enumerate(self.lines):
            path, velocity = table_state(recorded_t, recorded[:, k], time)
            std_error, maxima_error = estimate_error_along(
                line, self.environment, self.seabed, time, path, velocity)
            settings = line.dynamic
            if max(std_error, maxima_error) > settings.accuracy:
                sensitivity = path_sensitivity_along(line, self.environment, self.seabed, time,
                                                     path, velocity)
                if max(sensitivity) > SENSITIVE_SHARE * settings.accuracy:
                    raise sensitivity_error(line.name, sensitivity, settings.accuracy,
                                            line.length)
                raise accuracy_error(line.name, settings.elements, settings.order, std_error,
                                     maxima_error, settings.accuracy, 0)
            results.append(LineAccuracy(line.name, settings.elements, settings.order,
                                        std_error, maxima_error, settings.accuracy, 0,
                                        _time.perf_counter() - started))
        self.results = tuple(results)
