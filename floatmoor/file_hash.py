"""The SHA-256 of a file's bytes: what mesh geometries and imported databases record so that a
changed input file makes a database stale (read in blocks: mesh and BEM files can be large).

Only a regular file is read (:func:`floatmoor.input_files.open_regular`: a FIFO or a device
is refused before a byte is read, without blocking), and with ``size`` only a file of exactly
that size: a database records its source files' sizes, so a recorded path leading to some other,
possibly huge, file is not read at all."""

from __future__ import annotations

import hashlib
import os

from floatmoor.input_files import InputFileError, open_regular

__all__ = ["file_sha256"]


def file_sha256(path: str | os.PathLike[str], size: int | None = None) -> str:
    """SHA-256 of a regular file's bytes (hex).

    Parameters
    ----------
    path
        The file.
    size
        When given, the file must have exactly this many bytes (none is read otherwise).

    Raises
    ------
    OSError
        It cannot be read, is not a regular file (:class:`InputFileError`), or has another
        size than ``size``.
    """
    digest = hashlib.sha256()
    with open_regular(path, size) as f:
        if size is not None and os.fstat(f.fileno()).st_size != size:
            raise InputFileError(f"a file of {os.fstat(f.fileno()).st_size} bytes, not the "
                                 f"{size} bytes expected")
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()
