"""Coupled runs of a case with a floater: waves, the Cummins body on its lines, recorded and
written as the run goes (the coupling scheme is in :mod:`.coupled`). The floater's
radiation memory is the convolution of K(t) or, with ``[floater] radiation = "state-space"``,
the database's state-space realisation (whose states are in the checkpoint with the body's)."""

from __future__ import annotations

import time as _time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from floatmoor.body.kinematics import points_state
from floatmoor.case.coupling import CoupledCase
from floatmoor.case.schema import Case, Line
from floatmoor.case.sea import RegularWaveSettings, StillWaterSettings, WaveSettings
from floatmoor.errors import CaseError, SolverError
from floatmoor.io.netcdf3_format import NetCDF3Error
from floatmoor.io.output_files import OutputWriteError
from floatmoor.simulation.checkpoint import (
    CheckpointError, RunIdentity, check_checkpoint, read_checkpoint, remove_stale_temporaries,
    write_checkpoint,
)
from floatmoor.simulation.assembly import CoupledSettings, assemble, settings_from_case
from floatmoor.simulation.coupled import MooredBody
from floatmoor.simulation.forced import RunResult, output_times, shape_stride
from floatmoor.simulation.line_accuracy import (NOT_YET_ESTIMATED, LineRefinement, RunProbe,
                                                describe, describe_raises)
from floatmoor.simulation.recorder import FLUSH_INTERVAL_S, Recorder
from floatmoor.simulation.validity import ValidityMonitor
from floatmoor.signals import deferred_interrupts
from floatmoor.waves.synthesis import harmonic_sum

__all__ = ["CoupledSettings", "run_coupled", "check_coupled_case", "settings_from_case"]

#: Body steps per chunk between progress reports, partial writes and finiteness checks.
CHUNK_STEPS = 500

#: Default wall time between checkpoints of a run with an output file [s] (written at the
#: end of the first chunk that ends this long after the last one, and once at the start): a
#: hard kill (SIGKILL, out of memory, power cut) loses at most this and one chunk. Measured
#: on the buoy case (2 shared cores under a load of 14): the state written and flushed and
#: the folder flushed take 40 ms a checkpoint (quasi-static and dynamic lines alike; 157 kB
#: for quasi-static lines), 0.4 % of the run at this interval; appending the samples since
#: the last write adds 40 to 60 ms, but the partial writes every FLUSH_INTERVAL_S (the same
#: 10 s) append them anyway (docs/guide/running.md#checkpoints).
CHECKPOINT_INTERVAL_S = 10.0


def irregular_sea(waves: WaveSettings) -> bool:
    """Whether a run's waves are an irregular sea, whose probe records
    :data:`~floatmoor.simulation.line_accuracy.IRREGULAR_PROBE_CYCLES` peak periods."""
    return not isinstance(waves, (RegularWaveSettings, StillWaterSettings))


def checkpoint_path(output: str | Path) -> Path:
    """The checkpoint file of a run writing ``output``."""
    return Path(str(output) + ".checkpoint")


@dataclass(frozen=True)
class _Snapshot:
    """The run's state at the end of a chunk: body and lines (copies of their state arrays,
    which later steps do not touch), body steps done and output samples complete. With the
    samples before ``n_done`` (written to the output file before the checkpoint, and never
    rewritten) it is a consistent state to resume from, whenever the run stops."""

    state: dict[str, NDArray]
    done: int
    n_done: int

    @classmethod
    def take(cls, moored: MooredBody, recorder: Recorder, done: int) -> "_Snapshot":
        return cls(moored.state_arrays(), done, recorder.n_done)


#: The checkpoint's array of the element counts of the lines a probe raised (0: the line as
#: the case gives or the rule chooses it): a resumed run is built with them.
RAISED_ELEMENTS = "progress/raised_elements"


def _write_checkpoint(path: Path, snapshot: _Snapshot, recorder: Recorder,
                      identity: RunIdentity, raised: NDArray[np.int64]) -> None:
    """Write ``snapshot`` atomically, as plain arrays
    (:mod:`floatmoor.simulation.checkpoint`), after the samples it covers are in the output
    file and on disk: the checkpoint holds the state, the file the samples, which a resumed
    run continues (cut to the checkpoint's samples). Killed or cut off at any moment, the
    run leaves a checkpoint that its file covers. ``raised``: :data:`RAISED_ELEMENTS`."""
    if recorder.written < snapshot.n_done:
        recorder.write(status=f"running: partial results up to "
                              f"t = {recorder.simulated_time:.6g} s")
    recorder.sync()
    arrays = {f"state/{k}": v for k, v in snapshot.state.items()}
    arrays["progress/done"] = np.array(snapshot.done, dtype=np.int64)
    arrays["progress/n_done"] = np.array(snapshot.n_done, dtype=np.int64)
    arrays[RAISED_ELEMENTS] = np.asarray(raised, dtype=np.int64)
    write_checkpoint(path, arrays, identity)


