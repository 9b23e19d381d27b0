"""Command-line overrides: ``--set path.to.key=VALUE`` with VALUE written as a TOML value.

Entries of arrays of tables (``[[lines]]``) are addressed by their ``name`` or by index:
``--set lines.chain.length=34.0`` and ``--set lines.0.length=34.0`` are the same.
Missing intermediate tables are created, so an optional sub-table can be set from the
command line. The values are validated afterwards exactly like the file's.
"""

from __future__ import annotations

import tomllib
from typing import Any

from floatmoor.case.reader import Path
from floatmoor.errors import CaseError

__all__ = ["parse_override", "apply_overrides"]

_VALUE_HELP = 'a TOML value such as 3.5, "text", true or [0.0, 1.0] (strings need quotes)'


def parse_override(text: str, source: str) -> tuple[list[str], Any]:
    """Split ``path.to.key=VALUE`` into its key segments and parsed TOML value.

    Parameters
    ----------
    text
        The override as typed.
    source
        The case file, named in errors.
    """
    where = f"{source} (--set {text})"
    if "=" not in text:
        raise CaseError(where, "", "an override of the form path.to.key=VALUE", f"'{text}'")
    key, _, value_text = text.partition("=")
    segments = [s.strip() for s in key.strip().split(".")]
    if not key.strip() or any(not s for s in segments):
        raise CaseError(where, key.strip(), "a dotted key path such as motion.period",
                        f"'{key.strip()}'")
    try:
        value = tomllib.loads(f"value = {value_text.strip()}")["value"]
    except tomllib.TOMLDecodeError:
        raise CaseError(where, ".".join(segments), _VALUE_HELP, f"'{value_text.strip()}'") from None
    return segments, value


def apply_overrides(raw: dict[str, Any], overrides: list[str] | tuple[str, ...],
                    source: str) -> dict[Path, str]:
    """Apply overrides to the raw case table, in place.

    Returns
    -------
    dict
        Canonical key path (list entries by index) -> override text, so that validation
        errors can say the value came from the command line.
    """
    applied: dict[Path, str] = {}
    for text in overrides:
        segments, value = parse_override(text, source)
        where = f"{source} (--set {text})"
        node: Any = raw
        path: list[str | int] = []
        for i, segment in enumerate(segments):
            last = i == len(segments) - 1
            if isinstance(node, list):
                index = _entry_index(node, segment)
                if index is None:
                    names = [str(e.get("name")) for e in node if isinstance(e, dict)]
                    raise CaseError(where, ".".join(map(str, path)) or segment,
                                    f"the name or index of an entry ({', '.join(names)} or 0.."
                                    f"{len(node) - 1})", f"'{segment}'")
                path.append(index)
                if last:
                    node[index] = value
                else:
                    node = node[index]
                continue
            if not isinstance(node, dict):
                raise CaseError(where, ".".join(map(str, path)), "a table to set a key in",
                                f"a value of type {type(node).__name__}")
            path.append(segment)
            if last:
                node[segment] = value
            else:
                node = node.setdefault(segment, {})
        applied[tuple(path)] = text
    return applied


def _entry_index(entries: list[Any], segment: str) -> int | None:
    for index, entry in enumerate(entries):
        if isinstance(entry, dict) and entry.get("name") == segment:
            return index
    if segment.isdigit() and int(segment) < len(entries):
        return int(segment)
    return None
