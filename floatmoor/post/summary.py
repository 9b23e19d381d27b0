"""The run summary printed by ``floatmoor run``: fairlead-tension statistics per line."""

from __future__ import annotations

from typing import Any

import xarray as xr

from floatmoor.case.schema import Case
from floatmoor.post.statistics import channel_statistics

__all__ = ["run_summary", "format_summary"]


def run_summary(case: Case, dataset: xr.Dataset) -> dict[str, Any]:
    """Statistics of the fairlead tension of every line after the ramp.

    The window starts at the end of the motion ramp (t = 0 without motion). For periodic
    motion the maxima of the complete cycles after the ramp are averaged (``mean_cycle_max``).
    Tensions are in N.
    """
    motion = case.motion
    start = motion.ramp_duration if motion is not None else 0.0
    period = motion.cycle_period if motion is not None else None
    time = dataset["time"].values
    lines: dict[str, Any] = {}
    for line in case.lines:
        series = dataset["fairlead_tension"].sel(line=line.name).values
        lines[line.name] = {"model": line.model, "fairlead_tension_N":
                            channel_statistics(time, series, start=start, period=period)}
    return {
        "title": case.title,
        "case": case.source,
        "overrides": list(case.overrides),
        "status": str(dataset.attrs.get("status", "")),
        "motion_period_s": period,
        "lines": lines,
    }


def format_summary(summary: dict[str, Any]) -> str:
    """A plain-text table of :func:`run_summary`."""
    rows = [f"{summary['title']}",
            "fairlead tension [N] from t = {:.6g} s:".format(
                next(iter(summary["lines"].values()))["fairlead_tension_N"]["window_start"]),
            f"  {'line':<16}{'model':<15}{'mean':>10}{'std':>10}{'min':>10}{'max':>10}"
            f"{'cycle max':>11}{'cycles':>8}"]
    for name, entry in summary["lines"].items():
        s = entry["fairlead_tension_N"]
        cycle = f"{s['mean_cycle_max']:>11.4g}" if s["mean_cycle_max"] is not None else f"{'-':>11}"
        rows.append(f"  {name:<16}{entry['model']:<15}{s['mean']:>10.4g}{s['std']:>10.4g}"
                    f"{s['min']:>10.4g}{s['max']:>10.4g}{cycle}{s['n_cycles']:>8d}")
    return "\n".join(rows)
