"""Writing a report: figures (PNG) and tables of one or more runs, with a Markdown summary.

Everything is made in a temporary folder beside the output folder and moved into it only when
every figure and table succeeded, so a failing report (an empty or NaN series, a bad input)
leaves nothing behind.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence

from floatmoor._version import __version__
from floatmoor.io.output_files import OutputWriteError
from floatmoor.io.shape_samples import has_complete_shapes
from floatmoor.plots.run_figures import plot_shape_views
from floatmoor.report import figures as fig
from floatmoor.report.markdown import Block, Figure, Heading, Paragraph, render_html, \
    render_markdown
from floatmoor.report.reference import ReferenceValues
from floatmoor.report.runs import ReportInputError, RunData, resolve_nominal_diameters
from floatmoor.report.tables import (
    RunAnalysis, analyse_run, decay_table, fatigue_tables, motion_table, runs_table,
    strength_table, tension_tables,
)

__all__ = ["ReportFiles", "write_report", "report_title", "check_output_folder", "SUMMARY_NAME"]

SUMMARY_NAME = "summary.md"


@dataclass
class ReportFiles:
    """What a report wrote."""

    folder: Path
    summary: Path
    figures: list[Path] = field(default_factory=list)
    html: Path | None = None
    analyses: list[RunAnalysis] = field(default_factory=list)


def check_output_folder(path: str | Path, option: str = "-o/--output") -> Path:
    """The output folder, after checking it is (or can be made) a folder.

    Raises
    ------
    ReportInputError
        When it is a file, or its parent folder does not exist.
    CaseError
        When floatmoor cannot write in it (or in its parent, for a new folder).
    """
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ReportInputError(option, "a folder", f"the file '{path}'")
    if not path.exists() and not path.resolve().parent.is_dir():
        raise ReportInputError(option, "a folder in an existing folder", f"'{path}'")
    from floatmoor.io.output_files import check_output_folder as check_writable_folder

    return check_writable_folder(path, option)  # CaseError: not writable


def _check_reference(runs: Sequence[RunData], reference: ReferenceValues) -> None:
    known = {line for run in runs for line in run.lines}
    unknown = sorted(reference.line_names - known)
    if unknown:
        raise ReportInputError(reference.path, "reference lines named as in the runs ("
                               + ", ".join(sorted(known)) + ")",
                               "line(s) " + ", ".join(unknown))


def report_title(runs: Sequence[RunData]) -> str:
    """The runs' title when they share it; else what their titles share up to the last
    separator (``, `` or `` [``) before they differ, and the number of runs: a title that
    speaks for every run, not the first run's."""
    titles = [str(run.dataset.attrs.get("title", "")).strip() for run in runs]
    if len(set(titles)) == 1:
        return titles[0] or "floatmoor report"
    common = os.path.commonprefix(titles)
    cut = max(common.rfind(", "), common.rfind(" ["))
    base = common[:cut].strip() if cut > 0 else ""
    return f"{base} ({len(runs)} runs)" if base else f"floatmoor report ({len(runs)} runs)"


def write_report(runs: Sequence[RunData], output: str | Path, *,
                 reference: ReferenceValues | None = None,
                 nominal_diameters: Mapping[str, float] | None = None,
                 html: bool = False, title: str | None = None) -> ReportFiles:
    """Write the figures, the tables and ``summary.md`` of ``runs`` into ``output``.

    Parameters
    ----------
    runs
        The runs, in column order (:func:`floatmoor.report.runs.load_run`).
    output
        Output folder, created if its parent exists; files of an earlier report are replaced
        (the command checks first that the folder is its own: :mod:`floatmoor.io.output_folders`).
    reference
        Optional reference values, printed in their own, labelled columns.
    nominal_diameters
        Chain nominal diameters [m] by line or line-type name (``--nominal-diameter``).
    html
        Also write ``summary.html``.
    title
        Report title (default: the first run's title).

    Returns
    -------
    ReportFiles
        The files written and the numbers of every run.

    Raises
    ------
    ReportInputError
        For unusable inputs (nothing is written).
    FigureDataError
        When a series to plot is empty or not finite (nothing is written).
    OutputWriteError
        When a file cannot be written (disk full): naming it; the files written into
        ``output`` by this call may remain (the command removes them,
        :class:`floatmoor.io.output_folders.OwnedFolder`).
    """
    if not runs:
        raise ReportInputError("RUN.nc", "one or more run files", "none")
    output = check_output_folder(output)
    if reference is not None:
        _check_reference(runs, reference)
    lines = sorted({line for run in runs for line in run.lines})
    resolve_nominal_diameters(runs, dict(nominal_diameters or {}),
                              reference.nominal_diameter_map(lines) if reference else None)
    analyses = [analyse_run(run) for run in runs]
    title = title or report_title(runs)

    parent = output.resolve().parent
    name = SUMMARY_NAME
    try:
        with tempfile.TemporaryDirectory(prefix=".floatmoor-report-", dir=parent) as tmp:
            work = Path(tmp)
            blocks, made = _content(runs, analyses, reference, work, title)
            (work / SUMMARY_NAME).write_text(render_markdown(blocks), encoding="utf-8")
            names = [p.name for p in made] + [SUMMARY_NAME]
            if html:
                name = "summary.html"
                (work / name).write_text(render_html(blocks, title), encoding="utf-8")
                names.append(name)
            output.mkdir(exist_ok=True)
            for name in names:
                shutil.move(str(work / name), str(output / name))
    except OSError as err:  # disk full, folder made read-only: one line naming the file
        failed = getattr(err, "target", None) or getattr(err, "filename", None)
        where = output / Path(failed).name if failed else output / name
        cause = err.__cause__ if isinstance(err, OutputWriteError) and \
            isinstance(err.__cause__, OSError) else err
        raise OutputWriteError(f"cannot write {where}: {cause.strerror or cause}",
                               where) from err
    return ReportFiles(folder=output, summary=output / SUMMARY_NAME,
                       figures=[output / p.name for p in made],
                       html=output / "summary.html" if html else None, analyses=analyses)


def _content(runs: Sequence[RunData], analyses: Sequence[RunAnalysis],
             reference: ReferenceValues | None, work: Path,
             title: str) -> tuple[list[Block], list[Path]]:
    made: list[Path] = []
    blocks: list[Block] = [Heading(title, 1), Paragraph(
        f"floatmoor {__version__} report of {len(runs)} run(s). Tensions in N, displacements "
        "in m and rad (in degrees in the motion histories), times in s. Statistics, spectra, extremes and fatigue are taken over "
        "each run's analysis window, which starts after its ramp (the table of runs says "
        "where and why; without a ramp the whole record).")]
    blocks.append(runs_table(runs, analyses))
    if reference is not None:
        blocks.append(Paragraph(f"Reference values: **{reference.title}** ({reference.source};"
                                f" file {reference.path}). They are shown in their own "
                                "columns, labelled as such, beside the runs' results."))

    def figure(name: str, caption: str, draw) -> None:
        path = draw(work / name)
        made.append(Path(path))
        blocks.append(Figure(name, caption))

    blocks.append(Heading("Fairlead tension"))
    blocks.extend(tension_tables(runs, analyses, reference))
    figure("tension_timeseries.png", "Fairlead tension histories",
           lambda p: fig.plot_tension_timeseries(runs, p))
    figure("tension_psd.png", "Power spectral densities of fairlead tension",
           lambda p: fig.plot_tension_psd(runs, p))
    figure("tension_exceedance.png", "Probability of exceedance of tension maxima and minima",
           lambda p: fig.plot_exceedance(runs, p))

    blocks.append(Heading("Fatigue"))
    blocks.extend(fatigue_tables(runs, analyses, reference))
    blocks.append(strength_table(runs, analyses))
    figure("rainflow_histogram.png", "Rainflow-counted tension ranges",
           lambda p: fig.plot_rainflow(runs, p))

    motions = motion_table(runs, analyses)
    if motions is not None:
        blocks.append(Heading("Floater motions"))
        blocks.append(motions)
        dofs = fig.active_dofs(runs)
        if dofs:
            figure("motion_timeseries.png", "Floater displacements and wave elevation",
                   lambda p: fig.plot_motion_timeseries(runs, p, dofs))
            figure("motion_psd.png", "Power spectral densities of floater displacements",
                   lambda p: fig.plot_motion_psd(runs, p, dofs))
    shaped = [(k, run) for k, run in enumerate(runs) if has_complete_shapes(run.dataset)]
    if shaped:
        blocks.append(Heading("Line shapes and tension along the lines"))
        for k, run in shaped:
            shapes_name = f"line_shapes_{k + 1}.png"
            tension_name = f"line_tension_{k + 1}.png"
            plot_shape_views(run.dataset, work / shapes_name, work / tension_name,
                             start=run.start)
            made.extend([work / shapes_name, work / tension_name])
            blocks.append(Figure(shapes_name, f"Line shapes (side and plan views), run "
                                 f"{run.label}"))
            blocks.append(Figure(tension_name, f"Tension along the lines and its envelope "
                                 f"after the window start, run {run.label}"))
    decay = decay_table(runs, analyses)
    if decay is not None:
        blocks.append(Heading("Free decay"))
        blocks.append(decay)
        for k, (run, a) in enumerate(zip(runs, analyses)):
            for dof, fit in a.decay.items():
                if fit is not None:
                    figure(f"free_decay_{k + 1}_{dof.lower()}.png",
                           f"Free decay of {dof}, run {run.label}",
                           lambda p, run=run, dof=dof, fit=fit:
                           fig.plot_free_decay(run, dof, fit, p))
    return blocks, made
