"""Running a study: the design's runs, the surrogates, the results file and the report.

A case study runs its design as one campaign (:func:`floatmoor.campaign.runner.run_campaign`):
one zipped axis of all uncertain keys whose values are the design nodes, time series kept,
into ``DIR/runs.nc``, so an interrupted study resumes from the runs that finished. A built-in
model study evaluates the model at the nodes. Then one gPC surrogate is fitted per quantity
of interest (:func:`floatmoor.uq.propagate.fit`) and saved to ``DIR/surrogates/NAME.nc``,
the results go to ``DIR/uq.nc`` (:mod:`floatmoor.uq.output`) and the figures and summary to
``DIR/report`` (:mod:`floatmoor.uq.report`).

A quadrature rule needs every node: a failed run (or a run whose quantity is not finite)
fails the study (:class:`StudyRunsFailed`, nothing but ``runs.nc`` written). A regression
drops such runs, says so in the results and fits on the others.

Several studies submitted together (:func:`run_studies`, ``floatmoor uq A.toml B.toml -o A
-o B``) run their case runs as one pool of jobs on the same workers, taken in turn from each
study, each into its own ``runs.nc``; each study is then finished on its own
(:func:`finish_study`), so a failed run fails only its study.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.campaign.design import Axis, CampaignDesign
from floatmoor.campaign.runner import (
    PreparedCampaign, prepare_campaign, run_campaigns, validate_campaign,
)
from floatmoor.case.naming import toml_text
from floatmoor.errors import FloatmoorError
from floatmoor.io.netcdf import write_dataset
from floatmoor.uq.output import build_uq_dataset
from floatmoor.uq.propagate import QuadratureMethod, design, fit
from floatmoor.uq.quantities import history_times, quantity_values
from floatmoor.uq.report import write_study_report
from floatmoor.uq.results import StudyResult, StudyRuns
from floatmoor.uq.study import Study
from floatmoor.uq.taut_string import BUILTIN_MODELS

__all__ = ["StudyRunsFailed", "run_study", "study_design", "PreparedStudy", "prepare_study",
           "run_studies", "finish_study",
           "RUNS_NAME", "RESULTS_NAME", "SURROGATES_NAME", "REPORT_NAME"]

RUNS_NAME, RESULTS_NAME, SURROGATES_NAME, REPORT_NAME = "runs.nc", "uq.nc", "surrogates", \
    "report"

Progress = Callable[[int, int, float], None]


class StudyRunsFailed(FloatmoorError, RuntimeError):
    """Runs of a quadrature design failed (or gave non-finite quantities): the rule needs
    every node, so no surrogate is built.

    Parameters
    ----------
    failed
        (run label: its input values; why) of every such run.
    total
        Runs in the design.
    """

    def __init__(self, failed: Sequence[tuple[str, str]], total: int) -> None:
        self.failed = list(failed)
        self.total = total
        super().__init__(f"{len(self.failed)} of {total} runs of the quadrature design failed "
                         "(every node is needed): " + "; ".join(f"{label}: {why}" for label,
                                                                 why in self.failed[:3]))


def study_design(study: Study) -> tuple[NDArray[np.float64], NDArray[np.float64] | None,
                                        CampaignDesign]:
    """The design nodes and weights, and the campaign running them (one zipped axis)."""
    nodes, weights = design(list(study.inputs), study.method)
    nodes = np.asarray(nodes, dtype=float)
    axis = Axis(study.keys, tuple(tuple(float(v) for v in nodes[:, k])
                                  for k in range(nodes.shape[1])))
    return nodes, None if weights is None else np.asarray(weights, dtype=float), \
        CampaignDesign((axis,))


def _label(keys: Sequence[str], row: NDArray[np.float64]) -> str:
    return ", ".join(f"{k}={toml_text(float(v))}" for k, v in zip(keys, row))


def run_study(study: Study, folder: str | Path, *, workers: int = 1,
              scheduler: str | None = None, progress: Progress | None = None,
              restart: bool = False,
              moved_aside: Callable[[Path, Path], None] | None = None) -> StudyResult:
    """Run ``study`` into ``folder`` (created if its parent exists).

    Parameters
    ----------
    study
        The checked study (:func:`floatmoor.uq.study.load_study`).
    folder
        Output folder: ``runs.nc`` (case studies), ``uq.nc``, ``surrogates/``, ``report/``.
    workers, scheduler
        Local worker processes, or a Dask scheduler address, for the case runs.
    progress
        Called with (runs done, runs in total, estimated seconds left).
    restart, moved_aside
        Start the runs afresh (``runs.nc`` moved aside, never deleted), as ``sweep
        --restart`` does; see :func:`floatmoor.campaign.runner.run_campaign`.

    Raises
    ------
    CaseError, HydroDatabaseError
        For bad input found when checking every run (nothing written).
    StudyRunsFailed
        When runs of a quadrature design failed (``runs.nc`` holds them).
    """
    prepared = prepare_study(study, folder, restart=restart, moved_aside=moved_aside)
    run_studies([prepared], workers=workers, scheduler=scheduler, progress=progress)
    return finish_study(prepared)


class PreparedStudy:
    """A checked study with its folder made and its runs resumed (:func:`prepare_study`),
    ready for :func:`run_studies` and then :func:`finish_study`.

    Attributes
    ----------
    study, folder
        The study and its output folder.
    nodes, weights
        The design's nodes and weights (None for a regression).
    campaign
        The campaign of a case study's runs (None for a built-in model).
    runs
        The model study's evaluations once :func:`run_studies` ran them.
    """

    def __init__(self, study: Study, folder: Path, nodes: NDArray[np.float64],
                 weights: NDArray[np.float64] | None,
                 campaign: PreparedCampaign | None) -> None:
        self.study, self.folder, self.nodes, self.weights = study, folder, nodes, weights
        self.campaign = campaign
        self.runs: StudyRuns | None = None


def prepare_study(study: Study, folder: str | Path, *, restart: bool = False,
                  moved_aside: Callable[[Path, Path], None] | None = None) -> PreparedStudy:
    """Check every run of ``study``, make ``folder`` and resume ``folder/runs.nc``; nothing
    runs. The arguments and errors are :func:`run_study`'s."""
    folder = Path(folder)
    nodes, weights, campaign_design = study_design(study)
    campaign = None
    if study.case is not None:
        validate_campaign(study.case, campaign_design, study.base_overrides, timeseries=True)
        folder.mkdir(exist_ok=True)
        campaign = prepare_campaign(study.case, campaign_design,
                                    base_overrides=study.base_overrides,
                                    output=folder / RUNS_NAME, timeseries=True,
                                    restart=restart, moved_aside=moved_aside)
    else:
        folder.mkdir(exist_ok=True)
    return PreparedStudy(study, folder, nodes, weights, campaign)


