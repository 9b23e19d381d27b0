"""Forced-motion runs: every fairlead follows the prescribed motion, each line responds with
its chosen model, and the line forces are recorded.

A case with parts a forced-motion run would ignore (a ``[floater]`` and what goes with it) is
refused, not run without them: :func:`check_forced_case`.
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.case.schema import Case, Line, Simulation
from floatmoor.errors import CaseError, SolverError
from floatmoor.mooring.stepping import PathStepper
from floatmoor.motion.rigid_body import (body_motion_state, is_body_motion,
                                         prescribed_fairlead_state, start_line)
from floatmoor.simulation.assembly import assemble
from floatmoor.simulation.line_accuracy import (LineAccuracy, checked_line, describe,
                                                probe_frequency)
from floatmoor.simulation.groups import SingleLine, SystemGroup, body_point_line
from floatmoor.simulation.recorder import FLUSH_INTERVAL_S, Recorder
from floatmoor.simulation.validity import ValidityMonitor

__all__ = ["RunResult", "run_forced_motion", "check_forced_case", "check_line_accuracy",
           "output_times", "body_points_state"]

#: Output samples solved per chunk between progress reports and checks: large enough to make
#: the per-chunk Python overhead negligible, small enough to report progress every ~0.1 s.
CHUNK_SAMPLES = 2000

@dataclass(frozen=True)
class RunResult:
    """What a run produced: its results and how it went.

    Returned by :func:`run_forced_motion` and :func:`floatmoor.run_coupled` when a run
    completes; a run that fails or is interrupted raises instead, after writing its partial
    results to its output file if it has one.

    Attributes
    ----------
    dataset
        The results: the lines' (and the floater's) time series in SI units, with the case
        text, overrides, version and run status in the attributes
        (docs/guide/running.md#what-a-run-writes-and-prints).
    status
        ``"complete"`` (a run that stops early raises instead; its output file's ``status``
        attribute says why it stopped).
    wall_time_s
        Wall time of the run [s]: a forced run's from its set-up on, a coupled run's of its
        time loops (those of passes its lines' check restarted included).
    simulated_time_s
        Time of the last recorded sample [s].
    line_accuracy
        The a-posteriori check of each dynamic line whose numerics the accuracy chose
        (:class:`~floatmoor.simulation.line_accuracy.LineAccuracy`); empty when no line was
        checked.
    """

    dataset: xr.Dataset  #: the results (partial when the run stopped early)
    status: str  #: "complete", or why it stopped
    wall_time_s: float  #: [s]
    simulated_time_s: float  #: time of the last recorded sample [s]
    #: the a-posteriori check of each dynamic line whose numerics the accuracy chose
    line_accuracy: tuple[LineAccuracy, ...] = ()


def output_times(simulation: Simulation) -> NDArray[np.float64]:
    """Output times 0, dt, 2 dt, ... up to the duration (inclusive when it is a multiple) [s]."""
    n = int(np.floor(simulation.duration / simulation.output_interval * (1.0 + 1e-12))) + 1
    return np.arange(n) * simulation.output_interval


def shape_stride(case: Case) -> int:
    """Output samples between line-shape samples (0: no shapes)."""
    interval = case.simulation.shape_output_interval
    if interval is None:
        return 0
    return max(1, int(round(interval / case.simulation.output_interval)))


def check_forced_case(case: Case) -> None:
    """Refuse a case that a forced-motion run cannot run as asked.

    A forced-motion run moves the fairleads as ``[motion]`` prescribes (fixed without one);
    it has no floater, so a case with a ``[floater]`` (or the ``[hydro]``, ``[waves]``,
    ``[wind]``, ``[initial]`` or ``simulation.time_step`` of one) would run with those parts
    ignored and its fairleads fixed.

    Raises
    ------
    CaseError
        Naming the first such part and the function that runs the case.
    """
    parts = (("floater", "a [floater] table", case.floater is not None),
             ("hydro", "a [hydro] table", case.hydro is not None),
             ("waves", "a [waves] table", case.waves is not None),
             ("wind", "a [wind] table", case.wind is not None),
             ("initial", "an [initial] offset", any(v != 0.0 for v in case.initial_offset)),
             ("simulation.time_step", "a body time step",
              case.simulation.time_step is not None))
    for key, found, present in parts:
        if present:
            raise CaseError(case.source, key, "a case without a floater for run_forced_motion "
                            "(a case with a [floater] runs coupled: floatmoor.run_coupled, or "
                            "floatmoor.run_case, which picks the runner)", found)


def run_forced_motion(case: Case, *, output: str | Path | None = None,
                      progress: Callable[[float], None] | None = None,
                      flush_interval: float = FLUSH_INTERVAL_S) -> RunResult:
    """Run a forced-motion case.

    Parameters
    ----------
    case
        A validated case.
    output
        netCDF file written as the run goes (partial on failure or interruption), or None.
    progress
        Called with the simulated time after each chunk.
    flush_interval
        Wall time between partial writes [s].

    Raises
    ------
    CaseError
        For a case with a ``[floater]`` (see :func:`check_forced_case`); nothing is run.
    SolverError
        When a line has no valid state; the partial results are written first.
    KeyboardInterrupt
        Re-raised after writing the partial results.

    Warns
    -----
    ModelValidityWarning
        Once per condition, when a quasi-dynamic line leaves its model's range
        (:mod:`floatmoor.simulation.validity`); the messages are also in the dataset's
        ``validity_warnings`` attribute.
    """
    check_forced_case(case)
    times = output_times(case.simulation)
    start_wall = _time.perf_counter()
    system = assemble(case)
    models, groups = system.line_models, system.groups
    accuracy = check_line_accuracy(case, models)
    # every independent line a group of one: one chunk loop solves and records them all
    units = [SingleLine(i, m) for i, m in enumerate(models) if m is not None] + groups
    stride = shape_stride(case)
    attrs = {"line_accuracy": "\n".join(describe(a) for a in accuracy)} if accuracy else None
    recorder = Recorder(case, times, output, flush_interval,
                        shape_nodes=_shape_nodes(models, groups) if stride else None,
                        shape_stride=stride, prescribed=is_body_motion(case.motion),
                        chunk=CHUNK_SAMPLES, attrs=attrs)
    monitor = ValidityMonitor(case, body=False)
    with recorder.partial_on_failure():
        for start in range(0, times.size, CHUNK_SAMPLES):
            stop = min(start + CHUNK_SAMPLES, times.size)
            _solve_chunk(case, units, recorder, start, stop)
            off = recorder.offset  # the chunk's samples are still in the window
            monitor.check(times[start:stop],
                          recorder.series["fairlead_position"][:, start - off:stop - off])
            recorder.validity_warnings = monitor.messages()
            if progress is not None:
                progress(float(times[stop - 1]))
    dataset = recorder.result(status="complete")
    return RunResult(dataset=dataset, status="complete",
                     wall_time_s=_time.perf_counter() - start_wall,
                     simulated_time_s=recorder.simulated_time, line_accuracy=accuracy)


def check_line_accuracy(case: Case, models: list[PathStepper | None]
                        ) -> tuple[LineAccuracy, ...]:
    """Check every independent dynamic line whose element count the accuracy chose
    (:mod:`floatmoor.simulation.line_accuracy`) along its prescribed path, replacing in
    ``models`` those the check refined; lines under a still fairlead are not checked.

    Raises
    ------
    LineAccuracyError
        For a line whose numerics cannot be brought within its accuracy.
    """
    motion = case.motion
    if motion is None:
        return ()
    results = []
    for i, (line, model) in enumerate(zip(case.lines, models)):
        if model is None or not model.accuracy_checked or line.dynamic.elements is not None:
            continue
        # built as the run builds it: its fairlead where the motion starts
        resolved = replace(start_line(motion, line), dynamic=model.settings)
        table = getattr(motion, "time", None)  # a table's rows: the motion ends at the last
        omega = probe_frequency(resolved, None if table is None else float(table[-1]),
                                motion.ramp_duration)
        # probed over cycles of omega: shorter than the motion's when its table ends first
        probed = replace(resolved, dynamic=replace(resolved.dynamic, motion_frequency=omega))

        def path_state(t: NDArray[np.float64], line: Line = line
                       ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
            return prescribed_fairlead_state(motion, line, t)

        checked, result = checked_line(probed, case.environment, case.seabed, path_state,
                                       motion.ramp_duration)
        omega = model.settings.motion_frequency  # the run's, as the rule and its steps use
        checked = replace(checked, dynamic=replace(checked.dynamic, motion_frequency=omega))
        if checked.dynamic != model.settings:
            models[i] = type(model).from_case(checked, case.environment, case.seabed)
        results.append(result)
    return tuple(results)


def _shape_nodes(models: list[PathStepper | None], groups: list[SystemGroup]
                 ) -> list[NDArray[np.float64]]:
    """Arc lengths of every line's shape nodes: its model's, or its group's."""
    arcs = {i: g.arc_lengths[i] for g in groups for i in g.lines}
    return [m.arc_length if m is not None else arcs[i] for i, m in enumerate(models)]


def _solve_chunk(case: Case, units: list[SingleLine | SystemGroup], recorder: Recorder,
                 start: int, stop: int) -> None:
    """Solve samples [start, stop) of every independent line and group; on failure keep
    what every one completed (the others stop where the first failure did)."""
    t = recorder.time[start:stop]
    failure: SolverError | None = None
    limit = stop
    recorder.reserve(stop)
    off = recorder.offset  # sample k is at k - off in the recorder's arrays
    for unit in units:
        if limit <= start:
            break
        try:
            _solve_unit_chunk(case, unit, recorder, start, limit)
        except SolverError as err:
            failure = failure or err
            limit = start + unit.failed_index
    if recorder.prescribed is not None:
        x, dx = body_motion_state(case.motion, t[:limit - start])
        recorder.prescribed["prescribed_displacement"][start - off:limit - off] = x
        recorder.prescribed["prescribed_displacement_rate"][start - off:limit - off] = dx
    recorder.advance(limit)
    if failure is not None:
        raise failure


def _unit_path(case: Case, unit: SingleLine | SystemGroup, t: NDArray[np.float64]
               ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Positions and velocities (n, points, 3) of a unit's body points under the case's
    prescribed motion (each moves as the fairlead of its :meth:`path_lines` line)."""
    lines = unit.path_lines(case)
    pos = np.zeros((t.size, len(lines), 3))
    vel = np.zeros((t.size, len(lines), 3))
    for k, line in enumerate(lines):
        pos[:, k], vel[:, k] = prescribed_fairlead_state(case.motion, line, t)
    return pos, vel


def body_points_state(case: Case, names: list[str], t: NDArray[np.float64]
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Positions and velocities (n, points, 3) of the body points ``names`` under the case's
    prescribed motion (a body point moves as the fairlead of a line at it)."""
    pos = np.zeros((t.size, len(names), 3))
    vel = np.zeros((t.size, len(names), 3))
    for k, name in enumerate(names):
        pos[:, k], vel[:, k] = prescribed_fairlead_state(case.motion, body_point_line(case, name),
                                                         t)
    return pos, vel


def _solve_unit_chunk(case: Case, unit: SingleLine | SystemGroup, recorder: Recorder,
                      start: int, stop: int) -> None:
    """Solve samples [start, stop) of an independent line or a system group, in segments
    ending at the shape samples (whose shapes are then taken from the unit's state), and
    record them.

    Raises
    ------
    SolverError
        As the unit's solver, after recording the samples it solved
        (``unit.failed_index`` counts from ``start``).
    """
    t = recorder.time[start:stop]
    path, velocity = _unit_path(case, unit, t)
    samples = unit.empty_samples(t.size)
    stride = recorder.shape_stride
    cuts = {start, stop}
    if stride:
        cuts.update(k + 1 for k in range(start, stop) if k % stride == 0)
    bounds = sorted(cuts)
    done = start
    try:
        for a, b in zip(bounds[:-1], bounds[1:]):
            seg = slice(a - start, b - start)
            try:
                unit.solve_path(t[seg], path[seg], velocity[seg], samples.part(seg))
            except SolverError:
                done = a + unit.failed_index
                raise
            done = b
            if stride and (b - 1) % stride == 0:
                for i in unit.lines:
                    recorder.store_shape(i, (b - 1) // stride,
                                         *unit.line_shape(case, i, path[b - 1 - start]))
    finally:
        unit.store(case, recorder, samples, path, start, done)
        unit.failed_index = done - start
