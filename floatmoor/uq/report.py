"""The report of a study: PNG figures and a Markdown (and HTML) summary in ``DIR/report``.

Per scalar quantity: the probability density of the output (kernel density of the
surrogate's samples, :meth:`Surrogate.density`) with the runs' values, and its Sobol indices
as bars. Per history quantity: the mean and the central band over time with the runs'
histories, the total Sobol indices over time (absolute, and relative to their sum as the gpc
paper's Figure 8 shows them), the variance-weighted Sobol indices over the window as bars
(each index weighted by the output's variance at each time, so the bars say who drives the
window's variance), and the density of the output over time: a time x value map of the
histogram of the surrogate's samples at each time (the paper's Figures 6 and 7).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from floatmoor._version import __version__
from floatmoor.io.output_files import write_errors
from floatmoor.report.figures import DPI, check_series
from floatmoor.report.markdown import Block, Figure, Heading, Paragraph, render_html, \
    render_markdown
from floatmoor.report.tables import Table, format_number
from floatmoor.uq.output import BAND_LEVEL, BAND_SEED, input_text, method_text, \
    weighted_sobol
from floatmoor.uq.results import StudyResult
from floatmoor.uq.study import Quantity
from floatmoor.uq.surrogate import Surrogate

__all__ = ["write_study_report", "SUMMARY_NAME", "DENSITY_POINTS",
           "DENSITY_BINS"]

SUMMARY_NAME = "summary.md"
#: Points of the density curves of scalar quantities.
DENSITY_POINTS = 400
#: Value bins of the time x value density maps.
DENSITY_BINS = 80
#: Margin of the density grid beyond the sampled range, as a fraction of the range.
_GRID_MARGIN = 0.15


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


#: Characters per line of a figure title (wrapped: a long quantity description would run off
#: the figure's edges).
TITLE_WIDTH = 90


def _save(fig, path: Path, title: str) -> Path:
    import textwrap

    plt = _pyplot()
    fig.suptitle("\n".join(textwrap.wrap(title, TITLE_WIDTH)), fontsize=10)
    try:
        with write_errors(path):
            fig.savefig(path, dpi=DPI)
    finally:
        plt.close(fig)
    return path


def _axis_label(q: Quantity) -> str:
    return f"{q.name} [{q.units}]" if q.units else q.name


def density_label(q: Quantity) -> str:
    """The label of a probability density of ``q``: per unit of ``q`` ([-] when ``q`` has
    none)."""
    return f"probability density [1/{q.units}]" if q.units else "probability density [-]"


def _plot_pdf(q: Quantity, s: Surrogate, runs: NDArray[np.float64], samples: int,
              path: Path) -> Path:
    draws = check_series(s.sample(samples, BAND_SEED)[:, 0], f"surrogate samples of {q.name}")
    low, high = float(draws.min()), float(draws.max())
    pad = _GRID_MARGIN * (high - low) if high > low else max(abs(low), 1.0) * 1e-3
    grid = np.linspace(low - pad, high + pad, DENSITY_POINTS)
    fig, ax = _pyplot().subplots(figsize=(7.0, 3.6))
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.15, top=0.88)
    try:
        density = check_series(s.density(0, grid, n=samples, seed=BAND_SEED),
                               f"density of {q.name}")
        ax.plot(grid, density, color="C0", label=f"kernel density, {samples} surrogate "
                "samples")
    except ValueError as err:  # an output that does not vary has no density: say so
        ax.text(0.5, 0.5, str(err), transform=ax.transAxes, ha="center", fontsize=8)
    finite = runs[np.isfinite(runs)]
    ax.plot(finite, np.zeros_like(finite), "|", color="k", markersize=12,
            label="design runs")
    ax.axvline(float(s.mean[0]), color="C3", lw=1, label="mean")
    ax.set_xlabel(_axis_label(q))
    ax.set_ylabel(density_label(q))
    ax.legend(fontsize=7)
    return _save(fig, path, f"{q.describe()}: probability density")


def _plot_bars(q: Quantity, keys: list[str], first: NDArray[np.float64],
               total: NDArray[np.float64], path: Path, what: str) -> Path:
    fig, ax = _pyplot().subplots(figsize=(7.0, 1.2 + 0.45 * len(keys)))
    fig.subplots_adjust(left=0.45, right=0.97, bottom=0.25 if len(keys) < 3 else 0.12,
                        top=0.85)
    y = np.arange(len(keys))
    first, total = np.asarray(first, dtype=float), np.asarray(total, dtype=float)
    if not np.all(np.isfinite(total)):  # NaN: the output does not vary, nothing to share
        ax.text(0.5, 0.5, "the output does not vary: no Sobol indices",
                transform=ax.transAxes, ha="center", fontsize=8)
    ax.barh(y + 0.2, np.nan_to_num(total), 0.4, color="C1", label="total")
    ax.barh(y - 0.2, np.nan_to_num(first), 0.4, color="C0", label="first order")
    ax.set_yticks(y, keys, fontsize=7)
    ax.set_xlim(0.0, 1.05)
    ax.set_xlabel("Sobol index")
    ax.legend(fontsize=7, loc="lower right")
    return _save(fig, path, f"{q.name}: {what}")


def _plot_band(q: Quantity, s: Surrogate, time: NDArray[np.float64],
               runs: NDArray[np.float64], lower: NDArray[np.float64],
               upper: NDArray[np.float64], path: Path) -> Path:
    fig, ax = _pyplot().subplots(figsize=(8.0, 3.8))
    fig.subplots_adjust(left=0.1, right=0.97, bottom=0.14, top=0.88)
    for k, row in enumerate(runs):
        if np.all(np.isfinite(row)):
            ax.plot(time, row, color="0.75", lw=0.6, label="design runs" if k == 0 else None)
    ax.fill_between(time, check_series(lower, f"band of {q.name}"),
                    check_series(upper, f"band of {q.name}"), color="C0", alpha=0.3,
                    label=f"central {BAND_LEVEL:.0%} band")
    ax.plot(time, check_series(s.mean, f"mean of {q.name}"), color="k", lw=1.2, label="mean")
    ax.set_xlabel("time [s]")
    ax.set_ylabel(_axis_label(q))
    ax.legend(fontsize=7)
    return _save(fig, path, f"{q.describe()}: mean and band")


def _plot_sobol_time(q: Quantity, s: Surrogate, keys: list[str], time: NDArray[np.float64],
                     path: Path) -> Path:
    plt = _pyplot()
    fig, axes = plt.subplots(3, 1, figsize=(10.0, 7.5), sharex=True)
    fig.subplots_adjust(left=0.08, right=0.6, bottom=0.08, top=0.92, hspace=0.15)
    total = np.asarray(s.sobol_total, dtype=float)  # NaN where the output does not vary
    axes[0].plot(time, check_series(s.mean, f"mean of {q.name}"), color="k")
    axes[0].set_ylabel(f"mean [{q.units}]")
    sums = np.nansum(total, axis=0)
    share = np.nan_to_num(total) / np.where(sums > 0.0, sums, 1.0)
    axes[1].stackplot(time, share, labels=keys, colors=[f"C{k % 10}" for k in range(len(keys))])
    axes[1].set_ylabel("relative total index")
    axes[1].set_ylim(0.0, 1.0)
    for k, key in enumerate(keys):
        axes[2].plot(time, total[k], color=f"C{k % 10}", label=key)
    axes[2].set_ylabel("total Sobol index")
    axes[2].set_xlabel("time [s]")
    axes[1].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return _save(fig, path, f"{q.name}: Sobol indices over time (gaps: no variance)")


def _plot_density_map(q: Quantity, s: Surrogate, time: NDArray[np.float64], samples: int,
                      path: Path) -> Path:
    draws = s.sample(samples, BAND_SEED)
    check_series(np.ravel(draws), f"surrogate samples of {q.name}")
    low, high = float(draws.min()), float(draws.max())
    if not high > low:
        high = low + max(abs(low), 1.0) * 1e-3
    edges = np.linspace(low, high, DENSITY_BINS + 1)
    density = np.stack([np.histogram(draws[:, j], bins=edges, density=True)[0]
                        for j in range(draws.shape[1])], axis=1)
    fig, ax = _pyplot().subplots(figsize=(8.0, 4.2))
    fig.subplots_adjust(left=0.1, right=0.97, bottom=0.13, top=0.88)
    mesh = ax.pcolormesh(time, 0.5 * (edges[1:] + edges[:-1]), density, shading="nearest",
                         cmap="viridis")
    ax.plot(time, s.mean, color="w", lw=1.0, label="mean")
    fig.colorbar(mesh, ax=ax, label=density_label(q))
    ax.set_xlabel("time [s]")
    ax.set_ylabel(_axis_label(q))
    ax.legend(fontsize=7, loc="upper right")
    return _save(fig, path, f"{q.describe()}: density over time ({samples} surrogate "
                 "samples, histogram per time)")


def _inputs_table(result: StudyResult) -> Table:
    study = result.study
    return Table("Uncertain inputs", ["input", "distribution"],
                 [[key, input_text(study, k)] for k, key in enumerate(study.keys)])


def _scalar_table(result: StudyResult, scalars: list[Quantity]) -> Table:
    keys = list(result.study.keys)
    ds = result.dataset
    rows = []
    for q in scalars:
        rows.append([q.name, q.units, format_number(float(ds[f"{q.name}_mean"])),
                     format_number(float(ds[f"{q.name}_std"])),
                     f"{format_number(float(ds[f'{q.name}_lower']))} to "
                     f"{format_number(float(ds[f'{q.name}_upper']))}",
                     format_number(float(ds[f"{q.name}_validation_error"]))]
                    + [format_number(float(v)) for v in ds[f"{q.name}_sobol_total"].values])
    return Table("Scalar quantities", ["quantity", "units", "mean", "std",
                                       f"{BAND_LEVEL:.0%} band", "validation error"]
                 + [f"S_T {k}" for k in keys], rows,
                 notes=[q.name + ": " + q.describe() for q in scalars])


def _history_table(result: StudyResult, histories: list[Quantity]) -> Table:
    keys = list(result.study.keys)
    ds = result.dataset
    rows = []
    for q in histories:
        weighted = weighted_sobol(ds[f"{q.name}_sobol_total"].values,
                                  ds[f"{q.name}_variance"].values)
        rows.append([q.name, q.units, f"{q.window[0]:g} to {q.window[1]:g}",
                     format_number(float(ds[f"{q.name}_mean"].max())),
                     format_number(float(ds[f"{q.name}_upper"].max())),
                     format_number(float(ds[f"{q.name}_lower"].min())),
                     format_number(float(ds[f"{q.name}_std"].max())),
                     format_number(float(ds[f"{q.name}_validation_error"].max()))]
                    + [format_number(float(v)) for v in weighted])
    return Table("History quantities", ["quantity", "units", "window [s]", "max of mean",
                                        "max of upper band", "min of lower band", "max std",
                                        "max validation error"]
                 + [f"S_T {k} (variance-weighted)" for k in keys], rows,
                 notes=[q.name + ": " + q.describe() for q in histories])


def write_study_report(result: StudyResult, folder: str | Path) -> Path:
    """Write the figures, ``summary.md`` and ``summary.html`` of a study into ``folder``
    (created); returns the Markdown summary's path."""
    folder = Path(folder)
    folder.mkdir(exist_ok=True)
    study, runs = result.study, result.runs
    keys = list(study.keys)
    samples = study.surrogate_samples
    failed = [lb for lb, st in zip(runs.labels, runs.status) if st != "complete"]
    source = f"case {study.case}" + (f" with {', '.join(study.base_overrides)}"
                                     if study.base_overrides else "") \
        if study.case else f"built-in model {study.model}"
    blocks: list[Block] = [Heading(study.title, 1), Paragraph(
        f"floatmoor {__version__} uncertainty study {study.path} of the {source}: gPC "
        f"surrogates by {method_text(study)}, {len(runs.labels)} runs ({len(failed)} failed, "
        f"{len(result.dropped)} dropped from the fit); densities and bands from {samples} "
        "surrogate samples.")]
    blocks.append(_inputs_table(result))
    scalars = [q for q in study.quantities if not q.is_history]
    histories = [q for q in study.quantities if q.is_history]
    if scalars:
        blocks.append(_scalar_table(result, scalars))
    if histories:
        blocks.append(_history_table(result, histories))

    def figure(caption: str, path: Path) -> None:
        blocks.append(Figure(path.name, caption))

    for q in study.quantities:
        s = result.surrogates[q.name]
        values = runs.outputs[q.name]
        blocks.append(Heading(q.name))
        blocks.append(Paragraph(q.describe() + "."))
        if not q.is_history:
            figure("Probability density", _plot_pdf(
                q, s, values[:, 0], samples, folder / f"{q.name}_pdf.png"))
            figure("Sobol indices", _plot_bars(
                q, keys, np.asarray(s.sobol_first)[:, 0], np.asarray(s.sobol_total)[:, 0],
                folder / f"{q.name}_sobol.png", "Sobol indices"))
            continue
        time = runs.times[q.name]
        ds = result.dataset
        figure(f"Mean and central {BAND_LEVEL:.0%} band over time", _plot_band(
            q, s, time, values, ds[f"{q.name}_lower"].values, ds[f"{q.name}_upper"].values,
            folder / f"{q.name}_band.png"))
        figure("Density over time", _plot_density_map(
            q, s, time, samples, folder / f"{q.name}_density.png"))
        figure("Sobol indices over time", _plot_sobol_time(
            q, s, keys, time, folder / f"{q.name}_sobol_time.png"))
        variance = np.asarray(s.variance, dtype=float)
        figure("Variance-weighted Sobol indices over the window", _plot_bars(
            q, keys, weighted_sobol(s.sobol_first, variance),
            weighted_sobol(s.sobol_total, variance), folder / f"{q.name}_sobol.png",
            "variance-weighted Sobol indices over the window"))
    with write_errors(folder / SUMMARY_NAME):
        (folder / SUMMARY_NAME).write_text(render_markdown(blocks), encoding="utf-8")
    with write_errors(folder / "summary.html"):
        (folder / "summary.html").write_text(render_html(blocks, study.title), encoding="utf-8")
    return folder / SUMMARY_NAME
