"""Largest line tension of a run against the line's minimum breaking load (MBL) (the static
tension against it, before a run: :mod:`floatmoor.mooring.static_strength`).

The largest tension is taken over both ends of the line, fairlead and anchor: on a static
line the fairlead end carries the most, but in motion a tension wave (snap) can peak at the
anchor. It is given over the analysis window (from the end of the ramp, the window of the other
statistics) and over the whole record, so that a start-up peak that reaches the MBL still shows.
The ratio is ``T_max / MBL`` and the safety factor ``MBL / T_max``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from floatmoor.case.schema import Case

__all__ = ["MBL_VARIABLE", "TENSION_ENDS", "SECTION_TENSION_ENDS", "mbl_ratio",
           "safety_factor", "line_mbl", "largest_tension", "line_strength", "section_strength"]

#: The per-line MBL variable of a result dataset [N] (NaN: none given).
MBL_VARIABLE = "minimum_breaking_load"
#: Tension variables of a result dataset searched for the largest tension, with their end.
TENSION_ENDS = (("fairlead_tension", "fairlead"), ("anchor_tension", "anchor"))
#: The same for a section of a mooring system (dimension ``section``).
SECTION_TENSION_ENDS = (("section_end_tension", "end"), ("section_start_tension", "start"))
#: Relative slack on the window start, as in floatmoor.post.statistics [-].
_TIME_EPS = 1e-9


def mbl_ratio(tension: float, mbl: float | None) -> float | None:
    """``T / MBL`` [-], or None without an MBL (None or NaN)."""
    if mbl is None or not math.isfinite(mbl):
        return None
    return float(tension) / mbl


def safety_factor(tension: float, mbl: float | None) -> float | None:
    """``MBL / T`` [-] (inf at zero tension), or None without an MBL (None or NaN).

    Parameters
    ----------
    tension
        The tension T [N].
    mbl
        The line type's minimum breaking load [N], or None.

    Returns
    -------
    float or None
        The safety factor.
    """
    if mbl is None or not math.isfinite(mbl):
        return None
    return math.inf if tension <= 0.0 else mbl / float(tension)


def line_mbl(dataset: xr.Dataset, line: str, case: Case | None = None) -> float | None:
    """The MBL of ``line`` [N]: the dataset's :data:`MBL_VARIABLE`, else its type's in
    ``case`` (datasets written before the variable existed), else None."""
    if MBL_VARIABLE in dataset:
        value = float(dataset[MBL_VARIABLE].sel(line=line))
        return value if math.isfinite(value) else None
    if case is not None:
        for ln in case.lines:
            if ln.name == line:
                return ln.end_type.minimum_breaking_load
    return None


def largest_tension(dataset: xr.Dataset, line: str, *, start: float = 0.0,
                    ends: tuple[tuple[str, str], ...] = TENSION_ENDS, dim: str = "line"
                    ) -> tuple[float, str, float]:
    """The largest tension of ``line`` at either end from ``start`` on (of a section with
    ``ends=SECTION_TENSION_ENDS, dim="section"``).

    Returns
    -------
    tuple
        (tension [N], end ``"fairlead"`` or ``"anchor"``, time [s]). When no sample lies at
        or after ``start`` the whole record is used (as :func:`channel_statistics` does).
    """
    time = np.asarray(dataset["time"].values, dtype=float)
    inside = time >= start - _TIME_EPS * max(abs(start), 1.0)
    if not np.any(inside):
        inside = np.ones_like(time, dtype=bool)
    best = (-math.inf, "", math.nan)
    for name, end in ends:
        if name not in dataset:
            continue
        values = np.asarray(dataset[name].sel({dim: line}).values, dtype=float)[inside]
        if values.size == 0:
            continue
        k = int(np.argmax(values))
        if values[k] > best[0]:
            best = (float(values[k]), end, float(time[inside][k]))
    if not best[1]:
        raise ValueError(f"no tension samples of line '{line}' in the dataset")
    return best


def line_strength(dataset: xr.Dataset, line: str, mbl: float | None, *, start: float
                  ) -> dict[str, Any]:
    """Largest tension of ``line`` against its MBL, after ``start`` and over the whole run.

    Parameters
    ----------
    dataset
        A run's result dataset (fairlead and anchor tensions).
    line
        The line's name.
    mbl
        The line type's minimum breaking load [N], or None.
    start
        Start of the window [s] (e.g. the end of the ramp).

    Returns
    -------
    dict
        ``minimum_breaking_load_N`` (None without one), ``max_tension_N``,
        ``max_tension_end``, ``max_tension_time_s``, ``max_tension_over_mbl`` and
        ``safety_factor`` over the window from ``start``; ``whole_run_max_tension_N`` and
        ``whole_run_max_tension_over_mbl`` over the whole record. Ratios are None without an
        MBL; the safety factor is inf at zero tension.
    """
    return _strength(dataset, line, mbl, start, TENSION_ENDS, "line")


def section_strength(dataset: xr.Dataset, section: str, mbl: float | None, *, start: float
                     ) -> dict[str, Any]:
    """:func:`line_strength` of a section of a mooring system (``line[index]``), its ends
    ``"start"`` and ``"end"``, against the MBL of its own line type."""
    return _strength(dataset, section, mbl, start, SECTION_TENSION_ENDS, "section")


def _strength(dataset: xr.Dataset, name: str, mbl: float | None, start: float,
              ends: tuple[tuple[str, str], ...], dim: str) -> dict[str, Any]:
    tension, end, at = largest_tension(dataset, name, start=start, ends=ends, dim=dim)
    whole, _, _ = largest_tension(dataset, name, start=-math.inf, ends=ends, dim=dim)
    return {
        "minimum_breaking_load_N": mbl,
        "max_tension_N": tension,
        "max_tension_end": end,
        "max_tension_time_s": at,
        "max_tension_over_mbl": mbl_ratio(tension, mbl),
        "safety_factor": safety_factor(tension, mbl),
        "whole_run_max_tension_N": whole,
        "whole_run_max_tension_over_mbl": mbl_ratio(whole, mbl),
    }
