"""Checkpoints of coupled runs as plain numeric data, validated before use
(docs/guide/safeguards.md#checkpoints-and---resume).

A checkpoint is an uncompressed ``.npz`` (a zip of ``.npy`` arrays, :func:`numpy.savez`): a
flat set of named arrays -- the format name and version, the floatmoor version, what
identifies the run (the case text's hash, the ``--set`` overrides, the run settings' hash),
the state of body and lines (:meth:`floatmoor.simulation.coupled.MooredBody.state_arrays`)
and how far the run got. The samples recorded up to there are in the run's output file,
written before the checkpoint, which a resumed run continues (version 1 checkpoints held the
samples too, so their size grew with the run). Nothing in it is a pickle, and nothing
derivable from the case (operators, wave and wind realisations) is stored: a resumed run
rebuilds those and restores only the state.

Reading checks, in order, before any value is used: a regular file (not a FIFO or device),
a zip of ``.npy`` members (a pickle, an empty or a truncated file is refused without being
unpickled or read further), no object arrays (``allow_pickle=False``), the format and its
version, the floatmoor version, the run's identity (a message naming what differs: the case
text, which overrides, or the settings), then every array's name, shape and dtype against
those the resumed run expects, read from the ``.npy`` headers before any data is read (so a
crafted header cannot make it allocate), and the finiteness of every float.
"""

from __future__ import annotations

import glob
import hashlib
import os
import stat
import zipfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from floatmoor._version import __version__
from floatmoor.errors import CaseError
from floatmoor.input_files import file_kind
from floatmoor.io.output_files import sync_folder

__all__ = ["CheckpointError", "RunIdentity", "write_checkpoint", "check_checkpoint",
           "read_checkpoint", "temporary_path", "remove_stale_temporaries", "FORMAT",
           "VERSION"]

#: The format name stored in every checkpoint (``meta/format``).
FORMAT = "floatmoor coupled-run checkpoint"
#: The layout version (``meta/version``); a checkpoint of another version is refused.
VERSION = 2
#: Largest member holding metadata [bytes]: the overrides of a run fit easily (a crafted
#: header may not make the reader allocate more).
_META_MAX_BYTES = 1 << 20
#: Most members a checkpoint may have: a run's state is a dozen arrays per line (a crafted
#: zip of millions of empty members may not keep the reader busy).
_MAX_MEMBERS = 100_000
_PICKLE_MAGIC = b"\x80"
_ZIP_MAGIC = b"PK"
_START_OVER = ("resume with the same case file and --set overrides, or run without --resume "
               "to start over, which replaces the checkpoint")


class CheckpointError(CaseError):
    """A checkpoint that cannot be resumed from: missing, not a regular file, damaged,
    truncated, foreign, of another format version or of another run. Bad input (exit 2)."""

    def __init__(self, path: str | os.PathLike[str], expected: str, found: str) -> None:
        super().__init__(str(path), "", expected, found)


@dataclass(frozen=True)
class RunIdentity:
    """What a checkpoint must share with the run resuming it."""

    case_text_sha256: str
    overrides: tuple[str, ...]
    settings_sha256: str
    case_source: str = ""

    @classmethod
    def of(cls, case_text: str, overrides: Sequence[str], settings: str, source: str = ""
           ) -> "RunIdentity":
        """The identity of a run of ``case_text`` with ``overrides`` and settings whose
        ``repr`` is ``settings``."""
        return cls(_sha256(case_text), tuple(overrides), _sha256(settings), str(source))

    def arrays(self) -> dict[str, NDArray]:
        """The identity as ``meta/...`` arrays."""
        return {"meta/case_text_sha256": np.array(self.case_text_sha256),
                "meta/overrides": np.array(list(self.overrides), dtype=str).reshape(-1),
                "meta/settings_sha256": np.array(self.settings_sha256)}

    def differences(self, other: "RunIdentity") -> list[str]:
        """What differs from ``other`` (the checkpoint's), in words: empty when the same."""
        out = []
        if self.case_text_sha256 != other.case_text_sha256:
            where = f" {self.case_source}" if self.case_source else ""
            out.append(f"the case file{where} has changed since the checkpoint was written")
        if self.overrides != other.overrides:
            mine, theirs = list(self.overrides), list(other.overrides)
            only_theirs = [o for o in theirs if o not in mine]
            only_mine = [o for o in mine if o not in theirs]
            parts = []
            if only_theirs:
                parts.append("the checkpoint's run had " + ", ".join(
                    f"--set {o}" for o in only_theirs))
            if only_mine:
                parts.append("this run has " + ", ".join(f"--set {o}" for o in only_mine))
            if not parts:
                parts.append("the same ones in another order")
            out.append("the --set overrides differ: " + "; ".join(parts))
        if self.settings_sha256 != other.settings_sha256:
            out.append("the run settings differ (time step, waves, initial offset, database "
                       "or damping given to run_coupled)")
        return out


