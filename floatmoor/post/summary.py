"""The run summary printed by ``floatmoor run``: fairlead-tension statistics per line and the
largest tension against the line's minimum breaking load (MBL)."""

from __future__ import annotations

import numpy as np

from typing import Any

import xarray as xr

from floatmoor.case.schema import Case
from floatmoor.post.statistics import channel_statistics
from floatmoor.post.run_strength import line_strength, section_strength
from floatmoor.terminal_text import shown

__all__ = ["run_summary", "format_summary"]


def run_summary(case: Case, dataset: xr.Dataset) -> dict[str, Any]:
    """Statistics of the fairlead tension of every line after the ramp.

    The window starts at the end of the motion ramp (t = 0 without motion), and
    ``window_start_reason`` says why it starts there: without a ramp the record from t = 0 is
    in it, the lines starting at rest in the motion's pose at t = 0
    (docs/guide/running.md#what-a-run-writes-and-prints). For periodic motion the maxima of
    the complete cycles after the ramp are averaged (``mean_cycle_max``).
    Per line, ``strength`` holds the largest tension at either end, after the ramp and over the
    whole run, over the MBL of its type and the safety factor MBL / T_max
    (:func:`floatmoor.post.run_strength.line_strength`; None without an MBL). Tensions are in N.
    ``validity_warnings``: the messages of the conditions under which the run left its
    models' range (the dataset's attribute; :mod:`floatmoor.simulation.validity`).

    Parameters
    ----------
    case
        The run's case (its lines, line types and motion).
    dataset
        The run's result dataset.

    Returns
    -------
    dict
        JSON-ready: the window, per line the statistics and ``strength``, and the warnings
        (:func:`format_summary` prints it).
    """
    motion = case.motion
    start = motion.ramp_duration if motion is not None else 0.0
    reason = _window_reason(case)
    waves = getattr(case, "waves", None)
    if waves is not None:
        start = waves.ramp_duration
    period = motion.cycle_period if motion is not None else None
    time = dataset["time"].values
    lines: dict[str, Any] = {}
    for line in case.lines:
        series = dataset["fairlead_tension"].sel(line=line.name).values
        stats = channel_statistics(time, series, start=start, period=period)
        lines[line.name] = {
            "model": line.model, "fairlead_tension_N": stats,
            "strength": line_strength(dataset, line.name,
                                      line.end_type.minimum_breaking_load,
                                      start=float(stats["window_start"]))}
    # the sections of the lines solved as systems, each against its own type's MBL
    sections: dict[str, Any] = {}
    if "section_end_tension" in dataset:
        window = float(next(iter(lines.values()))["fairlead_tension_N"]["window_start"]) \
            if lines else 0.0
        for section in case.sections:
            line = next(ln for ln in case.lines if ln.name == section.line)
            if case.is_independent(line):
                continue
            sections[section.label] = section_strength(
                dataset, section.label, section.line_type.minimum_breaking_load, start=window)
    validity = str(dataset.attrs.get("validity_warnings", ""))
    out = {
        "title": case.title,
        "case": case.source,
        "overrides": list(case.overrides),
        "status": str(dataset.attrs.get("status", "")),
        "motion_period_s": period,
        "window_start_reason": reason,
        "lines": lines,
        "sections": sections,
        # where the run left its models' range (floatmoor.simulation.validity)
        "validity_warnings": [m for m in validity.split("\n") if m],
    }
    checked = str(dataset.attrs.get("line_accuracy", ""))
    if checked:  # the a-posteriori check of lines whose numerics the accuracy chose
        out["line_accuracy"] = checked.split("\n")
    if "body_displacement" in dataset:
        keep = time >= start
        if not keep.any():  # a run shorter than the ramp: the whole record, as for the lines
            keep = np.ones_like(keep)
        body = {}
        for dof in dataset["dof"].values:
            x = dataset["body_displacement"].sel(dof=dof).values[keep]
            body[str(dof)] = {"mean": float(x.mean()), "std": float(x.std()),
                              "min": float(x.min()), "max": float(x.max())} if x.size else {}
        out["body_displacement"] = body
    return out


def _window_reason(case: Case) -> str:
    """Why the statistics start where they do (``window_start_reason`` of
    :func:`run_summary`)."""
    waves = getattr(case, "waves", None)
    if waves is not None:
        return "end of the wave ramp" if waves.ramp_duration > 0.0 else \
            "no wave ramp: the start-up from the equilibrium included"
    if case.motion is None:
        return "no motion: the whole record"
    if case.motion.ramp_duration > 0.0:
        return "end of the motion ramp"
    return ("no motion ramp: the whole record, the lines starting at rest in the motion's "
            "pose at t = 0")


