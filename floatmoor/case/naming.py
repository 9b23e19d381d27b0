"""How a run's overrides are written in titles, report labels and file names.

One rule for every place a run is named, so that a run with overrides never reads like (or
overwrites) the run without them: ``key=value`` per override, the key path as typed, strings
without quotes. File names join these with ``_`` and keep only file-system-safe characters:
``motion.period=3.5_motion.radius=0.15`` (the campaign's ``--runs-dir`` files and ``floatmoor
run``'s default output name).
"""

from __future__ import annotations

import hashlib
import re
from typing import Any, Sequence

from floatmoor.case.overrides import WILDCARD, parse_override
from floatmoor.errors import CaseError

__all__ = ["toml_text", "value_text", "override_label", "override_items", "file_stem",
           "MAX_NAME_LENGTH", "MAX_VALUE_LENGTH"]

#: Longest file-name stem made from overrides [characters]; longer ones keep their start and
#: end with a hash of the whole (255 bytes is the usual file-name limit, and the case name
#: and suffix come on top).
MAX_NAME_LENGTH = 120
#: Longest value in a file name [characters]; a longer one (an array, a long string) keeps
#: its start and a hash of the whole.
MAX_VALUE_LENGTH = 32
#: Characters hashed values keep before their hash.
_KEPT = 16
#: Characters kept in file names; the others are dropped (quotes, brackets, spaces) or, for
#: path separators and the like, replaced by '-'.
_UNSAFE = re.compile(r"[^A-Za-z0-9._+,=-]")
_DROPPED = re.compile(r"[\s\[\]{}\"']")
#: How the wildcard segment reads in a file name ('*' is a shell pattern).
_WILDCARD_IN_NAMES = "all"


def toml_text(value: Any) -> str:
    """``value`` written as a TOML value (what ``--set key=...`` takes)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(toml_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {toml_text(v)}" for k, v in value.items()) + "}"
    return repr(value) if isinstance(value, float) else str(value)


def value_text(value: Any) -> str:
    """``value`` as a title or label shows it: strings without quotes, others as TOML."""
    return value if isinstance(value, str) else toml_text(value)


def override_items(overrides: Sequence[str]) -> list[tuple[str, Any]]:
    """``key=VALUE`` overrides as (dotted key as typed, parsed value) pairs.

    Raises
    ------
    CaseError
        For an override that does not parse.
    """
    items = []
    for text in overrides:
        segments, value = parse_override(text, "--set")
        items.append((".".join(segments), value))
    return items


def override_label(text: str) -> str:
    """An override as titles and report labels show it: ``lines.*.model=quasi-static``
    (an override that does not parse is shown as typed)."""
    try:
        ((key, value),) = override_items([text])
    except CaseError:
        return text.strip()
    return f"{key}={value_text(value)}"


def file_stem(items: Sequence[tuple[str, Any]]) -> str:
    """A file-name stem naming (key, value) pairs: ``motion.period=3.5_motion.radius=0.15``.

    Only ``A-Z a-z 0-9 . _ + , = -`` are kept: quotes, brackets and spaces are dropped,
    ``*`` reads ``all`` and other characters become '-'. A value longer than
    :data:`MAX_VALUE_LENGTH` and a stem longer than :data:`MAX_NAME_LENGTH` are shortened
    deterministically, keeping their start and an 8-digit hash of the whole.
    """
    parts = []
    for key, value in items:
        segments = [_WILDCARD_IN_NAMES if s == WILDCARD else s for s in key.split(".")]
        text = _UNSAFE.sub("-", _DROPPED.sub("", value_text(value)))
        if len(text) > MAX_VALUE_LENGTH:
            text = f"{text[:_KEPT]}-{_hash(value_text(value))}"
        parts.append(f"{_UNSAFE.sub('-', '.'.join(segments))}={text}")
    stem = "_".join(parts)
    if len(stem) > MAX_NAME_LENGTH:
        stem = f"{stem[:MAX_NAME_LENGTH - 9]}-{_hash(stem)}"
    return stem


def _hash(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:8]
