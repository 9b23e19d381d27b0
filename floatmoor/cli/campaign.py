"""``floatmoor sweep CASE --grid ...``: run a campaign; the progress and failure reports
that the ``study`` and ``uq`` commands share."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Sequence

from floatmoor.case.load import load_case
from floatmoor.case.schema import Case
from floatmoor.cli.run_case import default_stem
from floatmoor.cli.status import EXIT_FAILED, EXIT_OK
from floatmoor.errors import CaseError
from floatmoor.signals import exit_status, signal_name

if TYPE_CHECKING:
    from floatmoor.campaign.design import CampaignDesign

__all__ = ["sweep_command", "campaign_reporters", "report_failures", "say_moved_aside",
           "say_part_done", "NAMED_FAILURES"]


def sweep_command(args: argparse.Namespace) -> int:
    """``floatmoor sweep``: run the campaign into its checked, locked file; the exit status."""
    from floatmoor.campaign.design import design_from_options
    from floatmoor.io.output_files import output_lock

    case = load_case(args.case, args.overrides)
    design = design_from_options(args.grid, args.zipped, getattr(case, "campaign", None))
    output = _campaign_output(args, case, design.size)
    if args.workers < 1:
        raise CaseError("--workers", "", "a whole number >= 1", str(args.workers))
    with output_lock(output):
        return _sweep_locked(args, design, output)


def _campaign_output(args: argparse.Namespace, case: Case, runs: int) -> Path:
    """The sweep's checked campaign file (and runs folder), with room for what they will
    hold."""
    from floatmoor.io.output_files import CAMPAIGN, check_output_file
    from floatmoor.simulation.recorder import estimated_output_bytes

    run_bytes = estimated_output_bytes(case)
    text = args.output if args.output else default_stem(case) + "_campaign.nc"
    # per run: a few statistics per line (and DOF); with --timeseries the histories, about
    # a tenth of a run file's values (one of its 13 values per line and sample)
    expected = runs * ((run_bytes / 10.0 if args.timeseries else 0.0) + 8192.0)
    output = check_output_file(text, "-o/--output", kind=CAMPAIGN,
                               protected={"case file": case.source},
                               expected_bytes=int(min(expected, 2**62))).path
    if args.runs_dir is not None:
        folder = Path(args.runs_dir)
        probe = folder / ".floatmoor-runs-dir" if folder.is_dir() else folder
        if folder.is_dir() or not folder.exists():
            check_output_file(probe, "--runs-dir", expected_bytes=int(min(
                runs * run_bytes, 2**62)))
    return output


def _sweep_locked(args: argparse.Namespace, design: CampaignDesign, output: Path) -> int:
    """Run a campaign into its checked and locked output file."""
    from floatmoor._numba import watch_compilation
    from floatmoor.campaign.runner import run_campaign
    from floatmoor.campaign.store import failed_runs
    from floatmoor.io.output_files import OutputWriteError, file_state

    progress, compiling = campaign_reporters(args.quiet, workers_text(args.workers,
                                                                        args.scheduler))
    before = file_state(output)
    try:
        with watch_compilation(compiling, lambda seconds: None):
            ds = run_campaign(args.case, design, base_overrides=args.overrides, output=output,
                              workers=args.workers, scheduler=args.scheduler,
                              timeseries=args.timeseries, runs_dir=args.runs_dir,
                              progress=progress, restart=args.restart,
                              moved_aside=say_moved_aside)
    except KeyboardInterrupt as stop:
        print(f"floatmoor: {signal_name(stop)}; {_campaign_left_behind(output, before)}",
              file=sys.stderr)
        return exit_status(stop)
    except OutputWriteError as err:
        print(f"floatmoor: sweep failed: {err}\n  {_campaign_left_behind(output, before)}",
              file=sys.stderr)
        return EXIT_FAILED
    failed = failed_runs(ds, design)
    print(f"{ds.attrs['runs_complete']} of {ds['status'].size} runs complete, {len(failed)} "
          f"failed; results in {output}")
    if failed:
        report_failures("sweep", failed, int(ds["status"].size))
        return EXIT_FAILED
    return EXIT_OK


def campaign_reporters(quiet: bool, workers: str = "", parts: str = "") -> tuple[
        Callable[[int, int, float], None], Callable[[], None]]:
    """The progress callback of a campaign's runs (runs done, runs in total, seconds left)
    and the compiling notice (said once: kernels compile in this process with one worker).

    Before the runs it says how many there are (and how many a resumed campaign already
    holds), of what (``parts``, e.g. ``"3 studies"`` submitted together: one count and one
    estimate for all) and on what (``workers``, e.g. ``"2 local workers"``); once the first
    runs give an estimate it says the wall time to finish, once, then each finished run says
    what is left.
    """
    from floatmoor.cli.progress import COMPILING_MESSAGE

    said: list[str] = []

    def progress(done: int, total: int, left: float) -> None:
        if quiet:
            return
        if not said:
            said.append("count")
            before = f" ({done} already done)" if done else ""
            where = f" on {workers}" if workers else ""
            of = f" of {parts}" if parts else ""
            print(f"floatmoor: {total} runs{of}{before}{where}; the wall-time estimate follows "
                  "the first finished run", file=sys.stderr, flush=True)
            if done == 0:
                return
        if left == left and "estimate" not in said:
            said.append("estimate")
            print(f"floatmoor: estimated wall time to finish the {total - done} runs left: "
                  f"{duration_text(left)}", file=sys.stderr, flush=True)
        eta = "" if left != left else f", ~{duration_text(left)} left"
        print(f"floatmoor: {done} / {total} runs done{eta}", file=sys.stderr, flush=True)

    def compiling() -> None:
        if not quiet and "compiling" not in said:
            said.append("compiling")
            print(COMPILING_MESSAGE, file=sys.stderr, flush=True)

    return progress, compiling


def say_part_done(quiet: bool, what: str, runs: int, failed: int) -> None:
    """Say on standard error that one campaign of several run together (``what``, e.g.
    ``"study cases/uq/a.toml"``) has all its runs done, and how many failed."""
    if not quiet:
        print(f"floatmoor: {what}: all {runs} runs done, {failed} failed", file=sys.stderr,
              flush=True)


def duration_text(seconds: float) -> str:
    """A wall time as an engineer reads it: ``42 s``, ``17 min``, ``3 h 05 min``."""
    if seconds < 120.0:
        return f"{seconds:.0f} s"
    minutes = int(round(seconds / 60.0))
    if minutes < 120:
        return f"{minutes} min"
    return f"{minutes // 60} h {minutes % 60:02d} min"


def workers_text(workers: int, scheduler: str | None) -> str:
    """What runs the campaign: the scheduler's workers or the local worker processes."""
    if scheduler is not None:
        return f"the workers of the Dask scheduler at {scheduler}"
    return f"{workers} local worker{'s' if workers != 1 else ''}"


