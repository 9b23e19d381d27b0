"""Running a campaign: serially, on local processes, or on a Dask distributed cluster.

Runs are independent; each completes on whatever executor into the same
:class:`~floatmoor.campaign.store.CampaignStore`, which is written after every completed run
(at most every ``write_interval`` seconds), so an interrupted campaign keeps what finished and
a re-run with the same output file resumes: completed runs are skipped, failed ones retried.
With a runs folder every run also writes its full output file there (``NAME.nc``, named from
its swept values); a completed run is then skipped only if its file is there and complete.
Cases with a ``[floater]`` run coupled, the others in forced motion.
"""

from __future__ import annotations

import time as _time
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from pathlib import Path
from typing import Any, Callable, Iterator, Sequence

import xarray as xr

from floatmoor.campaign.design import CampaignDesign
from floatmoor.campaign.scheduler import check_address, connect
from floatmoor.campaign.store import CampaignStore, run_file_is_complete, same_campaign
from floatmoor.campaign.worker import run_one
from floatmoor.case.load import load_case
from floatmoor.case.schema import Case
from floatmoor.errors import CaseError
from floatmoor.io.dataset import DOFS

__all__ = ["run_campaign", "validate_campaign", "WRITE_INTERVAL_S"]

#: Wall time between writes of the output file while runs complete [s].
WRITE_INTERVAL_S = 5.0

Progress = Callable[[int, int, float], None]
#: (index along each axis, overrides, run file or None) of a run to execute.
Job = tuple[tuple[int, ...], list[str], str | None]


def run_campaign(case_path: str | Path, design: CampaignDesign, *,
                 base_overrides: Sequence[str] = (), output: str | Path | None = None,
                 workers: int = 1, scheduler: str | None = None, timeseries: bool = False,
                 runs_dir: str | Path | None = None, run_names: Sequence[str] | None = None,
                 replace_other: bool = False, progress: Progress | None = None,
                 write_interval: float = WRITE_INTERVAL_S) -> xr.Dataset:
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
        netCDF file, written as runs complete; if it exists and holds the same campaign, its
        completed runs are kept and not run again.
    workers
        Local worker processes (1: run in this process).
    scheduler
        Address of a Dask distributed scheduler (``tcp://host:8786``) to run on instead.
    timeseries
        Also keep each run's fairlead tension history (and the body displacement history of
        coupled runs).
    runs_dir
        Folder (created if its parent exists) for every run's full output file,
        ``NAME.nc``; the paths are stored in the ``run_file`` variable. A completed run of
        the output file is run again when its file is missing or incomplete. With a
        ``scheduler``, the workers must see the folder (a shared file system).
    run_names
        File-name stems of the runs in :meth:`CampaignDesign.runs` order (default:
        :meth:`CampaignDesign.run_names`, from the swept values).
    replace_other
        When ``output`` holds another campaign, start afresh (and replace it) instead of
        refusing.
    progress
        Called with (runs done, runs in total, estimated seconds left) after each run; the
        estimate is NaN until a run completes after the last one that compiled kernels.

    Raises
    ------
    CaseError
        For a bad case, override, design, output or runs folder (nothing run or written), or
        an output file holding another campaign.
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
    case_path = str(case_path)
    if scheduler is not None:
        check_address(scheduler)
    base = validate_campaign(case_path, design, base_overrides)
    runs = design.runs()
    files = _run_files(design, runs_dir, run_names)
    store = CampaignStore(design, case_path, base.text, list(base_overrides), base.line_names,
                          dofs=DOFS if base.floater is not None else (),
                          run_files=files is not None)
    path = Path(output) if output is not None else None
    if path is not None and path.exists():
        if not replace_other or same_campaign(path, design, base.text, base_overrides):
            store.resume_from(path)
    if files:
        Path(files[0]).parent.mkdir(exist_ok=True)
    todo: list[Job] = []
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
    total, done = len(runs), len(runs) - len(todo)
    start, last_write = _time.perf_counter(), -float("inf")
    if progress is not None:
        progress(done, total, float("nan"))
    executed = 0
    # the estimate's origin (wall time, runs executed): moved to each run that compiled
    # kernels, whose time says nothing about the runs left
    origin = (start, 0)
    try:
        for index, run_file, result in _execute(case_path, todo, workers, scheduler,
                                                timeseries):
            store.record(index, result, run_file)
            done += 1
            executed += 1
            now = _time.perf_counter()
            if path is not None and now - last_write >= write_interval:
                store.write(path)
                last_write = now
            if result.get("compile_time_s", 0.0) > 0.0:
                origin = (now, executed)
            if progress is not None:
                since = executed - origin[1]
                left = ((now - origin[0]) / since * (total - done) if since > 0
                        else float("nan"))
                progress(done, total, left)
    finally:
        if path is not None:
            store.write(path)
    return store.dataset()


def validate_campaign(case_path: str | Path, design: CampaignDesign,
                      base_overrides: Sequence[str] = ()) -> Case:
    """Check that every run of a campaign is valid input; returns the base case.

    Every run's case is loaded, and the hydrodynamic database of every distinct floater
    configuration is loaded once (and checked), so a bad override or a missing, damaged,
    stale or failing database is bad input before anything runs or is written.

    Raises
    ------
    CaseError
        For a bad case or override.
    HydroDatabaseError
        For a missing, damaged or stale database, or one failing a check the case does not
        accept.
    """
    from floatmoor.hydro.database import (
        database_inputs, database_path, inputs_hash, load_for_case,
    )

    case_path = str(case_path)
    base = load_case(case_path, list(base_overrides))
    cases = [load_case(case_path, [*base_overrides, *overrides])
             for _, overrides in design.runs()]
    seen = set()
    for case in cases:
        if case.floater is None or case.hydro is None:
            continue
        key = (str(database_path(case)),
               inputs_hash(database_inputs(case.floater, case.hydro, case.environment)))
        if key not in seen:
            seen.add(key)
            load_for_case(case)
    return base


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
    return [str(folder / f"{name}.nc") for name in names]


def _absolute(run_file: str | None) -> str | None:
    """The path a worker writes to: absolute, as a Dask worker may run in another folder."""
    return None if run_file is None else str(Path(run_file).resolve())


def _execute(case_path: str, todo: list[Job], workers: int, scheduler: str | None,
             timeseries: bool
             ) -> Iterator[tuple[tuple[int, ...], str | None, dict[str, Any]]]:
    """Yield (index, run file, result) as runs complete."""
    if not todo:
        return
    if scheduler is not None:
        yield from _execute_dask(case_path, todo, scheduler, timeseries)
    elif workers <= 1:
        for index, overrides, run_file in todo:
            yield index, run_file, run_one(case_path, overrides, timeseries, _absolute(run_file))
    else:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            pending: dict[Future[dict[str, Any]], tuple[tuple[int, ...], str | None]] = {
                pool.submit(run_one, case_path, overrides, timeseries, _absolute(run_file)):
                (index, run_file) for index, overrides, run_file in todo}
            while pending:
                finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in finished:
                    index, run_file = pending.pop(future)
                    yield index, run_file, future.result()


def _execute_dask(case_path: str, todo: list[Job], scheduler: str, timeseries: bool
                  ) -> Iterator[tuple[tuple[int, ...], str | None, dict[str, Any]]]:
    from distributed import as_completed

    with connect(scheduler) as client:
        futures = {client.submit(run_one, case_path, overrides, timeseries,
                                 _absolute(run_file), pure=False): (index, run_file)
                   for index, overrides, run_file in todo}
        for future in as_completed(futures):
            index, run_file = futures[future]
            yield index, run_file, future.result()
