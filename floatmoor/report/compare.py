"""``floatmoor compare``: run one case once per line model and report the runs side by side,
as the quasi-dynamic paper's section 5 compares the quasi-static, quasi-dynamic and dynamic
models.

The runs are a campaign (:mod:`floatmoor.campaign`) with one axis, ``lines.*.model`` (every
line's model), one value per model (after the user's overrides). It runs in this process, on local worker processes or on a Dask cluster, each run
writing its full result file ``runs/<model>.nc`` in the output folder and the campaign file
``runs/campaign.nc`` beside them; the report then reads the run files. A re-run of the same
comparison resumes: models whose run file is complete are not run again.
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable, Mapping, Sequence

from floatmoor.campaign.design import Axis, CampaignDesign
from floatmoor.campaign.runner import run_campaign, validate_campaign
from floatmoor.case.load import load_case
from floatmoor.case.schema import AVAILABLE_LINE_MODELS, Case
from floatmoor.errors import SolverError
from floatmoor.io.run_case import default_start
from floatmoor.report.build import ReportFiles, check_output_folder, write_report
from floatmoor.report.reference import ReferenceValues
from floatmoor.report.runs import ReportInputError, load_run

__all__ = ["parse_models", "model_overrides", "model_design", "compare_models",
           "check_report_window", "excitation_period", "RUNS_FOLDER", "CAMPAIGN_FILE",
           "MODEL_KEY", "REPORT_MIN_PERIODS"]

#: Subfolder of the output holding the result file of each model.
RUNS_FOLDER = "runs"
#: The campaign file of the comparison, in the runs folder (what a re-run resumes from).
CAMPAIGN_FILE = "campaign.nc"


def parse_models(text: str | Sequence[str]) -> list[str]:
    """Line models from ``"quasi-static,dynamic"`` (or a list), checked.

    Raises
    ------
    ReportInputError
        For an unknown, repeated or missing model name.
    """
    items = [m.strip() for m in (text.split(",") if isinstance(text, str) else text)]
    items = [m for m in items if m]
    expected = "comma-separated line models among " + ", ".join(AVAILABLE_LINE_MODELS)
    if not items:
        raise ReportInputError("--models", expected, f"'{text}'")
    for model in items:
        if model not in AVAILABLE_LINE_MODELS:
            raise ReportInputError("--models", expected, f"'{model}'")
    if len(set(items)) != len(items):
        raise ReportInputError("--models", expected + ", each once", f"'{text}'")
    return items


#: The key setting every line's model.
MODEL_KEY = "lines.*.model"


def model_overrides(model: str) -> list[str]:
    """The override giving every line ``model``: ``lines.*.model="MODEL"``."""
    return [f'{MODEL_KEY}="{model}"']


#: Excitation periods the analysis window of a compared run must span: the report plots the
#: exceedance of the local tension maxima and minima, and a window of two periods holds a
#: whole cycle, so at least one of each, of a response periodic with the excitation.
REPORT_MIN_PERIODS = 2.0


def excitation_period(case: Case) -> float | None:
    """The period of a case's excitation [s]: its motion's cycle, its regular waves' period or
    its sea state's peak period; None without one (a table, free decay, still water)."""
    if case.motion is not None:
        return case.motion.cycle_period
    settings = getattr(case.waves, "settings", None)
    period = getattr(settings, "period", None) or getattr(settings, "tp", None)
    return float(period) if period else None


def check_report_window(case: Case, start: float | None) -> None:
    """Check, before any run, that the runs of ``case`` will be long enough for their report:
    two output samples after the window start (as :func:`floatmoor.report.runs.prepare_run`
    asks) and :data:`REPORT_MIN_PERIODS` excitation periods.

    Raises
    ------
    ReportInputError
        Naming the duration needed and the one the case gives.
    """
    sim = case.simulation
    begin, source = (start, "--start") if start is not None else default_start(case)
    period = excitation_period(case)
    need = max(begin + sim.output_interval,
               begin + REPORT_MIN_PERIODS * period if period else 0.0)
    if sim.duration < need:
        why = (f"{REPORT_MIN_PERIODS:g} periods of {period:g} s" if period else
               "two output samples") + f" after the window start {begin:g} s ({source})"
        raise ReportInputError(f"{case.source}: simulation.duration", f"runs of at least "
                               f"{need:g} s for the report ({why})", f"{sim.duration:g} s")


