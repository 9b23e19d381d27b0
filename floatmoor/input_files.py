"""Input files from elsewhere (BEM results, hydrodynamic databases, meshes): regular files
only, opened without blocking, of bounded size; and what a path that is not one is.

A file named on the command line or recorded in a database may be a FIFO (opening it for
reading waits for a writer: the command hangs), a device (``/dev/zero`` reads forever) or a
folder. :func:`open_regular` looks at what the path is before opening it, opens it with
``O_NONBLOCK`` (a FIFO that appears between the look and the open does not block) and looks
again at what was opened, so only a regular file is ever read; a size limit is checked on the
opened file before its bytes are read. The failures are :class:`InputFileError` whose
``found`` says what the path is ("a FIFO (named pipe)", "no such file", ...), for the caller's
one-line error. :func:`file_kind` names what a file mode is, for those messages and for the
case's files (:mod:`floatmoor.case.files`) and output files alike.
"""

from __future__ import annotations

import os
import stat
from typing import BinaryIO

__all__ = ["InputFileError", "file_kind", "regular_file_size", "open_regular", "read_bounded"]


def file_kind(mode: int) -> str:
    """What a file of mode ``mode`` is, for a message ("a FIFO (named pipe)", ...)."""
    for test, name in ((stat.S_ISDIR, "a folder"), (stat.S_ISLNK, "a symbolic link"),
                       (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


class InputFileError(OSError):
    """A path that is not a readable regular file (or one over its size limit).

    Attributes
    ----------
    found
        What the path is instead, for a message's "found ..." part.
    """

    def __init__(self, found: str) -> None:
        super().__init__(found)
        self.found = found
        self.strerror = found  # what callers catching OSError quote


def _checked_mode(mode: int, size: int, limit: int | None) -> int:
    if not stat.S_ISREG(mode):
        raise InputFileError(f"{file_kind(mode)}, not a regular file")
    if limit is not None and size > limit:
        raise InputFileError(f"a file of {size} bytes, more than the {limit} bytes read")
    return size


def regular_file_size(path: str | os.PathLike[str], limit: int | None = None) -> int:
    """The size [bytes] of the regular file at ``path`` (symbolic links followed), without
    opening it.

    Raises
    ------
    InputFileError
        Missing, unreadable, not a regular file, or larger than ``limit``.
    """
    try:
        info = os.stat(path)
    except FileNotFoundError:
        raise InputFileError("no such file") from None
    except (OSError, ValueError) as err:
        raise InputFileError(f"a path that cannot be read ({getattr(err, 'strerror', None) or err})"
                             ) from None
    return _checked_mode(info.st_mode, info.st_size, limit)


def open_regular(path: str | os.PathLike[str], limit: int | None = None) -> BinaryIO:
    """The regular file at ``path`` opened for binary reading, without blocking on a FIFO.

    Parameters
    ----------
    path
        The file (symbolic links followed).
    limit
        Largest size accepted [bytes] (None: any).

    Raises
    ------
    InputFileError
        Missing, unreadable, not a regular file, or larger than ``limit``.
    """
    regular_file_size(path, limit)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                     | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0))
    except FileNotFoundError:
        raise InputFileError("no such file") from None
    except OSError as err:
        raise InputFileError(f"a file that cannot be opened ({err.strerror or err})") from None
    try:
        info = os.fstat(fd)
        _checked_mode(info.st_mode, info.st_size, limit)
    except BaseException:
        os.close(fd)
        raise
    return os.fdopen(fd, "rb")


def read_bounded(path: str | os.PathLike[str], limit: int) -> bytes:
    """The bytes of the regular file at ``path``, at most ``limit`` of them
    (:class:`InputFileError` for a larger file, also one that grew while being read)."""
    with open_regular(path, limit) as stream:
        data = stream.read(limit + 1)
    if len(data) > limit:
        raise InputFileError(f"a file of more than the {limit} bytes read")
    return data