def _sha256(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()


def _meta(identity: RunIdentity) -> dict[str, NDArray]:
    return {"meta/format": np.array(FORMAT), "meta/version": np.array(VERSION, dtype=np.int64),
            "meta/floatmoor_version": np.array(__version__), **identity.arrays()}


def write_checkpoint(path: str | os.PathLike[str], arrays: Mapping[str, NDArray],
                     identity: RunIdentity) -> None:
    """Write ``arrays`` (numeric, no objects) with the metadata of ``identity`` to ``path``
    atomically and durably: into a new temporary file beside it (``.NAME.PID.tmp``, created
    with ``O_EXCL | O_NOFOLLOW``, so a file or link already there is never written through),
    flushed to disk, renamed over ``path``, then the folder flushed, so that a process killed
    or a machine losing power at any moment leaves the previous checkpoint or this one whole.
    The temporary file is removed if the write fails."""
    path = Path(path)
    members = {**_meta(identity), **{k: np.asarray(v) for k, v in arrays.items()}}
    objects = [k for k, v in members.items() if v.dtype.hasobject]
    if objects:  # numpy.savez would pickle them (its allow_pickle needs numpy >= 2.1)
        raise ValueError(f"checkpoint arrays must be numeric or text, not objects: {objects}")
    tmp = temporary_path(path)
    tmp.unlink(missing_ok=True)  # left by a killed process of this id (which is gone)
    fd = os.open(tmp, _CREATE_FLAGS, 0o666)
    try:
        with open(fd, "wb") as fh:
            np.savez(fh, **members)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    sync_folder(path.parent)


#: Flags of a checkpoint's temporary file: a new file (never one already there, nor the
#: target of a symbolic link at its name).
_CREATE_FLAGS = (os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
                 | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0))


def temporary_path(path: str | os.PathLike[str], pid: int | None = None) -> Path:
    """The temporary file process ``pid`` (default: this one) writes the checkpoint ``path``
    through: hidden, beside it."""
    path = Path(path)
    return path.with_name(f".{path.name}.{os.getpid() if pid is None else pid}.tmp")


def remove_stale_temporaries(path: str | os.PathLike[str]) -> list[Path]:
    """Remove the temporary files of checkpoint ``path`` left by processes that no longer
    run (killed while writing it); returns those removed."""
    path = Path(path)
    removed = []
    for tmp in path.parent.glob(f".{glob.escape(path.name)}.*.tmp"):
        pid = tmp.name[len(path.name) + 2:-len(".tmp")]
        if not pid.isdigit() or _running(int(pid)):
            continue
        try:
            if stat.S_ISREG(os.lstat(tmp).st_mode):
                tmp.unlink()
                removed.append(tmp)
        except OSError:
            pass
    return removed


def _running(pid: int) -> bool:
    """Whether process ``pid`` may be writing a checkpoint: another process that exists,
    whoever owns it (this one writes none while it cleans up)."""
    if pid == os.getpid():
        return False  # this process has no write in progress when it cleans up
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError, OverflowError):
        return True
    return True


