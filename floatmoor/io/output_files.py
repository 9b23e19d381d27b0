"""Guards for the files a command writes: checked before any work, locked while it runs.

Before a run, every output path of a command is checked (:func:`check_output_file`): it must
name a file (not a folder, ``-o newdir/``) in an existing, writable folder with room for the
estimated output; it must not be one of the command's inputs (the case file) or another of its
outputs (``-o x --plot x``); and anything already there must be a regular file (not a symbolic
link, device, FIFO or folder) of the kind the command writes (a run result, a database, a case
file: :mod:`floatmoor.io.output_kinds`; an image for a plot), which is then replaced (the
caller announces it). Output folders are checked by :mod:`floatmoor.io.output_folders`
(docs/guide/safeguards.md#output-files). While the command runs,
:func:`output_lock` holds an advisory lock beside the output, so a second floatmoor process
writing the same file stops with a clear message before doing any work; the lock is released
when the process ends, however it ends, so a killed run leaves no stale lock.

Writes themselves are atomic (:mod:`floatmoor.io.netcdf`), or, for a run's results, an
atomic creation followed by appends that keep the file valid at every moment
(:mod:`floatmoor.io.netcdf_stream`); :func:`file_mode_for` gives the mode a replaced file
keeps.
"""

from __future__ import annotations

import errno
import fcntl
import os
import shutil
import stat
import tempfile
import time
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from floatmoor.errors import CaseError, FloatmoorError
from floatmoor.input_files import file_kind

__all__ = ["OutputFile", "OutputWriteError", "check_output_file", "check_output_folder",
           "output_lock", "open_lock_file", "atomic_target", "write_errors", "sync_folder",
           "file_mode_for", "file_state", "written_since", "SPACE_MARGIN", "NETCDF", "IMAGE"]

#: Free space asked for beyond the estimated output: the estimate leaves out the file format's
#: headers and attributes (the case text, a few kB), and a nearly full disk fails for other
#: writers too; 1 MiB covers both at no cost on any real disk.
SPACE_MARGIN = 1 << 20

#: Leading bytes of the files each kind of output may replace: netCDF-3 (classic and 64-bit
#: offset) and netCDF-4/HDF5 for results; PNG, PDF and SVG (XML) for plots.
NETCDF = ("netCDF", (b"CDF\x01", b"CDF\x02", b"CDF\x05", b"\x89HDF\r\n\x1a\n"))
IMAGE = ("image", (b"\x89PNG\r\n\x1a\n", b"%PDF", b"<?xml", b"<svg"))
#: Any regular file: for a campaign file, which is never overwritten (it is resumed after its
#: own validation, or moved aside with ``sweep --restart``).
CAMPAIGN = ("campaign", (b"",))



class OutputWriteError(FloatmoorError, OSError):
    """An output file could not be written while a command ran (disk full, folder made
    read-only): the message names the file and the system's reason; ``target`` is the file
    (None when not known)."""

    def __init__(self, message: str, target: str | os.PathLike[str] | None = None) -> None:
        super().__init__(message)
        self.target = None if target is None else Path(target)


@dataclass(frozen=True)
class OutputFile:
    """A checked output path.

    Attributes
    ----------
    path
        The file to write.
    replaces
        Size in bytes of the regular file already there, which the write replaces, or None
        when there is none.
    """

    path: Path
    replaces: int | None


