"""``floatmoor uq STUDY.toml -o DIR``: an uncertainty-quantification study (gPC surrogates
of quantities of interest, :mod:`floatmoor.uq.run`; a failed run of a quadrature design
exits 1)."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from floatmoor.cli.campaign import (
    NAMED_FAILURES, campaign_reporters, report_failures, say_moved_aside, workers_text,
)
from floatmoor.cli.status import EXIT_FAILED, EXIT_OK
from floatmoor.errors import CaseError
from floatmoor.signals import exit_status, signal_name
from floatmoor.terminal_text import shown

if TYPE_CHECKING:
    from floatmoor.uq.study import Study

__all__ = ["uq_command"]


def uq_command(args: argparse.Namespace) -> int:
    """``floatmoor uq``: run the study into its checked, locked folder; the exit status."""
    from floatmoor.io.output_files import output_lock
    from floatmoor.io.output_folders import check_owned_folder
    from floatmoor.uq.study import load_study

    study = load_study(args.study)
    if args.workers < 1:
        raise CaseError("--workers", "", "a whole number >= 1", str(args.workers))
    if args.scheduler is not None:
        from floatmoor.campaign.scheduler import check_address

        check_address(args.scheduler)
    folder = check_owned_folder(args.output, "-o/--output", "uq")
    with output_lock(folder.resolve()):
        return _uq_locked(args, study, folder)


def _uq_locked(args: argparse.Namespace, study: "Study", folder: Path) -> int:
    """Run a checked study into its checked and locked output folder."""
    from floatmoor._numba import watch_compilation
    from floatmoor.io.output_files import OutputWriteError
    from floatmoor.io.output_folders import OwnedFolder
    from floatmoor.uq.output import study_summary
    from floatmoor.uq.run import RUNS_NAME, StudyRunsFailed, run_study

    progress, compiling = campaign_reporters(args.quiet, workers_text(args.workers,
                                                                        args.scheduler))
    runs = folder / RUNS_NAME
    try:  # the runs are kept whatever happens: a re-run resumes them
        with watch_compilation(compiling, lambda seconds: None), \
                OwnedFolder(folder, "uq", keep=(RUNS_NAME,), keep_on=(StudyRunsFailed,)):
            result = run_study(study, folder, workers=args.workers, scheduler=args.scheduler,
                               progress=progress, restart=args.restart,
                               moved_aside=say_moved_aside)
    except KeyboardInterrupt as stop:
        held = f"the finished runs are in {runs} (re-run the same command to resume)" \
            if runs.is_file() else "no run finished"
        print(f"floatmoor: {signal_name(stop)}; {held}", file=sys.stderr)
        return exit_status(stop)
    except StudyRunsFailed as err:
        print(f"{err.total - len(err.failed)} of {err.total} runs complete; the quadrature "
              f"rule needs every node: no surrogate built; the runs are in {runs}")
        report_failures("uq", err.failed, err.total)
        return EXIT_FAILED
    except OutputWriteError as err:
        held = f"; the finished runs are in {runs} (re-run the same command to resume)" \
            if runs.is_file() else ""
        print(f"floatmoor: uq failed: {err}; the other files it wrote were removed{held}",
              file=sys.stderr)
        return EXIT_FAILED
    summary = study_summary(result)
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(_format_uq_summary(summary))
    if summary["dropped_runs"]:  # the surrogate is written, and the study still fails loudly
        print(f"floatmoor: uq: {len(summary['dropped_runs'])} of {summary['runs']} runs "
              "failed or gave non-finite values and were dropped from the regression (the "
              f"results without them are in {folder}): "
              + "; ".join(summary["dropped_runs"][:NAMED_FAILURES]), file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def _format_uq_summary(summary: dict) -> str:
    """The study summary as plain text: one line per quantity."""
    rows = [f"{shown(summary['title'])}: {summary['method']}, {summary['runs']} runs "
            f"({len(summary['dropped_runs'])} dropped)"]
    for name, q in summary["quantities"].items():
        u = q["units"]
        if "window_s" in q:
            total = ", ".join(f"{k} {v:.3g}" for k, v in q["sobol_total_weighted"].items())
            rows.append(f"  {name} [{u}] over {q['window_s'][0]:g} to {q['window_s'][1]:g} s: "
                        f"mean {q['min_mean']:.5g} to {q['max_mean']:.5g}, band "
                        f"{q['min_lower']:.5g} to {q['max_upper']:.5g}, largest std "
                        f"{q['max_std']:.4g}; variance-weighted S_T: {total}")
        else:
            total = ", ".join(f"{k} {v:.3g}" for k, v in q["sobol_total"].items())
            rows.append(f"  {name} [{u}]: mean {q['mean']:.7g}, variance {q['variance']:.7g}, "
                        f"std {q['std']:.5g}, band {q['lower']:.5g} to {q['upper']:.5g}, "
                        f"validation error {q['validation_error']:.3g}; S_T: {total}")
    rows.append(f"results in {summary['output']}")
    return "\n".join(rows)