def _open_zip(path: Path) -> zipfile.ZipFile:
    """The checkpoint's zip, after checking it is a regular file that starts like one."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise CheckpointError(path, "a checkpoint to resume from (an interrupted floater run "
                              "leaves one; run without --resume to start)", "no checkpoint")
    except OSError as err:
        raise CheckpointError(path, "a readable checkpoint", f"{err.strerror or err}")
    if not stat.S_ISREG(mode):
        kind = file_kind(mode)
        raise CheckpointError(path, "a checkpoint file (a regular file)", kind)
    try:
        with open(path, "rb") as fh:
            head = fh.read(4)
    except OSError as err:
        raise CheckpointError(path, "a readable checkpoint", f"{err.strerror or err}")
    if not head:
        raise CheckpointError(path, f"a {FORMAT}", "an empty file (run without --resume to "
                              "start over)")
    if head.startswith(_PICKLE_MAGIC):
        raise CheckpointError(path, f"a {FORMAT} (a zip of numeric arrays)",
                              "a pickle, which is never loaded (it could run code; checkpoints "
                              "of earlier floatmoor versions were pickles: run without "
                              "--resume to start over)")
    if not head.startswith(_ZIP_MAGIC):
        raise CheckpointError(path, f"a {FORMAT} (a zip of numeric arrays)",
                              "another kind of file (run without --resume to start over)")
    try:
        return zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError, ValueError, EOFError) as err:
        raise CheckpointError(path, f"a complete {FORMAT}",
                              f"a damaged or truncated file ({err}); run without --resume to "
                              "start over")


def _header(zf: zipfile.ZipFile, info: zipfile.ZipInfo) -> tuple[tuple[int, ...], np.dtype]:
    """(shape, dtype) from a ``.npy`` member's header, no data read."""
    with zf.open(info) as fp:
        version = np.lib.format.read_magic(fp)
        if version == (1, 0):
            shape, _, dtype = np.lib.format.read_array_header_1_0(fp)
        elif version == (2, 0):
            shape, _, dtype = np.lib.format.read_array_header_2_0(fp)
        else:
            raise ValueError(f"npy format version {version}")
    return tuple(int(n) for n in shape), np.dtype(dtype)


def _read(zf: zipfile.ZipFile, info: zipfile.ZipInfo) -> NDArray:
    with zf.open(info) as fp:
        return np.lib.format.read_array(fp, allow_pickle=False)


class _Members:
    """The headers of a checkpoint's members, checked for object arrays."""

    def __init__(self, path: Path, zf: zipfile.ZipFile) -> None:
        self.path, self.zf = path, zf
        self.info: dict[str, zipfile.ZipInfo] = {}
        self.headers: dict[str, tuple[tuple[int, ...], np.dtype]] = {}
        if len(zf.infolist()) > _MAX_MEMBERS:
            raise CheckpointError(path, f"a {FORMAT} of at most {_MAX_MEMBERS} arrays",
                                  f"{len(zf.infolist())} members")
        try:
            for info in zf.infolist():
                if not info.filename.endswith(".npy"):
                    raise ValueError(f"member {info.filename!r} is not an array")
                name = info.filename[:-4]
                shape, dtype = _header(zf, info)
                if dtype.hasobject:
                    raise CheckpointError(path, f"a {FORMAT} of numeric arrays",
                                          f"an object array '{name}' (never unpickled)")
                self.info[name], self.headers[name] = info, (shape, dtype)
        except CheckpointError:
            raise
        except Exception as err:  # any damage of the zip or the npy headers
            raise self.damaged(err) from None

    def damaged(self, err: BaseException) -> CheckpointError:
        return CheckpointError(self.path, f"a complete {FORMAT}",
                               f"a damaged file ({type(err).__name__}: {err}); run without "
                               "--resume to start over")

    def read(self, name: str) -> NDArray:
        try:
            return _read(self.zf, self.info[name])
        except Exception as err:
            raise self.damaged(err) from None

    def meta(self, name: str, kind: str) -> NDArray:
        """A ``meta/`` member of dtype kind ``kind`` ('U' text, 'i' integer)."""
        key = f"meta/{name}"
        if key not in self.headers:
            raise CheckpointError(self.path, f"a {FORMAT}", f"a file without '{key}' (not a "
                                  "floatmoor checkpoint)")
        shape, dtype = self.headers[key]
        if dtype.kind != kind or len(shape) > 1 or self.info[key].file_size > _META_MAX_BYTES:
            raise CheckpointError(self.path, f"a {FORMAT}", f"a malformed '{key}'")
        return self.read(key)


