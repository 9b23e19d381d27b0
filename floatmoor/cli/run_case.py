"""``floatmoor run CASE``: run a case into its output file (and plots, VTK series), print
its summary, and say what a failed or interrupted run left behind (docs/guide/running.md)."""

from __future__ import annotations

import argparse
import json
import shlex
import sys
import time
from contextlib import contextmanager, nullcontext
from pathlib import Path
from typing import TYPE_CHECKING, Iterator

from floatmoor.case.load import load_case
from floatmoor.case.schema import Case
from floatmoor.cli.status import EXIT_FAILED, EXIT_OK
from floatmoor.errors import CaseError, SolverError
from floatmoor.signals import exit_status, signal_name

if TYPE_CHECKING:
    from floatmoor.simulation.forced import RunResult

__all__ = ["run_command", "default_stem"]


def default_stem(case: Case) -> str:
    """The case file's name, and its overrides by the campaign's run-name rule, so that a run
    with overrides does not overwrite the run without them:
    ``lindahl_r0.20_T1.25_motion.period=3.5``."""
    from floatmoor.case.naming import file_stem, override_items

    stem = Path(case.source).stem
    return f"{stem}_{file_stem(override_items(case.overrides))}" if case.overrides else stem


def _output_path(args: argparse.Namespace, case: Case) -> Path:
    """The run's checked output file (and its plot's, when asked for); a file there that the
    run will replace is announced on standard error once every check has passed."""
    from floatmoor.io.output_files import IMAGE, check_output_file
    from floatmoor.io.output_kinds import CHECKPOINT, RUN_RESULT_FILE
    from floatmoor.plots.style import SUPPORTED_FORMATS
    from floatmoor.simulation.recorder import estimated_output_bytes

    protected = {"case file": case.source}
    if case.hydro is not None:
        from floatmoor.hydro.database import database_path

        protected["hydrodynamic database"] = str(database_path(case))
    text = args.output if args.output else default_stem(case) + ".nc"
    output = check_output_file(text, "-o/--output", protected=protected, kind=RUN_RESULT_FILE,
                               expected_bytes=int(min(estimated_output_bytes(case), 2**62)))
    if case.floater is not None and not args.resume:  # the checkpoint it writes replaces
        # only a checkpoint (a numpy zip); with --resume it is an input, checked when read
        from floatmoor.simulation.coupled_run import checkpoint_path

        check_output_file(checkpoint_path(output.path), "-o/--output", kind=CHECKPOINT,
                          protected=protected)
    plot = []
    shapes = case.simulation.shape_output_interval is not None
    if args.plot is not None:
        from floatmoor.plots.run_figures import figure_paths

        if Path(args.plot).suffix.lower() not in SUPPORTED_FORMATS:
            raise CaseError("--plot", "", "an image file (" + ", ".join(SUPPORTED_FORMATS)
                            + ") in an existing folder", f"'{args.plot}'")
        taken = {"result file (-o)": output.path}
        for view, path in figure_paths(args.plot, floater=case.floater is not None,
                                       shapes=shapes).items():
            plot.append(check_output_file(path, "--plot", kind=IMAGE,
                                          protected={**protected, **taken}))
            taken[f"--plot {view} image"] = path
    args.plot_times_s = _plot_times(args, case, shapes)
    if args.vtk is not None:
        from floatmoor.io.output_folders import check_owned_folder

        if not shapes:
            raise CaseError("--vtk", "", "a case that records line shapes (set "
                            "simulation.shape_output_interval)", "no line shapes")
        check_owned_folder(args.vtk, "--vtk", "vtk")
    for checked in (output, *plot):
        if checked is not None and checked.replaces and not (checked is output and args.resume):
            print(f"floatmoor: replacing the existing {checked.path}", file=sys.stderr)
    return output.path


def _plot_times(args: argparse.Namespace, case: Case, shapes: bool) -> list[float] | None:
    """``--plot-times`` as seconds within the run (None when not given).

    Raises
    ------
    CaseError
        Without --plot or line shapes, or for a time that is not a number in the run.
    """
    if args.plot_times is None:
        return None
    if args.plot is None or not shapes:
        raise CaseError("--plot-times", "", "--plot and a case that records line shapes "
                        "(simulation.shape_output_interval)",
                        "no --plot" if args.plot is None else "no line shapes")
    duration = case.simulation.duration
    times = []
    for text in str(args.plot_times).split(","):
        try:
            value = float(text)
        except ValueError:
            value = float("nan")
        if not 0.0 <= value <= duration:
            raise CaseError("--plot-times", "", f"comma-separated times from 0 to {duration:g} "
                            "s (the run's duration)", f"'{text.strip()}'")
        times.append(value)
    return times


