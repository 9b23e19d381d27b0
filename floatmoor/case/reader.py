"""Strict, path-aware reading of a parsed TOML table.

:class:`TableReader` wraps one table of the raw case dictionary. Each accessor reads one key,
checks its type and range, and raises :class:`~floatmoor.errors.CaseError` naming the file,
the key path, what was expected and what was found. :meth:`TableReader.finish` rejects the
keys nobody asked for, so a misspelt key is an error rather than a silently ignored value.

The accessors are the schema of the input files: each states a key's type, unit, bounds,
choices and default. Inside :func:`recording`, every accessor also reports them as a
:class:`KeyRecord` (the case-file reference is generated from these records,
:mod:`floatmoor.case.reference`); outside it the report costs one ``is None`` test.
"""

from __future__ import annotations

import difflib
import math
import unicodedata
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Any, Callable, Iterator

from floatmoor.errors import CaseError

__all__ = ["Path", "ReadContext", "TableReader", "MISSING", "describe_value", "format_path",
           "KeyRecord", "recording", "generic_path"]

Path = tuple[str | int, ...]


class _Missing:
    def __repr__(self) -> str:
        return "MISSING"


MISSING: Any = _Missing()


#: How alike a missing key and an unknown one must be for the error to name the unknown one as
#: its likely misspelling (difflib's ratio: 'mass_per_lenght' against 'mass_per_length' is 0.93,
#: 'length' against 'diameter' 0.29).
SPELLING_CUTOFF = 0.75


def format_path(path: Path) -> str:
    """``('lines', 0, 'anchor')`` -> ``lines[0].anchor``."""
    text = ""
    for part in path:
        if isinstance(part, int):
            text += f"[{part}]"
        else:
            text += ("." if text else "") + part
    return text


def describe_value(value: Any) -> str:
    """A short TOML-like rendering of ``value`` for error messages."""
    if value is MISSING:
        return "nothing (the key is missing)"
    if isinstance(value, bool):
        return f"the boolean {'true' if value else 'false'}"
    if isinstance(value, str):
        return f'the string "{value}"'
    if isinstance(value, (int, float)):
        return f"{value!r}"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        items = ", ".join(_short(v) for v in value[:6])
        more = ", ..." if len(value) > 6 else ""
        return f"an array of {len(value)} [{items}{more}]"
    return f"a {type(value).__name__}"


def _short(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, dict):
        return "{...}"
    if isinstance(value, list):
        return "[...]"
    return repr(value)


@dataclass(frozen=True)
class KeyRecord:
    """What one accessor asked of one key: the schema of that key, as read.

    ``path`` is the key's generic path: entries of an array of tables as ``[]``
    (``lines[].name``), the tables of a table of named tables as ``<name>``
    (``line_types.<name>.diameter``). ``default`` is :data:`MISSING` for a required key.
    """

    source: str  #: the file read
    path: str  #: generic key path
    kind: str  #: number, integer, string, boolean, vector, table, array, ...
    unit: str = ""
    bounds: str = ""  #: e.g. "> 0 and <= 1"
    choices: tuple[str, ...] = ()
    default: Any = MISSING
    size: int | None = None  #: length of a vector
    table: str = ""  #: concrete path of the table the key is in (``lines[2].dynamic``)
    #: the key's description, for a key declared as a setting (floatmoor.case.setting)
    doc: str = ""
    #: the wording of a default computed from other values (``"{default}"``: the recorded one)
    default_text: str | None = None
    #: the wording of bounds or choices computed from other values
    allowed_text: str | None = None
    #: the wording of the type of an array whose length depends on its value
    type_text: str | None = None


#: The recorder of the current :func:`recording` block (None: not recording).
_RECORDER: ContextVar[Callable[[KeyRecord], None] | None] = ContextVar("floatmoor_key_recorder",
                                                                        default=None)


@contextmanager
def recording() -> Iterator[list[KeyRecord]]:
    """Collect a :class:`KeyRecord` for every key every reader created inside the block asks
    for (case and study loaders alike); yields the list they are appended to."""
    records: list[KeyRecord] = []
    token = _RECORDER.set(records.append)
    try:
        yield records
    finally:
        _RECORDER.reset(token)


def generic_path(parent: str, key: str) -> str:
    """``generic_path("lines[]", "dynamic")`` -> ``lines[].dynamic``."""
    return f"{parent}.{key}" if parent else key


