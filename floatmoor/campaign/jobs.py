"""What a campaign's executors (local processes, a Dask cluster) are given and report back."""

from __future__ import annotations

from typing import Any, Callable

__all__ = ["Job", "Record"]

#: (index along each axis, overrides, run file or None) of a run to execute.
Job = tuple[tuple[int, ...], list[str], "str | None"]
#: Called with (index, run file, result) of every run that completes.
Record = Callable[[tuple[int, ...], "str | None", dict[str, Any]], None]
