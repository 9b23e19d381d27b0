"""Command-line overrides: ``--set path.to.key=VALUE`` with VALUE written as a TOML value.

Entries of arrays of named tables (``[[lines]]``) are addressed by their ``name``, or all at
once by ``*``: ``--set lines.chain.length=34.0`` sets one line, ``--set
'lines.*.model="quasi-static"'`` every line. A digit segment there is an error listing the
names: line names often hold digits (``line1``), so ``lines.1`` would read as a name but
address the second entry. Arrays whose entries have no name (a semisubmersible's
``columns``, a vector such as ``anchor``) are addressed by index, which is then the only
handle and cannot be mistaken for a name. Missing intermediate tables are created, so an
optional sub-table can be set from the command line. The values are validated afterwards
exactly like the file's.
"""

from __future__ import annotations

import tomllib
from typing import Any

from floatmoor.case.reader import Path
from floatmoor.errors import CaseError

__all__ = ["parse_override", "apply_overrides", "resolve_key", "WILDCARD"]

#: The segment addressing every entry of an array of tables.
WILDCARD = "*"
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
    except (tomllib.TOMLDecodeError, RecursionError):  # a value nested past the parser's reach
        raise CaseError(where, ".".join(segments), _VALUE_HELP, f"'{value_text.strip()}'") from None
    return segments, value


def apply_overrides(raw: dict[str, Any], overrides: list[str] | tuple[str, ...],
                    source: str) -> list[tuple[str, list[Path]]]:
    """Apply overrides to the raw case table, in place.

    The values are set as given, not checked: the case reader validates them afterwards as
    it does the file's (:func:`floatmoor.case.parse_case` calls this first).

    Parameters
    ----------
    raw
        The case file's table as parsed from TOML; modified in place.
    overrides
        ``path.to.key=VALUE`` assignments, VALUE a TOML value, applied in order (a later
        one wins); an array of named tables is addressed by name or by ``*``
        (:mod:`floatmoor.case.overrides`).
    source
        The case file, named in errors.

    Returns
    -------
    list of (str, list of tuple)
        Per override, in order: its text and the canonical key paths it set (list entries by
        index; a wildcard override sets one path per entry), so that validation errors can
        say a value came from the command line and titles which overrides they show.

    Raises
    ------
    CaseError
        For an override that is not ``path.to.key=VALUE`` with a TOML value, or whose key
        path cannot be set (through a value that is not a table, to an entry that is not
        there, ``*`` outside an array of tables); the message names the source, the
        ``--set`` and the key. Overrides before the failing one are already applied.
    """
    return [(text, _assign(raw, *parse_override(text, source), f"{source} (--set {text})"))
            for text in overrides]


def _assign(node: Any, segments: list[str], value: Any, where: str,
            path: tuple[str | int, ...] = (), typed: tuple[str, ...] = ()) -> list[Path]:
    """Set ``segments`` below ``node`` (at canonical ``path``, ``typed`` as the user wrote
    it) to ``value``; the canonical paths set."""
    segment, rest = segments[0], segments[1:]
    if isinstance(node, list):
        indices = _entry_indices(node, segment, where, typed)
        out: list[Path] = []
        for index in indices:
            if not rest:
                node[index] = value
                out.append(path + (index,))
            else:
                out.extend(_assign(node[index], rest, value, where, path + (index,),
                                   typed + (segment,)))
        return out
    if not isinstance(node, dict):
        raise CaseError(where, _dotted(typed), "a table to set a key in",
                        f"a value of type {type(node).__name__}")
    if segment == WILDCARD:
        raise CaseError(where, _dotted(typed + (segment,)), f"'{WILDCARD}' only after an array "
                        "of tables such as lines (it addresses every entry)",
                        f"'{WILDCARD}' in a table")
    if not rest:
        node[segment] = value
        return [path + (segment,)]
    return _assign(node.setdefault(segment, {}), rest, value, where, path + (segment,),
                   typed + (segment,))


def resolve_key(raw: dict[str, Any], segments: list[str], where: str) -> tuple[Path, Any]:
    """The canonical path and value of one dotted key in the raw case table (no wildcard).

    Raises
    ------
    CaseError
        When the key path names nothing in the table.
    """
    node: Any = raw
    path: tuple[str | int, ...] = ()
    for i, segment in enumerate(segments):
        typed = tuple(segments[:i + 1])
        if isinstance(node, list):
            if segment == WILDCARD:
                raise CaseError(where, _dotted(typed), "a key path naming one "
                                f"value (no '{WILDCARD}')", f"'{'.'.join(segments)}'")
            (index,) = _entry_indices(node, segment, where, typed[:-1])
            path, node = path + (index,), node[index]
        elif isinstance(node, dict) and segment in node:
            path, node = path + (segment,), node[segment]
        else:
            found = ", ".join(sorted(node)) if isinstance(node, dict) else \
                f"a value of type {type(node).__name__}"
            raise CaseError(where, _dotted(typed),
                            "a key the case file gives",
                            f"no key '{segment}' there (keys: {found})"
                            if isinstance(node, dict) else found)
    return path, node


def _entry_indices(entries: list[Any], segment: str, where: str,
                   typed: tuple[str, ...]) -> list[int]:
    """The entries ``segment`` (after ``typed``) addresses: a name, ``*`` or, in an array
    without names, an index."""
    names = [e.get("name") for e in entries if isinstance(e, dict) and "name" in e]
    if segment == WILDCARD:
        if not entries:
            raise CaseError(where, _dotted(typed + (segment,)), "an array with entries for "
                            f"'{WILDCARD}' to address", "an empty array")
        return list(range(len(entries)))
    for index, entry in enumerate(entries):
        if isinstance(entry, dict) and entry.get("name") == segment:
            return [index]
    key = _dotted(typed + (segment,))
    if names:
        listed = ", ".join(str(n) for n in names)
        hint = (f" (entries are addressed by name, not by index: '{segment}' is not one of "
                "the names)" if segment.isdigit() else "")
        raise CaseError(where, key, f"the name of an entry ({listed}) or '{WILDCARD}' for "
                        f"every entry{hint}", f"'{segment}'")
    if segment.isdigit() and int(segment) < len(entries):
        return [int(segment)]
    raise CaseError(where, key, f"an index 0..{len(entries) - 1} or '{WILDCARD}' (these "
                    "entries have no names)", f"'{segment}'")


def _dotted(path: Path) -> str:
    return ".".join(map(str, path))
