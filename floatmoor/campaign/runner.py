"""Running a campaign: serially, on local processes, or on a Dask distributed cluster.

Runs are independent; each completes on whatever executor into the same
:class:`~floatmoor.campaign.store.CampaignStore`, which is written as runs complete (once per
batch of runs that finished together), so an interrupted or killed campaign keeps what
finished and a re-run with the same output file resumes: completed runs are skipped, failed
ones retried. When interrupted, the runs that finished meanwhile are recorded and written
before the workers are stopped; local workers die with the parent process, even when it is
killed (:func:`floatmoor.signals.die_with_parent`).
With a runs folder every run also writes its full output file there (``NAME.nc``, named from
its swept values); a completed run is then skipped only if its file is there and complete.
Cases with a ``[floater]`` run coupled, the others in forced motion. On a Dask cluster the
workers are sent the case and the files it names, and send every result (and run file) back
to this process, which writes them (:mod:`floatmoor.campaign.cluster`).
Several campaigns can run as one pool of jobs on the same workers
(:func:`prepare_campaign`, then :func:`run_campaigns`): their runs are taken in turn, each
result recorded into its own campaign's store.
"""

from __future__ import annotations

import os
import warnings
import time as _time
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np
import xarray as xr

from floatmoor.campaign.design import CampaignDesign
from floatmoor.campaign.jobs import Job, Record
from floatmoor.campaign.reopen import move_aside
from floatmoor.campaign.scheduler import check_address
from floatmoor.campaign.store import CampaignStore, run_file_is_complete, same_campaign
from floatmoor.campaign.worker import run_one
from floatmoor.case.load import load_case
from floatmoor.case.schema import Case
from floatmoor.errors import CaseError, ModelValidityWarning
from floatmoor.io.dataset import DOFS
from floatmoor.signals import die_with_parent

__all__ = ["run_campaign", "validate_campaign", "prepare_campaign", "run_campaigns",
           "PreparedCampaign"]

Progress = Callable[[int, int, float], None]


def run_campaign(case_path: str | Path, design: CampaignDesign, *,
                 base_overrides: Sequence[str] = (), output: str | Path | None = None,
                 workers: int = 1, scheduler: str | None = None, timeseries: bool = False,
                 runs_dir: str | Path | None = None, run_names: Sequence[str] | None = None,
                 replace_other: bool = False, progress: Progress | None = None,
                 restart: bool = False,
                 moved_aside: Callable[[Path, Path], None] | None = None) -> xr.Dataset:
    """Run every run of ``design`` and gather the results.

    Parameters
    ----------
    case_path
        The base case file.
    design
        The swept keys and values.
    base_overrides
        ``--set`` overrides applied to every run before the swept ones.
    output
        netCDF file, written as runs complete (no finished run is lost when the campaign is
        interrupted or killed); if it exists and holds the same campaign, its completed runs
        are kept and not run again.
    workers
        Local worker processes (1: run in this process).
    scheduler
        Address of a Dask distributed scheduler (``tcp://host:8786``) to run on instead: the
        case and the files it names are sent to the workers, which need the same floatmoor
        and nothing else (:mod:`floatmoor.campaign.cluster`).
    timeseries
        Also keep each run's fairlead tension history (and the body displacement history of
        coupled runs).
    runs_dir
        Folder (created if its parent exists) for every run's full output file,
        ``NAME.nc``; the paths are stored in the ``run_file`` variable. A completed run of
        the output file is run again when its file is missing or incomplete. With a
        ``scheduler`` too, this process writes the files (the workers send them back): the
        folder is only this machine's.
    run_names
        File-name stems of the runs in :meth:`CampaignDesign.runs` order (default:
        :meth:`CampaignDesign.run_names`, from the swept values).
    replace_other
        When ``output`` holds another campaign (or is damaged), start afresh instead of
        refusing: the old file is moved aside to ``OUTPUT.bak-N``
        (:func:`floatmoor.campaign.reopen.move_aside`).
    restart
        Start afresh even from this campaign's own file, moving it aside the same way.
    moved_aside
        Called with (output, backup) when the existing output was moved aside.
    progress
        Called with (runs done, runs in total, estimated seconds left) after each run; the
        estimate is NaN until a run completes after the last one that compiled kernels.

    Raises
    ------
    CaseError
        For a bad case, override, design, output or runs folder (nothing run or written), or
        an output file that is not this campaign's to resume: another campaign, a damaged,
        truncated or foreign file (a :class:`~floatmoor.campaign.reopen.CampaignFileError`
        saying how to start over).
    HydroDatabaseError
        When a coupled run's database is missing, damaged, stale or fails a check its case
        does not accept (nothing run or written).

    Returns
    -------
    xarray.Dataset
        The campaign (:mod:`floatmoor.campaign.store`). A run that fails is recorded (its
        ``status`` is ``failed: ...``) and the campaign goes on: check the attribute
        ``runs_failed`` (or :func:`floatmoor.campaign.store.failed_runs`) before using the
        results; ``floatmoor sweep`` exits with 1 when it is not 0.
    """
    if scheduler is not None:
        check_address(scheduler)
    campaign = prepare_campaign(case_path, design, base_overrides=base_overrides,
                                output=output, timeseries=timeseries, runs_dir=runs_dir,
                                run_names=run_names, replace_other=replace_other,
                                restart=restart, moved_aside=moved_aside)
    run_campaigns([campaign], workers=workers, scheduler=scheduler, progress=progress)
    return campaign.dataset()