def _raised_elements(path: Path, identity: RunIdentity, n_lines: int) -> dict[int, int]:
    """The element counts of the lines the probe of the checkpoint's run raised (line index
    -> elements): the resumed run keeps the numerics its checkpoint was made with."""
    raised = read_checkpoint(path, identity, {RAISED_ELEMENTS: ((n_lines,), np.int64)},
                             exact=False)[RAISED_ELEMENTS]
    if np.any(raised < 0):
        raise CheckpointError(path, "element counts >= 0 in array "
                              f"'{RAISED_ELEMENTS}'", str(raised.tolist()))
    return {i: int(k) for i, k in enumerate(raised) if k > 0}


def _with_elements(case: Case, raised: dict[int, int]) -> Case:
    """``case`` with the element counts the probe raised (line index -> elements); the
    order stays the one the case gives or the rule chooses (which does not depend on the
    elements)."""
    if not raised:
        return case
    return replace(case, lines=tuple(
        replace(line, dynamic=replace(line.dynamic, elements=raised[i])) if i in raised
        else line for i, line in enumerate(case.lines)))


def _load_checkpoint(path: Path, identity: RunIdentity, moored: MooredBody,
                     recorder: Recorder, stride: int, n_steps: int) -> int:
    """Restore the checkpoint ``path`` into ``moored`` and continue the recorder's output
    file from the samples it covers (both built as for a fresh start); returns the body
    steps done.

    Raises
    ------
    CheckpointError
        When the checkpoint is not one of this run (see :func:`read_checkpoint`), its
        progress is not a state this run reaches, or the output file is not this run's or
        holds fewer samples than the checkpoint covers.
    """
    int64 = np.dtype(np.int64)
    progress = read_checkpoint(path, identity, {"progress/done": ((), int64),
                                                "progress/n_done": ((), int64)}, exact=False)
    done, n = int(progress["progress/done"]), int(progress["progress/n_done"])
    if not (0 <= done <= n_steps and n == done // stride + 1):
        raise CheckpointError(path, f"a state of this run (body steps done: 0 to {n_steps}, "
                              f"output samples done: steps // {stride} + 1)",
                              f"{done} steps and {n} samples done")
    template = {f"state/{k}": v for k, v in moored.state_arrays().items()}
    template.update(progress)
    template[RAISED_ELEMENTS] = np.zeros(len(recorder.case.lines), dtype=np.int64)
    arrays = read_checkpoint(path, identity, {k: (v.shape, v.dtype)
                                              for k, v in template.items()})
    try:
        recorder.continue_file(n)
    except (NetCDF3Error, OutputWriteError) as err:
        raise CheckpointError(recorder.path, "the output file of the checkpoint's run, which "
                              "the resumed run continues (run without --resume to start "
                              "over)", str(err)) from None
    moored.set_state_arrays({k[len("state/"):]: v for k, v in arrays.items()
                             if k.startswith("state/")})
    return done


def check_coupled_case(case: Case) -> None:
    """Refuse a case that a coupled run cannot run as asked: one without a ``[floater]`` (no
    body to couple; its fairleads would stay fixed) or with a ``[motion]`` (the floater's
    motion follows from its dynamics; a prescribed one would be ignored).

    Raises
    ------
    CaseError
        Naming the part and the function that runs the case.
    """
    if case.floater is None:
        raise CaseError(case.source, "floater", "a case with a [floater] for run_coupled (a "
                        "case without one runs in forced motion: floatmoor.run_forced_motion, "
                        "or floatmoor.run_case, which picks the runner)", "none")
    if case.motion is not None:
        raise CaseError(case.source, "motion", "no [motion] in a case run by run_coupled (the "
                        "floater's motion follows from its dynamics)", "a [motion] table")


def run_coupled(case: Case, settings: CoupledSettings | None = None, *,
                output: str | Path | None = None,
                progress: Callable[[float], None] | None = None,
                flush_interval: float = FLUSH_INTERVAL_S,
                checkpoint_interval: float | None = None, resume: bool = False) -> RunResult:
    """Run a case with a floater on its lines, in waves.

    With ``output``, a checkpoint (``OUTPUT.checkpoint``, the whole state of body and lines
    at the end of a chunk of steps) is written at the start, then at the end of the first
    chunk that ends ``checkpoint_interval`` seconds of wall time after the last one (default
    :data:`CHECKPOINT_INTERVAL_S`; 0: every chunk), each after the samples it covers are in
    the output file and on disk, so that a hard kill (SIGKILL, out of memory, power cut)
    loses at most that interval and a chunk; an interrupted run writes one of the end of its
    last complete chunk. ``resume=True``
    continues from the checkpoint and gives the same results as an uninterrupted run (the
    checkpoint holds plain arrays, checked against this run before use:
    :mod:`floatmoor.simulation.checkpoint`), appending to the same output file (which must
    be there: it holds the samples the checkpoint covers; any written after them are
    replaced). A failed run removes its checkpoint (resumed, it would fail again); a
    completed one removes it too. With ``simulation.shape_output_interval`` the lines'
    shapes are recorded too.

    ``settings`` (default :func:`settings_from_case`) gives the options the case does not:
    another database file, additional linear or quadratic damping.

    Parameters
    ----------
    case
        A validated case with a ``[floater]`` (and its ``[hydro]``), without ``[motion]``.
    settings
        Options beyond the case (:class:`~floatmoor.simulation.assembly.CoupledSettings`),
        or None for a plain run of the case.
    output
        netCDF file written as the run goes (partial on failure or interruption), or None
        (then no checkpoint either).
    progress
        Called with the simulated time [s] after each chunk of steps.
    flush_interval
        Wall time between partial writes of ``output`` [s].
    checkpoint_interval
        Wall time between checkpoints [s]; None for :data:`CHECKPOINT_INTERVAL_S`, 0 for
        every chunk.
    resume
        Continue from ``OUTPUT.checkpoint`` instead of starting at t = 0.

    Returns
    -------
    RunResult
        The dataset (body motion and line forces, SI units), the wall and simulated times
        [s] and the check of the lines whose numerics the accuracy chose.

    Raises
    ------
    CaseError
        For a case without a ``[floater]``, or with a ``[motion]`` (see
        :func:`check_coupled_case`); nothing is run.
    HydroDatabaseError
        When the case's database is missing, damaged, stale or fails a check the case does
        not accept (:func:`floatmoor.hydro.database.load_for_case`).
    ValueError
        For a ``checkpoint_interval`` that is not a number >= 0 s; nothing is run.
    CheckpointError
        With ``resume``: no checkpoint, or one that is damaged, truncated, foreign or of
        another run (the message names what differs), or an output file that is missing,
        not this run's or shorter than the checkpoint; nothing is run or written.
    SolverError
        When a line or the body goes unstable (partial results written first).
    KeyboardInterrupt
        Re-raised after writing the partial results.

    Warns
    -----
    ModelValidityWarning
        Once per condition, when the floater's rotations or heave or a quasi-dynamic line
        leave their models' range (:mod:`floatmoor.simulation.validity`); the messages are
        also in the dataset's ``validity_warnings`` attribute.
    """
    check_coupled_case(case)
    if checkpoint_interval is None:
        checkpoint_interval = CHECKPOINT_INTERVAL_S
    if not checkpoint_interval >= 0.0:  # NaN too
        raise ValueError(f"checkpoint_interval must be >= 0 s, not {checkpoint_interval}")
    if settings is None:
        settings = settings_from_case(case)
    identity = RunIdentity.of(case.text, case.overrides, repr(settings), case.source)
    ckpt = checkpoint_path(output) if output is not None else None
    if resume:
        if ckpt is None:
            raise CheckpointError("--resume", "a run with an output file (its checkpoint is "
                                  "OUTPUT.checkpoint)", "no output")
        check_checkpoint(ckpt, identity)  # before the set-up: the file, its format and run
    raised = _raised_elements(ckpt, identity, len(case.lines)) if resume else {}
    raised_from: dict[int, tuple[tuple[int, float, float], ...]] = {}
    earlier_loops = 0.0  # [s] time loops of the passes the probe stopped
    while True:  # a pass per raise of the lines' elements by the probe (up to MAX_REFINEMENTS)
        try:
            return _run_pass(_with_elements(case, raised), case.lines, settings, identity,
                             raised, raised_from, output=output, progress=progress,
                             flush_interval=flush_interval,
                             checkpoint_interval=checkpoint_interval, resume=resume,
                             earlier_loops=earlier_loops)
        except LineRefinement as refined:
            earlier_loops += refined.loop_wall_s
            # the aborted pass's checkpoint is not of the run that starts now
            if ckpt is not None:
                ckpt.unlink(missing_ok=True)
            raised.update(refined.elements)
            raised_from.update(refined.raised_from)
            restarted = getattr(progress, "restarted", None)
            if restarted is not None:
                restarted(f"{refined}: the run starts again from t = 0")


def _run_pass(case: Case, rule_lines: tuple[Line, ...], settings: CoupledSettings,
              identity: RunIdentity, raised: dict[int, int],
              raised_from: dict[int, tuple[tuple[int, float, float], ...]], *,
              output: str | Path | None, progress: Callable[[float], None] | None,
              flush_interval: float, checkpoint_interval: float, resume: bool,
              earlier_loops: float) -> RunResult:
    """One pass of :func:`run_coupled` from t = 0 (or its checkpoint) of ``case``: the case
    with the element counts ``raised`` by the probes of earlier passes (whose estimates are
    ``raised_from``); ``rule_lines`` are the case's own lines (those whose elements the rule
    chose are probed). The result's wall time is the time loop's, ``earlier_loops`` [s] (the
    earlier passes') included.

    Raises
    ------
    LineRefinement
        When the probe raises lines' elements: the output file is left to the next pass,
        which rewrites it from its start.
    """
    ckpt = checkpoint_path(output) if output is not None else None
    view = CoupledCase.of(case)
    dt = view.time_step
    times = output_times(case.simulation)
    stride = view.steps_per_output
    system = assemble(case, settings)
    moored, loads = system.moored, system.loads
    body, x_eq = moored.body, system.equilibrium
    sea, centre = system.sea, moored.centre
    n_lines = len(case.lines)
    stride_shapes = shape_stride(case)
    # the lines whose elements the accuracy chose are checked as the run goes (not resumed:
    # a resumed run keeps what its file says of them)
    probe = None if resume else RunProbe.for_run(
        list(rule_lines), moored.models, case.environment, case.seabed,
        view.waves.ramp_duration, raised_from=raised_from,
        irregular=irregular_sea(view.waves.settings))
    not_yet = NOT_YET_ESTIMATED + "".join(
        f"\nline '{rule_lines[i].name}': raised to {raised[i]} elements from "
        f"{describe_raises(history)}; the run started again from t = 0"
        for i, history in raised_from.items())
    attrs = {**system.second_order, **({} if probe is None else {"line_accuracy": not_yet})}
    recorder = Recorder(case, times, output, flush_interval, body=True, equilibrium=x_eq,
                        shape_nodes=moored.shape_arc_lengths() if stride_shapes else None,
                        shape_stride=stride_shapes, chunk=CHUNK_STEPS // stride + 1,
                        attrs=attrs or None, second_order=loads.second_order is not None)
    elements = np.array([raised.get(i, 0) for i in range(len(case.lines))], dtype=np.int64)
    series, bseries = recorder.series, recorder.body
    n_steps = (times.size - 1) * stride
    done = 0
    if resume:
        done = _load_checkpoint(ckpt, identity, moored, recorder, stride, n_steps)
    monitor = ValidityMonitor(case, body=True, carried=recorder.validity_warnings)
    checked = recorder.n_done  # samples the monitor has seen: from the first (or the resumed)

    def record(index: int) -> None:
        ff, af = moored.line_forces(body.x, body.v)
        pos, _ = points_state(body.x, body.v, moored.arms, centre)
        k = index - recorder.offset  # in the recorder's window
        for i in range(n_lines):
            series["fairlead_force"][i, k] = ff[i]
            series["anchor_force"][i, k] = af[i]
            series["fairlead_position"][i, k] = pos[i]
            series["laid_length"][i, k] = moored.laid_length[i]
        for group, sample in zip(moored.groups, moored.group_samples(body.x, body.v)):
            recorder.store_group(case, group, sample, index, index + 1)
        bseries["body_displacement"][k] = body.x - x_eq
        bseries["body_velocity"][k] = body.v
        if loads.second_order is not None:
            bseries["second_order_force"][k] = loads.second_order_force(float(times[index]))
        if probe is not None and not probe.done:
            probe.sample(float(times[index]), pos)
            if probe.done:
                recorder.set_attribute("line_accuracy",
                                       "\n".join(describe(r) for r in probe.results))
        if recorder.shape_stride and index % recorder.shape_stride == 0:
            for i, (p, t) in enumerate(moored.line_shapes(pos)):
                recorder.store_shape(i, index // recorder.shape_stride, p, t)

    # the incident elevation at the reference point, filled per chunk of output samples
    elevation = sea.complex_elevation(centre[0], centre[1]) if sea.n_components else None

    def fill_elevation(first: int, last: int) -> None:
        if elevation is not None and last >= first:
            off = recorder.offset
            bseries["wave_elevation"][first - off:last + 1 - off] = harmonic_sum(
                elevation, sea.omega, times[first:last + 1])

    start_wall = _time.perf_counter()
    last_ckpt = start_wall
    snapshot: _Snapshot | None = None  # the last consistent state

    def checkpoint_last() -> None:
        if ckpt is not None and snapshot is not None:
            with deferred_interrupts():  # a second Ctrl-C must not cut it
                _write_checkpoint(ckpt, snapshot, recorder, identity, elements)

    if ckpt is not None:
        remove_stale_temporaries(ckpt)
    # on interruption: the partial results first, then the checkpoint; on failure none
    with _no_checkpoint_on_failure(ckpt), _checkpoint_on_interrupt(checkpoint_last), \
            recorder.partial_on_failure(), _closed_on_refinement(recorder, start_wall):
        if not resume:
            recorder.reserve(1)
            fill_elevation(0, 0)
            record(0)
            recorder.advance(1)
        if ckpt is not None:
            snapshot = _Snapshot.take(moored, recorder, done)
            if not resume:  # a hard kill from now on leaves a run to resume
                _write_checkpoint(ckpt, snapshot, recorder, identity, elements)
                last_ckpt = _time.perf_counter()
        while done < n_steps:
            chunk = min(CHUNK_STEPS, n_steps - done)
            recorder.reserve((done + chunk) // stride + 1)
            fill_elevation(done // stride + 1, (done + chunk) // stride)
            loads.prepare(body.time, chunk)
            for _ in range(chunk):
                moored.step()
                done += 1
                if done % stride == 0:
                    record(done // stride)
            if not np.all(np.isfinite(body.x)):
                raise SolverError(f"floater: the body motion is not finite at "
                                  f"t = {body.time:.6g} s")
            first, stop = max(checked, recorder.offset), done // stride + 1
            a, b = first - recorder.offset, stop - recorder.offset
            monitor.check(times[first:stop], series["fairlead_position"][:, a:b],
                          bseries["body_displacement"][a:b])
            recorder.validity_warnings = monitor.messages()
            checked = stop
            recorder.advance(stop)
            if ckpt is not None:
                snapshot = _Snapshot.take(moored, recorder, done)
                if _time.perf_counter() - last_ckpt >= checkpoint_interval:
                    _write_checkpoint(ckpt, snapshot, recorder, identity, elements)
                    last_ckpt = _time.perf_counter()
            if progress is not None:
                progress(recorder.simulated_time)
    if probe is not None and not probe.done:
        recorder.set_attribute("line_accuracy", "not estimated: the run ended before the wave "
                               f"ramp and {probe.cycles} "
                               f"{'peak' if irregular_sea(view.waves.settings) else 'wave'} periods")
    dataset = recorder.result(status="complete")
    if ckpt is not None and ckpt.is_file():
        ckpt.unlink()
    return RunResult(dataset=dataset, status="complete",
                     wall_time_s=earlier_loops + _time.perf_counter() - start_wall,
                     simulated_time_s=recorder.simulated_time,
                     line_accuracy=() if probe is None or not probe.done else probe.results)


@contextmanager
def _no_checkpoint_on_failure(ckpt: Path | None) -> Iterator[None]:
    """Remove the checkpoint ``ckpt`` when the block fails (:class:`SolverError`): resumed
    from it, the run would fail again."""
    try:
        yield
    except SolverError:
        if ckpt is not None:
            ckpt.unlink(missing_ok=True)
        raise


@contextmanager
def _closed_on_refinement(recorder: Recorder, start_wall: float) -> Iterator[None]:
    """Close the recorder's output file when the probe raises lines' elements
    (:class:`LineRefinement`; the next pass rewrites it from its start), and give the
    exception the pass's time-loop wall time (``loop_wall_s`` [s], from ``start_wall``)."""
    try:
        yield
    except LineRefinement as refined:
        refined.loop_wall_s = _time.perf_counter() - start_wall
        recorder.close()
        raise


@contextmanager
def _checkpoint_on_interrupt(write: Callable[[], None]) -> Iterator[None]:
    """Call ``write`` (the checkpoint of the last consistent state) when the block is
    interrupted; the interrupt goes on."""
    try:
        yield
    except KeyboardInterrupt:
        write()
        raise
