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
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np
from numpy.typing import NDArray

from floatmoor.campaign.design import Axis, CampaignDesign
from floatmoor.campaign.runner import run_campaign, validate_campaign
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

__all__ = ["StudyRunsFailed", "run_study", "study_design",
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
    folder = Path(folder)
    nodes, weights, campaign_design = study_design(study)
    if study.case is not None:
        validate_campaign(study.case, campaign_design, study.base_overrides, timeseries=True)
        folder.mkdir(exist_ok=True)
        runs = _run_case(study, folder, nodes, weights, campaign_design, workers, scheduler,
                         progress, restart, moved_aside)
    else:
        folder.mkdir(exist_ok=True)
        runs = _run_model(study, nodes, weights, progress)
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


def _run_case(study: Study, folder: Path, nodes: NDArray[np.float64],
              weights: NDArray[np.float64] | None, campaign_design: CampaignDesign,
              workers: int, scheduler: str | None, progress: Progress | None, restart: bool,
              moved_aside: Callable[[Path, Path], None] | None) -> StudyRuns:
    campaign = run_campaign(study.case, campaign_design, base_overrides=study.base_overrides,
                            output=folder / RUNS_NAME, workers=workers, scheduler=scheduler,
                            timeseries=True, progress=progress, restart=restart,
                            moved_aside=moved_aside)
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