class PreparedCampaign:
    """A checked campaign ready to run (:func:`prepare_campaign`): its store (resumed from
    its output file), the runs left and their cases; :func:`run_campaigns` runs it, alone or
    with others on one pool of workers.

    Attributes
    ----------
    case_path, timeseries
        The base case file, and whether histories are kept.
    path
        The output file, or None.
    todo
        (index, overrides, run file) of every run left, in :meth:`CampaignDesign.runs` order.
    cases
        The case of each run of ``todo`` (what a cluster's workers are sent).
    total
        Runs in the design.
    """

    def __init__(self, case_path: str, timeseries: bool, store: CampaignStore,
                 path: Path | None, todo: list[tuple[tuple[int, ...], list[str], str | None]],
                 cases: list[Case], total: int) -> None:
        self.case_path, self.timeseries, self.store, self.path = case_path, timeseries, store, \
            path
        self.todo, self.cases, self.total = todo, cases, total
        self.recorded: set[tuple[int, ...]] = set()
        self.existed = path is not None and path.exists()
        self.unsaved = False

    @property
    def done(self) -> int:
        """Runs complete or recorded (failed ones too)."""
        return self.total - len(self.todo) + len(self.recorded)

    def record(self, index: tuple[int, ...], run_file: str | None,
               result: dict[str, Any]) -> bool:
        """Record a run's result; False when it was recorded already (after an interrupt)."""
        self.store.record(index, result, run_file)
        self.unsaved = True
        if index in self.recorded:
            return False
        self.recorded.add(index)
        return True

    def save(self, *, final: bool = False) -> bool:
        """Write what is recorded to the output file (if any) when something is new; at the
        ``final`` save also a resumed campaign's or one that had nothing to run (no file for
        a campaign that ran nothing). True when the file was written."""
        if final:
            self.unsaved = self.unsaved or self.existed or not self.todo
        if not self.unsaved:
            return False
        self.unsaved = False
        if self.path is None:
            return False
        self.store.write(self.path)
        return True

    def dataset(self) -> xr.Dataset:
        """The campaign (:meth:`CampaignStore.dataset`)."""
        return self.store.dataset()


