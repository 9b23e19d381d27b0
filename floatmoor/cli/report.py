"""Command-line parsers and handlers of ``floatmoor report`` and ``floatmoor compare``.

Wire into :mod:`floatmoor.cli` with ``add_report_parsers(sub)`` in its parser and
``if args.command in REPORT_COMMANDS: return args.report_handler(args)`` in ``main``. Handlers
return the exit status: 0 done; 2 bad input (a missing or unreadable file, an unknown model, a
bad ``--start``, ``--nominal-diameter`` or reference file, a series that cannot be plotted),
with one message on standard error, no traceback and nothing written; 1 a run of ``compare``
that failed (the message names the model; the other models still run, no report is written)
or a file that could not be written (disk full: the files this invocation wrote are
removed); 130 an interrupted ``compare`` (the finished runs are kept; a re-run resumes). The
output folder must be new, empty or one the same command wrote
(:mod:`floatmoor.io.output_folders`).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

from floatmoor.errors import CaseError, SolverError
from floatmoor.terminal_text import MESSAGE_LIMIT, shown

__all__ = ["add_report_parsers", "report_command", "compare_command", "REPORT_COMMANDS",
           "parse_start", "parse_nominal_diameters"]

REPORT_COMMANDS = ("report", "compare")
EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130


def _add_common(p: argparse.ArgumentParser) -> None:
    p.add_argument("-o", "--output", metavar="DIR", required=True,
                   help="report folder: new (created if its parent exists), empty, or one "
                   "the same command wrote")
    p.add_argument("--start", metavar="SECONDS", default=None,
                   help="start of the analysis window [s] (default: each case's ramp: the "
                        "motion ramp of forced-motion runs, the wave ramp of coupled runs)")
    p.add_argument("--reference", metavar="FILE.toml", default=None,
                   help="reference values printed in labelled columns beside the results, "
                        "e.g. cases/deepcwind/published_lc34.toml")
    p.add_argument("--nominal-diameter", dest="nominal_diameter", action="append",
                   default=[], metavar="LINE=VALUE",
                   help="chain nominal diameter [m] of a line or line type for the fatigue "
                        "damage (default: the reference file's, else the case's diameter)")
    p.add_argument("--html", action="store_true", help="also write summary.html")


def add_report_parsers(subparsers: Any) -> None:
    """Add the ``report`` and ``compare`` subcommands to ``floatmoor``'s subparsers."""
    report = subparsers.add_parser(
        "report", help="figures and tables of one or more runs, side by side")
    report.add_argument("runs", nargs="+", metavar="RUN.nc", help="result files")
    _add_common(report)
    report.set_defaults(report_handler=report_command)
    compare = subparsers.add_parser(
        "compare", help="run a case once per line model and report the runs side by side")
    compare.add_argument("case", help="TOML case file")
    compare.add_argument("--models", default="quasi-static,quasi-dynamic,dynamic",
                         help="comma-separated line models (default: all three)")
    compare.add_argument("--set", dest="overrides", action="append", default=[],
                         metavar="KEY=VALUE", help="override a case key for every run")
    compare.add_argument("--workers", default=1, help="local worker processes")
    compare.add_argument("--scheduler", metavar="ADDRESS", default=None,
                         help="run on this Dask distributed scheduler (tcp://host:8786); "
                              "its workers are sent the case and send the runs back")
    compare.add_argument("--quiet", action="store_true", help="no progress reports")
    _add_common(compare)
    compare.set_defaults(report_handler=compare_command)


def parse_start(value: Any) -> float | None:
    """``--start`` as seconds, or None when not given.

    Raises
    ------
    ReportInputError
        When not a finite number >= 0.
    """
    from floatmoor.cli.plots import parse_time
    from floatmoor.report.runs import ReportInputError

    try:
        return parse_time(value, "--start")
    except CaseError:  # the same rule, reported as the report's input error
        raise ReportInputError("--start", "a time >= 0 [s]", f"'{value}'") from None


def parse_nominal_diameters(items: list[str] | None) -> dict[str, float]:
    """``--nominal-diameter LINE=VALUE`` options as {name: diameter [m]}.

    Raises
    ------
    ReportInputError
        For an item without ``=``, a name given twice or a value that is not a number > 0.
    """
    from floatmoor.report.runs import ReportInputError

    out: dict[str, float] = {}
    for item in items or []:
        name, sep, text = str(item).partition("=")
        name = name.strip()
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not sep or not name or not (math.isfinite(value) and value > 0.0) or name in out:
            raise ReportInputError("--nominal-diameter", "LINE=VALUE with a diameter > 0 [m], "
                                   "each line or line type once", f"'{item}'")
        out[name] = value
    return out


