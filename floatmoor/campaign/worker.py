"""One run of a campaign, as executed on a worker (a local process or a Dask worker).

The function takes and returns plain Python data only, so it pickles to any executor.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

__all__ = ["run_one", "SUMMARY_STATISTICS"]

#: Fairlead-tension statistics kept per run and line (see floatmoor.post.summary).
SUMMARY_STATISTICS = ("mean", "std", "min", "max", "mean_cycle_max")


def run_one(case_path: str, overrides: list[str], timeseries: bool = False) -> dict[str, Any]:
    """Run a case with overrides; never raises for a failing run.

    Returns
    -------
    dict
        ``status`` ("complete" or "failed: message"), ``compute_time_s`` (CPU time of the run
        in this process), ``wall_time_s``, ``statistics`` {line: {statistic: value [N]}}, and
        with ``timeseries`` the output ``time`` and ``fairlead_tension`` (line, time) arrays.
    """
    from floatmoor.case.load import load_case
    from floatmoor.post.summary import run_summary
    from floatmoor.simulation.forced import run_forced_motion

    cpu, wall = time.process_time(), time.perf_counter()
    out: dict[str, Any] = {"status": "complete", "statistics": {}}
    try:
        case = load_case(case_path, overrides)
        dataset = run_forced_motion(case).dataset
        summary = run_summary(case, dataset)
        for name, entry in summary["lines"].items():
            stats = entry["fairlead_tension_N"]
            out["statistics"][name] = {k: (np.nan if stats[k] is None else float(stats[k]))
                                       for k in SUMMARY_STATISTICS}
        if timeseries:
            out["time"] = dataset["time"].values
            out["fairlead_tension"] = dataset["fairlead_tension"].values
    except Exception as err:  # a campaign records any failure and goes on
        text = str(err).strip().splitlines()[0] if str(err).strip() else ""
        out["status"] = f"failed: {type(err).__name__}: {text}"
    out["compute_time_s"] = time.process_time() - cpu
    out["wall_time_s"] = time.perf_counter() - wall
    return out