def run_studies(studies: Sequence[PreparedStudy], *, workers: int = 1,
                scheduler: str | None = None, progress: Progress | None = None,
                finished: Callable[[int], None] | None = None,
                saved: Callable[[int], None] | None = None) -> None:
    """Run the runs of several studies as one pool of jobs on the same workers
    (:func:`floatmoor.campaign.runner.run_campaigns`: their runs taken in turn, each into
    its study's ``runs.nc``); a built-in model study is evaluated here first.

    Parameters
    ----------
    studies
        From :func:`prepare_study`, each into its own folder.
    workers, scheduler
        Local worker processes, or a Dask scheduler address.
    progress
        Called with (runs done, runs in total, estimated seconds left) of the case studies'
        runs together (of the model study's evaluations when it is alone).
    finished
        Called with a study's number once all its runs are done.
    saved
        Called with a study's number after each write of its ``runs.nc``.
    """
    cases: list[int] = []
    campaigns: list[PreparedCampaign] = []
    for k, prepared in enumerate(studies):
        if prepared.campaign is not None:
            cases.append(k)
            campaigns.append(prepared.campaign)
            continue
        prepared.runs = _run_model(prepared.study, prepared.nodes, prepared.weights,
                                   progress if len(studies) == 1 else None)
        if finished is not None:
            finished(k)
    if not campaigns:
        return
    run_campaigns(campaigns, workers=workers, scheduler=scheduler, progress=progress,
                  finished=None if finished is None else lambda n: finished(cases[n]),
                  saved=None if saved is None else lambda n: saved(cases[n]))


