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
"""

from __future__ import annotations

import dataclasses
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
}


@dataclass(frozen=True)
class Setting:
    """What a case file may give for one key, and what it means.

    ``kind`` names the :class:`~floatmoor.case.reader.TableReader` accessor that reads it (a
    :class:`SettingTable` also reads :data:`TABLE_KINDS` and :data:`CLAIMED_KINDS`);
    ``default`` is what a file that leaves the key out gets (:data:`MISSING`: required);
    ``default_text`` words a default the reader computes from other values (``"{default}"``
    in it stands for the recorded one); ``doc`` is the reference page's description;
    ``scale`` how ``floatmoor scale`` rewrites the value.
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
    #: the wording of a range or of choices the reader computes from other values, for the
    #: reference page (a :class:`SettingTable` key read with computed options)
    allowed_text: str | None = None
    #: quantity kind under a change of scale (floatmoor.similitude.laws.QUANTITY_KINDS:
    #: "length", "force", "same", ...); "" for a table ``floatmoor scale`` maps by hand
    scale: str = ""

    def read(self, t: TableReader, key: str, default: Any = MISSING) -> Any:
        """Read ``key`` of ``t`` as declared (``default``: a computed one, else the
        declared one)."""
        options = {name: getattr(self, name) for name in _OPTIONS[self.kind]
                   if getattr(self, name) is not None}
        default = self.default if default is MISSING else default
        accessor = getattr(t, self.kind)
        if t.context.recorder is None:
            return accessor(key, default=default, **options)
        with t.describing(self.doc, self.default_text):
            return accessor(key, default=default, **options)


def setting(kind: str, *, doc: str, field_default: Any = MISSING, **options: Any) -> Any:
    """A dataclass field declared as a case-file :class:`Setting`.

    ``field_default`` is the dataclass's own default (for Python code building the object),
    distinct from ``default``, the value a file that leaves the key out gets.
    """
    spec = Setting(kind, doc, **options)
    if field_default is MISSING:
        return dataclasses.field(metadata={_METADATA_KEY: spec})
    return dataclasses.field(default=field_default, metadata={_METADATA_KEY: spec})


def settings_of(cls: type) -> dict[str, Setting]:
    """The declared settings of a dataclass, by key, in field order."""
    return {f.name: f.metadata[_METADATA_KEY] for f in dataclasses.fields(cls)
            if _METADATA_KEY in f.metadata}


def read_settings(cls: type, t: TableReader, defaults: Mapping[str, Any] | None = None,
                  skip: tuple[str, ...] = ()) -> dict[str, Any]:
    """The values of ``cls``'s declared settings read from ``t``, in field order.

    ``defaults`` replaces the declared default of some keys (computed ones, or a parent
    table's values); keys in ``skip`` are left to the caller. ``t.finish()`` is the caller's,
    after its checks between keys.
    """
    defaults = defaults or {}
    return {key: spec.read(t, key, defaults.get(key, MISSING))
            for key, spec in settings_of(cls).items() if key not in skip}


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