def say_moved_aside(path: Path, backup: Path) -> None:
    """Say on standard error that ``--restart`` moved ``path`` aside to ``backup``."""
    print(f"floatmoor: --restart: moved the existing {path} aside to {backup}; starting "
          "afresh", file=sys.stderr, flush=True)


#: Failed runs named in the one-line summary, and failure messages printed after it.
NAMED_FAILURES, _FAILURE_MESSAGES = 10, 3


def report_failures(what: str, failed: Sequence[tuple[str, str]], total: int) -> None:
    """Print on standard error the one-line summary of a campaign's failed runs (how many,
    which) and the first failure messages.

    Parameters
    ----------
    what
        The command (``"sweep"``, ``"study qd-verification"``).
    failed
        (run label, e.g. its swept values; failure message) of every failed run.
    total
        Runs in the campaign.
    """
    labels = [label for label, _ in failed]
    named = "; ".join(labels[:NAMED_FAILURES]) + (
        f"; and {len(labels) - NAMED_FAILURES} more" if len(labels) > NAMED_FAILURES else "")
    print(f"floatmoor: {what} failed: {len(failed)} of {total} runs failed ({named})",
          file=sys.stderr)
    for label, message in failed[:_FAILURE_MESSAGES]:
        print(f"  {label}: {message}", file=sys.stderr)


def _campaign_left_behind(output: Path, before: tuple[int, int, int] | None) -> str:
    """What a stopped sweep left in ``output``: how many runs it holds, or nothing."""
    from floatmoor.io.netcdf import read_attributes
    from floatmoor.io.output_files import written_since

    if not written_since(output, before):
        return "nothing written" + (f" ({output} is unchanged)" if before is not None else "")
    attrs = read_attributes(output) or {}
    complete = attrs.get("runs_complete")
    held = f"{int(complete)} finished runs are" if complete is not None else "finished runs are"
    return f"{held} in {output} (re-run the same command to resume)"
