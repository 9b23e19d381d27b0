"""MoorDyn driver inputs: the driver file (``md_driver.inp`` of OpenFAST's MoorDyn driver) and
its motion file (``InputsFile``), read strictly, for ``floatmoor import moordyn DECK --driver``.

The driver file (OpenFAST's ``MoorDyn_Driver``, OpenFAST mode): two title lines, an optional
``Echo`` flag row, then sections opened by lines of dashes: ENVIRONMENTAL CONDITIONS
(``Gravity``, ``rhoW``, ``WtrDpth``), MOORDYN (``MDInputFile``, ``OutRootName``, ``TMax`` [s],
``dtC`` [s], ``InputsMode`` 0 or 1, ``InputsFile``, ``NumTurbines``), Initial Positions (a
names row, a units row, one row ``ref_X ref_Y surge sway heave roll pitch yaw`` [m, rad]),
and a closing ``END`` line. Rows are ``value key [- description]``, strings quoted.

The motion file: header lines (``#`` or column names), then rows ``time`` and either the
absolute positions of the deck's coupled points (three columns each, in the deck's order:
what the driver passes to MoorDyn's coupled points) or the platform's six DOFs (surge, sway,
heave [m], roll, pitch, yaw [rad]). Which one: the column count against the number of
coupled points, and the header's names when both fit (two coupled points: six columns).
Positions are fitted to a rigid-body motion (:mod:`.motion_fit`).

Every error names the file and line (:class:`floatmoor.errors.CaseError`); sizes are bounded
(:data:`MAX_DRIVER_FILE_BYTES`, :data:`MAX_MOTION_FILE_BYTES`, :data:`MAX_MOTION_ROWS`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from floatmoor.errors import CaseError

__all__ = ["DriverInput", "MotionRecord", "read_driver", "parse_driver", "read_motion_file",
           "MAX_DRIVER_FILE_BYTES", "MAX_MOTION_FILE_BYTES", "MAX_MOTION_ROWS"]

#: Largest driver file read [bytes]: OpenFAST's are about 1.6 kB.
MAX_DRIVER_FILE_BYTES = 1 << 16
#: Largest motion file read [bytes]: r-test's largest (md_syrope) is 8.6 MB.
MAX_MOTION_FILE_BYTES = 1 << 26
#: Most data rows of a motion file: 10^6 rows is 10^4 s at 100 Hz.
MAX_MOTION_ROWS = 1_000_000
#: Header lines before a motion file's first row (names, units, comments).
_MAX_HEADER_LINES = 10

#: Driver keys by section (lower case) -> the spelling in messages.
_KEYS = {
    "ENVIRONMENTAL CONDITIONS": ("Gravity", "rhoW", "WtrDpth"),
    "MOORDYN": ("MDInputFile", "OutRootName", "TMax", "dtC", "InputsMode", "InputsFile",
                "NumTurbines"),
}
_SECTIONS = ("ENVIRONMENTAL CONDITIONS", "MOORDYN", "INITIAL POSITIONS")
_ROW = re.compile(r'^("[^"]*"|\S+)\s+(\S+)(\s.*)?$')
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?")
_POSE_COLUMNS = ("ref_X", "ref_Y", "surge_init", "sway_init", "heave_init", "roll_init",
                 "pitch_init", "yaw_init")


@dataclass(frozen=True)
class DriverInput:
    """A parsed MoorDyn driver file (SI units, radians)."""

    source: str
    gravity: float  #: [m/s^2]
    water_density: float  #: [kg/m^3]
    water_depth: float  #: [m]
    deck_file: str  #: MDInputFile, as written
    duration: float  #: TMax [s]
    coupling_interval: float  #: dtC [s]
    inputs_mode: int  #: 0: coupled objects at the initial pose; 1: from inputs_file
    inputs_file: str  #: InputsFile, as written ("" for none)
    reference: tuple[float, float]  #: ref_X, ref_Y [m] (FAST.Farm's turbine position)
    initial_pose: tuple[float, ...]  #: surge, sway, heave [m], roll, pitch, yaw [rad]
    line_numbers: dict[str, int]  #: key -> line number, for messages

    def where(self, key: str) -> str:
        """``file:line`` of a key, for comments and messages."""
        return f"{self.source}:{self.line_numbers[key]}"


@dataclass(frozen=True)
class MotionRecord:
    """A motion file's data rows."""

    source: str
    names: tuple[str, ...]  #: the last header line's column names (without Time), or ()
    time: NDArray[np.float64]  #: (n,) [s]
    values: NDArray[np.float64]  #: (n, columns - 1)
    line_numbers: NDArray[np.int64]  #: (n,) file line of each row


