"""Output folders a command owns: new or empty, or written earlier by the same command.

A command that writes a folder (``report``, ``compare``, ``uq``, ``vtk``, ``study``) writes
into it only when the folder is new, empty, or holds a manifest
(:data:`MANIFEST_NAME`, a small JSON file) saying that this same command wrote it, and
nothing but the files that manifest lists; so ``-o .`` or ``-o hydrodb`` (a project or
database folder) or a folder holding a user's own ``summary.md`` is refused before any work
(docs/guide/safeguards.md#output-files). :class:`OwnedFolder` records, when the command
ends, every file it wrote in the manifest; when it fails (a disk that fills, bad input found
late) it removes the files it created in this invocation, and the folder if it made it, and
keeps what it did not write.
"""

from __future__ import annotations

import json
import os
import stat
from pathlib import Path
from types import TracebackType

from floatmoor.errors import CaseError

__all__ = ["MANIFEST_NAME", "OwnedFolder", "check_owned_folder", "owned_files"]

#: The manifest of an output folder: {"command": ..., "files": [relative paths]}.
MANIFEST_NAME = ".floatmoor-output.json"
#: Largest manifest read: a folder lists at most a few thousand files (a VTK series of a
#: long run: one file per shape sample), about 100 bytes each.
_MAX_MANIFEST_BYTES = 4 << 20
#: Files floatmoor itself leaves for a moment beside the files it writes (locks, atomic
#: writes' temporaries, the folder probe): never the user's, never listed.
_TRANSIENT_SUFFIXES = (".lock", ".tmp", ".partial")


def _transient(name: str) -> bool:
    return name.startswith(".") and (name.endswith(_TRANSIENT_SUFFIXES)
                                     or name.startswith(".floatmoor-"))


