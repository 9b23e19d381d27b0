"""Run datasets as a report sees them: label, analysis window and chain diameters per line.

A result dataset carries its case (attributes ``case_toml``, ``case_overrides`` and
``case_file``), from which the report recovers the default start of the analysis window (the
end of the transient: the motion ramp of a forced-motion run, the wave ramp of a coupled run,
else 0), the line types of the lines (for the chain's nominal diameter in the fatigue damage)
and the initial offset of a free-decay run.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np
import xarray as xr

from floatmoor.case.naming import override_label, value_text
from floatmoor.case.overrides import resolve_key
from floatmoor.case.schema import Case
from floatmoor.errors import CaseError, FloatmoorError
from floatmoor.io.netcdf import read_dataset
from floatmoor.io.run_case import case_from_dataset, default_start, run_overrides

__all__ = ["ReportInputError", "LineChain", "NominalDiameter", "RunData", "load_run",
           "prepare_run", "case_from_dataset", "default_start", "resolve_nominal_diameters",
           "unique_labels", "run_labels", "run_overrides", "SOLID_ROD_DENSITY_LIMIT",
           "REQUIRED_VARIABLES"]

#: Variables every run dataset must hold for a report.
REQUIRED_VARIABLES = ("fairlead_tension",)

#: Mass per length over the area of the ``diameter`` of a line type [kg/m^3] below which the
#: diameter is read as a solid-rod (volume-equivalent) one, not a chain's nominal bar diameter.
#: Solid steel gives ~7850; a studless chain at its nominal diameter d weighs ~19.9 d^2 t/m
#: (d in m, the usual catalogue rule), i.e. 19.9e3 * 4 / pi = 25,300 kg/m^3 over pi d^2 / 4.
#: 14,000 is about the geometric mean of the two, so either side is clear.
SOLID_ROD_DENSITY_LIMIT = 14_000.0

#: Offsets of a free-decay run below this (m or rad) count as none.
_DECAY_OFFSET_EPS = 1e-12


class ReportInputError(FloatmoorError, ValueError):
    """A report input (run file, option, reference file) is unusable.

    The message names the file or option, what was expected and what was found.
    """

    def __init__(self, where: str, expected: str, found: str) -> None:
        self.where = where
        super().__init__(f"{where}: expected {expected}, found {found}")


@dataclass(frozen=True)
class LineChain:
    """The line type of one line as the case gives it."""

    line: str  #: line name
    line_type: str  #: line-type name
    diameter: float  #: the case's ``diameter`` key (the drag diameter) [m]
    mass_per_length: float  #: [kg/m]

    @property
    def apparent_density(self) -> float:
        """Mass per length over the area of ``diameter`` [kg/m^3]."""
        return self.mass_per_length / (math.pi * self.diameter**2 / 4.0)

    @property
    def looks_volume_equivalent(self) -> bool:
        """True when ``diameter`` looks like a solid-rod (volume-equivalent) diameter."""
        return self.apparent_density < SOLID_ROD_DENSITY_LIMIT


@dataclass(frozen=True)
class NominalDiameter:
    """The chain nominal diameter used for a line's fatigue damage, and where it came from."""

    value: float  #: [m]
    source: str  #: e.g. "--nominal-diameter", "reference file", "case diameter"
    warning: str = ""  #: a caution for the report (e.g. a volume-equivalent case diameter)


@dataclass
class RunData:
    """One run of a report.

    Attributes
    ----------
    label
        Column heading of the run in tables and legend entry in figures.
    dataset
        The result dataset (in memory).
    start
        Start of the analysis window [s]; the transient before it is excluded.
    start_source
        How ``start`` was chosen (``--start``, ``motion ramp``, ``wave ramp``, ...).
    path
        The file it was read from, or None.
    case
        The case recovered from the dataset attributes, or None if it could not be.
    chains
        Line name -> its line type, from the case (empty without a case).
    decay_dofs
        DOFs given an initial offset (a free-decay run).
    diameters
        Line name -> nominal diameter used for fatigue (filled by
        :func:`resolve_nominal_diameters`).
    """

    label: str
    dataset: xr.Dataset
    start: float
    start_source: str
    path: Path | None = None
    case: Case | None = None
    chains: dict[str, LineChain] = field(default_factory=dict)
    decay_dofs: tuple[str, ...] = ()
    diameters: dict[str, NominalDiameter] = field(default_factory=dict)

    @property
    def lines(self) -> list[str]:
        """Line names, in dataset order."""
        return [str(x) for x in self.dataset["line"].values]

    @property
    def models(self) -> dict[str, str]:
        """Line name -> line model."""
        if "model" not in self.dataset.coords:
            return {name: "" for name in self.lines}
        return {str(n): str(m) for n, m in zip(self.dataset["line"].values,
                                               self.dataset["model"].values)}

    @property
    def has_body(self) -> bool:
        """True for a coupled (floater) run."""
        return "body_displacement" in self.dataset

    @property
    def record_end(self) -> float:
        """Last output time [s]."""
        return float(self.dataset["time"].values[-1])


