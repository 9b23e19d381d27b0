"""Report tables: the runs, tension statistics, fatigue damage and floater motions, with the
runs side by side and optional reference (e.g. published) columns.

Numbers are computed by :func:`analyse_run` with :mod:`floatmoor.post` over each run's analysis
window (from ``RunData.start``) and kept as floats; :class:`Table` holds their text, formatted
to :data:`SIGNIFICANT_DIGITS` significant digits. Fatigue damage is Miner's sum over the
rainflow-counted fairlead tension with the DNV-OS-E301 studless-chain S-N curve, on the nominal
area of a chain link's two legs (``2 pi d^2 / 4``, d the nominal diameter chosen by
:func:`floatmoor.report.runs.resolve_nominal_diameters`), over the window (not scaled to any
other duration). The damage equivalent load is that of m = 3 and 1 Hz reference cycles. The
strength table gives the largest tension at either end over the window against the minimum
breaking load (MBL) of the line type (:mod:`floatmoor.post.run_strength`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Sequence

import xarray as xr

from floatmoor.post.fatigue import (
    DNV_STUDLESS_CHAIN, chain_nominal_area, damage_equivalent_load, fatigue_damage,
)
from floatmoor.post.spectra import peak_period, welch_psd, zero_upcrossing_period
from floatmoor.post.statistics import time_statistics, time_window
from floatmoor.post.run_strength import line_mbl, line_strength
from floatmoor.report.figures import (
    MOTION_ACTIVE_STD, TENSION_PSD_SEGMENT, DecayFit, check_series, decay_fit,
)
from floatmoor.report.reference import ReferenceValues
from floatmoor.report.runs import RunData

__all__ = ["Table", "RunAnalysis", "analyse_run", "format_number", "runs_table",
           "tension_tables", "fatigue_tables", "strength_table", "motion_table", "decay_table",
           "SIGNIFICANT_DIGITS", "TENSION_STATISTICS", "FATIGUE_CURVE", "DEL_SLOPE"]

#: Significant digits of the numbers in the tables.
SIGNIFICANT_DIGITS = 4
#: Tension statistics in the tables, in order, with their units.
TENSION_STATISTICS = (("mean", "N"), ("std", "N"), ("min", "N"), ("max", "N"),
                      ("skewness", "-"), ("kurtosis", "-"), ("Tp", "s"), ("Tz", "s"))
#: The S-N curve of the damage tables.
FATIGUE_CURVE = DNV_STUDLESS_CHAIN
#: Inverse S-N slope of the damage equivalent load (chain, DNV-OS-E301).
DEL_SLOPE = 3.0
#: Placeholder of a cell without a value.
EMPTY = "–"


def format_number(value: float | None) -> str:
    """``value`` to :data:`SIGNIFICANT_DIGITS` significant digits, or a dash."""
    if value is None or not math.isfinite(value):
        return EMPTY
    return f"{value:.{SIGNIFICANT_DIGITS}g}"


@dataclass
class Table:
    """A table of text cells with a title and notes."""

    title: str
    headers: list[str]
    rows: list[list[str]]
    notes: list[str] = field(default_factory=list)


@dataclass
class RunAnalysis:
    """The numbers of one run over its analysis window.

    Attributes
    ----------
    tension
        Line -> statistic name (:data:`TENSION_STATISTICS`) -> value [N, -, s].
    damage
        Line -> Miner damage over the window [-].
    equivalent_load
        Line -> damage equivalent tension range [N].
    window
        Duration of the analysis window [s].
    motion
        DOF -> statistic (mean, std, min, max) -> value [m or rad]; empty without a floater.
    decay
        Decaying DOF -> its fit, or None with too few extrema.
    strength
        Line -> the largest tension over the window against the MBL
        (:func:`floatmoor.post.run_strength.line_strength`).
    """

    tension: dict[str, dict[str, float]]
    damage: dict[str, float]
    equivalent_load: dict[str, float]
    window: float
    motion: dict[str, dict[str, float]] = field(default_factory=dict)
    decay: dict[str, DecayFit | None] = field(default_factory=dict)
    strength: dict[str, dict[str, Any]] = field(default_factory=dict)


def _periods(series: xr.DataArray, start: float, std: float) -> tuple[float, float]:
    if not std > 0.0:
        return math.nan, math.nan
    psd = welch_psd(series, start=start, segment_duration=TENSION_PSD_SEGMENT)
    return float(peak_period(psd)), float(zero_upcrossing_period(psd))


def analyse_run(run: RunData) -> RunAnalysis:
    """Statistics, spectral periods, fatigue damage, motions and decay fits of one run.

    The nominal diameters must have been resolved (``run.diameters``).
    """
    ds = run.dataset
    for line in run.lines:  # nothing is computed from a NaN or empty record
        check_series(time_window(ds["fairlead_tension"].sel(line=line), start=run.start).values,
                     f"fairlead_tension of run {run.label}, line {line}")
    if run.has_body:
        check_series(time_window(ds["body_displacement"], start=run.start).values,
                     f"body_displacement of run {run.label}")
    stats = time_statistics(ds["fairlead_tension"], start=run.start)
    tension: dict[str, dict[str, float]] = {}
    damage: dict[str, float] = {}
    equivalent: dict[str, float] = {}
    for line in run.lines:
        entry = {name: float(stats[name].sel(line=line)) for name, _ in TENSION_STATISTICS
                 if name in stats}
        series = ds["fairlead_tension"].sel(line=line)
        entry["Tp"], entry["Tz"] = _periods(series, run.start, entry["std"])
        tension[line] = entry
        area = chain_nominal_area(run.diameters[line].value)
        damage[line] = float(fatigue_damage(series, FATIGUE_CURVE, start=run.start,
                                            nominal_area=area))
        equivalent[line] = float(damage_equivalent_load(series, DEL_SLOPE, start=run.start))
    time = ds["time"].values
    window = float(time[-1] - time[time >= run.start - 1e-9 * max(run.start, 1.0)][0])
    out = RunAnalysis(tension, damage, equivalent, window)
    for line in run.lines:
        out.strength[line] = line_strength(ds, line, line_mbl(ds, line, run.case),
                                           start=run.start)
    if run.has_body:
        body = time_statistics(ds["body_displacement"], start=run.start)
        for dof in ds["dof"].values:
            out.motion[str(dof)] = {k: float(body[k].sel(dof=dof))
                                    for k in ("mean", "std", "min", "max")}
        for dof in run.decay_dofs:
            out.decay[dof] = decay_fit(time, ds["body_displacement"].sel(dof=dof).values,
                                       f"free decay: run {run.label}, {dof}")
    return out


def _lines(runs: Sequence[RunData]) -> list[str]:
    names: list[str] = []
    for run in runs:
        names.extend(n for n in run.lines if n not in names)
    return names


def _reference_cell(reference: ReferenceValues | None, line: str, quantity: str) -> list[str]:
    if reference is None:
        return []
    return [format_number(c.lines.get(line, {}).get(quantity)) for c in reference.columns]


def _reference_headers(reference: ReferenceValues | None) -> list[str]:
    return [c.label for c in reference.columns] if reference is not None else []


def _reference_note(reference: ReferenceValues | None) -> list[str]:
    if reference is None:
        return []
    note = (f"Reference columns ({', '.join(c.label for c in reference.columns)}) are "
            f"**{reference.title}**, not results of these runs: {reference.source} "
            f"(file {reference.path}).")
    if reference.duration is not None:
        note += f" They refer to records of {reference.duration:g} s."
    return [note]


def runs_table(runs: Sequence[RunData], analyses: Sequence[RunAnalysis]) -> Table:
    """One row per run: file, title, line models, status and analysis window; a note for
    each run that left its models' validity (its file's ``validity_warnings``,
    :mod:`floatmoor.simulation.validity`)."""
    rows, notes = [], []
    for run, a in zip(runs, analyses):
        notes += [f"**Run {run.label} is outside its model's validity**: {m}" for m in
                  str(run.dataset.attrs.get("validity_warnings", "")).split("\n") if m]
        models = ", ".join(f"{k}: {v}" for k, v in run.models.items())
        rows.append([run.label, str(run.path) if run.path else EMPTY,
                     str(run.dataset.attrs.get("title", "")), models,
                     str(run.dataset.attrs.get("status", "")),
                     f"{run.start:g} s ({run.start_source})", f"{a.window:g} s"])
    return Table("Runs", ["run", "file", "title", "line models", "status",
                          "analysis window from", "window length"], rows, notes)


def tension_tables(runs: Sequence[RunData], analyses: Sequence[RunAnalysis],
                   reference: ReferenceValues | None = None) -> list[Table]:
    """One table per line: the tension statistics of every run side by side (and the
    reference columns for mean, std, min and max)."""
    tables = []
    for line in _lines(runs):
        rows = []
        for name, unit in TENSION_STATISTICS:
            cells = [name, unit]
            for run, a in zip(runs, analyses):
                cells.append(format_number(a.tension[line][name]) if line in a.tension
                             else EMPTY)
            rows.append(cells + _reference_cell(reference, line, name))
        notes = ["Statistics over each run's analysis window (see Runs); std is the "
                 "population standard deviation, kurtosis the plain (Pearson) one, 3 for a "
                 "Gaussian process; Tp and Tz from the Welch PSD "
                 f"({TENSION_PSD_SEGMENT:g} s segments or the window)."]
        tables.append(Table(f"Fairlead tension statistics, line {line}",
                            ["statistic", "unit", *[r.label for r in runs],
                             *_reference_headers(reference)], rows,
                            notes + _reference_note(reference)))
    return tables


def fatigue_tables(runs: Sequence[RunData], analyses: Sequence[RunAnalysis],
                   reference: ReferenceValues | None = None) -> list[Table]:
    """Damage per line per run (and reference), the equivalent loads, and the diameters."""
    lines = _lines(runs)
    damage_rows, del_rows = [], []
    for line in lines:
        damage_rows.append([line, *[format_number(a.damage.get(line)) for a in analyses],
                            *_reference_cell(reference, line, "damage")])
        del_rows.append([line, *[format_number(a.equivalent_load.get(line))
                                 for a in analyses]])
    windows = ", ".join(f"{r.label}: {a.window:g} s" for r, a in zip(runs, analyses))
    damage = Table("Fatigue damage (Miner) of the fairlead tension",
                   ["line", *[r.label for r in runs], *_reference_headers(reference)],
                   damage_rows,
                   [f"S-N curve {FATIGUE_CURVE.name} (a_D = {FATIGUE_CURVE.a_d:g}, m = "
                    f"{FATIGUE_CURVE.m:g}, S in MPa) on the nominal area 2 pi d^2 / 4 of the "
                    "diameters below; damage over each run's analysis window "
                    f"({windows}), not scaled to another duration."]
                   + _reference_note(reference))
    equivalent = Table(f"Damage equivalent tension range (m = {DEL_SLOPE:g}, 1 Hz reference "
                       "cycles) [N]", ["line", *[r.label for r in runs]], del_rows)
    d_rows, warnings = [], []
    for run in runs:
        for line in run.lines:
            d = run.diameters[line]
            d_rows.append([line, run.label, format_number(d.value), d.source])
            if d.warning and d.warning not in warnings:
                warnings.append(d.warning)
    diameters = Table("Chain nominal diameters used for the damage",
                      ["line", "run", "d [m]", "from"], d_rows,
                      [f"Caution: {w}." for w in warnings])
    return [damage, equivalent, diameters]


def strength_table(runs: Sequence[RunData], analyses: Sequence[RunAnalysis]) -> Table:
    """Per line and run: the largest tension at either end over the analysis window, the MBL
    of the line type, their ratio and the safety factor MBL / T_max."""
    rows, broken = [], []
    for line in _lines(runs):
        for run, a in zip(runs, analyses):
            if line not in a.strength:
                continue
            b = a.strength[line]
            mbl = b["minimum_breaking_load_N"]
            rows.append([line, run.label, format_number(b["max_tension_N"]),
                         b["max_tension_end"], format_number(b["max_tension_time_s"]),
                         format_number(mbl) if mbl is not None else "no MBL",
                         format_number(b["max_tension_over_mbl"]),
                         format_number(b["safety_factor"])])
            if mbl is not None and b["max_tension_over_mbl"] >= 1.0:
                broken.append(f"line {line} of run {run.label}")
    notes = ["Largest tension at either end (fairlead or anchor) over each run's analysis "
             "window; MBL: the minimum_breaking_load of the line type in the case; safety "
             "factor = MBL / T_max."]
    if broken:
        notes.append("Caution: the tension reached the MBL on " + ", ".join(broken)
                     + ": the line would break.")
    return Table("Largest tension against the minimum breaking load",
                 ["line", "run", "T_max [N]", "at", "t [s]", "MBL [N]", "T_max / MBL",
                  "safety factor"], rows, notes)


def motion_table(runs: Sequence[RunData], analyses: Sequence[RunAnalysis]) -> Table | None:
    """Floater displacement statistics per DOF, runs side by side; None without a floater."""
    body = [(r, a) for r, a in zip(runs, analyses) if a.motion]
    if not body:
        return None
    dofs = list(body[0][1].motion)
    rows = []
    for dof in dofs:
        if all(a.motion[dof]["std"] < MOTION_ACTIVE_STD and abs(a.motion[dof]["mean"])
               < MOTION_ACTIVE_STD for _, a in body):
            continue
        unit = "m" if dof in ("Surge", "Sway", "Heave") else "rad"
        for stat in ("mean", "std", "min", "max"):
            rows.append([dof, stat, unit, *[format_number(a.motion[dof][stat])
                                            for _, a in body]])
    return Table("Floater displacement from the static equilibrium",
                 ["DOF", "statistic", "unit", *[r.label for r, _ in body]], rows,
                 [f"DOFs whose mean and std stay below {MOTION_ACTIVE_STD:g} in every run are "
                  "left out."])


def decay_table(runs: Sequence[RunData], analyses: Sequence[RunAnalysis]) -> Table | None:
    """Damped period and damping ratio of every decaying DOF; None without decay runs."""
    rows = []
    for run, a in zip(runs, analyses):
        for dof, fit in a.decay.items():
            if fit is None:
                rows.append([run.label, dof, EMPTY, EMPTY, "too few extrema to fit"])
            else:
                rows.append([run.label, dof, format_number(fit.period),
                             format_number(fit.damping_ratio),
                             f"{fit.extremum_times.size} extrema"])
    if not rows:
        return None
    return Table("Free decay", ["run", "DOF", "damped period T_d [s]", "damping ratio [-]",
                                "fit"], rows,
                 ["From the ranges between successive extrema (logarithmic decrement); "
                  "whole record, from t = 0."])
