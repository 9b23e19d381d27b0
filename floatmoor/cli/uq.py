"""``floatmoor uq STUDY.toml -o DIR``: an uncertainty-quantification study (gPC surrogates
of quantities of interest, :mod:`floatmoor.uq.run`; a failed run of a quadrature design
exits 1). Several studies at once (``floatmoor uq A.toml B.toml -o A -o B``) share the
workers: their runs are one pool of jobs (:func:`floatmoor.uq.run.run_studies`), each study
keeps its own folder, and a failed run fails only its study."""

from __future__ import annotations

import argparse
import contextlib
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Sequence

from floatmoor.cli.campaign import (
    NAMED_FAILURES, campaign_reporters, report_failures, say_moved_aside, say_part_done,
    workers_text,
)
from floatmoor.cli.status import EXIT_FAILED, EXIT_OK
from floatmoor.errors import CaseError
from floatmoor.signals import exit_status, signal_name
from floatmoor.terminal_text import shown

if TYPE_CHECKING:
    from floatmoor.uq.run import PreparedStudy
    from floatmoor.uq.study import Study

__all__ = ["uq_command"]


def uq_command(args: argparse.Namespace) -> int:
    """``floatmoor uq``: run the studies into their checked, locked folders (one ``-o`` per
    study, in the same order); the exit status."""
    from floatmoor.io.output_files import output_lock
    from floatmoor.io.output_folders import check_owned_folder
    from floatmoor.uq.study import load_study

    paths = [args.study] if isinstance(args.study, str) else list(args.study)
    outputs = [args.output] if isinstance(args.output, str) else list(args.output)
    if len(outputs) != len(paths):
        raise CaseError("-o/--output", "", f"one output folder per study ({len(paths)}, in "
                        "the order of the study files)", f"{len(outputs)}")
    studies = [load_study(path) for path in paths]
    if args.workers < 1:
        raise CaseError("--workers", "", "a whole number >= 1", str(args.workers))
    if args.scheduler is not None:
        from floatmoor.campaign.scheduler import check_address

        check_address(args.scheduler)
    folders = [check_owned_folder(output, "-o/--output", "uq") for output in outputs]
    _check_separate(folders)
    with contextlib.ExitStack() as locks:
        for folder in folders:
            locks.enter_context(output_lock(folder.resolve()))
        return _uq_locked(args, studies, folders)


def _check_separate(folders: Sequence[Path]) -> None:
    """Refuse two studies writing into one folder (or one inside the other's)."""
    resolved = [folder.resolve() for folder in folders]
    for i, a in enumerate(resolved):
        for j, b in enumerate(resolved):
            if i != j and (a == b or b.is_relative_to(a)):
                raise CaseError("-o/--output", "", "a folder of its own for each study",
                                f"'{folders[i]}' and '{folders[j]}'")


