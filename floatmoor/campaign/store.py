"""The results of a campaign: one labelled dataset, written as runs complete.

Dimensions: one per campaign axis (named by its first key, zipped keys as extra coordinates),
``line``, for cases with a floater ``dof`` (capytaine's names, Surge ... Yaw), and with time
series ``time``. Variables: ``status`` (``complete``, ``failed: ...`` or ``pending``),
``compute_time_s`` and ``wall_time_s`` per run, per run and line the fairlead-tension
statistics, the largest tension at either end (``max_line_tension``) and its ratio to the
line type's minimum breaking load (``max_tension_over_mbl``, NaN without one), per run and
DOF the floater-displacement statistics of coupled runs, and with run files (``--runs-dir``)
``run_file``, the path of each run's full output; runs that failed or have not run hold NaN.
Attributes: the case file and text, the base overrides and the design, so a re-run can
resume.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
from pathlib import Path
from typing import Any, Sequence

import numpy as np
import xarray as xr

from floatmoor._version import __version__
from floatmoor.campaign.design import CampaignDesign
from floatmoor.campaign.reopen import read_campaign_file
from floatmoor.campaign.worker import BODY_STATISTICS, STRENGTH_STATISTICS, SUMMARY_STATISTICS
from floatmoor.errors import CaseError
from floatmoor.io.netcdf import read_attributes, write_dataset
from floatmoor.io.variables import attributes

__all__ = ["CampaignStore", "run_file_is_complete", "same_campaign", "failed_runs"]

_LONG_NAMES = {
    "mean": "mean fairlead tension after the ramp",
    "std": "standard deviation of the fairlead tension after the ramp",
    "min": "minimum fairlead tension after the ramp",
    "max": "maximum fairlead tension after the ramp",
    "mean_cycle_max": "mean of the per-cycle maxima of the fairlead tension",
}
#: The largest-tension variables: name -> (long name, units).
_STRENGTH_VARIABLES = {
    "max_line_tension": ("largest tension at either end of the line after the ramp", "N"),
    "max_tension_over_mbl": ("largest tension after the ramp over the minimum breaking load of "
                             "the line type (NaN: no MBL given)", "1"),
}
_BODY_LONG_NAMES = {
    "mean": "mean floater displacement from equilibrium after the wave ramp",
    "std": "standard deviation of the floater displacement after the wave ramp",
    "min": "minimum floater displacement from equilibrium after the wave ramp",
    "max": "maximum floater displacement from equilibrium after the wave ramp",
}
_BODY_UNITS = attributes("body_displacement")["units"]  # "m or rad": Surge..Heave, Roll..Yaw
#: The attributes that identify a campaign (a re-run resumes only the same campaign).
_IDENTITY = ("case_toml", "case_overrides", "campaign_design")


def _coordinate(values: tuple[Any, ...]) -> np.ndarray:
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.array(values, dtype=float)
    return np.array([json.dumps(v) if not isinstance(v, str) else v for v in values], dtype=str)


def run_file_is_complete(path: str | os.PathLike[str], case_text: str,
                         overrides: Sequence[str]) -> bool:
    """Whether ``path`` holds the complete output of the run of ``case_text`` with ``overrides``.

    Only the attributes are read: the run's status (``complete``), case text and overrides
    (so a file left by another run of the same name is not taken for this one).
    """
    attrs = read_attributes(path)
    return (attrs is not None and attrs.get("status") == "complete"
            and attrs.get("case_toml") == case_text
            and attrs.get("case_overrides") == ("\n".join(overrides) or "none"))


def _identity(design: CampaignDesign, case_text: str, base_overrides: Sequence[str]
              ) -> dict[str, str]:
    return {
        "case_toml": case_text,
        "case_overrides": "\n".join(base_overrides) if base_overrides else "none",
        "campaign_design": json.dumps([{"keys": list(a.keys), "values": [list(v) for v in
                                                                        a.values]}
                                       for a in design.axes]),
    }


def same_campaign(path: str | os.PathLike[str], design: CampaignDesign, case_text: str,
                  base_overrides: Sequence[str]) -> bool:
    """Whether the campaign file ``path`` holds this campaign (same case text, base overrides
    and design), so that a run into it resumes; False for another campaign or an unreadable
    file."""
    attrs = read_attributes(path)
    wanted = _identity(design, case_text, base_overrides)
    return attrs is not None and all(attrs.get(key) == wanted[key] for key in _IDENTITY)


def failed_runs(dataset: xr.Dataset, design: CampaignDesign) -> list[tuple[str, str]]:
    """The runs of a campaign dataset that did not complete, in :meth:`CampaignDesign.runs`
    order: (their swept values as ``key=VALUE, ...``, their status, e.g. ``failed: ...``).

    Parameters
    ----------
    dataset
        A campaign's dataset (:func:`floatmoor.campaign.runner.run_campaign`).
    design
        The campaign's design.

    Returns
    -------
    list of tuple
        (values, status) of each run that did not complete."""
    status = dataset["status"].values
    return [(", ".join(overrides), str(status[index])) for index, overrides in design.runs()
            if str(status[index]) != "complete"]


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
    dofs
        The floater's DOF names (capytaine's) for a case with a floater, else empty: the
        floater-displacement statistics are kept per DOF.
    run_files
        Whether runs write their full output files (``run_file`` is then stored).
    """

    def __init__(self, design: CampaignDesign, case_path: str, case_text: str,
                 base_overrides: list[str], lines: list[str], dofs: Sequence[str] = (),
                 run_files: bool = False) -> None:
        self.design = design
        self.lines = lines
        self.dofs = list(dofs)
        shape = design.shape
        self.status = np.full(shape, "pending", dtype=object)
        self.compute_time = np.full(shape, np.nan)
        self.wall_time = np.full(shape, np.nan)
        self.statistics = {k: np.full(shape + (len(lines),), np.nan) for k in SUMMARY_STATISTICS}
        self.strength = {k: np.full(shape + (len(lines),), np.nan) for k in STRENGTH_STATISTICS}
        self.body_statistics = {k: np.full(shape + (len(self.dofs),), np.nan)
                                for k in BODY_STATISTICS} if self.dofs else {}
        self.run_files = run_files
        self.run_file = np.full(shape, "", dtype=object)
        self.time: np.ndarray | None = None
        self.series: np.ndarray | None = None
        self.body_series: np.ndarray | None = None
        self.attrs = {
            "title": "floatmoor campaign",
            "case_file": case_path,
            **_identity(design, case_text, base_overrides),
            "floatmoor_version": __version__,
        }

    # -- filling ---------------------------------------------------------------------------
    def record(self, index: tuple[int, ...], result: dict[str, Any],
               run_file: str | None = None) -> None:
        """Store one run's result (and the path of its output file, if it wrote one).

        Raises
        ------
        CaseError
            If its histories have other output times than the runs before (nothing stored).
        """
        if "fairlead_tension" in result or ("body_displacement" in result and self.dofs):
            self._check_time(result["time"])  # before anything is stored
        self.status[index] = result["status"]
        self.compute_time[index] = result["compute_time_s"]
        self.wall_time[index] = result["wall_time_s"]
        if run_file is not None:
            self.run_file[index] = run_file
        for i, line in enumerate(self.lines):
            stats = result["statistics"].get(line)
            for key in SUMMARY_STATISTICS:
                self.statistics[key][index + (i,)] = np.nan if stats is None else stats[key]
            for key in STRENGTH_STATISTICS:
                self.strength[key][index + (i,)] = np.nan if stats is None else stats[key]
        body = result.get("body_statistics", {})
        for j, dof in enumerate(self.dofs):
            stats = body.get(dof)
            for key in BODY_STATISTICS:
                self.body_statistics[key][index + (j,)] = np.nan if stats is None else stats[key]
        if "fairlead_tension" in result:
            self._check_time(result["time"])
            if self.series is None:
                self.series = np.full(self.design.shape + (len(self.lines), self.time.size),
                                      np.nan)
            self.series[index] = result["fairlead_tension"]
        elif self.series is not None:  # a failed re-run of a resumed run
            self.series[index] = np.nan
        if "body_displacement" in result and self.dofs:
            self._check_time(result["time"])
            if self.body_series is None:
                self.body_series = np.full(self.design.shape + (self.time.size,
                                                                len(self.dofs)), np.nan)
            self.body_series[index] = result["body_displacement"]
        elif self.body_series is not None:
            self.body_series[index] = np.nan

    def _check_time(self, time: Any) -> None:
        time = np.asarray(time, dtype=float)
        if self.time is None:
            self.time = time
        elif time.shape != self.time.shape:
            raise CaseError("--timeseries", "", "runs with the same output times",
                            "runs of different durations or output intervals")

    def done(self, index: tuple[int, ...]) -> bool:
        """Whether the run at ``index`` completed."""
        return self.status[index] == "complete"

    def set_run_file(self, index: tuple[int, ...], run_file: str) -> None:
        """Record the output file of a run taken over from an earlier campaign."""
        self.run_file[index] = run_file

    # -- resume ----------------------------------------------------------------------------
    def resume_from(self, path: Path) -> int:
        """Take the completed runs of an earlier, identical campaign; returns their number.

        Raises
        ------
        CampaignFileError
            If the file is not this campaign's: not a readable campaign file, or another
            campaign (case, overrides or design differ), or damaged
            (:func:`floatmoor.campaign.reopen.read_campaign_file`).
        """
        old = read_campaign_file(path, self.design, {k: self.attrs[k] for k in _IDENTITY},
                                 self.lines, self.dofs)
        status = old["status"].values.astype(str)
        body = self.dofs and "dof" in old.coords and \
            [str(d) for d in old["dof"].values] == self.dofs
        for index in zip(*np.nonzero(status == "complete")):
            index = tuple(int(i) for i in index)
            self.status[index] = "complete"
            self.compute_time[index] = old["compute_time_s"].values[index]
            self.wall_time[index] = old["wall_time_s"].values[index]
            for key in SUMMARY_STATISTICS:
                self.statistics[key][index] = old[f"fairlead_tension_{key}"].values[index]
            for key in STRENGTH_STATISTICS:  # NaN from a file written before they existed
                if key in old:
                    self.strength[key][index] = old[key].values[index]
            if body:
                for key in BODY_STATISTICS:
                    self.body_statistics[key][index] = \
                        old[f"body_displacement_{key}"].values[index]
            if "run_file" in old:
                self.run_file[index] = str(old["run_file"].values[index])
            if "fairlead_tension" in old:
                if self.series is None:
                    self.time = old["time"].values
                    self.series = np.full(old["fairlead_tension"].shape, np.nan)
                self.series[index] = old["fairlead_tension"].values[index]
            if body and "body_displacement" in old:
                if self.body_series is None:
                    self.time = old["time"].values
                    self.body_series = np.full(old["body_displacement"].shape, np.nan)
                self.body_series[index] = old["body_displacement"].values[index]
        if "run_file" in old:
            self.run_files = True
        return int(np.sum(status == "complete"))

    # -- output ----------------------------------------------------------------------------
    def dataset(self) -> xr.Dataset:
        """The campaign as a labelled dataset; its attributes ``runs_complete`` and
        ``runs_failed`` count the complete and failed runs (a campaign records a failed run
        and goes on: check ``runs_failed``, or :func:`failed_runs`, before using the
        results)."""
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
        if self.run_files:
            data["run_file"] = (dims, self.run_file.astype(str), {
                "long_name": "the run's full output file (netCDF, as floatmoor run writes it; "
                             "empty: not written)", "units": "1"})
        for key in SUMMARY_STATISTICS:
            data[f"fairlead_tension_{key}"] = (dims + ("line",), self.statistics[key],
                                               {"long_name": _LONG_NAMES[key], "units": "N"})
        for key in STRENGTH_STATISTICS:
            long_name, units = _STRENGTH_VARIABLES[key]
            data[key] = (dims + ("line",), self.strength[key],
                         {"long_name": long_name, "units": units})
        if self.dofs:
            coords["dof"] = ("dof", np.array(self.dofs, dtype=str), attributes("dof"))
            for key in BODY_STATISTICS:
                data[f"body_displacement_{key}"] = (
                    dims + ("dof",), self.body_statistics[key],
                    {"long_name": _BODY_LONG_NAMES[key] + ": Surge, Sway, Heave [m], Roll, "
                     "Pitch, Yaw [rad]", "units": _BODY_UNITS})
        if self.series is not None or self.body_series is not None:
            coords["time"] = ("time", self.time, attributes("time"))
        if self.series is not None:
            data["fairlead_tension"] = (dims + ("line", "time"), self.series,
                                        attributes("fairlead_tension"))
        if self.body_series is not None:
            data["body_displacement"] = (dims + ("time", "dof"), self.body_series,
                                         attributes("body_displacement"))
        attrs = dict(self.attrs)
        attrs["created"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
        attrs["runs_complete"] = int(np.sum(self.status == "complete"))
        attrs["runs_failed"] = int(sum(str(s).startswith("failed") for s in self.status.flat))
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def write(self, path: str | os.PathLike[str]) -> None:
        """Write the campaign so far (atomically)."""
        write_dataset(self.dataset(), path)