def owned_files(folder: Path, command: str) -> set[str] | None:
    """The files ``folder``'s manifest lists when ``command`` wrote it, else None."""
    manifest = folder / MANIFEST_NAME
    try:
        info = os.lstat(manifest)
        if not stat.S_ISREG(info.st_mode) or info.st_size > _MAX_MANIFEST_BYTES:
            return None
        data = json.loads(manifest.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("command") != command:
        return None
    files = data.get("files")
    if not isinstance(files, list) or not all(isinstance(f, str) for f in files):
        return None
    return set(files)


def _entries(folder: Path) -> tuple[dict[str, tuple[int, int, int]], list[str]]:
    """(regular files by relative path: (inode, size, mtime), other entries) under ``folder``,
    not following links; floatmoor's transient files and the manifest are left out."""
    files: dict[str, tuple[int, int, int]] = {}
    other: list[str] = []
    for root, dirs, names in os.walk(folder):
        base = Path(root).relative_to(folder)
        for name in list(dirs):
            if os.path.islink(os.path.join(root, name)):
                dirs.remove(name)
                other.append((base / name).as_posix())
        for name in names:
            rel = (base / name).as_posix()
            if rel == MANIFEST_NAME or _transient(name):
                continue
            info = os.lstat(os.path.join(root, name))
            if stat.S_ISREG(info.st_mode):
                files[rel] = (info.st_ino, info.st_size, info.st_mtime_ns)
            else:
                other.append(rel)
    return files, other


def check_owned_folder(text: str | os.PathLike[str], option: str, command: str) -> Path:
    """Check an output folder before any work: writable (:func:`floatmoor.io.output_files.
    check_output_folder`), and new, empty, or written by ``command`` and holding nothing but
    the files its manifest lists.

    Raises
    ------
    CaseError
        Naming the option, what the folder should be and a file in it that is not the
        command's.
    """
    from floatmoor.io.output_files import check_output_folder

    path = check_output_folder(text, option)
    if not path.is_dir():
        return path
    try:
        if not os.path.lexists(path / MANIFEST_NAME):  # must be empty: its top level tells
            owned: set[str] | None = set()
            foreign = sorted(e.name for e in os.scandir(path) if not _transient(e.name))
        else:
            owned = owned_files(path, command)
            files, other = _entries(path)
            foreign = sorted(other + [f for f in files if owned is None or f not in owned])
    except OSError as err:
        raise CaseError(option, "", "a folder that can be listed",
                        f"'{path}': {err.strerror}") from None
    if owned is None or foreign:
        example = f" (e.g. '{foreign[0]}')" if foreign else ""
        raise CaseError(option, "", f"a new or empty folder, or one that floatmoor {command} "
                        f"wrote (floatmoor does not write into other folders)",
                        f"'{path}', which holds {len(foreign) or 'files'} "
                        f"{'entry' if len(foreign) == 1 else 'entries'} floatmoor {command} "
                        f"did not write{example}")
    return path


class OwnedFolder:
    """The files a command writes into a checked folder (:func:`check_owned_folder`).

    Used as a context manager around the writing: on exit the manifest lists the files it
    lists already and those written in the block; when the block raises an exception
    other than one of ``keep_on`` (KeyboardInterrupt is always one: a re-run resumes), the
    files created in the block are removed, except those named in ``keep`` (relative paths,
    e.g. a study's resumable runs, or folders), and the folders the block made and left
    empty, the output folder too. A file that was there before under another name (moved
    aside) is not removed; nor is a file it replaced (writes are atomic: it holds the new
    content, whole).
    """

    def __init__(self, folder: str | os.PathLike[str], command: str, *,
                 keep: tuple[str, ...] = (),
                 keep_on: tuple[type[BaseException], ...] = ()) -> None:
        self.folder = Path(folder)
        self.command = command
        self.keep = keep
        self.keep_on = (KeyboardInterrupt, *keep_on)
        self._existed = False
        self._before: dict[str, tuple[int, int, int]] = {}
        self._owned: set[str] = set()
        self._dirs_before: set[str] = set()

    def __enter__(self) -> "OwnedFolder":
        self._existed = self.folder.is_dir()
        if self._existed:
            self._before, _ = _entries(self.folder)
            self._owned = owned_files(self.folder, self.command) or set()
            self._dirs_before = {Path(root).relative_to(self.folder).as_posix()
                                 for root, _, _ in os.walk(self.folder)}
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        if not self.folder.is_dir():
            return
        try:
            now, _ = _entries(self.folder)
        except OSError:
            return
        written = {f for f, state in now.items() if self._before.get(f) != state}
        if exc is not None and not isinstance(exc, self.keep_on):
            inodes = {state[0] for state in self._before.values()}
            created = {f for f in written if f not in self._before and now[f][0] not in inodes}
            for rel in sorted(created):  # a file moved aside (runs.nc.bak-1) is not new
                if not any(rel == k or rel.startswith(k.rstrip("/") + "/") for k in self.keep):
                    (self.folder / rel).unlink(missing_ok=True)
                    written.discard(rel)
                    self._owned.discard(rel)
            self._remove_empty_folders()
            if not self._existed and not any(self.folder.iterdir()):
                self.folder.rmdir()
                return
        owned = sorted((self._owned | written) & set(now))
        if not owned and not os.path.lexists(self.folder / MANIFEST_NAME):  # nothing to list
            return
        try:
            _write_manifest(self.folder, self.command, owned)
        except OSError:
            if exc is None:
                raise

    def record_written(self) -> None:
        """List in the manifest now the files written so far in the block (a long command's
        results kept as it goes, e.g. a study's finished runs), so that they stay the
        command's even if the process is killed before the block ends.

        Raises
        ------
        OSError
            When the manifest cannot be written.
        """
        now, _ = _entries(self.folder)
        written = {f for f, state in now.items() if self._before.get(f) != state}
        self._owned = (self._owned | written) & set(now)
        _write_manifest(self.folder, self.command, sorted(self._owned))

    def _remove_empty_folders(self) -> None:
        """Remove the folders under the output folder that the block made and left empty."""
        for root, _, _ in os.walk(self.folder, topdown=False):
            rel = Path(root).relative_to(self.folder).as_posix()
            if rel != "." and rel not in self._dirs_before and not os.listdir(root):
                try:
                    os.rmdir(root)
                except OSError:
                    pass


def _write_manifest(folder: Path, command: str, files: list[str]) -> None:
    """Write the manifest atomically (it lists files; it holds no data of its own)."""
    from floatmoor.io.output_files import atomic_target

    text = json.dumps({"command": command, "files": files}, indent=1) + "\n"
    with atomic_target(folder / MANIFEST_NAME) as tmp:
        tmp.write_text(text, encoding="utf-8")