def _read_text(path: str | Path, what: str, limit: int) -> str:
    p = Path(path)
    try:
        if not p.is_file():
            raise CaseError(str(path), "", f"{what} (a regular file)",
                            "no such file" if not p.exists() else "not a regular file")
        with p.open("rb") as stream:
            data = stream.read(limit + 1)
    except OSError as err:
        raise CaseError(str(path), "", f"a readable {what}", err.strerror or str(err)) from None
    if len(data) > limit:
        raise CaseError(str(path), "", f"{what} of at most {limit} bytes",
                        f"more than {limit} bytes")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise CaseError(str(path), "", f"{what} (UTF-8 text)",
                        f"a byte that is not UTF-8 at offset {err.start}") from None


def read_driver(path: str | Path) -> DriverInput:
    """Read and parse the MoorDyn driver file at ``path``.

    Raises
    ------
    CaseError
        The file cannot be read or is malformed (naming the file and line).
    """
    return parse_driver(_read_text(path, "a MoorDyn driver file", MAX_DRIVER_FILE_BYTES),
                        str(path))


def _number(source: str, n: int, key: str, text: str, unit: str) -> float:
    if not _NUMBER.fullmatch(text):
        raise CaseError(f"{source}:{n}", key, f"a number [{unit}]", repr(text))
    value = float(text.replace("d", "e").replace("D", "e"))
    if not math.isfinite(value):
        raise CaseError(f"{source}:{n}", key, f"a finite number [{unit}]", repr(text))
    return value


def parse_driver(text: str, source: str = "<driver>") -> DriverInput:
    """Parse the text of a MoorDyn driver file (see the module docstring).

    Raises
    ------
    CaseError
        Naming ``source`` and the line, what was expected and what was found.
    """
    lines = text.splitlines()
    if len(lines) < 3:
        raise CaseError(source, "", "a MoorDyn driver file (two title lines, then sections)",
                        f"{len(lines)} lines")
    section = ""
    values: dict[str, tuple[int, str]] = {}
    pose_rows: list[tuple[int, str]] = []
    table_rows = 0
    ended = 0
    for n, raw in enumerate(lines[2:], start=3):
        stripped = raw.strip()
        if not stripped:
            continue
        if ended:
            raise CaseError(f"{source}:{n}", "", f"nothing after END (line {ended})",
                            repr(stripped[:60]))
        if "---" in stripped:
            name = " ".join(stripped.replace("-", " ").upper().split())
            found = [s for s in _SECTIONS if s in name]
            if not found:
                raise CaseError(f"{source}:{n}", "", "a section heading naming one of "
                                + ", ".join(_SECTIONS), repr(stripped[:60]))
            section = found[0]
            continue
        if section == "INITIAL POSITIONS":
            if stripped.upper().startswith("END"):
                ended = n
                continue
            table_rows += 1
            if table_rows == 1 and stripped.split()[0].upper() != "REF_X":
                raise CaseError(f"{source}:{n}", "Initial Positions",
                                "a row of column names " + " ".join(_POSE_COLUMNS),
                                repr(stripped[:60]))
            if table_rows == 2 and not stripped.startswith("("):
                raise CaseError(f"{source}:{n}", "Initial Positions",
                                "a row of units in parentheses", repr(stripped[:60]))
            if table_rows > 2:
                pose_rows.append((n, stripped))
            continue
        match = _ROW.match(stripped)
        if not match:
            raise CaseError(f"{source}:{n}", section or "header",
                            "a row 'value key [- description]'", repr(stripped[:60]))
        value, key = match.group(1), match.group(2)
        if not section and key.upper() == "ECHO":
            continue  # OpenFAST's echo flag: no effect on the run
        known = {k.upper(): k for k in _KEYS.get(section, ())}
        if key.upper() not in known:
            raise CaseError(f"{source}:{n}", section or "header",
                            "one of the keys " + ", ".join(_KEYS.get(section, ("Echo",))),
                            repr(key))
        key = known[key.upper()]
        if key in values:
            raise CaseError(f"{source}:{n}", key, "each key once",
                            f"a second {key} (first on line {values[key][0]})")
        values[key] = (n, value)
    for keys in _KEYS.values():
        for key in keys:
            if key not in values:
                raise CaseError(source, key, f"a {key} row", "none")
    num = {}
    for key, unit, low, strict in (("Gravity", "m/s^2", 0.0, False),
                                   ("rhoW", "kg/m^3", 0.0, False),
                                   ("WtrDpth", "m", 0.0, True), ("TMax", "s", 0.0, True),
                                   ("dtC", "s", 0.0, True)):
        n, text_value = values[key]
        v = _number(source, n, key, text_value, unit)
        if v < low or (strict and v == low):
            raise CaseError(f"{source}:{n}", key, f"a number {'>' if strict else '>='} "
                            f"{low:g} [{unit}]", repr(text_value))
        num[key] = v
    ints = {}
    for key, allowed in (("InputsMode", ("0", "1")), ("NumTurbines", ("0",))):
        n, text_value = values[key]
        if text_value not in allowed:
            expected = ("0 (OpenFAST mode: FAST.Farm's several turbines are not supported)"
                        if key == "NumTurbines" else "0 (no inputs file) or 1 (an inputs file)")
            raise CaseError(f"{source}:{n}", key, expected, repr(text_value))
        ints[key] = int(text_value)
    strings = {}
    for key in ("MDInputFile", "OutRootName", "InputsFile"):
        n, text_value = values[key]
        strings[key] = text_value[1:-1] if text_value.startswith('"') else text_value
    if ints["InputsMode"] == 1 and not strings["InputsFile"]:
        raise CaseError(f"{source}:{values['InputsFile'][0]}", "InputsFile",
                        "a file name (InputsMode is 1)", '""')
    if not pose_rows:
        raise CaseError(source, "Initial Positions", "one row of " + " ".join(_POSE_COLUMNS),
                        "none")
    if len(pose_rows) > 1:
        raise CaseError(f"{source}:{pose_rows[1][0]}", "Initial Positions",
                        "one row (NumTurbines = 0)", "a second row")
    n, row = pose_rows[0]
    fields = row.split()
    if len(fields) != len(_POSE_COLUMNS):
        raise CaseError(f"{source}:{n}", "Initial Positions",
                        f"{len(_POSE_COLUMNS)} numbers ({' '.join(_POSE_COLUMNS)})",
                        f"{len(fields)}: {row[:60]!r}")
    pose = [_number(source, n, c, f, "m" if i < 5 else "rad")
            for i, (c, f) in enumerate(zip(_POSE_COLUMNS, fields))]
    line_numbers = {k: v[0] for k, v in values.items()}
    line_numbers["Initial Positions"] = n
    return DriverInput(source=source, gravity=num["Gravity"], water_density=num["rhoW"],
                       water_depth=num["WtrDpth"], deck_file=strings["MDInputFile"],
                       duration=num["TMax"], coupling_interval=num["dtC"],
                       inputs_mode=ints["InputsMode"], inputs_file=strings["InputsFile"],
                       reference=(pose[0], pose[1]), initial_pose=tuple(pose[2:]),
                       line_numbers=line_numbers)