def check_output_file(text: str | os.PathLike[str], option: str, *,
                      kind: tuple = NETCDF,
                      protected: Mapping[str, str | os.PathLike[str]] | None = None,
                      expected_bytes: int = 0) -> OutputFile:
    """Check an output path before a command does any work.

    Parameters
    ----------
    text
        The path as given (a trailing ``/`` names a folder and is refused).
    option
        The option that gave it, for the message (``"-o/--output"``, ``"--plot"``).
    kind
        What may be replaced: (name, accepted leading bytes), :data:`NETCDF` or :data:`IMAGE`,
        or (name, leading bytes, check) where ``check(path)`` gives None for a file of this
        kind and otherwise what the file is (:mod:`floatmoor.io.output_kinds`: a run result,
        a hydrodynamic database, a case file). An empty file may always be replaced.
    protected
        Files the output must not be: {what it is (``"case file"``): path}; the same file
        reached through another name (a symbolic or hard link) counts.
    expected_bytes
        Estimated size of the output; the folder must have this much free space and
        :data:`SPACE_MARGIN`.

    Raises
    ------
    CaseError
        Naming the option, what it should be and what it is; nothing has been written (a
        probe file created to test the folder is removed).
    """
    raw = os.fspath(text)
    if not raw or raw.endswith(("/", os.sep)) or Path(raw).name in ("", ".", ".."):
        raise CaseError(option, "", "a file name (not a folder)", f"'{raw}'")
    path = Path(raw)
    folder = path.parent
    if not folder.is_dir():
        raise CaseError(option, "", "a file in an existing folder", f"'{raw}'")
    for what, other in (protected or {}).items():
        if _same_file(path, Path(other)):
            raise CaseError(option, "", f"a file other than the {what}",
                            f"'{raw}', the {what}")
    replaces = _existing_size(path, option, kind)
    _check_writable(folder, option)
    free = shutil.disk_usage(folder).free
    if expected_bytes + SPACE_MARGIN > free:
        raise CaseError(option, "", f"a folder with room for the output (about "
                        f"{_size(expected_bytes + SPACE_MARGIN)})",
                        f"{_size(free)} free in '{folder}'")
    return OutputFile(path=path, replaces=replaces)


def check_output_folder(text: str | os.PathLike[str], option: str) -> Path:
    """Check an output folder (of a study or report) before a command does any work: an
    existing folder floatmoor can write to, or a new one in such a folder.

    Raises
    ------
    CaseError
        Naming the option, what it should be and what it is.
    """
    path = Path(text)
    if path.exists() and not path.is_dir():
        raise CaseError(option, "", "a folder", f"the file '{path}'")
    if path.is_dir():
        _check_writable(path, option)
    else:
        parent = path.resolve().parent
        if not parent.is_dir():
            raise CaseError(option, "", "a folder in an existing folder", f"'{path}'")
        _check_writable(parent, option)
    return path


def _existing_size(path: Path, option: str, kind: tuple) -> int | None:
    """Size of the regular file of ``kind`` at ``path``, None when nothing is there."""
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        return None
    except OSError as err:
        raise CaseError(option, "", "a path that can be examined",
                        f"'{path}': {err.strerror}") from None
    file_type = stat.S_IFMT(info.st_mode)
    if file_type == stat.S_IFDIR:
        raise CaseError(option, "", "a file name (not a folder)", f"'{path}', a folder")
    if file_type != stat.S_IFREG:
        what = file_kind(info.st_mode)
        raise CaseError(option, "", "a new or regular file to replace", f"'{path}', {what}")
    if info.st_size == 0:
        return 0
    name, magics, *content = kind
    try:
        with open(path, "rb") as fh:
            head = fh.read(max(len(m) for m in magics)).lstrip()
        if not head.startswith(magics):
            raise CaseError(option, "", f"a new file or a {name} file to replace (floatmoor "
                            "does not overwrite other files)",
                            f"'{path}', which is not a {name} file")
        found = content[0](path) if content else None
    except OSError as err:
        raise CaseError(option, "", "a file that can be read",
                        f"'{path}': {err.strerror}") from None
    if found is not None:
        raise CaseError(option, "", f"a new file or a {name} to replace (a command replaces "
                        "only files of its own kind)", f"'{path}', {found}")
    return info.st_size


def _same_file(a: Path, b: Path) -> bool:
    """Whether ``a`` and ``b`` name one file (through links too); paths that do not exist
    compare by their resolved names."""
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