def _chains(case: Case | None) -> dict[str, LineChain]:
    if case is None:
        return {}
    return {ln.name: LineChain(ln.name, ln.end_type.name, float(ln.end_type.diameter),
                               float(ln.end_type.mass_per_length)) for ln in case.lines}


def _decay_dofs(case: Case | None, dataset: xr.Dataset) -> tuple[str, ...]:
    if case is None or "dof" not in dataset.coords:
        return ()
    names = [str(d) for d in dataset["dof"].values]
    return tuple(name for name, offset in zip(names, case.initial_offset)
                 if abs(offset) > _DECAY_OFFSET_EPS)


def _check_dataset(dataset: xr.Dataset, where: str) -> None:
    for name in REQUIRED_VARIABLES:
        if name not in dataset:
            raise ReportInputError(where, f"a floatmoor result dataset with '{name}'",
                                   f"variables {sorted(map(str, dataset.data_vars))}")
    if "time" not in dataset.dims or dataset.sizes["time"] < 2:
        raise ReportInputError(where, "a record of two or more output times",
                               f"{dataset.sizes.get('time', 0)} samples")


def prepare_run(dataset: xr.Dataset, label: str, *, start: float | None = None,
                path: Path | None = None) -> RunData:
    """Wrap a result dataset for a report: case, window start, line types, decay DOFs.

    Parameters
    ----------
    dataset
        A result dataset.
    label
        Its column heading.
    start
        Start of the analysis window [s]; None: the case's ramp (:func:`default_start`).
    path
        The file it came from, for messages.

    Raises
    ------
    ReportInputError
        Without fairlead tensions, or when fewer than two samples follow ``start``.
    """
    where = str(path) if path is not None else label
    _check_dataset(dataset, where)
    case = case_from_dataset(dataset)
    if start is None:
        start, source = default_start(case)
    else:
        source = "--start"
    time = np.asarray(dataset["time"].values, dtype=float)
    if not math.isfinite(start) or start < 0.0 or np.count_nonzero(time >= start) < 2:
        raise ReportInputError(f"--start (run {where})", "a time >= 0 s with two or more "
                               f"output samples after it (the record spans {time[0]:g} to "
                               f"{time[-1]:g} s)", f"{start:g} s ({source})")
    return RunData(label=label, dataset=dataset, start=float(start), start_source=source,
                   path=path, case=case, chains=_chains(case),
                   decay_dofs=_decay_dofs(case, dataset))


def load_run(path: str | Path, *, start: float | None = None,
             label: str | None = None) -> RunData:
    """Read a run file and :func:`prepare_run` it (label: the file stem).

    Raises
    ------
    ReportInputError
        For a missing or unreadable file, or one that is not a floatmoor result.
    """
    path = Path(path)
    if not path.is_file():
        raise ReportInputError(str(path), "a floatmoor result file (netCDF)",
                               "no such file" if not path.exists() else "a folder")
    try:
        dataset = read_dataset(path)
    except Exception as err:  # any reader failure is an unreadable input
        text = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
        raise ReportInputError(str(path), "a readable netCDF result file", text) from None
    return prepare_run(dataset, label or path.stem, start=start, path=path)


def run_labels(runs: Sequence[RunData]) -> list[str]:
    """Labels that say how the runs differ: the overrides (swept values) whose value is not
    the same in all runs of a case file, ``motion.period=3.5`` (a run without one shows its
    case file's value), led by the file name when the runs come from different case files or
    the overrides do not tell them apart; repeats get ``#2``, ``#3``, ...

    What all runs share is dropped, so labels stay short without being cut.
    """
    groups: dict[str, list[int]] = {}
    for k, run in enumerate(runs):
        groups.setdefault(str(run.dataset.attrs.get("case_file", "")), []).append(k)
    differing = [""] * len(runs)
    for members in groups.values():
        texts = _differing_overrides([runs[k] for k in members])
        for k, text in zip(members, texts):
            differing[k] = text
    if len(groups) == 1 and all(differing) and len(set(differing)) == len(differing):
        return differing
    stems = [run.path.stem if run.path is not None else run.label for run in runs]
    return unique_labels([f"{stem} [{text}]" if text else stem
                          for stem, text in zip(stems, differing)])