def _uq_locked(args: argparse.Namespace, studies: Sequence["Study"],
               folders: Sequence[Path]) -> int:
    """Run checked studies into their checked and locked output folders: every run first
    (one pool of jobs), then each study's surrogates, results and report."""
    from floatmoor._numba import watch_compilation
    from floatmoor.io.output_files import OutputWriteError, write_errors
    from floatmoor.io.output_folders import MANIFEST_NAME, OwnedFolder
    from floatmoor.uq.run import RUNS_NAME, prepare_study, run_studies

    several = len(studies) > 1
    progress, compiling = campaign_reporters(args.quiet, workers_text(args.workers,
                                                                        args.scheduler),
                                             parts=f"{len(studies)} studies" if several else "")
    runs = [folder / RUNS_NAME for folder in folders]
    made = [not folder.exists() for folder in folders]
    try:  # the runs are kept whatever happens: a re-run resumes them
        with watch_compilation(compiling, lambda seconds: None):
            with contextlib.ExitStack() as stack:
                owned = [stack.enter_context(OwnedFolder(folder, "uq", keep=(RUNS_NAME,)))
                         for folder in folders]
                prepared = [prepare_study(study, folder, restart=args.restart,
                                          moved_aside=say_moved_aside)
                            for study, folder in zip(studies, folders)]

                def kept(k: int) -> None:  # runs.nc stays the study's if the client is killed
                    with write_errors(folders[k] / MANIFEST_NAME):
                        owned[k].record_written()

                def finished(k: int) -> None:
                    campaign = prepared[k].campaign
                    if several and campaign is not None:
                        status = campaign.dataset()["status"].values
                        say_part_done(args.quiet, f"study {studies[k].path}", status.size,
                                      int((status != "complete").sum()))

                run_studies(prepared, workers=args.workers, scheduler=args.scheduler,
                            progress=progress, finished=finished, saved=kept)
            return _finish_studies(args, prepared, made)
    except KeyboardInterrupt as stop:
        held = [str(path) for path in runs if path.is_file()]
        said = f"the finished runs are in {', '.join(held)} (re-run the same command to " \
            "resume)" if held else "no run finished"
        print(f"floatmoor: {signal_name(stop)}; {said}", file=sys.stderr)
        return exit_status(stop)
    except OutputWriteError as err:
        held = [str(path) for path in runs if path.is_file()]
        said = f"; the finished runs are in {', '.join(held)} (re-run the same command to " \
            "resume)" if held else ""
        print(f"floatmoor: uq failed: {err}; the other files it wrote were removed{said}",
              file=sys.stderr)
        return EXIT_FAILED


def _finish_studies(args: argparse.Namespace, prepared: Sequence["PreparedStudy"],
                    made: Sequence[bool]) -> int:
    """Fit, write and report each study whose runs are done; a study that fails (a failed
    run of a quadrature design, a file not written) fails alone: the exit status is 1 when
    any did."""
    from floatmoor.io.output_files import OutputWriteError
    from floatmoor.io.output_folders import OwnedFolder
    from floatmoor.uq.output import study_summary
    from floatmoor.uq.run import RUNS_NAME, StudyRunsFailed, finish_study

    several = len(prepared) > 1
    status, summaries = EXIT_OK, []
    for k, study in enumerate(prepared):
        folder, runs = study.folder, study.folder / RUNS_NAME
        what = f"uq {study.study.path}" if several else "uq"
        try:
            with OwnedFolder(folder, "uq", keep=(RUNS_NAME,), keep_on=(StudyRunsFailed,)):
                result = finish_study(study)
        except StudyRunsFailed as err:
            named = f"{study.study.path}: " if several else ""
            print(f"{named}{err.total - len(err.failed)} of {err.total} runs complete; the "
                  "quadrature rule needs every node: no surrogate built; the runs are in "
                  f"{runs}")
            report_failures(what, err.failed, err.total)
            status = EXIT_FAILED
            continue
        except OutputWriteError as err:
            held = f"; the finished runs are in {runs} (re-run the same command to resume)" \
                if runs.is_file() else ""
            print(f"floatmoor: {what} failed: {err}; the other files it wrote were removed"
                  f"{held}", file=sys.stderr)
            if made[k] and folder.is_dir() and not any(folder.iterdir()):
                folder.rmdir()
            status = EXIT_FAILED
            continue
        summary = study_summary(result)
        summaries.append(summary)
        if not args.json:
            print(_format_uq_summary(summary))
        if summary["dropped_runs"]:  # the surrogate is written, and the study fails loudly
            print(f"floatmoor: {what}: {len(summary['dropped_runs'])} of {summary['runs']} "
                  "runs failed or gave non-finite values and were dropped from the regression "
                  f"(the results without them are in {folder}): "
                  + "; ".join(summary["dropped_runs"][:NAMED_FAILURES]), file=sys.stderr)
            status = EXIT_FAILED
    if args.json and summaries:
        print(json.dumps(summaries if several else summaries[0], indent=2))
    return status


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
