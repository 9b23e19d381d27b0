"""A case's title filled from its final values, and the overrides it does not show appended.

The title of a case file is the author's text. It may name key paths in placeholders, with an
optional Python format spec: ``"r = {motion.radius:.2f} m, T = {motion.period:.2f} s"`` reads
``r = 0.20 m, T = 1.25 s``, and after ``--set motion.period=3.5`` ``... T = 3.50 s``. Every
override whose keys no placeholder shows is appended in brackets, ``... [lines.*.model=dynamic]``,
so no run reads like another. ``{{`` and ``}}`` write literal braces.

A placeholder must name a value the case file itself gives (so a misspelt key is an error
whatever the overrides); where an override replaced its table (``--set 'motion={kind =
"harmonic", ...}'``) it reads :data:`REMOVED`, and that override is appended.
"""

from __future__ import annotations

import re
import string
from typing import Any, Sequence

from floatmoor.case.naming import override_label, value_text
from floatmoor.case.overrides import resolve_key
from floatmoor.case.reader import Path
from floatmoor.errors import CaseError

__all__ = ["render_title", "literal_title", "REMOVED", "MAX_SPEC_FIELD", "MAX_TITLE_CHARS"]

#: What a placeholder reads when an override removed its key.
REMOVED = "n/a"
#: Largest width and precision of a placeholder's format spec: a number needs at most ~25
#: digits to be told apart (17 significant digits and an exponent); 64 leaves room for
#: alignment, while ``{motion.radius:300000000.2f}`` would be a 300 MB title.
MAX_SPEC_FIELD = 64
#: Longest title once filled [characters] (before the overrides are appended): the shipped
#: titles take about 90; a title is a line of a summary, a plot and a result file's
#: attributes, whose header a longer text would bloat.
MAX_TITLE_CHARS = 1000
#: A standard format spec: [[fill]align][sign][z][#][0][width][grouping][.precision][type].
_SPEC = re.compile(r"(?:.?[<>=^])?[-+ ]?z?#?0?(?P<width>\d*)[,_]?(?:\.(?P<precision>\d*))?"
                   r"[a-zA-Z%]?", re.DOTALL)

_EXPECTED = ("a title whose {...} placeholders each name one key path of the case, such as "
             "{motion.period} or {motion.period:.2f} ({{ and }} write braces)")


def literal_title(text: str) -> str:
    """``text`` as a title template that reads as ``text`` itself: its braces doubled, so
    none is taken for a placeholder (an importer's title quoting a file name or deck title)."""
    return text.replace("{", "{{").replace("}", "}}")


def render_title(template: str, original: dict[str, Any], raw: dict[str, Any],
                 applied: Sequence[tuple[str, list[Path]]], source: str) -> str:
    """Fill the placeholders of ``template`` from ``raw`` and append the unshown overrides.

    Parameters
    ----------
    template
        The title as the case file gives it.
    original
        The case table as the file gives it (what placeholders may name).
    raw
        The case table after the overrides (what placeholders show).
    applied
        Per override: its text and the key paths it set (:func:`apply_overrides`).
    source
        The case file, named in errors.

    Raises
    ------
    CaseError
        At ``title`` for a malformed placeholder, one naming no value of the case, or a format
        spec that does not fit the value.
    """
    try:
        pieces = list(string.Formatter().parse(template))
    except ValueError as err:
        raise CaseError(source, "title", _EXPECTED, f'"{template}" ({err})') from None
    out: list[str] = []
    length = 0
    shown: set[Path] = {("title",)}  # an override of the title is the title
    for literal, field, spec, conversion in pieces:
        out.append(literal)
        length += len(literal)
        if length > MAX_TITLE_CHARS:
            break
        if field is None:
            continue
        if not field or conversion is not None or "{" in (spec or ""):
            raise CaseError(source, "title", _EXPECTED, f'the placeholder "{{{field}}}" in '
                            f'"{template}"')
        _lookup(original, field, source)
        try:
            path, value = _lookup(raw, field, source)
        except CaseError:
            out.append(REMOVED)
            continue
        shown.add(path)
        out.append(_format(value, spec or "", field, source))
        length += len(out[-1])
        if length > MAX_TITLE_CHARS:
            break
    if length > MAX_TITLE_CHARS:  # stopped at the first piece past the bound
        raise CaseError(source, "title", f"a title of at most {MAX_TITLE_CHARS} characters once "
                        "its placeholders are filled (floatmoor.case.title.MAX_TITLE_CHARS)",
                        f"more than {MAX_TITLE_CHARS} characters")
    title = "".join(out)
    unshown = [override_label(text) for text, paths in applied
               if not paths or not set(paths) <= shown]
    return f"{title} [{', '.join(unshown)}]" if unshown else title


def _lookup(raw: dict[str, Any], field: str, source: str) -> tuple[Path, Any]:
    segments = [s.strip() for s in field.split(".")]
    try:
        path, value = resolve_key(raw, segments, source)
    except CaseError as err:
        raise CaseError(source, "title", _EXPECTED, f'the placeholder "{{{field}}}" ({err.key}: '
                        f"expected {err.expected}, found {err.found})") from None
    if isinstance(value, dict):
        raise CaseError(source, "title", _EXPECTED + " (a value, not a table)",
                        f'the placeholder "{{{field}}}", a table')
    return path, value


def _check_spec(spec: str, field: str, source: str) -> None:
    """Refuse a format spec whose width or precision exceeds :data:`MAX_SPEC_FIELD` (checked
    before formatting: the width alone sizes the output)."""
    match = _SPEC.fullmatch(spec)
    if match is None:
        raise CaseError(source, "title", "a Python format spec ([[fill]align][sign][#][0]"
                        "[width][,][.precision][type])", f'"{{{field}:{spec}}}"')
    for name in ("width", "precision"):
        digits = match.group(name) or ""
        if digits and (len(digits) > 3 or int(digits) > MAX_SPEC_FIELD):
            raise CaseError(source, "title", f"a format spec of {name} at most "
                            f"{MAX_SPEC_FIELD} (floatmoor.case.title.MAX_SPEC_FIELD)",
                            f'"{{{field}:{spec}}}"')


def _format(value: Any, spec: str, field: str, source: str) -> str:
    if spec:
        _check_spec(spec, field, source)
    if not spec:
        return value_text(value)
    if isinstance(value, bool):
        return value_text(value)
    try:
        if isinstance(value, list):  # a key an override may turn into an array (per-axis)
            return "[" + ", ".join(format(v, spec) for v in value) + "]"
        return format(value, spec)
    except (ValueError, TypeError) as err:
        raise CaseError(source, "title", f"a format spec that fits {{{field}}} = "
                        f"{value_text(value)}", f'"{{{field}:{spec}}}" ({err})') from None
