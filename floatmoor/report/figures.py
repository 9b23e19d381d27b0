"""Report figures (matplotlib, Agg): time series, PSDs, exceedance, rainflow, free decay.

Every figure overlays the runs of a report (one colour per run) with one panel per line (or per
degree of freedom). Every plotted series passes :func:`check_series` first, which raises
:class:`FigureDataError` on an empty series or one holding NaN or infinite samples, so a figure
is never saved with a missing curve. A series that is legitimately featureless (a constant
tension has no extrema and no rainflow cycles) is named in the panel instead of drawn.

Free decay (:func:`decay_fit`): the successive extrema e_k of a decaying record, their ranges
r_k = |e_{k+1} - e_k| and a least-squares line through ln r_k over k give the ratio q of
successive ranges; for a linear oscillator q = exp(-delta / 2) with delta the logarithmic
decrement per cycle, so zeta = delta / sqrt(4 pi^2 + delta^2) exactly, and the damped period
is twice the mean spacing of the extrema. The level the record decays to is
c = (e_{k+1} + q e_k) / (1 + q), averaged over k.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from floatmoor.io.output_files import write_errors
from floatmoor.io.dataset import DOFS
from floatmoor.post.extremes import exceedance_probability
from floatmoor.post.rainflow import rainflow_cycles
from floatmoor.post.spectra import welch_psd
from floatmoor.post.statistics import time_window
from floatmoor.plots.motions import MOTION_ACTIVE_STD, TRANSLATIONS
from floatmoor.plots.series import FigureDataError, check_series
from floatmoor.plots.style import plain_axes
from floatmoor.report.runs import RunData

__all__ = [
    "FigureDataError", "DecayFit", "check_series", "decay_fit", "active_dofs",
    "plot_tension_timeseries", "plot_motion_timeseries", "plot_tension_psd",
    "plot_motion_psd", "plot_exceedance", "plot_rainflow", "plot_free_decay",
    "TENSION_PSD_SEGMENT", "MOTION_PSD_SEGMENT", "MOTION_ACTIVE_STD", "MIN_DECAY_EXTREMA",
    "RAINFLOW_BINS", "PSD_VARIANCE_SHOWN", "DPI",
]

#: Welch segment of tension PSDs [s] (0.005 Hz resolution; cut to the record if shorter).
TENSION_PSD_SEGMENT = 200.0
#: Welch segment of motion PSDs [s]: long enough to resolve slow-drift surge near 0.01 Hz
#: (the DeepCwind surge period is ~107 s) with several cycles per segment.
MOTION_PSD_SEGMENT = 600.0
#: Fewest extrema (3 ranges) a free-decay fit takes.
MIN_DECAY_EXTREMA = 4
#: Ranges below this fraction of the first are decay noise (round-off ripples), not fitted.
DECAY_NOISE_FRACTION = 1e-3
#: Bins of the rainflow range histograms.
RAINFLOW_BINS = 30
#: PSD axes extend to the frequency below which this fraction of every series' variance lies
#: (times :data:`PSD_AXIS_MARGIN`), not to the Nyquist frequency of the output (snap loads of
#: a dynamic chain spread a little variance up to the Nyquist frequency).
PSD_VARIANCE_SHOWN = 0.99
PSD_AXIS_MARGIN = 1.5
#: Decades of PSD shown below the highest ordinate of a panel.
PSD_DECADES = 8.0
#: Resolution of saved figures [dots per inch].
DPI = 110


@dataclass(frozen=True)
class DecayFit:
    """Free-decay characteristics of one record (see the module docstring).

    Attributes
    ----------
    extremum_times, extremum_values
        The extrema used [s], [unit of the record].
    period
        Damped period T_d [s].
    damping_ratio
        zeta [-].
    level
        The level the record decays to, c.
    """

    extremum_times: NDArray[np.float64]
    extremum_values: NDArray[np.float64]
    period: float
    damping_ratio: float
    level: float

    def envelope(self, time: NDArray[np.float64]) -> tuple[NDArray[np.float64],
                                                           NDArray[np.float64]]:
        """Upper and lower fitted envelopes ``c +- A0 exp(-(delta / T_d)(t - t0))``."""
        delta = _log_decrement(self.damping_ratio)
        a0 = abs(self.extremum_values[0] - self.level)
        amp = a0 * np.exp(-(delta / self.period) * (time - self.extremum_times[0]))
        return self.level + amp, self.level - amp


def _log_decrement(zeta: float) -> float:
    return 2.0 * math.pi * zeta / math.sqrt(1.0 - zeta**2)


def decay_fit(time: ArrayLike, values: ArrayLike, what: str = "free decay") -> DecayFit | None:
    """Damped period and damping ratio of a free-decay record; None with too few extrema.

    Parameters
    ----------
    time
        Sample times [s].
    values
        The decaying record.
    what
        Description for error messages.
    """
    t = check_series(time, f"{what} (time)")
    x = check_series(values, what)
    keep = np.concatenate(([True], np.diff(x) != 0.0))
    t, x = t[keep], x[keep]
    slope = np.sign(np.diff(x))
    idx = np.flatnonzero(slope[:-1] != slope[1:]) + 1
    if idx.size < MIN_DECAY_EXTREMA:
        return None
    te, xe = t[idx], x[idx]
    ranges = np.abs(np.diff(xe))
    keep_n = int(np.argmax(ranges < DECAY_NOISE_FRACTION * ranges[0])) \
        if np.any(ranges < DECAY_NOISE_FRACTION * ranges[0]) else ranges.size
    if keep_n < MIN_DECAY_EXTREMA - 1:
        return None
    te, xe, ranges = te[: keep_n + 1], xe[: keep_n + 1], ranges[:keep_n]
    k = np.arange(ranges.size, dtype=float)
    slope_k = float(np.polyfit(k, np.log(ranges), 1)[0])
    q = math.exp(slope_k)
    delta = -2.0 * slope_k
    zeta = delta / math.sqrt(4.0 * math.pi**2 + delta**2)
    period = 2.0 * float(np.mean(np.diff(te)))
    level = float(np.mean((xe[1:] + q * xe[:-1]) / (1.0 + q)))
    return DecayFit(te, xe, period, zeta, level)


# -- helpers ----------------------------------------------------------------------------------

def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _colour(i: int) -> str:
    return f"C{i % 10}"


#: Fixed figure margins [inch] (a fixed layout: tight_layout draws every figure twice).
_TOP, _BOTTOM, _GAP = 0.6, 0.55, 0.75
#: Space kept right of the widest legend [inch].
_LEGEND_MARGIN = 0.1


def _panels(n: int, *, height: float = 2.4, width: float = 9.0):
    plt = _pyplot()
    total = height * n + _GAP * (n - 1) + _TOP + _BOTTOM
    fig, axes = plt.subplots(n, 1, figsize=(width, total), squeeze=False)
    fig.subplots_adjust(left=0.1, right=0.8, top=1.0 - _TOP / total, bottom=_BOTTOM / total,
                        hspace=_GAP / height)
    return plt, fig, list(axes[:, 0])


def _save(plt, fig, path: Path, title: str) -> Path:
    fig.suptitle(title, fontsize=11)
    _fit_legends(fig)
    try:
        with write_errors(path):  # disk full: the image library's error, one line
            fig.savefig(path, dpi=DPI)
    finally:
        plt.close(fig)
    return path


def _fit_legends(fig) -> None:
    """Widen the figure so that legends beside the axes are not cut at its right edge (long
    run labels would otherwise read alike); the axes keep their size in inches."""
    renderer = fig.canvas.get_renderer()
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    if not legends:
        return
    width = fig.get_figwidth()
    reach = max(legend.get_window_extent(renderer).x1 for legend in legends) / fig.dpi
    extra = reach + _LEGEND_MARGIN - width
    if extra <= 0.0:
        return
    left, right = fig.subplotpars.left * width, fig.subplotpars.right * width
    fig.set_figwidth(width + extra)
    fig.subplots_adjust(left=left / (width + extra), right=right / (width + extra))


def _lines(runs: Sequence[RunData]) -> list[str]:
    names: list[str] = []
    for run in runs:
        names.extend(n for n in run.lines if n not in names)
    return names


def _legend(ax) -> None:
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.005, 1.0))


def active_dofs(runs: Sequence[RunData]) -> list[str]:
    """DOFs that move in some floater run: std over the window >= MOTION_ACTIVE_STD."""
    active: list[str] = []
    for run in runs:
        if not run.has_body:
            continue
        window = time_window(run.dataset["body_displacement"], start=run.start)
        std = window.std("time")
        for dof in run.dataset["dof"].values:
            if float(std.sel(dof=dof)) >= MOTION_ACTIVE_STD and str(dof) not in active:
                active.append(str(dof))
    return [d for d in DOFS if d in active]


def _dof_unit(dof: str) -> str:
    return "m" if dof in ("Surge", "Sway", "Heave") else "rad"


# -- time series ------------------------------------------------------------------------------

def plot_tension_timeseries(runs: Sequence[RunData], path: str | Path) -> Path:
    """Fairlead tension histories, one panel per line, the transient before ``start`` shaded."""
    lines = _lines(runs)
    plt, fig, axes = _panels(len(lines))
    for ax, line in zip(axes, lines):
        for i, run in enumerate(runs):
            if line not in run.lines:
                continue
            t = check_series(run.dataset["time"].values, f"time of run {run.label}")
            y = check_series(run.dataset["fairlead_tension"].sel(line=line).values,
                             f"tension time series: run {run.label}, line {line}")
            ax.plot(t, y, lw=0.8, color=_colour(i), label=f"{run.label}")
            if run.start > 0.0:
                ax.axvline(run.start, color=_colour(i), ls=":", lw=0.8)
        ax.set_title(f"line {line}: fairlead tension (dotted: start of the analysis window)",
                     fontsize=9)
        ax.set_ylabel("tension [N]")
        ax.set_xlabel("time [s]")
        ax.grid(alpha=0.3)
        _legend(ax)
    return _save(plt, fig, Path(path), "Fairlead tension")


def plot_motion_timeseries(runs: Sequence[RunData], path: str | Path,
                           dofs: Sequence[str]) -> Path:
    """Floater displacements (active DOFs; rotations in degrees) and the wave elevation, one
    panel each."""
    body_runs = [(i, r) for i, r in enumerate(runs) if r.has_body]
    waves = any("wave_elevation" in r.dataset for _, r in body_runs)
    plt, fig, axes = _panels(len(dofs) + int(waves), height=2.2)
    for ax, dof in zip(axes, dofs):
        for i, run in body_runs:
            t = check_series(run.dataset["time"].values, f"time of run {run.label}")
            y = check_series(run.dataset["body_displacement"].sel(dof=dof).values,
                             f"motion time series: run {run.label}, {dof}")
            metres = dof in TRANSLATIONS  # rotations drawn in degrees
            ax.plot(t, y if metres else np.degrees(y), lw=0.8, color=_colour(i),
                    label=run.label)
        ax.set_ylabel(f"{dof} [{'m' if dof in TRANSLATIONS else 'deg'}]")
        ax.grid(alpha=0.3)
        plain_axes(ax)
        _legend(ax)
    if waves:
        ax = axes[-1]
        for i, run in body_runs:
            if "wave_elevation" in run.dataset:
                t = check_series(run.dataset["time"].values, f"time of run {run.label}")
                y = check_series(run.dataset["wave_elevation"].values,
                                 f"wave elevation: run {run.label}")
                ax.plot(t, y, lw=0.8, color=_colour(i), label=run.label)
        ax.set_ylabel("wave elevation [m]")
        ax.grid(alpha=0.3)
        _legend(ax)
    axes[-1].set_xlabel("time [s]")
    return _save(plt, fig, Path(path), "Floater motions from the static equilibrium")


# -- spectra ----------------------------------------------------------------------------------

def _psd_panel(ax, psds: list[tuple[int, str, xr.DataArray]], what: str, unit: str) -> None:
    f_max = 0.0
    for i, label, psd in psds:
        f = check_series(psd["frequency"].values, f"{what}: frequencies of run {label}")
        s = check_series(psd.values, f"{what}: run {label}")
        cumulative = np.cumsum(s)
        if cumulative[-1] > 0.0:
            k = int(np.searchsorted(cumulative, PSD_VARIANCE_SHOWN * cumulative[-1]))
            f_max = max(f_max, PSD_AXIS_MARGIN * f[min(k, f.size - 1)])
        positive = s > 0.0
        if np.any(positive):
            ax.semilogy(f[positive], s[positive], lw=0.9, color=_colour(i), label=label)
        else:
            ax.text(0.5, 0.5, f"{label}: zero PSD (constant record)",
                    transform=ax.transAxes, ha="center", fontsize=8)
    if f_max > 0.0:
        ax.set_xlim(0.0, f_max)
    top = max((float(np.max(psd.values)) for _, _, psd in psds), default=0.0)
    if top > 0.0:
        ax.set_ylim(top * 10.0**-PSD_DECADES, 3.0 * top)
    ax.set_ylabel(f"PSD [{unit}^2/Hz]")
    ax.set_xlabel("frequency [Hz]")
    ax.grid(alpha=0.3, which="both")
    _legend(ax)


def plot_tension_psd(runs: Sequence[RunData], path: str | Path) -> Path:
    """Welch PSDs of the fairlead tensions after ``start``, one panel per line."""
    lines = _lines(runs)
    plt, fig, axes = _panels(len(lines))
    for ax, line in zip(axes, lines):
        psds = []
        for i, run in enumerate(runs):
            if line in run.lines:
                psds.append((i, run.label, welch_psd(
                    run.dataset["fairlead_tension"].sel(line=line), start=run.start,
                    segment_duration=TENSION_PSD_SEGMENT)))
        _psd_panel(ax, psds, f"tension PSD, line {line}", "N")
        ax.set_title(f"line {line}: fairlead tension (Welch, {TENSION_PSD_SEGMENT:g} s "
                     "segments or the record)", fontsize=9)
    return _save(plt, fig, Path(path), "Power spectral density of fairlead tension")


def plot_motion_psd(runs: Sequence[RunData], path: str | Path, dofs: Sequence[str]) -> Path:
    """Welch PSDs of the floater displacements (active DOFs) after ``start``."""
    plt, fig, axes = _panels(len(dofs), height=2.3)
    for ax, dof in zip(axes, dofs):
        psds = [(i, run.label, welch_psd(run.dataset["body_displacement"].sel(dof=dof),
                                         start=run.start, segment_duration=MOTION_PSD_SEGMENT))
                for i, run in enumerate(runs) if run.has_body]
        _psd_panel(ax, psds, f"motion PSD, {dof}", _dof_unit(dof))
        ax.set_title(f"{dof} (Welch, {MOTION_PSD_SEGMENT:g} s segments or the record)",
                     fontsize=9)
    return _save(plt, fig, Path(path), "Power spectral density of floater motions")


# -- extremes and cycles ----------------------------------------------------------------------

def _constant(run: RunData, line: str) -> bool:
    window = time_window(run.dataset["fairlead_tension"].sel(line=line), start=run.start)
    return bool(np.ptp(window.values) == 0.0)


def plot_exceedance(runs: Sequence[RunData], path: str | Path) -> Path:
    """Probability of exceedance of the local tension maxima (solid) and of non-exceedance of
    the minima (dashed), after ``start``, on a logarithmic probability axis."""
    lines = _lines(runs)
    plt, fig, axes = _panels(len(lines))
    for ax, line in zip(axes, lines):
        notes = []
        for i, run in enumerate(runs):
            if line not in run.lines:
                continue
            if _constant(run, line):
                notes.append(f"{run.label}: constant tension, no extrema")
                continue
            tension = run.dataset["fairlead_tension"].sel(line=line)
            for kind, style in (("maxima", "-"), ("minima", "--")):
                ex = exceedance_probability(tension, start=run.start, kind=kind)
                valid = np.isfinite(ex["probability"].values)
                what = f"tension {kind} exceedance: run {run.label}, line {line}"
                x = check_series(ex["value"].values[valid], what)
                p = check_series(ex["probability"].values[valid], what)
                ax.semilogy(x, p, style, marker=".", ms=2.5, lw=0.8, color=_colour(i),
                            label=f"{run.label} {kind}")
        if notes:
            ax.text(0.02, 0.05, "\n".join(notes), transform=ax.transAxes, fontsize=8)
        ax.set_title(f"line {line}: P(max > T) solid, P(min < T) dashed", fontsize=9)
        ax.set_xlabel("fairlead tension T [N]")
        ax.set_ylabel("probability")
        ax.grid(alpha=0.3, which="both")
        _legend(ax)
    return _save(plt, fig, Path(path), "Exceedance of local tension maxima and minima")


def plot_rainflow(runs: Sequence[RunData], path: str | Path) -> Path:
    """Histograms of rainflow-counted tension ranges after ``start`` (half cycles count 0.5)."""
    lines = _lines(runs)
    plt, fig, axes = _panels(len(lines))
    for ax, line in zip(axes, lines):
        counted = []
        notes = []
        for i, run in enumerate(runs):
            if line not in run.lines:
                continue
            window = time_window(run.dataset["fairlead_tension"].sel(line=line),
                                 start=run.start)
            what = f"rainflow ranges: run {run.label}, line {line}"
            cycles = rainflow_cycles(check_series(window.values, what))
            if cycles.ranges.size == 0 or not np.any(cycles.ranges > 0.0):
                notes.append(f"{run.label}: constant tension, no cycles")
                continue
            counted.append((i, run.label, check_series(cycles.ranges, what),
                            check_series(cycles.counts, what)))
        top = max((float(r.max()) for _, _, r, _ in counted), default=1.0)
        bins = np.linspace(0.0, top, RAINFLOW_BINS + 1)
        for i, label, ranges, counts in counted:
            ax.hist(ranges, bins=bins, weights=counts, histtype="step", lw=1.2,
                    color=_colour(i), label=f"{label} ({counts.sum():g} cycles)")
        if counted:
            ax.set_yscale("log")
        if notes:
            ax.text(0.02, 0.85, "\n".join(notes), transform=ax.transAxes, fontsize=8)
        ax.set_title(f"line {line}: rainflow range histogram (ASTM E1049)", fontsize=9)
        ax.set_xlabel("tension range [N]")
        ax.set_ylabel("cycles per bin")
        ax.grid(alpha=0.3, which="both")
        _legend(ax)
    return _save(plt, fig, Path(path), "Rainflow-counted fairlead tension ranges")


def plot_free_decay(run: RunData, dof: str, fit: DecayFit, path: str | Path) -> Path:
    """A decaying DOF with its extrema and the fitted exponential envelope."""
    plt, fig, axes = _panels(1, height=3.4)
    ax = axes[0]
    t = check_series(run.dataset["time"].values, f"time of run {run.label}")
    x = check_series(run.dataset["body_displacement"].sel(dof=dof).values,
                     f"free decay: run {run.label}, {dof}")
    upper, lower = fit.envelope(t[t >= fit.extremum_times[0]])
    ax.plot(t, x, lw=0.9, color="C0", label=f"{dof}")
    ax.plot(fit.extremum_times, check_series(fit.extremum_values, f"decay extrema {dof}"),
            "o", ms=3, color="C3", label="extrema fitted")
    tt = t[t >= fit.extremum_times[0]]
    ax.plot(tt, check_series(upper, f"decay envelope {dof}"), "--", color="C2", lw=0.9,
            label="fitted envelope")
    ax.plot(tt, check_series(lower, f"decay envelope {dof}"), "--", color="C2", lw=0.9)
    ax.set_title(f"damped period T_d = {fit.period:.4g} s, damping ratio zeta = "
                 f"{fit.damping_ratio:.3g} ({fit.extremum_times.size} extrema)", fontsize=9)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"{dof} [{_dof_unit(dof)}]")
    ax.grid(alpha=0.3)
    _legend(ax)
    return _save(plt, fig, Path(path), f"Free decay of {dof}: run {run.label}")