def model_design(models: Sequence[str]) -> CampaignDesign:
    """The campaign of a comparison: one axis, ``lines.*.model``, one value per model."""
    return CampaignDesign((Axis((MODEL_KEY,), (tuple(models),)),))


def compare_models(case_path: str | Path, models: Sequence[str], output: str | Path, *,
                   overrides: Sequence[str] = (), start: float | None = None,
                   reference: ReferenceValues | None = None,
                   nominal_diameters: Mapping[str, float] | None = None,
                   html: bool = False, workers: int = 1, scheduler: str | None = None,
                   progress: Callable[[str], None] | None = None) -> ReportFiles:
    """Run ``case_path`` once per line model (a campaign) and write the comparison report.

    Parameters
    ----------
    case_path
        The case file.
    models
        Line models, one run each (column order of the report).
    output
        Report folder; the runs go to ``output/runs/<model>.nc``, the campaign to
        ``output/runs/campaign.nc``. Models already run there (same case, overrides and
        models, complete run file) are not run again; a campaign of other models or overrides
        (or a damaged campaign file) there is replaced, the old file moved aside to
        ``campaign.nc.bak-N``.
    overrides
        ``--set`` overrides applied to every run before the model.
    start, reference, nominal_diameters, html
        As :func:`floatmoor.report.build.write_report` (``start`` None: the case's ramp).
    workers
        Local worker processes (1: run in this process, one after the other).
    scheduler
        Address of a Dask distributed scheduler to run on instead (its workers are sent the
        case and send the runs back: :mod:`floatmoor.campaign.cluster`).
    progress
        Called with a message as runs finish.

    Raises
    ------
    CaseError
        For a bad case or override (nothing run or written).
    HydroDatabaseError
        For a floater case whose database is missing, damaged, stale or failing a check
        (nothing run or written).
    ReportInputError
        For bad models, workers or output folder, or runs too short for the report
        (:func:`check_report_window`; nothing run or written).
    SolverError
        When a run fails, naming the model and the failure (the other models still run;
        the partial result is in ``output/runs``; no report is written).
    """
    models = parse_models(list(models))
    if workers < 1:
        raise ReportInputError("--workers", "a whole number >= 1", str(workers))
    output = check_output_folder(output)
    case_path = str(case_path)
    base = load_case(case_path, list(overrides))
    if start is not None and start >= base.simulation.duration:
        raise ReportInputError("--start", f"a time before the end of the runs "
                               f"({base.simulation.duration:g} s)", f"{start:g} s")
    check_report_window(base, start)
    design = model_design(models)
    # every run's case (and a floater's database) is valid before anything is written
    validate_campaign(case_path, design, overrides)
    folder = output / RUNS_FOLDER

    def report(done: int, total: int, left: float) -> None:
        if progress is not None and done:
            eta = "" if left != left else f", ~{left:.0f} s left"
            progress(f"{done} / {total} model runs done{eta}")

    output.mkdir(exist_ok=True)
    dataset = run_campaign(case_path, design, base_overrides=list(overrides),
                           output=folder / CAMPAIGN_FILE, workers=workers,
                           scheduler=scheduler, runs_dir=folder, run_names=models,
                           replace_other=True, progress=report)
    failed = [f"{model}: {str(status).removeprefix('failed: ')}"
              for model, status in zip(models, dataset["status"].values) if status != "complete"]
    if failed:
        raise SolverError(f"{len(failed)} of {len(models)} model runs failed (partial results "
                          f"in {folder}; no report written): " + "; ".join(failed))
    paths = {model: str(path) for model, path in zip(models, dataset["run_file"].values)}
    runs = [load_run(paths[model], start=start, label=model) for model in models]
    title = f"{base.title}: line models compared ({', '.join(models)})"
    return write_report(runs, output, reference=reference,
                        nominal_diameters=nominal_diameters, html=html, title=title)
