"""Reading values of an OrcaFlex model: numbers with units, names, tables, key paths.

Every failure is a :class:`floatmoor.errors.CaseError` naming the file, the key path (as
``Lines["Line1"].Connection[End B].ConnectionX``), what was expected and what was found, the
text from the file shown through :func:`floatmoor.terminal_text.shown`.
"""

from __future__ import annotations

import math
import re
from typing import Any

from floatmoor.errors import CaseError
from floatmoor.terminal_text import shown

__all__ = ["Values", "plain", "MAX_ABS_VALUE", "MAX_OBJECTS", "MAX_NAME_LENGTH"]

#: Largest magnitude of a number read, in the file's units (kN, m, te, s) [-]: a chain's EA is
#: about 1e6 kN, a seabed stiffness 1e2 to 1e5 kN/m/m^2; nothing in a mooring comes within
#: seven orders of 1e12, so a larger number is a typing error, and refusing it keeps the
#: mapping's products (kN -> N, squares of diameters) far from overflow.
MAX_ABS_VALUE = 1e12
#: Most objects of one kind (line types, lines, buoys, vessels) and most rows of one table
#: (a line's sections): real mooring models have tens; this bounds the case file written.
MAX_OBJECTS = 10_000
#: Longest object name kept [characters] (OrcaFlex's own names are short).
MAX_NAME_LENGTH = 200

_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")


class Values:
    """Value readers for one file (``source``, for the messages)."""

    def __init__(self, source: str) -> None:
        self.source = source

    def error(self, path: str, expected: str, found: Any) -> CaseError:
        """The error for ``path`` (``found`` shown as the file has it)."""
        return CaseError(self.source, shown(path, 300), expected, _found(found))

    def mapping(self, value: Any, path: str, what: str) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise self.error(path, what, value)
        return value

    def items(self, value: Any, path: str, what: str) -> list[dict[str, Any]]:
        """A list of objects (each a mapping with a Name), at most :data:`MAX_OBJECTS`."""
        if not isinstance(value, list):
            raise self.error(path, f"a list of {what}", value)
        if len(value) > MAX_OBJECTS:
            raise self.error(path, f"at most {MAX_OBJECTS} {what}", f"{len(value)}")
        for i, item in enumerate(value):
            self.mapping(item, f"{path}[{i}]", f"one of the {what} (a mapping with a Name)")
        return value

    def name(self, value: Any, path: str) -> str:
        """An object name: non-empty text without '.' or control characters."""
        if isinstance(value, bool) or value is None or isinstance(value, (list, dict)):
            raise self.error(path, "a name", value)
        text = str(value)
        if (not text.strip() or "." in text or len(text) > MAX_NAME_LENGTH
                or shown(text) != text or '"' in text or "\\" in text):
            raise self.error(path, f"a name of 1 to {MAX_NAME_LENGTH} characters without "
                             "'.', quotes, backslashes or control characters (floatmoor names "
                             "lines and points by it)", value)
        return text

    def text(self, value: Any, path: str, expected: str) -> str:
        if not isinstance(value, str):
            raise self.error(path, expected, value)
        return value

    def number(self, value: Any, path: str, unit: str, *, minimum: float | None = None,
               positive: bool = False) -> float:
        """A finite number of magnitude at most :data:`MAX_ABS_VALUE` (``unit`` for the
        message), ``> 0`` when ``positive``, ``>= minimum`` when given."""
        bound = (" > 0" if positive else f" >= {minimum:g}" if minimum is not None else "")
        expected = f"a number{bound} [{unit}]"
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise self.error(path, expected, value)
        if isinstance(value, str):
            if not _NUMBER.fullmatch(value.strip()):
                raise self.error(path, expected, value)
            value = float(value)
        number = float(value)
        if not math.isfinite(number) or abs(number) > MAX_ABS_VALUE:
            raise self.error(path, f"{expected}, of magnitude at most {MAX_ABS_VALUE:g}",
                             value)
        if (positive and not number > 0.0) or (minimum is not None and number < minimum):
            raise self.error(path, expected, value)
        return number

    def vector(self, value: Any, path: str, unit: str, size: int = 3) -> tuple[float, ...]:
        if not isinstance(value, list) or len(value) != size:
            raise self.error(path, f"a list of {size} numbers [{unit}]", value)
        return tuple(self.number(v, f"{path}[{i}]", unit) for i, v in enumerate(value))

    def table(self, obj: dict[str, Any], path: str, first: str,
              allowed: tuple[str, ...], required: tuple[str, ...],
              optional: bool = False) -> tuple[str, list[dict[str, Any]], list[str]] | None:
        """OrcaFlex's table of rows under a key naming its columns (``"LineType, Length,
        TargetSegmentLength"``): the key, its rows as {column: value} (a short row leaves its
        last columns ~) and the columns not in ``allowed``, which must be ~ in every row (a
        value there is refused: floatmoor does not read it). None when ``optional`` and there
        is no such key."""
        keys = [k for k in obj if isinstance(k, str) and k.split(",")[0].strip() == first]
        if not keys:
            if optional:
                return None
            raise self.error(path, f"a table '{', '.join(required)}: [...]'", "none")
        if len(keys) > 1:
            raise self.error(path, f"one table starting with {first}", ", ".join(keys))
        key = keys[0]
        columns = [c.strip() for c in key.split(",")]
        for column in required:
            if column not in columns:
                raise self.error(f"{path}.{key}", f"a column {column}", "none")
        rows = obj[key]
        if not isinstance(rows, list) or not rows or len(rows) > MAX_OBJECTS:
            raise self.error(f"{path}.{key}", f"a list of 1 to {MAX_OBJECTS} rows", rows)
        out = []
        for i, row in enumerate(rows):
            if not isinstance(row, list) or len(row) > len(columns):
                raise self.error(f"{path}.{key}[{i}]", f"a row of at most {len(columns)} "
                                 "values", row)
            out.append(dict(zip(columns, row + [None] * (len(columns) - len(row)))))
        unknown = [c for c in columns if c not in allowed]
        for column in unknown:
            for i, row in enumerate(out):
                if row[column] is not None:
                    raise self.error(f"{path}.{key}[{i}].{column}", "~ (floatmoor reads only "
                                     + ", ".join(allowed) + ")", row[column])
        return key, out, unknown


def plain(value: Any, limit: int = 120) -> str:
    """A value as the file writes it (``~`` for nothing, lists in brackets), shown safely."""
    def text(v: Any) -> str:
        if v is None:
            return "~"
        if isinstance(v, bool):
            return "Yes" if v else "No"
        if isinstance(v, list):
            return "[" + ", ".join(text(x) for x in v[:20]) + (", ...]" if len(v) > 20
                                                                else "]")
        if isinstance(v, dict):
            return "{...}"
        return str(v)
    return shown(text(value), limit)


def _found(value: Any) -> str:
    if value is None:
        return "~ (nothing)"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list " + plain(value)
    return shown(repr(value) if isinstance(value, str) else value, 120)