def _line_rows(lines: dict[str, Any], reason: str | None = None) -> list[str]:
    """Tension statistics and strength rows of the lines of a summary."""
    rows = ["fairlead tension [N] from t = {:.6g} s{}:".format(
                next(iter(lines.values()))["fairlead_tension_N"]["window_start"],
                f" ({reason})" if reason else ""),
            f"  {'line':<16}{'model':<15}{'mean':>10}{'std':>10}{'min':>10}{'max':>10}"
            f"{'cycle max':>11}{'cycles':>8}"]
    for name, entry in lines.items():
        s = entry["fairlead_tension_N"]
        cycle = f"{s['mean_cycle_max']:>11.4g}" if s["mean_cycle_max"] is not None else f"{'-':>11}"
        rows.append(f"  {name:<16}{entry['model']:<15}{s['mean']:>10.4g}{s['std']:>10.4g}"
                    f"{s['min']:>10.4g}{s['max']:>10.4g}{cycle}{s['n_cycles']:>8d}")
    rows.append("largest tension at either end against the minimum breaking load (MBL) [N]:")
    table, warnings = _strength_rows({name: e["strength"] for name, e in lines.items()}, "line")
    rows.extend(table)
    rows.append("  (T_max from the window start above, SF = MBL / T_max; whole run: from t = 0)")
    return rows + warnings


def _strength_rows(entries: dict[str, Any], what: str) -> tuple[list[str], list[str]]:
    """The strength table of lines or sections (:func:`floatmoor.post.run_strength.line_strength`
    entries), and a warning for each that reached its MBL."""
    rows = [f"  {what:<16}{'T_max':>10}{'at':>10}{'t [s]':>10}{'MBL':>10}"
            f"{'T_max/MBL':>11}{'SF':>8}{'whole run T_max/MBL':>21}"]
    warnings = []
    for name, b in entries.items():
        if b["minimum_breaking_load_N"] is None:
            tail = f"{'no MBL':>10}{'-':>11}{'-':>8}{'-':>21}"
        else:
            tail = (f"{b['minimum_breaking_load_N']:>10.4g}{b['max_tension_over_mbl']:>11.4g}"
                    f"{b['safety_factor']:>8.3g}{b['whole_run_max_tension_over_mbl']:>21.4g}")
            if b["whole_run_max_tension_over_mbl"] >= 1.0:
                warnings.append(f"warning: {what} '{name}' reached its MBL (T_max / MBL = "
                                f"{b['whole_run_max_tension_over_mbl']:.3g}): it would break")
        rows.append(f"  {name:<16}{b['max_tension_N']:>10.4g}{b['max_tension_end']:>10}"
                    f"{b['max_tension_time_s']:>10.4g}{tail}")
    return rows, [f"  {w}" for w in warnings]


def _section_rows(sections: dict[str, Any]) -> list[str]:
    """The strength rows of the sections of a summary, each against its type's MBL."""
    table, warnings = _strength_rows(sections, "section")
    return ["largest section tension at either end against its line type's MBL [N]:"] + table \
        + warnings


def format_summary(summary: dict[str, Any]) -> str:
    """A plain-text table of :func:`run_summary`."""
    rows = [shown(summary["title"])]  # the case's text: escapes shown, not obeyed
    if summary["lines"]:
        rows.extend(_line_rows(summary["lines"], summary.get("window_start_reason")))
    else:
        rows.append("no mooring lines")
    if summary.get("sections"):
        rows.extend(_section_rows(summary["sections"]))
    if summary.get("line_accuracy"):
        rows.append("dynamic lines' numerics checked against their accuracy (a probe at twice "
                    "the elements):")
        rows.extend(f"  {text}" for text in summary["line_accuracy"])
    if summary.get("body_displacement"):
        rows.append("floater displacement from equilibrium [m, rad]:")
        rows.append(f"  {'dof':<10}{'mean':>11}{'std':>11}{'min':>11}{'max':>11}")
        for dof, b in summary["body_displacement"].items():
            if b:
                rows.append(f"  {dof:<10}{b['mean']:>11.4g}{b['std']:>11.4g}{b['min']:>11.4g}"
                            f"{b['max']:>11.4g}")
    rows.extend(f"warning: outside the model's validity: {m}"
                for m in summary.get("validity_warnings", ()))
    return "\n".join(rows)
