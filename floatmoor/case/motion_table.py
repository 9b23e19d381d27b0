"""Reading motion tables: CSV files of a time column and motion columns.

``[motion] kind = "table"`` reads ``time, x, y, z`` (:func:`read_motion_table`);
``[motion] kind = "body"`` reads its six DOFs through the same :func:`read_csv_table`.

The file is found by :func:`floatmoor.case.files.resolve_case_file` (inside the case file's
folder, a regular file) and read up to :data:`~floatmoor.case.limits.MAX_MOTION_TABLE_BYTES`.
Numbers are plain decimals (``1.5``, ``-2e-3``): Python's ``float()`` also takes ``1_0``,
``inf`` and ``nan``, which in a measured record are typing errors. Errors name the file, the
row and the column, and never repeat the file's contents.
"""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.files import resolve_case_file
from floatmoor.case.limits import MAX_MOTION_TABLE_BYTES
from floatmoor.case.reader import TableReader, _Found
from floatmoor.input_files import file_kind

__all__ = ["read_motion_table", "read_csv_table", "HEADER"]

#: The header line a motion table must start with (after comment lines).
HEADER = ("time", "x", "y", "z")
#: A plain decimal number: digits, an optional fraction and exponent, no underscores.
_DECIMAL = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


def _header_text(headers: Sequence[tuple[str, ...]]) -> str:
    return " or ".join(f"'{','.join(h)}'" for h in headers)


def _read_bytes(t: TableReader, path: Path, expected: str) -> bytes:
    # O_NONBLOCK: should the file have been replaced by a FIFO since it was checked, opening
    # it does not wait for a writer; fstat then refuses it.
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as err:
        raise t.error("file", expected, _Found(f"{path} unreadable ({err.strerror})")) from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise t.error("file", expected, _Found(f"{path}, {file_kind(info.st_mode)}"))
        if info.st_size > MAX_MOTION_TABLE_BYTES:
            raise t.error("file", f"{expected}, at most {MAX_MOTION_TABLE_BYTES} bytes "
                          "(floatmoor.case.limits.MAX_MOTION_TABLE_BYTES)",
                          _Found(f"{path} of {info.st_size} bytes"))
        with os.fdopen(fd, "rb", closefd=False) as stream:
            data = stream.read(MAX_MOTION_TABLE_BYTES + 1)
    finally:
        os.close(fd)
    if len(data) > MAX_MOTION_TABLE_BYTES:  # grew while read
        raise t.error("file", f"{expected}, at most {MAX_MOTION_TABLE_BYTES} bytes",
                      _Found(f"{path} of more than that"))
    return data


def read_motion_table(t: TableReader, base_dir: Path, name: str
                      ) -> tuple[Path, NDArray[np.float64], NDArray[np.float64]]:
    """Read the motion table ``name`` of ``[motion]`` (key ``file``).

    Returns
    -------
    (Path, ndarray, ndarray)
        The resolved file, times [s] (n,), strictly increasing from <= 0, and displacements
        [m] (n, 3).

    Raises
    ------
    CaseError
        Naming the file and the row; never quoting the file's contents.
    """
    path, _, time, values = read_csv_table(t, base_dir, name, (HEADER,))
    return path, time, values


def read_csv_table(t: TableReader, base_dir: Path, name: str,
                   headers: Sequence[tuple[str, ...]]
                   ) -> tuple[Path, tuple[str, ...], NDArray[np.float64], NDArray[np.float64]]:
    """Read the CSV table ``name`` (key ``file`` of ``t``) with one of the ``headers``.

    Every header starts with ``time`` and has the same number of columns; the file's header
    row must be one of them exactly (after comment lines starting with ``#``).

    Returns
    -------
    (Path, tuple, ndarray, ndarray)
        The resolved file, the header it has, times [s] (n,), strictly increasing from <= 0,
        and the other columns (n, columns - 1).

    Raises
    ------
    CaseError
        Naming the file, the row and the column; never quoting the file's contents.
    """
    columns = len(headers[0])
    expected_file = (f"a CSV file with the header {_header_text(headers)} and rows of "
                     f"{columns} decimal numbers")
    path = resolve_case_file(t, "file", base_dir, name)
    data = _read_bytes(t, path, expected_file)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise t.error("file", f"{path}: UTF-8 text", _Found(
            f"a byte that is not UTF-8 at offset {err.start}")) from None
    rows = [(number, line) for number, line in enumerate(text.splitlines(), start=1)
            if line.strip() and not line.lstrip().startswith("#")]
    found_header = tuple(h.strip() for h in rows[0][1].split(",")) if rows else ()
    if found_header not in headers:
        found = f"something else in row {rows[0][0]}{_header_difference(found_header, headers)}" \
            if rows else "no rows"
        raise t.error("file", f"{path}: a header row {_header_text(headers)} before the data",
                      _Found(found))
    values = np.empty((len(rows) - 1, columns))
    for i, (number, line) in enumerate(rows[1:]):
        cells = [c.strip() for c in line.split(",")]
        expected = f"{path}: data row {number} with {columns} comma-separated decimal numbers"
        if len(cells) != columns:
            raise t.error("file", expected, _Found(f"{len(cells)} values in row {number}"))
        for j, cell in enumerate(cells):
            if not _DECIMAL.fullmatch(cell):
                raise t.error("file", expected, _Found(f"a value in column {j + 1} "
                                                       f"({found_header[j]}) of row {number} "
                                                       "that is not one"))
            values[i, j] = float(cell)
        if not np.all(np.isfinite(values[i])):
            raise t.error("file", expected, _Found(f"a number too large for a double in row "
                                                   f"{number}"))
    time = values[:, 0]
    expected = f"{path}: at least 2 data rows with strictly increasing time from <= 0 s"
    if len(values) < 2:
        raise t.error("file", expected, _Found(f"{len(values)} data row"
                                               f"{'' if len(values) == 1 else 's'}"))
    steps = np.diff(time)
    if np.any(steps <= 0.0):
        k = int(np.argmax(steps <= 0.0)) + 1
        raise t.error("file", expected, _Found(f"time {time[k]:g} s in row {rows[k + 1][0]} "
                                               f"after {time[k - 1]:g} s"))
    if time[0] > 0.0:
        raise t.error("file", expected, _Found(f"a first time of {time[0]:g} s"))
    return path, found_header, time.copy(), values[:, 1:].copy()


def _header_difference(found: tuple[str, ...], headers: Sequence[tuple[str, ...]]) -> str:
    """Which column of a wrong header row differs, told by the expected names only (the
    file's own text is never repeated)."""
    if len(found) != len(headers[0]):
        return f" ({len(found)} columns instead of {len(headers[0])})"
    for j in range(len(found)):
        names = sorted({h[j] for h in headers})
        if found[j] not in names:
            return f" (column {j + 1} is not {' or '.join(names)})"
    return " (a mix of the headers' columns)"
