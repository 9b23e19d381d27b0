"""Running a campaign's runs on a Dask distributed cluster (``--scheduler ADDRESS``).

The workers need floatmoor (the same version) and nothing of the client's disk or folder:

* before any run is submitted, every worker is asked for its :func:`worker_identity`
  (floatmoor version and :data:`BUNDLE_FORMAT`); a worker that differs is refused
  (:class:`WorkerVersionError`, naming it and both identities) and nothing runs. A worker
  joining later is held to the same by the task itself (:func:`run_bundled` refuses to run
  and its run is recorded as failed, saying why);
* the client resolves the case into a :class:`~floatmoor.campaign.bundle.RunBundle` (case
  text and the files it names) and scatters each distinct file's bytes once to every worker;
  a task carries the case text, its overrides and references to those bytes;
* each run's result comes back to the client, which records it as it arrives (the campaign
  file is written per batch, so a worker dying loses no finished run) and writes the run's
  full output file (``--runs-dir``) itself from the bytes the worker returns: the runs
  folder is the client's, not a shared file system.

Several campaigns run together (:func:`floatmoor.campaign.runner.run_campaigns`) have a
bundle each; their files are scattered together, each distinct content once.

A run lost with a worker is run again by Dask on another one; one that cannot be (it killed
every worker it ran on, or the scheduler went away) is recorded as failed, with Dask's
reason, and a re-run of the same campaign (same output) runs it again.
"""

from __future__ import annotations

import os
import tempfile
import uuid
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

from floatmoor._version import __version__
from floatmoor.campaign.bundle import RunBundle, load_bundled_case, make_bundle, materialise
from floatmoor.campaign.jobs import Job, Record
from floatmoor.campaign.scheduler import CONNECT_TIMEOUT, SchedulerError, connect
from floatmoor.campaign.worker import failed_result, run_loaded
from floatmoor.io.output_files import atomic_target

if TYPE_CHECKING:
    from distributed import Client, Future

    from floatmoor.case.schema import Case

__all__ = ["BUNDLE_FORMAT", "WorkerVersionError", "worker_identity", "check_workers",
           "run_bundled", "execute_on_cluster"]

#: Version of what a task receives and returns (:func:`run_bundled`'s arguments, the bundle
#: layout, the result dict); to be raised when they change, so that a worker and a client of
#: the same floatmoor version string but different code are refused rather than mismatched.
BUNDLE_FORMAT = 1



class WorkerVersionError(SchedulerError):
    """A worker of the cluster runs another floatmoor (or bundle format) than the client."""


def worker_identity() -> dict[str, Any]:
    """What a worker must share with the client: floatmoor version and bundle format."""
    return {"floatmoor": __version__, "bundle_format": BUNDLE_FORMAT}


def _describe(identity: Mapping[str, Any]) -> str:
    return (f"floatmoor {identity.get('floatmoor', '?')} (bundle format "
            f"{identity.get('bundle_format', '?')})")


def check_workers(client: "Client", address: str) -> None:
    """Refuse a cluster without workers or with a worker unlike the client.

    Raises
    ------
    SchedulerError
        No worker joined within :data:`~floatmoor.campaign.scheduler.CONNECT_TIMEOUT`.
    WorkerVersionError
        Naming every worker whose :func:`worker_identity` differs from the client's, with
        both.
    """
    try:
        client.wait_for_workers(1, timeout=CONNECT_TIMEOUT)
    except TimeoutError:
        raise SchedulerError(f"the Dask scheduler at {address} has no workers (none joined "
                             f"within {CONNECT_TIMEOUT:g} s); nothing was run") from None
    ours = worker_identity()
    theirs = client.run(worker_identity)
    wrong = {worker: found for worker, found in theirs.items() if found != ours}
    if wrong:
        listed = "; ".join(f"{worker} runs {_describe(found)}"
                           for worker, found in sorted(wrong.items()))
        raise WorkerVersionError(f"workers of the Dask scheduler at {address} differ from "
                                 f"this client's {_describe(ours)}: {listed}; install the "
                                 "same floatmoor on every worker; nothing was run")


def _worker_folder() -> Path:
    """This process's private folder for bundles and run files: the Dask worker's local
    directory (removed with the worker), else one under the system's temporary folder."""
    try:
        from distributed import get_worker

        return Path(get_worker().local_directory) / "floatmoor"
    except (ImportError, ValueError):
        return Path(tempfile.gettempdir()) / f"floatmoor-worker-{os.getpid()}"


