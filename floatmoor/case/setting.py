"""One declaration per case-file setting: type, unit, bounds, default and description.

A key of a case-file table is declared once, as a field of the table's frozen dataclass in
:mod:`floatmoor.case.schema`::

    diameter: float = setting("number", unit="m", gt=0.0,
                              doc="Diameter the drag and added-mass coefficients refer to.")

From that one declaration come both the strict reading of the key (:func:`read_settings`
calls the :class:`~floatmoor.case.reader.TableReader` accessor of its kind, with the error
messages of every other key: file, key path, expected, found) and its row of the generated
case-file reference (the description travels in the reader's
:class:`~floatmoor.case.reader.KeyRecord`; :mod:`floatmoor.case.reference`). Checks between
keys and defaults computed from other values stay as code beside the table's reader, which
passes the computed default to :func:`read_settings`. See docs/development.md#adding-a-line-type-key.

A table whose reader reads its keys one at a time, between checks that decide what comes next
(a study file's tables, a case's ``[campaign]``), declares them in a :class:`SettingTable`
instead of on a dataclass's fields; its reader asks the table for each key.

A field whose case-file key differs from its name gives ``key``: an angle stored in radians
is given in degrees by the file (``phase: float = setting("number", key="phase_deg",
unit="deg", radians=True, ...)``, docs/conventions.md). A description may say ``{table}``
for the name of the table the key is read in (one declaration for the six ``[motion.DOF]``
tables).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from contextlib import AbstractContextManager, nullcontext
from dataclasses import dataclass
from typing import Any, Iterator, Mapping

from floatmoor.case.reader import MISSING, TableReader, generic_path

__all__ = ["Setting", "setting", "settings_of", "read_settings", "SettingTable"]

#: The key of a dataclass field's metadata that holds its :class:`Setting`.
_METADATA_KEY = "floatmoor_setting"
#: The accessor keywords each kind of setting takes (besides ``default``).
_OPTIONS = {
    "number": ("unit", "gt", "ge", "lt", "le", "auto"),
    "integer": ("ge", "le", "auto"),
    "string": ("choices",),
    "boolean": (),
    "vector": ("size", "unit", "gt", "ge"),
    "number_or_vector": ("size", "unit", "gt", "ge"),
    "strings": ("choices",),
    "triples": ("unit",),
    "name": (),
}


@dataclass(frozen=True)
class Setting:
    """What a case file may give for one key, and what it means.

    ``kind`` names the :class:`~floatmoor.case.reader.TableReader` accessor that reads it (a
    :class:`SettingTable` also reads :data:`TABLE_KINDS` and :data:`CLAIMED_KINDS`);
    ``default`` is what a file that leaves the key out gets (:data:`MISSING`: required);
    ``default_text`` words a default the reader computes from other values (``"{default}"``
    in it stands for the recorded one), ``allowed_text`` and ``type_text`` bounds and an
    array's size it computes; ``doc`` is the reference page's description;
    ``scale`` how ``floatmoor scale`` rewrites the value; ``key`` the case-file key of a
    field named otherwise, ``radians`` that the file gives degrees and the field holds radians.
    Kinds ``strings`` and ``triples`` (of ``[first, last, count]``) are arrays the caller
    checks (:meth:`TableReader.claim`), kind ``name``
    the ``name`` of a line, point or floater (:meth:`TableReader.name`).
    """

    kind: str
    doc: str
    unit: str = ""
    gt: float | None = None
    ge: float | None = None
    lt: float | None = None
    le: float | None = None
    choices: tuple[str, ...] | None = None
    size: int | None = None
    auto: str | None = None  #: what "auto" means, for a number that may be "auto"
    default: Any = MISSING
    default_text: str | None = None
    #: the reference page's wording of bounds the reader computes from other values
    allowed_text: str | None = None
    #: the reference page's wording of an array whose size the reader computes
    type_text: str | None = None
    #: quantity kind under a change of scale (floatmoor.similitude.laws.QUANTITY_KINDS:
    #: "length", "force", "same", ...); "" for a table ``floatmoor scale`` maps by hand
    scale: str = ""
    key: str | None = None  #: the case-file key, when not the field's name
    radians: bool = False  #: a ``*_deg`` key read into radians

    def read(self, t: TableReader, key: str, default: Any = MISSING, **computed: Any) -> Any:
        """Read ``key`` of ``t`` as declared (``default``: a computed one, else the
        declared one; ``computed``: bounds or a size computed from other values)."""
        options = {name: getattr(self, name) for name in _OPTIONS[self.kind]
                   if getattr(self, name) is not None}
        wording = self.type_text if "size" in computed else self.allowed_text
        if computed and wording is None:  # the page would print one file's value as the rule
            raise TypeError(f"setting {key!r}: computed {', '.join(computed)} without the "
                            "declaration's wording of them (allowed_text, type_text)")
        options.update(computed)
        default = self.default if default is MISSING else default
        if t.context.recorder is None:
            value = self._access(t, key, default, options)
        else:
            doc = self.doc.replace("{table}", str(t.path[-1])) if t.path else self.doc
            with t.describing(doc, self.default_text, self.allowed_text, self.type_text):
                value = self._access(t, key, default, options)
        if self.radians and value is not None:
            return tuple(math.radians(v) for v in value) if isinstance(value, tuple) \
                else math.radians(value)
        return value

    def _access(self, t: TableReader, key: str, default: Any, options: dict[str, Any]) -> Any:
        if self.kind == "strings":
            return t.claim(key, "array of strings", default=default, **options)
        if self.kind == "triples":
            return t.claim(key, "array of [first, last, count]", default=default, **options)
        if self.kind == "name":
            return t.name()
        return getattr(t, self.kind)(key, default=default, **options)


def setting(kind: str, *, doc: str, field_default: Any = MISSING, **options: Any) -> Any:
    """A dataclass field declared as a case-file :class:`Setting`.

    ``field_default`` is the dataclass's own default (for Python code building the object),
    distinct from ``default``, the value a file that leaves the key out gets.
    """
    spec = Setting(kind, doc, **options)
    if field_default is MISSING:
        return dataclasses.field(metadata={_METADATA_KEY: spec})
    return dataclasses.field(default=field_default, metadata={_METADATA_KEY: spec})


@functools.cache
def _declared(cls: type) -> tuple[tuple[str, str, Setting], ...]:
    """(field name, case-file key, setting) of each declared field, in field order (once per
    class: the readers ask for every entry of a case of thousands of lines)."""
    return tuple((f.name, f.metadata[_METADATA_KEY].key or f.name, f.metadata[_METADATA_KEY])
                 for f in dataclasses.fields(cls) if _METADATA_KEY in f.metadata)


def settings_of(cls: type) -> dict[str, Setting]:
    """The declared settings of a dataclass, by case-file key, in field order."""
    return {key: spec for _, key, spec in _declared(cls)}


def read_settings(cls: type, t: TableReader, defaults: Mapping[str, Any] | None = None,
                  skip: tuple[str, ...] = ()) -> dict[str, Any]:
    """The values of ``cls``'s declared settings read from ``t``, in field order, by field
    name (the keyword arguments of ``cls``).

    ``defaults`` replaces the declared default of some keys (computed ones, or a parent
    table's values); keys in ``skip`` are left to the caller. ``t.finish()`` is the caller's,
    after its checks between keys.
    """
    defaults = defaults or {}
    return {name: spec.read(t, key, defaults.get(key, MISSING))
            for name, key, spec in _declared(cls) if key not in skip}


# -- tables read one key at a time -----------------------------------------------------------

#: The kinds a :class:`SettingTable` reads besides those of :meth:`Setting.read`: a sub-table
#: (default ``{}``: optional) and an array of tables.
TABLE_KINDS = ("table", "tables")
#: Kinds of a raw value the reader checks itself (:meth:`TableReader.claim`); the kind is the
#: reference page's type text.
CLAIMED_KINDS = ("array", "array of strings")


@dataclass(frozen=True)
class SettingTable:
    """The declared keys of one table whose reader reads them one at a time.

    ``path`` is the table's generic key path (``quantities[]``; ``""`` for a file's top
    level), ``settings`` its keys' :class:`Setting` by name (a key of any name, such as a
    swept key path of ``[campaign.grid]``, by a generic name like ``<key>``).
    """

    path: str
    settings: Mapping[str, Setting]

    def read(self, t: TableReader, key: str, *, declared: str | None = None,
             **computed: Any) -> Any:
        """Read ``key`` of ``t`` as declared (under ``declared``, a generic name, if given);
        ``computed`` replaces options the reader computes from other values (choices,
        bounds; the declaration's ``allowed_text`` words them)."""
        spec = self.settings[declared or key]
        if computed:
            spec = dataclasses.replace(spec, **computed)
        if spec.kind in CLAIMED_KINDS:
            with _noted(t, spec):
                return t.claim(key, spec.kind, default=spec.default, name=declared)
        return spec.read(t, key)

    def table(self, t: TableReader, key: str) -> TableReader:
        """The declared sub-table ``key`` of ``t`` (an absent optional one reads as
        empty)."""
        spec = self._kind(key, "table")
        with _noted(t, spec):
            return t.table(key, required=spec.default is MISSING)

    def tables(self, t: TableReader, key: str) -> Iterator[TableReader]:
        """The entries of the declared array of tables ``key`` of ``t``."""
        spec = self._kind(key, "tables")
        entries = t.tables(key)
        with _noted(t, spec):  # the array is checked (and recorded) on the first entry
            first = next(entries)
        yield first
        yield from entries

    def _kind(self, key: str, kind: str) -> Setting:
        spec = self.settings[key]
        if spec.kind != kind:
            raise TypeError(f"{generic_path(self.path, key)} is declared a {spec.kind}, "
                            f"not a {kind}")
        return spec

    def paths(self) -> dict[str, Setting]:
        """The declared settings by generic key path (``quantities[].window``)."""
        return {generic_path(self.path, key): spec for key, spec in self.settings.items()}


def _noted(t: TableReader, spec: Setting) -> AbstractContextManager[None]:
    """Record the keys read inside the block with ``spec``'s description (while recording)."""
    if t.context.recorder is None:
        return nullcontext()
    return t.describing(spec.doc, spec.default_text)
