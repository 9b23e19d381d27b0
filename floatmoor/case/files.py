"""The files a case names, and the case file itself: confined, regular and bounded.

A case file may be shared like any data file, so a file it names (a motion table) is
confined: the path is relative to the case file's folder and must stay inside it after
symbolic links are resolved (absolute paths and ``..`` out of the folder are refused), and
it must be a regular file. FIFOs, devices and folders are refused before they are opened, so
a case cannot hang a run on a pipe or read ``/dev/zero`` until memory runs out. The case file
given on the command line is held to the same kinds and to
:data:`~floatmoor.case.limits.MAX_CASE_FILE_BYTES`.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from floatmoor.case.limits import MAX_CASE_FILE_BYTES
from floatmoor.case.reader import TableReader, _Found
from floatmoor.errors import CaseError
from floatmoor.input_files import file_kind

__all__ = ["CaseFileKindError", "read_case_text", "read_input_text", "resolve_case_file"]


class CaseFileKindError(OSError):
    """The case file is not a regular file, or is too large."""


def read_case_text(path: Path) -> str:
    """The UTF-8 text of a case file, refusing FIFOs, devices, folders and files larger
    than :data:`~floatmoor.case.limits.MAX_CASE_FILE_BYTES` before reading them. A UTF-8
    byte order mark at the start (some Windows editors write one) is dropped, as Python's
    ``utf-8-sig`` codec does; anywhere else it is text (docs/guide/case_files.md).

    Raises
    ------
    CaseFileKindError, OSError, UnicodeDecodeError
    """
    mode = os.stat(path).st_mode
    if not stat.S_ISREG(mode):
        raise CaseFileKindError(file_kind(mode))
    # opened without blocking (a FIFO put in its place after the look above does not hang the
    # command) and looked at again: only the regular file that was checked is read
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    with os.fdopen(fd, "rb") as stream:
        mode = os.fstat(stream.fileno()).st_mode
        if not stat.S_ISREG(mode):
            raise CaseFileKindError(file_kind(mode))
        data = stream.read(MAX_CASE_FILE_BYTES + 1)
    if len(data) > MAX_CASE_FILE_BYTES:
        raise CaseFileKindError(f"a file of more than {MAX_CASE_FILE_BYTES} bytes")
    return data.decode("utf-8-sig")


def read_input_text(path: str | os.PathLike[str], kind: str) -> str:
    """:func:`read_case_text` of an input file of ``kind`` ("case", "study"), every failure a
    :class:`~floatmoor.errors.CaseError` naming the file and what it should have been."""
    source = str(path)
    try:
        return read_case_text(Path(path))
    except CaseFileKindError as err:
        raise CaseError(source, "", f"a readable {kind} file (a regular file of at most "
                        f"{MAX_CASE_FILE_BYTES} bytes)", str(err)) from None
    except FileNotFoundError:
        raise CaseError(source, "", f"a readable {kind} file", "no such file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise CaseError(source, "", f"a readable UTF-8 {kind} file", str(err)) from None


def resolve_case_file(t: TableReader, key: str, base_dir: Path, name: str) -> Path:
    """The regular file ``name`` inside ``base_dir`` (the case file's folder).

    Raises
    ------
    CaseError
        For an absolute path, a path leading out of the folder, a missing file or anything
        that is not a regular file.
    """
    expected = "a path to a regular file inside the case file's folder, relative to it"
    if "\0" in name:  # no file system takes it (os functions raise ValueError)
        raise t.error(key, expected, _Found("a path holding a null character (\\x00)"))
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
        raise t.error(key, expected, _Found(f"{folder / name}, {file_kind(mode)}"))
    return path