def read_motion_file(path: str | Path) -> MotionRecord:
    """Read a MoorDyn driver motion file (see the module docstring).

    Raises
    ------
    CaseError
        Naming the file and line: unreadable, too large, a row of another column count or not
        numbers, times not strictly increasing or not starting at or before 0.
    """
    source = str(path)
    text = _read_text(path, "a MoorDyn driver motion file", MAX_MOTION_FILE_BYTES)
    names: tuple[str, ...] = ()
    rows: list[list[float]] = []
    numbers: list[int] = []
    columns = 0
    header_lines = 0
    for n, raw in enumerate(text.splitlines(), start=1):
        fields = raw.replace(",", " ").split()
        if not fields:
            continue
        if not rows and not _NUMBER.fullmatch(fields[0]):
            header_lines += 1
            if header_lines > _MAX_HEADER_LINES:
                raise CaseError(f"{source}:{n}", "", "rows of numbers after at most "
                                f"{_MAX_HEADER_LINES} header lines", repr(raw.strip()[:60]))
            tokens = [f for f in fields if f != "#"]
            tokens[0] = tokens[0].lstrip("#") if tokens else ""
            names = tuple(t for t in tokens[1:] if t)
            continue
        if not columns:
            columns = len(fields)
            if columns < 2:
                raise CaseError(f"{source}:{n}", "", "a time and at least one value per row",
                                repr(raw.strip()[:60]))
        if len(fields) != columns:
            raise CaseError(f"{source}:{n}", "", f"{columns} numbers (as the first row)",
                            f"{len(fields)}")
        try:
            row = [float(f) for f in fields]
        except ValueError:
            bad = next(f for f in fields if not _NUMBER.fullmatch(f))
            raise CaseError(f"{source}:{n}", "", "numbers", repr(bad[:30])) from None
        if not all(math.isfinite(v) for v in row):
            raise CaseError(f"{source}:{n}", "", "finite numbers", "a NaN or infinity")
        if rows and not row[0] > rows[-1][0]:
            raise CaseError(f"{source}:{n}", "time", "times strictly increasing",
                            f"{row[0]:g} after {rows[-1][0]:g}")
        if not rows and row[0] > 0.0:
            raise CaseError(f"{source}:{n}", "time", "a first time <= 0 [s] (the run starts "
                            "at 0)", f"{row[0]:g}")
        if len(rows) == MAX_MOTION_ROWS:
            raise CaseError(f"{source}:{n}", "", f"at most {MAX_MOTION_ROWS} rows", "more")
        rows.append(row)
        numbers.append(n)
    if len(rows) < 2:
        raise CaseError(source, "", "at least two rows of numbers", f"{len(rows)}")
    data = np.asarray(rows, dtype=float)
    if len(names) != columns - 1:
        names = ()
    return MotionRecord(source=source, names=names, time=data[:, 0], values=data[:, 1:],
                        line_numbers=np.asarray(numbers, dtype=np.int64))
