"""The results of a campaign: one labelled dataset, written as runs complete.

Dimensions: one per campaign axis (named by its first key, zipped keys as extra coordinates),
``line``, and with time series ``time``. Variables: ``status`` (``complete``, ``failed: ...``
or ``pending``), ``compute_time_s`` and ``wall_time_s`` per run, and per run and line the
fairlead-tension statistics; runs that failed or have not run hold NaN there. Attributes:
the case file and text, the base overrides and the design, so a re-run can resume.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from floatmoor._version import __version__
from floatmoor.campaign.design import CampaignDesign
from floatmoor.campaign.worker import SUMMARY_STATISTICS
from floatmoor.errors import CaseError
from floatmoor.io.netcdf import read_dataset, write_dataset

__all__ = ["CampaignStore"]

_LONG_NAMES = {
    "mean": "mean fairlead tension after the ramp",
    "std": "standard deviation of the fairlead tension after the ramp",
    "min": "minimum fairlead tension after the ramp",
    "max": "maximum fairlead tension after the ramp",
    "mean_cycle_max": "mean of the per-cycle maxima of the fairlead tension",
}


def _coordinate(values: tuple[Any, ...]) -> np.ndarray:
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.array(values, dtype=float)
    return np.array([json.dumps(v) if not isinstance(v, str) else v for v in values], dtype=str)


class CampaignStore:
    """Collects run results into arrays shaped like the design.

    Parameters
    ----------
    design
        The campaign's axes.
    case_path, case_text, base_overrides
        What every run starts from (stored for provenance and resume checks).
    lines
        Line names of the case.
    """

    def __init__(self, design: CampaignDesign, case_path: str, case_text: str,
                 base_overrides: list[str], lines: list[str]) -> None:
        self.design = design
        self.lines = lines
        shape = design.shape
        self.status = np.full(shape, "pending", dtype=object)
        self.compute_time = np.full(shape, np.nan)
        self.wall_time = np.full(shape, np.nan)
        self.statistics = {k: np.full(shape + (len(lines),), np.nan) for k in SUMMARY_STATISTICS}
        self.time: np.ndarray | None = None
        self.series: np.ndarray | None = None
        self.attrs = {
            "title": "floatmoor campaign",
            "case_file": case_path,
            "case_toml": case_text,
            "case_overrides": "\n".join(base_overrides) if base_overrides else "none",
            "campaign_design": json.dumps([{"keys": list(a.keys), "values": [list(v) for v in
                                                                            a.values]}
                                           for a in design.axes]),
            "floatmoor_version": __version__,
        }

    # -- filling ---------------------------------------------------------------------------
    def record(self, index: tuple[int, ...], result: dict[str, Any]) -> None:
        """Store one run's result."""
        self.status[index] = result["status"]
        self.compute_time[index] = result["compute_time_s"]
        self.wall_time[index] = result["wall_time_s"]
        for i, line in enumerate(self.lines):
            stats = result["statistics"].get(line)
            for key in SUMMARY_STATISTICS:
                self.statistics[key][index + (i,)] = np.nan if stats is None else stats[key]
        if "fairlead_tension" in result:
            if self.series is None:
                self.time = np.asarray(result["time"])
                self.series = np.full(self.design.shape + (len(self.lines), self.time.size),
                                      np.nan)
            if np.asarray(result["time"]).shape != self.time.shape:
                raise CaseError("--timeseries", "", "runs with the same output times",
                                "runs of different durations or output intervals")
            self.series[index] = result["fairlead_tension"]

    def done(self, index: tuple[int, ...]) -> bool:
        """Whether the run at ``index`` completed."""
        return self.status[index] == "complete"

    # -- resume ----------------------------------------------------------------------------
    def resume_from(self, path: Path) -> int:
        """Take the completed runs of an earlier, identical campaign; returns their number.

        Raises
        ------
        CaseError
            If the file holds another campaign (case, overrides or design differ).
        """
        old = read_dataset(path)
        for key in ("case_toml", "case_overrides", "campaign_design"):
            if old.attrs.get(key) != self.attrs[key]:
                raise CaseError(str(path), key.replace("_", " "),
                                "the same campaign to resume (or another output file)",
                                "a different one in the existing file")
        status = old["status"].values.astype(str)
        for index in zip(*np.nonzero(status == "complete")):
            index = tuple(int(i) for i in index)
            self.status[index] = "complete"
            self.compute_time[index] = old["compute_time_s"].values[index]
            self.wall_time[index] = old["wall_time_s"].values[index]
            for key in SUMMARY_STATISTICS:
                self.statistics[key][index] = old[f"fairlead_tension_{key}"].values[index]
            if "fairlead_tension" in old:
                if self.series is None:
                    self.time = old["time"].values
                    self.series = np.full(old["fairlead_tension"].shape, np.nan)
                self.series[index] = old["fairlead_tension"].values[index]
        return int(np.sum(status == "complete"))

    # -- output ----------------------------------------------------------------------------
    def dataset(self) -> xr.Dataset:
        """The campaign as a labelled dataset."""
        dims = tuple(a.name for a in self.design.axes)
        coords: dict[str, Any] = {}
        for axis in self.design.axes:
            for key, values in zip(axis.keys, axis.values):
                coords[key] = (axis.name, _coordinate(values), {
                    "long_name": f"swept case key {key}", "units": "as in the case file"})
        coords["line"] = ("line", np.array(self.lines, dtype=str),
                          {"long_name": "mooring line name", "units": "1"})
        data = {
            "status": (dims, self.status.astype(str),
                       {"long_name": "run status", "units": "1"}),
            "compute_time_s": (dims, self.compute_time,
                               {"long_name": "CPU time of the run", "units": "s"}),
            "wall_time_s": (dims, self.wall_time,
                            {"long_name": "wall time of the run", "units": "s"}),
        }
        for key in SUMMARY_STATISTICS:
            data[f"fairlead_tension_{key}"] = (dims + ("line",), self.statistics[key],
                                               {"long_name": _LONG_NAMES[key], "units": "N"})
        if self.series is not None:
            coords["time"] = ("time", self.time, {"long_name": "simulated time", "units": "s"})
            data["fairlead_tension"] = (dims + ("line", "time"), self.series,
                                        {"long_name": "line tension at the fairlead",
                                         "units": "N"})
        attrs = dict(self.attrs)
        attrs["created"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
        attrs["runs_complete"] = int(np.sum(self.status == "complete"))
        attrs["runs_failed"] = int(sum(str(s).startswith("failed") for s in self.status.flat))
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def write(self, path: str | os.PathLike[str]) -> None:
        """Write the campaign so far (atomically)."""
        write_dataset(self.dataset(), path)