def prepare_campaign(case_path: str | Path, design: CampaignDesign, *,
                     base_overrides: Sequence[str] = (), output: str | Path | None = None,
                     timeseries: bool = False, runs_dir: str | Path | None = None,
                     run_names: Sequence[str] | None = None, replace_other: bool = False,
                     restart: bool = False,
                     moved_aside: Callable[[Path, Path], None] | None = None
                     ) -> PreparedCampaign:
    """Check a campaign and resume its output file, running nothing; the arguments and
    errors are :func:`run_campaign`'s."""
    case_path = str(case_path)
    cases = _load_campaign(case_path, design, base_overrides, timeseries)
    base = cases[0]
    runs = design.runs()
    files = _run_files(design, runs_dir, run_names)
    store = CampaignStore(design, case_path, base.text, list(base_overrides), base.line_names,
                          dofs=DOFS if base.floater is not None else (),
                          run_files=files is not None)
    path = Path(output) if output is not None else None
    if path is not None:
        _reopen(path, store, restart or (replace_other and path.exists() and not same_campaign(
            path, design, base.text, base_overrides)), moved_aside)
        if path.exists():
            _check_resumed_series(store, path, timeseries)
    if files:
        Path(files[0]).parent.mkdir(exist_ok=True)
    todo: list[tuple[tuple[int, ...], list[str], str | None]] = []
    todo_cases: list[Case] = []  # what a cluster's workers are sent: the runs to run
    for k, (index, overrides) in enumerate(runs):
        run_overrides = [*base_overrides, *overrides]
        run_file = None if files is None else files[k]
        if store.done(index):
            if run_file is None:
                continue
            if run_file_is_complete(run_file, base.text, run_overrides):
                store.set_run_file(index, run_file)
                continue
        todo.append((index, run_overrides, run_file))
        todo_cases.append(cases[1 + k])
    return PreparedCampaign(case_path, timeseries, store, path, todo, todo_cases, len(runs))


def run_campaigns(campaigns: Sequence[PreparedCampaign], *, workers: int = 1,
                  scheduler: str | None = None, progress: Progress | None = None,
                  finished: Callable[[int], None] | None = None,
                  saved: Callable[[int], None] | None = None) -> None:
    """Run the runs left of every campaign as one pool of jobs on the same workers, taken in
    turn from each campaign (its first run, the next one's first run, ...), so that no
    worker idles while any campaign has runs left; each result goes to its campaign's store,
    written after each batch of finished runs, so an interrupted or killed submission loses
    no finished run of any campaign.

    Parameters
    ----------
    campaigns
        From :func:`prepare_campaign`.
    workers, scheduler
        As :func:`run_campaign`'s.
    progress
        Called with (runs done, runs in total, estimated seconds left) of all the campaigns
        together, as :func:`run_campaign` calls it.
    finished
        Called with a campaign's number once all its runs are done (recorded and saved), or
        at the start for a campaign with nothing left to run.
    saved
        Called with a campaign's number after each write of its output file.
    """
    total = sum(c.total for c in campaigns)
    jobs = _in_turn(campaigns)
    start = sum(c.done for c in campaigns)
    if progress is not None:
        progress(start, total, float("nan"))
    # the estimate's origin (wall time, runs executed): moved to each run that compiled
    # kernels, whose time says nothing about the runs left
    count = {"executed": 0, "reported": start}
    origin = [_time.perf_counter(), 0]
    told: set[int] = set()

    def tell_finished() -> None:
        for k, campaign in enumerate(campaigns):
            if k not in told and campaign.done == campaign.total and not campaign.unsaved:
                told.add(k)
                if finished is not None:
                    finished(k)

    def record(k: int, index: tuple[int, ...], run_file: str | None,
               result: dict[str, Any]) -> None:
        if not campaigns[k].record(index, run_file, result):
            return  # recorded again after an interrupt: counted once
        for message in result.get("validity_warnings", ()):  # the worker's, warned here
            where = f"run {Path(run_file).stem}" if run_file else \
                "run " + ", ".join(map(str, index))
            warnings.warn(ModelValidityWarning(f"{where}: {message}"))
        count["executed"] += 1
        if result.get("compile_time_s", 0.0) > 0.0:
            origin[:] = [_time.perf_counter(), count["executed"]]

    def save(final: bool = False) -> None:
        """Write what is recorded, then report it (a run reported done is in the file)."""
        for k, campaign in enumerate(campaigns):
            if campaign.save(final=final) and saved is not None:
                saved(k)
        done = sum(c.done for c in campaigns)
        if progress is not None and done > count["reported"]:
            count["reported"] = done
            since = count["executed"] - origin[1]
            left = ((_time.perf_counter() - origin[0]) / since * (total - done)
                    if since > 0 else float("nan"))
            progress(done, total, left)
        tell_finished()

    tell_finished()
    try:
        _execute(campaigns, jobs, workers, scheduler, record, save)
    finally:
        save(final=True)


