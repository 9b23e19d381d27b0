"""One run of a campaign, as executed on a worker (a local process or a Dask worker).

:func:`run_one` takes and returns plain Python data only, so it pickles to any executor; a
Dask worker runs :func:`run_loaded` on the case it rebuilt from the client's bundle
(:func:`floatmoor.campaign.cluster.run_bundled`). A case with a ``[floater]`` is a coupled
run (:func:`~floatmoor.simulation.coupled_run.run_coupled`), any other a forced-motion run
(:func:`~floatmoor.simulation.forced.run_forced_motion`).
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from floatmoor.errors import ModelValidityWarning

if TYPE_CHECKING:
    from floatmoor.case.schema import Case

__all__ = ["run_one", "run_loaded", "failed_result", "SUMMARY_STATISTICS",
           "STRENGTH_STATISTICS", "BODY_STATISTICS"]

#: Fairlead-tension statistics kept per run and line (see floatmoor.post.summary).
SUMMARY_STATISTICS = ("mean", "std", "min", "max", "mean_cycle_max")
#: Largest-tension statistics kept per run and line: the campaign name -> the key of the run
#: summary's ``strength`` entry (floatmoor.post.run_strength.line_strength; after the ramp).
STRENGTH_STATISTICS = {"max_line_tension": "max_tension_N",
                       "max_tension_over_mbl": "max_tension_over_mbl"}
#: Floater-displacement statistics kept per run and DOF of coupled runs (after the wave ramp).
BODY_STATISTICS = ("mean", "std", "min", "max")


def run_one(case_path: str, overrides: list[str], timeseries: bool = False,
            run_file: str | None = None) -> dict[str, Any]:
    """Run a case with overrides; never raises for a failing run.

    Parameters
    ----------
    case_path
        The case file.
    overrides
        ``key=VALUE`` overrides of this run (base ones first).
    timeseries
        Also return the histories (fairlead tension; body displacement of coupled runs).
    run_file
        netCDF file to write the run's full output to, as ``floatmoor run -o`` does (partial
        on failure), or None to keep it in memory only.

    Returns
    -------
    dict
        ``status`` ("complete" or "failed: message"), ``compute_time_s`` (CPU time of the run
        in this process), ``wall_time_s``, ``compile_time_s`` (wall time spent compiling
        kernels, 0 once they are cached), ``statistics`` {line: {statistic: value [N]}}
        (fairlead-tension and largest-tension ones; ``max_tension_over_mbl`` in [-]),
        for coupled runs ``body_statistics`` {dof: {statistic: value [m or rad]}}, and with
        ``timeseries`` the output ``time``, ``fairlead_tension`` (line, time) and for coupled
        runs ``body_displacement`` (time, dof) arrays; ``validity_warnings``, the messages
        of the run's :class:`~floatmoor.errors.ModelValidityWarning` (kept for the campaign,
        which warns with them in its own process, not in the worker's).
    """
    from floatmoor.case.load import load_case

    return run_loaded(lambda: (load_case(case_path, overrides), None), timeseries, run_file)


def failed_result(status: str) -> dict[str, Any]:
    """The result of a run that did not run: ``status`` (``failed: ...``), no statistics,
    NaN times."""
    return {"status": status, "statistics": {}, "compile_time_s": 0.0,
            "compute_time_s": float("nan"), "wall_time_s": float("nan")}


def run_loaded(load: Callable[[], "tuple[Case, Path | None]"], timeseries: bool = False,
               run_file: str | None = None) -> dict[str, Any]:
    """:func:`run_one` of the case ``load`` returns with the path of its hydrodynamic
    database (None: the case's own, :func:`floatmoor.hydro.database.database_path`); a
    failure to load is a failed run like any other."""
    from floatmoor._numba import watch_compilation
    from floatmoor.mooring.static_strength import refuse_static_breaking
    from floatmoor.post.summary import run_summary

    cpu, wall = time.process_time(), time.perf_counter()
    out: dict[str, Any] = {"status": "complete", "statistics": {}, "compile_time_s": 0.0}

    def compiled(seconds: float) -> None:
        out["compile_time_s"] += seconds

    try:
        case, database = load()
        refuse_static_breaking(case)  # a line that breaks at rest: the run fails
        with watch_compilation(lambda: None, compiled), \
                warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", ModelValidityWarning)  # returned, not shown here
            dataset = _run(case, database, run_file).dataset
        for w in caught:
            if not issubclass(w.category, ModelValidityWarning):
                warnings.showwarning(w.message, w.category, w.filename, w.lineno)
        summary = run_summary(case, dataset)
        out["validity_warnings"] = summary["validity_warnings"]
        for name, entry in summary["lines"].items():
            stats = entry["fairlead_tension_N"]
            out["statistics"][name] = {k: (np.nan if stats[k] is None else float(stats[k]))
                                       for k in SUMMARY_STATISTICS}
            strength = entry["strength"]
            out["statistics"][name].update(
                {k: (np.nan if strength[key] is None else float(strength[key]))
                 for k, key in STRENGTH_STATISTICS.items()})
        if "body_displacement" in summary:
            out["body_statistics"] = {
                dof: {k: float(stats.get(k, np.nan)) for k in BODY_STATISTICS}
                for dof, stats in summary["body_displacement"].items()}
        if timeseries:
            out["time"] = dataset["time"].values
            out["fairlead_tension"] = dataset["fairlead_tension"].values
            if "body_displacement" in dataset:
                out["body_displacement"] = dataset["body_displacement"].values
    except Exception as err:  # a campaign records any failure and goes on
        text = str(err).strip().splitlines()[0] if str(err).strip() else ""
        out["status"] = f"failed: {type(err).__name__}: {text}"
    out["compute_time_s"] = time.process_time() - cpu
    out["wall_time_s"] = time.perf_counter() - wall
    return out


def _run(case: "Case", database: Path | None, run_file: str | None) -> Any:
    """:func:`floatmoor.simulation.run.run_case`, with a floater's database at ``database``
    when given (the coupled run's settings are otherwise the case's own)."""
    from floatmoor.simulation.run import run_case

    if database is None:
        return run_case(case, output=run_file)
    from dataclasses import replace

    from floatmoor.simulation.coupled_run import run_coupled, settings_from_case

    return run_coupled(case, replace(settings_from_case(case), database=database),
                       output=run_file)
