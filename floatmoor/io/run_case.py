"""The case of a run, re-read from its result dataset: a result carries its case (attributes
``case_toml``, ``case_overrides`` and ``case_file``), from which the views and reports recover
what the numbers alone do not say (the seabed depth, the ramp, the line types).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import xarray as xr

from floatmoor.case.load import parse_case
from floatmoor.case.schema import Case
from floatmoor.errors import CaseError

__all__ = ["case_from_dataset", "default_start", "run_overrides"]


def case_from_dataset(dataset: xr.Dataset) -> Case | None:
    """The case of a run, re-read from the dataset's ``case_toml`` and ``case_overrides``.

    Returns None when the attributes are missing or no longer give a valid case (for example
    a motion table file that moved).
    """
    text = dataset.attrs.get("case_toml")
    if not isinstance(text, str) or not text.strip():
        return None
    overrides = tuple(run_overrides(dataset))
    source = str(dataset.attrs.get("case_file", "case"))
    try:
        raw = tomllib.loads(text)
        return parse_case(raw, source=source, text=text, overrides=overrides,
                          base_dir=Path(source).parent)
    except (tomllib.TOMLDecodeError, CaseError, OSError, ValueError, RecursionError):
        return None


def default_start(case: Case | None) -> tuple[float, str]:
    """The end of a case's transient: its motion ramp or wave ramp, else 0 [s], and what it is
    (a motion without a ramp starts the lines at rest in its pose at t = 0, and its window is
    the whole record: docs/guide/running.md#what-a-run-writes-and-prints)."""
    if case is None:
        return 0.0, "record start (the case could not be re-read from the dataset)"
    if case.motion is not None:
        if case.motion.ramp_duration <= 0.0:
            return 0.0, "record start (no motion ramp)"
        return float(case.motion.ramp_duration), "motion ramp"
    if case.waves is not None:
        if case.waves.ramp_duration <= 0.0:
            return 0.0, "record start (no wave ramp)"
        return float(case.waves.ramp_duration), "wave ramp"
    return 0.0, "record start (no ramp)"


def run_overrides(dataset: xr.Dataset) -> list[str]:
    """The ``--set`` overrides of a run, as typed (the dataset's ``case_overrides``)."""
    text = str(dataset.attrs.get("case_overrides", "none"))
    return [s for s in text.splitlines() if s.strip()] if text != "none" else []