def _in_turn(campaigns: Sequence[PreparedCampaign]) -> list[Job]:
    """The runs left of every campaign, one of each in turn."""
    jobs: list[Job] = []
    for n in range(max((len(c.todo) for c in campaigns), default=0)):
        jobs.extend((k, *c.todo[n]) for k, c in enumerate(campaigns) if n < len(c.todo))
    return jobs


def _reopen(path: Path, store: CampaignStore, afresh: bool,
            moved_aside: Callable[[Path, Path], None] | None) -> None:
    """Resume ``store`` from an existing ``path`` (validated), or with ``afresh`` move the
    file aside (never deleted) and start from nothing."""
    if not (path.exists() or path.is_symlink()):
        return
    if afresh and (path.is_file() or path.is_symlink()):
        backup = move_aside(path)
        if moved_aside is not None:
            moved_aside(path, backup)
        return
    store.resume_from(path)  # refuses anything but this campaign's own file


def validate_campaign(case_path: str | Path, design: CampaignDesign,
                      base_overrides: Sequence[str] = (), *, timeseries: bool = False) -> Case:
    """Check that every run of a campaign is valid input; returns the base case.

    Every run's case is loaded, and the hydrodynamic database of every distinct floater
    configuration is loaded once (and checked), so a bad override or a missing, damaged,
    stale or failing database is bad input before anything runs or is written. With
    ``timeseries``, every run must have the same output times (the histories share one time
    axis).

    Raises
    ------
    CaseError
        For a bad case or override, or runs of different output times with ``timeseries``.
    HydroDatabaseError
        For a missing, damaged or stale database, or one failing a check the case does not
        accept.
    """
    return _load_campaign(case_path, design, base_overrides, timeseries)[0]


def _load_campaign(case_path: str | Path, design: CampaignDesign, base_overrides: Sequence[str],
                   timeseries: bool) -> list[Case]:
    """:func:`validate_campaign`'s checks; returns the base case and then every run's case
    in :meth:`CampaignDesign.runs` order."""
    from floatmoor.hydro.database import (
        database_inputs, database_path, inputs_hash, load_for_case,
    )

    case_path = str(case_path)
    base = load_case(case_path, list(base_overrides))
    cases = [load_case(case_path, [*base_overrides, *overrides])
             for _, overrides in design.runs()]
    if timeseries:
        _check_same_times(cases, design)
    seen = set()
    for case in cases:
        if case.floater is None or case.hydro is None:
            continue
        key = (str(database_path(case)),
               inputs_hash(database_inputs(case.floater, case.hydro, case.environment)))
        if key not in seen:
            seen.add(key)
            load_for_case(case)
    return [base, *cases]


def _check_same_times(cases: Sequence[Case], design: CampaignDesign) -> None:
    """Refuse histories of runs with different output times (one time axis holds them)."""
    from floatmoor.simulation.forced import output_times

    runs = design.runs()
    first = output_times(cases[0].simulation)
    for case, (_, overrides) in zip(cases[1:], runs[1:]):
        if not np.array_equal(output_times(case.simulation), first):
            sim0, sim = cases[0].simulation, case.simulation
            raise CaseError("--timeseries", "", "runs with the same output times (duration "
                            "and output_interval), as their histories share one time axis; "
                            "sweep them without --timeseries, or keep a run file of each "
                            "with --runs-dir",
                            f"duration {sim0.duration:g} s, output_interval "
                            f"{sim0.output_interval:g} s in run {', '.join(runs[0][1])}"
                            f" but {sim.duration:g} s, {sim.output_interval:g} s in run "
                            f"{', '.join(overrides)}")


def _check_resumed_series(store: CampaignStore, path: Path, timeseries: bool) -> None:
    """Refuse to resume a campaign file whose histories would not match this campaign's:
    with time series into a file of complete runs without them, or the other way round
    (the runs run now would hold none: complete runs with NaN histories)."""
    complete = bool(np.any(store.status == "complete"))
    if timeseries and complete and store.series is None:
        raise CaseError(str(path), "", "a campaign file with time series to resume with "
                        "--timeseries (resume it without, or write another output file)",
                        "complete runs without time series")
    if not timeseries and store.series is not None:
        raise CaseError(str(path), "", "a campaign file without time series to resume "
                        "without --timeseries (resume it with --timeseries, or write another "
                        "output file)", "time series")