@dataclass
class ReadContext:
    """Where the values come from: the file, and the key paths set on the command line.

    Parameters
    ----------
    source
        The case file path as the user gave it.
    overrides
        Key path -> the ``--set`` text that set it; an error at or below such a path names it.
    """

    source: str
    overrides: dict[Path, str] = field(default_factory=dict)
    #: Receives a :class:`KeyRecord` per key asked for; set from :func:`recording`.
    recorder: Callable[[KeyRecord], None] | None = field(
        default_factory=_RECORDER.get, repr=False, compare=False)

    def origin(self, path: Path) -> str:
        """The source to name for an error at ``path``."""
        for length in range(len(path), 0, -1):
            text = self.overrides.get(path[:length])
            if text is not None:
                return f"{self.source} (--set {text})"
        return self.source

    def error(self, path: Path, expected: str, found: str) -> CaseError:
        """Build the error for ``path``."""
        return CaseError(self.origin(path), format_path(path), expected, found)


def _bound_text(gt: float | None, ge: float | None, lt: float | None, le: float | None) -> str:
    def text(v: float) -> str:  # an integer bound exactly (2^32 - 1, not 4.29497e+09)
        return str(v) if isinstance(v, int) else f"{v:g}"

    parts = []
    if gt is not None:
        parts.append(f"> {text(gt)}")
    if ge is not None:
        parts.append(f">= {text(ge)}")
    if lt is not None:
        parts.append(f"< {text(lt)}")
    if le is not None:
        parts.append(f"<= {text(le)}")
    return " and ".join(parts)


def _number_text(kind: str, unit: str, gt: float | None, ge: float | None, lt: float | None,
                 le: float | None) -> str:
    bounds = _bound_text(gt, ge, lt, le)
    text = kind + (f" {bounds}" if bounds else "")
    return text + (f" [{unit}]" if unit else "")


