"""Reading a motion table (``[motion] kind = "table"``): a ``time, x, y, z`` CSV file.

A case file may be shared like any data file, so the table it names is confined: the path is
relative to the case file's folder and must stay inside it (after symbolic links are
resolved), and it must be a regular file no larger than
:data:`~floatmoor.case.limits.MAX_MOTION_TABLE_BYTES`. FIFOs, devices and folders are refused
before they are opened, so a case cannot hang the run on a pipe or read ``/dev/zero`` until
memory runs out. Numbers are plain decimals (``1.5``, ``-2e-3``): Python's ``float()`` also
takes ``1_0``, ``inf`` and ``nan``, which in a measured record are typing errors. Errors name
the file, the row and the column, and never repeat the file's contents.
"""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.limits import MAX_CASE_FILE_BYTES, MAX_MOTION_TABLE_BYTES
from floatmoor.case.reader import TableReader, _Found

__all__ = ["read_motion_table", "resolve_case_file", "read_case_text", "CaseFileKindError",
           "HEADER"]

#: The header line a motion table must start with (after comment lines).
HEADER = ("time", "x", "y", "z")
#: A plain decimal number: digits, an optional fraction and exponent, no underscores.
_DECIMAL = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_EXPECTED = "a CSV file with the header 'time,x,y,z' and rows of 4 decimal numbers"


def _kind(mode: int) -> str:
    for test, name in ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


class CaseFileKindError(OSError):
    """The case file is not a regular file, or is too large."""


def read_case_text(path: Path) -> str:
    """The UTF-8 text of a case file, refusing FIFOs, devices, folders and files larger
    than :data:`~floatmoor.case.limits.MAX_CASE_FILE_BYTES` before reading them.

    Raises
    ------
    CaseFileKindError, OSError, UnicodeDecodeError
    """
    mode = os.stat(path).st_mode
    if not stat.S_ISREG(mode):
        raise CaseFileKindError(_kind(mode))
    with open(path, "rb") as stream:
        data = stream.read(MAX_CASE_FILE_BYTES + 1)
    if len(data) > MAX_CASE_FILE_BYTES:
        raise CaseFileKindError(f"a file of more than {MAX_CASE_FILE_BYTES} bytes")
    return data.decode("utf-8")


def resolve_case_file(t: TableReader, key: str, base_dir: Path, name: str) -> Path:
    """The regular file ``name`` inside ``base_dir`` (the case file's folder).

    Raises
    ------
    CaseError
        For an absolute path, a path leading out of the folder, a missing file or anything
        that is not a regular file.
    """
    expected = "a path to a regular file inside the case file's folder, relative to it"
    if Path(name).is_absolute():
        raise t.error(key, expected, _Found(f'the absolute path "{name}"'))
    folder = base_dir.resolve()
    path = (folder / name).resolve()
    if not path.is_relative_to(folder):
        raise t.error(key, expected, _Found(f'"{name}", which leads out of {folder}'))
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise t.error(key, expected, _Found(f"no file {folder / name}")) from None
    except OSError as err:
        raise t.error(key, expected, _Found(f"{folder / name} unreadable ({err.strerror})")) \
            from None
    if not stat.S_ISREG(mode):
        raise t.error(key, expected, _Found(f"{folder / name}, {_kind(mode)}"))
    return path


def _read_bytes(t: TableReader, path: Path) -> bytes:
    # O_NONBLOCK: should the file have been replaced by a FIFO since it was checked, opening
    # it does not wait for a writer; fstat then refuses it.
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as err:
        raise t.error("file", _EXPECTED, _Found(f"{path} unreadable ({err.strerror})")) from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise t.error("file", _EXPECTED, _Found(f"{path}, {_kind(info.st_mode)}"))
        if info.st_size > MAX_MOTION_TABLE_BYTES:
            raise t.error("file", f"{_EXPECTED}, at most {MAX_MOTION_TABLE_BYTES} bytes "
                          "(floatmoor.case.limits.MAX_MOTION_TABLE_BYTES)",
                          _Found(f"{path} of {info.st_size} bytes"))
        with os.fdopen(fd, "rb", closefd=False) as stream:
            data = stream.read(MAX_MOTION_TABLE_BYTES + 1)
    finally:
        os.close(fd)
    if len(data) > MAX_MOTION_TABLE_BYTES:  # grew while read
        raise t.error("file", f"{_EXPECTED}, at most {MAX_MOTION_TABLE_BYTES} bytes",
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
    path = resolve_case_file(t, "file", base_dir, name)
    data = _read_bytes(t, path)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise t.error("file", f"{path}: UTF-8 text", _Found(
            f"a byte that is not UTF-8 at offset {err.start}")) from None
    rows = [(number, line) for number, line in enumerate(text.splitlines(), start=1)
            if line.strip() and not line.lstrip().startswith("#")]
    if not rows or tuple(h.strip() for h in rows[0][1].split(",")) != HEADER:
        found = f"something else in row {rows[0][0]}" if rows else "no rows"
        raise t.error("file", f"{path}: a header row 'time,x,y,z' before the data",
                      _Found(found))
    values = np.empty((len(rows) - 1, 4))
    for i, (number, line) in enumerate(rows[1:]):
        cells = [c.strip() for c in line.split(",")]
        expected = f"{path}: data row {number} with 4 comma-separated decimal numbers"
        if len(cells) != 4:
            raise t.error("file", expected, _Found(f"{len(cells)} values in row {number}"))
        for j, cell in enumerate(cells):
            if not _DECIMAL.fullmatch(cell):
                raise t.error("file", expected, _Found(f"a value in column {j + 1} ({HEADER[j]})"
                                                       f" of row {number} that is not one"))
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
    return path, time.copy(), values[:, 1:].copy()
