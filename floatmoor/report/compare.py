"""``floatmoor compare``: run one case once per line model and report the runs side by side,
as the quasi-dynamic paper's section 5 compares the quasi-static, quasi-dynamic and dynamic
models.

Every line of the case gets the model of the run (``--set lines.<i>.model="MODEL"`` for every
line i, after the user's overrides). The runs' cases are all validated before any runs. The
campaign machinery (:mod:`floatmoor.campaign`) keeps only statistics of forced-motion runs, so
the runs go here, in this process or on local worker processes, each writing its result file
``runs/<model>.nc`` in the output folder; the report then reads them.
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Callable, Mapping, Sequence

from floatmoor.case.load import load_case
from floatmoor.case.schema import AVAILABLE_LINE_MODELS, Case
from floatmoor.report.build import ReportFiles, check_output_folder, write_report
from floatmoor.report.reference import ReferenceValues
from floatmoor.report.runs import ReportInputError, load_run

__all__ = ["parse_models", "model_overrides", "run_model", "compare_models", "RUNS_FOLDER"]

#: Subfolder of the output holding the result file of each model.
RUNS_FOLDER = "runs"


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


def model_overrides(case: Case, model: str) -> list[str]:
    """``lines.<i>.model="MODEL"`` for every line of ``case``."""
    return [f'lines.{i}.model="{model}"' for i in range(len(case.lines))]


def run_model(case_path: str, overrides: list[str], output: str) -> str:
    """Run a case (forced motion or coupled) into ``output``; returns the output path.

    A top-level function so that it pickles to worker processes.
    """
    case = load_case(case_path, overrides)
    if case.floater is not None:
        from floatmoor.simulation.coupled_run import run_coupled

        run_coupled(case, output=output)
    else:
        from floatmoor.simulation.forced import run_forced_motion

        run_forced_motion(case, output=output)
    return output


def compare_models(case_path: str | Path, models: Sequence[str], output: str | Path, *,
                   overrides: Sequence[str] = (), start: float | None = None,
                   reference: ReferenceValues | None = None,
                   nominal_diameters: Mapping[str, float] | None = None,
                   html: bool = False, workers: int = 1,
                   progress: Callable[[str], None] | None = None) -> ReportFiles:
    """Run ``case_path`` once per line model and write the comparison report.

    Parameters
    ----------
    case_path
        The case file.
    models
        Line models, one run each (column order of the report).
    output
        Report folder; the runs go to ``output/runs/<model>.nc``.
    overrides
        ``--set`` overrides applied to every run before the model.
    start, reference, nominal_diameters, html
        As :func:`floatmoor.report.build.write_report` (``start`` None: the case's ramp).
    workers
        Local worker processes (1: run in this process, one after the other).
    progress
        Called with a message as each run finishes.

    Raises
    ------
    CaseError
        For a bad case or override (nothing run or written).
    ReportInputError
        For bad models, workers or output folder (nothing run or written).
    SolverError
        When a run fails (its partial result is in ``output/runs``).
    """
    models = parse_models(list(models))
    if workers < 1:
        raise ReportInputError("--workers", "a whole number >= 1", str(workers))
    output = check_output_folder(output)
    case_path = str(case_path)
    base = load_case(case_path, list(overrides))
    jobs = []
    for model in models:
        run_overrides = [*overrides, *model_overrides(base, model)]
        load_case(case_path, run_overrides)  # every run's case is valid before anything runs
        jobs.append((model, run_overrides))
    if start is not None and start >= base.simulation.duration:
        raise ReportInputError("--start", f"a time before the end of the runs "
                               f"({base.simulation.duration:g} s)", f"{start:g} s")
    folder = output / RUNS_FOLDER
    folder.mkdir(parents=True, exist_ok=True)
    paths = {model: str(folder / f"{model}.nc") for model in models}
    if workers == 1:
        for model, run_overrides in jobs:
            run_model(case_path, run_overrides, paths[model])
            if progress is not None:
                progress(f"{model} run done: {paths[model]}")
    else:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            futures = {model: pool.submit(run_model, case_path, run_overrides, paths[model])
                       for model, run_overrides in jobs}
            for model, future in futures.items():
                future.result()
                if progress is not None:
                    progress(f"{model} run done: {paths[model]}")
    runs = [load_run(paths[model], start=start, label=model) for model in models]
    title = f"{base.title}: line models compared ({', '.join(models)})"
    return write_report(runs, output, reference=reference,
                        nominal_diameters=nominal_diameters, html=html, title=title)