class TableReader:
    """Reads the keys of one table, with range checks, and remembers which were read.

    Parameters
    ----------
    data
        The raw table.
    path
        Its key path in the case.
    context
        The :class:`ReadContext` for error messages.
    generic
        Its generic key path (:class:`KeyRecord`), kept only while recording.
    """

    def __init__(self, data: dict[str, Any], path: Path, context: ReadContext,
                 generic: str = "") -> None:
        self.data = data
        self.path = path
        self.context = context
        self.generic = generic
        self._read: set[str] = set()
        self._note: tuple[str, str | None, str | None, str | None] = ("", None, None, None)

    @contextmanager
    def describing(self, doc: str, default_text: str | None, allowed_text: str | None = None,
                   type_text: str | None = None) -> Iterator[None]:
        """Record the keys read inside the block with this description (and wordings of a
        computed default, of computed bounds and of an array's type): a declared setting's
        (floatmoor.case.setting)."""
        self._note = (doc, default_text, allowed_text, type_text)
        try:
            yield
        finally:
            self._note = ("", None, None, None)

    def _record(self, key: str, kind: str, *, unit: str = "", bounds: str = "",
                choices: tuple[str, ...] | None = None, default: Any = MISSING,
                size: int | None = None, name: str | None = None) -> None:
        """Report ``key`` to the context's recorder (``name``: its generic name, if not
        itself)."""
        self.context.recorder(KeyRecord(  # type: ignore[misc]
            self.context.source, generic_path(self.generic, name or key), kind, unit, bounds,
            tuple(choices or ()), default, size, format_path(self.path), *self._note))

    def claim(self, key: str, kind: str, *, unit: str = "", bounds: str = "",
              choices: tuple[str, ...] = (), default: Any = MISSING,
              name: str | None = None) -> Any:
        """Mark ``key`` read and return its raw value (``default`` when absent), for a key
        the caller checks itself (an array of triples, of names, ...); ``kind`` and
        ``name`` (its generic name, e.g. ``<coefficient>``) are for the record."""
        if self.context.recorder is not None:
            self._record(key, kind, unit=unit, bounds=bounds, choices=choices, default=default,
                         name=name)
        self._read.add(key)
        return self.data.get(key, default)

    # -- generic -------------------------------------------------------------------------------
    def error(self, key: str | int | Path, expected: str, found: Any) -> CaseError:
        """An error at ``key`` of this table; ``found`` is a raw value or a preformatted str."""
        sub = key if isinstance(key, tuple) else (key,)
        text = found if isinstance(found, _Found) else describe_value(found)
        return self.context.error(self.path + sub, expected, str(text))

    def has(self, key: str) -> bool:
        """Whether ``key`` is present."""
        return key in self.data

    def _get(self, key: str, default: Any, expected: str) -> Any:
        self._read.add(key)
        if key in self.data:
            return self.data[key]
        if default is MISSING:
            raise self.error(key, expected, self._missing(key))
        return default

    def _missing(self, key: str) -> "_Found | object":
        """What a missing ``key`` found: nothing, and the unread key of this table that looks
        like a misspelling of it, if one does."""
        unread = [k for k in self.data if k not in self._read and isinstance(k, str)]
        close = difflib.get_close_matches(key, unread, n=1, cutoff=SPELLING_CUTOFF)
        if not close:
            return MISSING
        return _Found(f"{describe_value(MISSING)}; the unknown key '{close[0]}' of the same "
                      "table looks like it")

    # -- scalars -------------------------------------------------------------------------------
    def number(self, key: str, *, unit: str, gt: float | None = None, ge: float | None = None,
               lt: float | None = None, le: float | None = None, default: Any = MISSING,
               auto: str | None = None) -> float:
        """A finite number (TOML integer or float) within the given bounds; with ``auto``
        (what it means, for the message) also the string "auto", read as None."""
        if self.context.recorder is not None:
            self._record(key, "number", unit=unit, bounds=_bound_text(gt, ge, lt, le),
                         choices=("auto",) if auto is not None else None, default=default)
        expected = _number_text("a finite number", unit, gt, ge, lt, le)
        if auto is not None:
            expected += f' or "auto" ({auto})'
        value = self._get(key, default, expected)
        if value is default and default is not MISSING:
            return value
        if auto is not None and value == "auto":
            return None  # type: ignore[return-value]
        return self._check_number(key, value, expected, gt, ge, lt, le)

    def _check_number(self, key: str | Path, value: Any, expected: str, gt: float | None,
                      ge: float | None, lt: float | None, le: float | None) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(key, expected, value)
        value = float(value)
        if not math.isfinite(value):
            raise self.error(key, expected, value)
        if ((gt is not None and not value > gt) or (ge is not None and not value >= ge)
                or (lt is not None and not value < lt) or (le is not None and not value <= le)):
            raise self.error(key, expected, value)
        return value

    def integer(self, key: str, *, ge: int | None = None, le: int | None = None,
                default: Any = MISSING, auto: str | None = None) -> int:
        """A TOML integer within the given bounds; with ``auto`` (what it means, for the
        message) also the string "auto", read as None."""
        if self.context.recorder is not None:
            self._record(key, "integer", bounds=_bound_text(None, ge, None, le),
                         choices=("auto",) if auto is not None else None, default=default)
        expected = _number_text("an integer", "", None, ge, None, le)
        if auto is not None:
            expected += f' or "auto" ({auto})'
        value = self._get(key, default, expected)
        if value is default and default is not MISSING:
            return value
        if auto is not None and value == "auto":
            return None  # type: ignore[return-value]
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(key, expected, value)
        if (ge is not None and value < ge) or (le is not None and value > le):
            raise self.error(key, expected, value)
        return value

    def string(self, key: str, *, choices: tuple[str, ...] | None = None,
               default: Any = MISSING) -> str:
        """A string, optionally one of ``choices``."""
        if self.context.recorder is not None:
            self._record(key, "string", choices=choices, default=default)
        if choices:
            expected = "one of " + ", ".join(f'"{c}"' for c in choices)
        else:
            expected = "a non-empty string"
        value = self._get(key, default, expected)
        if value is default and default is not MISSING:
            return value
        if not isinstance(value, str) or not value.strip():
            raise self.error(key, expected, value)
        if choices and value not in choices:
            raise self.error(key, expected, value)
        return value

    def name(self) -> str:
        """The key ``name`` (of a line, point or floater): a non-empty string without
        control, format or line-separator characters, since it is printed, written into
        result files and exported decks, each of which takes one line."""
        value = self.string("name")
        bad = [c for c in value if unicodedata.category(c) in ("Cc", "Cf", "Zl", "Zp")]
        if bad:
            raise self.error("name", "a name without control or format characters (newline, "
                             "tab, escape, bidi controls)", _Found(
                                 f"a name holding {', '.join(sorted({repr(c) for c in bad}))}"))
        return value

    def boolean(self, key: str, *, default: Any = MISSING) -> bool:
        """A TOML boolean (``true`` / ``false``)."""
        if self.context.recorder is not None:
            self._record(key, "boolean", default=default)
        expected = "a boolean (true or false)"
        value = self._get(key, default, expected)
        if not isinstance(value, bool):
            raise self.error(key, expected, value)
        return value

    def vector(self, key: str, *, size: int, unit: str, gt: float | None = None,
               ge: float | None = None, default: Any = MISSING) -> tuple[float, ...]:
        """An array of ``size`` finite numbers."""
        if self.context.recorder is not None:
            self._record(key, "vector", unit=unit, bounds=_bound_text(gt, ge, None, None),
                         default=default, size=size)
        return self._vector(key, size, unit, gt, ge, default)

    def _vector(self, key: str, size: int, unit: str, gt: float | None, ge: float | None,
                default: Any) -> tuple[float, ...]:
        bounds = _bound_text(gt, ge, None, None)
        expected = (f"an array of {size} finite numbers" + (f" {bounds}" if bounds else "")
                    + (f" [{unit}]" if unit else ""))
        value = self._get(key, default, expected)
        if value is default and default is not MISSING:
            return tuple(value)
        if not isinstance(value, list) or len(value) != size:
            raise self.error(key, expected, value)
        for i, item in enumerate(value):
            if isinstance(item, bool) or not isinstance(item, (int, float)) or not math.isfinite(item):
                raise self.error((key, i), expected.replace(f"an array of {size} finite numbers",
                                                            "a finite number"), item)
            if (gt is not None and not item > gt) or (ge is not None and not item >= ge):
                raise self.error((key, i), "a finite number " + bounds, item)
        return tuple(float(v) for v in value)

    def number_or_vector(self, key: str, *, size: int, unit: str, gt: float | None = None,
                         ge: float | None = None, default: Any = MISSING) -> tuple[float, ...]:
        """One number (used for every component) or an array of ``size`` numbers."""
        if self.context.recorder is not None:
            self._record(key, "number_or_vector", unit=unit, bounds=_bound_text(gt, ge, None, None),
                         default=default, size=size)
        value = self.data.get(key, MISSING)
        if isinstance(value, list):
            return self._vector(key, size, unit, gt, ge, MISSING)
        bounds = _bound_text(gt, ge, None, None)
        expected = (f"a finite number {bounds} or an array of {size} of them".replace("  ", " ")
                    + (f" [{unit}]" if unit else ""))
        raw = self._get(key, default, expected)
        if raw is default and default is not MISSING:
            return tuple(raw)
        return (self._check_number(key, raw, expected, gt, ge, None, None),) * size

    # -- tables --------------------------------------------------------------------------------
    def table(self, key: str, *, required: bool = True) -> "TableReader":
        """A sub-table; an absent optional one reads as empty."""
        if self.context.recorder is not None:
            self._record(key, "table", default=MISSING if required else {})
        return self._table(key, required)

    def _table(self, key: str, required: bool) -> "TableReader":
        value = self._get(key, MISSING if required else {}, "a table")
        if not isinstance(value, dict):
            raise self.error(key, "a table", value)
        return TableReader(value, self.path + (key,), self.context, self._child(key))

    def _child(self, key: str, suffix: str = "") -> str:
        """The generic path of a sub-table (empty when not recording)."""
        if self.context.recorder is None:
            return ""
        return generic_path(self.generic, key) + suffix

    def tables(self, key: str, *, min_items: int = 1) -> Iterator["TableReader"]:
        """The entries of an array of tables (``[[key]]``)."""
        if self.context.recorder is not None:
            self._record(key, "tables", bounds=f">= {min_items} entries")
        expected = f"an array of tables ([[{key}]]) with at least {min_items} entry"
        value = self._get(key, MISSING, expected)
        if not isinstance(value, list) or len(value) < min_items:
            raise self.error(key, expected, value)
        for i, item in enumerate(value):
            if not isinstance(item, dict):
                raise self.error((key, i), "a table", item)
            yield TableReader(item, self.path + (key, i), self.context, self._child(key, "[]"))

    def named_tables(self, key: str) -> Iterator[tuple[str, "TableReader"]]:
        """The sub-tables of a table of named tables (``[key.NAME]``)."""
        if self.context.recorder is not None:
            self._record(key, "named_tables")
        parent = self._table(key, True)
        if not parent.data:
            raise self.error(key, f"at least one [{key}.NAME] table", "an empty table")
        for name, item in parent.data.items():
            parent._read.add(name)
            if not isinstance(item, dict):
                raise parent.error(name, "a table", item)
            yield name, TableReader(item, parent.path + (name,), self.context,
                                    parent._child("<name>"))

    def finish(self) -> None:
        """Reject keys that no accessor read."""
        for key in self.data:
            if key not in self._read:
                known = ", ".join(sorted(self._read)) or "none"
                raise self.error(key, f"one of the known keys ({known}){self._replace_hint()}",
                                 _Found(f"the unknown key '{key}'"))

    def _replace_hint(self) -> str:
        """Where an override set a key of this table (``--set waves.kind="still"``), the keys
        the file gave for the old choice stay and may be unknown to the new one: the rule to
        replace the whole table instead."""
        set_here = [text for path, text in self.context.overrides.items()
                    if len(path) == len(self.path) + 1 and path[:-1] == self.path]
        if not set_here or not self.path:
            return ""
        table = format_path(self.path)
        return (f"; --set {set_here[0]} changed one key of [{table}] and kept the file's "
                f"others: to replace the whole table give it as an inline table, e.g. --set "
                f"'{table}={{kind = \"...\", ...}}'")


class _Found(str):
    """A preformatted 'found' text."""
