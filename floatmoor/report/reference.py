"""Reference values to print beside a report's results (``--reference FILE``), e.g. published.

A reference file is TOML; tensions in N, damage dimensionless::

    title = "DeepCwind LC34, published values"       # heading of the reference columns
    source = "quasi-dynamic paper, Tables 8 and 10"  # where the numbers come from
    duration = 10800.0        # s, optional: the record length the damage refers to
    nominal_diameter = 0.0779 # m, optional: chain nominal diameter of every line ...
    # ... or per line: [nominal_diameter] line1 = 0.0779

    [values.experiment]       # one table per reference column; its label:
    label = "experiment"
    [values.experiment.line1] # per line: any of mean, std, min, max [N], damage [-]
    mean = 1.033e6

Loading is strict: unknown keys and non-numbers are errors naming the key.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from floatmoor.report.runs import ReportInputError

__all__ = ["ReferenceColumn", "ReferenceValues", "load_reference", "REFERENCE_QUANTITIES"]

#: Quantities a reference line may give: tension statistics [N] and fatigue damage [-].
REFERENCE_QUANTITIES = ("mean", "std", "min", "max", "damage")


@dataclass(frozen=True)
class ReferenceColumn:
    """One reference column: a label and, per line, quantity -> value."""

    key: str
    label: str
    lines: dict[str, dict[str, float]]


@dataclass(frozen=True)
class ReferenceValues:
    """A reference file's contents."""

    title: str
    source: str
    path: str
    columns: tuple[ReferenceColumn, ...]
    duration: float | None = None  #: record length the damage refers to [s]
    nominal_diameters: dict[str, float] = field(default_factory=dict)  #: line -> [m]
    default_nominal_diameter: float | None = None  #: [m], lines not in nominal_diameters

    @property
    def line_names(self) -> set[str]:
        """Every line a column names."""
        return {line for column in self.columns for line in column.lines}

    def nominal_diameter_map(self, lines: list[str]) -> dict[str, float]:
        """Line -> nominal diameter for ``lines`` (only those the file gives one)."""
        out = {}
        for line in lines:
            if line in self.nominal_diameters:
                out[line] = self.nominal_diameters[line]
            elif self.default_nominal_diameter is not None:
                out[line] = self.default_nominal_diameter
        return out


def _number(where: str, value: object, *, positive: bool = False) -> float:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) \
        and math.isfinite(float(value))
    if ok and positive:
        ok = float(value) > 0.0
    if not ok:
        raise ReportInputError(where, "a finite number" + (" > 0" if positive else ""),
                               repr(value))
    return float(value)


def _unknown(where: str, table: dict, allowed: tuple[str, ...]) -> None:
    extra = sorted(set(table) - set(allowed))
    if extra:
        raise ReportInputError(where, "keys among " + ", ".join(allowed),
                               "unknown key(s) " + ", ".join(extra))


def load_reference(path: str | Path) -> ReferenceValues:
    """Read a reference file.

    Raises
    ------
    ReportInputError
        For a missing or unreadable file, malformed TOML, an unknown key or a bad value.
    """
    path = Path(path)
    name = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ReportInputError(name, "a reference file (TOML)", "no such file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise ReportInputError(name, "a readable UTF-8 reference file", str(err)) from None
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ReportInputError(name, "valid TOML", f"a syntax error ({err})") from None
    except RecursionError:  # nesting deep enough to exhaust the parser
        raise ReportInputError(name, "valid TOML", "nesting deeper than the parser can "
                               "follow") from None
    _unknown(name, raw, ("title", "source", "duration", "nominal_diameter", "values"))
    title = raw.get("title", "reference values")
    source = raw.get("source", "")
    if not isinstance(title, str) or not isinstance(source, str):
        raise ReportInputError(f"{name}: title/source", "strings", f"{title!r}, {source!r}")
    duration = _number(f"{name}: duration", raw["duration"], positive=True) \
        if "duration" in raw else None
    diameters: dict[str, float] = {}
    default_d = None
    d_raw = raw.get("nominal_diameter")
    if isinstance(d_raw, dict):
        diameters = {str(k): _number(f"{name}: nominal_diameter.{k}", v, positive=True)
                     for k, v in d_raw.items()}
    elif d_raw is not None:
        default_d = _number(f"{name}: nominal_diameter", d_raw, positive=True)
    values = raw.get("values")
    if not isinstance(values, dict) or not values:
        raise ReportInputError(f"{name}: values", "one or more [values.NAME] tables",
                               "none" if values is None else repr(values))
    columns = []
    for key, table in values.items():
        where = f"{name}: values.{key}"
        if not isinstance(table, dict):
            raise ReportInputError(where, "a table", repr(table))
        label = table.get("label", key)
        if not isinstance(label, str):
            raise ReportInputError(f"{where}.label", "a string", repr(label))
        lines: dict[str, dict[str, float]] = {}
        for line, entries in table.items():
            if line == "label":
                continue
            if not isinstance(entries, dict):
                raise ReportInputError(f"{where}.{line}", "a table of line values",
                                       repr(entries))
            _unknown(f"{where}.{line}", entries, REFERENCE_QUANTITIES)
            lines[line] = {q: _number(f"{where}.{line}.{q}", v) for q, v in entries.items()}
        columns.append(ReferenceColumn(key, label, lines))
    return ReferenceValues(title=title, source=source, path=name, columns=tuple(columns),
                           duration=duration, nominal_diameters=diameters,
                           default_nominal_diameter=default_d)
