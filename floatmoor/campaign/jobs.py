"""What a campaign's executors (local processes, a Dask cluster) are given and report back.

The executors run the jobs of one or several campaigns as one pool
(:func:`floatmoor.campaign.runner.run_campaigns`): each job carries the number of its
campaign in the submission, and its result goes back to that campaign's store.
"""

from __future__ import annotations

from typing import Any, Callable

__all__ = ["Job", "Record"]

#: (campaign number, index along each axis, overrides, run file or None) of a run to execute.
Job = tuple[int, tuple[int, ...], list[str], "str | None"]
#: Called with (campaign number, index, run file, result) of every run that completes.
Record = Callable[[int, tuple[int, ...], "str | None", dict[str, Any]], None]