def _run_files(design: CampaignDesign, runs_dir: str | Path | None,
               run_names: Sequence[str] | None) -> list[str] | None:
    """The output file of every run (in :meth:`CampaignDesign.runs` order), or None."""
    if runs_dir is None:
        return None
    folder = Path(runs_dir)
    if folder.exists() and not folder.is_dir():
        raise CaseError("--runs-dir", "", "a folder", f"the file '{folder}'")
    if not folder.exists() and not folder.resolve().parent.is_dir():
        raise CaseError("--runs-dir", "", "a folder in an existing folder", f"'{folder}'")
    names = list(run_names) if run_names is not None else design.run_names()
    if len(names) != design.size or len(set(names)) != len(names):
        raise CaseError("--runs-dir", "", f"{design.size} distinct run names",
                        f"{len(set(names))} distinct of {len(names)}")
    paths = [folder / f"{name}.nc" for name in names]
    from floatmoor.io.output_files import check_output_file
    from floatmoor.io.output_kinds import RUN_RESULT_FILE

    for path in paths:  # a run (re)written there replaces only a run result
        if os.path.lexists(path):
            check_output_file(path, "--runs-dir", kind=RUN_RESULT_FILE)
    return [str(path) for path in paths]


def _absolute(run_file: str | None) -> str | None:
    """The path a local worker process writes to: absolute, whatever its folder."""
    return None if run_file is None else str(Path(run_file).resolve())


def _execute(campaigns: Sequence[PreparedCampaign], jobs: list[Job], workers: int,
             scheduler: str | None, record: Record, save: Callable[[], None]) -> None:
    """Run ``jobs``, passing each result to ``record`` as it completes and calling ``save``
    after each batch; when interrupted, the runs finished meanwhile are recorded and saved
    before the workers are stopped, then the interrupt goes on."""
    if not jobs:
        return
    if scheduler is not None:
        from floatmoor.campaign.cluster import execute_on_cluster

        execute_on_cluster(scheduler, [(c.cases, c.timeseries) for c in campaigns], jobs,
                           record, save)
    elif workers <= 1:
        for k, index, overrides, run_file in jobs:
            campaign = campaigns[k]
            record(k, index, run_file, run_one(campaign.case_path, overrides,
                                               campaign.timeseries, _absolute(run_file)))
            save()
    else:
        _execute_local(campaigns, jobs, workers, record, save)


def _execute_local(campaigns: Sequence[PreparedCampaign], jobs: list[Job], workers: int,
                   record: Record, save: Callable[[], None]) -> None:
    """On local worker processes that die with this one."""
    pool = ProcessPoolExecutor(max_workers=workers, initializer=die_with_parent,
                               initargs=(os.getpid(),))
    pending: dict[Future[dict[str, Any]], tuple[int, tuple[int, ...], str | None]] = {}
    try:
        for k, index, overrides, run_file in jobs:
            campaign = campaigns[k]
            pending[pool.submit(run_one, campaign.case_path, overrides, campaign.timeseries,
                                _absolute(run_file))] = (k, index, run_file)
        while pending:
            finished, _ = wait(pending, return_when=FIRST_COMPLETED)
            for future in finished:
                record(*pending[future], future.result())
                del pending[future]  # after recording: an interrupt records it again
            save()
    except BaseException:
        _record_finished(pending, record)
        save()
        raise
    finally:
        _stop_workers(pool)


def _record_finished(pending: dict[Any, tuple[int, tuple[int, ...], str | None]],
                     record: Record) -> None:
    """Record the runs of ``pending`` that have finished (their results are there)."""
    for future, (k, index, run_file) in list(pending.items()):
        if future.done() and not future.cancelled() and future.exception() is None:
            record(k, index, run_file, future.result())


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """Cancel the runs not started and end the workers, even those running a run."""
    # the executor has no public way to end busy workers (Python 3.14 adds
    # terminate_workers); its process table is the only handle on them
    processes = list(getattr(pool, "_processes", {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        if process.is_alive():
            process.terminate()
    for process in processes:
        process.join()
    pool.shutdown(wait=True)