def run_bundled(bundle: RunBundle, blobs: Mapping[str, bytes], overrides: Sequence[str],
                timeseries: bool, keep_run_file: bool, expected: Mapping[str, Any],
                root: Path | None = None) -> dict[str, Any]:
    """One run of a bundled campaign, on a worker; never raises for a failing run.

    Parameters
    ----------
    bundle, blobs
        The campaign's bundle and its files' bytes by SHA-256.
    overrides
        The run's overrides (base ones first).
    timeseries
        Also return the histories.
    keep_run_file
        Write the run's full output file (in the worker's folder) and return its bytes as
        ``run_file_bytes`` (also a failed run's partial file).
    expected
        The client's :func:`worker_identity`: a worker unlike it runs nothing.
    root
        The private folder (default: the Dask worker's local directory).

    Returns
    -------
    dict
        As :func:`floatmoor.campaign.worker.run_one`, with ``run_file_bytes``.
    """
    here = worker_identity()
    if dict(expected) != here:
        return failed_result(f"failed: WorkerVersionError: worker {_address()} runs "
                             f"{_describe(here)}, the client {_describe(expected)}; not run")
    folder = root if root is not None else _worker_folder()
    output = folder / "runs" / f"{uuid.uuid4().hex}.nc" if keep_run_file else None
    if output is not None:
        output.parent.mkdir(parents=True, exist_ok=True)
    try:
        result = run_loaded(lambda: load_bundled_case(bundle, materialise(bundle, blobs, folder),
                                                      overrides),
                            timeseries, None if output is None else str(output))
        if output is not None and output.is_file():
            try:
                result["run_file_bytes"] = output.read_bytes()
            except OSError as err:
                result["status"] = f"failed: run file not read back on the worker: {err}"
    finally:
        if output is not None:
            for leftover in (output, output.with_name(output.name + ".checkpoint")):
                leftover.unlink(missing_ok=True)
    return result


def _address() -> str:
    try:
        from distributed import get_worker

        return str(get_worker().address)
    except (ImportError, ValueError):
        return "(not a Dask worker)"


def _outcome(future: "Future") -> dict[str, Any]:
    """The result of a finished task; a failed one (its worker lost, the scheduler gone)
    as a failed run saying why."""
    if future.status == "finished":
        return future.result()
    if future.status == "cancelled":
        return failed_result("failed: cancelled on the cluster (its scheduler or workers "
                             "went away); re-run the campaign to run it")
    err = future.exception()
    return failed_result(f"failed: lost on the cluster ({type(err).__name__}: "
                         f"{str(err).strip().splitlines()[0] if str(err).strip() else ''}); "
                         "re-run the campaign to run it")


def _keep(record: Record, k: int, index: tuple[int, ...], run_file: str | None,
          result: dict[str, Any]) -> None:
    """Write the run file a worker sent (the client's runs folder), then record the run; a
    run file that cannot be written fails the run."""
    data = result.pop("run_file_bytes", None)
    if run_file is not None and data is not None:
        try:
            with atomic_target(run_file) as tmp:
                tmp.write_bytes(data)
        except OSError as err:
            result = {**failed_result(f"failed: run file not written: {err}"),
                      "compute_time_s": result["compute_time_s"],
                      "wall_time_s": result["wall_time_s"]}
    record(k, index, run_file, result)


def execute_on_cluster(address: str, campaigns: Sequence[tuple[Sequence["Case"], bool]],
                       jobs: Sequence[Job], record: Record, save: Callable[[], None]) -> None:
    """Run ``jobs`` on the cluster at ``address``, recording each result as it arrives and
    saving after each batch; when interrupted, the finished runs are recorded and saved and
    the others cancelled, then the interrupt goes on.

    Parameters
    ----------
    campaigns
        Of every campaign the jobs belong to (by number): the case of each of its runs
        left (loaded on the client), whose files make the campaign's bundle, and whether its
        histories are kept. The files of all the campaigns are scattered together, each
        distinct content once.
    jobs
        The runs, submitted in this order (the scheduler's priority).

    Raises
    ------
    SchedulerError
        The scheduler does not answer or has no workers (nothing run).
    WorkerVersionError
        A worker runs another floatmoor (nothing run).
    BundleError
        A file a case names cannot be read (nothing run).
    """
    from distributed import as_completed

    bundles: dict[int, tuple[RunBundle, dict[str, bytes]]] = {
        k: make_bundle(cases) for k, (cases, _) in enumerate(campaigns) if cases}
    blobs = {digest: data for _, files in bundles.values() for digest, data in files.items()}
    with connect(address) as client:
        check_workers(client, address)
        scattered = client.scatter({f"floatmoor-file-{digest}": data
                                    for digest, data in blobs.items()}, broadcast=True) \
            if blobs else {}
        shipped = {key.removeprefix("floatmoor-file-"): future
                   for key, future in scattered.items()}
        expected = worker_identity()
        futures = {}
        for k, index, overrides, run_file in jobs:
            bundle, files = bundles[k]
            futures[client.submit(run_bundled, bundle, {d: shipped[d] for d in files},
                                  overrides, campaigns[k][1], run_file is not None, expected,
                                  pure=False)] = (k, index, run_file)
        pending = dict(futures)
        try:
            for batch in as_completed(futures).batches():
                for future in batch:
                    _keep(record, *futures[future], _outcome(future))
                    pending.pop(future)
                save()
        except BaseException:
            for future, (k, index, run_file) in list(pending.items()):
                if future.status == "finished":
                    _keep(record, k, index, run_file, future.result())
            save()
            client.cancel([f for f in pending if f.status != "finished"])
            raise
