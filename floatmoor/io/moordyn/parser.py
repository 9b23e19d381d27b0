"""A strict reader of MoorDyn v2 input files (and of v1's section names where their columns are
v2's, plus v1's nine-column LINE DICTIONARY).

Why our own and not MoorPy's ``System.load``: MoorPy (a test-only dependency) matches section
names and point attachments by substring, skips a fixed number of header lines, replaces an
unreadable EA by 1e9 N with a printed note, converts the line types at once into its own
(weight-in-water) description, and reports no file line numbers; a case file built from it
could not say where a value came from, nor refuse a malformed deck. This reader keeps every row
with its line number and raises :class:`floatmoor.errors.CaseError` naming the file and line,
what was expected and what was found.

Layout read (MoorDyn-C 2.7): a title (lines starting with ``#`` before the first section are
comments, not title), then sections opened by a line of dashes naming them.
Tables (LINE TYPES, POINTS, LINES, and the kept-as-text ROD TYPES, BODIES, RODS) have a row of
column names and a row of units in parentheses, then one row per item; OPTIONS rows are
``value key [description]``; OUTPUTS rows are channel names. A line of dashes naming no section
(MoorDyn's "need this line", "END") closes the file.

Refused outright, with the line number: a control character (other than tab) on any line, title
and comments included. A text deck has none; one means a damaged or binary file, and written
into a case file it would make invalid TOML (in a name) or an invisible part of a title shown in
reports. Integers (IDs, NumSegs, AttachA/B, BodyN) are MoorDyn's C ``int``: at most
:data:`MAX_DECK_INTEGER`, checked on the text before it is converted.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from floatmoor.case.files import CaseFileKindError, read_case_text
from floatmoor.errors import CaseError
from floatmoor.io.moordyn.deck import (POINT_BODY, POINT_COUPLED, POINT_FIXED, POINT_FREE, Deck,
                                       DeckLine, DeckLineType, DeckOption, DeckPoint, DeckSection)
from floatmoor.terminal_text import shown

__all__ = ["parse_deck", "read_deck", "SECTION_NAMES", "MODELLED_SECTIONS", "MAX_DECK_INTEGER"]

#: Largest integer a deck may give (IDs, NumSegs, point numbers, BodyN): MoorDyn-C reads them
#: into a C ``int`` (32 bits), so a larger one is no MoorDyn deck. Checked by the number of
#: digits first: Python refuses to convert integers of more than 4300 digits.
MAX_DECK_INTEGER = 2**31 - 1
#: Longest quoted deck text in an error message [characters].
_QUOTED = 40
#: Control characters (Unicode category Cc) other than tab: no text deck holds them.
_CONTROL = re.compile(r"[\x00-\x08\x0a-\x1f\x7f-\x9f]")

#: Normalised section name -> the headings MoorDyn accepts for it (v2 first, then v1's).
SECTION_NAMES: dict[str, tuple[str, ...]] = {
    "LINE TYPES": ("LINE TYPES", "LINE DICTIONARY"),
    "ROD TYPES": ("ROD TYPES", "ROD DICTIONARY"),
    "BODIES": ("BODIES", "BODY LIST", "BODY PROPERTIES"),
    "RODS": ("RODS", "ROD LIST", "ROD PROPERTIES"),
    "POINTS": ("POINTS", "POINT LIST", "POINT PROPERTIES", "CONNECTION PROPERTIES",
               "NODE PROPERTIES", "CONNECTIONS"),
    "LINES": ("LINES", "LINE LIST", "LINE PROPERTIES"),
    "FAILURE": ("FAILURE",),
    "CONTROL": ("CONTROL",),
    "EXTERNAL LOADS": ("EXTERNAL LOADS",),
    "OPTIONS": ("OPTIONS",),
    "OUTPUTS": ("OUTPUTS", "OUTPUT"),
    "SYROPE IC": ("SYROPE IC",),
}
#: Sections floatmoor maps; the others are kept as text and listed by the importer.
MODELLED_SECTIONS = ("LINE TYPES", "POINTS", "LINES", "OPTIONS", "OUTPUTS")
#: Sections that are tables with a names row and a units row.
_TABLES = ("LINE TYPES", "ROD TYPES", "BODIES", "RODS", "POINTS", "LINES")
#: Point attachments (MoorDyn-C 2.7's spellings, upper case) -> deck.POINT_*.
ATTACHMENTS = {"FIXED": POINT_FIXED, "FIX": POINT_FIXED, "ANCHOR": POINT_FIXED,
               "VESSEL": POINT_COUPLED, "VES": POINT_COUPLED, "COUPLED": POINT_COUPLED,
               "CPLD": POINT_COUPLED, "FREE": POINT_FREE, "CONNECT": POINT_FREE,
               "CON": POINT_FREE}
_BODY = re.compile(r"^BODY(\d+)$")
#: A header flag row before the first section, such as MoorDyn v1's ``FALSE Echo - echo the
#: input file data (flag)``: a value, a key, nothing else or a description after a dash.
#: MoorDyn-C skips it; it is not part of the title.
_HEADER_OPTION = re.compile(r"^(TRUE|FALSE|T|F|[+-]?\d+\.?\d*)\s+([A-Za-z_]\w*)(\s+-.*)?$",
                            re.IGNORECASE)
_LINE_TYPE_COLUMNS = ("TypeName", "Diam", "Mass/m", "EA", "BA/-zeta", "EI", "Cd", "Ca", "CdAx",
                      "CaAx")
_V1_LINE_TYPE_COLUMNS = ("Name", "Diam", "MassDen", "EA", "BA/-zeta", "Can", "Cat", "Cdn",
                         "Cdt")
_POINT_COLUMNS = ("ID", "Attachment", "X", "Y", "Z", "Mass", "Volume", "CdA", "Ca")
_LINE_COLUMNS = ("ID", "LineType", "AttachA", "AttachB", "UnstrLen", "NumSegs", "Outputs")


def read_deck(path: str | Path) -> Deck:
    """Read and parse the MoorDyn input file at ``path``.

    Parameters
    ----------
    path
        The input file (deck).

    Returns
    -------
    Deck
        Its parsed contents.

    Raises
    ------
    CaseError
        The file cannot be read, or is malformed (naming the file and line).
    """
    try:
        text = read_case_text(Path(path))
    except CaseFileKindError as err:
        raise CaseError(shown(str(path)), "", "a MoorDyn input file (a regular text file)",
                        str(err)) from None
    except UnicodeDecodeError:
        raise CaseError(shown(str(path)), "", "a MoorDyn input file (UTF-8 text)",
                        "bytes that are not UTF-8") from None
    except OSError as err:
        raise CaseError(shown(str(path)), "", "a readable MoorDyn input file",
                        err.strerror or str(err)) from None
    return parse_deck(text, shown(str(path)))  # a message naming it stays one line


def _section_of(line: str) -> str | None:
    """The normalised section a dashed heading opens, or None (a closing line)."""
    name = " ".join(line.replace("-", " ").upper().split())
    for section, headings in SECTION_NAMES.items():
        for heading in headings:
            if re.search(rf"(^|\s){re.escape(heading)}(\s|$)", name):
                return section
    return None


class _Rows:
    """Rows of one section, with the file name for errors."""

    def __init__(self, source: str, section: str) -> None:
        self.source = source
        self.section = section

    def error(self, number: int, column: str, expected: str, found: str) -> CaseError:
        key = f"{self.section}, column {column}" if column else self.section
        return CaseError(f"{self.source}:{number}", key, expected, found)

    def number(self, number: int, column: str, text: str, unit: str) -> float:
        try:
            value = float(text)
        except ValueError:
            value = math.nan
            if not re.fullmatch(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?", text):
                raise self.error(number, column, f"a number [{unit}]",
                                 _q(text)) from None
        if not math.isfinite(value):
            raise self.error(number, column, f"a finite number [{unit}]",
                             _q(text))
        return value

    def integer(self, number: int, column: str, text: str, minimum: int) -> int:
        value = deck_integer(text)
        if value is None or value < minimum:
            raise self.error(number, column, f"an integer from {minimum} to "
                             f"{MAX_DECK_INTEGER} (MoorDyn's int)", _q(text))
        return value


def _q(text: str) -> str:
    """Deck text quoted in an error message: terminal-safe and bounded (one line)."""
    return f"'{shown(text, _QUOTED)}'"


def deck_integer(text: str) -> int | None:
    """The integer ``text`` writes, or None when it is none or beyond :data:`MAX_DECK_INTEGER`
    (decided on the digits, before any conversion)."""
    if not re.fullmatch(r"[+-]?\d+", text):
        return None
    digits = text.lstrip("+-").lstrip("0")
    if len(digits) > len(str(MAX_DECK_INTEGER)):
        return None
    value = int(text)
    return value if abs(value) <= MAX_DECK_INTEGER else None


def parse_deck(text: str, source: str = "<deck>") -> Deck:
    """Parse the text of a MoorDyn input file (see the module docstring).

    Parameters
    ----------
    text
        The file's text.
    source
        Where the text came from, for messages.

    Returns
    -------
    Deck
        Its parsed contents.

    Raises
    ------
    CaseError
        Naming ``source`` and the line number, what was expected and what was found.
    """
    lines = text.splitlines()
    for n, raw in enumerate(lines, start=1):
        bad = _CONTROL.search(raw)
        if bad:
            raise CaseError(f"{source}:{n}", "", "text without control characters (a MoorDyn "
                            "input file; tabs are fine)", f"{shown(bad.group())} in "
                            f"{_q(raw.strip())}")
    title: list[str] = []
    blocks: list[tuple[str, str, int, list[tuple[int, str]]]] = []  # section, heading, n, rows
    closed_at = 0
    header_options: list[DeckOption] = []
    outputs_end = 0  # line of OUTPUTS' END row: MoorDyn's end of the channel list
    for n, raw in enumerate(lines, start=1):
        stripped = raw.strip()
        if "---" in stripped:
            section = _section_of(stripped)
            if section is None:
                upper = stripped.upper()  # "MoorDyn Input File", "MoorDyn FAST.Farm Input File"
                if "MOORDYN" in upper and "INPUT FILE" in upper and not blocks and not title:
                    continue
                if not blocks:
                    raise CaseError(f"{source}:{n}", "", "a section heading (a line of dashes "
                                    "naming LINE TYPES, POINTS, LINES, OPTIONS, ...)",
                                    _q(stripped))
                closed_at = n
                break
            if any(b[0] == section for b in blocks):
                raise CaseError(f"{source}:{n}", section, "each section once",
                                f"a second {section} heading")
            blocks.append((section, stripped, n, []))
        elif not blocks:
            match = _HEADER_OPTION.match(stripped)
            if title and match:  # a header flag (Echo) after the title line, not more title
                header_options.append(DeckOption(key=match.group(2), value=match.group(1),
                                                 line_number=n))
            elif stripped and not stripped.startswith("#"):  # "#" lines: comments (the
                title.append(stripped)                       # export's notes); MoorDyn reads none
        elif stripped and blocks[-1][0] == "OUTPUTS" and stripped.split()[0].upper() == "END":
            outputs_end = n
        elif stripped and outputs_end and blocks[-1][0] == "OUTPUTS":
            raise CaseError(f"{source}:{n}", "OUTPUTS", f"nothing after END (line {outputs_end}) "
                            "but the closing line of dashes", repr(stripped))
        elif stripped:
            blocks[-1][3].append((n, stripped))
    if closed_at:
        for n in range(closed_at + 1, len(lines) + 1):
            if lines[n - 1].strip():
                raise CaseError(f"{source}:{n}", "", "nothing after the closing line of dashes "
                                f"(line {closed_at})", _q(lines[n - 1].strip()))
    if not blocks:
        raise CaseError(source, "", "a MoorDyn input file (sections opened by lines of dashes)",
                        "no section heading")

    line_types: list[DeckLineType] = []
    points: list[DeckPoint] = []
    deck_lines: list[DeckLine] = []
    options: list[DeckOption] = list(header_options)
    outputs: list[str] = []
    others: list[DeckSection] = []
    bodies: dict[int, tuple[str, ...]] = {}
    for section, heading, n0, rows in blocks:
        reader = _Rows(source, section)
        if section in _TABLES:
            rows = _table_rows(reader, n0, rows)
        if section == "LINE TYPES":
            line_types = [_line_type(reader, n, row, heading) for n, row in rows]
        elif section == "POINTS":
            points = [_point(reader, n, row) for n, row in rows]
        elif section == "LINES":
            deck_lines = [_line(reader, n, row) for n, row in rows]
        elif section == "OPTIONS":
            for n, row in rows:
                fields = row.split()
                if len(fields) < 2:
                    raise reader.error(n, "", "an option row 'value key [description]'",
                                       _q(row))
                options.append(DeckOption(key=fields[1], value=fields[0], line_number=n))
        elif section == "OUTPUTS":
            outputs.extend(token for _, row in rows for token in row.replace(",", " ").split())
        else:
            if section == "BODIES":
                for n, row in rows:
                    fields = row.split()
                    number = reader.integer(n, "ID", fields[0], 1)
                    if len(fields) < 8:
                        raise reader.error(n, "", "a body row 'ID Attachment X0 Y0 Z0 r0 p0 y0 "
                                           "...'", _q(row))
                    bodies[number] = tuple(fields)
            others.append(DeckSection(name=section, heading=heading,
                                      rows=tuple(row for _, row in rows), line_number=n0))
    _check_references(source, line_types, points, deck_lines)
    return Deck(source=source, title=" ".join(title), line_types=tuple(line_types),
                points=tuple(points), lines=tuple(deck_lines), options=tuple(options),
                outputs=tuple(outputs), other_sections=tuple(others), bodies=bodies)


def _table_rows(reader: _Rows, n0: int, rows: list[tuple[int, str]]) -> list[tuple[int, str]]:
    """The item rows of a table, after its names and units rows."""
    if len(rows) < 2:
        raise reader.error(rows[-1][0] if rows else n0, "", "a row of column names and a row of "
                           "units before the items", "the section ends first")
    units_n, units = rows[1]
    if not units.startswith("("):
        raise reader.error(units_n, "", "a row of units in parentheses, such as '(-) (m) "
                           "(kg/m)', after the column names", _q(units))
    return rows[2:]


def _columns(reader: _Rows, n: int, row: str, names: tuple[str, ...]) -> list[str]:
    fields = row.split()
    if len(fields) != len(names):
        raise reader.error(n, "", f"{len(names)} columns ({' '.join(names)})",
                           f"{len(fields)}: {_q(row)}")
    return fields


def _line_type(reader: _Rows, n: int, row: str, heading: str) -> DeckLineType:
    fields = row.split()
    if len(fields) == len(_V1_LINE_TYPE_COLUMNS) and "DICTIONARY" in heading.upper():
        # v1: Name Diam MassDen EA BA/-zeta Can Cat Cdn Cdt
        name, d, m, ea, ba, can, cat, cdn, cdt = fields
        fields = [name, d, m, ea, ba, "0", cdn, can, cdt, cat]
    else:
        fields = _columns(reader, n, row, _LINE_TYPE_COLUMNS)
    col = dict(zip(_LINE_TYPE_COLUMNS, fields))
    units = dict(zip(_LINE_TYPE_COLUMNS, ("", "m", "kg/m", "N", "N s, or -zeta", "N m^2", "-",
                                          "-", "-", "-")))

    def num(column: str, positive: bool = False) -> float:
        text = col[column]
        if column == "EA" and text.upper().startswith("SYROPE"):
            raise reader.error(n, column, "a number [N] (MoorDyn-F's SYROPE synthetic-rope "
                               "model, a load-history-dependent stiffness, is not modelled by "
                               "floatmoor)", repr(text))
        if column == "BA/-zeta" and "|" in text:
            raise reader.error(n, column, "a number [N s, or -zeta] (MoorDyn's viscoelastic "
                               "'BA|BA_D' damping is not modelled by floatmoor)", repr(text))
        if column in ("EA", "BA/-zeta", "EI") and not re.fullmatch(r"[-+0-9.eE]+", text):
            raise reader.error(n, column, f"a number [{units[column]}] (tables of nonlinear "
                               "properties are not supported)", _q(text))
        value = reader.number(n, column, text, units[column])
        if positive and not value > 0.0:
            raise reader.error(n, column, f"a number > 0 [{units[column]}]", _q(text))
        if not positive and column != "BA/-zeta" and value < 0.0:
            raise reader.error(n, column, f"a number >= 0 [{units[column]}]", _q(text))
        return value

    return DeckLineType(name=col["TypeName"], diameter=num("Diam", True),
                        mass_per_length=num("Mass/m", True), axial_stiffness=num("EA", True),
                        internal_damping=num("BA/-zeta"), bending_stiffness=num("EI"),
                        normal_drag_coefficient=num("Cd"), added_mass_coefficient=num("Ca"),
                        tangential_drag_coefficient=num("CdAx"),
                        tangential_added_mass_coefficient=num("CaAx"), line_number=n)


def _point(reader: _Rows, n: int, row: str) -> DeckPoint:
    fields = _columns(reader, n, row, _POINT_COLUMNS)
    number = reader.integer(n, "ID", fields[0], 1)
    text = fields[1]
    upper = text.upper()
    body = 0
    if upper in ATTACHMENTS:
        attachment = ATTACHMENTS[upper]
    elif _BODY.match(upper):
        body = deck_integer(_BODY.match(upper).group(1)) or 0  # type: ignore[union-attr]
        if body < 1:
            raise reader.error(n, "Attachment", f"BodyN with N from 1 to {MAX_DECK_INTEGER}",
                               _q(text))
        attachment = POINT_BODY
    else:
        raise reader.error(n, "Attachment", "Fixed, Vessel (Coupled), Free or BodyN",
                           _q(text))
    x, y, z, mass, volume, cda, ca = (reader.number(n, c, f, u) for c, f, u in zip(
        _POINT_COLUMNS[2:], fields[2:], ("m", "m", "m", "kg", "m^3", "m^2", "-")))
    for column, value in (("Mass", mass), ("Volume", volume), ("CdA", cda), ("Ca", ca)):
        if value < 0.0:
            raise reader.error(n, column, "a number >= 0", repr(value))
    return DeckPoint(number=number, attachment=attachment, position=(x, y, z), mass=mass,
                     volume=volume, drag_area=cda, added_mass_coefficient=ca, body=body,
                     attachment_text=text, line_number=n)


def _line(reader: _Rows, n: int, row: str) -> DeckLine:
    fields = _columns(reader, n, row, _LINE_COLUMNS)
    ends = []
    for column, text in zip(("AttachA", "AttachB"), fields[2:4]):
        number = deck_integer(text) if re.fullmatch(r"\d+", text) else None
        if number is None:
            raise reader.error(n, column, f"a point number up to {MAX_DECK_INTEGER} (lines "
                               "attached to rods or bodies directly cannot be imported)",
                               _q(text))
        ends.append(number)
    length = reader.number(n, "UnstrLen", fields[4], "m")
    if length == 0.0:
        raise reader.error(n, "UnstrLen", "a non-zero number [m]", _q(fields[4]))
    return DeckLine(number=reader.integer(n, "ID", fields[0], 1), line_type=fields[1],
                    start=ends[0], end=ends[1], length=length,
                    segments=reader.integer(n, "NumSegs", fields[5], 1), outputs=fields[6],
                    line_number=n)


def _check_references(source: str, line_types: list[DeckLineType], points: list[DeckPoint],
                      lines: list[DeckLine]) -> None:
    """Unique numbers and names, and lines naming existing types and points."""
    for what, items, key in (("LINE TYPES", line_types, "name"), ("POINTS", points, "number"),
                             ("LINES", lines, "number")):
        seen: dict[object, int] = {}
        for item in items:
            k = getattr(item, key)
            if k in seen:
                raise CaseError(f"{source}:{item.line_number}", what, f"a unique {key}",
                                f"{k!r}, also on line {seen[k]}")
            seen[k] = item.line_number
    type_names = {t.name for t in line_types}
    point_numbers = {p.number for p in points}
    for line in lines:
        if line.line_type not in type_names:
            raise CaseError(f"{source}:{line.line_number}", "LINES, column LineType",
                            "the name of a LINE TYPES row (" + ", ".join(sorted(type_names))
                            + ")", _q(line.line_type))
        for column, number in (("AttachA", line.start), ("AttachB", line.end)):
            if number not in point_numbers:
                raise CaseError(f"{source}:{line.line_number}", f"LINES, column {column}",
                                "the ID of a POINTS row", repr(number))
