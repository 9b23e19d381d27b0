"""``floatmoor study qd-verification -o DIR``: the quasi-dynamic verification study
(docs/cases/qd_verification.md)."""

from __future__ import annotations

import argparse
import sys
from typing import Sequence

from floatmoor.cli.campaign import report_failures
from floatmoor.cli.status import EXIT_FAILED, EXIT_OK
from floatmoor.errors import CaseError
from floatmoor.signals import exit_status, signal_name

__all__ = ["study_command"]


def study_command(args: argparse.Namespace) -> int:
    """``floatmoor study qd-verification``: run the study into its folder; the exit status."""
    from floatmoor.studies import qd_verification

    from floatmoor.io.output_files import OutputWriteError, output_lock, write_errors
    from floatmoor.io.output_folders import MANIFEST_NAME, OwnedFolder, check_owned_folder

    output = check_owned_folder(args.output, "-o/--output", "study qd-verification")
    if args.workers < 1:
        raise CaseError("--workers", "", "a whole number >= 1", str(args.workers))
    options = _study_options(args.dynamic_elements, args.amplitudes, args.alphas,
                             quick=args.quick)

    def progress(done: int, total: int) -> None:
        if not args.quiet:
            print(f"floatmoor: {done} / {total} runs done", file=sys.stderr, flush=True)

    runs = qd_verification.qd_runs.RUNS_DIR
    try:
        with output_lock(output.resolve()), OwnedFolder(output, "study qd-verification",
                                                        keep=(runs,)) as folder:
            def kept() -> None:  # a run file stays the study's even if the process is killed
                with write_errors(output / MANIFEST_NAME):
                    folder.record_written()

            ds = qd_verification.run_study(output, workers=args.workers, quick=args.quick,
                                           progress=progress, resume=args.resume, kept=kept,
                                           **options)
    except KeyboardInterrupt as stop:
        n_kept = qd_verification.qd_runs.count_runs(output)
        said = (f"{n_kept} finished runs kept in {output / runs} (--resume continues the "
                "study)" if n_kept else "nothing written")
        print(f"floatmoor: {signal_name(stop)}; {said}; the dataset, summary and figures are "
              "written at the end", file=sys.stderr)
        return exit_status(stop)
    except OutputWriteError as err:
        n_kept = qd_verification.qd_runs.count_runs(output)
        print(f"floatmoor: study failed: {err}; the files it wrote were removed"
              + (f" but its {n_kept} finished runs, kept in {output / runs} for --resume"
                 if n_kept else ""), file=sys.stderr)
        return EXIT_FAILED
    print(qd_verification.summary(ds))
    print(f"results in {output}")
    failed = qd_verification.failed_runs(ds)
    if failed:
        report_failures("study qd-verification", failed, int(ds.attrs["runs"]))
        return EXIT_FAILED
    return EXIT_OK


def _study_options(dynamic_elements: str | None, amplitudes: str | None, alphas: str | None,
                  quick: bool = False) -> dict:
    """The keyword arguments of ``qd_verification.run_study`` from the command line's texts
    (``--dynamic-elements 20``, ``--amplitudes A1,A3,A5``, ``--alphas 0.1,0.2,0.6``).

    Raises
    ------
    CaseError
        Naming the option, what it takes and what it was given.
    """
    from floatmoor.studies.qd_verification import ALPHAS, AMPLITUDE_NAMES

    out: dict = {}
    if dynamic_elements is not None:
        text = dynamic_elements.strip()
        if not (text.isascii() and text.isdigit()) or int(text) < 1:
            raise CaseError("--dynamic-elements", "", "a whole number >= 1",
                            repr(dynamic_elements))
        out["dynamic_elements"] = int(text)
    if quick and (amplitudes is not None or alphas is not None):
        raise CaseError("--quick", "", "no --amplitudes or --alphas beside it (it picks its own)",
                        "--amplitudes" if amplitudes is not None else "--alphas")
    if amplitudes is not None:
        out["amplitudes"] = _study_pick("--amplitudes", amplitudes, AMPLITUDE_NAMES,
                                        "amplitude names among " + ", ".join(AMPLITUDE_NAMES))
    if alphas is not None:
        names = tuple(f"{a:g}" for a in ALPHAS)
        out["alphas"] = _study_pick("--alphas", alphas, names,
                                    "accelerations among " + ", ".join(names))
    return out


def _study_pick(option: str, text: str, names: Sequence[str], expected: str) -> list[int]:
    """Indices into ``names`` of the comma-separated items of ``text`` (each once)."""
    items = [item.strip() for item in text.split(",")]
    picked = []
    for item in items:
        key = item.upper() if option == "--amplitudes" else item
        if option == "--alphas":
            try:
                key = f"{float(item):g}"
            except ValueError:
                key = item
        if key not in names or names.index(key) in picked:
            why = "repeated" if key in names else "unknown"
            raise CaseError(option, "", f"a comma-separated list of distinct {expected}",
                            f"{repr(text)} ({why} item {repr(item)})")
        picked.append(names.index(key))
    return picked