def _identity_and_members(path: Path, zf: zipfile.ZipFile, identity: RunIdentity) -> _Members:
    members = _Members(path, zf)
    fmt = members.meta("format", "U")
    if fmt.shape != () or str(fmt) != FORMAT:
        raise CheckpointError(path, f"a {FORMAT}", f"a file of format '{fmt}'")
    version = members.meta("version", "i")
    if version.shape != () or int(version) != VERSION:
        raise CheckpointError(path, f"a {FORMAT} of version {VERSION}",
                              f"version {version} (run without --resume to start over)")
    written_by = str(members.meta("floatmoor_version", "U"))
    if written_by != __version__:
        raise CheckpointError(path, f"a checkpoint written by floatmoor {__version__}",
                              f"one written by floatmoor {written_by}, whose state need not "
                              "continue identically here (run without --resume to start over)")
    overrides = members.meta("overrides", "U")
    theirs = RunIdentity(str(members.meta("case_text_sha256", "U")),
                         tuple(str(o) for o in overrides.reshape(-1)),
                         str(members.meta("settings_sha256", "U")))
    differences = identity.differences(theirs)
    if differences:
        raise CheckpointError(path, f"a checkpoint of this run ({_START_OVER})",
                              "one of another run: " + "; ".join(differences))
    return members


def check_checkpoint(path: str | os.PathLike[str], identity: RunIdentity) -> None:
    """Check that ``path`` is a checkpoint of the run ``identity`` (file, format, version,
    identity; not yet the state's shapes, which need the run built).

    Raises
    ------
    CheckpointError
        Saying what is wrong (and naming what differs for another run's checkpoint).
    """
    path = Path(path)
    with _open_zip(path) as zf:
        _identity_and_members(path, zf, identity)


def read_checkpoint(path: str | os.PathLike[str], identity: RunIdentity,
                    expected: Mapping[str, tuple[tuple[int, ...], np.dtype | type]], *,
                    exact: bool = True) -> dict[str, NDArray]:
    """The arrays of the checkpoint ``path`` of the run ``identity``, every one named in
    ``expected`` with its (shape, dtype) -- with ``exact``, no more, no fewer -- and finite.
    (``exact=False`` reads a few arrays first, e.g. the progress that gives the others'
    lengths.)

    Raises
    ------
    CheckpointError
        As :func:`check_checkpoint`, or naming the missing, unexpected, misshapen or
        non-finite array.
    """
    path = Path(path)
    with _open_zip(path) as zf:
        members = _identity_and_members(path, zf, identity)
        stored = {k for k in members.headers if not k.startswith("meta/")}
        missing = sorted(set(expected) - stored)
        extra = sorted(stored - set(expected)) if exact else []
        if missing or extra:
            found = "; ".join(
                ([f"no array {', '.join(missing)}"] if missing else [])
                + ([f"unexpected array {', '.join(extra)}"] if extra else []))
            raise CheckpointError(path, f"the arrays of this run's state ({_START_OVER})",
                                  found)
        out = {}
        for name, (shape, dtype) in expected.items():
            want = (tuple(int(n) for n in shape), np.dtype(dtype))
            if members.headers[name] != want:
                got = members.headers[name]
                raise CheckpointError(path, f"array '{name}' of shape {want[0]} and dtype "
                                      f"{want[1]}", f"shape {got[0]} and dtype {got[1]}")
            value = members.read(name)
            if value.dtype.kind == "f" and not np.all(np.isfinite(value)):
                raise CheckpointError(path, f"finite values in array '{name}'",
                                      "NaN or infinite values")
            out[name] = value
    return out