def _differing_overrides(runs: Sequence[RunData]) -> list[str]:
    """Per run, ``key=value, ...`` of the overridden keys whose value is not the same in all
    ``runs`` (runs of one case file)."""
    items = []
    for run in runs:
        pairs: dict[str, str] = {}
        for text in run_overrides(run.dataset):
            key, _, value = override_label(text).partition("=")
            pairs.pop(key, None)
            pairs[key] = value
        items.append(pairs)
    keys = list(dict.fromkeys(key for pairs in items for key in pairs))
    keys = [key for key in keys if len({pairs.get(key) for pairs in items}) > 1]
    return [", ".join(f"{key}={pairs[key] if key in pairs else _file_value(run, key)}"
                      for key in keys) for run, pairs in zip(runs, items)]


def _file_value(run: RunData, key: str) -> str:
    """The value the run's case file gives ``key``, for a run that does not override it."""
    try:
        raw = tomllib.loads(str(run.dataset.attrs.get("case_toml", "")))
        return value_text(resolve_key(raw, key.split("."), "case")[1])
    except (tomllib.TOMLDecodeError, CaseError, RecursionError):
        return "(case file)"


def unique_labels(labels: Sequence[str]) -> list[str]:
    """Make labels unique by appending ``#2``, ``#3``, ... to repeats."""
    seen: dict[str, int] = {}
    out = []
    for label in labels:
        seen[label] = seen.get(label, 0) + 1
        out.append(label if seen[label] == 1 else f"{label} #{seen[label]}")
    return out


def resolve_nominal_diameters(runs: Sequence[RunData], overrides: Mapping[str, float],
                              reference: Mapping[str, float] | None = None) -> None:
    """Choose the chain nominal diameter of every line of every run (in place).

    Precedence: ``overrides`` (``--nominal-diameter``, keyed by line name or line-type name),
    then ``reference`` (the reference file's nominal diameters, keyed by line name), then the
    case's ``diameter`` of the line type, flagged when it looks volume-equivalent
    (:data:`SOLID_ROD_DENSITY_LIMIT`).

    Raises
    ------
    ReportInputError
        For an override key that names no line or line type of any run, a value that is not
        > 0, or a line without any diameter.
    """
    known = {name for run in runs for name in run.lines}
    known |= {chain.line_type for run in runs for chain in run.chains.values()}
    for key, value in overrides.items():
        if key not in known:
            raise ReportInputError("--nominal-diameter", "a line or line-type name of the runs ("
                                   + ", ".join(sorted(known)) + ")", f"'{key}'")
        if not (math.isfinite(value) and value > 0.0):
            raise ReportInputError("--nominal-diameter", "a diameter > 0 [m]",
                                   f"{key}={value!r}")
    reference = reference or {}
    for run in runs:
        run.diameters = {}
        for line in run.lines:
            chain = run.chains.get(line)
            type_name = chain.line_type if chain is not None else None
            if line in overrides:
                run.diameters[line] = NominalDiameter(overrides[line], "--nominal-diameter")
            elif type_name is not None and type_name in overrides:
                run.diameters[line] = NominalDiameter(overrides[type_name],
                                                      "--nominal-diameter")
            elif line in reference:
                run.diameters[line] = NominalDiameter(reference[line], "reference file")
            elif chain is not None:
                warning = ""
                if chain.looks_volume_equivalent:
                    warning = (f"the case diameter {chain.diameter:g} m of line type "
                               f"'{chain.line_type}' gives {chain.apparent_density:.0f} kg/m^3 "
                               "(mass per length over its area), a solid rod: it is likely a "
                               "volume-equivalent diameter, not the chain's nominal one; pass "
                               "--nominal-diameter")
                run.diameters[line] = NominalDiameter(
                    chain.diameter, f"case diameter of line type '{chain.line_type}'", warning)
            else:
                raise ReportInputError(
                    f"--nominal-diameter (run {run.path or run.label})",
                    f"a nominal diameter for line '{line}' (its case could not be re-read)",
                    "none")
