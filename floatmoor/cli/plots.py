"""Command-line parsers and handlers of ``floatmoor animate`` and ``floatmoor vtk``.

Both read a finished (or partial) run file and write its line shapes and body: ``animate
RUN.nc -o run.gif|mp4`` an animation of the side and plan views, ``vtk RUN.nc -o DIR`` a VTK
time series for ParaView (the body's panels beside the lines). Wired into
:mod:`floatmoor.cli` with ``add_view_parsers(sub)``; handlers return the exit status: 0 done;
2 bad input (a missing or unreadable run file, one without line shapes, a bad option, an .mp4
without ffmpeg) with one message on standard error, no traceback and nothing written; 1 a
write that failed; 130 interrupted (an animation is written whole or not at all; a VTK folder
holds its finished frames, without the .pvd).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any, Callable

from floatmoor.errors import CaseError
from floatmoor.signals import exit_status, signal_name
from floatmoor.terminal_text import MESSAGE_LIMIT, shown

__all__ = ["add_view_parsers", "animate_command", "vtk_command", "VIEW_COMMANDS",
           "parse_positive", "parse_every", "parse_time", "write_vtk",
           "ANIMATION"]

VIEW_COMMANDS = ("animate", "vtk")
EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT = 0, 1, 2
#: What an animation output may replace: (name, leading bytes) of GIF and MP4 files (an MP4
#: starts with the 4-byte size of its 'ftyp' box, small enough to begin with three zeros).
ANIMATION = ("animation", (b"GIF87a", b"GIF89a", b"\x00\x00\x00"))
#: Progress reports per command (every tenth of the frames).
_REPORTS = 10


def _add_window(p: argparse.ArgumentParser) -> None:
    p.add_argument("run", metavar="RUN.nc", help="result file of a run that recorded line "
                   "shapes (simulation.shape_output_interval)")
    p.add_argument("--every", default="1", metavar="K",
                   help="use every K-th line-shape sample (default 1: all)")
    p.add_argument("--start", default=None, metavar="S", help="first time [s] (default: the "
                   "first shape sample)")
    p.add_argument("--end", default=None, metavar="E", help="last time [s] (default: the "
                   "last complete shape sample)")
    p.add_argument("--quiet", action="store_true", help="no progress reports")


def add_view_parsers(subparsers: Any) -> None:
    """Add the ``animate`` and ``vtk`` subcommands to ``floatmoor``'s subparsers."""
    animate = subparsers.add_parser("animate", help="animate a run's line shapes and floater "
                                    "(side and plan views) into a .gif or .mp4")
    _add_window(animate)
    animate.add_argument("-o", "--output", required=True, metavar="OUT.gif|OUT.mp4",
                         help="animation file (.mp4 needs ffmpeg)")
    animate.add_argument("--fps", default="10", metavar="N",
                         help="frames per second (default 10)")
    animate.set_defaults(view_handler=animate_command)
    vtk = subparsers.add_parser("vtk", help="write a run's line shapes as a VTK time series "
                                "for ParaView (.vtu per time, lines.pvd)")
    _add_window(vtk)
    vtk.add_argument("-o", "--output", required=True, metavar="DIR",
                     help="output folder: new (created if its parent exists), empty, or one "
                     "vtk wrote")
    vtk.set_defaults(view_handler=vtk_command)


def parse_positive(text: str, option: str) -> float:
    """A finite number > 0, or CaseError naming ``option``."""
    try:
        value = float(text)
    except (TypeError, ValueError):
        value = math.nan
    if not (math.isfinite(value) and value > 0.0):
        raise CaseError(option, "", "a number > 0", f"'{text}'")
    return value


def parse_every(text: str) -> int:
    """``--every`` as a whole number >= 1, or CaseError."""
    try:
        value = int(str(text))
    except ValueError:
        value = 0
    if value < 1:
        raise CaseError("--every", "", "a whole number >= 1", f"'{text}'")
    return value


def parse_time(text: str | None, option: str) -> float | None:
    """A time >= 0 [s] (None when not given), or CaseError naming ``option``."""
    if text is None:
        return None
    try:
        value = float(text)
    except (TypeError, ValueError):
        value = math.nan
    if not (math.isfinite(value) and value >= 0.0):
        raise CaseError(option, "", "a time >= 0 [s]", f"'{text}'")
    return value


