"""Campaign designs: which overrides each run of a campaign applies.

A campaign sweeps case keys over values. ``--grid key=v1,v2,...`` keys span a Cartesian
product, one dimension per key; ``--zip key=v1,v2,...`` keys (all of the same length) vary
together along one dimension, named after the first of them. Values are TOML values.
"""

from __future__ import annotations

import itertools
import tomllib
from dataclasses import dataclass, field
from typing import Any, Sequence

from floatmoor.case.naming import file_stem, toml_text
from floatmoor.errors import CaseError

__all__ = ["Axis", "CampaignDesign", "parse_axis_option", "design_from_options"]


@dataclass(frozen=True)
class Axis:
    """One dimension of a campaign: one or more keys (zipped) and their values.

    Attributes
    ----------
    keys
        The case keys swept together (``--set`` paths).
    values
        One tuple of values (one per key) per point of the axis."""

    keys: tuple[str, ...]
    values: tuple[tuple[Any, ...], ...]  #: values[i][j]: key i at index j

    @property
    def name(self) -> str:
        """The dimension name: the first key."""
        return self.keys[0]

    def __len__(self) -> int:
        return len(self.values[0])


@dataclass(frozen=True)
class CampaignDesign:
    """The axes of a campaign; runs are the product of the axes.

    Attributes
    ----------
    axes
        The campaign's dimensions."""

    axes: tuple[Axis, ...] = field(default_factory=tuple)

    @property
    def shape(self) -> tuple[int, ...]:
        """Number of runs along each axis."""
        return tuple(len(a) for a in self.axes)

    @property
    def size(self) -> int:
        """Number of runs."""
        n = 1
        for s in self.shape:
            n *= s
        return n

    def runs(self) -> list[tuple[tuple[int, ...], list[str]]]:
        """Every run: its index along each axis and its ``key=VALUE`` overrides."""
        out = []
        for index in itertools.product(*(range(len(a)) for a in self.axes)):
            overrides = []
            for axis, j in zip(self.axes, index):
                for key, values in zip(axis.keys, axis.values):
                    overrides.append(f"{key}={toml_text(values[j])}")
            out.append((index, overrides))
        return out

    def run_names(self) -> list[str]:
        """A file-name stem per run, in :meth:`runs` order, from its swept values:
        ``motion.radius=0.1_motion.period=1.25`` (zipped keys by their first key), by the rule
        of :func:`floatmoor.case.naming.file_stem`.

        Falls back to the run's index along each axis (``run_0-1``) for every run when the
        values do not give distinct names (values that differ only in dropped characters).
        """
        names = [file_stem([(axis.name, axis.values[0][j]) for axis, j in zip(self.axes, index)])
                 for index in itertools.product(*(range(len(a)) for a in self.axes))]
        if len(set(names)) != len(names) or any(n.startswith(".") for n in names):
            names = ["run_" + "-".join(str(j) for j in index) for index in
                     itertools.product(*(range(len(a)) for a in self.axes))]
        return names


def parse_axis_option(text: str, option: str) -> tuple[str, list[Any]]:
    """``key=v1,v2,...`` (TOML values) -> (key, values)."""
    where = f"{option} {text}"
    key, sep, values_text = text.partition("=")
    key = key.strip()
    if not sep or not key or any(not part for part in key.split(".")):
        raise CaseError(where, "", "key=v1,v2,... with a dotted key and TOML values",
                        f"'{text}'")
    try:
        values = tomllib.loads(f"values = [{values_text}]")["values"]
    except (tomllib.TOMLDecodeError, RecursionError):  # RecursionError: absurdly deep nesting
        raise CaseError(where, key, "a comma-separated list of TOML values (strings quoted)",
                        f"'{values_text}'") from None
    if not values:
        raise CaseError(where, key, "at least one value", "none")
    return key, values


def design_from_options(grid: Sequence[str] = (), zipped: Sequence[str] = (),
                        table: dict[str, dict[str, list[Any]]] | None = None) -> CampaignDesign:
    """Build a design from ``--grid``/``--zip`` options and a case-file ``[campaign]`` table.

    Parameters
    ----------
    grid, zipped
        The options' texts, ``key=v1,v2,...``.
    table
        ``{"grid": {key: [values]}, "zip": {key: [values]}}`` from the case file; the command
        line's keys replace the table's.
    """
    grid_axes: dict[str, list[Any]] = dict((table or {}).get("grid", {}))
    zip_axes: dict[str, list[Any]] = dict((table or {}).get("zip", {}))
    given: dict[str, str] = {}  # key -> the option that swept it on the command line
    for option, texts, axes_of in (("--grid", grid, grid_axes), ("--zip", zipped, zip_axes)):
        for text in texts:
            key, values = parse_axis_option(text, option)
            if key in given:  # two sweeps of one key: neither may silently win
                raise CaseError(f"{option} {text}", key, "a key swept once (by one --grid or "
                                "--zip)", f"it also in {given[key]}")
            given[key] = f"{option} {text}"
            axes_of[key] = values
    for key in set(grid_axes) & set(zip_axes):
        raise CaseError("--grid/--zip", key, "a key swept once", "it in both a grid and a zip")
    axes = [Axis((key,), (tuple(values),)) for key, values in grid_axes.items()]
    if zip_axes:
        lengths = {key: len(v) for key, v in zip_axes.items()}
        if len(set(lengths.values())) != 1:
            raise CaseError("--zip", ", ".join(lengths), "zipped keys with equally many values",
                            ", ".join(f"{k}: {n}" for k, n in lengths.items()))
        axes.append(Axis(tuple(zip_axes), tuple(tuple(v) for v in zip_axes.values())))
    if not axes:
        raise CaseError("--grid/--zip", "", "at least one swept key", "none")
    return CampaignDesign(tuple(axes))
