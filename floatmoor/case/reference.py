"""The input-file reference, generated from what the readers ask for.

The accessors of :class:`~floatmoor.case.reader.TableReader` state each key's type, unit,
bounds, choices and default; :func:`~floatmoor.case.reader.recording` collects them as
:class:`~floatmoor.case.reader.KeyRecord` objects while files are loaded. Here the records of
many files are merged into one :class:`KeyEntry` per generic key path and rendered as
Markdown tables, one per TOML table, with the descriptions declared with the keys
(:mod:`floatmoor.case.setting`) or, for keys not yet declared so, those of
:mod:`floatmoor.case.key_docs`. A key the loaders read is thus on the page with the type and
range the loader checks, and it cannot be there without a description (the tests check both
ways).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Iterable, Mapping, Sequence

from floatmoor.case.key_docs import KeyDocs
from floatmoor.case.reader import MISSING, KeyRecord

__all__ = ["KeyEntry", "merge_records", "render_section", "table_of", "leaf_of", "toml_header"]

#: Kinds of keys that hold tables (each gets its own section).
TABLE_KINDS = ("table", "tables", "named_tables")
#: How a kind is shown in the type column.
_KIND_TEXT = {
    "number": "number", "integer": "integer", "string": "string", "boolean": "boolean",
    "vector": "array of numbers", "number_or_vector": "number or array of numbers",
    "table": "table", "tables": "array of tables", "named_tables": "tables by name",
}


@dataclass(frozen=True)
class KeyEntry:
    """One generic key path, merged over every file and table it was read in."""

    path: str
    kinds: tuple[str, ...]
    units: tuple[str, ...]
    bounds: tuple[str, ...]
    choices: tuple[str, ...]
    sizes: tuple[int, ...]
    defaults: tuple[Any, ...]  #: distinct defaults given (empty: never optional)
    required: bool  #: read without a default somewhere
    always: bool  #: read in every instance of its table that was read
    #: the description declared with the key (floatmoor.case.setting), "" for one of key_docs
    doc: str = ""
    #: the declared wording of a computed default, or None
    default_text: str | None = None
    #: the declared wordings of computed bounds and of an array's type, or None
    allowed_text: str | None = None
    type_text: str | None = None

    @property
    def is_table(self) -> bool:
        """Whether the key holds a table or tables (a section of its own)."""
        return any(kind in TABLE_KINDS for kind in self.kinds)


def table_of(path: str) -> str:
    """The generic path of the table holding ``path`` (``""``: the top level)."""
    return path.rpartition(".")[0]


def leaf_of(path: str) -> str:
    """The key name ``path`` ends with."""
    return path.rpartition(".")[2]


def _unique(values: Iterable[Any]) -> tuple[Any, ...]:
    out: list[Any] = []
    for value in values:
        if value not in out:
            out.append(value)
    return tuple(out)


def _reading_order(records: Sequence[KeyRecord]) -> list[str]:
    """Generic paths in reading order: each file's new keys inserted after the key read
    before them in that file, so optional keys sit beside their neighbours."""
    order: list[str] = []
    previous: dict[str, str | None] = {}
    for record in records:
        source_previous = previous.get(record.source)
        if record.path not in order:
            at = order.index(source_previous) + 1 if source_previous in order else len(order)
            order.insert(at, record.path)
        previous[record.source] = record.path
    return order


def merge_records(records: Sequence[KeyRecord]) -> dict[str, KeyEntry]:
    """One :class:`KeyEntry` per generic path, in reading order."""
    by_path: dict[str, list[KeyRecord]] = {}
    for record in records:
        by_path.setdefault(record.path, []).append(record)
    # the concrete tables read at each generic table path, and where each key was read
    instances: dict[str, set[tuple[str, str]]] = {}
    for record in records:
        instances.setdefault(table_of(record.path), set()).add((record.source, record.table))
    entries = {}
    for path in _reading_order(records):
        group = by_path[path]
        seen_in = {(r.source, r.table) for r in group}
        entries[path] = KeyEntry(
            path=path,
            kinds=_unique(r.kind for r in group),
            units=_unique(r.unit for r in group if r.unit),
            bounds=_unique(r.bounds for r in group if r.bounds),
            choices=_unique(c for r in group for c in r.choices),
            sizes=_unique(r.size for r in group if r.size is not None),
            defaults=_unique(r.default for r in group if r.default is not MISSING),
            required=any(r.default is MISSING for r in group),
            always=seen_in >= instances[table_of(path)],
            doc=next((r.doc for r in group if r.doc), ""),
            default_text=next((r.default_text for r in group if r.default_text is not None),
                              None),
            allowed_text=next((r.allowed_text for r in group if r.allowed_text is not None),
                              None),
            type_text=next((r.type_text for r in group if r.type_text is not None), None))
    return entries


def toml_header(table: str, entries: Mapping[str, KeyEntry]) -> str:
    """The TOML header of a generic table path: ``lines[].dynamic`` -> ``[lines.dynamic]``,
    ``lines[]`` -> ``[[lines]]``, ``line_types.<name>`` -> ``[line_types.NAME]``."""
    if not table:
        return "top level"
    text = table.replace("[]", "").replace("<name>", "NAME")
    entry = entries.get(table.removesuffix("[]"))
    if table.endswith("[]") or (entry is not None and "tables" in entry.kinds):
        return f"`[[{text}]]`"
    return f"`[{text}]`"


def _value_text(value: Any) -> str:
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return f"{value:g}" if math.isfinite(value) else str(value)
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(_value_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return "empty" if not value else "a table"
    return str(value)


def _type_text(entry: KeyEntry) -> str:
    kinds = list(entry.kinds)
    if "number_or_vector" in kinds and "number" in kinds:  # one kind of motion takes one
        kinds.remove("number")
    texts = [_KIND_TEXT.get(kind, kind) for kind in kinds]
    if entry.sizes:
        sizes = " or ".join(str(s) for s in sorted(entry.sizes))
        texts = [t.replace("array of numbers", f"array of {sizes} numbers") for t in texts]
    return "; ".join(_unique(texts))


def _need_text(entry: KeyEntry, default_text: str | None) -> str:
    """Required, optional, or the default (``default_text``: a computed one's wording;
    ``"{default}"`` in it stands for the recorded default)."""
    if default_text is not None:
        return default_text.replace("{default}", _need_text(entry, None))
    if entry.is_table and not entry.always:  # read only when given
        return "optional"
    if entry.required and entry.always and not entry.defaults:
        return "required"
    if entry.required and not entry.defaults:
        return "required where it applies"
    if entry.is_table:
        return "optional"
    if len(entry.defaults) == 1:
        default = entry.defaults[0]
        return "optional" if default is None or default == {} else f"default {_value_text(default)}"
    return "optional (default: see description)"


def _allowed_text(entry: KeyEntry) -> str:
    parts = list(entry.bounds)
    if entry.choices:
        choices = ", ".join(f'"{c}"' for c in entry.choices)
        parts.append(("or " if "integer" in entry.kinds else "one of ") + choices
                     if entry.choices != ("auto",) else 'or "auto"')
    return "; ".join(parts)


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def render_section(table: str, entries: Mapping[str, KeyEntry], docs: KeyDocs,
                   title: str | None = None) -> str:
    """The Markdown section of one table: its TOML header (or ``title``), its description
    and one row per key."""
    descriptions = docs.descriptions
    rows = [entry for path, entry in entries.items() if table_of(path) == table]
    lines = [f"### {title or toml_header(table, entries)}", ""]
    key = table.removesuffix("[]").removesuffix(".<name>")
    intro = descriptions.get(key) or (entries[key].doc if key in entries else "")
    if intro:  # the table's own description: key_docs', or its declaration's
        lines += [intro, ""]
    lines += ["| key | type | unit | required / default | allowed | description |",
              "| --- | --- | --- | --- | --- | --- |"]
    for entry in rows:
        lines.append("| " + " | ".join(_cell(text) for text in (
            f"`{leaf_of(entry.path)}`",
            docs.types.get(entry.path, entry.type_text or _type_text(entry)),
            ", ".join(entry.units),
            _need_text(entry, docs.defaults.get(entry.path, entry.default_text)),
            docs.allowed.get(entry.path, entry.allowed_text or _allowed_text(entry)),
            entry.doc or descriptions.get(entry.path, ""))) + " |")
    return "\n".join(lines) + "\n"