def _window(args: argparse.Namespace):
    """The run's dataset and its checked shape samples.

    Raises
    ------
    CaseError, ReportInputError, ShapeDataError
        For a bad option, an unusable run file or one without shapes in the window.
    """
    from floatmoor.io.shape_samples import ShapeDataError, window_samples
    from floatmoor.report.runs import load_run

    every = parse_every(args.every)
    start, end = parse_time(args.start, "--start"), parse_time(args.end, "--end")
    if start is not None and end is not None and end < start:
        raise CaseError("--end", "", f"a time >= --start ({start:g} s)", f"'{args.end}'")
    dataset = load_run(args.run, start=0.0).dataset
    try:
        return dataset, window_samples(dataset, start=start, end=end, every=every)
    except ShapeDataError as err:
        raise ShapeDataError(f"{args.run}: {err}") from None


def _bad_input(err: Exception) -> int:
    print(f"floatmoor: error: {shown(err, MESSAGE_LIMIT)}", file=sys.stderr)
    return EXIT_BAD_INPUT


def _bad_input_types() -> tuple[type[Exception], ...]:
    """The errors of these commands that are bad input (status 2)."""
    from floatmoor.io.shape_samples import ShapeDataError
    from floatmoor.plots.animation import AnimationWriterError
    from floatmoor.plots.series import FigureDataError
    from floatmoor.report.runs import ReportInputError

    return (CaseError, ReportInputError, ShapeDataError, FigureDataError, AnimationWriterError)


def _progress(quiet: bool, what: str) -> Callable[[int, int], None]:
    def report(done: int, total: int) -> None:
        if not quiet and (done == total or done % max(total // _REPORTS, 1) == 0):
            print(f"floatmoor: {what} {done} / {total}", file=sys.stderr, flush=True)

    return report


def _guarded(what: str, interrupted: str, work: Callable[[], str]) -> int:
    """Run a command's ``work`` (which returns its closing line): bad input exits 2, a
    failed write 1, an interruption 130 or 143 saying ``interrupted``."""
    from floatmoor.io.output_files import OutputWriteError

    try:
        done = work()
    except _bad_input_types() as err:
        return _bad_input(err)
    except OutputWriteError as err:
        print(f"floatmoor: {what} failed: {err}", file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt as stop:
        print(f"floatmoor: {signal_name(stop)}; {interrupted}", file=sys.stderr)
        return exit_status(stop)
    print(done)
    return EXIT_OK


def animate_command(args: argparse.Namespace) -> int:
    """``floatmoor animate RUN.nc -o OUT.gif``; returns the exit status."""
    from floatmoor.io.output_files import check_output_file, output_lock
    from floatmoor.plots.animation import animate_run, animation_writer

    def work() -> str:
        fps = parse_positive(args.fps, "--fps")
        animation_writer(args.output, fps)
        output = check_output_file(args.output, "-o/--output", kind=ANIMATION,
                                   protected={"run file": args.run}).path
        dataset, samples = _window(args)
        with output_lock(output):
            frames = animate_run(dataset, output, samples, fps=fps,
                                 progress=_progress(args.quiet, "frame"))
        return f"{frames} frames at {fps:g} per second in {output}"

    return _guarded("animate", "nothing written (the animation is written whole or not at "
                    "all)", work)


def vtk_command(args: argparse.Namespace) -> int:
    """``floatmoor vtk RUN.nc -o DIR``; returns the exit status."""
    from floatmoor.io.output_files import OutputWriteError, output_lock
    from floatmoor.io.output_folders import OwnedFolder, check_owned_folder

    def work() -> str:
        folder = check_owned_folder(args.output, "-o/--output", "vtk")
        dataset, samples = _window(args)
        try:
            with output_lock(folder.resolve()), OwnedFolder(folder, "vtk"):
                pvd = write_vtk(dataset, folder, samples, quiet=args.quiet)
        except OutputWriteError as err:
            raise OutputWriteError(f"{err}; the files it wrote were removed") from err
        return f"{len(samples)} line-shape samples in {folder}; open {pvd} in ParaView"

    return _guarded("vtk", f"the files written so far are in {args.output}, without the "
                    ".pvd collection", work)


def write_vtk(dataset, folder: Path, samples, *, quiet: bool) -> Path:
    """:func:`floatmoor.io.vtk.write_vtk_series` with progress reports (also for ``run
    --vtk``), with the run's body at each time: the floater's panels, or the polygon through
    a forced body's points."""
    from floatmoor.io.vtk import write_vtk_series
    from floatmoor.plots.body_pose import placed_body, polygon_through
    from floatmoor.plots.context import run_context

    model = run_context(dataset).body

    def body(time: float):
        placed = placed_body(model, dataset, time)
        faces = placed.faces if placed.faces is not None else polygon_through(placed.vertices)
        return placed.vertices, faces

    return write_vtk_series(dataset, folder, samples, progress=_progress(quiet, "VTK file"),
                            body=body if model is not None else None)
