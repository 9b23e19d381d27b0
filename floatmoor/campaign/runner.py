"""Running a campaign: serially, on local processes, or on a Dask distributed cluster.

Runs are independent; each completes on whatever executor into the same
:class:`~floatmoor.campaign.store.CampaignStore`, which is written after every completed run
(at most every ``write_interval`` seconds), so an interrupted campaign keeps what finished and
a re-run with the same output file resumes: completed runs are skipped, failed ones retried.
"""

from __future__ import annotations

import time as _time
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from pathlib import Path
from typing import Any, Callable, Iterator, Sequence

import xarray as xr

from floatmoor.campaign.design import CampaignDesign
from floatmoor.campaign.store import CampaignStore
from floatmoor.campaign.worker import run_one
from floatmoor.case.load import load_case

__all__ = ["run_campaign", "WRITE_INTERVAL_S"]

#: Wall time between writes of the output file while runs complete [s].
WRITE_INTERVAL_S = 5.0

Progress = Callable[[int, int, float], None]


def run_campaign(case_path: str | Path, design: CampaignDesign, *,
                 base_overrides: Sequence[str] = (), output: str | Path | None = None,
                 workers: int = 1, scheduler: str | None = None, timeseries: bool = False,
                 progress: Progress | None = None,
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
        Also keep each run's fairlead tension history.
    progress
        Called with (runs done, runs in total, estimated seconds left) after each run.
    """
    case_path = str(case_path)
    base = load_case(case_path, list(base_overrides))  # validates the base case up front
    runs = design.runs()
    for _, overrides in runs:  # every run's case is valid before anything runs (bad input)
        load_case(case_path, [*base_overrides, *overrides])
    store = CampaignStore(design, case_path, base.text, list(base_overrides), base.line_names)
    path = Path(output) if output is not None else None
    if path is not None and path.exists():
        store.resume_from(path)
    todo = [(index, [*base_overrides, *overrides]) for index, overrides in runs
            if not store.done(index)]
    total, done = len(runs), len(runs) - len(todo)
    start, last_write = _time.perf_counter(), -float("inf")
    if progress is not None:
        progress(done, total, float("nan"))
    executed = 0
    try:
        for index, result in _execute(case_path, todo, workers, scheduler, timeseries):
            store.record(index, result)
            done += 1
            executed += 1
            now = _time.perf_counter()
            if path is not None and now - last_write >= write_interval:
                store.write(path)
                last_write = now
            if progress is not None:
                rate = (now - start) / executed
                progress(done, total, rate * (total - done))
    finally:
        if path is not None:
            store.write(path)
    return store.dataset()


def _execute(case_path: str, todo: list[tuple[tuple[int, ...], list[str]]], workers: int,
             scheduler: str | None, timeseries: bool
             ) -> Iterator[tuple[tuple[int, ...], dict[str, Any]]]:
    """Yield (index, result) as runs complete."""
    if not todo:
        return
    if scheduler is not None:
        yield from _execute_dask(case_path, todo, scheduler, timeseries)
    elif workers <= 1:
        for index, overrides in todo:
            yield index, run_one(case_path, overrides, timeseries)
    else:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            pending: dict[Future[dict[str, Any]], tuple[int, ...]] = {
                pool.submit(run_one, case_path, overrides, timeseries): index
                for index, overrides in todo}
            while pending:
                finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in finished:
                    yield pending.pop(future), future.result()


def _execute_dask(case_path: str, todo: list[tuple[tuple[int, ...], list[str]]],
                  scheduler: str, timeseries: bool
                  ) -> Iterator[tuple[tuple[int, ...], dict[str, Any]]]:
    from distributed import Client, as_completed

    with Client(scheduler) as client:
        futures = {client.submit(run_one, case_path, overrides, timeseries, pure=False): index
                   for index, overrides in todo}
        for future in as_completed(futures):
            yield futures[future], future.result()