def finish_study(prepared: PreparedStudy) -> StudyResult:
    """Fit the surrogates of a study whose runs :func:`run_studies` ran, and write its
    ``surrogates/``, ``uq.nc`` and ``report/``.

    Raises
    ------
    StudyRunsFailed
        When runs of a quadrature design failed (``runs.nc`` holds them).
    """
    study, folder = prepared.study, prepared.folder
    if prepared.campaign is not None:
        runs = _case_runs(study, prepared.nodes, prepared.weights,
                          prepared.campaign.dataset())
    else:
        assert prepared.runs is not None, "the model study was not run (run_studies)"
        runs = prepared.runs
    if isinstance(study.method, QuadratureMethod):
        _refuse_missing(study, runs)
    surrogates = {q.name: fit(list(study.inputs), study.method, runs.nodes, runs.weights,
                              runs.outputs[q.name]) for q in study.quantities}
    dropped = sorted({int(k) for values in runs.outputs.values()
                      for k in np.flatnonzero(~np.all(np.isfinite(values), axis=1))})
    (folder / SURROGATES_NAME).mkdir(exist_ok=True)
    for q in study.quantities:
        surrogates[q.name].save(folder / SURROGATES_NAME / f"{q.name}.nc", {
            "study_file": study.path, "study_toml": study.text, "quantity": q.name,
            "quantity_description": q.describe()}, output_units=q.units or "1")
    dataset = build_uq_dataset(study, runs, surrogates, dropped)
    write_dataset(dataset, folder / RESULTS_NAME)
    result = StudyResult(study, runs, surrogates, dataset, dropped, folder)
    write_study_report(result, folder / REPORT_NAME)
    return result


def _case_runs(study: Study, nodes: NDArray[np.float64], weights: NDArray[np.float64] | None,
               campaign: xr.Dataset) -> StudyRuns:
    """The study's view of its campaign: each run's status and quantities."""
    status = [str(s) for s in campaign["status"].values]
    outputs, times = {}, {}
    for q in study.quantities:
        outputs[q.name] = quantity_values(q, campaign)
        times[q.name] = history_times(q, campaign) if q.is_history else None
    labels = [_label(study.keys, row) for row in nodes]
    return StudyRuns(nodes, weights, labels, status, outputs, times)


def _run_model(study: Study, nodes: NDArray[np.float64], weights: NDArray[np.float64] | None,
               progress: Progress | None) -> StudyRuns:
    model = BUILTIN_MODELS[study.model]
    (quantity,) = study.quantities
    values, status = np.full((len(nodes), 1), np.nan), []
    for k, row in enumerate(nodes):
        parameters: dict[str, Any] = {**study.parameters,
                                      **{key: float(v) for key, v in zip(study.keys, row)}}
        try:
            values[k, 0] = float(model.function(**parameters))
            status.append("complete" if math.isfinite(values[k, 0]) else
                          "failed: the model gave a non-finite value")
        except (ArithmeticError, ValueError) as err:  # a model's domain error: that run fails
            status.append(f"failed: {type(err).__name__}: {err}")
    if progress is not None:
        progress(len(nodes), len(nodes), 0.0)
    labels = [_label(study.keys, row) for row in nodes]
    return StudyRuns(nodes, weights, labels, status, {quantity.name: values},
                     {quantity.name: None})


def _refuse_missing(study: Study, runs: StudyRuns) -> None:
    """A quadrature rule needs every node: name the runs that failed or gave non-finite
    values."""
    bad = []
    for k, (label, status) in enumerate(zip(runs.labels, runs.status)):
        if status != "complete":
            bad.append((label, status))
            continue
        names = [q.name for q in study.quantities
                 if not np.all(np.isfinite(runs.outputs[q.name][k]))]
        if names:
            bad.append((label, "non-finite values of " + ", ".join(names)))
    if bad:
        raise StudyRunsFailed(bad, len(runs.labels))