def _check_writable(folder: Path, option: str) -> None:
    """Create and remove a probe file in ``folder``, as the atomic write will."""
    try:
        fd, probe = tempfile.mkstemp(prefix=".floatmoor-probe.", suffix=".tmp", dir=folder)
    except OSError as err:
        raise CaseError(option, "", "a file in a folder floatmoor can write to",
                        f"'{folder}': {err.strerror}") from None
    os.close(fd)
    os.unlink(probe)


def _size(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB"):
        if n < 1000.0:
            return f"{n:.3g} {unit}"
        n /= 1000.0
    return f"{n:.3g} TB"


@contextmanager
def atomic_target(path: str | os.PathLike[str], suffix: str = ".tmp") -> Iterator[Path]:
    """A temporary file beside ``path`` for the block to write, which then replaces ``path``.

    The file is flushed to disk before it replaces the target and keeps the mode of the file
    it replaces (:func:`file_mode_for`); on any error it is removed and the target is left
    as it was.

    Raises
    ------
    OutputWriteError
        When ``path`` exists and is not a regular file (a symbolic link, a device), or the
        write fails (disk full, read-only folder): naming the file and the reason.
    """
    target = Path(path)
    try:
        info = os.lstat(target)
    except FileNotFoundError:
        info = None
    except OSError as err:
        raise OutputWriteError(f"cannot write {target}: {err.strerror}") from None
    if info is not None and not stat.S_ISREG(info.st_mode):
        what = file_kind(info.st_mode)
        raise OutputWriteError(f"cannot write {target}: it is {what}, not a regular file")
    tmp: str | None = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=suffix,
                                   dir=target.parent)
        try:
            os.fchmod(fd, file_mode_for(target))
        finally:
            os.close(fd)
        yield Path(tmp)
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, target)
        tmp = None
    except OSError as err:
        if isinstance(err, OutputWriteError):
            raise
        raise OutputWriteError(f"cannot write {target}: {err.strerror or err}",
                               target) from err
    finally:
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass


@contextmanager
def write_errors(path: str | os.PathLike[str]) -> Iterator[None]:
    """Turn an OSError of the block, which writes ``path`` (a figure library's, a text
    write's: disk full), into an :class:`OutputWriteError` naming the file."""
    try:
        yield
    except OutputWriteError:
        raise
    except OSError as err:
        raise OutputWriteError(f"cannot write {path}: {err.strerror or err}", path) from err


#: Errors of opening or flushing a folder that mean it cannot be flushed here (a folder
#: that cannot be opened for reading, Windows, file systems without a folder fsync), not that
#: a write failed: the flush is then skipped.
_NO_FOLDER_SYNC = {errno.EACCES, errno.EPERM, errno.EINVAL, errno.EBADF, errno.EISDIR,
                   errno.ENOTSUP, getattr(errno, "EOPNOTSUPP", errno.ENOTSUP)}