def _bad_input(err: Exception) -> int:
    print(f"floatmoor: error: {shown(err, MESSAGE_LIMIT)}", file=sys.stderr)
    return EXIT_BAD_INPUT


def _reference(args: argparse.Namespace):
    from floatmoor.report.reference import load_reference

    path = getattr(args, "reference", None)
    return load_reference(path) if path else None


def report_command(args: argparse.Namespace) -> int:
    """``floatmoor report RUN.nc [RUN2.nc ...] -o DIR``; returns the exit status."""
    from floatmoor.io.output_files import OutputWriteError, output_lock
    from floatmoor.io.output_folders import OwnedFolder, check_owned_folder
    from floatmoor.report.build import check_output_folder, write_report
    from floatmoor.report.figures import FigureDataError
    from floatmoor.report.runs import ReportInputError, load_run, run_labels

    try:
        start = parse_start(getattr(args, "start", None))
        diameters = parse_nominal_diameters(getattr(args, "nominal_diameter", []))
        check_output_folder(args.output)
        check_owned_folder(args.output, "-o/--output", "report")
        reference = _reference(args)
        runs = [load_run(path, start=start) for path in args.runs]
        for run, label in zip(runs, run_labels(runs)):
            run.label = label
        with output_lock(Path(args.output).resolve()), OwnedFolder(args.output, "report"):
            files = write_report(runs, args.output, reference=reference,
                                 nominal_diameters=diameters, html=getattr(args, "html", False))
    except (ReportInputError, FigureDataError, CaseError) as err:
        return _bad_input(err)
    except OutputWriteError as err:
        print(f"floatmoor: report failed: {err}; nothing written", file=sys.stderr)
        return EXIT_FAILED
    print(f"report of {len(runs)} run(s) in {files.folder}: {files.summary.name}, "
          f"{len(files.figures)} figures")
    return EXIT_OK


def compare_command(args: argparse.Namespace) -> int:
    """``floatmoor compare CASE --models ... -o DIR``; returns the exit status."""
    from floatmoor.hydro.database import HydroDatabaseError
    from floatmoor.io.output_files import OutputWriteError, output_lock
    from floatmoor.io.output_folders import OwnedFolder, check_owned_folder
    from floatmoor.report.build import check_output_folder
    from floatmoor.report.compare import compare_models, parse_models
    from floatmoor.report.figures import FigureDataError
    from floatmoor.report.runs import ReportInputError

    quiet = getattr(args, "quiet", False)

    def progress(message: str) -> None:
        if not quiet:
            print(f"floatmoor: {message}", file=sys.stderr, flush=True)

    try:
        models = parse_models(args.models)
        try:
            workers = int(str(getattr(args, "workers", 1)))
        except ValueError:
            raise ReportInputError("--workers", "a whole number >= 1",
                                   f"'{args.workers}'") from None
        start = parse_start(getattr(args, "start", None))
        diameters = parse_nominal_diameters(getattr(args, "nominal_diameter", []))
        reference = _reference(args)
        check_output_folder(args.output)
        check_owned_folder(args.output, "-o/--output", "compare")
        with output_lock(Path(args.output).resolve()), \
                OwnedFolder(args.output, "compare", keep_on=(SolverError,)):
            files = compare_models(args.case, models, args.output,
                                   overrides=getattr(args, "overrides", []), start=start,
                                   reference=reference, nominal_diameters=diameters,
                                   html=getattr(args, "html", False), workers=workers,
                                   scheduler=getattr(args, "scheduler", None),
                                   progress=progress)
    except (ReportInputError, FigureDataError, CaseError, HydroDatabaseError) as err:
        return _bad_input(err)
    except SolverError as err:
        print(f"floatmoor: run failed: {err}", file=sys.stderr)
        return EXIT_FAILED
    except OutputWriteError as err:
        print(f"floatmoor: compare failed: {err}; the files it wrote were removed",
              file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt:
        print(f"floatmoor: interrupted; finished model runs are in {args.output} (re-run to "
              "resume; no report written)", file=sys.stderr)
        return EXIT_INTERRUPTED
    print(f"{len(models)} runs ({', '.join(models)}) and their report in {files.folder}: "
          f"{files.summary.name}, {len(files.figures)} figures")
    return EXIT_OK