def run_command(args: argparse.Namespace) -> int:
    """``floatmoor run``: run the case into its checked, locked output file; the exit
    status."""
    from floatmoor.io.output_files import output_lock

    case = load_case(args.case, args.overrides)
    output = _output_path(args, case)
    with output_lock(output), (nullcontext() if args.plot is None
                               else output_lock(args.plot, "--plot")), \
            (nullcontext() if args.vtk is None else output_lock(Path(args.vtk).resolve(),
                                                                 "--vtk")):
        return _run_case(args, case, output)


def _run_case(args: argparse.Namespace, case: Case, output: Path) -> int:
    """Run a checked case into its locked output file."""
    from floatmoor.mooring.static_strength import refuse_static_breaking
    from floatmoor._numba import watch_compilation
    from floatmoor.io.output_files import OutputWriteError, file_state
    from floatmoor.simulation.forced import run_forced_motion
    from floatmoor.cli.progress import ProgressReporter

    refuse_static_breaking(case)  # a line that breaks at rest is bad input (exit 2)

    if args.resume and case.floater is None:
        raise CaseError("--resume", "", "a case with a [floater] (forced-motion runs are not "
                        "checkpointed)", "--resume")
    every = _checkpoint_every(args, case)
    progress = None if args.quiet else ProgressReporter(case.simulation.duration)
    compile_time = [0.0]  # [s] of the run's wall time spent compiling kernels

    def compiling() -> None:
        if progress is not None:
            progress.compiling()

    def compiled(seconds: float) -> None:
        compile_time[0] += seconds
        if progress is not None:
            progress.compiled(seconds)

    before = file_state(output)
    started = time.perf_counter()
    try:
        with watch_compilation(compiling, compiled), _validity_in_summary():
            if case.floater is not None:
                from floatmoor.simulation.coupled_run import run_coupled

                result = run_coupled(case, output=output, progress=progress,
                                     resume=args.resume, checkpoint_interval=every)
            else:
                result = run_forced_motion(case, output=output, progress=progress)
    except SolverError as err:
        _close(progress)
        print(f"floatmoor: run failed: {err}\n  {_left_behind(output, before)}",
              file=sys.stderr)
        return EXIT_FAILED
    except OutputWriteError as err:
        _close(progress)
        print(f"floatmoor: run failed: {err}\n  "
              f"{_left_behind(output, before, 'its writes failed')}",
              file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt as stop:
        _close(progress)
        print(f"floatmoor: {signal_name(stop)}; {_left_behind(output, before)}"
              + _resume_hint(args, case, output), file=sys.stderr)
        return exit_status(stop)
    _close(progress)
    try:
        return _report_run(args, case, result, output, compile_time[0],
                           time.perf_counter() - started)
    except KeyboardInterrupt as stop:
        print(f"floatmoor: {signal_name(stop)} after the run; its complete results are in "
              f"{output}" + (f", the plot {args.plot} may be missing" if args.plot else ""),
              file=sys.stderr)
        return exit_status(stop)


def _checkpoint_every(args: argparse.Namespace, case: Case) -> float | None:
    """``--checkpoint-every`` in seconds (None when not given).

    Raises
    ------
    CaseError
        For a case without a floater (not checkpointed) or a value that is not a finite
        number >= 0.
    """
    text = args.checkpoint_every
    if text is None:
        return None
    if case.floater is None:
        raise CaseError("--checkpoint-every", "", "a case with a [floater] (forced-motion runs "
                        "are not checkpointed)", f"'{text}'")
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not 0.0 <= value < float("inf"):
        raise CaseError("--checkpoint-every", "", "seconds of wall time, a number >= 0",
                        f"'{text}'")
    return value


@contextmanager
def _validity_in_summary() -> Iterator[None]:
    """Keep the run's model-validity warnings for its summary, which prints them (and so does
    the message of a run that stops; both from the output file's ``validity_warnings``):
    not shown as they are raised, once the progress line has moved on. Other warnings are
    shown as they are raised (a database's accepted failed checks, before the run)."""
    import warnings

    from floatmoor.errors import ModelValidityWarning

    with warnings.catch_warnings():
        warnings.simplefilter("always", ModelValidityWarning)
        show = warnings.showwarning  # (a caller's recorder, if any, keeps recording)

        def show_others(message, category, filename, lineno, file=None, line=None) -> None:
            if not issubclass(category, ModelValidityWarning):
                show(message, category, filename, lineno, file, line)

        warnings.showwarning = show_others
        yield


def _report_run(args: argparse.Namespace, case: Case, result: RunResult, output: Path,
                compile_time: float = 0.0, wall_time: float | None = None) -> int:
    """Print the summary of a completed run (and draw its plot). ``wall_time``: the run's
    whole wall time, set-up included [s] (default: the time loop's); ``compile_time``: the
    part of it spent compiling kernels [s]."""
    wall_time = result.wall_time_s if wall_time is None else wall_time
    from floatmoor.io.output_files import OutputWriteError
    from floatmoor.post.summary import format_summary, run_summary

    summary = run_summary(case, result.dataset)
    summary.update(output=str(output), wall_time_s=result.wall_time_s,
                   simulated_time_s=result.simulated_time_s, compile_time_s=compile_time,
                   run_wall_time_s=wall_time)
    if args.plot is not None:
        from floatmoor.plots.run_figures import plot_run
        from floatmoor.plots.series import FigureDataError

        try:
            figures = plot_run(result.dataset, args.plot, args.plot_times_s)
        except (OutputWriteError, FigureDataError) as err:
            print(f"floatmoor: the plot failed: {err}\n  the run completed; results in "
                  f"{output}", file=sys.stderr)
            return EXIT_FAILED
        summary["plot"] = str(args.plot)
        summary["figures"] = [str(p) for p in figures.values()]
    if args.vtk is not None:
        from floatmoor.io.output_folders import OwnedFolder
        from floatmoor.io.shape_samples import window_samples
        from floatmoor.cli.plots import write_vtk

        try:
            with OwnedFolder(args.vtk, "vtk"):
                summary["vtk"] = str(write_vtk(result.dataset, Path(args.vtk),
                                               window_samples(result.dataset),
                                               quiet=args.quiet))
        except OutputWriteError as err:
            print(f"floatmoor: the VTK output failed: {err} (the VTK files it wrote were "
                  f"removed)\n  the run completed; results in {output}", file=sys.stderr)
            return EXIT_FAILED
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(format_summary(summary))
        compiling = (f" ({compile_time:.3g} s of it compiling the numerical kernels, which "
                     "later runs load from their cache)") if compile_time > 0.0 else ""
        print(f"simulated {result.simulated_time_s:.6g} s in {wall_time:.3g} s of wall "
              f"time{compiling}; results in {output}"
              + (f", plots in {', '.join(summary['figures'])}" if args.plot else "")
              + (f", VTK series {summary['vtk']}" if args.vtk else ""))
    return EXIT_OK


def _resume_hint(args: argparse.Namespace, case: Case, output: Path) -> str:
    """Where an interrupted floater run left its checkpoint and the command that resumes it
    ("" when there is none)."""
    if case.floater is None:
        return ""
    from floatmoor.simulation.coupled_run import checkpoint_path

    ckpt = checkpoint_path(output)
    if not ckpt.is_file():
        return ""
    command = ["floatmoor", "run", args.case, "-o", str(output), "--resume"]
    for text in args.overrides:
        command += ["--set", text]
    for option in ("plot", "plot_times", "vtk", "checkpoint_every"):
        if getattr(args, option) is not None:
            command += [f"--{option.replace('_', '-')}", getattr(args, option)]
    return f"\n  checkpoint written to {ckpt}; continue with: {shlex.join(command)}"


def _left_behind(output: Path, before: tuple[int, int, int] | None,
                 why: str = "the run stopped before recording") -> str:
    """What a stopped run left in ``output`` (``before``: its
    :func:`~floatmoor.io.output_files.file_state` when the run began): partial results up to
    some time, or nothing."""
    from floatmoor.io.netcdf import read_attributes
    from floatmoor.io.output_files import written_since

    if not written_since(output, before):
        return ("nothing written" + (f" ({output} is unchanged)" if before is not None else "")
                + f": {why}")
    attrs = read_attributes(output) or {}
    t = attrs.get("simulated_time_s")
    upto = f" up to t = {float(t):.6g} s" if isinstance(t, (int, float)) else ""
    validity = [m for m in str(attrs.get("validity_warnings", "")).split("\n") if m]
    return f"partial results{upto} written to {output}" + "".join(
        f"\n  warning: outside the model's validity: {m}" for m in validity)


def _close(progress: object) -> None:
    if progress is not None:
        progress.close()  # type: ignore[attr-defined]