def sync_folder(folder: str | os.PathLike[str]) -> None:
    """Flush ``folder``'s entries to disk (``fsync`` of the folder), so that a file created or
    renamed in it survives a power cut; skipped where the folder cannot be flushed (not
    readable, Windows, a file system without it).

    Raises
    ------
    OSError
        When the flush fails (an I/O error).
    """
    flags = os.O_RDONLY | getattr(os, "O_DIRECTORY", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(folder, flags)
    except OSError as err:
        if err.errno in _NO_FOLDER_SYNC:
            return
        raise
    try:
        os.fsync(fd)
    except OSError as err:
        if err.errno not in _NO_FOLDER_SYNC:
            raise
    finally:
        os.close(fd)


def file_mode_for(path: str | os.PathLike[str]) -> int:
    """The permission bits a file written to ``path`` gets: those of the file it replaces,
    else what ``open`` would give a new file (0o666 less the umask)."""
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except OSError:
        mask = os.umask(0o022)
        os.umask(mask)
        return 0o666 & ~mask


def file_state(path: str | os.PathLike[str]) -> tuple[int, int, int] | None:
    """(inode, size, modification time in ns) of ``path``, or None when there is none: with
    :func:`written_since`, tells whether a command wrote the file."""
    try:
        info = os.stat(path)
    except OSError:
        return None
    return info.st_ino, info.st_size, info.st_mtime_ns


def written_since(path: str | os.PathLike[str], before: tuple[int, int, int] | None) -> bool:
    """Whether ``path`` exists and was written since :func:`file_state` gave ``before``:
    atomic writes replace the file, so its inode changes; appends change its size and
    modification time."""
    now = file_state(path)
    return now is not None and now != before


def lock_path(path: str | os.PathLike[str]) -> Path:
    """The lock file of an output: ``.NAME.lock`` beside it."""
    target = Path(path)
    return target.parent / f".{target.name}.lock"


@contextmanager
def output_lock(path: str | os.PathLike[str], option: str = "-o/--output") -> Iterator[None]:
    """Hold an exclusive advisory lock on the output ``path`` for the block.

    The lock is ``fcntl.flock`` on :func:`lock_path`, which records the holder's process id
    and start time for the message a second writer gets; it is removed on release. The
    kernel drops the lock when its process ends, so a killed process leaves no stale lock
    (at most a lock file, which the next writer takes over).

    Raises
    ------
    CaseError
        When another process holds the lock (nothing is done), or the lock file cannot be
        created.
    """
    lock = lock_path(path)
    while True:
        fd = open_lock_file(lock, option)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as err:
            holder = _read_holder(fd)
            os.close(fd)
            if err.errno not in (errno.EWOULDBLOCK, errno.EACCES):
                raise CaseError(option, "", "a file that can be locked",
                                f"'{lock}': {err.strerror}") from None
            raise CaseError(option, "", "a file no other floatmoor process is writing",
                            f"'{path}', being written by {holder} (wait for it to end, or "
                            f"choose another output)") from None
        # the previous holder may have removed the file between our open and flock: then
        # the lock is on a deleted file, and another process may lock the new one; retry
        try:
            same = os.path.samestat(os.fstat(fd), os.stat(lock))
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)
    try:
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()} {time.strftime('%Y-%m-%d %H:%M:%S')}\n".encode())
        yield
    finally:
        try:
            os.unlink(lock)  # while still held: no other process has it
        except OSError:
            pass
        os.close(fd)


def open_lock_file(lock: Path, option: str) -> int:
    """Open (or create) the lock file ``lock`` for reading and writing without following a
    symbolic link and without truncating it, and check it is a regular file of one name: a
    link or FIFO planted at the lock's name cannot make floatmoor write (or truncate) another
    file.

    Raises
    ------
    CaseError
        When it cannot be opened, or is not a regular file (nothing is written to it).
    """
    try:
        fd = os.open(lock, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC | os.O_NOFOLLOW
                     | os.O_NONBLOCK, 0o644)
    except OSError as err:
        if err.errno == errno.ELOOP:
            raise CaseError(option, "", "a lock file that is a regular file (floatmoor does "
                            "not follow links to lock)", f"'{lock}', a symbolic link") from None
        raise CaseError(option, "", "a file in a folder floatmoor can write to",
                        f"'{lock}': {err.strerror}") from None
    info = os.fstat(fd)
    if not stat.S_ISREG(info.st_mode) or info.st_nlink != 1:
        os.close(fd)
        what = file_kind(info.st_mode) if not stat.S_ISREG(info.st_mode) else \
            f"a file with {info.st_nlink} names (hard links)"
        raise CaseError(option, "", "a lock file that is a regular file of one name",
                        f"'{lock}', {what}")
    os.set_blocking(fd, True)
    return fd


def _read_holder(fd: int) -> str:
    """The lock holder as the message names it: ``process 1234 (since 2026-11-24 22:30:00)``."""
    try:
        text = os.pread(fd, 200, 0).decode("ascii", "replace").split()
    except OSError:
        text = []
    if len(text) >= 3 and text[0].isdigit():
        return f"process {text[0]} (since {text[1]} {text[2]})"
    return "another process"
